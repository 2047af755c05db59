"""The per-step kernels of the LAMMPS bridge on their own (no LAMMPS needed): the Verlet candidates against
a brute-force search, and the atoms marked as able to change rank."""
import numpy as np

from dem_contact.lammps import kernels as K


def _points(n, seed, box=1.0):
    rng = np.random.default_rng(seed)
    return rng.uniform(0.0, box, (n, 3)), rng.uniform(0.02, 0.05, n)


def test_candidates_are_every_close_pair_once_lower_id_first():
    nall, nlocal, skin = 400, 300, 0.01
    x, radius = _points(nall, 1)
    tag = np.random.default_rng(2).permutation(nall).astype(np.int64) + 1     # ids unrelated to indices
    walls = np.array([[0.0, 0.0, 0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 0.0, 0.0, -1.0]])
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
    gap = np.stack([(x[:nlocal] - w[:3]) @ w[3:] for w in walls], axis=1)
    want_w = {(i, w) for i in range(nlocal) for w in range(2) if gap[i, w] < radius[i] + skin}
    assert {(int(i), int(w)) for i, w in wall_pairs} == want_w


def test_near_boundary_marks_atoms_within_reach_of_open_faces_only():
    x = np.array([[4.6, 5.0, 5.0], [3.0, 5.0, 5.0], [0.2, 5.0, 5.0], [3.0, 9.7, 5.0], [3.0, 5.0, 0.1]])
    near = np.zeros(len(x), dtype=np.bool_)
    lo, hi = np.zeros(3), np.array([5.0, 10.0, 10.0])
    # the face x = 5 is shared with another subdomain; y is periodic; the z faces and x = 0 are walls
    open_lo = np.array([False, True, False])
    open_hi = np.array([True, True, False])
    K.near_boundary(len(x), x, lo, hi, open_lo, open_hi, 0.5, near)
    assert near.tolist() == [True, False, False, True, False]
