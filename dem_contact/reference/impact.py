"""Oblique impact of an elastic sphere on a wall with the boundary-element tangential contact (``bem``):
the exact reference for impacts, with any initial spin vector, the spin about the normal included
(Horak 1948's spinning sphere dropped on a plane; the twist resisted as in Lubkin 1951 and Deresiewicz
1954, here without their axisymmetric assumption).

The normal motion is Hertz's and, with the normal-tangential coupling dropped (as in the BEM and in MDR),
independent of the tangential one: the overlap delta(t) is integrated once, to 1e-12 relative accuracy
(scipy's DOP853), from first touch to separation, and the contact time t_c found by event location. The
tangential motion (centre velocity, spin, contact-point displacement) is then integrated by velocity
Verlet with ``steps`` equal steps over [0, t_c], the BEM giving the tangential force at every step. The
impulses are the sums of the kicks, so the momentum identities hold to rounding error.

Spin about the normal. Every step also passes the BEM the twist increment dt w_z and kicks w_z with the
moment about the normal: I dw_z/dt = M_z, M_z = ``TangentialBEM.moment()``. Signs: the BEM's twist is the
rotation of the sphere relative to the wall about the normal n = -e_z in a right-handed frame (x', y', n),
and its elements' rigid increments are (du_x' - d beta y', du_y' + d beta x'). Taking x' = x, y' = -y
(so that (x', y', n) is right-handed) and d beta = -w_z dt (a rotation w_z about +e_z is -w_z about n),
the increments in (x, y) are (du_x - w_z dt y, du_y + w_z dt x): the same expressions with the wall-frame
components and d beta = +w_z dt. So the BEM runs in (x, y) with dtwist = w_z dt, and its moment() is then
the moment on the sphere about +e_z (the tractions act in the plane z = 0, at (x, y, -R) from the centre:
their torque has the z component sum (x T_y - y T_x) and the in-plane part R (T_y, -T_x)). The tests check
the physics: the spin decreases, kinetic energy is never created, and at full slip w_z loses Lubkin's
angular impulse (3 pi/16) mu int N a dt / I.

Step tolerance. A sticking twist (w_z t_c far below the no-slip twist at unit moment, Horak's small Psi)
moves the contact edge by ~1e-4 of the slip displacement per step; a step solve stopped at a fraction of
the slip displacement would leave ~10% of every step unresolved, stored as slip. So the impact solves each
step also to ``step_tol`` of the step's own largest rigid increment (``TangentialBEM``), which needs the
convolutions in double precision (single precision rounds at 1e-7 of the displacements, above such a
tolerance): the defaults here are step_tol = tol and ``single=False``.

Accuracy. The error is first order in the step (an element entering the contact takes the whole step's
increment) and, in partial slip, about first order in the element (the contact edge collocated at the
element centres), of opposite signs; in full slip the element error is second order
(``validation/twist/report.md``, Horak's spinning impact: refinement to 800 steps and 128 across, and
extrapolation in both).

Frame: the wall is z = 0, the sphere above it; x along the incident tangential velocity of the centre
(when it has one), y = z cross x. The contact-point velocity of the sphere relative to the wall is
v_c = V + omega x (-R e_z) = (Vx - R omega_y, Vy + R omega_x); the tangential force T at the contact point
gives the torque R (Ty, -Tx, 0). The planar convention of Wu, Thornton & Li (2009) (v_t = V_t + R omega)
has omega = -omega_y.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError, NumericalError
from ..materials import Sphere, Wall, check_finite
from .bem import DEFAULT_TOL, TangentialBEM

#: Default number of BEM elements across the largest contact diameter in an impact.
IMPACT_N_ACROSS = 32
#: Default number of velocity-Verlet steps over the contact time.
IMPACT_STEPS = 200


@dataclass
class BEMImpactResult:
    """Outcome of a BEM impact (SI units). Vectors are (x, y) in the wall plane or (x, y, z) for spins.

    f: impulse ratio P_t/P_n along the incident contact-point velocity (the Coulomb-opposing part);
    f_over_mu; Theta = 2 |v_ci| / ((1 + e_n) mu V_n) (e_n = 1: elastic Hertz); Omega_r = 2 R omega_r /
    (5 (1 + e_n) mu V_n) with the planar omega = -omega_y; P_t the tangential impulse vector on the sphere;
    omega_r: the spin vector after the impact (its z component slowed by the moment about the normal).
    """

    f: float
    f_over_mu: float
    Theta: float
    Omega_r: float
    e_n: float
    e_t: float
    normal_impulse: float
    tangential_impulse: np.ndarray
    v_r: np.ndarray
    omega_r: np.ndarray
    v_cr: np.ndarray
    contact_time: float
    max_overlap: float
    steps: int
    n_across: int
    series: dict = field(default_factory=dict)


def hertz_overlap_history(E_star, R_star, m_star, vn, t):
    """Overlap delta(t) [m] of the elastic Hertz impact at normal speed vn on the times t (within the
    contact), and the contact time, by DOP853 integration of m* delta'' = -(4/3) E* sqrt(R*) delta^(3/2)
    (Johnson 1985, ch. 11) with rtol 1e-12 and event location of the separation."""
    from scipy.integrate import solve_ivp

    k = 4.0 / 3.0 * E_star * math.sqrt(R_star) / m_star
    dmax = (15.0 * m_star * vn * vn / (16.0 * E_star * math.sqrt(R_star))) ** 0.4

    def rhs(_, y):
        return (y[1], -k * max(y[0], 0.0) ** 1.5)

    def separation(_, y):
        return y[0]
    separation.terminal = True
    separation.direction = -1
    tc_est = 2.9433 * dmax / vn
    sol = solve_ivp(rhs, (0.0, 2.0 * tc_est), (0.0, vn), method="DOP853", rtol=1e-12, atol=1e-14 * dmax,
                    events=separation, dense_output=True)
    if sol.status != 1 or len(sol.t_events[0]) == 0:
        raise NumericalError("the Hertz normal impact did not end")
    # the event at t = 0 (delta = 0 on the way in) is excluded by its direction
    tc = float(sol.t_events[0][-1])
    return (None if t is None else np.maximum(sol.sol(t)[0], 0.0)), tc, dmax, float(sol.y_events[0][-1][1])


def bem_impact(scene, vn, vt=0.0, spin=0.0, *, n_across=IMPACT_N_ACROSS, steps=IMPACT_STEPS,
               tol=DEFAULT_TOL, step_tol=DEFAULT_TOL, single=False, series=False, workers=1) -> BEMImpactResult:
    """Impact of the scene's sphere on its wall, Hertz normal contact, BEM tangential contact.

    scene: a ``Scene`` (laws.model) with a Wall as body 2 (its tangential law is not used); vn > 0:
    normal speed towards the wall [m/s]; vt: tangential velocity of the centre, a number (along x) or
    (vx, vy) [m/s]; spin: initial angular velocity, a number (the planar omega of Wu et al., v_t = vt +
    R omega) or (wx, wy, wz) [rad/s] in the frame of the module text. n_across: BEM elements across the
    largest contact diameter; steps: velocity-Verlet steps over the contact time; tol, step_tol, single:
    the step solve's tolerances (fractions of the slip displacement and of the step's rigid increment; None
    drops step_tol) and the convolutions' precision (``TangentialBEM``; module text). series: also return
    the histories t, overlap, normal_force, tangential_force (steps + 1 rows), moment_z [N m] and spin
    (rows wx, wy, wz [rad/s]).
    """
    if not isinstance(scene.body2, Wall) or not isinstance(scene.sphere, Sphere):
        raise InputError("bem_impact simulates a sphere against a wall: scene.body2 must be a Wall")
    if scene.normal != "hertz":
        raise InputError(f"bem_impact needs the hertz normal law, the scene has {scene.normal!r}")
    vn = check_finite("vn (normal speed towards the wall, m/s)", vn, lo=0.0)
    if isinstance(steps, bool) or int(steps) != steps or not 4 <= steps <= 10**6:
        raise InputError(f"steps = {steps!r} must be an integer in [4, 1e6]")
    steps = int(steps)
    V = np.zeros(2)
    W = np.zeros(3)
    if np.ndim(vt) == 0:
        V[0] = check_finite("vt (tangential velocity of the centre, m/s)", vt)
    else:
        if np.shape(vt) != (2,):
            raise InputError("vt must be a number or a pair (vx, vy) [m/s]")
        V[:] = [check_finite(f"vt[{i}] (tangential velocity, m/s)", v) for i, v in enumerate(vt)]
    if np.ndim(spin) == 0:
        W[1] = -check_finite("spin (initial angular velocity, rad/s)", spin)
    else:
        if np.shape(spin) != (3,):
            raise InputError("spin must be a number or a vector (wx, wy, wz) [rad/s]")
        W[:] = [check_finite(f"spin[{i}] (angular velocity, rad/s)", w) for i, w in enumerate(spin)]
    sph = scene.sphere
    R, m, inertia = sph.radius, sph.mass, sph.inertia
    pr = scene.pair
    _, tc, dmax, vn_out = hertz_overlap_history(pr.E_star, pr.R_star, pr.m_star, vn, None)
    t = np.linspace(0.0, tc, steps + 1)
    delta, _, _, _ = hertz_overlap_history(pr.E_star, pr.R_star, pr.m_star, vn, t)
    delta[0] = delta[-1] = 0.0
    m1 = sph.material
    m2 = scene.body2.material
    bem = TangentialBEM(m1.E, m1.nu, m2.E, m2.nu, pr.R_star, scene.mu, math.sqrt(pr.R_star * dmax),
                        n_across=n_across, tol=tol, workers=workers, single=single, step_tol=step_tol)
    dt = tc / steps
    inv_m, inv_I = 1.0 / m, 1.0 / inertia

    def contact_velocity(V, W):
        return np.array([V[0] - R * W[1], V[1] + R * W[0]])

    v_ci = contact_velocity(V, W)
    T = np.zeros(2)
    P = np.zeros(2)
    ser_T = np.zeros((steps + 1, 2))
    ser_N = np.zeros(steps + 1)
    ser_M = np.zeros(steps + 1)
    ser_W = np.zeros((steps + 1, 3))
    ser_W[0] = W
    Mz = 0.0
    for k in range(steps):
        # velocity Verlet: half kick with the force and moment of the current position, drift, force, half kick
        V += 0.5 * dt * inv_m * T
        W += 0.5 * dt * inv_I * np.array([R * T[1], -R * T[0], Mz])
        P += 0.5 * dt * T
        du = dt * contact_velocity(V, W)
        N, Tx, Ty = bem.step(delta[k + 1], du[0], du[1], dt * W[2])
        T = np.array([Tx, Ty])
        Mz = bem.moment()
        V += 0.5 * dt * inv_m * T
        W += 0.5 * dt * inv_I * np.array([R * T[1], -R * T[0], Mz])
        P += 0.5 * dt * T
        ser_T[k + 1] = T
        ser_N[k + 1] = N
        ser_M[k + 1] = Mz
        ser_W[k + 1] = W
        if not (np.all(np.isfinite(T)) and math.isfinite(Mz)):
            raise NumericalError(f"non-finite tangential force or moment at step {k + 1}")
    Pn = m * (vn - vn_out)            # vn_out < 0: the rebound normal velocity (towards the wall positive)
    e_n = -vn_out / vn
    speed_ci = float(np.hypot(*v_ci))
    mu = scene.mu
    if speed_ci > 0.0:
        f = -float(P @ v_ci) / (speed_ci * Pn)
    else:
        f = float(np.hypot(*P)) / Pn
    denom = (1.0 + e_n) * mu * vn
    v_cr = contact_velocity(V, W)
    return BEMImpactResult(
        f=f, f_over_mu=f / mu if mu > 0 else math.nan,
        Theta=2.0 * speed_ci / denom if mu > 0 else math.inf,
        Omega_r=2.0 * R * (-W[1]) / (5.0 * denom) if mu > 0 else math.nan,
        e_n=e_n, e_t=float(V[0] / vt) if np.ndim(vt) == 0 and vt != 0 else math.nan,
        normal_impulse=Pn, tangential_impulse=P, v_r=V.copy(), omega_r=W.copy(), v_cr=v_cr,
        contact_time=tc, max_overlap=dmax, steps=steps, n_across=bem.n,
        series={"t": t, "overlap": delta, "normal_force": ser_N, "tangential_force": ser_T, "moment_z": ser_M,
                "spin": ser_W} if series else {},
    )
