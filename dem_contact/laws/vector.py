"""3D forms of the contact laws on flat arrays, for the DEM kernels of ``dem.contact3d``.

Every kernel here reads the parameter table by 2D indexing, ``params[row, P_...]``, and the state of a
contact in the history table, ``H[c, j]``: no row views, no allocation, scalar arguments. The arithmetic of
the normal laws is that of ``normal`` (so that a 3D contact that stays in a plane repeats the planar laws);
the tangential laws act on vectors in the tangent plane.

Layout of a 3D history row (float64):

=========================  =============================================================================
slot                       meaning
=========================  =============================================================================
V_N, V_A                   normal force [N] and contact radius [m] after the last step
V_DSTAR .. V_DP            the four slots of the Thornton law (only when the normal law is ``thornton``)
b + W_WORK                 running work absorbed by the tangential force, sum of 0.5 (T_old + T) . dd [J]
b + W_X, W_Y, W_Z          the law's vector (global axes): the spring displacement xi [m] (total laws),
                           the force T [N] (incremental laws), the force axis u (md), the first axis e1
                           of the cells' frame (mdr)
b + M_T .. M_SIGN          md: T along u, T*, T**, regime, loading sign (the planar slots)
b + R_T1, R_T2             mdr: T in the cells' frame (e1, e2 = n x e1) [N]
b + R_DX                   mdr_adaptive: cell width [m]
b + R_CELLS + 2 i (+1)     mdr: the displacement of cell i in the frame (e1, e2) [m]
=========================  =============================================================================

with b = ``tangential_base(nid)`` (2, or 6 for ``thornton``). T is the tangential force in the direction of
the displacement (the force on body 1 is -T). Each step every stored vector is first carried into the
current tangent plane and turned about the normal with the contact (``carry``), then the slip increment
dd (a vector in the tangent plane) acts on it.
"""
import math

import numpy as np
from numba import njit

from .contact import (DDM, HERTZ, HERTZ_DAMPED, LINEAR_NORMAL, LINEAR_TANGENTIAL, MD, MD_RESCALE, MDR,
                      MDR_ADAPTIVE, MINDLIN_INCREMENTAL, MINDLIN_RESCALE, MINDLIN_TOTAL, THORNTON)
from .slots import (P_DELTA_Y, P_DX, P_ESTAR, P_F_Y, P_GAMMA, P_GSTAR, P_KN, P_KT, P_MSTAR, P_MU,
                    P_NSPRING, P_PY, P_RSTAR)

#: numba options of every flat kernel: numpy's error model (no zero-division checks) and the
#: floating-point contractions that keep results within rounding of the strict build (see README)
FASTMATH = {"contract", "afn"}
JIT = dict(cache=True, error_model="numpy", fastmath=FASTMATH)

# header of a 3D history row (the same slots as the planar row)
V_N = 0
V_A = 1
V_DSTAR = 2
V_FSTAR = 3
V_RP = 4
V_DP = 5
# tangential slots, relative to b = tangential_base(nid)
W_WORK = 0
W_X = 1
W_Y = 2
W_Z = 3
M_T = 4
M_TS = 5
M_TSS = 6
M_REGIME = 7
M_SIGN = 8
N_MD = 9
R_T1 = 4
R_T2 = 5
R_DX = 6
R_CELLS = 7
N_SPRING_VECTOR = 4

NORMAL_IDS = (HERTZ, THORNTON, HERTZ_DAMPED, LINEAR_NORMAL)
TANGENTIAL_IDS = (MD, MD_RESCALE, MINDLIN_TOTAL, MINDLIN_INCREMENTAL, MINDLIN_RESCALE, LINEAR_TANGENTIAL,
                  DDM, MDR, MDR_ADAPTIVE)


@njit(inline="always", **JIT)
def tangential_base(nid):
    """First tangential slot of a 3D history row: after the Thornton slots for ``thornton``."""
    return 6 if nid == THORNTON else 2


def history_size(nid: int, tid: int, n_cells: int = 0) -> int:
    """Length of a 3D history row for the normal law ``nid`` and the tangential law ``tid``; ``n_cells``:
    the MDR cell count (params[P_NSPRING]) for mdr and mdr_adaptive."""
    if nid not in NORMAL_IDS:
        raise ValueError(f"unknown normal law id {nid}")
    if tid not in TANGENTIAL_IDS:
        raise ValueError(f"unknown tangential law id {tid}")
    b = 6 if nid == THORNTON else 2
    if tid in (MD, MD_RESCALE):
        return b + N_MD
    if tid in (MDR, MDR_ADAPTIVE):
        return b + R_CELLS + 2 * int(n_cells)
    return b + N_SPRING_VECTOR


