"""One contact evaluation: normal law, then tangential law, chosen by integer ids.

This is the single entry point the integrator (and user code) calls; adding a law means one kernel,
one id in ``registry`` and one branch here.
"""
from numba import njit

from . import mdr, normal, tangential
from .slots import H_A, H_N, P_KT

# normal law ids
HERTZ = 0
THORNTON = 1
HERTZ_DAMPED = 2
LINEAR_NORMAL = 3
# tangential law ids
MD = 0
MD_RESCALE = 1
MINDLIN_TOTAL = 2
MINDLIN_INCREMENTAL = 3
MINDLIN_RESCALE = 4
LINEAR_TANGENTIAL = 5
DDM = 6
MDR = 7
MDR_ADAPTIVE = 8


@njit(inline="always", cache=True)
def normal_force(nid, p, h, delta, vel):
    """Normal force N [N] (may be tensile only for the linear law) and contact radius a [m]."""
    if nid == HERTZ:
        return normal.hertz(p, delta)
    if nid == THORNTON:
        return normal.thornton(p, h, delta)
    if nid == HERTZ_DAMPED:
        return normal.hertz_damped(p, delta, vel)
    return normal.linear(p, delta, vel)


@njit(inline="always", cache=True)
def normal_gap(nid, p, h, delta, vel):
    """Pure: > 0 while the bodies are in contact at overlap ``delta`` and rate ``vel``, <= 0 otherwise."""
    if nid == THORNTON:
        return normal.thornton_gap(h, delta)
    if nid == HERTZ_DAMPED:
        return normal.hertz_damped_gap(p, delta, vel)
    return delta


@njit(inline="always", cache=True)
def tangential_force(tid, p, h, N, dN, a, a_old, dd):
    """Tangential force T [N] in the direction of the displacement increment ``dd`` [m]."""
    if tid == MD:
        return tangential.md(p, h, N, dN, a, a_old, dd, False)
    if tid == MD_RESCALE:
        return tangential.md(p, h, N, dN, a, a_old, dd, True)
    if tid == MINDLIN_TOTAL:
        return tangential.mindlin_total(p, h, N, a, dd, 1.0)
    if tid == MINDLIN_INCREMENTAL:
        return tangential.mindlin_incremental(p, h, N, a, a_old, dd, False)
    if tid == MINDLIN_RESCALE:
        return tangential.mindlin_incremental(p, h, N, a, a_old, dd, True)
    if tid == LINEAR_TANGENTIAL:
        return tangential.incremental(p, h, N, a, a, dd, False, p[P_KT])
    if tid == MDR:
        return mdr.mdr(p, h, N, a, a_old, dd)
    if tid == MDR_ADAPTIVE:
        return mdr.mdr_adaptive(p, h, N, a, a_old, dd)
    return tangential.mindlin_total(p, h, N, a, dd, 2.0 / 3.0)


@njit(inline="always", cache=True)
def contact_step(nid, tid, p, h, delta, vel, dd):
    """Advance one contact by one step to overlap ``delta`` [m] (rate ``vel`` [m/s]) with tangential
    displacement increment ``dd`` [m]. Returns (N, a, T); N is the law's force (tension only for the
    linear law), the tangential law sees max(N, 0). Writes H_N, H_A and the law's own slots."""
    N, a = normal_force(nid, p, h, delta, vel)
    Np = N if N > 0.0 else 0.0
    T = tangential_force(tid, p, h, Np, Np - h[H_N], a, h[H_A], dd)
    h[H_N] = Np
    h[H_A] = a
    return N, a, T
