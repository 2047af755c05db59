"""Boundary-element solution of the tangential (Cattaneo-Mindlin) contact of two elastic spheres, or a
sphere and a wall, for arbitrary histories of the normal overlap and of the tangential displacement
vector. It is slow and exact up to its grid: it exists to judge the fast laws.

Model (the assumptions of the method of dimensionality reduction, so that the two can be compared):
half-spaces, quasi-static contact, Coulomb friction with a constant mu, normal-tangential coupling dropped
(exact for identical materials and for nu = 0.5). The pressure is Hertz's, from the current overlap:
p = p0 sqrt(1 - r^2/a^2), a = sqrt(R* delta), p0 = 3 N / (2 pi a^2) (Johnson 1985, section 4.2).

Discretisation (Kalker 1990, *Three-Dimensional Elastic Bodies in Rolling Contact*, Kluwer; FFT form:
Pohrt & Li 2014, *Phys. Mesomech.* 17:334):

- the square [-a_max, a_max]^2 around the largest contact is cut into n x n square elements of side h
  carrying uniform tractions q = (qx, qy);
- the relative tangential surface displacement of the two bodies is w = A q, where A sums the influence
  coefficients of both bodies: the Cerruti point-force solution (Johnson 1985, eq. 2.19, with the
  normal-tangential term dropped), u_x = [(1-nu)/r + nu x^2/r^3] Q_x / (2 pi G) + nu x y / r^3 Q_y / (2 pi G),
  integrated in closed form over a square of uniform traction (Love 1929, *Phil. Trans. A* 228:377;
  Kalker 1990), see ``influence_kernels``;
- A q is a discrete convolution: evaluated by FFT on a grid of 2n x 2n with zero padding (no periodic
  images; Pohrt & Li 2014, section 3);
- each element has its own Coulomb circle |q| <= mu p, p the Hertz pressure at its centre, scaled so
  that the elements carry N exactly (``hertz_element_pressure``).

Each step (overlap delta, a rigid tangential displacement increment (dux, duy) and a rigid twist increment
d beta of body 1 relative to body 2) solves Kalker's incremental problem. The twist is a rotation about
the normal n (from body 1 to body 2; (x, y, n) right-handed): it adds d beta n x r = (-d beta y, d beta x)
to the rigid displacement of the element at r = (x, y), so the element's rigid increment is
d = (dux - d beta y, duy + d beta x) (Lubkin 1951, *J. Appl. Mech.* 18:183: torsion of spheres in contact;
the twist traction is circumferential and, for half-spaces, carries no normal displacement). The local
slip increment is s = d - A (q - q_old); stick elements
(|q| < mu p) have s = 0, slipping elements have |q| = mu p with q along s (maximal dissipation). Its
solution minimises the complementary energy 1/2 q.A q - q.(d + A q_old) over the product of Coulomb disks
(Kalker's variational principle, 1990); we minimise it by an accelerated projected gradient (FISTA: Beck & Teboulle
2009, SIAM J. Imaging Sci. 2:183, with the adaptive restart of O'Donoghue & Candes 2015, Found. Comput.
Math. 15:715), warm-started from the previous step. Elements outside the current contact have a disk of
radius 0 and so drop their traction; elements entering start unloaded.

Sign convention: q is the traction that displaces the surfaces along d; the tangential force on body 1 is
T = -h^2 sum q (it opposes the displacement: T = -k d in the elastic limit) and the moment on body 1 about
the normal is M_z = -h^2 sum (x q_y - y q_x) (it opposes the twist: M_z = -(16/3) G_c a^3 beta in the
elastic limit, 1/G_c = 1/G1 + 1/G2, Johnson 1985 section 7.4).
"""
from __future__ import annotations

import math
import time

import numpy as np
from numba import njit
from scipy import fft as sfft

from ..errors import InputError, NumericalError
from ..materials import check_finite

#: Default number of elements across the largest contact diameter.
DEFAULT_N_ACROSS = 64
#: Convergence of the step solve: the gradient mapping (the slip increment the iterate still violates)
#: below this fraction of the slip displacement 3 mu N / (16 G* a) (mu capped at 1), in the max norm.
DEFAULT_TOL = 1e-5
#: Iteration cap of one step solve (the solve raises NumericalError if it is reached).
MAX_ITERATIONS = 20000
#: Floor of a step-relative tolerance, in units of the rounding of the convolutions (their machine epsilon
#: times the largest displacement of the step): the solve is not asked to resolve rounding.
ROUNDING_MARGIN = 1e4


