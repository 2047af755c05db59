"""Thornton & Yin (1991) incremental Mindlin-Deresiewicz.

Planar: the regimes of ``md`` (loading, unloading, reloading with the reversal points T*, T**). In 3D the
planar law acts along the force axis u (carried into the tangent plane and turned with the contact); slip
across the axis turns the force about the normal keeping the planar law's |T| (``md_axis_turn``).
"""
import math

import numpy as np
from numba import njit

from ..declare import GSTAR, MU
from ..slots import H_REGIME, H_SIGN, H_T, H_TS, H_TSS, P_GSTAR, P_MU
from ..vector import JIT, V_A, V_N, W_WORK, W_X, W_Y, W_Z, carry_unit, renamed
from .common import mean_radius, release

NAME, FAMILY = "md", "tangential"
SOURCE = "Thornton & Yin (1991) incremental Mindlin-Deresiewicz"
PARAMETERS, STATE = (GSTAR, MU), ("T", "T*", "T**", "regime", "sign")
RESCALE = False

# 3D slots relative to the tangential base b: the work, the axis u (W_X, W_Y, W_Z), then these
M_T = 4
M_TS = 5
M_TSS = 6
M_REGIME = 7
M_SIGN = 8
#: fixed 3D slots of the law (work and axis included); the sign rules for swapping the bodies: the axis
#: changes sign (T along it keeps its value)
VECTOR_SLOTS = 9
SWAP_NEGATE = (W_X, W_Y, W_Z)


@njit(cache=True)
def md(p, h, N, dN, a, a_old, dd, rescale):
    """Thornton & Yin (1991) incremental Mindlin-Deresiewicz (Thornton & Yin 1991).

    dT = 8 G* a theta_k d(delta_t) + (-1)^k mu dN (1 - theta_k), with, for N after the step,
      k = 0 loading:   theta^3 = 1 - (T + mu dN) / (mu N)
      k = 1 unloading: theta^3 = 1 - (T* - T + 2 mu dN) / (2 mu N)
      k = 2 reloading: theta^3 = 1 - (T - T** + 2 mu dN) / (2 mu N)
    theta^3 clamped to [0, 1]; after every step T* += mu dN and T** -= mu dN (the reversal points
    follow +/- mu N). T, T*, T** are handled in a canonical frame where the current loading is positive
    (H_SIGN holds its direction). Reversal of d(delta_t): loading -> unloading (T* = T), unloading ->
    reloading (T** = T), reloading -> unloading (T* = T); reloading reaching T* is loading again;
    unloading past -T* is loading in the opposite direction; |T| >= mu N is slip (T = +/- mu N, loading).
    The stiffness uses the mean contact radius of the step (``mean_radius``).
    ``rescale`` (Thornton, Cummins & Cleary 2013): when the contact shrinks, T, T* and T** are first scaled
    by a / a_old. Slots: H_T, H_TS, H_TSS, H_REGIME, H_SIGN.
    """
    mu = p[P_MU]
    muN = mu * N
    if muN <= 0.0 or a <= 0.0:
        release(h)
        return 0.0
    s = h[H_SIGN]
    if s == 0.0:
        s = 1.0 if dd >= 0.0 else -1.0
    t = s * h[H_T]
    ts = h[H_TS]
    tss = h[H_TSS]
    k = int(h[H_REGIME])
    if rescale and a < a_old:
        r = a / a_old
        t *= r
        ts *= r
        tss *= r
    d = s * dd
    mdN = mu * dN
    # reversals of the tangential displacement
    if k == 0:
        if d < 0.0:
            if t <= 0.0:          # nothing loaded in this direction: load the other way
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
    kt = 8.0 * p[P_GSTAR] * mean_radius(a_old, a)
    if mdN > 0.0 and abs(kt * d) < mdN:
        # Mindlin & Deresiewicz: N grows faster than T / mu, nothing slips (theta = 1)
        t += kt * d
    elif k == 0:
        th3 = 1.0 - (t + mdN) / muN
        th = min(max(th3, 0.0), 1.0) ** (1.0 / 3.0)
        t += kt * th * d + mdN * (1.0 - th)
    elif k == 1:
        th3 = 1.0 - (ts - t + 2.0 * mdN) / (2.0 * muN)
        th = min(max(th3, 0.0), 1.0) ** (1.0 / 3.0)
        t += kt * th * d - mdN * (1.0 - th)
    else:
        th3 = 1.0 - (t - tss + 2.0 * mdN) / (2.0 * muN)
        th = min(max(th3, 0.0), 1.0) ** (1.0 / 3.0)
        t += kt * th * d + mdN * (1.0 - th)
    ts += mdN
    tss -= mdN
    if k == 1 and t < -ts:        # unloaded past -T*: loading in the opposite direction
        s = -s
        t = -t
        k = 0
    elif k == 2 and t >= ts:      # reloaded up to T*: loading again
        k = 0
    if abs(t) >= muN:             # Coulomb slip
        if t < 0.0:
            s = -s
        t = muN
        k = 0
    h[H_T] = s * t
    h[H_TS] = ts
    h[H_TSS] = tss
    h[H_REGIME] = k
    h[H_SIGN] = s
    return s * t


