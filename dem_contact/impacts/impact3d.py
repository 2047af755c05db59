"""One impact in 3D: a sphere hitting a wall (or another sphere) with any tangential velocity in the
tangent plane and any spin vector.

Frame (right-handed): z is the contact normal, from the sphere (body 1) into the wall or the other sphere
(body 2), i.e. the direction of approach, so V_z = vn > 0 before impact; x and y span the tangent plane.
Spin vectors are given in the same axes. With this frame the planar quantities of Wu, Thornton & Li (2009)
are the x velocity and the y spin: the planar ``impact(scene, vn, vt, spin)`` is
``impact3d(scene, vn, (vt, 0), (0, spin, 0))``.

Motion, relative to the contact (as in ``integrator.integrate_impact``; the normal stays fixed, the
impact-plane approximation of the planar integrator): the overlap with rate vn and the relative velocity
of the centres V = (Vx, Vy) with the effective mass m*, the spin vectors w1, w2 of the bodies with their
moments of inertia. Contact point r1 = R1 n from centre 1, r2 = -R2 n from centre 2, so the slip velocity
of body 1 relative to body 2 at the contact is

    s = V + (R1 w1 + R2 w2) x n,

the tangential force F_t on body 1 changes m* dV/dt = F_t and I_i dw_i/dt = R_i n x F_t; the normal force
never exerts a torque. The contact force comes from the 3D per-contact kernel ``dem.contact3d`` (one call
per step, in ``_contact``), driven with the half-step slip velocity, the normal velocity predicted at the
end of the step (for dashpots, as the planar integrator does) and the mean spin of the two bodies about the
normal (the rotation of the contact frame).

Time stepping is the planar integrator's, step for step: velocity Verlet with the contact starting at
delta = 0 with the incident state and the separation located inside the last step (``scheme="located"``)
or the standard DEM end (``"standard"``). With no out-of-plane spin (w1 = w2 = (0, w, 0), V = (vt, 0)) it
performs the planar integrator's arithmetic and reproduces ``impact`` to rounding error.

For a sphere on a flat wall (and two spheres on a fixed line of centres) the slip velocity obeys
ds/dt = (1/m* + R1^2/I1 + R2^2/I2) F_t, the same factor in every tangential direction; a law that, for a
straight displacement path, gives a force along the path therefore keeps a straight slip path: an
out-of-plane spin does not turn the slip during the impact, and the impact is the planar impact along the
incident slip direction (only a rotation of the contact frame, the mean spin about the normal, can turn it).

In-plane quantities (``Impact3DResult``) are those of the impact plane, spanned by the normal and the
incident tangential velocity of the centre (the x axis when that is zero): e_t, f, Theta, Psi_r and
Omega of Wu, Thornton & Li (2009, eqs 2.1-2.20 and 7.1), from the components along that plane;
the components across it are reported beside them (``*_across``).
"""
from __future__ import annotations

import math
import warnings

import numpy as np
from numba import njit

from ..dem.contact3d import contact_force_torque, history_size, new_histories
from ..errors import InputError, NumericalError, kernel_failed
from ..laws.model import Scene
from ..laws.normal_impact import drift, eval_overlap, normal_close, normal_start, step_status
from ..laws.slots import P_MU
from ..materials import Wall, check_finite
from .impact import (ENERGY_CREATION_TOL, KE_ROUNDING_TOL, MAX_CONTACT_TIMES, SCHEMES, EnergyBudget,
                     ImpactResult, _raise_failed, body_inertia, check_law_grid, check_scales, impact_warnings, raise_if_no_impulse,
                     raise_if_restitution_impossible, scene_constants, time_step, with_outcome)
from .integrator import SLIDE_TOL, STATUS_MAX_STEPS, STATUS_OK, put

