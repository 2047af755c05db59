"""Normal contact laws (jitted kernels).

Each law maps the overlap ``delta`` [m] and its rate ``vel`` = d(delta)/dt [m/s] to the normal force N [N]
(positive = repulsive) and the contact radius a [m] that the tangential laws need (k_t = 8 G* a).
``*_gap`` functions are pure: positive while the bodies are in contact, <= 0 once the contact has ended;
the integrator uses them to locate separation inside a time step.

History slots (see ``slots``): only ``thornton`` uses the normal slots H_DSTAR, H_FSTAR, H_RP, H_DP.
"""
import math

from numba import njit

from .slots import (H_DP, H_DSTAR, H_FSTAR, H_N, H_RP, H_T, P_DELTA_Y, P_ESTAR, P_F_Y, P_GAMMA, P_KN,
                    P_MSTAR, P_MU, P_PY, P_RSTAR, P_TY_DMU, P_TY_NODES, P_TY_TABLE)


@njit(inline="always", cache=True)
def hertz(p, delta):
    """Hertz (Johnson 1985, eq. 4.23): a = sqrt(R* delta), N = (4/3) E* a delta."""
    if delta <= 0.0:
        return 0.0, 0.0
    a = math.sqrt(p[P_RSTAR] * delta)
    return 4.0 / 3.0 * p[P_ESTAR] * a * delta, a


@njit(cache=True)
def thornton(p, h, delta):
    """Thornton (1997) elastic-perfectly plastic normal law (J. Appl. Mech. 64:383).

    Loading to a new maximum delta* (reads and writes H_DSTAR, H_FSTAR, H_RP, H_DP):
      Hertz while delta <= delta_y; then N = F_y + pi p_y R* (delta - delta_y), a = sqrt(R* delta).
      On every new maximum with N > F_y the unloading curve is stored:
      R_p = 4 E* a*^3 / (3 F*) and delta_p = delta* - (3 F* / (4 E* sqrt(R_p)))^(2/3).
    Unloading and elastic reloading below delta*: N = (4/3) E* sqrt(R_p) (delta - delta_p)^(3/2),
      a = sqrt(R_p (delta - delta_p)) (Hertz with R*, delta_p = 0 if the contact never yielded).
    With a traction-yield table in the row (P_TY_NODES > 0) loading follows
    ``_thornton_traction_loading``.
    """
    if delta <= 0.0:
        return 0.0, 0.0
    E = p[P_ESTAR]
    R = p[P_RSTAR]
    if delta >= h[H_DSTAR] and p[P_TY_NODES] > 0.0:
        return _thornton_traction_loading(p, h, delta)
    if delta >= h[H_DSTAR]:
        a = math.sqrt(R * delta)
        if delta <= p[P_DELTA_Y]:
            F = 4.0 / 3.0 * E * a * delta
        else:
            F = p[P_F_Y] + math.pi * p[P_PY] * R * (delta - p[P_DELTA_Y])
        h[H_DSTAR] = delta
        h[H_FSTAR] = F
        if F > p[P_F_Y]:
            Rp = 4.0 * E * a * a * a / (3.0 * F)
            h[H_RP] = Rp
            h[H_DP] = delta - (3.0 * F / (4.0 * E * math.sqrt(Rp))) ** (2.0 / 3.0)
        return F, a
    Rp = h[H_RP]
    if Rp <= 0.0:
        Rp = R
    w = delta - h[H_DP]
    if w <= 0.0:
        return 0.0, 0.0
    a = math.sqrt(Rp * w)
    return 4.0 / 3.0 * E * a * w, a


@njit(cache=True)
def yield_ratio(p, h):
    """p_y(mu_eff) / p_y of the traction-coupled Thornton law: the first-yield pressure of a Hertz contact
    with sliding traction mu_eff p over that without (``traction_yield``), interpolated in the table of
    the parameter row, at mu_eff = |T| / N of the contact's last step (at most mu)."""
    N = h[H_N]
    if N <= 0.0:
        return 1.0
    m = min(abs(h[H_T]) / N, p[P_MU])
    s = m / p[P_TY_DMU]
    last = int(p[P_TY_NODES]) - 1
    i = min(int(s), last - 1)
    t = min(s - i, 1.0)
    return (1.0 - t) * p[P_TY_TABLE + i] + t * p[P_TY_TABLE + i + 1]


