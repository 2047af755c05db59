"""3D forms of the contact laws, for the flat DEM kernels of ``dem.contact3d``.

The kernels here are functions of scalars that return scalars (the state in, the new state out): the
kernels of ``dem.contact3d`` read a contact's state from its row of the history table, ``H[c, j]``, call
them, and write the state back, so that no array is passed between functions on the hot path. The
arithmetic of the normal laws is that of ``normal`` (a 3D contact that stays in a plane repeats the planar
laws); the tangential laws act on vectors in the tangent plane.

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

from ..errors import InputError
from .contact import (DDM, HERTZ, HERTZ_DAMPED, LINEAR_NORMAL, LINEAR_TANGENTIAL, MD, MD_RESCALE, MDR,
                      MDR_ADAPTIVE, MINDLIN_INCREMENTAL, MINDLIN_RESCALE, MINDLIN_TOTAL, THORNTON)

#: numba options of every flat kernel: numpy's error model (no zero-division checks), and of fastmath only
#: 'contract' (fused multiply-add, as gcc does by default) and 'afn' (library functions such as cbrt may be
#: approximated): results stay within rounding of the strict build. Not 'nnan' / 'ninf' (a NaN force
#: signals an outgrown mdr grid, and the checks rely on NaN and inf), not 'reassoc' (cell sums keep order).
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
    the MDR cell count (the largest params[:, P_NSPRING] of the table, >= 2) for mdr and mdr_adaptive,
    which have no default (``PairTable.history_size`` has it all)."""
    if isinstance(nid, bool) or nid not in NORMAL_IDS:
        raise InputError(f"nid = {nid!r} is not a normal law id (valid: {', '.join(map(str, NORMAL_IDS))})")
    if isinstance(tid, bool) or tid not in TANGENTIAL_IDS:
        raise InputError(f"tid = {tid!r} is not a tangential law id (valid: {', '.join(map(str, TANGENTIAL_IDS))})")
    if tid in (MDR, MDR_ADAPTIVE) and not (isinstance(n_cells, (int, np.integer)) and n_cells >= 2):
        raise InputError(f"n_cells = {n_cells!r}: the mdr and mdr_adaptive laws need their cell count (an integer "
                         f">= 2, the largest params[:, P_NSPRING] of the table; PairTable.history_size has it)")
    b = 6 if nid == THORNTON else 2
    if tid in (MD, MD_RESCALE):
        return b + N_MD
    if tid in (MDR, MDR_ADAPTIVE):
        return b + R_CELLS + 2 * int(n_cells)
    return b + N_SPRING_VECTOR


# ---------------------------------------------------------------------------------------------- normal laws

@njit(inline="always", **JIT)
def hertz(E, R, delta):
    """Hertz (Johnson 1985, eq. 4.23): a = sqrt(R* delta), N = (4/3) E* a delta. Returns (N, a)."""
    if delta <= 0.0:
        return 0.0, 0.0
    a = math.sqrt(R * delta)
    return 4.0 / 3.0 * E * a * delta, a


@njit(**JIT)
def thornton(E, R, delta_y, F_y, p_y, dstar, fstar, Rp, dp, delta):
    """Thornton (1997, J. Appl. Mech. 64:383) elastic-perfectly plastic law, the arithmetic of
    ``normal.thornton`` on its four state values. Returns (N, a, delta*, F*, R_p, delta_p)."""
    if delta <= 0.0:
        return 0.0, 0.0, dstar, fstar, Rp, dp
    if delta >= dstar:
        a = math.sqrt(R * delta)
        if delta <= delta_y:
            F = 4.0 / 3.0 * E * a * delta
        else:
            F = F_y + math.pi * p_y * R * (delta - delta_y)
        if F > F_y:
            Rp = 4.0 * E * a * a * a / (3.0 * F)
            dp = delta - (3.0 * F / (4.0 * E * math.sqrt(Rp))) ** (2.0 / 3.0)
        return F, a, delta, F, Rp, dp
    Ru = Rp if Rp > 0.0 else R
    w = delta - dp
    if w <= 0.0:
        return 0.0, 0.0, dstar, fstar, Rp, dp
    a = math.sqrt(Ru * w)
    return 4.0 / 3.0 * E * a * w, a, dstar, fstar, Rp, dp