def _corner_sums(X, Y, h):
    """Closed-form integrals over the square [-h/2, h/2]^2 of source points, at field offsets (X, Y):
    returns (I1, Ixx, Iyy, Ixy) = integrals of 1/r, x^2/r^3, y^2/r^3, x y/r^3 with (x, y) = field - source.

    Primitives (Love 1929; Kalker 1990): d2/dxdy of x asinh(y/|x|) + y asinh(x/|y|) is 1/r,
    of y asinh(x/|y|) is x^2/r^3, of x asinh(y/|x|) is y^2/r^3 and of -r is x y/r^3 (the terms x ln|x|,
    y ln|y| dropped from the logarithmic forms cancel in the corner sum). Field offsets are multiples of h,
    so no corner lies on an axis."""
    def px(x, y):      # x asinh(y / |x|)
        return x * np.arcsinh(y / np.abs(x))

    def py(x, y):      # y asinh(x / |y|)
        return y * np.arcsinh(x / np.abs(y))

    xa, xb, ya, yb = X - 0.5 * h, X + 0.5 * h, Y - 0.5 * h, Y + 0.5 * h

    def corners(f):
        return f(xb, yb) - f(xa, yb) - f(xb, ya) + f(xa, ya)

    Ixx = corners(py)
    Iyy = corners(px)
    Ixy = corners(lambda x, y: -np.hypot(x, y))
    return Ixx + Iyy, Ixx, Iyy, Ixy


def compliance_coefficients(E1, nu1, E2, nu2):
    """(c1, c2) with the relative tangential displacement of the two surfaces under a point force Q,
    w_x = c1 Q_x / r + c2 (x^2 Q_x + x y Q_y) / r^3 (Cerruti; Johnson 1985 eq. 2.19, both bodies summed):
    c1 = sum (1 - nu)/(2 pi G), c2 = sum nu/(2 pi G); a rigid body (E = inf) adds nothing."""
    c1 = c2 = 0.0
    for E, nu in ((E1, nu1), (E2, nu2)):
        if math.isinf(E):
            continue
        G = E / (2.0 * (1.0 + nu))
        c1 += (1.0 - nu) / (2.0 * math.pi * G)
        c2 += nu / (2.0 * math.pi * G)
    return c1, c2


def influence_kernels(n, h, c1, c2):
    """Influence coefficients (Kxx, Kyy, Kxy) [m/Pa] of a square element of side h with uniform unit
    traction, at the offsets of a 2n x 2n circulant grid (offset index i stands for i h for i < n,
    (i - 2n) h otherwise; index n is never used by a zero-padded product)."""
    m = 2 * n
    k = np.arange(m)
    off = np.where(k < n, k, k - m) * h
    X, Y = np.meshgrid(off, off, indexing="ij")
    I1, Ixx, Iyy, Ixy = _corner_sums(X, Y, h)
    return c1 * I1 + c2 * Ixx, c1 * I1 + c2 * Iyy, c2 * Ixy


def hertz_element_pressure(xc, h, a, N):
    """Hertz pressure p0 sqrt(1 - r^2/a^2) at the element centres (the collocation points; xc: 1D, both
    axes), scaled so that h^2 sum p = N exactly (the Coulomb limit of gross slip is then mu N). An
    element is in contact when its centre is: this keeps the moving contact edge consistent with the
    collocation and makes impacts converge at second order in h (the element average smears the edge and
    converges at first order). A contact that covers no centre yet carries no traction."""
    n = xc.size
    if a <= 0.0 or N <= 0.0:
        return np.zeros((n, n))
    r2 = (xc[:, None] ** 2 + xc[None, :] ** 2) / (a * a)
    p = np.sqrt(np.clip(1.0 - r2, 0.0, None))
    total = p.sum() * h * h
    return p * (N / total) if total > 0.0 else p


