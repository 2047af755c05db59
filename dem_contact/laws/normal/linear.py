"""Linear spring-dashpot (Cundall & Strack 1979): N = k_n delta + 2 gamma sqrt(m* k_n) d(delta)/dt, no clamp
(the contact ends at delta = 0, so e_n = exp(-gamma pi / sqrt(1 - gamma^2)) in closed form; the force may
be tensile just before separation). k_n is matched to the Hertz contact time at v_ref; a = sqrt(R* delta)
is the geometric contact radius."""
import math

from numba import njit

from ...errors import InputError
from .. import closed_forms as cf
from ..declare import E_N, MSTAR, RSTAR, V_REF, Param
from ..slots import P_GAMMA, P_KN, P_KT, P_MSTAR, P_RSTAR
from ..vector import JIT

NAME, FAMILY = "linear", "normal"
SOURCE = "linear spring-dashpot, stiffness matched to the Hertz contact time at v_ref, closed-form e_n"
#: the stiffnesses of the linear laws of both families (``linear_stiffness``)
KN = Param("k_n", "P_KN", "linear normal stiffness k_n", "N/m")
KT = Param("k_t", "P_KT", "linear tangential stiffness k_t", "N/m")
GAMMA = Param("gamma", "P_GAMMA", "dashpot ratio gamma", "-")
PARAMETERS, STATE = (KN, KT, GAMMA, MSTAR, RSTAR), ()
OPTIONS = (E_N, V_REF)
USES_RATE, PLASTIC = True, False
#: the Scene settings of a typical contact of this law (the contract tests use them)
EXAMPLE = {"e_n": 0.3}


def linear_stiffness(scene, p, what):
    """k_n matched to the Hertz contact time at v_ref, and k_t = kappa k_n (the linear laws of both families)."""
    pr = scene.pair
    v = scene.need_v_ref(what)
    p[P_KN] = pr.m_star * (math.pi / cf.hertz_contact_time(pr.E_star, pr.R_star, pr.m_star, v)) ** 2
    p[P_KT] = pr.kappa * p[P_KN]


def configure(scene, p):
    p[P_GAMMA] = cf.linear_damping_ratio(1.0 if scene.e_n is None else scene.e_n)
    if p[P_GAMMA] >= 1.0:
        raise InputError("e_n = 0 cannot be reached by the linear law: valid range (0, 1]")
    linear_stiffness(scene, p, "the linear normal law")


def calibration_target(scene):
    """The closed-form e_n of the dashpot, at every speed."""
    return 1.0 if scene.e_n is None else scene.e_n, None, f"the {NAME} dashpot's calibration"


def hint(scene, situation):
    if situation == "coarse_step":
        e = 1.0 if scene.e_n is None else scene.e_n
        return (f" (its dashpot, set for e_n = {e:g}, must change the normal velocity by a small fraction per "
                f"step: the lower e_n, the more steps per contact it needs)")
    if situation == "long_contact":
        return "; the linear law's stiffness is matched at v_ref: check v_ref against the impact speed"
    if situation == "impulse_excess":
        return (": the linear law's unclamped dashpot pulls at the end of the contact, so the normal impulse is "
                "smaller than the compressive force the Coulomb limit acts on")
    return ""


def describe(scene, p):
    return dict(e_n_target=1.0 if scene.e_n is None else scene.e_n, gamma=p[P_GAMMA], k_n_linear=p[P_KN],
                k_t_linear=p[P_KT], v_ref=scene.v_ref)


def contact_time(scene, vn):
    """The closed form of the damped linear spring."""
    return cf.linear_contact_time(scene.params[P_KN], scene.pair.m_star, scene.params[P_GAMMA])


@njit(cache=True)
def linear(p, delta, vel):
    if delta <= 0.0:
        return 0.0, 0.0
    kn = p[P_KN]
    return kn * delta + 2.0 * p[P_GAMMA] * math.sqrt(p[P_MSTAR] * kn) * vel, math.sqrt(p[P_RSTAR] * delta)


@njit(inline="always", cache=True)
def planar(p, h, delta, vel):
    return linear(p, delta, vel)


@njit(inline="always", cache=True)
def gap(p, h, delta, vel):
    return delta


@njit(**JIT)
def linear_vector(kn, gamma, m, R, delta, vel):
    """``linear`` on scalars. Returns (N, a)."""
    if delta <= 0.0:
        return 0.0, 0.0
    return kn * delta + 2.0 * gamma * math.sqrt(m * kn) * vel, math.sqrt(R * delta)


@njit(inline="always", **JIT)
def vector(params, row, H, c, delta, vel):
    """The 3D form: (N, a) and no state."""
    N, a = linear_vector(params[row, P_KN], params[row, P_GAMMA], params[row, P_MSTAR], params[row, P_RSTAR],
                         delta, vel)
    return N, a, 0.0, 0.0, 0.0, 0.0, 0.0