# ---------------------------------------------------------------------------------------------- normal laws

@njit(inline="always", **JIT)
def hertz(params, row, delta):
    """Hertz (Johnson 1985, eq. 4.23): a = sqrt(R* delta), N = (4/3) E* a delta. Returns (N, a)."""
    if delta <= 0.0:
        return 0.0, 0.0
    a = math.sqrt(params[row, P_RSTAR] * delta)
    return 4.0 / 3.0 * params[row, P_ESTAR] * a * delta, a


@njit(**JIT)
def thornton(params, row, H, c, delta):
    """Thornton (1997, J. Appl. Mech. 64:383) elastic-perfectly plastic law, as ``normal.thornton``."""
    if delta <= 0.0:
        return 0.0, 0.0
    E = params[row, P_ESTAR]
    R = params[row, P_RSTAR]
    if delta >= H[c, V_DSTAR]:
        a = math.sqrt(R * delta)
        if delta <= params[row, P_DELTA_Y]:
            F = 4.0 / 3.0 * E * a * delta
        else:
            F = params[row, P_F_Y] + math.pi * params[row, P_PY] * R * (delta - params[row, P_DELTA_Y])
        H[c, V_DSTAR] = delta
        H[c, V_FSTAR] = F
        if F > params[row, P_F_Y]:
            Rp = 4.0 * E * a * a * a / (3.0 * F)
            H[c, V_RP] = Rp
            H[c, V_DP] = delta - (3.0 * F / (4.0 * E * math.sqrt(Rp))) ** (2.0 / 3.0)
        return F, a
    Rp = H[c, V_RP]
    if Rp <= 0.0:
        Rp = R
    w = delta - H[c, V_DP]
    if w <= 0.0:
        return 0.0, 0.0
    a = math.sqrt(Rp * w)
    return 4.0 / 3.0 * E * a * w, a


@njit(**JIT)
def hertz_damped(params, row, delta, vel):
    """Hertz plus dashpot 2 gamma sqrt(m* k_n) d(delta)/dt, k_n = 2 E* a, clamped at N >= 0
    (as ``normal.hertz_damped``; Tsuji et al. 1992 form)."""
    F, a = hertz(params, row, delta)
    kn = 2.0 * params[row, P_ESTAR] * a
    F = F + 2.0 * params[row, P_GAMMA] * math.sqrt(params[row, P_MSTAR] * kn) * vel
    if F < 0.0:
        F = 0.0
    return F, a


@njit(**JIT)
def linear_normal(params, row, delta, vel):
    """Linear spring-dashpot (Cundall & Strack 1979), as ``normal.linear``."""
    if delta <= 0.0:
        return 0.0, 0.0
    kn = params[row, P_KN]
    return (kn * delta + 2.0 * params[row, P_GAMMA] * math.sqrt(params[row, P_MSTAR] * kn) * vel,
            math.sqrt(params[row, P_RSTAR] * delta))


# ------------------------------------------------------------------------------------------ vector helpers

@njit(inline="always", **JIT)
def turn(x, y, z, nx, ny, nz, cs, sn):
    """Vector (x, y, z) in the plane normal to n turned by the angle (cos, sin) = (cs, sn) about n
    (Rodrigues' formula for a vector perpendicular to the axis)."""
    return (x * cs + (ny * z - nz * y) * sn,
            y * cs + (nz * x - nx * z) * sn,
            z * cs + (nx * y - ny * x) * sn)


@njit(inline="always", **JIT)
def carry(x, y, z, nx, ny, nz, cs, sn):
    """A history vector carried into the tangent plane of n keeping its magnitude (projection and
    rescaling, as LAMMPS granular's tangential models do), then turned with the contact about n."""
    un = x * nx + y * ny + z * nz
    if un != 0.0:
        m2 = x * x + y * y + z * z
        x -= un * nx
        y -= un * ny
        z -= un * nz
        p2 = x * x + y * y + z * z
        s = math.sqrt(m2 / p2) if p2 > 0.0 else 0.0
        x *= s
        y *= s
        z *= s
    if sn != 0.0:
        x, y, z = turn(x, y, z, nx, ny, nz, cs, sn)
    return x, y, z