@njit(cache=True)
def _combine(kxx, kyy, kxy, f, out):
    """Spectral product of the 2 x 2 influence block with the transformed tractions f[0], f[1]."""
    for i in range(f.shape[1]):
        for j in range(f.shape[2]):
            fx, fy = f[0, i, j], f[1, i, j]
            out[0, i, j] = kxx[i, j] * fx + kxy[i, j] * fy
            out[1, i, j] = kxy[i, j] * fx + kyy[i, j] * fy


@njit(cache=True)
def _project(qx, qy, rad):
    """Radial return of every element's traction onto its Coulomb disk |q| <= rad (in place)."""
    for i in range(qx.shape[0]):
        for j in range(qx.shape[1]):
            m2 = qx[i, j] * qx[i, j] + qy[i, j] * qy[i, j]
            if m2 > rad[i, j] * rad[i, j]:
                f = rad[i, j] / math.sqrt(m2)
                qx[i, j] *= f
                qy[i, j] *= f


@njit(cache=True)
def _gradient_step(yx, yy, ywx, ywy, cx, cy, inv_L, rad, nx, ny):
    """One projected gradient step from y (n = P(y - (A y - c) / L), into nx, ny); returns the largest
    |y - n| (the gradient mapping over L)."""
    res = 0.0
    for i in range(yx.shape[0]):
        for j in range(yx.shape[1]):
            zx = yx[i, j] - (ywx[i, j] - cx[i, j]) * inv_L
            zy = yy[i, j] - (ywy[i, j] - cy[i, j]) * inv_L
            m2 = zx * zx + zy * zy
            r = rad[i, j]
            if m2 > r * r:
                f = r / math.sqrt(m2)
                zx *= f
                zy *= f
            nx[i, j] = zx
            ny[i, j] = zy
            dx = yx[i, j] - zx
            dy = yy[i, j] - zy
            d2 = dx * dx + dy * dy
            if d2 > res:
                res = d2
    return math.sqrt(res)


@njit(cache=True)
def _momentum(nx, ny, nwx, nwy, qx, qy, wx, wy, yx, yy, ywx, ywy, t):
    """FISTA extrapolation y = n + b (n - q) (and its image A y), with the gradient restart of O'Donoghue
    & Candes (2015): when (y - n).(n - q) > 0 the momentum is dropped. Writes y, A y; returns the new t."""
    dot = 0.0
    for i in range(nx.shape[0]):
        for j in range(nx.shape[1]):
            dot += (yx[i, j] - nx[i, j]) * (nx[i, j] - qx[i, j]) + (yy[i, j] - ny[i, j]) * (ny[i, j] - qy[i, j])
    if dot > 0.0:
        t_new, b = 1.0, 0.0
    else:
        t_new = 0.5 * (1.0 + math.sqrt(1.0 + 4.0 * t * t))
        b = (t - 1.0) / t_new
    for i in range(nx.shape[0]):
        for j in range(nx.shape[1]):
            yx[i, j] = nx[i, j] + b * (nx[i, j] - qx[i, j])
            yy[i, j] = ny[i, j] + b * (ny[i, j] - qy[i, j])
            ywx[i, j] = nwx[i, j] + b * (nwx[i, j] - wx[i, j])
            ywy[i, j] = nwy[i, j] + b * (nwy[i, j] - wy[i, j])
    return t_new


