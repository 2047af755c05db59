"""Run by test_lammps.py as ``[mpirun -np 2] python tests/lammps/lammps_runs.py DIR``: what a LAMMPS user does
around the contact forces during and between runs, each scene with LammpsContacts on this number of ranks and,
where LAMMPS has the equivalent, with LAMMPS's own models (``native_commands``) on the same ranks. Prints
one JSON object on rank 0; DIR takes the dump file of the rerun scene.

Scenes (hertz + mindlin_total without the frame spin, LAMMPS's ``hertz/material`` + ``tangential mindlin``;
x split at 0 between two ranks):

- belt: spheres pressed 20 um into a plane sliding along x (a belt) and a pressed pair straddling x = 0
  sliding past each other, all overlapping when the first run starts: the state after 1 step and after 300;
- rising: a sphere resting under gravity on a plane rising at 0.02 m/s, in two runs of 1000 steps, with
  `reset_timestep 0` between them or without;
- adapt: two still spheres 0.1 mm apart (more than the skin), straddling x = 0, grown by `fix adapt`
  to an overlap of 0.1 mm; and grown past r_max;
- rerun: `rerun` of a dump written during a run;
- pour: spheres inserted by `fix pour` onto a floor, and a pour of two types whose wall materials differ
  (LAMMPS's wall fixes then act on type groups);
- exclude: two spheres meeting head on, with `neigh_modify exclude type 1 2` or `group a b` or neither;
- bonded: two overlapping spheres bonded with `special_bonds lj 0 1 1` or `lj 1 1 1`, or of one molecule
  excluded by `neigh_modify exclude molecule/intra all` (a rigid clump), each beside a third sphere.
"""
import json
import os
import sys

import numpy as np

from dem_contact.dem.pairs import pair_table
from dem_contact.errors import InputError
from dem_contact.lammps import LammpsContacts, native_commands, new_lammps
from dem_contact.materials import Material, Sphere, Wall
from dem_contact.walls import PlaneWall
from lammps_cases import world

R = 1e-3
MAT = Material(E=5e7, nu=0.3, rho=2500.0)
SOFT = Material(E=2e7, nu=0.4, rho=1100.0)
MU = 0.5
OUT = sys.argv[1]


def table(spheres=(Sphere(R, MAT),)):
    return pair_table(list(spheres), [Wall(MAT)], mu=MU, normal="hertz", tangential="mindlin_total")


def gather(lmp, name):
    return np.array(lmp.gather_atoms(name, 1, 3)).reshape(-1, 3).tolist()


def state(lmp):
    return {k: gather(lmp, k) for k in ("x", "v", "omega")}


def box(lmp, lo, hi, ntypes=1, style="sphere", periodic="f f f"):
    for c in ("units si", f"atom_style {style}", f"boundary {periodic}", "atom_modify map array", "processors * 1 1",
              "region box block " + " ".join(f"{a!r} {b!r}" for a, b in zip(lo, hi)), f"create_box {ntypes} box",
              "comm_modify vel yes"):
        lmp.command(c)


def atoms(lmp, xs, radius=R, dt=1e-6):
    for x in xs:
        lmp.command("create_atoms 1 single " + " ".join(repr(float(c)) for c in x))
    lmp.command(f"set type 1 diameter {2 * radius!r}")
    lmp.command(f"set type 1 density {MAT.rho!r}")
    lmp.command(f"timestep {dt!r}")


def attach_or_native(lmp, native, t, walls, v_max=1.0, **kw):
    if native:
        lmp.command(f"neighbor {0.3 * R!r} bin")
        lmp.command("neigh_modify delay 0 every 1 check yes")
        for c in native_commands(t, walls):
            lmp.command(c)
        return None
    return LammpsContacts(lmp, t, walls, v_max=v_max, frame_spin=False, **kw)


def go(lmp, bridge, n):
    lmp.command(f"run {n}") if bridge is None else bridge.run(n)


# ------------------------------------------------------------------------------------------------- belt

def belt(native):
    lmp = new_lammps()
    box(lmp, (-0.004, -0.004, -0.001), (0.004, 0.004, 0.006))
    z = R - 2e-5
    atoms(lmp, [(-2.5e-3, 0.0, z), (2.5e-3, 1e-3, z), (-0.99e-3, 0.0, 3.5e-3), (0.99e-3, 0.0, 3.5e-3)])
    lmp.command("fix nve all nve/sphere")
    for c in ("group c id 3", "group d id 4", "velocity c set 0 0.3 0", "velocity d set 0 -0.3 0"):
        lmp.command(c)
    bridge = attach_or_native(lmp, native, table(), [PlaneWall.axis("z", 0.0, "lo", velocity=(0.1, 0.0, 0.0))],
                              slots=2)
    go(lmp, bridge, 1)
    out = {"one": state(lmp)}
    go(lmp, bridge, 299)
    out["many"] = state(lmp)
    lmp.close()
    return out


