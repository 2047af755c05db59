"""Per-step contact work of the LAMMPS bridge, on one MPI rank: contact search over local and ghost
atoms, history lookup by partner atom id, the contact laws, forces and torques. No LAMMPS import here:
the kernels take numpy views of LAMMPS's per-atom arrays.

History storage. Every atom carries ``slots`` history rows in per-atom arrays (LAMMPS ``fix
property/atom d2_...``, which migrate with the atom between ranks and survive neighbour-list rebuilds and
atom sorting): the keys of its rows, ``keys`` (nmax, slots), in a narrow array read at every step; for
each row the separation of its contact when it was last matched and a mark of an out-of-date second copy
(see below), ``sep`` (nmax, 4 slots), in another; and the rows in a third, viewed as ``H`` (nmax * slots, history_size): row i * slots + s is row s of atom i. A key is the
partner's atom id (> 0), the wall's key (< 0, ``walls.table.history_key``: -(w + 1) for wall w when
every wall has one patch, as planes and cylinders; for a mesh, one per side and set of triangles joined
by flat or convex edges) for a wall, or 0 for a free row. A wall contact that moves from one element to
another of its patch (a mesh's triangles) keeps its row: the row of a wall contact that ended is freed only after the new contacts of the step have
looked for their rows by key. A contact is the partner and the
periodic image it is touched through: in a periodic box narrower than two diameters an atom can touch
two images of one partner, each its own contact with its own row, told apart by the separation
(x_partner - x_atom, continuous in time whatever the atoms' wraps), which is stored with the row when it
is taken and at every rebuild of the Verlet lists, and differs between two images by a box period. The
Verlet list keeps the slot numbers found for each candidate pair, so a continuing contact finds its
rows without a search.

One step: ``gather_contacts`` finds the contacts among the Verlet candidates, their history rows and the
inputs of the law; the batch law kernel of the law family (``dem.contact3d.batch_loop``, the
law inlined in its loop) advances the histories in place, in the per-atom rows; and ``scatter_contacts``
writes the second copies of the histories and the forces and torques into LAMMPS's arrays.

Newton's third law between ranks, without reverse communication: each rank computes the contacts of its
own (local) atoms, including those with ghost atoms, and writes forces and torques on local atoms only.
A contact between atoms on two ranks is therefore evaluated twice, once by each owner, each with its own
copy of the history. Both evaluations are made in one canonical order, the atom with the lower id as
body 1, from the same inputs (ghost positions, velocities and spins are exact copies of the owner's),
so the two copies of the history stay bitwise equal and the two forces are exact opposites. A contact
between two local atoms is evaluated once; each atom has a row for it: the lower atom id's is the current
one, and the other is rewritten with it at every step while either atom is near a subdomain face it can
cross (``near_boundary``), so that an atom that moves to another rank takes a current copy along; the
bridge has every second copy rewritten at the last step of each run and at every step of a run in which
atoms can change rank otherwise (subdomains that move), so that a pair split between ranks between runs
(a restart read on other ranks, ``balance``, ``displace_atoms``) or by a rebalancing finds two current
copies. A second copy not rewritten at every step is marked out of date (at the rebuild that stops its
rewriting) until the run's last step rewrites it: a contact that would read a marked row as its only
copy (its atom changed rank in a way the bridge did not follow, as after a restart file written during
a run and read on other ranks) is counted, and the bridge refuses it. (Across a periodic boundary the
ghost position is x + L, rounded: there the two sides agree to rounding error only.)

Kinematics follow LAMMPS's granular models (``pair granular``, ``fix wall/gran``): the slip velocity
uses the full radii, v = v1 - v2 + (R1 w1 + R2 w2) x n; the torque arm is R - delta/2 for a sphere pair
and R for a wall. The terms of one contact (its law's inputs, its parameter row for atoms of other sizes,
its load on a wall) are ``contact_terms``'s, which the plugin's steps share.

Walls: packed rows of ``walls.table.pack`` (float64[n_walls, walls.ROW_SIZE]), read only through the wall
kernels of ``walls.table`` (``contact``: distance and normal; ``velocity``: the wall's velocity at the
contact point, subtracted from the sphere's; ``history_key``: the key of the contact's history), so that
every kind of wall of the table works here; ``contact_terms.wall_loads`` sums each wall's force, torque and
power.
"""
import math

import numpy as np
from numba import njit

from ..laws.dispatch import uses_rate
from ..laws.vector import V_N
from ..walls import table as W
from ..walls.search import near_elements
from .contact_terms import (RI_ALPHA, RI_DEEPEST, RI_TC, contact_row, effective, frame_spin_rate, normal_cross,
                             put_contact, resized, size_factor, sphere_pair, wall_slip)

# columns of the per-atom statistics array (d2 property, written for local atoms every step)
ST_PAIRS = 0     # sphere-sphere contacts of the atom
ST_WALLS = 1     # wall contacts of the atom
ST_NEED = 2      # history rows the atom needed (its contacts), largest since the column was zeroed
ST_OVERLAP = 3   # largest overlap of its contacts [m]
N_STAT = 4

# columns of the per-atom stored contact force (d2 property): reapplied at LAMMPS's run set-up
SF_MARK = 6      # 1 + the mark (evaluation number) of the step the force and torque were saved at (0: none)
SF_X = 7         # the atom's state when they were saved: position (3 columns), radius, velocity (3),
SF_R = 10        # spin (3), mass and type
SF_V = 11
SF_W = 14
SF_M = 17
SF_T = 18
SF_ID = 19       # the atom's id at the end of the last run (0: none yet), which its partners' keys name
N_SAVED = 20

# onset statistics of new contacts (float64[N_ONSET], accumulated by gather_contacts)
ON_FAST = 0      # contacts that began at a normal speed above v_max
ON_VMAX = 1      # the largest such speed [m/s]
ON_STEPS = 2     # the fewest time steps per contact time among them
N_ONSET = 3

