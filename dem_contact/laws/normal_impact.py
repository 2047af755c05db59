"""Head-on impact under a normal law alone: the calibrations of ``model`` (damped-Hertz dashpot,
contact time, largest contact radius) and the located end of contact that the impact integrator shares.

Velocity Verlet with constant dt from first touch (delta = 0) to separation: the normal motion of
``impacts.integrator.integrate_impact`` (which takes ``TOUCH_OVERLAP`` and ``end_fraction`` from here and
repeats the arithmetic of ``drift`` inline: calling it from that hot loop costs about 15% per impact), so
a calibration and an impact of the same law agree to the last bit.
"""
import math

from numba import njit

from .contact import normal_force, normal_gap
from .slots import H_A, H_N

#: Overlap at which the force just after first touch is evaluated [m].
TOUCH_OVERLAP = 1e-300


@njit(cache=True)
def end_fraction(nid, p, h, delta, vn, N, inv_m, dt):
    """Fraction s in [0, 1] of the step at which the gap function reaches 0 (Illinois regula falsi).
    Drift of a partial step of length s dt: delta + (vn - N s dt / (2 m*)) s dt. Returns the point on
    the contact side of the root (the force there is the limit from inside the contact). The rate seen
    by the gap function is the predicted end-of-step velocity, as in the impact integrator."""
    s_lo = 0.0
    g_lo = normal_gap(nid, p, h, delta, vn)
    if g_lo <= 0.0:
        return 0.0
    s_hi = 1.0
    v = vn - 0.5 * dt * N * inv_m
    g_hi = normal_gap(nid, p, h, delta + v * dt, v - 0.5 * dt * N * inv_m)
    side = 0
    for it in range(200):
        if s_hi - s_lo <= 1e-15:
            break
        if it < 60 and g_hi != g_lo:      # (both can reach 0: an exact root, halved end values)
            s = (s_lo * g_hi - s_hi * g_lo) / (g_hi - g_lo)
            if not (s > s_lo and s < s_hi):
                s = 0.5 * (s_lo + s_hi)
        else:
            s = 0.5 * (s_lo + s_hi)
        v = vn - 0.5 * s * dt * N * inv_m
        g = normal_gap(nid, p, h, delta + v * s * dt, v - 0.5 * s * dt * N * inv_m)
        if g > 0.0:
            s_lo, g_lo = s, g
            if side == 1:
                g_hi *= 0.5
            side = 1
        else:
            s_hi, g_hi = s, g
            if side == -1:
                g_lo *= 0.5
            side = -1
    return s_lo


@njit(cache=True)
def drift(nid, p, h, delta, vn, N, inv_m, dt, locate):
    """Half kick and drift of a velocity-Verlet step with the old normal force N. When the contact ends in
    this step and ``locate`` is set, the step is cut at the separation (``end_fraction``). Returns
    (step length, half kick, half-step velocity, new overlap, ended)."""
    hdt = dt
    kick = 0.5 * hdt * N * inv_m
    vn_h = vn - kick
    delta_new = delta + vn_h * hdt
    # velocity-dependent forces see the end-of-step velocity predicted with the old force
    ended = normal_gap(nid, p, h, delta_new, vn_h - kick) <= 0.0
    if ended and locate:
        hdt = dt * end_fraction(nid, p, h, delta, vn, N, inv_m, dt)
        kick = 0.5 * hdt * N * inv_m
        vn_h = vn - kick
        delta_new = delta + vn_h * hdt
    return hdt, kick, vn_h, delta_new, ended


@njit(cache=True)
def normal_impact(nid, p, h, vn0, inv_m, dt, max_steps):
    """Head-on impact at speed vn0 > 0 [m/s] with effective mass 1/inv_m, separation located inside the
    last step. h: zeroed history row. Returns (final normal velocity [m/s], contact time [s], maximum
    overlap [m], status: 0 ended, 1 step limit, 2 non-finite)."""
    delta = 0.0
    vn = vn0
    t = 0.0
    dmax = 0.0
    N = normal_force(nid, p, h, TOUCH_OVERLAP, vn0)[0]
    h[H_N] = N if N > 0.0 else 0.0
    for k in range(max_steps):
        hdt, kick, vn_h, delta_new, ended = drift(nid, p, h, delta, vn, N, inv_m, dt, True)
        d_eval = delta_new if not ended or delta_new > TOUCH_OVERLAP else TOUCH_OVERLAP
        N, a = normal_force(nid, p, h, d_eval, vn_h - kick)
        h[H_N] = N if N > 0.0 else 0.0
        h[H_A] = a
        vn = vn_h - 0.5 * hdt * N * inv_m
        t += hdt
        delta = delta_new
        if delta > dmax:
            dmax = delta
        if not (math.isfinite(vn) and math.isfinite(delta) and math.isfinite(N)):
            return vn, t, dmax, 2
        if ended:
            return vn, t, dmax, 0
    return vn, t, dmax, 1
