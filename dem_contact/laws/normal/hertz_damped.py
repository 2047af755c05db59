"""Damped Hertz (Tsuji, Tanaka & Ishida 1992 form): Hertz plus the dashpot 2 gamma sqrt(m* k_n) d(delta)/dt,
k_n = 2 E* a, the total force clamped at N >= 0 (the contact ends where N reaches 0). gamma is calibrated
for a target restitution e_n by simulated normal impacts of the unit problem (e_n and the contact time
over Hertz's depend on gamma alone)."""
import functools
import math

import numpy as np
from numba import njit

from ...errors import InputError
from .. import closed_forms as cf
from ..declare import E_N, ESTAR, MSTAR, RSTAR, Param
from ..slots import N_HIST_BASE, N_PARAMS, P_ESTAR, P_GAMMA, P_MSTAR, P_RSTAR
from ..vector import JIT
from .hertz import hertz, hertz_vector

NAME, FAMILY = "hertz_damped", "normal"
SOURCE = "Hertz + dashpot 2 gamma sqrt(m* k_n) d(delta)/dt, force clamped at 0, gamma calibrated for e_n"
#: the dashpot ratio, shared with the linear law
GAMMA = Param("gamma", "P_GAMMA", "dashpot ratio gamma", "-")
PARAMETERS, STATE = (ESTAR, RSTAR, MSTAR, GAMMA), ()
OPTIONS = (E_N,)
USES_RATE, PLASTIC = True, False
#: the Scene settings of a typical contact of this law (the contract tests use them)
EXAMPLE = {"e_n": 0.3}

#: Steps per Hertz contact time used to calibrate the dashpot.
CALIBRATION_STEPS = 4000
#: Hertz contact time of the unit problem E* = R* = m* = V = 1.
UNIT_HERTZ_TC = cf.hertz_contact_time(1.0, 1.0, 1.0, 1.0)
#: e_n = 0 (and any e_n below this) uses the dashpot calibrated for this e_n: a dashpot reaches e_n = 0
#: only in the limit gamma -> inf, so the rebound speed is at most 1e-4 of the impact speed.
EN_FLOOR = 1e-4


def configure(scene, p):
    # e_n = 0 is the gamma -> inf limit of the dashpot (rebound speed ~ gamma^-2, contact time -> 0),
    # reached at no finite gamma: the dashpot of e_n = EN_FLOOR stands for it.
    e_used = 1.0 if scene.e_n is None else max(scene.e_n, EN_FLOOR)
    p[P_GAMMA] = damping_for_restitution(e_used, scene.integrate_normal, scene.normal_id)


def calibration_target(scene):
    """The dashpot's e_n at every speed (that of EN_FLOOR for any e_n below it)."""
    e = 1.0 if scene.e_n is None else scene.e_n
    return max(e, EN_FLOOR), None, f"the {NAME} dashpot's calibration"


def hint(scene, situation):
    if situation == "coarse_step":
        e = 1.0 if scene.e_n is None else scene.e_n
        return (f" (its dashpot, set for e_n = {e:g}, must change the normal velocity by a small fraction per "
                f"step: the lower e_n, the more steps per contact it needs)")
    return ""


def describe(scene, p):
    d = dict(e_n_target=1.0 if scene.e_n is None else scene.e_n, gamma=p[P_GAMMA])
    if scene.e_n is not None and scene.e_n < EN_FLOOR:
        d.update(e_n_dashpot=EN_FLOOR)
    return d


def contact_time(scene, vn):
    """Hertz's contact time times the ratio of the damped law (gamma alone)."""
    pr = scene.pair
    ratio = time_ratio(float(scene.params[P_GAMMA]), scene.integrate_normal, scene.normal_id)
    return cf.hertz_contact_time(pr.E_star, pr.R_star, pr.m_star, vn) * ratio


