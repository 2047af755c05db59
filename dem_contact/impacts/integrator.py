"""Impact integrator: one contact between body 1 and body 2 (a wall or a sphere) in the impact plane.

Three kinds of motion, relative to the contact: the normal approach (overlap delta, rate vn, effective
mass m*), the tangential motion of the centres (vt, mass m*) and the spins w1, w2 of the bodies. The
contact-patch slip velocity is v_t = vt + R1 w1 + R2 w2 (Wu, Thornton & Li 2009, section 2: rolling without slip has
v_t = 0). The tangential force T acts against v_t:
    m* dvn/dt = -N,  m* dvt/dt = -T,  I_i dw_i/dt = -R_i T.
For a wall, R2 = 0 and 1/I2 = 0.

Velocity Verlet (kick-drift-kick) with constant dt. The contact starts exactly at delta = 0 with the
incident state. Two ways to end it:

- located separation (``locate=True``): in the step where the contact ends, the step length is cut to
  the root of the law's gap function (regula falsi, Illinois variant), so e_n, the impulses and the
  contact time carry no error of order dt from the last step;
- standard DEM scheme (``locate=False``, as LIGGGHTS and LAMMPS): the contact ends at the first full
  step with no overlap, where the force is zero.

Impulses are accumulated from the very kicks that change the velocities, so the momentum identities
(2.21)-(2.23) hold to rounding error.
"""
import math

import numpy as np
from numba import njit
from numba.core import cgutils, types
from numba.extending import intrinsic

from ..errors import InputError
from ..laws.contact import contact_step
from ..laws.normal_impact import (STATUS_MAX_STEPS, STATUS_NONFINITE, STATUS_OK, drift, eval_overlap,  # noqa: F401
                                  normal_close, normal_start, step_status)
from ..laws.slots import P_MU, P_NORMAL_LAW
from ..laws.dispatch import NORMAL_IDS, TANGENTIAL_IDS

# slots of the output row, in the order of the values that ``integrate_inlined`` writes
O_VN = 0        # final normal approach velocity, V_nr (negative: moving away) [m/s]
O_VT = 1        # final tangential velocity of the centre of body 1 relative to body 2 [m/s]
O_W1 = 2        # final spin of body 1 [rad/s]
O_W2 = 3        # final spin of body 2 [rad/s]
O_PN = 4        # normal impulse [N s]
O_PT = 5        # tangential impulse (against v_t) [N s]
O_TC = 6        # contact time [s]
O_DMAX = 7      # maximum overlap [m]
O_FMAX = 8      # maximum normal force [N]
O_SLID = 9      # fraction of the normal impulse delivered before the first step with |T| < (1 - SLIDE_TOL) mu N (1 if none)
O_STEPS = 10    # number of steps
O_WN = 11       # work absorbed by the normal force, integral N d(delta) (trapezoid) [J]
O_WT = 12       # work absorbed by the tangential force, integral T d(delta_t) (trapezoid) [J]
O_COULOMB = 13  # max over steps of |T| - mu N [N] (<= 0 when Coulomb holds)
O_STATUS = 14   # 0 ended, 1 step limit reached, 2 non-finite state
O_MINWT = 15    # minimum over time of the running tangential work [J]
N_OUT = 16


# columns of the optional time series
S_T, S_DELTA, S_N, S_TANG, S_A, S_VN, S_VSLIP = range(7)
N_SERIES = 7


#: Persistent sliding (the direct criterion of Theta_c): |T| >= (1 - SLIDE_TOL) mu N at every step until
#: the last SLIDE_IMPULSE_TOL of the normal impulse. A contact that sticks anywhere falls below the limit by
#: far more than SLIDE_TOL (by 0.07 to 1 of mu N at 0.5% below Theta_c of eq. 4.1 of Wu et al. 2009), while
#: a sliding contact of the fixed-grid mdr dips by a few 1e-6 where its cells cross the contact edge and by
#: up to 2e-2 in the last steps, where the contact spans only a few springs: that last SLIDE_IMPULSE_TOL of
#: the impulse is a vanishing set (the adaptive MDR and md stay at the limit to rounding). With these values the
#: direct Theta_c of mdr, the adaptive MDR and md lies 0.03% to 0.06% below eq. 4.1 from 50 to 50,000 steps per
#: contact (tests/impacts/test_sweep.py).
SLIDE_TOL = 1e-3
SLIDE_IMPULSE_TOL = 1e-4


