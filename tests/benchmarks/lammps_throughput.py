"""Contact updates per second per MPI rank of a LAMMPS pour (examples/lammps_pour.py): dem_contact's
hertz + default tangential law and hertz + mindlin_total (pair_style dem/contact), against LAMMPS's own
pair granular hertz/material + mindlin with fix wall/gran, on the same scene, on 1 and 2 ranks, in one run
of this script (a script, not a pytest benchmark: each case is its own MPI job).

Two scenes (--scene):

- pour (the example's own scene): spheres of two materials and radii on a loose lattice (spacing 1.15
  diameters) with random velocities (0.3 m/s rms per axis) falling under gravity into a box with five
  walls: few contacts per sphere (about 1 per 15 spheres in the first 1000 steps), many candidate pairs;
- pressed: spheres of both materials with one radius (--same-size) on a cubic lattice closed by six
  walls (--lid), spacing 0.995 diameters, at rest: about 3 contacts per sphere (sphere pairs and walls)
  from the first step, as in a packed bed.

Contacts are counted every --every steps; contact updates = contacts counted x steps between counts.
Two figures per case, in ns per contact update per rank: the whole step (wall_s, the time inside
LAMMPS's ``run``: contact search, laws, forces, integration, communication) and the contact work
(contact_s of lammps_pour.py, per sphere-pair contact update: LAMMPS's Pair + Neigh timers, i.e. the pair
style, dem/contact or granular, and its neighbour lists; the walls are fixes, timed apart, in either case).

Each case runs --repeat times, interleaved with the others; the fastest run of each case is reported
(on a machine shared with other work the slower runs measure the other work).

Usage: python tests/benchmarks/lammps_throughput.py [--scene pour|pressed] [--n 20000] [--steps 1000] [--ranks 1 2]
       [--repeat 3] [--json]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CASES = {"lammps native": ["--native"], "hertz + default": [],
         "hertz + mindlin_total": ["--tangential", "mindlin_total"]}


def pour(args, ranks):
    mpirun = shutil.which("mpirun", path=os.path.join(sys.prefix, "bin")) or "mpirun"
    cmd = [sys.executable, "examples/lammps_pour.py", "--json", *args]
    if ranks > 1:
        cmd = [mpirun, "-np", str(ranks), *cmd]
    r = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT,
                       env=dict(os.environ, PYTHONPATH=str(ROOT)))
    if r.returncode != 0:
        raise SystemExit(r.stderr[-3000:])
    return json.loads(r.stdout)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scene", choices=("pour", "pressed"), default="pour", help="the scene (pour)")
    p.add_argument("--n", type=int, default=20000)
    p.add_argument("--steps", type=int, default=1000)
    p.add_argument("--every", type=int, default=100)
    p.add_argument("--spacing", type=float, default=None,
                   help="lattice spacing [diameters] (pour 1.15, pressed 0.995)")
    p.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    p.add_argument("--repeat", type=int, default=3, help="runs of each case, interleaved; the fastest counts (3)")
    p.add_argument("--json", action="store_true")
    a = p.parse_args()
    scene = ["--n", str(a.n), "--steps", str(a.steps), "--every", str(a.every)]
    if a.scene == "pressed":
        scene += ["--spacing", str(a.spacing or 0.995), "--speed", "0", "--same-size", "--lid"]
    elif a.spacing is not None:
        scene += ["--spacing", str(a.spacing)]
    for args in CASES.values():                      # compile and cache the laws' steps first
        pour(["--n", "200", "--steps", "20", "--every", "10", *args], 1)
    best = {}
    for _ in range(a.repeat):
        for ranks in a.ranks:
            for name, args in CASES.items():
                d = pour(scene + args, ranks)
                if (name, ranks) not in best or d["wall_s"] < best[name, ranks]["wall_s"]:
                    best[name, ranks] = d
    rows = []
    for (name, ranks), d in best.items():
        ns = 1e9 / d["contact_updates_per_s_per_rank"]
        rows.append({"case": name, "scene": a.scene, "ranks": ranks, "natoms": d["natoms"], "steps": d["steps"],
                     "contacts_at_end": d["contacts"], "wall_s": d["wall_s"], "runs": a.repeat,
                     "contact_updates_per_s_per_rank": d["contact_updates_per_s_per_rank"],
                     "ns_per_contact_update_per_rank": ns, "contact_s": d["contact_s"],
                     "contact_ns_per_update_per_rank": d["contact_ns_per_update"]})
    for r in rows:
        base = next(b for b in rows if b["case"] == "lammps native" and b["ranks"] == r["ranks"])
        one = next((b for b in rows if b["case"] == r["case"] and b["ranks"] == 1), None)
        r["cost_vs_native"] = r["ns_per_contact_update_per_rank"] / base["ns_per_contact_update_per_rank"]
        r["contact_work_vs_native"] = r["contact_ns_per_update_per_rank"] / base["contact_ns_per_update_per_rank"]
        r["speedup_vs_1_rank"] = one["wall_s"] / r["wall_s"] if one else None
    if a.json:
        print(json.dumps(rows, indent=2))
    else:
        print(f"scene: {a.scene}; ns per contact update per rank, whole step and contact work")
        print(f"{'case':24s} {'ranks':>5s} {'contacts':>9s} {'wall_s':>8s} {'step ns':>8s} {'x native':>9s} "
              f"{'contact ns':>11s} {'x native':>9s} {'speedup':>8s}")
        for r in rows:
            sp = "" if r["speedup_vs_1_rank"] is None else f"{r['speedup_vs_1_rank']:.2f}"
            print(f"{r['case']:24s} {r['ranks']:5d} {r['contacts_at_end']:9d} {r['wall_s']:8.2f} "
                  f"{r['ns_per_contact_update_per_rank']:8.0f} {r['cost_vs_native']:9.2f} "
                  f"{r['contact_ns_per_update_per_rank']:11.0f} {r['contact_work_vs_native']:9.2f} {sp:>8s}")


if __name__ == "__main__":
    main()