def _unit_impact(gamma: float, integrate, nid: int):
    """(final normal velocity, contact time, max overlap, status) of a normal impact of the unit problem
    (E* = R* = m* = V = 1) at CALIBRATION_STEPS steps per Hertz contact time, integrated by ``integrate``
    (``Scene.integrate_normal``: the head-on impact of the normal law ``nid``, this law's id)."""
    p = np.zeros(N_PARAMS)
    p[P_ESTAR] = p[P_RSTAR] = p[P_MSTAR] = 1.0
    p[P_GAMMA] = gamma
    return integrate(nid, p, np.zeros(N_HIST_BASE), 1.0, 1.0, UNIT_HERTZ_TC / CALIBRATION_STEPS,
                     100 * CALIBRATION_STEPS)


@functools.lru_cache(maxsize=256)
def damping_for_restitution(e_n: float, integrate, nid: int) -> float:
    """Dashpot ratio gamma that gives restitution ``e_n`` (0 < e_n <= 1), found once by root finding on
    simulated normal impacts of the unit problem (``_unit_impact``)."""
    from scipy.optimize import brentq

    if e_n >= 1.0:
        return 0.0

    def restitution(gamma):
        vn, _, _, status = _unit_impact(gamma, integrate, nid)
        if status != 0:
            raise InputError(f"e_n = {e_n:g} is too low to be reached by the hertz_damped law")
        return -vn

    if restitution(0.0) <= e_n:
        return 0.0      # the undamped law already gives e_n within the calibration's resolution
    hi = 1.0
    while restitution(hi) > e_n:
        hi *= 2.0
        if hi > 1e3:
            raise InputError(f"e_n = {e_n:g} is too low to be reached by the hertz_damped law")
    return brentq(lambda g: restitution(g) - e_n, 0.0, hi, xtol=1e-13, rtol=1e-12)


@functools.lru_cache(maxsize=256)
def time_ratio(gamma: float, integrate, nid: int) -> float:
    """Contact time of the damped law over the elastic Hertz contact time (gamma alone; ``_unit_impact``)."""
    if gamma == 0.0:
        return 1.0
    return min(1.0, _unit_impact(gamma, integrate, nid)[1] / UNIT_HERTZ_TC)


@njit(cache=True)
def unclamped(p, delta, vel):
    """Hertz plus the dashpot before the clamp at zero force. Returns (force, a)."""
    F, a = hertz(p, delta)
    kn = 2.0 * p[P_ESTAR] * a
    return F + 2.0 * p[P_GAMMA] * math.sqrt(p[P_MSTAR] * kn) * vel, a


@njit(cache=True)
def hertz_damped(p, delta, vel):
    """The total force clamped at N >= 0."""
    F, a = unclamped(p, delta, vel)
    if F < 0.0:
        F = 0.0
    return F, a


@njit(inline="always", cache=True)
def planar(p, h, delta, vel):
    return hertz_damped(p, delta, vel)


@njit(cache=True)
def gap(p, h, delta, vel):
    """Positive while in contact: the unclamped force (or delta once delta <= 0)."""
    if delta <= 0.0:
        return delta
    return unclamped(p, delta, vel)[0]


@njit(**JIT)
def hertz_damped_vector(E, R, m, gamma, delta, vel):
    """``hertz_damped`` on scalars. Returns (N, a)."""
    F, a = hertz_vector(E, R, delta)
    kn = 2.0 * E * a
    F = F + 2.0 * gamma * math.sqrt(m * kn) * vel
    if F < 0.0:
        F = 0.0
    return F, a


@njit(inline="always", **JIT)
def vector(params, row, H, c, delta, vel):
    """The 3D form: (N, a) and no state."""
    N, a = hertz_damped_vector(params[row, P_ESTAR], params[row, P_RSTAR], params[row, P_MSTAR],
                               params[row, P_GAMMA], delta, vel)
    return N, a, 0.0, 0.0, 0.0, 0.0, 0.0