class TangentialBEM:
    """The boundary-element contact of two bodies (or a body and a wall) for one contact history.

    E1, nu1, E2, nu2: the materials (E = math.inf for a rigid body) [Pa, -]; R_star: effective radius [m];
    mu: friction coefficient; a_max: largest contact radius the grid must hold [m]; n_across: elements
    across 2 a_max; tol: step-solve tolerance (fraction of the slip displacement); step_tol: None (default)
    or a second tolerance, a fraction of the step's own rigid increment (see ``step``); workers: FFT
    threads; single: convolutions in single precision (default; double with False).

    Tolerances. With ``tol`` alone a step is solved to tol times the slip displacement s = 3 mu N /
    (16 G* a): right when the steps are a fair fraction of s, not when they are far smaller (a sticking
    twist or shear of amplitude << s, in many steps): what a step leaves unresolved is stored as slip, so
    over M steps of increment d the error is M tol s against the M d travelled, tol s / d relative.
    ``step_tol`` bounds it by step_tol: the solve then stops at the smaller of tol s and step_tol d_max,
    d_max the step's largest rigid increment |du + d beta n x r| over the contact, but not below
    ``ROUNDING_MARGIN`` machine epsilons of the convolutions times the step's largest displacement (a step
    with no rigid increment, only the overlap changing, is solved to that floor). In single precision the
    floor (1e-3 of the displacements) exceeds tol s: use step_tol with ``single=False``.

    ``step(delta, dux, duy, dtwist)`` advances by one step and returns (N, Tx, Ty); ``moment()`` is the
    moment M_z about the normal of the current tractions.
    """

    def __init__(self, E1, nu1, E2, nu2, R_star, mu, a_max, *, n_across=DEFAULT_N_ACROSS, tol=DEFAULT_TOL,
                 workers=1, single=True, step_tol=None):
        E1 = check_finite("E1 (Young's modulus of body 1, Pa)", E1, lo=0.0, allow_inf=True)
        E2 = check_finite("E2 (Young's modulus of body 2, Pa)", E2, lo=0.0, allow_inf=True)
        nu1 = check_finite("nu1 (Poisson ratio of body 1)", nu1, lo=-1.0, hi=0.5)
        nu2 = check_finite("nu2 (Poisson ratio of body 2)", nu2, lo=-1.0, hi=0.5)
        if math.isinf(E1) and math.isinf(E2):
            raise InputError("E1 and E2 are both infinite: two rigid bodies have no elastic contact")
        self.R_star = check_finite("R_star (effective radius, m)", R_star, lo=0.0)
        self.mu = check_finite("mu (friction coefficient)", mu, lo=0.0, lo_open=False)
        self.a_max = check_finite("a_max (largest contact radius, m)", a_max, lo=0.0)
        if isinstance(n_across, bool) or int(n_across) != n_across or not 4 <= n_across <= 1024:
            raise InputError(f"n_across = {n_across!r} must be an integer in [4, 1024]")
        self.tol = check_finite("tol (step-solve tolerance)", tol, lo=0.0, hi=1e-2)
        self.step_tol = None if step_tol is None else check_finite(
            "step_tol (step-solve tolerance, fraction of the step's rigid increment; or None)", step_tol, lo=0.0,
            hi=1e-2)
        if not isinstance(single, (bool, np.bool_)):
            raise InputError(f"single = {single!r} must be True (single-precision convolutions) or False (double)")
        self.n = n = int(n_across)
        self.workers = workers
        inv_E = sum((1.0 - nu * nu) / E for E, nu in ((E1, nu1), (E2, nu2)) if not math.isinf(E))
        inv_G = sum(2.0 * (2.0 - nu) * (1.0 + nu) / E for E, nu in ((E1, nu1), (E2, nu2)) if not math.isinf(E))
        self.E_star, self.G_star = 1.0 / inv_E, 1.0 / inv_G
        self.h = h = 2.0 * self.a_max / n
        self.xc = -self.a_max + (np.arange(n) + 0.5) * h
        c1, c2 = compliance_coefficients(E1, nu1, E2, nu2)
        kxx, kyy, kxy = influence_kernels(n, h, c1, c2)
        self._shape = (2 * n, 2 * n)
        # the convolutions run in single precision by default (half the time; their rounding, 1e-7 of the
        # displacements, is far below the solve tolerance); tractions and sums stay in double precision
        self._real = np.float32 if single else np.float64
        self._rounding = ROUNDING_MARGIN * float(np.finfo(self._real).eps)
        cplx = np.complex64 if single else np.complex128
        self._kxx = sfft.rfft2(kxx, workers=workers).astype(cplx)
        self._kyy = sfft.rfft2(kyy, workers=workers).astype(cplx)
        self._kxy = sfft.rfft2(kxy, workers=workers).astype(cplx)
        self._pad = np.zeros((2, 2 * n, 2 * n), dtype=self._real)       # zero-padded tractions
        self._spec = np.zeros((2, 2 * n, n + 1), dtype=cplx)
        self._L_table = self._lipschitz_table()
        self.reset()

    # -- linear algebra ------------------------------------------------------------------------------
    def apply(self, qx, qy):
        """Relative surface displacement (wx, wy) [m] of the tractions (qx, qy) [Pa] on the n x n grid."""
        n = self.n
        self._pad[0, :n, :n] = qx
        self._pad[1, :n, :n] = qy
        f = sfft.rfft2(self._pad, axes=(1, 2), workers=self.workers)
        _combine(self._kxx, self._kyy, self._kxy, f, self._spec)
        w = sfft.irfft2(self._spec, s=self._shape, axes=(1, 2), workers=self.workers)
        return w[0, :n, :n].astype(np.float64), w[1, :n, :n].astype(np.float64)

    def _lipschitz_table(self):
        """Largest eigenvalue of A restricted to the disks of radius r_k = a_max k/8 (k = 1..8), by power
        iteration, times a safety factor: the step length of the projected gradient."""
        r = np.hypot(self.xc[:, None], self.xc[None, :])
        rng = np.random.default_rng(1)
        table = []
        for k in range(1, 9):
            mask = r <= self.a_max * k / 8 + 0.71 * self.h
            vx, vy = rng.random((2, self.n, self.n)) * mask
            lam = 0.0
            for _ in range(60):
                nv = math.sqrt(np.sum(vx * vx + vy * vy))
                vx, vy = vx / nv, vy / nv
                wx, wy = self.apply(vx, vy)
                wx, wy = wx * mask, wy * mask
                lam_new = float(np.sum(vx * wx + vy * wy))
                vx, vy = wx, wy
                if abs(lam_new - lam) < 1e-6 * lam_new:
                    lam = lam_new
                    break
                lam = lam_new
            table.append(1.02 * lam)
        return np.array(table)

    def _lipschitz(self, a):
        k = min(8, max(1, math.ceil(8.0 * a / self.a_max - 1e-12)))
        return self._L_table[k - 1]

    # -- state ---------------------------------------------------------------------------------------
    def reset(self):
        """Open the contact: no traction anywhere."""
        n = self.n
        self.qx = np.zeros((n, n))
        self.qy = np.zeros((n, n))
        self.wx = np.zeros((n, n))
        self.wy = np.zeros((n, n))
        self.iterations = 0
        self.N = 0.0

    def normal(self, delta):
        """(N, a, element pressures) of the Hertz contact at overlap delta (Johnson 1985, section 4.2)."""
        if delta <= 0.0:
            return 0.0, 0.0, None
        a = math.sqrt(self.R_star * delta)
        if a > self.a_max * (1.0 + 1e-9):
            raise InputError(f"the contact radius {a:.6g} m exceeds the grid's a_max = {self.a_max:.6g} m")
        N = 4.0 / 3.0 * self.E_star * math.sqrt(self.R_star) * delta ** 1.5
        return N, a, hertz_element_pressure(self.xc, self.h, a, N)

    def step(self, delta, dux, duy, dtwist=0.0):
        """Advance by one step: overlap ``delta`` [m] now, rigid tangential displacement increment
        (dux, duy) [m] and rigid twist increment ``dtwist`` [rad] (about the normal) of body 1 relative to
        body 2 since the last step. Returns (N, Tx, Ty) [N], T the tangential force on body 1 (``moment()``
        gives the moment about the normal). The solve's tolerance: tol times the slip displacement, or with
        ``step_tol`` the smaller of that and step_tol times the step's largest rigid increment over the
        contact, floored at the rounding of the convolutions (class text)."""
        N, a, p = self.normal(delta)
        self.N = N
        if N == 0.0:
            self.reset()
            return 0.0, 0.0, 0.0
        rad = self.mu * p                      # Coulomb radius of every element
        if self.mu == 0.0:
            self.reset()
            self.N = N
            return N, 0.0, 0.0
        cx = self.wx + dux                     # the complementary energy's linear term: d + A q_old
        cy = self.wy + duy
        if dtwist != 0.0:                      # the rigid twist: d beta n x r at every element
            cx = cx - dtwist * self.xc[None, :]
            cy = cy + dtwist * self.xc[:, None]
        # displacement scale of the step: the slip displacement 3 mu N / (16 G* a), mu capped at 1
        scale = 3.0 * min(self.mu, 1.0) * N / (16.0 * self.G_star * a)
        tol = self.tol * scale
        if self.step_tol is not None:
            inside = rad > 0.0
            ix = dux - dtwist * self.xc[None, :]
            iy = duy + dtwist * self.xc[:, None]
            inc = float(np.sqrt(np.max(np.where(inside, ix * ix + iy * iy, 0.0))))
            floor = self._rounding * float(max(np.max(np.abs(cx)), np.max(np.abs(cy))))
            tol = min(tol, max(self.step_tol * inc, floor))
        self._solve(rad, cx, cy, self._lipschitz(a), tol)
        h2 = self.h * self.h
        return N, -h2 * float(self.qx.sum()), -h2 * float(self.qy.sum())

    def moment(self):
        """Moment on body 1 about the normal of the current tractions [N m]: M_z = -h^2 sum (x q_y - y q_x)
        (the elements' tractions acting at their centres)."""
        x = self.xc[:, None]
        y = self.xc[None, :]
        return -self.h * self.h * float(np.sum(x * self.qy - y * self.qx))

    def _solve(self, rad, cx, cy, L, tol):
        """Minimise 1/2 q.A q - q.c over |q_i| <= rad_i by FISTA with adaptive restart, from the current q
        (Beck & Teboulle 2009; O'Donoghue & Candes 2015). Stops when the gradient mapping L |y - q_new|
        (the slip increment the iterate still gets wrong) is below ``tol`` [m] at every element."""
        qx, qy = self.qx.copy(), self.qy.copy()
        _project(qx, qy, rad)
        wx, wy = self.apply(qx, qy)
        yx, yy, ywx, ywy = qx.copy(), qy.copy(), wx.copy(), wy.copy()
        nx, ny = np.empty_like(qx), np.empty_like(qy)
        t = 1.0
        inv_L = 1.0 / L
        for it in range(1, MAX_ITERATIONS + 1):
            res = L * _gradient_step(yx, yy, ywx, ywy, cx, cy, inv_L, rad, nx, ny)
            if not math.isfinite(res):
                raise NumericalError("BEM step solve produced a non-finite traction")
            nwx, nwy = self.apply(nx, ny)
            if res <= tol:
                qx, qy, wx, wy = nx, ny, nwx, nwy
                break
            t = _momentum(nx, ny, nwx, nwy, qx, qy, wx, wy, yx, yy, ywx, ywy, t)
            qx, nx = nx, qx              # the new iterate becomes q; the old buffer takes the next step
            qy, ny = ny, qy
            wx, wy = nwx, nwy
        else:
            raise NumericalError(f"BEM step solve did not converge in {MAX_ITERATIONS} iterations "
                                 f"(residual {res:.3g} m, tolerance {tol:.3g} m)")
        self.iterations = it
        self.qx, self.qy, self.wx, self.wy = qx, qy, wx, wy