@njit(**JIT)
def hertz_damped(E, R, m, gamma, delta, vel):
    """Hertz plus dashpot 2 gamma sqrt(m* k_n) d(delta)/dt, k_n = 2 E* a, clamped at N >= 0
    (as ``normal.hertz_damped``; Tsuji et al. 1992 form)."""
    F, a = hertz(E, R, delta)
    kn = 2.0 * E * a
    F = F + 2.0 * gamma * math.sqrt(m * kn) * vel
    if F < 0.0:
        F = 0.0
    return F, a


@njit(**JIT)
def linear_normal(kn, gamma, m, R, delta, vel):
    """Linear spring-dashpot (Cundall & Strack 1979), as ``normal.linear``."""
    if delta <= 0.0:
        return 0.0, 0.0
    return kn * delta + 2.0 * gamma * math.sqrt(m * kn) * vel, math.sqrt(R * delta)


# ------------------------------------------------------------------------------------------ vector helpers

@njit(inline="always", **JIT)
def turn(x, y, z, nx, ny, nz, cs, sn):
    """Vector (x, y, z) in the plane normal to n turned by the angle (cos, sin) = (cs, sn) about n
    (Rodrigues' formula for a vector perpendicular to the axis)."""
    return (x * cs + (ny * z - nz * y) * sn,
            y * cs + (nz * x - nx * z) * sn,
            z * cs + (nx * y - ny * x) * sn)


@njit(inline="always", **JIT)
def in_plane(x, y, z, nx, ny, nz, un):
    """(x, y, z) less its part un = (x, y, z).n along n, and the squared length of what is left."""
    x -= un * nx
    y -= un * ny
    z -= un * nz
    return x, y, z, x * x + y * y + z * z


@njit(inline="always", **JIT)
def carry(x, y, z, nx, ny, nz, cs, sn):
    """A history vector carried into the tangent plane of n keeping its magnitude (projection and
    rescaling, as LAMMPS granular's tangential models do), then turned with the contact about n."""
    un = x * nx + y * ny + z * nz
    if un != 0.0:
        m2 = x * x + y * y + z * z
        x, y, z, p2 = in_plane(x, y, z, nx, ny, nz, un)
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
    x, y, z, p2 = in_plane(x, y, z, nx, ny, nz, x * nx + y * ny + z * nz)
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


# ------------------------------------------------------------------------------------ vector spring laws

@njit(inline="always", **JIT)
def spring_total(g8, mu, N, a, a_old, x, y, z, nx, ny, nz, ddx, ddy, ddz, cs, sn):
    """Total-displacement Hertz-Mindlin as a vector spring (LAMMPS ``tangential mindlin``; with
    g8 = (2/3) 8 G*: Di Renzo & Di Maio 2005): the spring displacement xi = (x, y, z) is carried into the
    plane, xi += dd, T = g8 a xi, and if |T| > mu N, T is scaled to mu N and xi = T / (g8 a).
    Returns (T, new xi, work increment 0.5 (T_old + T) . dd)."""
    if N <= 0.0 or a <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    x, y, z = carry(x, y, z, nx, ny, nz, cs, sn)
    w_old = g8 * a_old * (x * ddx + y * ddy + z * ddz)
    kt = g8 * a
    x += ddx
    y += ddy
    z += ddz
    tx, ty, tz, slip = cap_vector(kt * x, kt * y, kt * z, mu * N)
    if slip:
        x = tx / kt
        y = ty / kt
        z = tz / kt
    return tx, ty, tz, x, y, z, 0.5 * (w_old + tx * ddx + ty * ddy + tz * ddz)