@njit(inline="always", **JIT)
def carry_unit(x, y, z, nx, ny, nz, cs, sn):
    """A unit axis carried into the tangent plane of n and turned with the contact about n; returns
    (0, 0, 0) when the axis is unset or parallel to n."""
    un = x * nx + y * ny + z * nz
    x -= un * nx
    y -= un * ny
    z -= un * nz
    p2 = x * x + y * y + z * z
    if p2 <= 0.0:
        return 0.0, 0.0, 0.0
    s = 1.0 / math.sqrt(p2)
    x *= s
    y *= s
    z *= s
    if sn != 0.0:
        x, y, z = turn(x, y, z, nx, ny, nz, cs, sn)
    return x, y, z


@njit(inline="always", **JIT)
def cap_vector(x, y, z, muN):
    """Coulomb: scale the vector back to |T| = mu N if it is longer (direction kept)."""
    m2 = x * x + y * y + z * z
    if m2 > muN * muN:
        s = muN / math.sqrt(m2)
        return x * s, y * s, z * s, True
    return x, y, z, False


@njit(inline="always", **JIT)
def release_vector(H, c, b):
    H[c, b + W_X] = 0.0
    H[c, b + W_Y] = 0.0
    H[c, b + W_Z] = 0.0


# ------------------------------------------------------------------------------------ vector spring laws

@njit(**JIT)
def spring_total(params, row, H, c, b, N, a, a_old, nx, ny, nz, ddx, ddy, ddz, cs, sn, factor):
    """Total-displacement Hertz-Mindlin as a vector spring (LAMMPS ``tangential mindlin``; factor 2/3:
    Di Renzo & Di Maio 2005): xi carried into the plane, xi += dd, T = factor 8 G* a xi, and if
    |T| > mu N, T scaled to mu N with xi = T / (factor 8 G* a). Returns T."""
    if N <= 0.0 or a <= 0.0:
        release_vector(H, c, b)
        return 0.0, 0.0, 0.0
    g8 = factor * 8.0 * params[row, P_GSTAR]
    x, y, z = carry(H[c, b + W_X], H[c, b + W_Y], H[c, b + W_Z], nx, ny, nz, cs, sn)
    k_old = g8 * a_old
    w_old = k_old * (x * ddx + y * ddy + z * ddz)
    kt = g8 * a
    x += ddx
    y += ddy
    z += ddz
    tx, ty, tz, slip = cap_vector(kt * x, kt * y, kt * z, params[row, P_MU] * N)
    if slip:
        x = tx / kt
        y = ty / kt
        z = tz / kt
    H[c, b + W_X] = x
    H[c, b + W_Y] = y
    H[c, b + W_Z] = z
    H[c, b + W_WORK] += 0.5 * (w_old + tx * ddx + ty * ddy + tz * ddz)
    return tx, ty, tz


@njit(**JIT)
def spring_incremental(params, row, H, c, b, N, a, a_old, nx, ny, nz, ddx, ddy, ddz, cs, sn, kt, rescale):
    """Incremental force law as a vector spring (LAMMPS ``mindlin/force``, ``mindlin_rescale/force``;
    Cundall & Strack's linear spring with a constant kt): T carried into the plane, scaled by a / a_old
    when the contact shrinks (rescale), T += kt dd, scaled back to mu N if longer. Returns T."""
    if N <= 0.0 or a <= 0.0:
        release_vector(H, c, b)
        return 0.0, 0.0, 0.0
    x, y, z = carry(H[c, b + W_X], H[c, b + W_Y], H[c, b + W_Z], nx, ny, nz, cs, sn)
    if rescale and a < a_old:
        r = a / a_old
        x *= r
        y *= r
        z *= r
    w_old = x * ddx + y * ddy + z * ddz
    tx, ty, tz, slip = cap_vector(x + kt * ddx, y + kt * ddy, z + kt * ddz, params[row, P_MU] * N)
    H[c, b + W_X] = tx
    H[c, b + W_Y] = ty
    H[c, b + W_Z] = tz
    H[c, b + W_WORK] += 0.5 * (w_old + tx * ddx + ty * ddy + tz * ddz)
    return tx, ty, tz


# --------------------------------------------------------------------------------------- md along an axis