def _as_path(delta, ux, uy, twist=None):
    names = ("delta", "ux", "uy") + (() if twist is None else ("twist",))
    cols = [np.asarray(v, dtype=float) for v in (delta, ux, uy) + (() if twist is None else (twist,))]
    for name, v in zip(names, cols):
        if v.ndim != 1:
            raise InputError(f"{name} must be a 1D array (one row per step), got shape {v.shape}")
        if not np.all(np.isfinite(v)):
            raise InputError(f"{name} must be finite at every step")
    if len({v.size for v in cols}) != 1:
        raise InputError(f"{', '.join(names)} must have the same length, got {', '.join(str(v.size) for v in cols)}")
    if cols[0].size == 0:
        raise InputError(f"{', '.join(names)} must have at least one row")
    return cols


def bem_path(E1, nu1, E2, nu2, R_star, mu, delta, ux, uy, twist=None, *, n_across=DEFAULT_N_ACROSS,
             tol=DEFAULT_TOL, substeps=1, workers=1, return_solver=False, single=True, step_tol=None):
    """Forces along a prescribed contact history, by the boundary-element method (see the module text).

    E1, nu1, E2, nu2: materials of the two bodies (E = math.inf: rigid) [Pa, -]; R_star: effective radius
    [m]; mu: friction coefficient; delta: overlap [m] per step (<= 0: contact open, traction dropped);
    ux, uy: tangential displacement of body 1 relative to body 2 at the contact, components in the tangent
    plane [m], per step; twist (optional): rotation of body 1 relative to body 2 about the normal (from
    body 1 to body 2) [rad], per step. All are measured from the state before the first row (no traction,
    u = 0, twist 0): each step is driven by the increments since the previous row. n_across: elements
    across the largest contact diameter 2 sqrt(R* max(delta)). substeps: solve each row in this many
    equal steps (delta, u and the twist interpolated linearly from the previous row; the first row at its
    own delta): on turning paths the step error is first order in the step (the slip direction of a step
    is that of its increment). tol, step_tol, single: the step solve's tolerances and the convolutions'
    precision (``TangentialBEM``; for paths of many steps far smaller than the slip displacement pass
    step_tol with single=False).

    Returns (N, Tx, Ty): arrays of the normal force [N] and the tangential force on body 1 [N] (opposing
    the displacement; T = -k u in the elastic limit); with ``twist``, (N, Tx, Ty, Mz), Mz the moment on
    body 1 about the normal [N m] (opposing the twist). With ``return_solver``, also the TangentialBEM.
    """
    cols = _as_path(delta, ux, uy, twist)
    d, x, y = cols[:3]
    b = cols[3] if twist is not None else np.zeros(d.size)
    R_star = check_finite("R_star (effective radius, m)", R_star, lo=0.0)
    if isinstance(substeps, bool) or int(substeps) != substeps or not 1 <= substeps <= 10**4:
        raise InputError(f"substeps = {substeps!r} must be an integer in [1, 10000]")
    k = int(substeps)
    dmax = float(d.max())
    n = d.size
    out = [np.zeros(n) for _ in range(3 if twist is None else 4)]
    solver = None
    if dmax > 0.0:
        solver = TangentialBEM(E1, nu1, E2, nu2, R_star, mu, math.sqrt(R_star * dmax), n_across=n_across,
                               tol=tol, workers=workers, single=single, step_tol=step_tol)
        px = py = pb = 0.0
        pd = d[0]
        for i in range(n):
            dx, dy, db = (x[i] - px) / k, (y[i] - py) / k, (b[i] - pb) / k
            for j in range(1, k + 1):
                f = solver.step(pd + (d[i] - pd) * j / k, dx, dy, db)
            out[0][i], out[1][i], out[2][i] = f
            if twist is not None:
                out[3][i] = solver.moment()
            px, py, pb, pd = x[i], y[i], b[i], d[i]
    return (*out, solver) if return_solver else tuple(out)