@njit(inline="always", **JIT)
def md_scalar(mu, G, N, dN, a, a_old, dd, rescale, T, ts, tss, k, s):
    """Thornton & Yin (1991) incremental Mindlin-Deresiewicz along one axis: the arithmetic of
    ``md`` (see there for the regimes and reversal points) on its state (T, T*, T**, regime k,
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
    """The law in 3D, before the planar law: the force axis u carried into the tangent plane and
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
    """The law in 3D, after the planar law: slip across the axis, d_perp = (px, py, pz), turns the force about
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


def _vector(params, row, H, c, b, N, a, fstar, nx, ny, nz, ddx, ddy, ddz, cs, sn):
    """One 3D step of the law (see the module docstring), with the global RESCALE bound by ``forms``.
    Returns T (tx, ty, tz)."""
    G = params[row, P_GSTAR]
    ux, uy, uz, t_old, d_par, px, py, pz = md_axis_start(H[c, b + W_X], H[c, b + W_Y], H[c, b + W_Z],
                                                        H[c, b + M_T], nx, ny, nz, ddx, ddy, ddz, cs, sn)
    T, ts, tss, k, s = md_scalar(params[row, P_MU], G, N, N - H[c, V_N], a, H[c, V_A], d_par, RESCALE, t_old,
                                 H[c, b + M_TS], H[c, b + M_TSS], int(H[c, b + M_REGIME]), H[c, b + M_SIGN])
    ux, uy, uz = md_axis_turn(T, 8.0 * G * a, ux, uy, uz, px, py, pz)
    H[c, b + W_WORK] += 0.5 * (t_old * d_par + T * (ux * ddx + uy * ddy + uz * ddz))
    H[c, b + W_X] = ux
    H[c, b + W_Y] = uy
    H[c, b + W_Z] = uz
    H[c, b + M_T] = T
    H[c, b + M_TS] = ts
    H[c, b + M_TSS] = tss
    H[c, b + M_REGIME] = k
    H[c, b + M_SIGN] = s
    return T * ux, T * uy, T * uz


def _planar(p, h, N, dN, a, a_old, dd):
    return md(p, h, N, dN, a, a_old, dd, RESCALE)


def forms(name, rescale):
    """(planar, vector) kernels of the law with ``rescale`` (a law of this file or its variant)."""
    return (njit(inline="always", cache=True)(renamed(_planar, f"planar_{name}", RESCALE=rescale)),
            njit(inline="always", **JIT)(renamed(_vector, f"vector_{name}", RESCALE=rescale)))


_FORMS = forms(NAME, RESCALE)
planar = _FORMS[0]
"""The planar kernel, ``planar(p, h, N, dN, a, a_old, dd) -> T`` (``md`` without rescaling)."""
vector = _FORMS[1]
"""The 3D kernel, ``vector(params, row, H, c, b, N, a, F*, n, dd, cos, sin) -> T``."""