@njit(**JIT)
def md_scalar(params, row, H, c, b, N, dN, a, a_old, dd, rescale):
    """Thornton & Yin (1991) incremental Mindlin-Deresiewicz along one axis: the arithmetic of
    ``tangential.md`` (see there for the regimes and reversal points) on the slots b + M_T .. M_SIGN;
    the cube root is ``cbrt``. Returns T along the axis."""
    mu = params[row, P_MU]
    muN = mu * N
    if muN <= 0.0 or a <= 0.0:
        for j in range(M_T, N_MD):
            H[c, b + j] = 0.0
        return 0.0
    s = H[c, b + M_SIGN]
    if s == 0.0:
        s = 1.0 if dd >= 0.0 else -1.0
    t = s * H[c, b + M_T]
    ts = H[c, b + M_TS]
    tss = H[c, b + M_TSS]
    k = int(H[c, b + M_REGIME])
    if rescale and a < a_old:
        r = a / a_old
        t *= r
        ts *= r
        tss *= r
    d = s * dd
    mdN = mu * dN
    if k == 0:
        if d < 0.0:
            if t <= 0.0:
                s = -s
                t = -t
                d = -d
            else:
                k = 1
                ts = t
    elif k == 1:
        if d > 0.0:
            k = 2
            tss = t
    elif d < 0.0:
        k = 1
        ts = t
    kt = 8.0 * params[row, P_GSTAR] * (2.0 / 3.0 * (a_old * a_old + a_old * a + a * a) / (a_old + a))
    if mdN > 0.0 and abs(kt * d) < mdN:
        t += kt * d
    elif k == 0:
        th = np.cbrt(min(max(1.0 - (t + mdN) / muN, 0.0), 1.0))
        t += kt * th * d + mdN * (1.0 - th)
    elif k == 1:
        th = np.cbrt(min(max(1.0 - (ts - t + 2.0 * mdN) / (2.0 * muN), 0.0), 1.0))
        t += kt * th * d - mdN * (1.0 - th)
    else:
        th = np.cbrt(min(max(1.0 - (t - tss + 2.0 * mdN) / (2.0 * muN), 0.0), 1.0))
        t += kt * th * d + mdN * (1.0 - th)
    ts += mdN
    tss -= mdN
    if k == 1 and t < -ts:
        s = -s
        t = -t
        k = 0
    elif k == 2 and t >= ts:
        k = 0
    if abs(t) >= muN:
        if t < 0.0:
            s = -s
        t = muN
        k = 0
    H[c, b + M_T] = s * t
    H[c, b + M_TS] = ts
    H[c, b + M_TSS] = tss
    H[c, b + M_REGIME] = k
    H[c, b + M_SIGN] = s
    return s * t


@njit(**JIT)
def md_axis(params, row, H, c, b, N, dN, a, a_old, nx, ny, nz, ddx, ddy, ddz, cs, sn, rescale):
    """md / md_rescale in 3D: the planar law along the force axis u.

    1. u is carried into the tangent plane and turned with the contact (``carry_unit``); when T = 0 it is
       the slip direction.
    2. The slip along u, d_par = dd . u, drives the planar law (``md_scalar``).
    3. The slip across, d_perp = dd - d_par u, turns the force about the normal keeping the planar law's
       |T|: T takes the direction of T u + k_0 d_perp with the elastic stiffness k_0 = 8 G* a.
    Returns T."""
    t_old = H[c, b + M_T]
    ux = 0.0
    uy = 0.0
    uz = 0.0
    if t_old != 0.0:
        ux, uy, uz = carry_unit(H[c, b + W_X], H[c, b + W_Y], H[c, b + W_Z], nx, ny, nz, cs, sn)
    if ux == 0.0 and uy == 0.0 and uz == 0.0:
        t_old = 0.0
        dmag = math.sqrt(ddx * ddx + ddy * ddy + ddz * ddz)
        if dmag > 0.0:
            ux = ddx / dmag
            uy = ddy / dmag
            uz = ddz / dmag
    d_par = ddx * ux + ddy * uy + ddz * uz
    px = ddx - d_par * ux
    py = ddy - d_par * uy
    pz = ddz - d_par * uz
    T = md_scalar(params, row, H, c, b, N, dN, a, a_old, d_par, rescale)
    if T != 0.0 and (px != 0.0 or py != 0.0 or pz != 0.0):
        k0 = 8.0 * params[row, P_GSTAR] * a
        wx = T * ux + k0 * px
        wy = T * uy + k0 * py
        wz = T * uz + k0 * pz
        inv = 1.0 / math.sqrt(wx * wx + wy * wy + wz * wz)
        if T < 0.0:
            inv = -inv
        ux = wx * inv
        uy = wy * inv
        uz = wz * inv
    H[c, b + W_X] = ux
    H[c, b + W_Y] = uy
    H[c, b + W_Z] = uz
    H[c, b + W_WORK] += 0.5 * (t_old * d_par + T * (ux * ddx + uy * ddy + uz * ddz))
    return T * ux, T * uy, T * uz


