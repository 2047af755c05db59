"""The per-step kernels of the LAMMPS bridge on their own (no LAMMPS needed): the Verlet candidates against
a brute-force search, and the atoms marked as able to change rank."""
import numpy as np

from dem_contact.lammps import contact_terms as T
from dem_contact.lammps import kernels as K
from dem_contact.walls import PlaneWall, pack


def _points(n, seed, box=1.0):
    rng = np.random.default_rng(seed)
    return rng.uniform(0.0, box, (n, 3)), rng.uniform(0.02, 0.05, n)


def test_candidates_are_every_close_pair_once_lower_id_first():
    nall, nlocal, skin = 400, 300, 0.01
    x, radius = _points(nall, 1)
    tag = np.random.default_rng(2).permutation(nall).astype(np.int32) + 1     # ids unrelated to indices (LAMMPS's int32)
    planes = np.array([[0.0, 0.0, 0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 0.0, 0.0, -1.0]])
    walls, _ = pack([PlaneWall(tuple(p[:3]), tuple(p[3:])) for p in planes])
    pairs, wall_pairs = K.candidates(nlocal, nall, x, radius, tag, walls, radius.max(), skin)
    got = {(int(i), int(j)) for i, j in pairs}
    assert len(got) == len(pairs)                                   # no pair twice
    want = set()
    for i in range(nlocal):
        for j in range(nall):
            if j == i or np.linalg.norm(x[j] - x[i]) >= radius[i] + radius[j] + skin:
                continue
            if j >= nlocal or tag[i] < tag[j]:                         # local pairs from the lower id
                want.add((i, j))
    assert got == want
    assert np.all(np.diff(pairs[:, 0]) >= 0)                        # in the order of i
    gap = np.stack([(x[:nlocal] - p[:3]) @ p[3:] for p in planes], axis=1)
    want_w = {(i, w, 0) for i in range(nlocal) for w in range(2) if gap[i, w] < radius[i] + skin}
    assert {(int(i), int(w), int(e)) for i, w, e in wall_pairs} == want_w     # (a plane: one element, 0)


def test_wall_candidates_of_a_mesh_are_every_close_element_in_order():
    """The Verlet list of wall elements, with a mesh's triangles binned into the cells of the atoms: every
    (atom, wall, element) whose element is closer than r + skin to the centre (brute force over all
    triangles, by the contract's distance), none other, each once, in the order of atom, wall, element; the
    plane between the mesh's walls in that order too; a mesh far from every atom has none."""
    import os

    from dem_contact.walls import MeshWall
    from dem_contact.walls import table as W

    nall, nlocal, skin = 400, 300, 0.01
    x, radius = _points(nall, 3)
    hopper = MeshWall.from_stl(os.path.join(os.path.dirname(__file__), "..", "..", "examples", "hopper.stl"))
    span = hopper.vertices.max(axis=0) - hopper.vertices.min(axis=0)
    scale = 1.2 / span.max()                                 # the hopper over the atoms' box, and beyond it
    near = MeshWall(hopper.vertices * scale - 0.1, hopper.triangles)
    far = MeshWall(hopper.vertices * scale + 50.0, hopper.triangles)
    walls, _ = pack([near, PlaneWall((0.0, 0.0, 0.5), (0.0, 0.0, 1.0)), far])
    tag = np.arange(nall, dtype=np.int32) + 1
    _, hits = K.candidates(nlocal, nall, x, radius, tag, walls, radius.max(), skin)
    want = [(i, w, e) for i in range(nlocal) for w in range(3) for e in range(W.elements(walls, w))
            if W.distance(walls, w, e, *x[i]) < radius[i] + skin]
    assert len(want) > nlocal // 2 and any(w == 0 for _, w, _ in want)
    assert [tuple(int(q) for q in h) for h in hits] == want


