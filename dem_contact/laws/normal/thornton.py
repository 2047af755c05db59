"""Thornton (1997, J. Appl. Mech. 64:383) elastic-perfectly plastic normal law, limiting contact pressure p_y.

Loading to a new maximum delta* (state delta*, F*, R_p, delta_p):
  Hertz while delta <= delta_y; then N = F_y + pi p_y R* (delta - delta_y), a = sqrt(R* delta).
  On every new maximum with N > F_y the unloading curve is stored:
  R_p = 4 E* a*^3 / (3 F*) and delta_p = delta* - (3 F* / (4 E* sqrt(R_p)))^(2/3).
Unloading and elastic reloading below delta*: N = (4/3) E* sqrt(R_p) (delta - delta_p)^(3/2),
  a = sqrt(R_p (delta - delta_p)) (Hertz with R*, delta_p = 0 if the contact never yielded).

Option ``traction_yield``: the limiting pressure falls with the traction the contact carries,
p_y g(|T|/N) (Hamilton 1983 stresses, von Mises; ``laws.traction_yield``), loading by
``_traction_loading``. The planar and the 3D forms read |T| / N of the contact's last step (3D: the
fifth state slot, written by ``store`` after the tangential law).
"""
import math

from numba import njit

from ...errors import InputError
from .. import closed_forms as cf
from ..declare import E_N, ESTAR, RSTAR, V_REF, Option, Param
from ..slots import (H_DP, H_DSTAR, H_FSTAR, H_N, H_RP, H_T, P_DELTA_Y, P_ESTAR, P_F_Y, P_MU, P_PY, P_RSTAR,
                     P_TY_DMU, P_TY_NODES, P_TY_TABLE)
from ..vector import JIT, V_STATE
from .hertz import contact_time  # noqa: F401  (Hertz's elastic contact time sets the step)
from .hertz import hertz_vector

NAME, FAMILY = "thornton", "normal"
SOURCE = "Thornton (1997) elastic-perfectly plastic, limiting contact pressure p_y"
#: the normal law's limiting contact pressure (0: elastic), which the tangential laws may read (``PLASTIC``)
PY = Param("p_y", "P_PY", "limiting contact pressure p_y (0: none)", "Pa")
#: nodes of the first-yield table (``traction_yield``)
TABLE_NODES = 16
PARAMETERS = (ESTAR, RSTAR, PY, Param("delta_y", "P_DELTA_Y", "yield overlap delta_y", "m"),
              Param("F_y", "P_F_Y", "yield force F_y", "N"),
              Param("table nodes", "P_TY_NODES", "nodes of the traction-yield table, 0 = off"),
              Param("table spacing", "P_TY_DMU", "spacing of the traction-yield table in mu_eff = |T|/N", "-"),
              Param("traction-yield table", "P_TY_TABLE", "p0(mu_eff)/p0(0) at mu_eff = 0, P_TY_DMU, ...",
                    size=TABLE_NODES))
#: values of traction_yield that switch it on (True is "proportional")
TRACTION_YIELD = ("proportional", "partial_slip")
#: 3D history slots (the planar row has the first four, and reads |T| / N from its header)
STATE = ("delta_star", "F_star", "R_p", "delta_p", "|T| / N of the last step (traction_yield; -1: N = 0)")


def _traction_yield(value):
    """False, or the name of the traction distribution of the first-yield table (True: "proportional")."""
    if value is False or value is None:
        return False
    if value is True:
        return "proportional"
    if isinstance(value, str) and value in TRACTION_YIELD:
        return value
    raise InputError(f"traction_yield = {value!r} is unknown; choose False, True or one of: "
                     f"{', '.join(TRACTION_YIELD)}")


OPTIONS = (E_N, V_REF, Option(
    "traction_yield", "the limiting pressure falls with the traction |T|/N the contact carries, as the "
    "first-yield pressure of a Hertz contact under that traction (Hamilton 1983); the traction is (|T|/N) p "
    "(proportional, the value without an argument) or the Cattaneo-Mindlin traction of stick radius "
    "c/a = (1 - |T|/(mu N))^(1/3) (partial_slip)", default=False, parse=_traction_yield,
    cli=dict(nargs="?", const="proportional", choices=list(TRACTION_YIELD))))
