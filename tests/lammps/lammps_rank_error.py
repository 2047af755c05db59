"""Run by test_lammps.py as ``mpirun -np 2 python tests/lammps/lammps_rank_error.py OUT_DIR``: two ranks (subdomains
x < 0 and x > 0), every atom on rank 0, and an error injected into the contact step on rank 1 only,
which owns no atom (so no per-atom flag can carry it). Each rank writes OUT_DIR/rank<k>.json: its
number of local atoms and the exception its ``run`` raised (null for none)."""
import json
import os
import sys

from lammps_injected import failing_after

from dem_contact.dem.pairs import pair_table
from dem_contact.lammps import LammpsContacts, new_lammps
from dem_contact.materials import Material, Sphere

mat = Material(E=5e7, nu=0.25, rho=2500.0)
table = pair_table([Sphere(1e-3, mat)], [], mu=0.3, tangential="mindlin_total")
lmp = new_lammps()
for c in ("units si", "atom_style sphere", "boundary f f f", "atom_modify map array", "processors 2 1 1",
          "region box block -0.01 0.01 -0.01 0.01 -0.01 0.01", "create_box 1 box",
          "create_atoms 1 single -0.005 0 0", "create_atoms 1 single -0.005 0 0.0019",
          "set type 1 diameter 2e-3", f"set type 1 density {mat.rho!r}", "timestep 1e-8",
          "fix nve all nve/sphere"):
    lmp.command(c)
me = lmp.extract_setting("world_rank")
bridge = LammpsContacts(lmp, table, slots=4, v_max=1.0, check_every=10)
if me == 1:
    bridge._step = failing_after(5, bridge._step)          # (a rank without atoms skips the kernels)
raised = None
try:
    bridge.run(50)
except Exception as e:            # (reported, not raised: every rank prints its outcome)
    raised = type(e).__name__
with open(os.path.join(sys.argv[1], f"rank{me}.json"), "w") as f:
    json.dump({"nlocal": lmp.extract_setting("nlocal"), "raised": raised}, f)
lmp.close()