def is_sliding(fraction):
    """Persistent sliding from the output slot O_SLID (see SLIDE_TOL and SLIDE_IMPULSE_TOL)."""
    return fraction >= 1.0 - SLIDE_IMPULSE_TOL


@intrinsic
def borrowed(typingctx, arr):
    """The array without its reference count (a null meminfo): passing it to a jitted function then costs
    no atomic increment and decrement. Valid while ``arr`` lives; never store or return it."""
    if not isinstance(arr, types.Array):
        return None

    def codegen(context, builder, signature, args):
        ary = cgutils.create_struct_proxy(arr)(context, builder, value=args[0])
        ary.meminfo = cgutils.get_null_value(ary.meminfo.type)
        ary.parent = cgutils.get_null_value(ary.parent.type)
        return ary._getvalue()

    return arr(arr), codegen


@njit(inline="always", cache=True)
def put(row, at, values):
    """Write the floats ``values`` (a tuple) to slots at, at + 1, ... of ``row`` (an output row, or a row of
    the time series)."""
    for j in range(len(values)):
        row[at + j] = values[j]


@njit(inline="always", cache=True)
def integrate_inlined(nid, tid, p, h, vn0, vt0, w10, w20, inv_m, R1, R2, inv_I1, inv_I2, dt, max_steps, locate, out,
               series):
    """Integrate one impact from first touch (delta = 0) to separation. Inlined into its callers: a caller
    whose law ids are constants (``integrator_for``) compiles those laws only.

    nid, tid: normal and tangential law ids; p: parameter row; h: history row (zeroed by the caller);
    vn0 > 0: incident normal approach speed [m/s]; vt0: incident tangential velocity of the centres
    [m/s]; w10, w20: incident spins [rad/s]; inv_m = 1/m* [1/kg]; R1, R2 [m]; inv_I1, inv_I2 [1/(kg m^2)];
    dt [s]; max_steps; locate: located separation (True) or the standard DEM end (False);
    out: float64[N_OUT] written with the results; series: float64[n, N_SERIES], the first n steps are
    recorded (pass shape (0, N_SERIES) for none).
    """
    p = borrowed(p)     # the laws take these rows at every step: uncounted views cost no atomic operations
    h = borrowed(h)
    mu = p[P_MU]
    vt = vt0
    w1 = w10
    w2 = w20
    T = 0.0
    PT = 0.0
    WT = 0.0
    minWT = 0.0
    pn_stick = -1.0     # normal impulse before the first step below the Coulomb limit (-1: none)
    coulomb = -np.inf
    delta, vn, N, t, PN, WN, dmax, fmax, steps, status = normal_start(nid, p, h, vn0)
    nser = series.shape[0]
    for k in range(max_steps):
        hdt, kick, vn_h, delta_new, ended = drift(nid, p, h, delta, vn, N, inv_m, dt, locate)
        vt_h = vt - 0.5 * hdt * T * inv_m
        w1_h = w1 - 0.5 * hdt * R1 * T * inv_I1
        w2_h = w2 - 0.5 * hdt * R2 * T * inv_I2
        v_slip = vt_h + R1 * w1_h + R2 * w2_h
        dd = v_slip * hdt
        if ended and not locate:
            Nn = 0.0
            a = 0.0
            Tn = 0.0
        else:
            Nn, a, Tn = contact_step(nid, tid, p, h, eval_overlap(delta_new, ended), vn_h - kick, dd)
        PN_before = PN
        PT += 0.5 * hdt * (T + Tn)
        WT += 0.5 * (T + Tn) * dd
        if WT < minWT:
            minWT = WT
        vt = vt_h - 0.5 * hdt * Tn * inv_m
        w1 = w1_h - 0.5 * hdt * R1 * Tn * inv_I1
        w2 = w2_h - 0.5 * hdt * R2 * Tn * inv_I2
        T = Tn
        delta, vn, N, t, PN, WN, dmax, fmax, steps = normal_close(N, Nn, hdt, delta, delta_new, vn_h, inv_m, t, PN,
                                                                  WN, dmax, fmax, steps)
        Np = N if N > 0.0 else 0.0
        if pn_stick < 0.0 and abs(T) < mu * Np * (1.0 - SLIDE_TOL):
            pn_stick = PN_before
        if abs(T) - mu * Np > coulomb:
            coulomb = abs(T) - mu * Np
        if k < nser:        # columns S_T ... S_VSLIP
            put(series[k], 0, (t, delta, N, T, a, vn, vt + R1 * w1 + R2 * w2))
        status = step_status(math.isfinite(vn) and math.isfinite(vt) and math.isfinite(w1) and math.isfinite(delta)
                             and math.isfinite(T) and math.isfinite(N), ended)
        if status != STATUS_MAX_STEPS:
            break
    slid = 1.0 if pn_stick < 0.0 else (pn_stick / PN if PN > 0.0 else 0.0)
    put(out, O_VN, (vn, vt, w1, w2, PN, PT, t, dmax, fmax, slid, float(steps), WN, WT, coulomb, float(status), minWT))