# per-rank summary returned by scatter_contacts
R_PAIRS = 0      # sphere-sphere contacts evaluated on this rank
R_WALLS = 1      # wall contacts evaluated on this rank
R_OVERLAP = 2    # largest overlap [m]
R_BAD = 3        # local atoms whose contact force or torque was not finite (given none)
N_SUMMARY = 4


def atom_columns(slots: int) -> int:
    """Columns of the per-atom array before the statistics: the keys."""
    return slots


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
    """Verlet lists of the local atoms: sphere pairs (i local; j local with a higher atom id, or ghost) closer
    than r_i + r_j + skin, in the order of i, and wall pairs (i, w, element e) whose surface is closer to
    the centre than r_i + skin (``walls.search.near_elements``: a mesh's triangles binned into cells). walls: the packed rows (``walls.table.pack``). Valid while no atom has moved
    more than skin / 2 and the local and ghost atoms keep their indices. Returns (pairs int64[m, 2],
    wall_pairs int64[k, 3]).

    Cell lists of side 2 r_max + skin (Allen & Tildesley, Computer Simulation of Liquids, 1987, sec. 5.3.2),
    local atoms and ghosts in separate lists on one grid: a pair of local atoms is found once, from the
    cell of the first in cell order, in the half of the 27-cell stencil ahead of it (the rest of its cell
    and the next along z, and the four (x, y) columns ahead, three cells each); a local atom's ghost
    partners in the whole stencil. The pairs are then put in the order of i (counting sort)."""
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
        first = np.empty(cap, dtype=np.int64)
        second = np.empty(cap, dtype=np.int64)
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
                            j = order[q]
                            # the lower atom id first
                            lower = tag[j] < ti
                            first[m] = j if lower else i
                            second[m] = i if lower else j
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
                                    first[m] = i
                                    second[m] = j
                                m += 1
        if m <= cap:
            break
        cap = m
    # in the order of i
    fill = np.zeros(nlocal + 1, dtype=np.int64)
    for c in range(m):
        fill[first[c] + 1] += 1
    for i in range(nlocal):
        fill[i + 1] += fill[i]
    pairs = np.empty((m, 2), dtype=np.int64)
    for c in range(m):
        q = fill[first[c]]
        fill[first[c]] = q + 1
        pairs[q, 0] = first[c]
        pairs[q, 1] = second[c]
    return pairs, near_elements(nlocal, x, radius, walls, skin)


@njit(inline="always", cache=True)
def _separation(x, radius, i, j):
    """(dx, dy, dz) = x_j - x_i, its squared length and r_i + r_j."""
    dx = x[j, 0] - x[i, 0]
    dy = x[j, 1] - x[i, 1]
    dz = x[j, 2] - x[i, 2]
    return dx, dy, dz, dx * dx + dy * dy + dz * dz, radius[i] + radius[j]


@njit(cache=True)
def overlapping(x, radius, walls, cand, cand_walls):
    """The candidates in contact now: (pairs, deltas, wall_hits (i, w, element), wall_deltas), deltas > 0 the
    overlaps."""
    m = 0
    keep = np.empty(cand.shape[0], dtype=np.int64)
    deltas = np.empty(cand.shape[0])
    for c in range(cand.shape[0]):
        i = cand[c, 0]
        j = cand[c, 1]
        _, _, _, r2, rs = _separation(x, radius, i, j)
        if r2 < rs * rs:
            keep[m] = c
            deltas[m] = rs - math.sqrt(r2)
            m += 1
    pairs = np.empty((m, 2), dtype=np.int64)
    for k in range(m):
        pairs[k, 0] = cand[keep[k], 0]
        pairs[k, 1] = cand[keep[k], 1]
    kw = 0
    wkeep = np.empty(cand_walls.shape[0], dtype=np.int64)
    wdel = np.empty(cand_walls.shape[0])
    for c in range(cand_walls.shape[0]):
        i = cand_walls[c, 0]
        w = cand_walls[c, 1]
        gap, _, _, _ = W.contact_of(walls, w, cand_walls[c, 2], x[i, 0], x[i, 1], x[i, 2], radius[i])
        d = radius[i] - gap
        if d > 0.0:
            wkeep[kw] = c
            wdel[kw] = d
            kw += 1
    hits = np.empty((kw, 3), dtype=np.int64)
    for k in range(kw):
        for q in range(3):
            hits[k, q] = cand_walls[wkeep[k], q]
    return pairs, deltas[:m], hits, wdel[:kw]


@njit(cache=True)
def any_touching(x, radius, walls, cand, cand_walls):
    """Whether any candidate of the Verlet lists is in contact now (a step without contacts is skipped)."""
    for c in range(cand.shape[0]):
        _, _, _, r2, rs = _separation(x, radius, cand[c, 0], cand[c, 1])
        if r2 < rs * rs:
            return True
    for c in range(cand_walls.shape[0]):
        i = cand_walls[c, 0]
        gap, _, _, _ = W.contact_of(walls, cand_walls[c, 1], cand_walls[c, 2], x[i, 0], x[i, 1], x[i, 2], radius[i])
        if gap < radius[i]:
            return True
    return False


@njit(cache=True)
def find_contacts(nlocal, nall, x, radius, tag, walls, rmax):
    """The contacts of the local atoms now (candidates with no skin, then their overlaps)."""
    cand, cand_walls = candidates(nlocal, nall, x, radius, tag, walls, rmax, 0.0)
    return overlapping(x, radius, walls, cand, cand_walls)


@njit(cache=True)
def _find_row(keys, sep, i, key, dx, dy, dz, tol2):
    """The slot of atom i that keeps contact ``key`` at separation (dx, dy, dz) (x_partner - x_i): among the
    rows with that key (one per periodic image of the partner touched), the one stored with the nearest
    separation, if nearer than sqrt(tol2) (half the shortest box period; a wall: its row); else -1."""
    best = -1
    for s in range(keys.shape[1]):
        if keys[i, s] == key:
            if key < 0.0:
                return s
            ex = sep[i, 4 * s] - dx
            ey = sep[i, 4 * s + 1] - dy
            ez = sep[i, 4 * s + 2] - dz
            d2 = ex * ex + ey * ey + ez * ez
            if d2 < tol2:
                best = s
                tol2 = d2
    return best


