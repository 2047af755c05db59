"""Per-step contact work of the LAMMPS bridge, on one MPI rank: contact search over local and ghost
atoms, history lookup by partner atom id, the contact laws, forces and torques. No LAMMPS import here:
the kernels take numpy views of LAMMPS's per-atom arrays.

History storage. Every atom carries ``slots`` history rows in one per-atom array (LAMMPS
``fix property/atom d2_...``, which migrates with the atom between ranks and survives neighbour-list
rebuilds and atom sorting): the keys of its rows, ``keys`` (nmax, slots), in one array, and the rows in
another, viewed as ``H`` (nmax * slots, history_size): row i * slots + s is row s of atom i, the
contact index handed to the contact kernel. A key is the partner's atom id (> 0), -(w + 1) for wall w,
or 0 for a free row.

Newton's third law between ranks, without reverse communication: each rank computes the contacts of its
own (local) atoms, including those with ghost atoms, and writes forces and torques on local atoms only.
A contact between atoms on two ranks is therefore evaluated twice, once by each owner, each with its own
copy of the history. Both evaluations are made in one canonical order, the atom with the lower id as
body 1, from the same inputs (ghost positions, velocities and spins are exact copies of the owner's),
so the two copies of the history stay bitwise equal and the two forces are exact opposites. A contact
between two local atoms is evaluated once and its history row is copied into both atoms' rows, so that
either atom can later move to another rank with it. (Across a periodic boundary the ghost position is
x + L, rounded: there the two sides agree to rounding error only.)

Kinematics follow LAMMPS's granular models (``pair granular``, ``fix wall/gran``): the slip velocity
uses the full radii, v = v1 - v2 + (R1 w1 + R2 w2) x n; the torque arm is R - delta/2 for a sphere pair
and R for a wall.
"""
import math

import numpy as np
from numba import njit

from ..dem.contact3d import contact_force
from ..laws.contact import HERTZ_DAMPED, LINEAR_NORMAL
from ..laws.vector import V_N

# columns of the per-atom statistics array (d2 property, written for local atoms every step)
ST_PAIRS = 0     # sphere-sphere contacts of the atom
ST_WALLS = 1     # wall contacts of the atom
ST_NEED = 2      # history rows the atom needed (its contacts), largest since the column was zeroed
ST_OVERLAP = 3   # largest overlap of its contacts [m]
N_STAT = 4

# columns of the per-atom stored contact force (d2 property): reapplied at LAMMPS's run set-up
SF_STEP = 6      # 1 + the time step at which the stored force and torque were computed (0: none)
N_SAVED = 7

# per-rank summary returned by step_contacts
R_PAIRS = 0      # sphere-sphere contacts evaluated on this rank
R_WALLS = 1      # wall contacts evaluated on this rank
R_OVERLAP = 2    # largest overlap [m]
R_NEED = 3       # largest number of history rows an atom needed
N_SUMMARY = 4


def atom_columns(slots: int) -> int:
    """Columns of the per-atom array before the statistics: the keys."""
    return slots


@njit(cache=True)
def law(nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt):
    """The one call of the contact kernel: force on body 1 and its tangential part for the contact whose
    history is row c of H (``dem.contact3d.contact_force``, conventions there)."""
    return contact_force(nid, tid, params, row, H, c, nx, ny, nz, delta, vx, vy, vz, wn, dt)


@njit(cache=True)
def _cells(x, n, cell):
    """Counting-sort cell list of the first n points: (lo, dims, cell size, start, order, cell of each)."""
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
        if total > 4.0 * n + 1000.0:           # sparse points: coarser cells keep memory O(n)
            cell *= (total / (4.0 * n + 1000.0)) ** (1.0 / 3.0)
        for d in range(3):
            dims[d] = int((hi[d] - lo[d]) / cell) + 1
    ncell = dims[0] * dims[1] * dims[2]
    which = np.empty(n, dtype=np.int64)
    start = np.zeros(ncell + 1, dtype=np.int64)
    for i in range(n):
        cx = min(int((x[i, 0] - lo[0]) / cell), dims[0] - 1)
        cy = min(int((x[i, 1] - lo[1]) / cell), dims[1] - 1)
        cz = min(int((x[i, 2] - lo[2]) / cell), dims[2] - 1)
        k = (cx * dims[1] + cy) * dims[2] + cz
        which[i] = k
        start[k + 1] += 1
    for k in range(ncell):
        start[k + 1] += start[k]
    fill = start[:-1].copy()
    order = np.empty(n, dtype=np.int64)
    for i in range(n):
        order[fill[which[i]]] = i
        fill[which[i]] += 1
    return lo, dims, cell, start, order, which