USES_RATE, PLASTIC = False, True
#: the Scene settings of a typical contact of this law (p_y calibrated for e_n at the scene's v_ref; the
#: contract tests use them)
EXAMPLE = {"e_n": 0.7}


def configure(scene, p):
    """p_y from the yielding material, or calibrated for e_n at v_ref (Thornton 1997 closed form)."""
    pr = scene.pair
    if pr.p_y is not None:
        if scene.e_n is not None:
            raise InputError("the thornton law takes p_y from the material's yield, so e_n cannot act: give "
                             "either a yield of a material or e_n (with v_ref) to calibrate p_y, not both")
        p_y, source = pr.p_y, "material"
    elif scene.e_n is not None:
        e_min = cf.thornton_restitution_ratio(cf.THORNTON_MIN_VELOCITY_RATIO)
        if not e_min <= scene.e_n < 1.0:
            raise InputError(f"e_n = {scene.e_n:g} cannot be calibrated with the thornton law: valid range "
                             f"[{e_min:.3g}, 1)")
        v = scene.need_v_ref("the thornton calibration from e_n")
        p_y = cf.thornton_yield_pressure_for_restitution(pr.E_star, pr.R_star, pr.m_star, scene.e_n, v)
        source = f"calibrated for e_n = {scene.e_n:g} at {v:g} m/s"
    else:
        raise InputError("the thornton law needs a yield: give yield_pressure or yield_stress of a "
                         "material, or e_n (with v_ref) to calibrate p_y")
    # F_y ~ p_y^3 R*^2 / E*^2 must stay an ordinary number
    py_max = (1e100 * 6.0 * pr.E_star**2 / (math.pi**3 * pr.R_star**2)) ** (1.0 / 3.0)
    py_min = (1e-100 * 6.0 * pr.E_star**2 / (math.pi**3 * pr.R_star**2)) ** (1.0 / 3.0)
    if not py_min <= p_y <= py_max:
        raise InputError(f"p_y = {p_y:g} Pa (limiting contact pressure of the thornton law) is outside "
                         f"[{py_min:.3g}, {py_max:.3g}] Pa for this pair, where its yield force is an "
                         f"ordinary number (a p_y that is never reached is the hertz law)")
    scene.p_y = p_y
    scene.p_y_source = source
    p[P_PY] = p_y
    p[P_DELTA_Y] = cf.thornton_yield_overlap(pr.E_star, pr.R_star, p_y)
    p[P_F_Y] = cf.thornton_yield_force(pr.E_star, pr.R_star, p_y)
    if scene.traction_yield:
        _set_traction_yield(scene, p)


def calibration_target(scene):
    """e_n at v_ref where p_y was calibrated for it (it holds at that speed only); None for a material yield."""
    if scene.e_n is None or scene.v_ref is None:
        return None
    return scene.e_n, scene.v_ref, f"the thornton calibration of p_y at {scene.v_ref:g} m/s"


def hint(scene, situation):
    if situation == "long_contact":
        return (f"; a thornton contact with a limiting pressure p_y = {scene.p_y:g} Pa far below the Hertz "
                f"pressure of the impact deforms plastically for much longer than the Hertz contact: check "
                f"p_y, or give a larger dt")
    return ""


def _set_traction_yield(scene, p):
    """Table of p0_first(mu_eff) / p0_first(0) on [0, mu] in the parameter row, for the traction
    distribution ``scene.traction_yield`` (none for mu = 0: the contact then carries no traction and the
    law is Thornton's)."""
    from ..traction_yield import TABLE_NODES, first_yield_ratio_table

    pr = scene.pair
    mats = [b.material for b in (scene.sphere, scene.body2) if not b.material.is_rigid]
    yielding = [m for m in mats if m.p_y is not None and m.p_y == pr.p_y]
    scene.traction_yield_nu = (yielding or mats)[0].nu
    if scene.mu == 0.0:
        return
    nu = min(max(scene.traction_yield_nu, 0.0), 0.5)
    table = first_yield_ratio_table(nu, scene.mu, scene.traction_yield)
    p[P_TY_NODES] = TABLE_NODES
    p[P_TY_DMU] = scene.mu / (TABLE_NODES - 1)
    p[P_TY_TABLE:P_TY_TABLE + TABLE_NODES] = table