# ----------------------------------------------------------------------------------------------- vector MDR

@njit(inline="always", **JIT)
def _cells(r, dx, n):
    """Number of cells of width dx overlapping [0, r) (at most n)."""
    if r <= 0.0:
        return 0
    m = int(r / dx) + 1
    return m if m < n else n


@njit(inline="always", **JIT)
def _radial(u1, u2, umax):
    """Local Coulomb circle |u| <= umax: radial return (direction kept)."""
    m2 = u1 * u1 + u2 * u2
    if m2 > umax * umax:
        s = umax / math.sqrt(m2)
        return u1 * s, u2 * s
    return u1, u2


@njit(**JIT)
def mdr_cells(params, row, H, c, k0, n, dx, N, a, a_old, d1, d2):
    """One step of the vector MDR cells H[c, k0 + 2 i], H[c, k0 + 2 i + 1] (i < n, width dx): the
    arithmetic of ``mdr._advance`` with a 2D displacement per cell and Coulomb circles (radial return)
    instead of intervals. Returns T in the cells' frame."""
    GM = 4.0 * params[row, P_GSTAR]
    cc = 3.0 * N / (4.0 * params[row, P_ESTAR] * a * a * a)
    umax_per_w = params[row, P_MU] * params[row, P_ESTAR] * cc / GM
    a2 = a * a
    da = a - a_old
    m = max(_cells(a, dx, n), _cells(a_old, dx, n))
    full = min(int(min(a, a_old) / dx), m)
    dx2 = dx * dx / 3.0
    S1 = 0.0
    S2 = 0.0
    for i in range(full):
        k = k0 + 2 * i
        umax = umax_per_w * (a2 - dx2 * (3 * i * (i + 1) + 1))
        u1, u2 = _radial(H[c, k] + d1, H[c, k + 1] + d2, umax)
        H[c, k] = u1
        H[c, k + 1] = u2
        S1 += u1
        S2 += u2
    T1 = S1 * dx
    T2 = S2 * dx
    for i in range(full, m):
        k = k0 + 2 * i
        x0 = i * dx
        l_new = min(max(a - x0, 0.0), dx)
        if l_new <= 0.0:
            H[c, k] = 0.0
            H[c, k + 1] = 0.0
            continue
        l_old = min(max(a_old - x0, 0.0), dx)
        u1 = H[c, k] + d1
        u2 = H[c, k + 1] + d2
        if l_new > l_old:
            # the part entering during the step takes the increment after its entry (mdr._advance)
            xm = x0 + 0.5 * (l_old + l_new)
            f = (a - xm) / da * (l_new - l_old)
            u1 = (u1 * l_old + d1 * f) / l_new
            u2 = (u2 * l_old + d2 * f) / l_new
        x1 = x0 + l_new
        u1, u2 = _radial(u1, u2, umax_per_w * (a2 - (x0 * x0 + x0 * x1 + x1 * x1) / 3.0))
        H[c, k] = u1
        H[c, k + 1] = u2
        T1 += u1 * l_new
        T2 += u2 * l_new
    return T1 * (2.0 * GM), T2 * (2.0 * GM)