# slots of the output row of integrate_impact3d, in the order of the values it writes
Q_VX, Q_VY, Q_VN = 0, 1, 2            # final relative velocity of the centres (V_n: + towards body 2) [m/s]
Q_W1 = 3                              # final spin of body 1, 3 slots [rad/s]
Q_W2 = 6                              # final spin of body 2, 3 slots [rad/s]
Q_PN = 9                              # normal impulse [N s]
Q_PX, Q_PY = 10, 11                   # impulse of the tangential force on body 1 [N s]
Q_TC = 12                             # contact time [s]
Q_DMAX = 13                           # maximum overlap [m]
Q_FMAX = 14                           # maximum normal force [N]
Q_SLID = 15                           # 1 if |F_t| = mu N at every step
Q_STEPS = 16                          # number of steps
Q_WN = 17                             # work absorbed by the normal force [J]
Q_WT = 18                             # work absorbed by the tangential force, integral -F_t . ds [J]
Q_COULOMB = 19                        # max over steps of |F_t| - mu N [N]
Q_STATUS = 20                         # integrator.STATUS_*
Q_MINWT = 21                          # minimum over time of the running tangential work [J]
N_OUT3 = 22

# columns of the optional time series
SERIES3 = ("t", "overlap", "normal_force", "tangential_force_x", "tangential_force_y", "vn", "slip_x",
           "slip_y", "spin_z")
N_SERIES3 = len(SERIES3)


# --- the 3D per-contact kernel: every call of dem.contact3d is here -----------------------------------

def new_contact_state(scene: Scene):
    """(params, H): the scene's parameter row as a one-row table and the zeroed 3D history of the one
    contact of an impact, as the 3D kernel takes them."""
    params = np.ascontiguousarray(scene.params[None, :])
    H = new_histories(1, history_size(scene.normal_id, scene.tangential_id, scene.mdr_springs, scene.twist_id,
                                      scene.rolling_id))
    return params, H


@njit(cache=True)
def _normal_history(H):
    """The history row that the normal law reads (separation test and its location): the header of the 3D
    row has the planar row's normal slots."""
    return H[0]


@njit(cache=True)
def _contact(nid, tid, params, H, delta, sx, sy, vn, wx, wy, wz, wn, dt):
    """Force of the 3D kernel on body 1 for the normal n = +z: (N, Ftx, Fty, Qx, Qy, Qz), advancing the
    history; Q the torque on body 1 of the twist and rolling laws (body 2 takes -Q).

    (sx, sy): slip velocity over the step [m/s]; vn: overlap rate [m/s]; (wx, wy, wz): relative spin
    w1 - w2 [rad/s]; wn: rotation rate of the contact frame about the normal [rad/s]."""
    fx, fy, fz, tx, ty, tz, qx, qy, qz = contact_force_torque(nid, tid, params, 0, H, 0, 0.0, 0.0, 1.0, delta, sx,
                                                              sy, vn, wx, wy, wz, wn, dt)
    return -fz, tx, ty, qx, qy, qz


# -------------------------------------------------------------------------------------------------------

@njit(inline="always", cache=True)
def _half_kick_torque(w1x, w1y, w1z, w2x, w2y, w2z, Qx, Qy, Qz, hdt, inv_I1, inv_I2):
    """Half a step of the torque Q of the twist and rolling laws on the two spins: I1 dw1 = Q dt,
    I2 dw2 = -Q dt."""
    h = 0.5 * hdt
    return (w1x + h * Qx * inv_I1, w1y + h * Qy * inv_I1, w1z + h * Qz * inv_I1,
            w2x - h * Qx * inv_I2, w2y - h * Qy * inv_I2, w2z - h * Qz * inv_I2)


@njit(inline="always", cache=True)
def _half_kick(vx, vy, w1x, w1y, w2x, w2y, Fx, Fy, hdt, inv_m, R1, R2, inv_I1, inv_I2):
    """Half a step of the tangential force (Fx, Fy) on the relative velocity and the two spins:
    m* dV = F_t dt, I dw = R n x F_t dt with n x F = (-Fy, Fx, 0)."""
    return (vx + 0.5 * hdt * Fx * inv_m, vy + 0.5 * hdt * Fy * inv_m,
            w1x - 0.5 * hdt * R1 * Fy * inv_I1, w1y + 0.5 * hdt * R1 * Fx * inv_I1,
            w2x - 0.5 * hdt * R2 * Fy * inv_I2, w2y + 0.5 * hdt * R2 * Fx * inv_I2)