def describe(scene, p):
    d = dict(p_y=scene.p_y, p_y_source=scene.p_y_source, delta_y=p[P_DELTA_Y], F_y=p[P_F_Y])
    if scene.traction_yield:
        d.update(traction_yield=scene.traction_yield, traction_yield_nu=scene.traction_yield_nu)
    return d


@njit(cache=True)
def thornton(p, h, delta):
    """Thornton's law (module docstring) on the planar history row: ``thornton_state`` on H_DSTAR, H_FSTAR,
    H_RP, H_DP. With a traction-yield table in the row (P_TY_NODES > 0) loading follows
    ``_traction_loading``."""
    if delta <= 0.0:
        return 0.0, 0.0
    if delta >= h[H_DSTAR] and p[P_TY_NODES] > 0.0:
        return _traction_loading(p, h, delta)
    F, a, h[H_DSTAR], h[H_FSTAR], h[H_RP], h[H_DP] = thornton_state(
        p[P_ESTAR], p[P_RSTAR], p[P_DELTA_Y], p[P_F_Y], p[P_PY], h[H_DSTAR], h[H_FSTAR], h[H_RP], h[H_DP], delta)
    return F, a


@njit(inline="always", cache=True)
def yield_ratio_at(p, N, T):
    """p_y(mu_eff) / p_y of the traction-coupled law: the first-yield pressure of a Hertz contact with
    sliding traction mu_eff p over that without (``traction_yield``), interpolated in the table of the
    parameter row, at mu_eff = |T| / N (at most mu) of the contact's last step."""
    if N <= 0.0:
        return 1.0
    m = min(abs(T) / N, p[P_MU])
    s = m / p[P_TY_DMU]
    last = int(p[P_TY_NODES]) - 1
    i = min(int(s), last - 1)
    t = min(s - i, 1.0)
    return (1.0 - t) * p[P_TY_TABLE + i] + t * p[P_TY_TABLE + i + 1]


@njit(cache=True)
def yield_ratio(p, h):
    """``yield_ratio_at`` for the planar history row (N and T of its last step)."""
    return yield_ratio_at(p, h[H_N], h[H_T])


@njit(inline="always", cache=True)
def traction_loading(E, R, py, dstar, fstar, Rp, dp, delta):
    """Loading branch (delta >= delta*) with the limiting pressure py = p_y g(mu_eff), which changes during
    the contact. Returns (F, a, delta*, F*, R_p, delta_p).

    Before first yield: Hertz while delta <= delta_y(py), then Thornton's law at that pressure,
    F = pi py R* (delta - delta_y / 3) (the Hertz pressure truncated at py). After yield, the increment
    dF = min(pi py R*, 2 E* a_H(F*)) d(delta), a_H(F*) = (3 F* R* / (4 E*))^(1/3): Thornton's plastic
    stiffness at the current limit, never stiffer than a Hertz contact of R* carrying F*. The loading
    curve is then nowhere stiffer, at a given force, than the Hertz unloading curve of (R_p, delta_p), so a
    loading-unloading cycle cannot create energy. With g = 1 throughout it is Thornton's law (to rounding)."""
    F_hertz, a = hertz_vector(E, R, delta)
    if Rp <= 0.0:
        dy = R * (math.pi * py / (2.0 * E)) ** 2
        if delta <= dy:
            F = F_hertz
        else:
            F = math.pi * py * R * (delta - dy / 3.0)
    else:
        k = min(math.pi * py * R, 2.0 * E * (3.0 * fstar * R / (4.0 * E)) ** (1.0 / 3.0))
        F = fstar + k * (delta - dstar)
    if F < F_hertz or Rp > 0.0:
        Rp = 4.0 * E * a * a * a / (3.0 * F)
        dp = delta - (3.0 * F / (4.0 * E * math.sqrt(Rp))) ** (2.0 / 3.0)
    return F, a, delta, F, Rp, dp


@njit(cache=True)
def _traction_loading(p, h, delta):
    """``traction_loading`` on the planar history row."""
    F, a, h[H_DSTAR], h[H_FSTAR], h[H_RP], h[H_DP] = traction_loading(
        p[P_ESTAR], p[P_RSTAR], p[P_PY] * yield_ratio(p, h), h[H_DSTAR], h[H_FSTAR], h[H_RP], h[H_DP], delta)
    return F, a


@njit(inline="always", cache=True)
def planar(p, h, delta, vel):
    return thornton(p, h, delta)