@njit(cache=True)
def integrate_impact(nid, tid, p, h, vn0, vt0, w10, w20, inv_m, R1, R2, inv_I1, inv_I2, dt, max_steps, locate, out,
                     series):
    """``integrate_inlined`` with the law ids chosen at run time (every law is compiled into it)."""
    integrate_inlined(nid, tid, p, h, vn0, vt0, w10, w20, inv_m, R1, R2, inv_I1, inv_I2, dt, max_steps, locate, out, series)


# slots of the body row of ``integrator_for`` (impact.body_row)
B_INV_M = 0         # 1/m* [1/kg]
B_R1 = 1            # radius of body 1 [m]
B_R2 = 2            # radius of body 2 [m] (0: a wall)
B_INV_I1 = 3        # 1/I1 [1/(kg m^2)]
B_INV_I2 = 4        # 1/I2 [1/(kg m^2)] (0: a wall)
N_BODY = 5

#: Signature of the integrator of one law pair (``integrator_for``): (p, h, body, vn0, vt0, w10, w20, dt,
#: max_steps, locate, out, series), as ``integrate_impact`` with the inertia in the body row (slots B_*).
INTEGRATOR = types.void(types.float64[::1], types.float64[::1], types.float64[::1], *[types.float64] * 5,
                        types.int64, types.boolean, types.float64[::1], types.float64[:, ::1])

_INTEGRATORS = {}


def integrator_for(nid: int, tid: int):
    """The integrator of the law pair (nid, tid): ``integrate_impact`` without the law ids (signature
    INTEGRATOR), from a clean history (it zeroes h first), compiled per tangential law (its id a constant, so
    the other tangential laws are never compiled into it; the normal law is that of the parameter row,
    ``P_NORMAL_LAW``, chosen at run time among the normal laws compiled into it: one integrator per tangential
    law rather than per pair, each with its own entry in numba's cache). Callable from Python and, as a
    first-class function, from other kernels (``sweep.sweep_kernel``). The kernel does not check its
    arguments: ``impact.impact`` is the checked entry (its rows record their normal law)."""
    if isinstance(nid, bool) or nid not in NORMAL_IDS or isinstance(tid, bool) or tid not in TANGENTIAL_IDS:
        raise InputError(f"(nid, tid) = ({nid!r}, {tid!r}) are not law ids (laws.model.NORMAL_LAWS, TANGENTIAL_LAWS)")
    integ = _INTEGRATORS.get(int(tid))
    if integ is None:
        integ = _INTEGRATORS[int(tid)] = _integrator(int(tid))
    return integ


def integrator_name(tid: int) -> str:
    """The qualified name under which the integrator of the tangential law tid is compiled and cached. numba
    names a compiled function by its qualified name and a counter of the process that compiles it, and a
    kernel calling a first-class function finds it by that name: two laws under one name, compiled first in
    two processes and loaded from the cache into a third, would run one law's code for both."""
    return f"integrate_tangential{tid}"


def _integrator(tid):
    def integrate(p, h, body, vn0, vt0, w10, w20, dt, max_steps, locate, out, series):
        h[:] = 0.0
        integrate_inlined(int(p[P_NORMAL_LAW]) - 1, tid, p, h, vn0, vt0, w10, w20, body[B_INV_M], body[B_R1],
                          body[B_R2], body[B_INV_I1], body[B_INV_I2], dt, max_steps, locate, out, series)
    integrate.__name__ = integrate.__qualname__ = integrator_name(tid)
    return njit(INTEGRATOR, cache=True)(integrate)