@njit(inline="always", cache=True)
def _store_sep(sep, i, s, dx, dy, dz):
    sep[i, 4 * s] = dx
    sep[i, 4 * s + 1] = dy
    sep[i, 4 * s + 2] = dz


@njit(cache=True)
def _free_row(keys, i):
    for s in range(keys.shape[1]):
        if keys[i, s] == 0.0:
            return s
    return -1


@njit(inline="always", cache=True)
def _candidate(cand, cand_walls, walls, c, tag, nlocal, x):
    """Candidate c of the lists (sphere pairs, then wall pairs): (i, j, key of j in atom i's rows, whether
    j is a local atom); j = -1 for a wall, keyed by its wall, element and the side of the atom (x)."""
    npc = cand.shape[0]
    if c < npc:
        j = cand[c, 1]
        return cand[c, 0], j, float(tag[j]), j < nlocal
    k = c - npc
    i = cand_walls[k, 0]
    return i, -1, W.key_of(walls, cand_walls[k, 1], cand_walls[k, 2], x[i, 0], x[i, 1], x[i, 2]), False


@njit(inline="always", cache=True)
def _copies(i, j, ri, rj, tag, slots, local_j, near):
    """The H rows that keep the history of contact (i, j) with slots ri, rj: (current, second copy or -1).

    A contact with a ghost atom or a wall has one copy here, atom i's. A contact of two local atoms has a
    copy in each atom's rows: the current one is that of the lower atom id (so local indices, which LAMMPS
    changes when it sorts atoms, do not matter); the other is kept equal to it (written every step) only
    while one of the two atoms is near its subdomain boundary (``near``), that is while it may move to
    another rank and take its copy along. Once an atom is near the boundary at a rebuild of the lists, the
    copy is rewritten at the next step."""
    if not local_j:
        return i * slots + ri, -1
    a = i * slots + ri
    b = j * slots + rj
    if tag[j] < tag[i]:
        a, b = b, a
    return a, (b if near[i] | near[j] else -1)      # (no short-circuit: a branch here costs ~10 ns)


@njit(inline="always", cache=True)
def _release(keys, H, i, r):
    """Free slot r of atom i: key and history zeroed."""
    keys[i, r] = 0.0
    row = i * keys.shape[1] + r
    for q in range(H.shape[1]):
        H[row, q] = 0.0


@njit(inline="always", cache=True)
def _clear_stat(stat, i):
    """Zero the statistics of atom i that describe one step (all but ST_NEED)."""
    for d in range(N_STAT):
        if d != ST_NEED:
            stat[i, d] = 0.0


@njit(cache=True)
def stiffest_candidate(cand, cand_walls, radius, rmass, typ, wall_mat, sphere_row, wall_row, rowinfo):
    """(shortest contact time at v_max [s], its parameter row, i, j) over the candidates of the Verlet lists
    (the pairs present; j = -1 for a wall), from each row's by the Hertzian scaling (``size_factor``); (inf, -1,
    -1, -1) without candidates."""
    best = np.inf
    brow = -1
    bi = -1
    bj = -1
    for c in range(cand.shape[0] + cand_walls.shape[0]):
        if c < cand.shape[0]:
            i = cand[c, 0]
            j = cand[c, 1]
            row = sphere_row[typ[i] - 1, typ[j] - 1]
        else:
            i = cand_walls[c - cand.shape[0], 0]
            j = -1
            row = wall_row[typ[i] - 1, wall_mat[cand_walls[c - cand.shape[0], 1]]]
        rs, ms = effective(radius, rmass, i, j, rowinfo, row)
        tc = rowinfo[row, RI_TC] * size_factor(rowinfo, row, rs, ms)
        if tc < best:
            best = tc
            brow = row
            bi = i
            bj = j
    return best, brow, bi, bj


@njit(cache=True)
def deep_overlaps(m, body, overlaps, radius, rmass, pair_rows, rowinfo):
    """(count, largest ratio): the contacts among the first m whose overlap exceeds that of a head-on impact
    at v_max of their pair (RI_DEEPEST scaled by ``size_factor``), and the largest overlap over that (0 if none)."""
    count = 0
    worst = 0.0
    for k in range(m):
        a = body[k, 0]
        b = body[k, 1]
        row = pair_rows[k]
        rs, ms = effective(radius, rmass, a, b, rowinfo, row)
        ratio = overlaps[k] / (rowinfo[row, RI_DEEPEST] * size_factor(rowinfo, row, rs, ms))
        if ratio > 1.0:
            count += 1
            worst = max(worst, ratio)
    return count, worst


