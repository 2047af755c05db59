"""The contact search of ``Census`` on its own (no LAMMPS needed): its candidates against a brute-force search."""
import numpy as np

from dem_contact.lammps import census as K
from dem_contact.walls import PlaneWall, pack


def _points(n, seed, box=1.0):
    rng = np.random.default_rng(seed)
    return rng.uniform(0.0, box, (n, 3)), rng.uniform(0.02, 0.05, n)


def test_candidates_are_every_close_pair_once():
    nall, nlocal, skin = 400, 300, 0.01
    x, radius = _points(nall, 1)
    tag = np.random.default_rng(2).permutation(nall).astype(np.int32) + 1     # ids unrelated to indices (LAMMPS's int32)
    planes = np.array([[0.0, 0.0, 0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 0.0, 0.0, -1.0]])
    walls, _ = pack([PlaneWall(tuple(p[:3]), tuple(p[3:])) for p in planes])
    pairs, wall_pairs = K.candidates(nlocal, nall, x, radius, tag, walls, radius.max(), skin)
    assert np.all(pairs[:, 0] < nlocal)                             # (i local)
    got = {frozenset((int(i), int(j))) for i, j in pairs}
    assert len(got) == len(pairs)                                   # no pair twice
    want = set()
    for i in range(nlocal):
        for j in range(nall):
            if j != i and np.linalg.norm(x[j] - x[i]) < radius[i] + radius[j] + skin:
                want.add(frozenset((i, j)))
    assert got == want
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