# ----------------------------------------------------------------------------------------------- rising

def rising(reset):
    lmp = new_lammps()
    box(lmp, (-0.004, -0.004, -0.001), (0.004, 0.004, 0.006))
    atoms(lmp, [(-1e-3, 0.0, R - 2e-7)])               # (resting: pressed by its weight)
    lmp.command("fix nve all nve/sphere")
    lmp.command("fix grav all gravity 9.81 vector 0 0 -1")
    lmp.command("velocity all set 0 0 0.02")
    bridge = LammpsContacts(lmp, table(), [PlaneWall.axis("z", 0.0, "lo", velocity=(0.0, 0.0, 0.02))], slots=2,
                            v_max=1.0, frame_spin=False)
    bridge.run(1000)
    if reset:
        lmp.command("reset_timestep 0")
    bridge.run(1000)
    out = state(lmp)
    lmp.close()
    return out


# ------------------------------------------------------------------------------------------------ adapt

def adapt(r_max):
    """Two still spheres (no integrator) 0.1 mm apart, grown by fix adapt from R to 1.1 R in 100 steps."""
    lmp = new_lammps()
    box(lmp, (-0.004, -0.004, -0.004), (0.004, 0.004, 0.004), style="sphere 1")
    atoms(lmp, [(-1.05e-3, 0.0, 0.0), (1.05e-3, 0.0, 0.0)])
    t = table()
    bridge = LammpsContacts(lmp, t, [], slots=2, v_max=1.0, frame_spin=False, skin=0.05e-3, r_max=r_max)
    lmp.command(f"variable dia equal ramp({2 * R!r},{2.2 * R!r})")
    lmp.command("fix grow all adapt 1 atom diameter v_dia")
    out = {"raised": None}
    try:
        bridge.run(100)
    except InputError as e:
        out["raised"] = str(e)
    out["f"] = gather(lmp, "f")
    out["radius"] = np.array(lmp.gather_atoms("radius", 1, 1)).tolist()
    out["e_star"] = float(t.scenes[0].pair.E_star)
    lmp.close()
    return out


# ------------------------------------------------------------------------------------------------ rerun

def rerun():
    lmp = new_lammps()
    box(lmp, (-0.004, -0.004, -0.001), (0.004, 0.004, 0.006))
    atoms(lmp, [(-1e-3, 0.0, R - 1e-5)])
    lmp.command("fix nve all nve/sphere")
    lmp.command("velocity all set 0.1 0 0")
    bridge = LammpsContacts(lmp, table(), [PlaneWall.axis("z", 0.0, "lo")], slots=2, v_max=1.0, frame_spin=False)
    path = os.path.join(OUT, f"rerun{lmp.extract_setting('world_size')}.dump")
    lmp.command(f"dump d all custom 5 {path} id type x y z")
    bridge.run(20)
    lmp.command("undump d")
    out = {"raised": None}
    try:
        lmp.command(f"rerun {path} dump x y z")
    except Exception as e:
        out["raised"] = str(e)
    lmp.close()
    return out


# ------------------------------------------------------------------------------------------------- pour

def pour(native, types=1, group="all"):
    """Spheres of radius R/2 poured (fix pour, moving down at 1 m/s) onto a floor z = 0; two types of two
    materials: type 2 poured after type 1."""
    r = 0.5 * R
    lmp = new_lammps()
    box(lmp, (0.0, 0.0, -0.002), (0.008, 0.008, 0.008), ntypes=types, periodic="p p fm")
    lmp.command("timestep 2e-6")
    spheres = [Sphere(r, MAT), Sphere(r, SOFT)][:types]
    t = table(spheres)
    lmp.command("fix nve all nve/sphere")
    lmp.command("fix grav all gravity 9.81 vector 0 0 -1")
    lmp.command("region ins block 0.001 0.007 0.001 0.007 0.003 0.006")
    lmp.command("thermo_modify lost ignore")
    bridge = attach_or_native(lmp, native, t, [PlaneWall.axis("z", 0.0, "lo")], v_max=2.5, slots=8)
    out = {"raised": None}
    try:
        for k, s in enumerate(spheres, start=1):
            lmp.command(f"fix ins{k} {group.format(k=k)} pour 12 {k} 4767 vol 0.05 100 diam one {2 * r!r} "
                        f"dens {s.material.rho!r} {s.material.rho!r} vel 0 0 0 0 -1.0 region ins")
            go(lmp, bridge, 4000)
            lmp.command(f"unfix ins{k}")
    except Exception as e:
        out["raised"] = str(e)
    out["natoms"] = lmp.extract_global("natoms")
    out["x"] = gather(lmp, "x") if out["natoms"] == 12 * types else []        # (none lost)
    lmp.close()
    return out


