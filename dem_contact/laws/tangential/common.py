"""Arithmetic shared by several tangential laws (planar forms)."""
from numba import njit

from ..slots import H_REGIME, H_SIGN, H_T, H_TS, H_TSS, H_XI

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
def cap(T, muN):
    """Coulomb cap |T| <= mu N."""
    if T > muN:
        return muN
    if T < -muN:
        return -muN
    return T
