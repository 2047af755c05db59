"""Run by test_lammps.py as ``[mpirun -np 2] python tests/lammps/lammps_cases.py DIR``: scenes of what a LAMMPS
user does around the contact forces, each run with LammpsContacts on this number of ranks and, on one rank, the
reference (LAMMPS's own ``pair granular``, or LammpsContacts on one rank where the reference is the one-rank
run). Prints one JSON object on rank 0; DIR keeps the restart file that the one-rank call
writes and the two-rank call reads.

Scenes (R = 1 mm spheres, hertz + mindlin_total without the frame spin, which is LAMMPS's
``hertz/material`` + ``tangential mindlin``; x split at 0 between two ranks):

- hold: a sphere dropped with spin onto a base sphere held by ``fix freeze`` or ``fix setforce 0 0 0``
  (defined after attaching LammpsContacts, or before);
- split: a pressed pair sliding under prescribed motion (fix move) that comes to be split between the
  ranks by a restart written on one rank (between runs, or during a run by the ``restart`` command),
  ``balance``, ``fix balance`` or ``displace_atoms``;
- images: periodic y of 1.95 diameters: atom 1 touches atom 2 and atom 2's periodic image, while atom 1
  spins and atom 2 slides (LAMMPS's own pair granular; LammpsContacts refuses it);
- wrap: a pressed spinning pair in runs of 10 steps while a far atom leaves the periodic box during the
  first (LAMMPS wraps it at the second run's set-up), and a periodic gas in 10 runs and in one;
- velocity: a hertz_damped pair pressed at 0.5 m/s, then ``velocity all set 0 0 0`` and zero spins, against
  the same state read from a restart file by a new LAMMPS instance (which computes every force anew).
"""
import json
import os
import sys
import warnings

import numpy as np

from dem_contact.dem.pairs import pair_table
from dem_contact.errors import InputError
from dem_contact.lammps import LammpsContacts, new_lammps
from dem_contact.materials import Material, Sphere
from dem_contact.laws.model import reference_speed

R = 1e-3
MAT = Material(E=5e7, nu=0.3, rho=2500.0)
MU = 0.5
OUT = sys.argv[1]


def table(normal="hertz", **kw):
    return pair_table([Sphere(R, MAT)], [], mu=MU, normal=normal, tangential="mindlin_total", v_ref=reference_speed(1.0), **kw)


def box(lmp, lo, hi, periodic="f f f", dt=1e-6):
    for c in ("units si", "atom_style sphere", f"boundary {periodic}", "atom_modify map array",
              "processors * 1 1", "region box block " + " ".join(f"{a!r} {b!r}" for a, b in zip(lo, hi)),
              "create_box 1 box"):
        lmp.command(c)
    return dt


def atoms(lmp, xs, dt):
    for x in xs:
        lmp.command("create_atoms 1 single " + " ".join(repr(float(c)) for c in x))
    lmp.command(f"set type 1 diameter {2 * R!r}")
    lmp.command(f"set type 1 mass {table().scenes[0].sphere.mass!r}")
    lmp.command(f"timestep {dt!r}")


def native(lmp, skin=0.3 * R):
    for c in (f"neighbor {skin!r} bin", "neigh_modify delay 0 every 1 check yes", "comm_modify vel yes",
              "pair_style granular", f"pair_coeff * * hertz/material {MAT.E!r} 0.0 {MAT.nu!r} tangential mindlin "
              f"NULL 0.0 {MU!r} damping viscoelastic"):
        lmp.command(c)


def gather(lmp, name):
    return np.array(lmp.gather_atoms(name, 1, 3)).reshape(-1, 3).tolist()


def state(lmp):
    return {k: gather(lmp, k) for k in ("x", "v", "omega", "f", "torque")}


def set_rows(lmp, name, rows):
    """Per-atom values by atom id (on the rank that owns each)."""
    ids = lmp.numpy.extract_atom("id")[:lmp.extract_setting("nlocal")]
    arr = lmp.numpy.extract_atom(name)
    for k, i in enumerate(ids):
        if i in rows:
            arr[k] = rows[i]