def _scene_materials(scene):
    """(E1, nu1, E2, nu2, R_star) of a Scene (laws.model)."""
    m1 = scene.sphere.material
    m2 = scene.body2.material
    return m1.E, m1.nu, m2.E, m2.nu, scene.pair.R_star


def bem_path_scene(scene, delta, ux, uy, twist=None, *, n_across=DEFAULT_N_ACROSS, tol=DEFAULT_TOL, substeps=1,
                   workers=1, single=True, step_tol=None):
    """``bem_path`` with the materials, R* and mu of a ``Scene`` (dem_contact.laws.model)."""
    E1, nu1, E2, nu2, R = _scene_materials(scene)
    return bem_path(E1, nu1, E2, nu2, R, scene.mu, delta, ux, uy, twist, n_across=n_across, tol=tol,
                    substeps=substeps, workers=workers, single=single, step_tol=step_tol)


def time_per_step(n_across, steps=10, *, increment=0.08, tol=DEFAULT_TOL, repeats=3, E=208e9, nu=0.3,
                  R_star=0.005, mu=0.3, workers=1):
    """Wall time [s] of one step of a partial-slip loading at constant overlap (steel on steel, steps of
    ``increment`` slip displacements from the unloaded contact), the min over ``repeats`` runs of
    ``steps`` steps, for reports."""
    solver = TangentialBEM(E, nu, E, nu, R_star, mu, 1e-4, n_across=n_across, tol=tol, workers=workers)
    delta = 1e-8 / R_star
    s = mu * delta * solver.E_star / (4.0 * solver.G_star)
    best = math.inf
    for _ in range(repeats):
        solver.reset()
        solver.step(delta, 0.0, 0.0)
        t0 = time.perf_counter()
        for _ in range(steps):
            solver.step(delta, increment * s, 0.0)
        best = min(best, (time.perf_counter() - t0) / steps)
    return best