@njit(cache=True)
def integrate_impact3d(nid, tid, params, H, vn0, vx0, vy0, w10, w20, inv_m, R1, R2, inv_I1, inv_I2,
                       dt, max_steps, locate, frame_spin, out, series):
    """Integrate one 3D impact from first touch (delta = 0) to separation.

    params, H: one-row parameter table and zeroed history (``new_contact_state``); vn0 > 0: incident
    normal approach speed [m/s]; vx0, vy0: incident tangential velocity of the centres [m/s]; w10, w20:
    float64[3] incident spins [rad/s]; inv_m = 1/m*; R1, R2 [m]; inv_I1, inv_I2; dt [s]; max_steps;
    locate: located separation (True) or the standard DEM end; frame_spin: pass the mean spin about the
    normal to the kernel as the rotation of the contact frame (True) or 0 (False);
    out: float64[N_OUT3]; series: float64[n, N_SERIES3] (first n steps recorded)."""
    p = params[0]
    mu = p[P_MU]
    hn = _normal_history(H)
    vx = vx0
    vy = vy0
    w1x, w1y, w1z = w10[0], w10[1], w10[2]
    w2x, w2y, w2z = w20[0], w20[1], w20[2]
    Fx = 0.0
    Fy = 0.0
    Qx = 0.0
    Qy = 0.0
    Qz = 0.0
    PX = 0.0
    PY = 0.0
    WT = 0.0
    minWT = 0.0
    slid = 1.0
    coulomb = -np.inf
    delta, vn, N, t, PN, WN, dmax, fmax, steps, status = normal_start(nid, p, hn, vn0)
    nser = series.shape[0]
    for k in range(max_steps):
        hdt, kick, vn_h, delta_new, ended = drift(nid, p, hn, delta, vn, N, inv_m, dt, locate)
        # half kick of the tangential force
        vx_h, vy_h, w1x_h, w1y_h, w2x_h, w2y_h = _half_kick(vx, vy, w1x, w1y, w2x, w2y, Fx, Fy, hdt, inv_m, R1, R2,
                                                            inv_I1, inv_I2)
        # and of the torque of the twist and rolling laws
        w1x_h, w1y_h, w1z_h, w2x_h, w2y_h, w2z_h = _half_kick_torque(w1x_h, w1y_h, w1z, w2x_h, w2y_h, w2z, Qx, Qy,
                                                                       Qz, hdt, inv_I1, inv_I2)
        # slip s = V + (R1 w1 + R2 w2) x n, with w x n = (wy, -wx, 0)
        sx = vx_h + R1 * w1y_h + R2 * w2y_h
        sy = vy_h - R1 * w1x_h - R2 * w2x_h
        ddx = sx * hdt
        ddy = sy * hdt
        wn = 0.5 * (w1z_h + w2z_h) if frame_spin else 0.0
        rx = w1x_h - w2x_h
        ry = w1y_h - w2y_h
        rz = w1z_h - w2z_h
        if ended and not locate:
            Nn = 0.0
            Fxn = 0.0
            Fyn = 0.0
            Qxn = 0.0
            Qyn = 0.0
            Qzn = 0.0
        else:
            Nn, Fxn, Fyn, Qxn, Qyn, Qzn = _contact(nid, tid, params, H, eval_overlap(delta_new, ended), sx, sy,
                                                   vn_h - kick, rx, ry, rz, wn, hdt)
        PX += 0.5 * hdt * (Fx + Fxn)
        PY += 0.5 * hdt * (Fy + Fyn)
        # the work of the tangential force and of the torque (on the relative spin)
        WT -= 0.5 * ((Fx + Fxn) * ddx + (Fy + Fyn) * ddy + ((Qx + Qxn) * rx + (Qy + Qyn) * ry + (Qz + Qzn) * rz) * hdt)
        if WT < minWT:
            minWT = WT
        vx, vy, w1x, w1y, w2x, w2y = _half_kick(vx_h, vy_h, w1x_h, w1y_h, w2x_h, w2y_h, Fxn, Fyn, hdt, inv_m, R1, R2,
                                                inv_I1, inv_I2)
        w1x, w1y, w1z, w2x, w2y, w2z = _half_kick_torque(w1x, w1y, w1z_h, w2x, w2y, w2z_h, Qxn, Qyn, Qzn, hdt, inv_I1,
                                                         inv_I2)
        Fx = Fxn
        Fy = Fyn
        Qx = Qxn
        Qy = Qyn
        Qz = Qzn
        delta, vn, N, t, PN, WN, dmax, fmax, steps = normal_close(N, Nn, hdt, delta, delta_new, vn_h, inv_m, t, PN,
                                                                  WN, dmax, fmax, steps)
        Np = N if N > 0.0 else 0.0
        Ft = math.sqrt(Fx * Fx + Fy * Fy)
        if Ft < mu * Np * (1.0 - SLIDE_TOL):
            slid = 0.0
        if Ft - mu * Np > coulomb:
            coulomb = Ft - mu * Np
        if k < nser:        # columns SERIES3
            put(series[k], 0, (t, delta, N, Fx, Fy, vn, vx + R1 * w1y + R2 * w2y, vy - R1 * w1x - R2 * w2x, w1z))
        status = step_status(math.isfinite(vn) and math.isfinite(vx) and math.isfinite(vy) and math.isfinite(w1x)
                             and math.isfinite(w1y) and math.isfinite(delta) and math.isfinite(Ft)
                             and math.isfinite(N), ended)
        if status != STATUS_MAX_STEPS:
            break
    put(out, Q_VX, (vx, vy, vn, w1x, w1y, w1z, w2x, w2y, w2z, PN, PX, PY, t, dmax, fmax, slid, float(steps), WN, WT,
                    coulomb, float(status), minWT))