@njit(cache=True)
def candidates(nlocal, nall, x, radius, tag, walls, rmax, skin):
    """Verlet lists of the local atoms: sphere pairs (i local; j local with j > i, or ghost) closer than
    r_i + r_j + skin, and wall pairs (i, w) closer than r_i + skin. walls: float64[n_walls, 6], a point
    and the unit normal pointing into the domain. Valid while no atom has moved more than skin / 2 and
    the local and ghost atoms keep their indices. Returns (pairs int64[m, 2], wall_pairs int64[k, 2])."""
    lo, dims, cell, start, order, which = _cells(x, nall, 2.0 * rmax + skin)
    d0 = dims[0]
    d1 = dims[1]
    d2 = dims[2]
    cap = 8 * nlocal + 16
    pairs = np.empty((cap, 2), dtype=np.int64)
    m = 0
    for i in range(nlocal):
        k = which[i]
        cz = k % d2
        cy = (k // d2) % d1
        cx = k // (d1 * d2)
        xi = x[i, 0]
        yi = x[i, 1]
        zi = x[i, 2]
        ri = radius[i] + skin
        for ax in range(max(cx - 1, 0), min(cx + 2, d0)):
            for ay in range(max(cy - 1, 0), min(cy + 2, d1)):
                # the three cells along z are consecutive in the cell order
                k0 = (ax * d1 + ay) * d2
                for q in range(start[k0 + max(cz - 1, 0)], start[k0 + min(cz + 2, d2)]):
                    j = order[q]
                    if j == i or (j < nlocal and j < i) or tag[j] == tag[i]:
                        continue
                    dx = x[j, 0] - xi
                    dy = x[j, 1] - yi
                    dz = x[j, 2] - zi
                    rs = ri + radius[j]
                    if dx * dx + dy * dy + dz * dz < rs * rs:
                        if m == pairs.shape[0]:
                            pairs = _grow2(pairs)
                        pairs[m, 0] = i
                        pairs[m, 1] = j
                        m += 1
    nw = walls.shape[0]
    hits = np.empty((max(nlocal * nw, 1), 2), dtype=np.int64)
    kw = 0
    for i in range(nlocal):
        for w in range(nw):
            gap = ((x[i, 0] - walls[w, 0]) * walls[w, 3] + (x[i, 1] - walls[w, 1]) * walls[w, 4]
                   + (x[i, 2] - walls[w, 2]) * walls[w, 5])
            if gap < radius[i] + skin:
                hits[kw, 0] = i
                hits[kw, 1] = w
                kw += 1
    return pairs[:m], hits[:kw]


@njit(cache=True)
def overlapping(x, radius, walls, cand, cand_walls):
    """The candidates in contact now: (pairs, deltas, wall_hits, wall_deltas), deltas > 0 the overlaps."""
    m = 0
    keep = np.empty(cand.shape[0], dtype=np.int64)
    deltas = np.empty(cand.shape[0])
    for c in range(cand.shape[0]):
        i = cand[c, 0]
        j = cand[c, 1]
        dx = x[j, 0] - x[i, 0]
        dy = x[j, 1] - x[i, 1]
        dz = x[j, 2] - x[i, 2]
        rs = radius[i] + radius[j]
        r2 = dx * dx + dy * dy + dz * dz
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
        gap = ((x[i, 0] - walls[w, 0]) * walls[w, 3] + (x[i, 1] - walls[w, 1]) * walls[w, 4]
               + (x[i, 2] - walls[w, 2]) * walls[w, 5])
        d = radius[i] - gap
        if d > 0.0:
            wkeep[kw] = c
            wdel[kw] = d
            kw += 1
    hits = np.empty((kw, 2), dtype=np.int64)
    for k in range(kw):
        hits[k, 0] = cand_walls[wkeep[k], 0]
        hits[k, 1] = cand_walls[wkeep[k], 1]
    return pairs, deltas[:m], hits, wdel[:kw]


@njit(cache=True)
def find_contacts(nlocal, nall, x, radius, tag, walls, rmax):
    """The contacts of the local atoms now (candidates with no skin, then their overlaps)."""
    cand, cand_walls = candidates(nlocal, nall, x, radius, tag, walls, rmax, 0.0)
    return overlapping(x, radius, walls, cand, cand_walls)


@njit(cache=True)
def moved(nlocal, nall, x, tag, x_ref, tag_ref, half_skin):
    """True when the Verlet lists built at x_ref, tag_ref must be rebuilt: other atoms or indices (LAMMPS
    exchanged, sorted or rebuilt its ghosts), or an atom moved more than skin / 2."""
    if x_ref.shape[0] != nall or tag_ref.shape[0] != nall:
        return True
    lim = half_skin * half_skin
    for i in range(nall):
        if tag[i] != tag_ref[i]:
            return True
        dx = x[i, 0] - x_ref[i, 0]
        dy = x[i, 1] - x_ref[i, 1]
        dz = x[i, 2] - x_ref[i, 2]
        if dx * dx + dy * dy + dz * dz > lim:
            return True
    return False


@njit(cache=True)
def _grow2(a):
    b = np.empty((2 * a.shape[0], a.shape[1]), dtype=a.dtype)
    b[:a.shape[0]] = a
    return b


@njit(cache=True)
def _grow1(a):
    b = np.empty(2 * a.shape[0], dtype=a.dtype)
    b[:a.shape[0]] = a
    return b


@njit(cache=True)
def _find_row(keys, i, key):
    for s in range(keys.shape[1]):
        if keys[i, s] == key:
            return s
    return -1


@njit(cache=True)
def _free_row(keys, i):
    for s in range(keys.shape[1]):
        if keys[i, s] == 0.0:
            return s
    return -1


@njit(inline="always", cache=True)
def _load_scratch(scratch, H, r, has_row):
    """Row 0 of ``scratch`` := history row r of H if the contact has one (has_row), else zeros."""
    if has_row:
        scratch[0, :] = H[r, :]
    else:
        scratch[0, :] = 0.0


@njit(cache=True)
def step_contacts(nlocal, x, v, omega, radius, rmass, tag, typ, walls, wall_mat, cand, cand_walls, keys, H,
                  nid, tid, params, sphere_row, wall_row, dt, advance, frame_spin, fext, torque, stat,
                  saved, step):
    """One step of contact forces for the local atoms of one rank.

    x, v, omega: float64[nall, 3]; radius, rmass: float64[nall]; tag: int[nall] atom ids; typ: int[nall]
    atom types (1-based, as LAMMPS); walls: float64[n_walls, 6]; wall_mat: int64[n_walls] column of
    wall_row; cand, cand_walls: the Verlet lists (``candidates``); keys: float64[nmax, slots], H:
    float64[nmax * slots, history_size] histories; params, sphere_row, wall_row: the pair
    table; dt [s]; advance: False evaluates on copies of the histories
    (LAMMPS's set-up call: nothing is advanced); frame_spin: pass the spin of the contact frame about
    the normal to the kernel (False: wn = 0, LAMMPS's granular models). fext: float64[nlocal, 3] receives the contact forces;
    torque: float64[nall, 3], contact torques are added to the local rows; stat: float64[nmax, N_STAT]
    per-atom statistics (local rows written); saved: float64[nmax, N_SAVED] receives the force and
    torque of each local atom with step + 1. Returns float64[N_SUMMARY].
    """
    hs = H.shape[1]
    summary = np.zeros(N_SUMMARY)
    pairs, deltas, hits, wdel = overlapping(x, radius, walls, cand, cand_walls)
    npair = pairs.shape[0]
    nhit = hits.shape[0]
    count = np.zeros(nlocal)
    for i in range(nlocal):
        for d in range(N_STAT):
            if d != ST_NEED:
                stat[i, d] = 0.0
        for d in range(3):
            fext[i, d] = 0.0
        for d in range(N_SAVED):
            saved[i, d] = 0.0
    # rows of the contacts that continue; mark them used
    slots = keys.shape[1]
    used = np.zeros((nlocal, slots), dtype=np.bool_)
    rowi = np.full(npair, -1, dtype=np.int64)
    rowj = np.full(npair, -1, dtype=np.int64)
    roww = np.full(nhit, -1, dtype=np.int64)
    for c in range(npair):
        i = pairs[c, 0]
        j = pairs[c, 1]
        stat[i, ST_PAIRS] += 1.0
        count[i] += 1.0
        rowi[c] = _find_row(keys, i, float(tag[j]))
        if rowi[c] >= 0:
            used[i, rowi[c]] = True
        if j < nlocal:
            stat[j, ST_PAIRS] += 1.0
            count[j] += 1.0
            rowj[c] = _find_row(keys, j, float(tag[i]))
            if rowj[c] >= 0:
                used[j, rowj[c]] = True
    for c in range(nhit):
        i = hits[c, 0]
        stat[i, ST_WALLS] += 1.0
        count[i] += 1.0
        roww[c] = _find_row(keys, i, -(hits[c, 1] + 1.0))
        if roww[c] >= 0:
            used[i, roww[c]] = True
    need = 0.0
    for i in range(nlocal):
        if count[i] > need:
            need = count[i]
        if count[i] > stat[i, ST_NEED]:
            stat[i, ST_NEED] = count[i]
    summary[R_NEED] = need
    if advance:
        # contacts that ended free their rows (reset) before new contacts take rows
        for i in range(nlocal):
            for s in range(slots):
                if not used[i, s] and keys[i, s] != 0.0:
                    keys[i, s] = 0.0
                    H[i * slots + s, :] = 0.0
    scratch = np.zeros((1, hs))
    for c in range(npair):
        i = pairs[c, 0]
        j = pairs[c, 1]
        local_j = j < nlocal
        ri = rowi[c]
        rj = rowj[c]
        if advance:
            if ri < 0:
                ri = _free_row(keys, i)
                if ri < 0:
                    continue                       # out of rows: reported through ST_NEED
            if local_j and rj < 0:
                rj = _free_row(keys, j)
                if rj < 0:
                    continue
        else:
            _load_scratch(scratch, H, i * slots + ri, ri >= 0)
        # canonical order: the lower id is body 1
        if tag[i] < tag[j]:
            a = i
            b = j
        else:
            a = j
            b = i
        dx = x[b, 0] - x[a, 0]
        dy = x[b, 1] - x[a, 1]
        dz = x[b, 2] - x[a, 2]
        r = math.sqrt(dx * dx + dy * dy + dz * dz)
        nx = dx / r
        ny = dy / r
        nz = dz / r
        delta = deltas[c]
        ra = radius[a]
        rb = radius[b]
        wx = ra * omega[a, 0] + rb * omega[b, 0]
        wy = ra * omega[a, 1] + rb * omega[b, 1]
        wz = ra * omega[a, 2] + rb * omega[b, 2]
        vx = v[a, 0] - v[b, 0] + (wy * nz - wz * ny)
        vy = v[a, 1] - v[b, 1] + (wz * nx - wx * nz)
        vz = v[a, 2] - v[b, 2] + (wx * ny - wy * nx)
        row = sphere_row[typ[a] - 1, typ[b] - 1]
        if nid == HERTZ_DAMPED or nid == LINEAR_NORMAL:
            # dashpots see the normal velocity predicted at the end of the step (as the impact integrator)
            n_old = H[i * slots + ri, V_N] if advance else scratch[0, V_N]
            kick = 0.5 * dt * n_old * (1.0 / rmass[a] + 1.0 / rmass[b])
            vx -= kick * nx
            vy -= kick * ny
            vz -= kick * nz
        wn = 0.0
        if frame_spin:
            wn = 0.5 * ((omega[a, 0] + omega[b, 0]) * nx + (omega[a, 1] + omega[b, 1]) * ny
                        + (omega[a, 2] + omega[b, 2]) * nz)
        if advance:
            fx, fy, fz, tx, ty, tz = law(nid, tid, params, row, H, i * slots + ri, nx, ny, nz, delta,
                                         vx, vy, vz, wn, dt)
            keys[i, ri] = tag[j]
            if local_j:
                H[j * slots + rj, :] = H[i * slots + ri, :]
                keys[j, rj] = tag[i]
        else:
            fx, fy, fz, tx, ty, tz = law(nid, tid, params, row, scratch, 0, nx, ny, nz, delta,
                                         vx, vy, vz, wn, dt)
        # torque on body k: (R_k - delta/2) n x Ft on both bodies (r_a = +arm n, force on b = -Ft)
        cx = ny * tz - nz * ty
        cy = nz * tx - nx * tz
        cz = nx * ty - ny * tx
        for k in (a, b):
            if k >= nlocal:
                continue
            sgn = 1.0 if k == a else -1.0
            arm = radius[k] - 0.5 * delta
            fext[k, 0] += sgn * fx
            fext[k, 1] += sgn * fy
            fext[k, 2] += sgn * fz
            saved[k, 3] += arm * cx
            saved[k, 4] += arm * cy
            saved[k, 5] += arm * cz
            if delta > stat[k, ST_OVERLAP]:
                stat[k, ST_OVERLAP] = delta
        summary[R_PAIRS] += 1.0
        if delta > summary[R_OVERLAP]:
            summary[R_OVERLAP] = delta
    for c in range(nhit):
        i = hits[c, 0]
        w = hits[c, 1]
        ri = roww[c]
        if advance:
            if ri < 0:
                ri = _free_row(keys, i)
                if ri < 0:
                    continue
        else:
            _load_scratch(scratch, H, i * slots + ri, ri >= 0)
        # body 1: the sphere; n from the sphere to the wall; the wall is at rest
        nx = -walls[w, 3]
        ny = -walls[w, 4]
        nz = -walls[w, 5]
        delta = wdel[c]
        ri_ = radius[i]
        wx = ri_ * omega[i, 0]
        wy = ri_ * omega[i, 1]
        wz = ri_ * omega[i, 2]
        vx = v[i, 0] + (wy * nz - wz * ny)
        vy = v[i, 1] + (wz * nx - wx * nz)
        vz = v[i, 2] + (wx * ny - wy * nx)
        row = wall_row[typ[i] - 1, wall_mat[w]]
        if nid == HERTZ_DAMPED or nid == LINEAR_NORMAL:
            n_old = H[i * slots + ri, V_N] if advance else scratch[0, V_N]
            kick = 0.5 * dt * n_old / rmass[i]
            vx -= kick * nx
            vy -= kick * ny
            vz -= kick * nz
        wn = 0.0
        if frame_spin:
            wn = 0.5 * (omega[i, 0] * nx + omega[i, 1] * ny + omega[i, 2] * nz)
        if advance:
            fx, fy, fz, tx, ty, tz = law(nid, tid, params, row, H, i * slots + ri, nx, ny, nz, delta,
                                         vx, vy, vz, wn, dt)
            keys[i, ri] = -(w + 1.0)
        else:
            fx, fy, fz, tx, ty, tz = law(nid, tid, params, row, scratch, 0, nx, ny, nz, delta,
                                         vx, vy, vz, wn, dt)
        fext[i, 0] += fx
        fext[i, 1] += fy
        fext[i, 2] += fz
        saved[i, 3] += ri_ * (ny * tz - nz * ty)
        saved[i, 4] += ri_ * (nz * tx - nx * tz)
        saved[i, 5] += ri_ * (nx * ty - ny * tx)
        if delta > stat[i, ST_OVERLAP]:
            stat[i, ST_OVERLAP] = delta
        summary[R_WALLS] += 1.0
        if delta > summary[R_OVERLAP]:
            summary[R_OVERLAP] = delta
    for i in range(nlocal):
        for d in range(3):
            saved[i, d] = fext[i, d]
            torque[i, d] += saved[i, 3 + d]
        saved[i, SF_STEP] = step + 1.0
    return summary


@njit(cache=True)
def reapply_saved(nlocal, fext, torque, saved, step):
    """Reapply the contact forces and torques saved at ``step`` (LAMMPS's set-up call at the start of a
    run, at the step where the previous run ended: the positions are those the forces were computed
    at). Returns False, adding nothing, if a local atom has no force saved at this step."""
    for i in range(nlocal):
        if saved[i, SF_STEP] != step + 1.0:
            return False
    for i in range(nlocal):
        for d in range(3):
            fext[i, d] = saved[i, d]
            torque[i, d] += saved[i, 3 + d]
    return True


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