@njit(cache=True)
def _thornton_traction_loading(p, h, delta):
    """Loading branch of ``thornton`` (delta >= delta*) with the limiting pressure p_y g(mu_eff), g from
    ``yield_ratio``, which changes during the contact.

    Before first yield: Hertz while delta <= delta_y(p_y g), then Thornton's law at that pressure,
    F = pi p_y g R* (delta - delta_y / 3) (the Hertz pressure truncated at p_y g). After yield, the
    increment dF = min(pi p_y g R*, 2 E* a_H(F*)) d(delta), a_H(F*) = (3 F* R* / (4 E*))^(1/3): Thornton's
    plastic stiffness at the current limit, never stiffer than a Hertz contact of R* carrying F*. The
    loading curve is then nowhere stiffer, at a given force, than the Hertz unloading curve of (R_p,
    delta_p), so a loading-unloading cycle cannot create energy. With g = 1 throughout it is Thornton's
    law (to rounding)."""
    E = p[P_ESTAR]
    R = p[P_RSTAR]
    py = p[P_PY] * yield_ratio(p, h)
    a = math.sqrt(R * delta)
    if h[H_RP] <= 0.0:
        dy = R * (math.pi * py / (2.0 * E)) ** 2
        if delta <= dy:
            F = 4.0 / 3.0 * E * a * delta
        else:
            F = math.pi * py * R * (delta - dy / 3.0)
    else:
        Fs = h[H_FSTAR]
        k = min(math.pi * py * R, 2.0 * E * (3.0 * Fs * R / (4.0 * E)) ** (1.0 / 3.0))
        F = Fs + k * (delta - h[H_DSTAR])
    if F < 4.0 / 3.0 * E * a * delta or h[H_RP] > 0.0:
        Rp = 4.0 * E * a * a * a / (3.0 * F)
        h[H_RP] = Rp
        h[H_DP] = delta - (3.0 * F / (4.0 * E * math.sqrt(Rp))) ** (2.0 / 3.0)
    h[H_DSTAR] = delta
    h[H_FSTAR] = F
    return F, a


@njit(inline="always", cache=True)
def thornton_gap(h, delta):
    """Positive while in contact: delta - delta_p (delta_p = 0 before yield)."""
    return delta - h[H_DP]


@njit(cache=True)
def hertz_damped_unclamped(p, delta, vel):
    """Hertz plus dashpot 2 gamma sqrt(m* k_n) d(delta)/dt with k_n = 2 E* a (Tsuji, Tanaka & Ishida 1992),
    before the clamp at zero force. Returns (force, a)."""
    F, a = hertz(p, delta)
    kn = 2.0 * p[P_ESTAR] * a
    return F + 2.0 * p[P_GAMMA] * math.sqrt(p[P_MSTAR] * kn) * vel, a


@njit(cache=True)
def hertz_damped(p, delta, vel):
    """Damped Hertz with the total force clamped at N >= 0; the contact ends where N reaches 0."""
    F, a = hertz_damped_unclamped(p, delta, vel)
    if F < 0.0:
        F = 0.0
    return F, a


@njit(cache=True)
def hertz_damped_gap(p, delta, vel):
    """Positive while in contact: the unclamped damped-Hertz force (or delta once delta <= 0)."""
    if delta <= 0.0:
        return delta
    return hertz_damped_unclamped(p, delta, vel)[0]


@njit(cache=True)
def linear(p, delta, vel):
    """Linear spring-dashpot: N = k_n delta + 2 gamma sqrt(m* k_n) d(delta)/dt (no clamp: the contact ends
    at delta = 0, so e_n = exp(-gamma pi / sqrt(1 - gamma^2)) in closed form; the force may be tensile
    just before separation). a = sqrt(R* delta) is the geometric contact radius."""
    if delta <= 0.0:
        return 0.0, 0.0
    kn = p[P_KN]
    return kn * delta + 2.0 * p[P_GAMMA] * math.sqrt(p[P_MSTAR] * kn) * vel, math.sqrt(p[P_RSTAR] * delta)