@with_outcome
class Impact3DResult:
    """Outcome of one 3D impact (frame and conventions: module docstring). Vectors are lists in the
    frame's axes: tangential ones (x, y), spins (x, y, z). Velocities in m/s, spins in rad/s.

    vt_r: rebound tangential velocity of the centre (relative to body 2); spin_r, spin2_r: rebound spins;
    tangential_impulse: impulse of the tangential force on body 1 [N s].
    Impact plane: ``plane_axis`` (unit vector e1 along the incident tangential velocity, or x), e2 = n x e1.
    In-plane (Wu et al. 2009): e_n = -V_nr/V_ni; e_t = (V_tr.e1)/(V_ti.e1) (NaN when V_ti = 0);
    f = -P_t.e1/P_n; Theta = 2 (s_i.e1)/((1 + e_n) mu V_ni) with the incident slip s_i (eq. 7.1);
    Psi_r the same of the rebound slip; Omega = 2 R1 (w1.e2)/(5 (1 + e_n) mu V_ni).
    Across the plane: f_across = -P_t.e2/P_n, Theta_across and Psi_r_across from s.e2, Omega_across from
    -w1.e1 (the spin whose contact-point velocity lies along e2), so the momentum identities of
    eqs 2.21-2.23 hold in both directions. slip_angle_i_deg, slip_angle_r_deg: direction of the incident
    and rebound slip in the tangent plane, from e1 towards e2; rebound_angle_deg: angle of the rebound
    centre velocity from the normal in the impact plane; out_of_plane_angle_deg: angle of the rebound
    centre velocity out of the impact plane.

    Checks as ``ImpactResult``: energy_created, energy_gained and the warnings (|f| > mu with the whole
    tangential impulse, energy balance, range of validity, calibration, coarse steps); an e_n outside
    [0, 1 + E_N_EXCESS_TOL] raises NumericalError.
    """

    vn_i: float
    vt_i: list
    spin_i: list
    spin2_i: list
    vn_r: float
    vt_r: list
    spin_r: list
    spin2_r: list
    plane_axis: list
    e_n: float
    e_t: float
    f: float
    f_over_mu: float
    f_across_over_mu: float
    Theta: float
    Theta_across: float
    Psi_r: float
    Psi_r_across: float
    Omega_i: float
    Omega_r: float
    Omega_across_i: float
    Omega_across_r: float
    slip_angle_i_deg: float
    slip_angle_r_deg: float
    rebound_angle_deg: float
    out_of_plane_angle_deg: float
    normal_impulse: float
    tangential_impulse: list
    contact_time: float
    max_overlap: float
    max_force: float
    persistent_sliding: bool
    # then the OUTCOME_FIELDS of ImpactResult (steps ... energy_gained)

    to_dict = ImpactResult.to_dict