@njit(inline="always", **JIT)
def spring_incremental(kt, mu, N, a, a_old, x, y, z, nx, ny, nz, ddx, ddy, ddz, cs, sn, rescale):
    """Incremental force law as a vector spring (LAMMPS ``mindlin/force``, ``mindlin_rescale/force``;
    Cundall & Strack's linear spring with a constant kt): T = (x, y, z) carried into the plane, scaled by
    a / a_old when the contact shrinks (rescale), T += kt dd, scaled back to mu N if longer.
    Returns (T, work increment)."""
    if N <= 0.0 or a <= 0.0:
        return 0.0, 0.0, 0.0, 0.0
    x, y, z = carry(x, y, z, nx, ny, nz, cs, sn)
    if rescale and a < a_old:
        r = a / a_old
        x *= r
        y *= r
        z *= r
    w_old = x * ddx + y * ddy + z * ddz
    tx, ty, tz, slip = cap_vector(x + kt * ddx, y + kt * ddy, z + kt * ddz, mu * N)
    return tx, ty, tz, 0.5 * (w_old + tx * ddx + ty * ddy + tz * ddz)


# --------------------------------------------------------------------------------------- md along an axis

@njit(inline="always", **JIT)
def md_scalar(mu, G, N, dN, a, a_old, dd, rescale, T, ts, tss, k, s):
    """Thornton & Yin (1991) incremental Mindlin-Deresiewicz along one axis: the arithmetic of
    ``tangential.md`` (see there for the regimes and reversal points) on its state (T, T*, T**, regime k,
    loading sign s); the cube root is ``cbrt``. Returns the new state; its first value is T."""
    muN = mu * N
    if muN <= 0.0 or a <= 0.0:
        return 0.0, 0.0, 0.0, 0, 0.0
    if s == 0.0:
        s = 1.0 if dd >= 0.0 else -1.0
    t = s * T
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
    kt = 8.0 * G * (2.0 / 3.0 * (a_old * a_old + a_old * a + a * a) / (a_old + a))
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
    return s * t, ts, tss, k, s


@njit(inline="always", **JIT)
def md_axis_start(ux, uy, uz, T, nx, ny, nz, ddx, ddy, ddz, cs, sn):
    """md / md_rescale in 3D, before the planar law: the force axis u carried into the tangent plane and
    turned with the contact (the slip direction when T = 0), and the split of the slip increment into
    d_par = dd . u (drives the planar law) and d_perp = dd - d_par u. Returns (u, T_old, d_par, d_perp)."""
    if T != 0.0:
        ux, uy, uz = carry_unit(ux, uy, uz, nx, ny, nz, cs, sn)
    else:
        ux = 0.0
        uy = 0.0
        uz = 0.0
    if ux == 0.0 and uy == 0.0 and uz == 0.0:
        T = 0.0
        dmag = math.sqrt(ddx * ddx + ddy * ddy + ddz * ddz)
        if dmag > 0.0:
            ux = ddx / dmag
            uy = ddy / dmag
            uz = ddz / dmag
    d_par = ddx * ux + ddy * uy + ddz * uz
    return ux, uy, uz, T, d_par, ddx - d_par * ux, ddy - d_par * uy, ddz - d_par * uz


@njit(inline="always", **JIT)
def md_axis_turn(T, k0, ux, uy, uz, px, py, pz):
    """md in 3D, after the planar law: slip across the axis, d_perp = (px, py, pz), turns the force about
    the normal keeping the planar law's |T|: T takes the direction of T u + k0 d_perp (k0 = 8 G* a, the
    elastic stiffness). Returns the new axis u."""
    if T != 0.0 and (px != 0.0 or py != 0.0 or pz != 0.0):
        wx = T * ux + k0 * px
        wy = T * uy + k0 * py
        wz = T * uz + k0 * pz
        inv = 1.0 / math.sqrt(wx * wx + wy * wy + wz * wz)
        if T < 0.0:
            inv = -inv
        return wx * inv, wy * inv, wz * inv
    return ux, uy, uz