# ----------------------------------------------------------------------------------------------- hold

def hold(how, ours, before=False):
    lmp = new_lammps()
    dt = box(lmp, (-0.004, -0.004, -0.004), (0.004, 0.004, 0.006))
    atoms(lmp, [(-0.4e-3, 0.0, 0.0), (0.5e-3, 0.1e-3, 1.84e-3)], dt)
    lmp.command("fix nve all nve/sphere")
    lmp.command("fix grav all gravity 9.81 vector 0 0 -1")
    lmp.command("group base id 1")
    set_rows(lmp, "v", {2: (0.05, 0.02, -0.5)})
    set_rows(lmp, "omega", {2: (30.0, -50.0, 20.0)})
    fix = "freeze" if how == "freeze" else "setforce 0.0 0.0 0.0"
    out = {}
    if ours:
        if before:
            lmp.command(f"fix hold base {fix}")
        bridge = LammpsContacts(lmp, table(), slots=2, v_max=1.0, frame_spin=False)
        if not before:
            lmp.command(f"fix hold base {fix}")
        step = bridge.run
    else:
        lmp.command(f"fix hold base {fix}")
        native(lmp)

        def step(n):
            lmp.command(f"run {n}")
    x0 = gather(lmp, "x")[0]
    drift, f_max = 0.0, 0.0
    for _ in range(8):
        step(50)
        s = state(lmp)
        drift = max(drift, float(np.abs(np.subtract(s["x"][0], x0)).max()))
        f_max = max(f_max, float(np.abs(s["f"][1]).max()))
    out.update(state(lmp), held_drift=drift, f_max=f_max)
    lmp.close()
    return out


# ----------------------------------------------------------------------------------------------- split

def pair_at(lmp, x1, dt, s=2e-3):
    """A pressed pair (overlap 2e-5 m), atom 2 beside atom 1 (x + 0.6 mm) and above it, atom 2 sliding
    along y at s under fix move, atom 1 still."""
    dx, gap = 0.6e-3, 2 * R - 2e-5
    atoms(lmp, [(x1, 0.0, 0.0), (x1 + dx, 0.0, float(np.sqrt(gap * gap - dx * dx)))], dt)
    moves(lmp, s)


def moves(lmp, s=2e-3):
    for c in ("group a1 id 1", "group a2 id 2", "fix m1 a1 move linear 0 0 0", f"fix m2 a2 move linear 0 {s!r} 0"):
        lmp.command(c)