@njit(cache=True)
def gather_contacts(nlocal, x, v, omega, radius, rmass, tag, typ, walls, wall_mat, cand, cand_walls, cand_rows,
                    keys, sep, sep_tol2, H, nid, sphere_row, wall_row, dt, advance, rebuilt, frame_spin, stat, used, near,
                    all_atoms, prev, n_prev, touched, params, rowinfo, sized, type_size, v_max, onset, work, body, src,
                    dst, hrow, pair_rows, normals, overlaps, velocities, wn, pc, prow):
    """The contacts of the local atoms at this step, laid out for the batch law kernel
    (``dem.contact3d.batch_loop``), with the H rows of their histories.

    x, v, omega: float64[nall, 3]; radius, rmass: float64[nall]; tag: int[nall] atom ids; typ: int[nall]
    atom types (1-based, as LAMMPS); walls: the packed rows (``walls.table.pack``); wall_mat: int64[n_walls] column of
    wall_row; cand, cand_walls: the Verlet lists (``candidates``); cand_rows: int64[len(cand) +
    len(cand_walls), 2] the history slots of both atoms of each candidate found at earlier steps (-1: none;
    all -1 when the lists were rebuilt): a continuing contact finds its rows without a search; keys:
    float64[nmax, slots], sep: float64[nmax, 4 slots] (the separation stored with each row and the
    out-of-date mark of a second copy, see the module's docstring; written when a row is taken or found by
    key, if ``advance``; the bridge clears the marks when it has every second copy rewritten), sep_tol2: the square
    of half the shortest period of the box (inf if none); H: float64[nmax * slots, history_size] histories; params rows: sphere_row,
    wall_row; dt [s]; advance: False at LAMMPS's set-up call (nothing is advanced: rows are neither freed
    nor taken); rebuilt: the lists were rebuilt since the last step (the rows of every local atom that no
    contact uses are then freed; otherwise a contact that ended frees the rows cached for its candidate,
    which a contact always is until the next rebuild); frame_spin: pass the spin of the contact frame about
    the normal (False: wn = 0, LAMMPS's granular models); stat: float64[nmax, N_STAT] per-atom statistics
    (local rows written, ST_NEED the largest since the column was zeroed); used: bool[>= nlocal, slots]
    scratch; near: bool[>= nlocal] the local atoms that may change rank before the lists are rebuilt
    (``near_boundary``).

    Sizes: params float64[n_rows, N_PARAMS] and rowinfo float64[n_rows, N_ROWINFO] (RI_...); prow int64[:]
    receives the row of each contact in pc (float64[n_rows + buffer length, N_PARAMS], whose first n_rows rows
    are params): its pair's row, or where ``sized`` and an atom of the contact has not its type's radius and
    mass (type_size float64[n_types, 2], to 1e-12), pc[n_rows + k], the row of its pair of types with the R*
    and m* of its two atoms (``contact_row``). onset float64[N_ONSET]: the contacts that begin (advance only) at a normal speed above v_max
    [m/s] are counted there (ON_...), with the fewest time steps per contact time among them.

    Per-atom work in proportion to the contacts: the statistics columns ST_PAIRS, ST_WALLS, ST_OVERLAP are
    zero for every local atom that had no contact at the last step, so only the atoms prev[:n_prev] (those
    that had one, with the same local indices: no rebuild since) are zeroed; all_atoms: zero every local
    atom's instead (a rebuild, a new run, reallocated arrays). The local atoms with a contact now are
    listed in touched int64[>= nlocal] (each once), for ``scatter_contacts``.

    Fills the first m rows of the buffers (``contact_buffers``, at least as long as the candidates): body
    int64[:, 2] bodies 1 and 2 of each contact (the lower atom id first; body 2 = -(w + 1) for wall w); src
    int64[:] the H row that keeps the law's history (-1: none) and dst int64[:] the row of a second copy
    (-1: none), see ``_copies``; hrow int64[:] the H row the law reads (-1: none, a new contact: zeros);
    pair_rows int64[:], normals float64[:, 3], overlaps float64[:], velocities float64[:, 3], wn float64[:]:
    the inputs of the law; work int64[:, 3] scratch. When ``advance``, every contact has its rows, hrow ==
    src, and the history to advance is in row src (copied there from the other copy when that was the
    one found): the law advances H in place (``history_rows=src``). Returns (m, the number of
    atoms in touched, the number of contacts whose history read is a second copy marked out of date). A contact for which an atom
    has no free history row is left out (no force; counted in ST_NEED, so the run stops at the next check).
    """
    slots = keys.shape[1]
    npc = cand.shape[0]
    nwc = cand_walls.shape[0]
    full = advance and rebuilt
    if all_atoms:
        for i in range(nlocal):
            _clear_stat(stat, i)
    else:
        for k in range(n_prev):
            _clear_stat(stat, prev[k])
    if full:
        for i in range(nlocal):
            for r in range(slots):
                used[i, r] = False
    nt = 0              # atoms listed in touched
    n = 0
    # (typed int64 from the start: a literal 0 would compile _rows_of_late_contacts a second time, for
    # Literal[int](0) arguments, on the first pass of type inference)
    late = np.int64(0)  # contacts whose rows are not cached (work[:late, :2]: contact, candidate)
    ended = np.int64(0)  # candidates whose contact ended (work[:ended, 2])
    for c in range(npc + nwc):
        dx = dy = dz = r2 = rs = delta = nx = ny = nz = gap = 0.0
        w = -1
        if c < npc:
            i = cand[c, 0]
            j = cand[c, 1]
            dx, dy, dz, r2, rs = _separation(x, radius, i, j)
            touch = r2 < rs * rs
            local_j = j < nlocal
        else:
            i = cand_walls[c - npc, 0]
            w = cand_walls[c - npc, 1]
            j = -1
            gap, nx, ny, nz = W.contact_of(walls, w, cand_walls[c - npc, 2], x[i, 0], x[i, 1], x[i, 2], radius[i])
            delta = radius[i] - gap
            touch = delta > 0.0
            local_j = False
        ri = cand_rows[c, 0]
        rj = cand_rows[c, 1] if local_j else -1
        if not touch:
            if advance and (ri >= 0 or rj >= 0):
                work[ended, 2] = c
                ended += 1
            continue
        if stat[i, ST_PAIRS] + stat[i, ST_WALLS] == 0.0:
            touched[nt] = i
            nt += 1
        stat[i, ST_PAIRS if j >= 0 else ST_WALLS] += 1.0
        if local_j:
            if stat[j, ST_PAIRS] + stat[j, ST_WALLS] == 0.0:
                touched[nt] = j
                nt += 1
            stat[j, ST_PAIRS] += 1.0
        if ri < 0 or (local_j and rj < 0):
            work[late, 0] = n
            work[late, 1] = c
            late += 1
        else:
            # a continuing contact: its rows are cached
            s, d = _copies(i, j, ri, rj, tag, slots, local_j, near)
            src[n] = s
            dst[n] = d
            hrow[n] = s
        if j >= 0:
            # canonical order: the lower id is body 1
            if tag[i] < tag[j]:
                a = i
                b = j
            else:
                a = j
                b = i
                dx = -dx
                dy = -dy
                dz = -dz
            nx, ny, nz, delta, vx, vy, vz = sphere_pair(x, v, omega, radius, a, b, dx, dy, dz, r2, rs)
            pair_rows[n] = prow[n] = sphere_row[typ[a] - 1, typ[b] - 1]
            if sized and (resized(radius, rmass, typ, type_size, a) or resized(radius, rmass, typ, type_size, b)):
                rs, ms = effective(radius, rmass, a, b, rowinfo, pair_rows[n])
                prow[n] = params.shape[0] + n
                contact_row(params, pair_rows[n], pc, prow[n], rowinfo, rs, ms)
            wn[n] = frame_spin_rate(omega, a, b, nx, ny, nz) if frame_spin else 0.0
        else:
            # body 1: the sphere; n from the sphere to the wall; minus the wall's velocity at the contact
            # point c = x + gap n on its surface
            a = i
            b = -(w + 1)
            vx, vy, vz, wn[n] = wall_slip(x, v, omega, radius, walls, i, w, gap, nx, ny, nz, frame_spin)
            pair_rows[n] = prow[n] = wall_row[typ[i] - 1, wall_mat[w]]
            if sized and resized(radius, rmass, typ, type_size, i):
                rs, ms = effective(radius, rmass, i, -1, rowinfo, pair_rows[n])
                prow[n] = params.shape[0] + n
                contact_row(params, pair_rows[n], pc, prow[n], rowinfo, rs, ms)
        body[n, 0] = a
        body[n, 1] = b
        put_contact(normals, overlaps, velocities, n, nx, ny, nz, delta, vx, vy, vz)
        n += 1
    for k in range(nt):
        i = touched[k]
        stat[i, ST_NEED] = max(stat[i, ST_NEED], stat[i, ST_PAIRS] + stat[i, ST_WALLS])
    left_out, stale = _rows_of_late_contacts(
        nlocal, x, radius, tag, walls, cand, cand_walls, cand_rows, keys, sep, sep_tol2, H, advance, full, used, near,
        work, body, src, dst, hrow, late, ended)
    if advance:
        _onset(late, work, body, hrow, H, normals, velocities, radius, rmass, pair_rows, rowinfo, v_max, dt, onset)
    if left_out:
        # drop the contacts left out
        k = 0
        for q in range(n):
            if body[q, 0] >= 0:
                body[k, 0] = body[q, 0]
                body[k, 1] = body[q, 1]
                src[k] = src[q]
                dst[k] = dst[q]
                hrow[k] = hrow[q]
                pair_rows[k] = pair_rows[q]
                overlaps[k] = overlaps[q]
                wn[k] = wn[q]
                prow[k] = prow[q]
                if prow[q] >= params.shape[0]:
                    prow[k] = params.shape[0] + k
                    for d in range(pc.shape[1]):
                        pc[prow[k], d] = pc[prow[q], d]
                for d in range(3):
                    normals[k, d] = normals[q, d]
                    velocities[k, d] = velocities[q, d]
                k += 1
        n = k
    if uses_rate(nid):
        # dashpots see the normal velocity predicted at the end of the step (as the impact integrator)
        for k in range(n):
            a = body[k, 0]
            b = body[k, 1]
            inv_m = 1.0 / rmass[a] + 1.0 / rmass[b] if b >= 0 else 1.0 / rmass[a]
            kick = 0.5 * dt * (H[hrow[k], V_N] if hrow[k] >= 0 else 0.0) * inv_m
            for d in range(3):
                velocities[k, d] -= kick * normals[k, d]
    return n, nt, stale


