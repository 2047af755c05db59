"""Fit of the Wu et al. model (eq. 4.5) to simulated (Theta, f/mu), and the critical Theta it implies.

``fit_wu`` never integrates: it takes data. Three estimates of Theta_c are reported side by side
(Wu, Thornton & Li 2009, sections 4 and 6): the crossing of the fitted curve with 1 (and with 0.99, the
level at which the paper's printed values sit), the direct simulation estimate (``sweep.critical_angle``,
passed in), and eq. 4.1 from kappa.

Two uncertainties of the crossing are reported apart. The statistical one treats the residuals as
independent scatter and shrinks as 1/sqrt(points); but simulated points carry no noise, and their
residuals are the systematic misfit of eq. 4.5 (a tanh crosses 1 at a finite slope, the simulated curve
meets 1 tangentially), which does not shrink with more points. The model-form error is the scale of that misfit carried
to the crossing: the largest residual divided by the slope of the fitted curve at its crossing (for the EE
scene it is 0.14, and the crossing lies 0.12 below eq. 4.1, whatever the number of angles). A crossing beyond every point given (the fitted ones and the sliding ones left
out) is an extrapolation and is flagged.
"""
from __future__ import annotations

import math
import warnings as _warnings
from dataclasses import asdict, dataclass, field

import numpy as np

from ..errors import InputError, NumericalError
from .models import theta_c_theory, wu_crossing, wu_curve

#: Points with f/mu at or above this level count as persistently sliding and are left out of the fit.
SLIDING_LEVEL = 1.0 - 1e-6
#: Bounds of (c1, c2, c3, c4): c2 < 0 and c4 < 0 make the curve rise with Theta.
LOWER = (-2.0, -5.0, -5.0, -5.0)
UPPER = (3.0, 0.0, 5.0, 0.0)


@dataclass
class WuFit:
    """c = (c1, c2, c3, c4) of eq. 4.5 with standard uncertainties ``c_err`` (from the Jacobian and the
    residual variance, as if the residuals were independent); Theta_c: crossing of the fitted curve with 1
    (inf if none); Theta_c_err: its statistical uncertainty (same assumption); Theta_c_model_err: the
    model-form error of eq. 4.5 at the crossing (see the module docstring; usually the larger);
    extrapolated: Theta_c lies beyond every point given (fitted or sliding); Theta_c_099: crossing with 0.99; rms:
    residual RMS; n_points: points used; Theta_max: largest Theta fitted; warnings: what the caller should
    tell the user."""

    c: tuple
    c_err: tuple
    Theta_c: float
    Theta_c_err: float
    Theta_c_099: float
    rms: float
    max_residual: float
    n_points: int
    Theta_max: float
    Theta_c_model_err: float = math.inf
    extrapolated: bool = False
    warnings: list = field(default_factory=list)

    def __call__(self, Theta):
        """The fitted model f/mu (1 above Theta_c)."""
        Theta = np.asarray(Theta, dtype=float)
        return np.where(Theta < self.Theta_c, wu_curve(Theta, self.c), 1.0)

    def to_dict(self) -> dict:
        d = asdict(self)
        c1, c2, c3, c4 = self.c
        e1, e2, e3, e4 = self.c_err
        d.update(c1=c1, c2=c2, c3=c3, c4=c4, c1_err=e1, c2_err=e2, c3_err=e3, c4_err=e4)
        d["c"] = list(self.c)
        d["c_err"] = list(self.c_err)
        return {k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in d.items()}


#: Start grid over (c3, c4); (c1, c2) are solved by linear least squares at every node at once.
START_C3 = np.linspace(-1.0, 3.0, 17)
START_C4 = np.linspace(-1.5, -0.05, 30)


def _start(T, y):
    """Start values: at every (c3, c4) of the start grid the model is linear in (c1, c2); the 2x2 normal
    equations of all nodes are solved together, and the node with the smallest residual among those with a
    rising curve (c2 < 0) is taken. None when no node rises."""
    c3 = np.repeat(START_C3, START_C4.size)
    c4 = np.tile(START_C4, START_C3.size)
    th = np.tanh(c3[:, None] + c4[:, None] * T[None, :])
    n = T.size
    st, stt = th.sum(axis=1), np.einsum("ij,ij->i", th, th)
    sy, sty = y.sum(), th @ y
    det = n * stt - st * st
    with np.errstate(all="ignore"):
        c2 = (n * sty - st * sy) / det
        c1 = (sy - c2 * st) / n
        r = c1[:, None] + c2[:, None] * th - y[None, :]
        ss = np.einsum("ij,ij->i", r, r)
    ok = (c2 < 0) & np.isfinite(ss) & (det > 1e-12 * n * n)
    if not np.any(ok):
        return None
    k = np.flatnonzero(ok)[np.argmin(ss[ok])]
    return np.array([c1[k], c2[k], c3[k], c4[k]])


