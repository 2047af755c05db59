"""The cost of a contact update in LAMMPS's Pair section: ``[mpirun -np N] python tests/lammps/plugin_bench.py
SCENE N STEPS [--tangential LAW] [--mdr-springs CELLS] [--energy] [--frame-spin] [--record-every K] [--repeat R]``,
run by test_bench_plugin.py (and by hand). Prints one JSON object (rank 0): per engine (``plugin``: pair_style
dem/contact with the law; ``native``: LAMMPS's own pair granular hertz/material + mindlin) the Pair section's time,
averaged over the ranks, of STEPS steps after a warm-up run (the fastest of R runs, the engines taking turns), the
sphere-sphere contacts, and ns_per_update: the Pair time of all ranks over STEPS x contacts.

Scenes: ``pack``, N spheres on a cubic lattice 1% closer than touching, periodic, with small random velocities and
spins (three contacts per sphere, lasting); ``pour``, N spheres on a loose lattice with random velocities falling
onto a bed in a periodic column (brief collisions, and the bed's contacts), timed after 500 steps."""
import argparse
import json
import math
import os
import re
import tempfile

import numpy as np

from dem_contact.dem.pairs import pair_table
from dem_contact.errors import InputError
from dem_contact.lammps import new_lammps, plugin_build, table_file
from dem_contact.materials import Material, Sphere

R = 1e-3
GLASS = Material(E=5e7, nu=0.25, rho=2500.0)
MU = 0.5


def pair_seconds(log_path):
    """The average Pair time of the last run in a LAMMPS log."""
    with open(log_path) as f:
        rows = re.findall(r"^Pair\s*\|\s*([\d.e+-]+)\s*\|\s*([\d.e+-]+)", f.read(), re.M)
    return float(rows[-1][1])


def setup(lmp, scene, n, rng):
    if scene == "pack":
        k = round(n ** (1 / 3))
        s = 2.0 * R * 0.99
        L = k * s
        for c in ("units si", "atom_style sphere", "atom_modify map array", "boundary p p p",
                  f"region box block 0 {L!r} 0 {L!r} 0 {L!r}", "create_box 1 box", f"lattice sc {s!r}",
                  "create_atoms 1 box", f"set type 1 diameter {2 * R!r}", f"set type 1 density {GLASS.rho!r}",
                  "velocity all create 1e-12 4928 loop geom", "timestep 2e-6", "fix 1 all nve/sphere"):
            lmp.command(c)
        v = rng.normal(0.0, 0.02, (lmp.extract_setting("nlocal"), 3))
        lmp.numpy.extract_atom("v")[:len(v)] = v
        lmp.numpy.extract_atom("omega")[:len(v)] = 50.0 * v[:, ::-1]
        return
    k = max(4, round(math.sqrt(n / 10)))        # spheres per side, ten layers of them
    s = 2.05 * R
    L = k * s
    for c in ("units si", "atom_style sphere", "atom_modify map array", "boundary p p f",
              f"region box block 0 {L!r} 0 {L!r} 0 {14 * s!r}", "create_box 1 box", f"lattice sc {s!r}",
              f"region fill block 0 {L!r} 0 {L!r} 0 {10 * s!r} units box", "create_atoms 1 region fill",
              f"set type 1 diameter {2 * R!r}", f"set type 1 density {GLASS.rho!r}",
              f"region bed block INF INF INF INF 0 {s!r} units box", "group bed region bed",
              "group grains subtract all bed", "timestep 2e-6", "fix 1 grains nve/sphere",
              "fix 2 grains gravity 9.81 vector 0 0 -1"):
        lmp.command(c)
    nlocal = lmp.extract_setting("nlocal")
    z = lmp.numpy.extract_atom("x")[:nlocal, 2]
    v = rng.normal(0.0, 0.2, (nlocal, 3)) + np.array([0.0, 0.0, -0.3])
    v[z < s] = 0.0                                  # (the bed stays)
    lmp.numpy.extract_atom("v")[:nlocal] = v


def bench_table(args):
    """The plugin's table: one sphere type, the law and cell count of the arguments."""
    cells = {} if args.mdr_springs is None else dict(mdr_springs=args.mdr_springs)
    return pair_table([Sphere(R, GLASS)], mu=MU, tangential=args.tangential, **cells)