@njit(cache=True)
def near_boundary(nlocal, x, sublo, subhi, open_lo, open_hi, reach, near):
    """near[i] := local atom i lies within ``reach`` of a face of its subdomain that an atom can cross
    (open_lo, open_hi: bool[3], the faces shared with another subdomain or a periodic boundary). Between
    two rebuilds of the Verlet lists an atom moves less than skin from where it was at the last one (LAMMPS
    exchanges atoms when one moved skin/2 since its own last build), so with reach >= skin the atoms that
    can change rank before the next rebuild are all marked."""
    for i in range(nlocal):
        f = False
        for d in range(3):
            if (open_lo[d] and x[i, d] - sublo[d] < reach) or (open_hi[d] and subhi[d] - x[i, d] < reach):
                f = True
        near[i] = f


@njit(cache=True)
def _onset(late, work, body, hrow, H, normals, velocities, radius, rmass, pair_rows, rowinfo, v_max, dt, onset):
    """Count in onset (ON_...) the contacts that begin at this step (work[k, 0] = -1 - contact, marked by
    ``_rows_of_late_contacts``) at a normal speed above v_max, the largest speed, and the fewest time steps
    per contact time at that speed (the row's contact time scaled by ``size_factor`` and (v_max / v)^alpha)."""
    for k in range(late):
        n = -1 - work[k, 0]
        if n < 0 or body[n, 0] < 0:
            continue
        vn = (velocities[n, 0] * normals[n, 0] + velocities[n, 1] * normals[n, 1]
              + velocities[n, 2] * normals[n, 2])
        if vn > v_max:
            row = pair_rows[n]
            rs, ms = effective(radius, rmass, body[n, 0], body[n, 1], rowinfo, row)
            tc = rowinfo[row, RI_TC] * size_factor(rowinfo, row, rs, ms) * (v_max / vn) ** rowinfo[row, RI_ALPHA]
            onset[ON_FAST] += 1.0
            onset[ON_VMAX] = max(onset[ON_VMAX], vn)
            onset[ON_STEPS] = min(onset[ON_STEPS], tc / dt)