# ----------------------------------------------------------------------------------------------- vector MDR

@njit(inline="always", **JIT)
def cells(r, dx, n):
    """Number of MDR cells of width dx overlapping [0, r) (at most n)."""
    if r <= 0.0:
        return 0
    m = int(r / dx) + 1
    return m if m < n else n


@njit(inline="always", **JIT)
def cells_q(r, q, n):
    """``cells`` given q = r / dx."""
    if r <= 0.0:
        return 0
    m = int(q) + 1
    return m if m < n else n


@njit(inline="always", **JIT)
def shrink_factor(x0, dx, a, a_old):
    """The factor of ``mdr.shrink_edge`` for the cell [x0, x0 + dx] that the new edge a < a_old cuts
    (x0 = int(a / dx) dx), the same arithmetic; 1 where the cell keeps its value."""
    l_new = a - x0
    l_old = min(a_old - x0, dx)
    if l_new > 0.0 and l_old > l_new:
        w_old = a_old * a_old - (x0 * x0 + x0 * (x0 + l_old) + (x0 + l_old) * (x0 + l_old)) / 3.0
        if w_old > 0.0:
            return (a_old * a_old - (x0 * x0 + x0 * a + a * a) / 3.0) / w_old
    return 1.0


@njit(inline="always", **JIT)
def initial_width(a, n, R):
    """``mdr.initial_width`` (R* times the power of 2 with n dx / 2 <= a < n dx) by ``ldexp``: the same value,
    without numba's integer power (a call that could raise, which would keep the array reference counts
    of the 3D kernels)."""
    L = R if R > 0.0 else 1.0
    return math.ldexp(L, int(math.floor(math.log2(2.0 * a / (n * L)))))


#: a cell with |u|^2 > NEAR umax^2 may be beyond its Coulomb circle (the margin covers the rounding of |u|^2)
NEAR = 1.0 - 1e-9


@njit(inline="always", **JIT)
def radial(u1, u2, umax):
    """Local Coulomb circle |u| <= umax of an MDR cell: radial return (direction kept)."""
    m2 = u1 * u1 + u2 * u2
    if m2 > umax * umax:
        s = umax / math.sqrt(m2)
        return u1 * s, u2 * s
    return u1, u2


@njit(inline="always", **JIT)
def new_frame(nx, ny, nz, ddx, ddy, ddz):
    """First axis of a new frame of the tangent plane: along the slip, or any axis of the plane."""
    ex, ey, ez = carry_unit(ddx, ddy, ddz, nx, ny, nz, 1.0, 0.0)
    if ex == 0.0 and ey == 0.0 and ez == 0.0:
        if abs(nx) < 0.9:
            ex, ey, ez = carry_unit(1.0, 0.0, 0.0, nx, ny, nz, 1.0, 0.0)
        else:
            ex, ey, ez = carry_unit(0.0, 1.0, 0.0, nx, ny, nz, 1.0, 0.0)
    return ex, ey, ez


@njit(inline="always", **JIT)
def mdr_frame(ex, ey, ez, nx, ny, nz, ddx, ddy, ddz, cs, sn):
    """Frame (e1, e2 = n x e1) of the vector MDR cells: e1 carried into the current plane and turned with
    the contact, which carries the whole cell field rigidly; a new frame (e1 = 0) is along the slip, or
    any axis of the tangent plane. Returns (e1, e2, dd . e1, dd . e2)."""
    ex, ey, ez = carry_unit(ex, ey, ez, nx, ny, nz, cs, sn)
    if ex == 0.0 and ey == 0.0 and ez == 0.0:
        ex, ey, ez = new_frame(nx, ny, nz, ddx, ddy, ddz)
    fx = ny * ez - nz * ey
    fy = nz * ex - nx * ez
    fz = nx * ey - ny * ex
    return ex, ey, ez, fx, fy, fz, ddx * ex + ddy * ey + ddz * ez, ddx * fx + ddy * fy + ddz * fz
