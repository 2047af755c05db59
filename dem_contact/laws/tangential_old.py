"""Tangential contact laws (jitted kernels).

Every law receives the normal force after the step N >= 0 [N], its increment dN [N], the contact radius
after and before the step a, a_old [m], and the tangential displacement increment dd = v_t dt [m] of
the contact patch. It returns T [N], the tangential force in the direction of positive displacement (the
force on body 1 is -T), and updates its history slots in place. Every law caps |T| <= mu N.
When N <= 0 or a <= 0 the contact carries no tangential load: history is released.
"""

from numba import njit

from .slots import H_REGIME, H_SIGN, H_T, H_TS, H_TSS, H_XI, P_GSTAR, P_MU


@njit(cache=True)
def release(h):
    """Zero the tangential history (contact lost or unloaded to N = 0)."""
    h[H_T] = 0.0
    h[H_TS] = 0.0
    h[H_TSS] = 0.0
    h[H_REGIME] = 0.0
    h[H_SIGN] = 0.0
    h[H_XI] = 0.0


@njit(cache=True)
def mean_radius(a0, a1):
    """Mean contact radius over a step in which the overlap changes linearly from a0^2/R to a1^2/R:
    (2/3)(a0^2 + a0 a1 + a1^2)/(a0 + a1). With it the stuck increment 8 G* a d(delta_t) integrates the
    Hertz stiffness exactly over the step; the end-of-step radius would overestimate the first step of a
    contact by a factor 3/2 (and so make it slip)."""
    return 2.0 / 3.0 * (a0 * a0 + a0 * a1 + a1 * a1) / (a0 + a1)


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
    ``rescale``: Thornton, Cummins & Cleary (2013) variant: when the contact shrinks, T, T* and T** are
    first scaled by a / a_old. Slots: H_T, H_TS, H_TSS, H_REGIME, H_SIGN.
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


@njit(cache=True)
def cap(T, muN):
    """Coulomb cap |T| <= mu N."""
    if T > muN:
        return muN
    if T < -muN:
        return -muN
    return T


@njit(cache=True)
def mindlin_total(p, h, N, a, dd, factor):
    """Total-displacement no-slip Hertz-Mindlin (LIGGGHTS `tangential history`, EDEM, LAMMPS `mindlin`;
    Mindlin 1949; Di Renzo & Di Maio 2004): xi += dd, T = factor 8 G* a xi, capped at mu N with xi = T / (factor 8 G* a).
    factor = 1; factor = 2/3 is Di Renzo & Di Maio (2005). Slots: H_XI, H_T."""
    muN = p[P_MU] * N
    if N <= 0.0 or a <= 0.0:
        release(h)
        return 0.0
    kt = factor * 8.0 * p[P_GSTAR] * a
    xi = h[H_XI] + dd
    T = kt * xi
    if abs(T) > muN:
        T = cap(T, muN)
        xi = T / kt
    h[H_XI] = xi
    h[H_T] = T
    return T


@njit(cache=True)
def incremental(p, h, N, a, a_old, dd, rescale, kt):
    """Incremental force laws (Mindlin 1949; Di Renzo & Di Maio 2004): T += kt dd, capped at mu N.
    Yade / LAMMPS `mindlin/force` (kt = 8 G* a); with ``rescale`` LAMMPS `mindlin_rescale/force` first
    scales T by a / a_old when the contact shrinks; Cundall-Strack linear spring (constant kt). Slot: H_T."""
    if N <= 0.0 or a <= 0.0:
        release(h)
        return 0.0
    T = h[H_T]
    if rescale and a < a_old:
        T *= a / a_old
    T = cap(T + kt * dd, p[P_MU] * N)
    h[H_T] = T
    return T


@njit(cache=True)
def mindlin_incremental(p, h, N, a, a_old, dd, rescale):
    return incremental(p, h, N, a, a_old, dd, rescale, 8.0 * p[P_GSTAR] * a)
