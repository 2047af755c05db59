"""Head-on impact under a normal law alone: the calibrations of ``model`` (damped-Hertz dashpot,
contact time, largest contact radius), and the normal motion that the impact integrators share.

Velocity Verlet with constant dt from first touch (delta = 0) to separation: the normal motion of
``impacts.integrator.integrate_impact`` and ``impacts.impact3d.integrate_impact3d``. Both take it from here,
inlined into their loops (numba ``inline="always"``: no call in the hot loop): the first touch
(``normal_start``), the half kick and drift of each step with the located end (``drift``), the overlap at
which the force of a step is evaluated (``eval_overlap``), the second half kick with the records of the
normal motion (``normal_close``) and the status of a step (``step_status``); so a calibration and an impact
of the same law agree to the last bit.
"""
import math

from numba import njit

from .contact import normal_force, normal_gap
from .slots import H_A, H_N

#: Overlap at which the force just after first touch is evaluated [m].
TOUCH_OVERLAP = 1e-300

# status of an impact (``step_status``)
STATUS_OK = 0           # the contact ended
STATUS_MAX_STEPS = 1    # the step limit was reached
STATUS_NONFINITE = 2    # the state is not finite


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


@njit(inline="always", cache=True)
def normal_start(nid, p, h, vn0):
    """The normal motion at first touch, at approach speed vn0, its records and status: (overlap 0, rate
    vn0, force N, time 0, normal impulse 0, work of the normal force 0, largest overlap 0, largest force 0,
    steps 0, STATUS_MAX_STEPS). N is the force just after touch (non-zero only for a dashpot acting at zero
    overlap), written to the history's normal slot."""
    N = normal_force(nid, p, h, TOUCH_OVERLAP, vn0)[0]
    h[H_N] = N if N > 0.0 else 0.0
    return 0.0, vn0, N, 0.0, 0.0, 0.0, 0.0, 0.0, 0, STATUS_MAX_STEPS


@njit(inline="always", cache=True)
def eval_overlap(delta_new, ended):
    """The overlap at which the force of a step is evaluated: at a located end, the limit from inside the
    contact."""
    return delta_new if not ended or delta_new > TOUCH_OVERLAP else TOUCH_OVERLAP


@njit(inline="always", cache=True)
def normal_close(N, Nn, hdt, delta, delta_new, vn_h, inv_m, t, PN, WN, dmax, fmax, steps):
    """End of a step of length hdt from overlap delta to delta_new: the second half kick with the new force Nn
    and the records (impulse and work of the normal force by the trapezoid rule, largest overlap and force,
    steps). Returns the state and records of ``normal_start`` (without the status) at the end of the step."""
    return (delta_new, vn_h - 0.5 * hdt * Nn * inv_m, Nn, t + hdt, PN + 0.5 * hdt * (N + Nn),
            WN + 0.5 * (N + Nn) * (delta_new - delta), delta_new if delta_new > dmax else dmax,
            Nn if Nn > fmax else fmax, steps + 1)


@njit(inline="always", cache=True)
def step_status(finite, ended):
    """Status after a step: STATUS_NONFINITE where the state is not finite, STATUS_OK where the contact ended,
    else STATUS_MAX_STEPS (the impact goes on; the status if the step limit ends it)."""
    if not finite:
        return STATUS_NONFINITE
    if ended:
        return STATUS_OK
    return STATUS_MAX_STEPS


@njit(inline="always", cache=True)
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
    overlap [m], status: STATUS_OK, STATUS_MAX_STEPS or STATUS_NONFINITE)."""
    delta, vn, N, t, PN, WN, dmax, fmax, steps, status = normal_start(nid, p, h, vn0)
    for k in range(max_steps):
        hdt, kick, vn_h, delta_new, ended = drift(nid, p, h, delta, vn, N, inv_m, dt, True)
        Nn, a = normal_force(nid, p, h, eval_overlap(delta_new, ended), vn_h - kick)
        h[H_N] = Nn if Nn > 0.0 else 0.0
        h[H_A] = a
        delta, vn, N, t, PN, WN, dmax, fmax, steps = normal_close(N, Nn, hdt, delta, delta_new, vn_h, inv_m, t, PN,
                                                                  WN, dmax, fmax, steps)
        status = step_status(math.isfinite(vn) and math.isfinite(delta) and math.isfinite(N), ended)
        if status != STATUS_MAX_STEPS:
            break
    return vn, t, dmax, status