# ---------------------------------------------------------------------------------------------- exclude

def exclude(native, how):
    """Two spheres of types 1 and 2 meeting head on at 0.3 m/s each, across x = 0, with LAMMPS's
    neighbour exclusion ``how`` (a neigh_modify exclude, or none)."""
    lmp = new_lammps()
    box(lmp, (-0.004, -0.004, -0.004), (0.004, 0.004, 0.004), ntypes=2)
    for x, k in ((-1.5e-3, 1), (1.5e-3, 2)):
        lmp.command(f"create_atoms {k} single {x!r} 0 0")
    for k in (1, 2):
        lmp.command(f"set type {k} diameter {2 * R!r}")
        lmp.command(f"set type {k} density {MAT.rho!r}")
    for c in ("timestep 1e-6", "fix nve all nve/sphere", "group a id 1", "group b id 2", "velocity a set 0.3 0 0",
              "velocity b set -0.3 0 0"):
        lmp.command(c)
    if how:
        lmp.command(f"neigh_modify exclude {how}")
    bridge = attach_or_native(lmp, native, table([Sphere(R, MAT)] * 2), [], slots=2)
    go(lmp, bridge, 4000)
    out = state(lmp)
    lmp.close()
    return out


def bonded(lj, molecule=False):
    """Two spheres overlapping 0.49 mm, bonded (special_bonds lj ``lj``), or of one molecule excluded by
    ``neigh_modify exclude molecule/intra all`` (a rigid clump's members), and a third sphere of its own
    pressed 20 um into the second: forces and the contact count after one step (no integrator)."""
    lmp = new_lammps()
    for c in ("units si", "atom_style hybrid sphere bond", "boundary f f f", "atom_modify map array",
              "processors * 1 1", "region box block -0.004 0.004 -0.004 0.004 -0.004 0.004",
              "create_box 1 box bond/types 1 extra/bond/per/atom 2 extra/special/per/atom 4", "comm_modify vel yes",
              "bond_style zero", "bond_coeff 1"):
        lmp.command(c)
    atoms(lmp, [(-0.755e-3, 0.0, 0.0), (0.755e-3, 0.0, 0.0), (0.755e-3, 0.0, 2 * R - 2e-5)])
    if molecule:
        lmp.command("set atom 1*2 mol 1")
        lmp.command("set atom 3 mol 2")
        lmp.command("neigh_modify exclude molecule/intra all")
    else:
        lmp.command("create_bonds single/bond 1 1 2")
        lmp.command(f"special_bonds lj {lj} 1 1")
    bridge = LammpsContacts(lmp, table(), [], slots=2, v_max=1.0, frame_spin=False)
    bridge.run(1)
    out = {"f": gather(lmp, "f"), "contacts": bridge.stats()["contacts"]}
    lmp.close()
    return out


def main():
    ranks, rank = world()
    res = {"ranks": ranks,
           "belt": {"ours": belt(False), "native": belt(True)},
           "rising": {"reset": rising(True), "plain": rising(False)},
           "rerun": rerun(),
           "adapt": {"within": adapt(1.15 * R), "past": adapt(1.05 * R)},
           "pour": {"ours": pour(False), "native": pour(True),
                    "native_types_all": pour(True, 2), "native_types_grouped": pour(True, 2, "native_t{k}"),
                    "ours_types": pour(False, 2)},
           "exclude": {how: {"ours": exclude(False, how), "native": exclude(True, how)}
                       for how in ("", "type 1 2", "group a b")},
           "bonded": {"lj0": bonded(0), "lj1": bonded(1), "clump": bonded(1, molecule=True)}}
    if rank == 0:
        print(json.dumps(res))


if __name__ == "__main__":
    main()