def _vector(name: str, what: str, value, n: int) -> np.ndarray:
    """A finite float vector of n components, or InputError naming the parameter."""
    try:
        v = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} ({what}) must be a sequence of {n} numbers") from None
    if v.shape != (n,):
        raise InputError(f"{name} ({what}) must have {n} components, got shape {v.shape}")
    for i, x in enumerate(v):
        check_finite(f"{name}[{i}] ({what})", float(x))
    return v


def impact3d(scene: Scene, vn: float, vt=(0.0, 0.0), spin=(0.0, 0.0, 0.0), *, spin2=(0.0, 0.0, 0.0),
             steps_per_contact: float | None = None, dt: float | None = None, scheme: str = "located",
             frame_spin: bool = True, series: bool = False) -> Impact3DResult:
    """Simulate one 3D impact of the scene's sphere (frame: module docstring).

    vn: normal speed towards the wall or the other sphere, > 0 [m/s]; vt: (Vx, Vy) tangential velocity of
    the centre relative to body 2 [m/s]; spin: (wx, wy, wz) of the sphere [rad/s]; spin2: of body 2
    (sphere-sphere only). Time step and scheme as ``impact``. frame_spin: turn the tangential history
    about the normal with the mean spin of the two bodies about it (the kernel's objective frame; False
    keeps it fixed, as LAMMPS does). series: also return time histories (columns ``SERIES3``).
    """
    if not isinstance(scene, Scene):
        raise InputError("scene must be a Scene")
    vn = check_finite("vn (normal impact speed towards the wall, m/s)", vn, lo=0.0)
    vt = _vector("vt", "tangential velocity (Vx, Vy) of the centre, m/s", vt, 2)
    w1 = _vector("spin", "angular velocity (wx, wy, wz) of the sphere, rad/s", spin, 3)
    w2 = _vector("spin2", "angular velocity (wx, wy, wz) of body 2, rad/s", spin2, 3)
    if isinstance(scene.body2, Wall) and np.any(w2 != 0.0):
        raise InputError("spin2 applies to sphere-sphere impacts only (body 2 is a wall)")
    if scheme not in SCHEMES:
        raise InputError(f"scheme {scheme!r} is unknown; choose one of: {', '.join(SCHEMES)}")
    check_scales(scene, vn, math.hypot(*vt), math.hypot(*w1), math.hypot(*w2))
    dt, spc = time_step(scene, vn, steps_per_contact, dt)
    inv_m, R1, R2, inv_I1, inv_I2 = body_inertia(scene)
    max_steps = int(math.ceil(MAX_CONTACT_TIMES * spc)) + 10
    out = np.zeros(N_OUT3)
    ser = np.zeros((max_steps if series else 0, N_SERIES3))
    params, H = new_contact_state(scene)
    try:
        integrate_impact3d(scene.normal_id, scene.tangential_id, params, H, vn, vt[0], vt[1], w1, w2,
                           inv_m, R1, R2, inv_I1, inv_I2, dt, max_steps, scheme == "located", bool(frame_spin),
                           out, ser)
    except Exception as e:      # a failure inside the compiled code: no result
        raise kernel_failed(e, f"the {scene.normal}/{scene.tangential} kernels at vn = {vn:g} m/s") from None
    check_law_grid(scene, H[0], vn)
    return build_result3d(scene, out, vn, vt, w1, w2, dt, spc, scheme, frame_spin, ser)


def _angle_deg(y: float, x: float) -> float:
    return math.degrees(math.atan2(y, x)) if (x != 0.0 or y != 0.0) else 0.0