def fit_wu(Theta, f_over_mu, persistent_sliding=None, *, loss: str = "soft_l1", f_scale: float = 0.01) -> WuFit:
    """Fit f/mu = c1 + c2 tanh(c3 + c4 Theta) (eq. 4.5) to the points below the persistent-sliding region.

    Theta, f_over_mu: arrays of simulated points; persistent_sliding: optional boolean array, points
    flagged True are left out (as are points with f/mu >= 1 - 1e-6 and non-finite ones). Start values:
    a grid over (c3, c4) with (c1, c2) solved by linear least squares at all nodes at once; then
    Levenberg-Marquardt on the analytic Jacobian with the robust soft-L1 loss (``loss="soft_l1"``, scale
    ``f_scale``; ``"linear"``: plain least squares; another scipy ``least_squares`` loss name uses scipy)
    within bounds c2 <= 0, c4 <= 0."""
    T = np.asarray(Theta, dtype=float).ravel()
    y = np.asarray(f_over_mu, dtype=float).ravel()
    if T.shape != y.shape:
        raise InputError(f"Theta and f_over_mu must have the same length (got {T.size}, {y.size})")
    keep = np.isfinite(T) & np.isfinite(y) & (y < SLIDING_LEVEL)
    if persistent_sliding is not None:
        ps = np.asarray(persistent_sliding, dtype=bool).ravel()
        if ps.shape != T.shape:
            raise InputError("persistent_sliding must have the length of Theta")
        keep &= ~ps
    T_all = float(np.max(T[np.isfinite(T)])) if np.any(np.isfinite(T)) else math.nan
    T, y = T[keep], y[keep]
    if T.size < 5:
        raise InputError(f"the fit needs at least 5 points below persistent sliding (got {T.size})")
    best = _start(T, y)
    if best is None:
        raise NumericalError("no start values with a rising curve: f/mu does not rise with Theta")
    x0 = np.clip(best, np.array(LOWER) + 1e-9, np.array(UPPER) - 1e-9)

    def resid(c):
        return wu_curve(T, c) - y

    if loss in ("soft_l1", "linear"):
        x = _robust_gauss_newton(T, y, x0, f_scale if loss == "soft_l1" else math.inf)
    else:
        from scipy.optimize import least_squares

        sol = least_squares(resid, x0, jac=lambda c: _jacobian(T, c), bounds=(LOWER, UPPER), loss=loss,
                            f_scale=f_scale, x_scale="jac", xtol=1e-14, ftol=1e-14, gtol=1e-14, max_nfev=20000)
        if not sol.success:
            raise NumericalError(f"the fit of eq. 4.5 did not converge: {sol.message}")
        x = sol.x
    sol_x = x
    c = tuple(float(v) for v in sol_x)
    r = resid(sol_x)
    dof = max(T.size - 4, 1)
    s2 = float(r @ r) / dof
    J = _jacobian(T, c)
    try:
        cov = np.linalg.inv(J.T @ J) * s2
        c_err = tuple(float(math.sqrt(max(v, 0.0))) for v in np.diag(cov))
    except np.linalg.LinAlgError:
        cov = None
        c_err = (math.inf,) * 4
    tc = wu_crossing(c)
    tc_err = math.inf
    if math.isfinite(tc) and cov is not None:
        g = np.array([(wu_crossing(_shift(c, k, h)) - wu_crossing(_shift(c, k, -h))) / (2 * h)
                      for k, h in enumerate(1e-6 * np.maximum(np.abs(c), 1e-3))])
        if np.all(np.isfinite(g)):
            tc_err = float(math.sqrt(max(g @ cov @ g, 0.0)))
    T_max = float(T.max())
    model_err = math.inf
    msgs = []
    if math.isfinite(tc):
        c1, c2, c3, c4 = c
        slope = c2 * c4 * (1.0 - math.tanh(c3 + c4 * tc) ** 2)
        if slope > 0.0:
            model_err = float(np.max(np.abs(r))) / slope
    else:
        msgs.append("the fitted curve of eq. 4.5 does not reach 1: no Theta_c from the fit")
    # bracketed when some point (a sliding one, left out of the fit) lies at or beyond the crossing
    extrapolated = bool(math.isfinite(tc) and tc > T_all)
    if extrapolated:
        model_err = math.inf        # the misfit inside the data says nothing about the curve beyond it
        msgs.append(f"Theta_c = {tc:.4g} from the fit is an extrapolation beyond the largest fitted Theta "
                    f"({T_max:.4g}) and every point given: simulate up to persistent sliding to bracket it")
    for m in msgs:
        _warnings.warn(m, RuntimeWarning, stacklevel=2)
    return WuFit(c=c, c_err=c_err, Theta_c=tc, Theta_c_err=tc_err, Theta_c_099=wu_crossing(c, 0.99),
                 rms=float(math.sqrt(np.mean(r * r))), max_residual=float(np.max(np.abs(r))),
                 n_points=int(T.size), Theta_max=T_max, Theta_c_model_err=model_err, extrapolated=extrapolated,
                 warnings=msgs)