@njit(inline="always", cache=True)
def gap(p, h, delta, vel):
    """Positive while in contact: delta - delta_p (delta_p = 0 before yield)."""
    return delta - h[H_DP]


@njit(inline="always", cache=True)
def thornton_state(E, R, delta_y, F_y, p_y, dstar, fstar, Rp, dp, delta):
    """Thornton's law (module docstring) on its four state values (no traction yield), the planar and the 3D
    kernels alike. Returns (N, a, delta*, F*, R_p, delta_p)."""
    if delta <= 0.0:
        return 0.0, 0.0, dstar, fstar, Rp, dp
    if delta >= dstar:
        if delta <= delta_y:
            F, a = hertz_vector(E, R, delta)
        else:
            a = math.sqrt(R * delta)
            F = F_y + math.pi * p_y * R * (delta - delta_y)
        if F > F_y:
            Rp = 4.0 * E * a * a * a / (3.0 * F)
            dp = delta - (3.0 * F / (4.0 * E * math.sqrt(Rp))) ** (2.0 / 3.0)
        return F, a, delta, F, Rp, dp
    Ru = Rp if Rp > 0.0 else R
    w = delta - dp
    if w <= 0.0:
        return 0.0, 0.0, dstar, fstar, Rp, dp
    F, a = hertz_vector(E, Ru, w)
    return F, a, dstar, fstar, Rp, dp


@njit(**JIT)
def thornton_vector(E, R, delta_y, F_y, p_y, dstar, fstar, Rp, dp, delta):
    """``thornton_state`` compiled with the 3D kernels' options. Returns (N, a, delta*, F*, R_p, delta_p)."""
    return thornton_state(E, R, delta_y, F_y, p_y, dstar, fstar, Rp, dp, delta)


@njit(inline="always", **JIT)
def yield_ratio_vector(params, row, ratio):
    """``yield_ratio_at`` in 3D: ``ratio`` = |T| / N of the last step (-1: N was 0, no coupling)."""
    if ratio < 0.0:
        return 1.0
    m = min(ratio, params[row, P_MU])
    s = m / params[row, P_TY_DMU]
    last = int(params[row, P_TY_NODES]) - 1
    i = min(int(s), last - 1)
    t = min(s - i, 1.0)
    return (1.0 - t) * params[row, P_TY_TABLE + i] + t * params[row, P_TY_TABLE + i + 1]


@njit(inline="always", **JIT)
def vector(params, row, H, c, delta, vel):
    """The 3D form: ``thornton_vector``, or with a traction-yield table the loading of ``traction_loading``
    at the limiting pressure of the last step's |T| / N (s4). Returns (N, a, state); s4 = OFF without a
    table (nothing to store: the parameter row is read here, before the history is written)."""
    E = params[row, P_ESTAR]
    R = params[row, P_RSTAR]
    s0 = H[c, V_STATE]
    s1 = H[c, V_STATE + 1]
    s2 = H[c, V_STATE + 2]
    s3 = H[c, V_STATE + 3]
    if params[row, P_TY_NODES] > 0.0:
        s4 = H[c, V_STATE + 4]
        if delta > 0.0 and delta >= s0:
            F, a, s0, s1, s2, s3 = traction_loading(E, R, params[row, P_PY] * yield_ratio_vector(params, row, s4),
                                                    s0, s1, s2, s3, delta)
            return F, a, s0, s1, s2, s3, s4
    else:
        s4 = OFF
    N, a, s0, s1, s2, s3 = thornton_vector(E, R, params[row, P_DELTA_Y], params[row, P_F_Y], params[row, P_PY],
                                           s0, s1, s2, s3, delta)
    return N, a, s0, s1, s2, s3, s4


#: s4 of a row without a traction-yield table
OFF = -2.0


@njit(inline="always", **JIT)
def store(H, c, s0, s1, s2, s3, s4, N, tx, ty, tz):
    """Write the 3D state after the step: the four values of the law and, with a traction-yield table,
    |T| / N of this step (-1 where N = 0)."""
    H[c, V_STATE] = s0
    H[c, V_STATE + 1] = s1
    H[c, V_STATE + 2] = s2
    H[c, V_STATE + 3] = s3
    if s4 != OFF:
        H[c, V_STATE + 4] = math.sqrt(tx * tx + ty * ty + tz * tz) / N if N > 0.0 else -1.0