def test_near_boundary_marks_atoms_within_reach_of_open_faces_only():
    x = np.array([[4.6, 5.0, 5.0], [3.0, 5.0, 5.0], [0.2, 5.0, 5.0], [3.0, 9.7, 5.0], [3.0, 5.0, 0.1]])
    near = np.zeros(len(x), dtype=np.bool_)
    lo, hi = np.zeros(3), np.array([5.0, 10.0, 10.0])
    # the face x = 5 is shared with another subdomain; y is periodic; the z faces and x = 0 are walls
    open_lo = np.array([False, True, False])
    open_hi = np.array([True, True, False])
    K.near_boundary(len(x), x, lo, hi, open_lo, open_hi, 0.5, near)
    assert near.tolist() == [True, False, False, True, False]


def _bridge_step(S, g, step, all_atoms, save):
    """One step of the bridge's kernels (gather, law in place, scatter) on the state S of one rank."""
    from dem_contact.dem.contact3d import contact_forces_serial
    t = g["table"]
    buf = S["buf"]
    m, nt, stale = K.gather_contacts(
        g["n"], g["x"], g["v"], g["omega"], g["radius"], g["rmass"], g["tag"], g["typ"], g["walls"],
        g["wall_mat"], *g["cand"], S["cand_rows"], S["keys"], S["sep"], np.inf, S["H"], t.normal_id, t.sphere_row, t.wall_row,
        g["dt"], True, S["rebuilt"], True, S["stat"], S["used"], g["near"], all_atoms, S["prev"], S["n_prev"],
        S["touched"], t.params, np.ones((len(t.params), T.N_ROWINFO)), False, np.ones((t.sphere_row.shape[0], 2)), 1.0,
        np.zeros(K.N_ONSET), *buf[:12])
    assert stale == 0
    _, body, src, dst, hrow, rows, normals, overlaps, vel, wn, _, _, forces, tforces, spins, torques = buf
    K.relative_spins(g["omega"], body, m, spins, g["walls"], True)
    contact_forces_serial(t.normal_id, t.tangential_id, t.params, rows[:m], S["H"], normals[:m], overlaps[:m],
                          vel[:m], wn[:m], g["dt"], forces[:m], tforces[:m], src[:m], spins=spins[:m],
                          torques=torques[:m])
    S["f"][:] = 0.0                                       # LAMMPS clears forces and torques every step
    S["torque"][:] = 0.0
    K.scatter_contacts(g["n"], g["x"], g["v"], g["omega"], g["radius"], g["rmass"], g["typ"], m, body, src, dst, normals, overlaps, S["H"], forces, tforces, torques, True,
                       S["f"], S["torque"], S["stat"], S["saved"], step, S["acc"], all_atoms, S["touched"], nt, save)
    S["prev"], S["touched"], S["n_prev"], S["rebuilt"] = S["touched"], S["prev"], nt, False
    return m