def split(how, restart):
    """Forces on both atoms and their positions every 250 steps, before and after the pair is split between
    ranks (on one rank: the same commands)."""
    lmp = new_lammps()
    ranks = lmp.extract_setting("world_size")
    rows = []

    def record(bridge, n):
        for _ in range(n // 250):
            bridge.run(250)
            rows.append((gather(lmp, "f"), gather(lmp, "x")))

    if how.startswith("restart"):
        # the run before the restart on one rank (the pair straddles x = 0, the face between two ranks):
        # write_restart between runs, or the restart command during a run
        restart += ".mid" if how == "restart during a run" else ""
        if ranks == 1:
            dt = box(lmp, (-0.004, -0.002, -0.002), (0.004, 0.002, 0.004))
            pair_at(lmp, -0.3e-3, dt)
            bridge = LammpsContacts(lmp, table(), slots=2, v_max=1.0, frame_spin=False)
            if how == "restart":
                record(bridge, 1500)
                lmp.command(f"write_restart {restart}")
            else:
                lmp.command(f"restart 1500 {restart}")
                bridge.run(1600)
            lmp.close()
            lmp = new_lammps()
        if how == "restart during a run":
            restart += ".1500"              # (the restart command's file of step 1500)
        for c in (f"read_restart {restart}", "timestep 1e-6", "fix m1 a1 move linear 0 0 0",
                  "fix m2 a2 move linear 0 0.002 0"):
            lmp.command(c)
        bridge = LammpsContacts(lmp, table(), slots=2, v_max=1.0, frame_spin=False)
        rows = []
        record(bridge, 1500)
    else:
        dt = box(lmp, (-0.004, -0.002, -0.002), (0.004, 0.002, 0.004))
        pair_at(lmp, -1.3e-3, dt)         # both atoms on rank 0, 0.7 mm from x = 0 (two skins: 0.6 mm)
        bridge = LammpsContacts(lmp, table(), slots=2, v_max=1.0, frame_spin=False)
        record(bridge, 1500)
        if how == "balance":
            if ranks > 1:
                lmp.command("balance 1.0 x 0.375")          # the face at x = -1 mm, between the atoms
        elif how == "fix balance":
            lmp.command("fix bal all balance 500 1.0 shift x 10 1.0")
        elif how == "displace":
            lmp.command("unfix m1")
            lmp.command("unfix m2")
            lmp.command("displace_atoms all move 0.001 0 0")    # to x = -0.3 and 0.3 mm
            moves(lmp)
        record(bridge, 1500)
    nloc = [lmp.extract_setting("nlocal")]
    out = {"f": [r[0] for r in rows], "x": [r[1] for r in rows], "ranks": ranks, "nlocal_rank0": nloc[0]}
    lmp.close()
    return out


# ---------------------------------------------------------------------------------------------- images

def images(mode):
    """mode: 'ours' (4 runs of 250 steps), 'native' (one run of 1000), 'native pieces' (4 runs)."""
    lmp = new_lammps()
    L = 3.9e-3                             # 1.95 diameters
    dt = box(lmp, (-0.004, 0.0, -0.002), (0.004, L, 0.002), periodic="f p f")
    atoms(lmp, [(-0.15e-3, 1.0e-3, 0.0), (0.15e-3, 2.93e-3, 0.0)], dt)    # |d| 1.953 mm and 1.993 mm
    for c in ("group a1 id 1", "group a2 id 2", "fix m1 a1 move rotate -0.00015 0.001 0 1 0 0 6.283185307179586",
              "fix m2 a2 move linear 0 0 0.002"):
        lmp.command(c)
    if mode == "ours":
        bridge = LammpsContacts(lmp, table(), slots=3, v_max=1.0, frame_spin=False)
        try:
            for _ in range(4):
                bridge.run(250)
        except InputError as e:
            return {"raised": str(e)}        # (an error on one rank: the instance is not closed, but left)
        lmp.close()
        return {"raised": None}
    else:
        native(lmp, skin=0.5e-3)
        for _ in range(4 if mode == "native pieces" else 1):
            lmp.command(f"run {250 if mode == 'native pieces' else 1000}")
    out = state(lmp)
    lmp.close()
    return out


# ------------------------------------------------------------------------------------------------ wrap

def wrap_pair(pieces):
    """A pressed spinning pair in the middle of a box periodic in x; a third atom leaves it through
    x = hi during the first of the runs."""
    lmp = new_lammps()
    dt = box(lmp, (0.0, -0.004, -0.004), (0.01, 0.004, 0.004), periodic="p f f", dt=1e-7)
    atoms(lmp, [(0.004, 0.0, 0.0), (0.004, 0.0, 0.0019), (0.01 - 2e-7, 0.0025, 0.0025)], dt)
    lmp.command("fix nve all nve/sphere")
    set_rows(lmp, "v", {1: (0.01, 0.0, 0.05), 3: (10.0, 0.0, 0.0)})
    set_rows(lmp, "omega", {1: (50.0, -80.0, 120.0)})
    bridge = LammpsContacts(lmp, table(), slots=4, v_max=1.0)
    for n in pieces:
        bridge.run(n)
    out = state(lmp)
    lmp.close()
    return out


def gas(pieces):
    """40 spheres in a box periodic in x, y and z, random velocities (1 m/s rms per axis)."""
    lmp = new_lammps()
    dt = box(lmp, (0.0, 0.0, 0.0), (0.01, 0.01, 0.01), periodic="p p p", dt=1e-6)
    g = (np.arange(4) + 0.5) * 0.0025
    xs = np.array([(a, b, c) for a in g for b in g for c in g])[:40]
    atoms(lmp, xs, dt)
    lmp.command("fix nve all nve/sphere")
    rng = np.random.default_rng(7)
    set_rows(lmp, "v", {k + 1: tuple(rng.normal(0.0, 1.0, 3)) for k in range(40)})
    v0 = np.array(gather(lmp, "v"))
    bridge = LammpsContacts(lmp, table(), slots=8, v_max=4.0)
    for n in pieces:
        bridge.run(n)
    out = state(lmp)
    out["collided"] = int((np.abs(np.array(out["v"]) - v0).max(axis=1) > 1e-6).sum())     # (atoms hit)
    lmp.close()
    return out


# -------------------------------------------------------------------------------------------- velocity

def velocity(restart):
    """Forces at the set-up (run 0) and the state after 10 steps, after the velocities were set to zero
    between runs: continued in this instance, and read from a restart file of the same state."""
    lmp = new_lammps()
    dt = box(lmp, (-0.004, -0.004, -0.004), (0.004, 0.004, 0.004), dt=1e-7)
    atoms(lmp, [(-0.5e-3, 0.0, 0.0), (0.5e-3, 0.3e-3, 1.70e-3)], dt)
    lmp.command("fix nve all nve/sphere")
    set_rows(lmp, "v", {1: (0.05, 0.0, 0.25), 2: (-0.05, 0.0, -0.25)})     # 0.5 m/s towards each other
    set_rows(lmp, "omega", {1: (50.0, -80.0, 120.0)})
    t = table("hertz_damped", e_n=0.5)
    bridge = LammpsContacts(lmp, t, slots=2, v_max=1.0)
    bridge.run(100)
    f_before = gather(lmp, "f")
    lmp.command("velocity all set 0 0 0")
    lmp.command("set group all omega 0 0 0")
    lmp.command(f"write_restart {restart}")
    out = {"continued": {}, "restarted": {}, "f_before": f_before}
    bridge.run(0)
    out["continued"]["setup_f"] = gather(lmp, "f")
    bridge.run(10)
    out["continued"].update(state(lmp))
    lmp.close()
    lmp = new_lammps()
    for c in (f"read_restart {restart}", "timestep 1e-7", "fix nve all nve/sphere"):
        lmp.command(c)
    bridge = LammpsContacts(lmp, t, slots=2, v_max=1.0)
    bridge.run(0)
    out["restarted"]["setup_f"] = gather(lmp, "f")
    bridge.run(10)
    out["restarted"].update(state(lmp))
    lmp.close()
    return out


def world():
    """(number of ranks, this rank) of the MPI run, from a LAMMPS instance made for the question."""
    probe = new_lammps()
    ranks, rank = probe.extract_setting("world_size"), probe.extract_setting("world_rank")
    probe.close()
    return ranks, rank


def main():
    # (the scenes start pressed on purpose: LAMMPS's warning of deep first overlaps)
    warnings.filterwarnings("ignore", "LAMMPS: pair dem/contact: .* start with an overlap deeper", RuntimeWarning)
    ranks, rank = world()
    res = {"ranks": ranks}
    res["hold"] = {how: {"ours": hold(how, True), "before": hold(how, True, before=True)}
                   for how in ("freeze", "setforce")}
    res["split"] = {how: split(how, os.path.join(OUT, "split.restart"))
                    for how in ("restart", "restart during a run", "balance", "fix balance", "displace")}
    res["images"] = {"ours": images("ours")}
    res["wrap"] = {"pieces": wrap_pair([10, 10]), "one": wrap_pair([20]),
                   "gas_pieces": gas([100] * 10), "gas_one": gas([1000])}
    res["velocity"] = velocity(os.path.join(OUT, f"velocity{ranks}.restart"))
    if ranks == 1:
        res["hold_native"] = {how: hold(how, False) for how in ("freeze", "setforce")}
        res["images"]["native"] = images("native")
    if rank == 0:
        print(json.dumps(res))


if __name__ == "__main__":
    main()