def build_result3d(scene, out, vn, vt, w1, w2, dt, spc, scheme, frame_spin, ser=None) -> Impact3DResult:
    """Turn the output row of ``integrate_impact3d`` into an Impact3DResult (NumericalError on failure)."""
    status = int(out[Q_STATUS])
    if status != STATUS_OK:
        _raise_failed(scene, status, out[Q_STEPS], vn, dt)
    inv_m, R1, R2, inv_I1, inv_I2 = body_inertia(scene)
    m = 1.0 / inv_m
    mu = scene.mu
    vt = np.asarray(vt, dtype=float)
    vt_r = np.array([out[Q_VX], out[Q_VY]])
    w1_r = out[Q_W1:Q_W1 + 3].copy()
    w2_r = out[Q_W2:Q_W2 + 3].copy()
    vn_r = out[Q_VN]
    PN = out[Q_PN]
    P = np.array([out[Q_PX], out[Q_PY]])
    speed_t = math.hypot(vt[0], vt[1])
    e1 = vt / speed_t if speed_t > 0.0 else np.array([1.0, 0.0])
    e2 = np.array([-e1[1], e1[0]])

    def slip(V, wa, wb):        # V + (R1 wa + R2 wb) x n, with w x n = (wy, -wx)
        return np.array([V[0] + R1 * wa[1] + R2 * wb[1], V[1] - R1 * wa[0] - R2 * wb[0]])

    s_i = slip(vt, w1, w2)
    s_r = slip(vt_r, w1_r, w2_r)
    e_n = -vn_r / vn
    nan = math.nan
    if not all(math.isfinite(x) for x in (vn_r, PN, out[Q_TC], *P, *vt_r, *w1_r, *w2_r)):
        raise NumericalError(f"non-finite result (velocity, spin or impulse) with the {scene.normal}/"
                             f"{scene.tangential} laws at dt = {dt:g} s")
    raise_if_no_impulse(scene, PN, out[Q_TC], vn, dt, spc)
    raise_if_restitution_impossible(scene, e_n, vn, dt, spc)
    f = -float(P @ e1) / PN if PN > 0 else nan
    f_across = -float(P @ e2) / PN if PN > 0 else nan
    vt_i1 = float(vt @ e1)
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = (1.0 + e_n) * mu * vn
        pos = mu > 0
        groups = dict(
            f_over_mu=f / mu if pos else nan, f_across_over_mu=f_across / mu if pos else nan,
            Theta=2.0 * float(s_i @ e1) / denom if pos else nan,
            Theta_across=2.0 * float(s_i @ e2) / denom if pos else nan,
            Psi_r=2.0 * float(s_r @ e1) / denom if pos else nan,
            Psi_r_across=2.0 * float(s_r @ e2) / denom if pos else nan,
            Omega_i=2.0 * R1 * float(w1[:2] @ e2) / (5.0 * denom) if pos else nan,
            Omega_r=2.0 * R1 * float(w1_r[:2] @ e2) / (5.0 * denom) if pos else nan,
            Omega_across_i=-2.0 * R1 * float(w1[:2] @ e1) / (5.0 * denom) if pos else nan,
            Omega_across_r=-2.0 * R1 * float(w1_r[:2] @ e1) / (5.0 * denom) if pos else nan)
    e_t = float(vt_r @ e1) / vt_i1 if vt_i1 != 0 else nan
    I1 = 0.0 if inv_I1 == 0 else 1.0 / inv_I1
    I2 = 0.0 if inv_I2 == 0 else 1.0 / inv_I2
    E0 = 0.5 * m * (vn * vn + float(vt @ vt)) + 0.5 * I1 * float(w1 @ w1) + 0.5 * I2 * float(w2 @ w2)
    E1 = 0.5 * m * (vn_r ** 2 + float(vt_r @ vt_r)) + 0.5 * I1 * float(w1_r @ w1_r) + 0.5 * I2 * float(w2_r @ w2_r)
    WN, WT = out[Q_WN], out[Q_WT]
    energy = EnergyBudget(initial=E0, final=E1, friction=WT, normal=WN, error=E0 - E1 - WT - WN)
    if not all(math.isfinite(x) for x in (E0, E1, WT, WN, PN)):
        raise NumericalError(f"non-finite result (energy or impulse) with the {scene.normal}/{scene.tangential} "
                             f"laws at dt = {dt:g} s")
    # the checks of the planar impact (impact.build_result), with the impulse ratio of the whole tangential impulse
    created = bool(out[Q_MINWT] < -ENERGY_CREATION_TOL * E0)
    gained_total = bool(E1 - E0 > KE_ROUNDING_TOL * E0)
    gained_normal = bool(e_n * e_n - 1.0 > KE_ROUNDING_TOL)
    coul = out[Q_COULOMB]
    msgs = impact_warnings(scene_constants(scene), scene, e_n=e_n, f_abs=math.hypot(*P) / PN, energy=energy,
                           minwt=out[Q_MINWT], coul=coul, fmax=out[Q_FMAX], dmax=out[Q_DMAX], spc=spc, vn=vn,
                           created=created, gained_total=gained_total, gained_normal=gained_normal)
    for msg in msgs:
        warnings.warn(msg, RuntimeWarning, stacklevel=3)
    series_dict = None
    if ser is not None and ser.shape[0] > 0:
        n = int(out[Q_STEPS])
        first = {"vn": vn, "slip_x": s_i[0], "slip_y": s_i[1], "spin_z": w1[2]}
        series_dict = {name: np.concatenate([[first.get(name, 0.0)], ser[:n, j]])
                       for j, name in enumerate(SERIES3)}
    return Impact3DResult(
        vn_i=vn, vt_i=vt.tolist(), spin_i=np.asarray(w1).tolist(), spin2_i=np.asarray(w2).tolist(),
        vn_r=vn_r, vt_r=vt_r.tolist(), spin_r=w1_r.tolist(), spin2_r=w2_r.tolist(), plane_axis=e1.tolist(),
        e_n=e_n, e_t=e_t, f=f, **groups,
        slip_angle_i_deg=_angle_deg(float(s_i @ e2), float(s_i @ e1)),
        slip_angle_r_deg=_angle_deg(float(s_r @ e2), float(s_r @ e1)),
        rebound_angle_deg=math.degrees(math.atan2(float(vt_r @ e1), -vn_r)),
        out_of_plane_angle_deg=math.degrees(math.atan2(float(vt_r @ e2), math.hypot(float(vt_r @ e1), vn_r))),
        normal_impulse=PN, tangential_impulse=P.tolist(), contact_time=out[Q_TC], max_overlap=out[Q_DMAX],
        max_force=out[Q_FMAX], persistent_sliding=bool(out[Q_SLID] > 0.5), steps=int(out[Q_STEPS]), dt=dt,
        energy=energy, energy_created=created, coulomb_violation=max(coul, 0.0), warnings=msgs,
        model=scene.describe(),
        settings={"scheme": scheme, "dt": dt, "steps_per_contact": spc, "frame_spin": bool(frame_spin),
                  "frame": "z: normal into body 2 (approach direction); x, y: tangent plane"},
        series=series_dict, energy_gained=gained_total or gained_normal)


