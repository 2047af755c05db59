"""Run by test_lammps.py as ``[mpirun -np 2] python tests/lammps/lammps_cross.py``: a sphere pair pressed
together (fixed overlap) and sliding slowly across the boundary between two MPI subdomains (x = 0),
with prescribed motion (fix move). Prints JSON on rank 0: rows of the step, the forces (fx1, fx2, fy1, ...) and the
positions of both atoms every --every steps; 8 G*, R*, the diameter and the slip per step."""
import argparse
import json
import math

from dem_contact.dem.pairs import pair_table
from dem_contact.lammps import LammpsContacts, new_lammps
from dem_contact.laws.slots import P_GSTAR, P_RSTAR
from dem_contact.materials import Material, Sphere
from dem_contact.laws.model import reference_speed

p = argparse.ArgumentParser()
p.add_argument("--steps", type=int, default=3000)
p.add_argument("--every", type=int, default=50)
p.add_argument("--tangential", default="mindlin_total")
a = p.parse_args()

R = 1e-3
mat = Material(E=5e7, nu=0.3, rho=2500.0)
table = pair_table([Sphere(R, mat)], [], mu=0.5, normal="hertz", tangential=a.tangential, v_ref=reference_speed(1.0))
dt = 1e-6
V, s = 1.0, 2e-3          # drift across the subdomain boundary; sliding speed (along y)
delta0 = 2e-5
gap = 2 * R - delta0
dx = 0.6 * R
lmp = new_lammps()
for c in ("units si", "atom_style sphere", "boundary f f f", "atom_modify map array", "processors * 1 1",
          "region box block -0.004 0.004 -0.002 0.002 -0.002 0.004", "create_box 1 box",
          "create_atoms 1 single -0.0025 0 0", f"create_atoms 1 single {-0.0025 + dx!r} 0 "
          f"{math.sqrt(gap * gap - dx * dx)!r}", f"set type 1 diameter {2 * R!r}",
          f"set type 1 mass {table.scenes[0].sphere.mass!r}", f"timestep {dt!r}",
          "group a1 id 1", "group a2 id 2", f"fix m1 a1 move linear {V!r} 0 0",
          f"fix m2 a2 move linear {V!r} {s!r} 0", "pair_style none"):
    lmp.command(c)
bridge = LammpsContacts(lmp, table, [], slots=2, v_max=1.0, frame_spin=False)
names = [f"{q}{i}" for q in ("fx", "fy", "fz", "x", "y", "z") for i in (1, 2)]
for n in names:
    lmp.command(f"variable {n} equal {n[:-1]}[{n[-1]}]")
rows = []
for k in range(0, a.steps, a.every):
    bridge.run(a.every)
    rows.append([k + a.every] + [lmp.extract_variable(n) for n in names])
out = {"columns": ["step"] + names, "rows": rows, "g8": 8.0 * table.params[0, P_GSTAR],
       "r_star": table.params[0, P_RSTAR], "diameter": 2 * R, "slip_per_step": s * dt,
       "ranks": lmp.extract_setting("world_size")}
if lmp.extract_setting("world_rank") == 0:
    print(json.dumps(out))
lmp.close()