@njit(cache=True)
def _rows_of_late_contacts(nlocal, x, radius, tag, walls, cand, cand_walls, cand_rows, keys, sep, sep_tol2, H, advance, full,
                           used, near, work, body, src, dst, hrow, late, ended):
    """The history rows of the contacts of ``gather_contacts`` whose rows are not cached (work[:late, :2]:
    contact, candidate) and of the candidates whose contact ended (work[:ended, 2]): rows freed, found by
    key, taken, the rows a contact reads and keeps (src, dst, hrow). A function of its own, so that the
    loop over the candidates, at every step, is compiled without this work of the rebuilds and of new
    contacts. Returns (contacts left out for want of a free row, contacts whose history read is a second
    copy marked out of date)."""
    hs = H.shape[1]
    slots = keys.shape[1]
    left_out = 0
    stale = 0
    for k in range(ended):
        # contacts that ended free their rows (reset); a wall contact's row only after the new contacts
        # have looked for theirs (the contact may have moved to another element of its patch: the row is
        # kept in cand_rows[c, 1] till then)
        c = work[k, 2]
        i, j, key_i, local_j = _candidate(cand, cand_walls, walls, c, tag, nlocal, x)
        r = cand_rows[c, 0]
        if j < 0:
            cand_rows[c, 0] = -1
            cand_rows[c, 1] = r
            continue
        if r >= 0 and keys[i, r] == key_i:
            _release(keys, H, i, r)
        r = cand_rows[c, 1]
        if local_j and r >= 0 and keys[j, r] == tag[i]:
            _release(keys, H, j, r)
        cand_rows[c, 0] = -1
        cand_rows[c, 1] = -1
    for k in range(late):
        # rows not cached: found by their keys (first step after a rebuild) or none yet (a new contact)
        c = work[k, 1]
        i, j, key_i, local_j = _candidate(cand, cand_walls, walls, c, tag, nlocal, x)
        dx = dy = dz = 0.0
        if j >= 0:
            dx, dy, dz, _, _ = _separation(x, radius, i, j)
        ri = _find_row(keys, sep, i, key_i, dx, dy, dz, sep_tol2)
        cand_rows[c, 0] = ri
        if full and ri >= 0:
            used[i, ri] = True
        if local_j:
            rj = _find_row(keys, sep, j, float(tag[i]), -dx, -dy, -dz, sep_tol2)
            cand_rows[c, 1] = rj
            if full and rj >= 0:
                used[j, rj] = True
    for k in range(ended):
        # the rows of wall contacts that ended, unless a new contact of the atom took them over
        c = work[k, 2]
        i, j, key_i, _ = _candidate(cand, cand_walls, walls, c, tag, nlocal, x)
        if j >= 0:
            continue
        r = cand_rows[c, 1]
        cand_rows[c, 1] = -1
        # (the row of this wall contact: a wall's key, which may differ from the key at the atom's place
        # now, a mesh's side and patch)
        if r < 0 or keys[i, r] >= 0.0:
            continue
        taken = False
        for q in range(late):
            c2 = work[q, 1]
            if c2 >= cand.shape[0] and cand_walls[c2 - cand.shape[0], 0] == i and cand_rows[c2, 0] == r:
                taken = True
        if not taken:
            _release(keys, H, i, r)
    if full:
        # after a rebuild: the rows no contact uses are freed (contacts that ended, rows that came with
        # an atom from another rank) before new contacts take rows
        for i in range(nlocal):
            for r in range(slots):
                if not used[i, r] and keys[i, r] != 0.0:
                    _release(keys, H, i, r)
    for k in range(late):
        # new contacts take free rows (advance only), or are left out (too few slots: the run stops at
        # the next check); the law reads atom i's row, else atom j's, else none (zeros)
        n_ = work[k, 0]
        c = work[k, 1]
        i, j, key_i, local_j = _candidate(cand, cand_walls, walls, c, tag, nlocal, x)
        ri = cand_rows[c, 0]
        rj = cand_rows[c, 1] if local_j else -1
        # the history read: the current copy (``_copies``), else the other, else none (a new contact)
        h_read = -1
        if ri >= 0 and (rj < 0 or tag[i] < tag[j]):
            h_read = i * slots + ri
        elif rj >= 0:
            h_read = j * slots + rj
        if h_read >= 0 and sep[h_read // slots, 4 * (h_read % slots) + 3] != 0.0:
            stale += 1
        if advance:
            fi = ri if ri >= 0 else _free_row(keys, i)
            fj = (rj if rj >= 0 else _free_row(keys, j)) if local_j else -1
            if fi < 0 or (local_j and fj < 0):
                body[n_, 0] = -1
                left_out += 1
                continue
            keys[i, fi] = key_i
            cand_rows[c, 0] = ri = fi
            sep[i, 4 * fi + 3] = 0.0
            if local_j:
                sep[j, 4 * fj + 3] = 0.0
            if j >= 0:
                # (the separation that tells this contact from one with another image of the partner)
                dx, dy, dz, _, _ = _separation(x, radius, i, j)
                _store_sep(sep, i, fi, dx, dy, dz)
                if local_j:
                    _store_sep(sep, j, fj, -dx, -dy, -dz)
            if local_j:
                keys[j, fj] = tag[i]
                cand_rows[c, 1] = rj = fj
        if ri >= 0 and (not local_j or rj >= 0):
            src[n_], dst[n_] = _copies(i, j, ri, rj, tag, slots, local_j, near)
            if advance and local_j:
                # the second copy (the higher id's) is out of date from now on unless rewritten every step
                hi, rh = (j, rj) if tag[i] < tag[j] else (i, ri)
                sep[hi, 4 * rh + 3] = 1.0 if dst[n_] < 0 else 0.0
        else:
            src[n_] = dst[n_] = -1         # set-up call, a new contact: evaluated, nothing kept
        fresh = h_read < 0
        if advance and h_read != src[n_]:
            # the law advances row src in place: it starts from the copy found, or from zeros
            s = src[n_]
            for q in range(hs):
                H[s, q] = H[h_read, q] if h_read >= 0 else 0.0
            h_read = s
        hrow[n_] = h_read
        if advance and fresh:
            work[k, 0] = -1 - n_          # (a contact that begins: ``_onset``)
    if not advance:
        # a set-up keeps nothing, the rows it found either: they stay uncached, so that the first step
        # after a rebuild finds every continuing contact's rows by key and marks them used
        for k in range(late):
            c = work[k, 1]
            cand_rows[c, 0] = -1
            cand_rows[c, 1] = -1
    return left_out, stale


@njit(cache=True)
def moved(nlocal, x, x_ref):
    """The largest displacement of the local atoms from x_ref[:nlocal] [m]."""
    big = 0.0
    for i in range(nlocal):
        d = (x[i, 0] - x_ref[i, 0]) ** 2 + (x[i, 1] - x_ref[i, 1]) ** 2 + (x[i, 2] - x_ref[i, 2]) ** 2
        big = max(big, d)
    return math.sqrt(big)


@njit(cache=True)
def carry_wall_rows(old, old_rows, new, new_rows):
    """new_rows[c, 0] := old_rows[c', 0] for the wall candidates (i, w, e) found in both lists (each in the
    order of i, w, e): the history rows of contacts that continue across a rebuild of the wall list."""
    p = 0
    for c in range(new.shape[0]):
        while p < old.shape[0] and (old[p, 0], old[p, 1], old[p, 2]) < (new[c, 0], new[c, 1], new[c, 2]):
            p += 1
        if p < old.shape[0] and old[p, 0] == new[c, 0] and old[p, 1] == new[c, 1] and old[p, 2] == new[c, 2]:
            new_rows[c, 0] = old_rows[p, 0]


def contact_buffers(n, params):
    """The buffers of ``gather_contacts`` for n candidates and the parameter table params: (work, body, src, dst,
    hrow, pair_rows, normals, overlaps, velocities, wn, pc (params, then n rows), prow, forces, tforces, spins,
    torques)."""
    pc = np.empty((len(params) + n, params.shape[1]))
    pc[:len(params)] = params
    return (np.empty((n, 3), dtype=np.int64), np.empty((n, 2), dtype=np.int64), np.empty(n, dtype=np.int64),
            np.empty(n, dtype=np.int64), np.empty(n, dtype=np.int64), np.empty(n, dtype=np.int64),
            np.empty((n, 3)), np.empty(n), np.empty((n, 3)), np.empty(n), pc, np.empty(n, dtype=np.int64),
            np.empty((n, 3)), np.empty((n, 3)), np.empty((n, 3)), np.empty((n, 3)))


@njit(cache=True)
def behind_walls(nlocal, x, radius, walls):
    """int64[n_walls]: the local atoms whose centre is behind each wall (signed distance to its surface < 0:
    a wall that faces away from the domain, or atoms placed through it). Only unbounded elements have a
    back (``walls.contract.bounds``: a mesh's triangles are two-sided)."""
    nw = W.count(walls)
    count = np.zeros(max(nw, 1), dtype=np.int64)
    for i in range(nlocal):
        for w in range(nw):
            for e in range(W.elements(walls, w)):
                if math.isfinite(W.bounds(walls, w, 0)[0]):
                    break
                s, _, _, _ = W.contact_of(walls, w, e, x[i, 0], x[i, 1], x[i, 2], radius[i])
                if s < 0.0:
                    count[w] += 1
                    break
    return count[:nw]


@njit(cache=True)
def relative_spins(omega, body, m, spins, walls, wall_spin):
    """spins[k] = w1 - w2 of the m contacts, the input of the twist and rolling laws: body 2 a wall turns
    with its rigid motion's angular velocity if ``wall_spin`` (else it counts as not turning, as LAMMPS's
    ``fix wall/gran``)."""
    for k in range(m):
        a = body[k, 0]
        b = body[k, 1]
        for d in range(3):
            if b >= 0:
                spins[k, d] = omega[a, d] - omega[b, d]
            else:
                spins[k, d] = omega[a, d] - (walls[-b - 1, W.OMEGA + d] if wall_spin else 0.0)


@njit(cache=True)
def read_histories(H, hrow, m):
    """float64[m, history_size]: the rows hrow[:m] of H (zeros for -1), for a law that must not advance
    them (LAMMPS's set-up call)."""
    out = np.zeros((m, H.shape[1]))
    for k in range(m):
        if hrow[k] >= 0:
            for q in range(H.shape[1]):
                out[k, q] = H[hrow[k], q]
    return out


@njit(cache=True)
def scatter_contacts(nlocal, x, v, omega, radius, rmass, typ, m, body, src, dst, normals, overlaps, H, forces, tforces, torques,
                     advance, f, torque, stat, saved, mark, acc, all_atoms, touched, n_touched, save):
    """Write back the m contacts of ``gather_contacts`` after the law (which advanced the histories in
    their rows src): the second copies, rows dst (advance only), and the forces and torques of the local
    atoms. forces, tforces: float64[m, 3] force on body 1 and its tangential part; torques: float64[m, 3]
    torque on body 1 of the twist and rolling laws (body 2 takes the opposite); f, torque:
    float64[>= nlocal, 3] LAMMPS's forces and torques (cleared by LAMMPS every step), the contact forces
    and torques are added to the local rows; stat[:, ST_OVERLAP] receives each local atom's largest
    overlap; saved: float64[nmax, N_SAVED] receives the contact force and torque of every local atom with
    mark + 1 and its state (position, radius, velocity, spin, mass, type) when ``save`` (then all_atoms must be set: the last step of a run,
    whose forces the next run's set-up reapplies; mark: the number of the evaluation, the same on every
    rank); acc: float64[>= nlocal, 7] scratch, zero on entry and left zero (every row summed into is
    cleared after it is written). A local atom whose force or torque is not finite gets none, and
    ST_NEED = inf marks it. Returns float64[N_SUMMARY].

    Per-atom work in proportion to the contacts (see ``gather_contacts``): only the atoms with a contact
    now (touched[:n_touched]) are written, unless all_atoms, or most atoms have contacts: then every local
    atom is, in the order of the atoms."""
    hs = H.shape[1]
    summary = np.zeros(N_SUMMARY)
    dense = all_atoms or 2 * n_touched > nlocal
    for n in range(m):
        a = body[n, 0]
        if advance and dst[n] >= 0:
            s = src[n]
            for q in range(hs):
                H[dst[n], q] = H[s, q]
        b = body[n, 1]
        fx = forces[n, 0]
        fy = forces[n, 1]
        fz = forces[n, 2]
        delta = overlaps[n]
        cx, cy, cz = normal_cross(normals, tforces, n)
        # torque on a sphere: (R - delta/2) n x Ft on both bodies of a pair (r_a = +arm n, force on b =
        # -Ft); R n x Ft against a wall
        arm = radius[a] - 0.5 * delta if b >= 0 else radius[a]
        mx = torques[n, 0]
        my = torques[n, 1]
        mz = torques[n, 2]
        if a < nlocal:
            acc[a, 0] += fx
            acc[a, 1] += fy
            acc[a, 2] += fz
            acc[a, 3] += arm * cx + mx
            acc[a, 4] += arm * cy + my
            acc[a, 5] += arm * cz + mz
            acc[a, 6] = max(acc[a, 6], delta)
        if b >= 0:
            summary[R_PAIRS] += 1.0
            if b < nlocal:
                arm = radius[b] - 0.5 * delta
                acc[b, 0] -= fx
                acc[b, 1] -= fy
                acc[b, 2] -= fz
                acc[b, 3] += arm * cx - mx
                acc[b, 4] += arm * cy - my
                acc[b, 5] += arm * cz - mz
                acc[b, 6] = max(acc[b, 6], delta)
        else:
            summary[R_WALLS] += 1.0
        summary[R_OVERLAP] = max(summary[R_OVERLAP], delta)
    if dense:
        for i in range(nlocal):
            summary[R_BAD] += _write_atom(i, acc, advance, f, torque, stat)
            if save:
                for d in range(6):
                    saved[i, d] = acc[i, d]
                saved[i, SF_MARK] = mark + 1.0
                for d in range(3):
                    saved[i, SF_X + d] = x[i, d]
                    saved[i, SF_V + d] = v[i, d]
                    saved[i, SF_W + d] = omega[i, d]
                saved[i, SF_R] = radius[i]
                saved[i, SF_M] = rmass[i]
                saved[i, SF_T] = typ[i]
            for d in range(7):
                acc[i, d] = 0.0
    else:
        for k in range(n_touched):
            i = touched[k]
            summary[R_BAD] += _write_atom(i, acc, advance, f, torque, stat)
            for d in range(7):
                acc[i, d] = 0.0
    return summary


@njit(inline="always", cache=True)
def _write_atom(i, acc, advance, f, torque, stat):
    """Contact force and torque of local atom i (accumulated in acc[i]) added to LAMMPS's arrays, and its
    largest overlap; none if not finite (acc zeroed, ST_NEED = inf marks it; returns 1.0, else 0.0)."""
    ok = True
    for d in range(6):
        ok = ok and math.isfinite(acc[i, d])
    if not ok:
        for d in range(6):
            acc[i, d] = 0.0
        if advance:
            stat[i, ST_NEED] = math.inf
    for d in range(3):
        f[i, d] += acc[i, d]
        torque[i, d] += acc[i, 3 + d]
    stat[i, ST_OVERLAP] = acc[i, 6]
    return 0.0 if ok else 1.0


@njit(cache=True)
def saved_match(nlocal, x, v, omega, radius, rmass, typ, saved, mark, periods, periodic, tol):
    """Whether every local atom has a contact force saved with ``mark`` (``scatter_contacts``) in its
    present state: the same velocity, spin, radius, mass and type, and the same position up to a period
    of the box (LAMMPS wraps atoms into the box at a run's set-up) and ``tol`` (the rounding of a wrap).
    periods: float64[3, 3] the box's edge vectors a, b, c (rows; LAMMPS's a = (lx, 0, 0), b = (xy, ly, 0),
    c = (xz, yz, lz)); periodic: bool[3]. The forces of that step are then those of the atoms now, on
    this rank."""
    for i in range(nlocal):
        if saved[i, SF_MARK] != mark + 1.0 or saved[i, SF_R] != radius[i] or saved[i, SF_M] != rmass[i] \
                or saved[i, SF_T] != typ[i]:
            return False
        for d in range(3):
            if saved[i, SF_V + d] != v[i, d] or saved[i, SF_W + d] != omega[i, d]:
                return False
        dx = x[i, 0] - saved[i, SF_X]
        dy = x[i, 1] - saved[i, SF_X + 1]
        dz = x[i, 2] - saved[i, SF_X + 2]
        for e in range(2, -1, -1):          # c, then b, then a (triangular edge vectors)
            if periodic[e]:
                k = math.floor((dz if e == 2 else (dy if e == 1 else dx)) / periods[e, e] + 0.5)
                dx -= k * periods[e, 0]
                dy -= k * periods[e, 1]
                dz -= k * periods[e, 2]
        if abs(dx) > tol or abs(dy) > tol or abs(dz) > tol:
            return False
    return True


@njit(cache=True)
def reapply_saved(nlocal, f, torque, saved):
    """Add the saved contact forces and torques of the local atoms to LAMMPS's (at the set-up call of a
    run, when ``saved_match`` holds on every rank)."""
    for i in range(nlocal):
        for d in range(3):
            f[i, d] += saved[i, d]
            torque[i, d] += saved[i, 3 + d]


@njit(cache=True)
def census(nlocal, nall, x, radius, tag, walls, rmax, stat):
    """Contacts of the local atoms without evaluating them (for any pair style): writes ST_PAIRS,
    ST_WALLS, ST_OVERLAP of stat[:nlocal] (ST_NEED: their sum)."""
    pairs, deltas, hits, wdel = find_contacts(nlocal, nall, x, radius, tag, walls, rmax)
    stat[:nlocal, :] = 0.0
    for c in range(pairs.shape[0]):
        for k in (pairs[c, 0], pairs[c, 1]):
            if k < nlocal:
                stat[k, ST_PAIRS] += 1.0
                stat[k, ST_NEED] += 1.0
                stat[k, ST_OVERLAP] = max(stat[k, ST_OVERLAP], deltas[c])
    for c in range(hits.shape[0]):
        k = hits[c, 0]
        stat[k, ST_WALLS] += 1.0
        stat[k, ST_NEED] += 1.0
        stat[k, ST_OVERLAP] = max(stat[k, ST_OVERLAP], wdel[c])