def sweep3d(scene: Scene, angles_deg, vn: float = 5.0, spin=(0.0, 0.0, 0.0), *, direction_deg: float = 0.0,
            spin2=(0.0, 0.0, 0.0), steps_per_contact: float | None = None, scheme: str = "located",
            frame_spin: bool = True) -> list:
    """3D impacts at fixed normal speed vn [m/s] over impact angles [deg] (Wu et al.'s protocol), each with
    the same spin vector [rad/s]: the incident tangential velocity vn tan(angle) points along
    ``direction_deg`` in the tangent plane (from x towards y). Returns one Impact3DResult per angle."""
    a = np.atleast_1d(np.asarray(angles_deg, dtype=float))
    if a.ndim != 1 or a.size == 0:
        raise InputError("angles_deg must be a non-empty list of angles [deg]")
    phi = math.radians(check_finite("direction_deg (direction of the tangential velocity, deg)", direction_deg))
    out = []
    for x in a:
        check_finite("impact angle (deg)", x, lo=-90.0, hi=90.0, lo_open=True, hi_open=True)
        v = vn * math.tan(math.radians(x))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")     # recorded per impact in Impact3DResult.warnings
            out.append(impact3d(scene, vn, (v * math.cos(phi), v * math.sin(phi)), spin, spin2=spin2,
                                steps_per_contact=steps_per_contact, scheme=scheme, frame_spin=frame_spin))
    return out