@njit(**JIT)
def _merge(H, c, k0, n, dx, r):
    """Halve the resolution (``mdr._merge``), both components."""
    for j in range(n // 2):
        x0 = 2 * j * dx
        l0 = min(max(r - x0, 0.0), dx)
        l1 = min(max(r - x0 - dx, 0.0), dx)
        u1 = 0.0
        u2 = 0.0
        if l0 + l1 > 0.0:
            u1 = (H[c, k0 + 4 * j] * l0 + H[c, k0 + 4 * j + 2] * l1) / (l0 + l1)
            u2 = (H[c, k0 + 4 * j + 1] * l0 + H[c, k0 + 4 * j + 3] * l1) / (l0 + l1)
        H[c, k0 + 2 * j] = u1
        H[c, k0 + 2 * j + 1] = u2
    for j in range(2 * (n // 2), 2 * n):
        H[c, k0 + j] = 0.0


@njit(**JIT)
def _split(H, c, k0, n):
    """Double the resolution of the lower half of the cells (``mdr._split``), both components."""
    for j in range(n // 2 - 1, -1, -1):
        u1 = H[c, k0 + 2 * j]
        u2 = H[c, k0 + 2 * j + 1]
        H[c, k0 + 4 * j] = u1
        H[c, k0 + 4 * j + 1] = u2
        H[c, k0 + 4 * j + 2] = u1
        H[c, k0 + 4 * j + 3] = u2


@njit(**JIT)
def mdr_vector(params, row, H, c, b, N, a, a_old, nx, ny, nz, ddx, ddy, ddz, cs, sn, adaptive):
    """Vector MDR (Popov & Hess 2015 with a displacement vector per cell; ``mdr`` and ``mdr_adaptive``).

    The cells hold 2D displacements in a frame (e1, e2 = n x e1) of the tangent plane; e1 is carried into
    the current plane and turned with the contact each step (``carry_unit``), which carries the whole
    field rigidly. The slip increment in the frame, (dd . e1, dd . e2), is added to every cell in contact
    (entry and exit as in the planar law) and each cell is returned radially to its Coulomb circle
    |G_M u| <= mu E* w. ``adaptive``: the grid of ``mdr.mdr_adaptive`` (cell width at b + R_DX), else the
    fixed grid of ``mdr.mdr`` (NaN when the contact outgrows it). Returns T = T1 e1 + T2 e2."""
    n = int(params[row, P_NSPRING])
    k0 = b + R_CELLS
    if adaptive:
        dx = H[c, b + R_DX]
    else:
        dx = params[row, P_DX]
    if N <= 0.0 or a <= 0.0:
        if dx > 0.0:
            for j in range(2 * max(_cells(a, dx, n), _cells(a_old, dx, n))):
                H[c, k0 + j] = 0.0
        for j in range(W_X, R_CELLS):
            H[c, b + j] = 0.0
        return 0.0, 0.0, 0.0
    if not adaptive and a > n * dx:
        return math.nan, math.nan, math.nan
    ex, ey, ez = carry_unit(H[c, b + W_X], H[c, b + W_Y], H[c, b + W_Z], nx, ny, nz, cs, sn)
    if ex == 0.0 and ey == 0.0 and ez == 0.0:
        # a new frame: along the slip, or any axis of the tangent plane
        ex, ey, ez = carry_unit(ddx, ddy, ddz, nx, ny, nz, 1.0, 0.0)
        if ex == 0.0 and ey == 0.0 and ez == 0.0:
            if abs(nx) < 0.9:
                ex, ey, ez = carry_unit(1.0, 0.0, 0.0, nx, ny, nz, 1.0, 0.0)
            else:
                ex, ey, ez = carry_unit(0.0, 1.0, 0.0, nx, ny, nz, 1.0, 0.0)
    fx = ny * ez - nz * ey
    fy = nz * ex - nx * ez
    fz = nx * ey - ny * ex
    d1 = ddx * ex + ddy * ey + ddz * ez
    d2 = ddx * fx + ddy * fy + ddz * fz
    if adaptive:
        if dx <= 0.0 or a_old <= 0.0:
            for j in range(2 * n):
                H[c, k0 + j] = 0.0
            a_old = 0.0
            dx = 2.0 ** math.floor(math.log2(2.0 * a / n))
        while a > n * dx:
            _merge(H, c, k0, n, dx, a_old)
            dx *= 2.0
        while 4.0 * a < n * dx and 4.0 * a_old < n * dx:
            _split(H, c, k0, n)
            dx *= 0.5
        H[c, b + R_DX] = dx
    T1, T2 = mdr_cells(params, row, H, c, k0, n, dx, N, a, a_old, d1, d2)
    H[c, b + W_WORK] += 0.5 * ((H[c, b + R_T1] + T1) * d1 + (H[c, b + R_T2] + T2) * d2)
    H[c, b + W_X] = ex
    H[c, b + W_Y] = ey
    H[c, b + W_Z] = ez
    H[c, b + R_T1] = T1
    H[c, b + R_T2] = T2
    return T1 * ex + T2 * fx, T1 * ey + T2 * fy, T1 * ez + T2 * fz