#: Convergence of the Gauss-Newton iteration: relative step size, and the most iterations.
FIT_XTOL = 1e-13
FIT_MAX_ITER = 500


def _robust_gauss_newton(T, y, x0, f_scale):
    """Minimise sum f_scale^2 rho((r / f_scale)^2), rho(z) = 2 (sqrt(1 + z) - 1) (the soft-L1 loss; plain
    least squares for f_scale = inf), r = eq. 4.5 - y, within the bounds LOWER, UPPER: Levenberg-Marquardt
    steps on the analytic Jacobian of eq. 4.5 with the loss's Gauss-Newton weights rho'(z) (gradient) and
    rho'(z) + 2 z rho''(z) = (1 + z)^-3/2 (curvature; Triggs et al. 2000), each step projected on the bounds
    and accepted only when it lowers the cost."""
    lo, hi = np.array(LOWER), np.array(UPPER)

    def cost_and_weights(c):
        r = wu_curve(T, c) - y
        if not math.isfinite(f_scale):
            return 0.5 * float(r @ r), r, np.ones_like(r), np.ones_like(r)
        z = (r / f_scale) ** 2
        s = np.sqrt(1.0 + z)
        return float(np.sum(f_scale**2 * (s - 1.0))), r, 1.0 / s, 1.0 / (s * s * s)

    x = np.array(x0, dtype=float)
    cost, r, w1, w2 = cost_and_weights(x)
    lam = 1e-3
    for _ in range(FIT_MAX_ITER):
        J = _jacobian(T, x)
        g = J.T @ (w1 * r)
        H = J.T @ (w2[:, None] * J)
        d = np.diag(H).copy()
        while True:
            try:
                step = -np.linalg.solve(H + lam * np.diag(np.maximum(d, 1e-300)), g)
            except np.linalg.LinAlgError:
                step = np.full(4, np.nan)
            xn = np.clip(x + step, lo, hi)
            if np.all(np.isfinite(xn)):
                cn, rn, w1n, w2n = cost_and_weights(xn)
                if cn <= cost:
                    break
            lam *= 10.0
            if lam > 1e16:
                return x        # no step lowers the cost: a minimum to rounding
        moved = np.max(np.abs(xn - x) / (np.abs(x) + 1e-3))
        x, cost, r, w1, w2 = xn, cn, rn, w1n, w2n
        lam = max(lam * 0.1, 1e-12)
        if moved < FIT_XTOL:
            return x
    raise NumericalError(f"the fit of eq. 4.5 did not converge in {FIT_MAX_ITER} iterations")


def _shift(c, k, h):
    c = list(c)
    c[k] += h
    return tuple(c)


def _jacobian(T, c):
    c1, c2, c3, c4 = c
    th = np.tanh(c3 + c4 * T)
    sech2 = 1.0 - th * th
    return np.column_stack([np.ones_like(T), th, c2 * sech2, c2 * sech2 * T])


@dataclass
class CriticalTheta:
    """Three estimates of the critical Theta (Wu, Thornton & Li 2009): ``fit`` (crossing of the fitted
    curve with 1), ``fit_099`` (crossing with 0.99), ``simulation`` (smallest Theta at which the
    contact slides at every step, from ``sweep.critical_angle``), ``theory`` (7 - 2 e_n / (kappa (1 + e_n)),
    ``models.theta_c_theory``; eq. 4.1 at e_n = 1)."""

    fit: float
    fit_099: float
    simulation: float | None
    theory: float

    def to_dict(self) -> dict:
        return {k: (None if v is None or not math.isfinite(v) else float(v)) for k, v in asdict(self).items()}


def critical_theta(fit: WuFit, kappa: float, simulation: float | None = None, e_n: float = 1.0) -> CriticalTheta:
    """Collect the three estimates of Theta_c (``simulation`` is computed by ``sweep.critical_angle``; e_n: that
    of the sliding impacts)."""
    return CriticalTheta(fit=fit.Theta_c, fit_099=fit.Theta_c_099, simulation=simulation,
                         theory=theta_c_theory(kappa, e_n))