def run(engine, args, log, table):
    rng = np.random.default_rng(5)
    lmp = new_lammps("-log", log, "-screen", "none", "-nocite")
    setup(lmp, args.scene, args.n, rng)
    for c in ("neighbor 0.0003 bin", "neigh_modify delay 0 every 1 check yes", "comm_modify vel yes"):
        lmp.command(c)
    if engine == "native":
        lmp.command("pair_style granular")
        lmp.command(f"pair_coeff * * hertz/material {GLASS.E!r} 0.0 {GLASS.nu!r} tangential mindlin NULL 0.0 {MU!r} "
                    f"damping viscoelastic")
    else:
        path = table_file.save(table, os.path.join(args.dir, f"bench_{lmp.extract_setting('world_rank')}.json"))
        lmp.command(f"plugin load {plugin_build.plugin_path()}")
        lmp.command(f"pair_style dem/contact vmax 1.0 frame_spin {'yes' if args.frame_spin else 'no'} "
                    f"energy {'yes' if args.energy else 'no'}")
        lmp.command(f"pair_coeff * * {path}")
        if args.record_every:
            # (every contact's row written out at those steps: a dump local of compute dem/contact/local)
            lmp.command("compute contacts all dem/contact/local")
            lmp.command(f"dump rows all local {args.record_every} {os.devnull} c_contacts[1] c_contacts[12]")
    lmp.command(f"run {20 if args.scene == 'pack' else 500}")       # (not timed: the contacts of the pour form)
    lmp.command(f"run {args.steps}")
    contacts = count_contacts(lmp)
    ranks = lmp.extract_setting("world_size")
    rank = lmp.extract_setting("world_rank")
    lmp.close()
    if rank != 0:
        return rank, None
    seconds = pair_seconds(log)     # (rank 0 writes the log)
    return rank, dict(pair_s=seconds, contacts=contacts, ranks=ranks,
                      ns_per_update=1e9 * seconds * ranks / (args.steps * max(contacts, 1)))


def count_contacts(lmp):
    """Touching sphere pairs (periodic images included), counted on rank 0's gathered copy."""
    x = np.array(lmp.gather_atoms("x", 1, 3)).reshape(-1, 3)
    r = np.array(lmp.gather_atoms("radius", 1, 1))
    lo, hi, _, _, _, periodic, _ = lmp.extract_box()
    L = np.array(hi) - np.array(lo)
    p = np.array(periodic, dtype=bool)
    from scipy.spatial import cKDTree
    box = np.where(p, L, 0.0)
    xs = x - np.array(lo)
    xs[:, p] %= L[p]
    if np.any(~p):
        # (a non-periodic axis: the tree takes no box there)
        tree = cKDTree(xs)
        pairs = tree.query_pairs(2.0 * r.max())
        pairs = np.array(sorted(pairs)) if pairs else np.zeros((0, 2), int)
        d = xs[pairs[:, 0]] - xs[pairs[:, 1]]
        d[:, p] -= L[p] * np.round(d[:, p] / L[p])
    else:
        tree = cKDTree(xs, boxsize=box)
        pairs = np.array(sorted(tree.query_pairs(2.0 * r.max())))
        d = xs[pairs[:, 0]] - xs[pairs[:, 1]]
        d -= L * np.round(d / L)
    gap = np.sqrt((d**2).sum(1)) - r[pairs[:, 0]] - r[pairs[:, 1]]
    return int((gap < 0).sum())


def main():
    p = argparse.ArgumentParser()
    p.add_argument("scene", choices=("pack", "pour"))
    p.add_argument("n", type=int)
    p.add_argument("steps", type=int)
    p.add_argument("--tangential", default="mindlin_total")
    p.add_argument("--mdr-springs", type=int, metavar="CELLS",
                   help="cells of the MDR laws (mdr_adaptive: even; default: the law's)")
    p.add_argument("--engines", default="native,plugin")
    p.add_argument("--energy", action="store_true", help="the plugin accounts the work of the contact forces")
    p.add_argument("--frame-spin", action="store_true", help="the plugin's frame_spin yes (the tangential history "
                   "turns with the contact, LammpsContacts' default; else no, as LAMMPS's granular models)")
    p.add_argument("--record-every", type=int, default=0, metavar="K",
                   help="the plugin records the contacts every K steps (a dump local of compute dem/contact/local)")
    p.add_argument("--dir", default=tempfile.gettempdir())
    p.add_argument("--repeat", type=int, default=1, help="runs of each engine, taking turns; the fastest counts")
    args = p.parse_args()
    try:
        table = bench_table(args)
    except InputError as e:         # (a law or cell count the table refuses: before any run)
        p.error(str(e))
    out = {}
    for _ in range(args.repeat):
        for engine in args.engines.split(","):
            rank, got = run(engine, args, os.path.join(args.dir, f"bench_{engine}.log"), table)
            if rank == 0 and (engine not in out or got["pair_s"] < out[engine]["pair_s"]):
                out[engine] = got
    if rank == 0:
        print(json.dumps(out))


if __name__ == "__main__":
    main()