def test_per_atom_writes_in_proportion_to_the_contacts_match_a_pass_over_every_atom():
    """The bridge writes forces, torques and statistics only for the atoms with a contact now or at the
    last step: along a run in which contacts form and end (spheres moving through each other and onto a
    floor), forces, torques and the statistics equal those of a pass over every local atom, bit for bit, and
    the forces saved at the last step of a run are those applied."""
    from dem_contact.dem.pairs import pair_table
    from dem_contact.materials import Material, Sphere, Wall

    n, slots = 40, 8
    mat = Material(5e7, 0.3, 2500.0)
    table = pair_table([Sphere(1e-3, mat)], [Wall(mat)], mu=0.3)
    rng = np.random.default_rng(3)
    x = rng.uniform(0.0, 0.008, (n, 3))
    x[:, 2] += 0.5e-3
    v = rng.normal(0.0, 1.0, (n, 3))
    g = dict(table=table, n=n, x=x, v=v, omega=rng.normal(0.0, 50.0, (n, 3)), radius=np.full(n, 1e-3),
             rmass=np.full(n, mat.rho * 4.0 / 3.0 * np.pi * 1e-9), tag=np.arange(1, n + 1, dtype=np.int32),
             typ=np.ones(n, dtype=np.int32), walls=pack([PlaneWall.axis("z", 0.0, "lo")])[0],
             wall_mat=np.zeros(1, dtype=np.int64), dt=2e-6, near=np.zeros(n, dtype=np.bool_))

    def state():
        # (LAMMPS's types: int32 ids and types, keys, separations and statistics in columns of one per-atom
        # array, as the bridge passes them: the kernels compiled once for the bridge and this test)
        cols = np.zeros((n, 5 * slots + K.N_STAT + 1))
        return dict(keys=cols[:, :slots], sep=cols[:, slots:5 * slots], H=np.zeros((n * slots, table.history_size)),
                    stat=cols[:, 5 * slots:5 * slots + K.N_STAT], saved=np.zeros((n, K.N_SAVED)), used=np.zeros((n, slots), bool),
                    acc=np.zeros((n, 7)), prev=np.zeros(n, dtype=np.int64),
                    touched=np.zeros(n, dtype=np.int64), n_prev=0, f=np.zeros((n, 3)), torque=np.zeros((n, 3)),
                    rebuilt=True, buf=None, cand_rows=None)

    every, few = state(), state()            # a pass over every atom at every step; the bridge's
    skin, counts = 2e-4, []
    x_ref = None
    for step in range(400):
        rebuild = x_ref is None or np.abs(x - x_ref).max() > 0.25 * skin
        if rebuild:
            g["cand"] = K.candidates(n, n, x, g["radius"], g["tag"], g["walls"], 1e-3, skin)
            x_ref = x.copy()
            rows = np.full((len(g["cand"][0]) + len(g["cand"][1]), 2), -1, dtype=np.int64)
            for S in (every, few):
                S["cand_rows"], S["rebuilt"] = rows.copy(), True
                S["buf"] = K.contact_buffers(2 * len(rows) + 16, g["table"].params)
        save = step % 100 == 99
        counts.append(_bridge_step(every, g, step, True, save))
        _bridge_step(few, g, step, rebuild or save, save)
        for key in ("f", "torque", "stat", "H", "keys", "sep"):
            assert np.array_equal(every[key], few[key]), (step, key)
        assert not few["acc"].any()
        if save:
            assert np.array_equal(few["saved"][:, :3], few["f"])
            assert np.array_equal(few["saved"][:, 3:6], few["torque"])
            f, torque = np.zeros((n, 3)), np.zeros((n, 3))
            periods, periodic = np.diag([0.008, 0.008, 0.02]), np.array([True, True, False])

            def match(x=x, v=v, omega=g["omega"], mark=step):
                return K.saved_match(n, x, v, omega, g["radius"], g["rmass"], g["typ"], few["saved"], mark,
                                     periods, periodic, 1e-17)

            assert match()
            K.reapply_saved(n, f, torque, few["saved"])
            assert np.array_equal(f, few["f"]) and np.array_equal(torque, few["torque"])
            assert not match(mark=step + 1)                                         # another step's
            for name, arr, d in (("x", x, 2), ("x", x, 0), ("v", v, 1), ("omega", g["omega"], 2)):
                changed = arr.copy()
                changed[n // 2, d] += 1e-9
                assert not match(**{name: changed}), name                           # a state changed since
            wrapped = x.copy()
            wrapped[n // 3, 0] -= 0.008                                              # a wrap: the same state
            wrapped[n // 4, 1] += 0.008
            assert match(x=wrapped)
            wrapped[n // 5, 2] += 0.02                                               # z is not periodic
            assert not match(x=wrapped)
        x += v * g["dt"] * 5.0                   # (positions moved by hand: contacts form and end)
        v[:, 2] -= 0.02
    counts = np.array(counts)
    assert counts.max() >= 5 and (np.diff(counts) < 0).any() and (np.diff(counts) > 0).any()
