"""Twist and shear of a Hertz contact from one local state: the vector MDR cells (``laws.tangential.mdr``)
and the twist cells (``laws.twist.deresiewicz``) on one grid over the punch radius s, with the Coulomb
limit shared at points of the ring.

The two exact laws. Both are superpositions of rigid flat punches of radius s (Jaeger 1995, Arch. Appl.
Mech. 65:478; Popov & Hess 2015, "Method of Dimensionality Reduction in Contact Mechanics and Friction",
chapters 3 and 6). A punch displaced by a tangential vector holds a traction of uniform direction,
Q / (2 pi s sqrt(s^2 - r^2)) (Johnson 1985, section 7.2, with a -> s); a punch twisted about the normal
holds the circumferential traction 3 M r / (4 pi s^3 sqrt(s^2 - r^2)) (Reissner & Sagoci 1944; Johnson
1985, section 7.4). The MDR cell at s carries the tangential displacement u(s) (2 vector) with the limit
|u| <= u_max(s) = mu q_z(s) / G_M (q_z the MDR line load of the pressure p, G_M = 4 G*); the twist cell
carries the rotation theta(s) with the limit |theta| <= theta_max(s) = mu L(s) / k (L the transform
(2/pi) int_s^a p / sqrt(t^2 - s^2) dt of p, k = 4 G_c / pi). T = 2 G_M int u ds and
M = 16 G_c int s^2 theta ds. Each is exact on its own (Mindlin-Deresiewicz histories of the shear at
constant N; Lubkin's twist and Deresiewicz's reversals).

The shared limit. Write a cell's state in units of its limits, x = u / u_max (vector) and z = theta /
theta_max. If every cell s > c holds the same (x, z), the traction on each ring r > c is exactly
mu p(r) (x + z e_phi) (the Abel maps are linear and each limit profile is the map of mu p): a uniform
vector plus a circumferential one. The pointwise Coulomb limit |q| <= mu p at the point of the ring at
the polar angle phi is then |x + z e_phi| <= 1: the shear and the twist share the limit, and around the
ring the points where they add slip first while those where they oppose stick.

The law. Each cell holds K points of its ring, at the angles phi_k = (k + 1/2) 2 pi / K of the path's x
axis, each with a 2 vector v_k [m] in units of the tangential displacement: v_k = u + lambda theta e_k,
lambda = u_max / theta_max, e_k = (-sin phi_k, cos phi_k). A step adds the rigid increment of the point,
dv_k = du + lambda d(beta) e_k, to every point of every cell and returns each point radially to its
circle |v_k| <= u_max (local Coulomb, as the vector MDR law returns a cell). The cell's displacement and
rotation are the two Fourier modes of the ring's field that carry force and moment: u = mean_k v_k and
theta = mean_k (v_k . e_k) / lambda; the other modes (radial, second harmonics) carry neither and are the
memory of where the ring slipped. T and M are then the sums of the two exact laws.

The slip lever (``slip_lever``). With ``limits`` a point that passes its circle is returned
radially: its traction turns with the increment du + lambda d(beta) e_k, the lever lambda = u_max /
theta_max of the elastic response (1.06 a at s = a/2, G_c a / G* at the edge). Under sliding with spin
into full slip the traction of a point then follows that lever, where Coulomb's law makes it follow the
slip, the rigid relative motion du + r d(beta) e_phi at the point's radius r: the moment comes out about
twice the reference's. With ``rings`` (default) the part of a step after the point reaches its circle moves it with
the lever rho(s) of ``ring_radius``, the mean radius of the rings whose pressure the cell's line load
carries (the kernel r p(r) / sqrt(r^2 - s^2) of the MDR transform): the point moves by
du + (f lambda + (1 - f) rho) d(beta) e_k, f the fraction of the step before it reaches the circle, and is
returned to the circle. Both keep the two exact limits below (pure shear: d(beta) = 0; pure twist: every
increment along e_k); ``rings`` is not associated with the points' elastic metric.

What is exact: pure shear (every point of a cell alike: the vector MDR cell, so the Mindlin-Deresiewicz
and Popov-Hess results, ``mdr_adaptive`` to rounding on the same grid); pure twist (every point at the
same |theta|: the deresiewicz cell, so Lubkin 1951, Deresiewicz 1954, no-slip stiffness (16/3) G_c a^3 and
full slip (3 pi/16) mu N a); any elastic superposition of the two; the onset of slip at a point of a
state of the form above. What is approximated: once the points of a ring slip differently, the field
over the ring has modes that no rigid punch carries; the law gives them the 1D stiffness of the cells
(each angle of the ring treated as its own axisymmetric problem), which the 3D problem does not (its slip
zone is not axisymmetric and the punches are coupled through it). The error is measured against the
boundary-element reference with twist (``reference.bem``; ``validation/twist/run_twist_shear.py``,
``validation/twist/report.md``), 32 cells, 8 points, max error in mu N / mu N a: with ``rings``
(default), 0.022 / 0.006 and 0.017 / 0.027 on the twist paths of ``reference.paths.TWIST_SET`` (a sheared
contact twisted, a circle with twist), 0.032 / 0.013 on a shear cycle of a twisted contact, 0.033 / 0.024
and 0.045 / 0.056 under sliding with spin into full slip, 0.054 / 0.055 on a random path; with ``limits``,
0.005 / 0.015, 0.016 / 0.009, 0.032 / 0.013, then 0.057 / 0.100 and 0.143 / 0.146 under sliding with spin,
0.062 / 0.063 on the random path (the separate laws: 0.22 / 0.09, 0.10 / 0.14, 0.10 / 0.42, 0.12 / 0.45,
0.34 / 0.27, 0.19 / 0.42). In exact full slip the cells are not at their limits (each is an average over
r > s of differing slip directions), which no cell-local limit represents. K points sample the ring: the
mean over K equispaced points is exact for trigonometric polynomials of degree < K; the law's results
depend on the orientation of the points in a combined path by up to about 0.005 mu N (K = 4, ``limits``)
or 0.004 (K = 8, ``rings``), and are exactly invariant under turns by 2 pi / K.

A varying normal force (N and a given per row). The two exact laws keep their physical state when N
changes: the MDR cell keeps its displacement u(s) and is returned to its new limit u_max(s), the twist cell
keeps its rotation theta(s) and is returned to theta_max(s) (a flat punch's displacement and rotation are
those of the bodies, which a change of N does not move; what changes is which punches touch and their
limits); cells that enter the contact start unstrained, with the part of the step's increment after their
entry, cells that leave it are released, and the cell cut by a receding edge keeps the part of its mean
inside the contact (``mdr._advance``, ``mdr.shrink_edge``, ``deresiewicz.advance``). This law does the same
with its rings: on a change of N and a it splits each cell's points into the force mode u = mean_k v_k, the
moment mode theta = mean_k (v_k . e_k) / lambda_old and the residual r_k = v_k - u - lambda_old theta e_k
(which carries neither force nor moment: the memory of where the ring slipped); it keeps u and theta
physical (the cut cell and a growing cell carry them as the MDR and twist cells do: u with the length and
the profile a_old^2 - s^2, theta with the weight s^2, the cut cell's kept), rebuilds
v_k = u + lambda_new theta e_k + r_k', then adds the step's increment and returns each point to its new
circle |v_k| <= u_max_new. The residual rule (``residual``): ``scaled`` (default), r_k' = (u_max_new /
u_max_old) r_k, the residual keeps its fraction of the limit (the pattern of slip around a ring, which
in a ring at its limit is a pattern of the limit); ``kept``, r_k' = r_k, physical like the modes; ``dropped``,
r_k' = 0, the ring forgets where it slipped. A point beyond its new circle before the step's increment (its
limit lowered) slides through the step: with ``rings`` it moves with the lever min(lambda, rho) (rho, the
lever of a sliding point, wherever rho <= lambda: every cell but the innermost for steel; with lambda where
that would leave it on the other side of the origin from its elastic trial, so that the return of a pure
twist is deresiewicz's in any step), with ``limits`` with lambda. Under pure shear every point of a cell
is alike (residual and theta 0 to rounding): the vector MDR cell, so ``mdr_adaptive`` to rounding on the
same grid; under pure twist every point is lambda theta e_k (residual and u 0) and its return is
deresiewicz's, to rounding (the tests, for every residual rule and both levers).

Measured against the BEM with twist under a varying overlap (``validation/twist/run_twist_shear_varying.py``,
64 elements across, steel on steel, mu 0.3; max error in mu N / mu N a, N and a of each row), default law:
0.017 / 0.005 on a path that shears to 0.6 of slip, twists to beta_1, loads to twice the overlap, twists
back and unloads to 0.7 while shearing back; 0.064 / 0.036 on a circle with twist while the overlap
oscillates by 40% (the vector MDR alone misses the force of its shear by 0.047 there); 0.127 / 0.059 on a
random path sliding with spin through full slip while the overlap varies by -17% to +42% (0.125 / 0.053
at a constant overlap); the separate laws 0.21 / 0.09, 0.07 / 0.22, 0.38 / 0.57. ``kept`` is within 0.005
of ``scaled`` on each; ``dropped`` misses the circle by 0.126 / 0.098. A point beyond its lowered circle
taking its step elastically (lambda, the exact laws' order) instead of sliding (rho) misses the random path
by 0.164 / 0.121: a contact sliding with spin kept the moment of its larger radius while it unloaded.

Energy: with ``limits`` each point is elastic-perfectly plastic with radial return (``rings``: not
associated), but the physical work per cell is the sum over the points' works only where the cell's stored
energy at the two limits is equal (G_M u_max^2 ds = 8 G_c s^2 theta_max^2 ds, true at no s in general),
so the absence of energy creation on closed loops is checked (random loops, in the tests and the
validation), not proven. Under a varying N a closed loop in (delta, u, beta) may give back work that the
history stored (7 of 200 random loops; the separate exact laws on the same cells: 8); the loop's work less the change of the
stored energy of the force and moment modes (``stored``) was positive in all 200, for every residual rule
and lever. Single steps that unload can show a small negative one, at the cell cut by the receding edge
(its force mode, as the MDR cells'; it falls as the cells refine) (``validation/twist/report.md``).

Scope: a path function in numpy, not a kernel of the 3D step (``laws.compose``): the step gives the slip
to the tangential law and the spin to the twist law, while this law needs both in one place. The grid is
that of ``mdr_adaptive`` and ``deresiewicz`` (cell width R* times the power of 2 with n ds / 2 <= a < n ds)
for the path's largest contact radius, fixed along the path: no cells are merged or split. It is their grid
while the first contact's radius lies in the same octave as the largest and the contact never shrinks below
n ds / 4 (those laws set the width at first contact and halve or double it); otherwise the cells differ and
so do the results, by the laws' discretisation error.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from ..materials import check_finite
from .twist import deresiewicz as _d

#: Default cells (as ``deresiewicz.TWIST_CELLS``) and points per ring.
CELLS = 32
SECTORS = 8


def _jtab(u):
    """J(u) = int_0^u t^2 (K - E)(1 - t^2) dt (``deresiewicz.jtab``, vectorised: the same table and cubic
    Hermite interpolation; J(1) for u >= 1)."""
    u = np.minimum(np.asarray(u, float), 1.0)
    nodes = _d.TABLE_NODES
    x = u * (nodes - 1)
    i = np.minimum(x.astype(int), nodes - 2)
    t = x - i
    h = 1.0 / (nodes - 1)
    t2 = t * t
    t3 = t2 * t
    out = ((2.0 * t3 - 3.0 * t2 + 1.0) * _d._J[i] + (t3 - 2.0 * t2 + t) * h * _d._DJ[i]
           + (3.0 * t2 - 2.0 * t3) * _d._J[i + 1] + (t3 - t2) * h * _d._DJ[i + 1])
    return np.where(u >= 1.0, _d.J_ONE, out)


def cell_width(a: float, n: int, R_star: float) -> float:
    """The cell width of ``mdr_adaptive`` and ``deresiewicz`` at first contact: R* times the power of 2 with
    n ds / 2 <= a < n ds."""
    return math.ldexp(R_star, int(math.floor(math.log2(2.0 * a / (n * R_star)))))


def limits(G_star, G_c, mu, N, a, ds, n):
    """Per cell of width ds (n cells from s = 0): its length l and weight w = int s^2 ds inside the contact,
    u_max [m] (the mean of mu q_z / G_M over l, Hertz shape scaled to N, as ``mdr``) and theta_max [rad]
    (the s^2-weighted mean of mu L / k, as ``deresiewicz``)."""
    x0 = np.arange(n) * ds
    x1 = np.minimum(x0 + ds, a)
    on = x1 > x0
    x1 = np.where(on, x1, x0)
    l = x1 - x0
    w = (x1**3 - x0**3) / 3.0
    umax = np.where(on, 3.0 * mu * N / (16.0 * G_star * a**3) * (a * a - (x0 * x0 + x0 * x1 + x1 * x1) / 3.0), 0.0)
    C = 3.0 * mu * N * a / (4.0 * math.pi * G_c)
    tmax = np.where(on, C * (_jtab(x1 / a) - _jtab(x0 / a)) / np.where(on, w, 1.0), 0.0)
    return l, w, umax, tmax


def ring_radius(s, a):
    """Mean radius of the rings whose pressure the MDR line load at s carries, weighted by the kernel of
    q_z(s) = 2 int_s^a r p(r) / sqrt(r^2 - s^2) dr for the Hertz pressure: rho(s) = (4/pi) int_0^(pi/2)
    sqrt(s^2 + (a^2 - s^2) sin^2 t) cos^2 t dt (r^2 = s^2 + (a^2 - s^2) sin^2 t); 4 a / (3 pi) at s = 0, a at
    s = a. Gauss-Legendre, 32 points (a smooth integrand)."""
    g, wg = np.polynomial.legendre.leggauss(32)
    t = 0.25 * np.pi * (g + 1.0)
    s = np.asarray(s, float)[..., None]
    r = np.sqrt(s * s + (a * a - s * s) * np.sin(t) ** 2)
    return (r * np.cos(t) ** 2 * wg).sum(axis=-1)


#: the slip levers (module docstring)
SLIP_LEVERS = ("limits", "rings")
#: what a change of the normal force does to the residual of a ring (module docstring)
RESIDUAL_RULES = ("scaled", "kept", "dropped")
#: a point is beyond its new circle before a step's increment when |v|^2 > OUTSIDE u_max^2 (above rounding)
OUTSIDE = 1.0 + 1e-9


def _per_row(name, x, rows):
    """A normal force or contact radius: a scalar (every row) or one value per row, finite and >= 0."""
    v = np.asarray(x, dtype=float)
    if v.ndim == 0:
        v = np.full(rows, float(v))
    if v.shape != (rows,):
        raise InputError(f"{name} must be a number or one value per row ({rows}), got shape {v.shape}")
    bad = np.flatnonzero(~(np.isfinite(v) & (v >= 0.0)))
    if bad.size:
        raise InputError(f"{name}[{bad[0]}] = {float(v[bad[0]]):g} must be finite and >= 0")
    return v


def _cut_factors(a, a_old, ds, n):
    """Before a step in which the contact shrinks from a_old to a: the cell that the new edge cuts keeps its
    part inside a, its displacement scaled with the profile a_old^2 - s^2 (``mdr.shrink_edge``) and its
    rotation kept (``deresiewicz.advance``: the twist springs' energy does not rise). Returns (i, f_u);
    i = -1: no cell is cut."""
    i = int(a / ds)
    if i < n:
        x0 = i * ds
        x1 = min(x0 + ds, a_old)
        if a > x0 and x1 > a:
            def wbar(y):
                return a_old * a_old - (x0 * x0 + x0 * y + y * y) / 3.0
            return i, wbar(a) / wbar(x1)
    return -1, 1.0


def _renew(v, old, new, e, x0, ds, residual):
    """The points of every cell after a change of the normal force and contact radius, before the step's
    increment (module docstring): each ring's force mode u and moment mode theta kept physical (the cut cell
    and a growing cell as ``mdr`` and ``deresiewicz`` carry them), the residual by the rule ``residual``,
    rebuilt with the new lever. ``old``, ``new``: (a, l, w, u_max, lambda, rho) before and after. Returns
    (v, iu, it): the points and the weights of the step's increments du and d(beta) per cell (1, or the
    part of the step after entry averaged over a cell that grows, as ``mdr._advance`` and
    ``deresiewicz.advance`` weight them)."""
    a0, l0, w0, umax0, lam0 = old[:5]
    a1, l1, w1, umax1, lam1 = new[:5]
    on0 = l0 > 0.0
    on1 = l1 > 0.0
    u = v.mean(axis=1)
    theta = np.where(on0, (v * e[None]).sum(axis=2).mean(axis=1) / np.where(on0, lam0, 1.0), 0.0)
    r = v - u[:, None, :] - (lam0 * theta)[:, None, None] * e[None]
    if residual == "dropped":
        r[:] = 0.0
    elif residual == "scaled":      # the residual keeps its fraction of the cell's limit
        r *= np.where(on0 & on1, umax1 / np.where(on0, umax0, 1.0), 0.0)[:, None, None]
    if 0.0 < a1 < a0:
        i, fu = _cut_factors(a1, a0, ds, u.shape[0])
        if i >= 0:
            u[i] *= fu
            if residual == "kept":
                r[i] *= fu
    # a cell that grows: its mean over the part in contact, the new part unstrained, which took the part of the
    # increment after its entry (entered at the fraction (s - a_old) / (a - a_old) of the step, s its middle)
    grow = l1 > l0
    safe_l = np.where(grow, l1, 1.0)
    safe_w = np.where(grow, w1, 1.0)
    frac = np.where(grow, (a1 - (x0 + 0.5 * (l0 + l1))) / np.where(grow, a1 - a0, 1.0), 0.0)
    gu = np.where(grow, l0 / safe_l, 1.0)
    gt = np.where(grow, w0 / safe_w, 1.0)
    iu = np.where(grow, (l0 + frac * (l1 - l0)) / safe_l, 1.0)
    it = np.where(grow, (w0 + frac * (w1 - w0)) / safe_w, 1.0)
    u *= gu[:, None]
    theta *= gt
    r *= gu[:, None, None]
    v = np.where(on1[:, None, None], u[:, None, :] + (lam1 * theta)[:, None, None] * e[None] + r, 0.0)
    return v, iu, it


def twist_shear_path(G_star, G_c, mu, R_star, N, a, ux, uy, beta, *, cells: int = CELLS, sectors: int = SECTORS,
                     slip_lever: str = "rings", residual: str = "scaled", stored: bool = False):
    """Tangential force (Tx, Ty) [N], moment M [N m] and work absorbed [J] along a path of tangential
    displacements (ux, uy) [m] and twists beta [rad] (relative, body 1 against body 2; arrays, the first row
    the state before the path, from rest) under the normal force N [N] and contact radius a [m]: numbers
    (constant along the path) or one value per row (N <= 0 or a <= 0: no contact, every cell released)
    (module docstring). T and M are the force and the moment about the normal on body 1, as
    ``studies.paths.run_path`` returns them: they resist the motion (T . du < 0 and M d(beta) < 0 while
    sticking); the work absorbed is -int (T . du + M d(beta)). G_star,
    G_c: the tangential and twist moduli [Pa] (1/G* = sum (2 - nu)/G, 1/G_c = sum 1/G); R_star [m]: the
    grid's scale; cells (even), sectors (points per ring), slip_lever (``limits`` or ``rings``) and
    residual (``scaled``, ``kept`` or ``dropped``: the ring's residual on a change of N) as in the module
    docstring. With ``stored``, also the elastic energy [J] of the force and moment modes per row,
    G_M sum l |u|^2 + 8 G_c sum w theta^2 (the energy of the flat punches whose T and M the law returns)."""
    G_star = check_finite("G_star (tangential modulus, Pa)", G_star, lo=0.0)
    G_c = check_finite("G_c (twist modulus, Pa)", G_c, lo=0.0)
    mu = check_finite("mu (friction coefficient)", mu, lo=0.0)
    R_star = check_finite("R_star (effective radius, m)", R_star, lo=0.0)
    for name, v, lo, hi in (("cells", cells, 2, 1024), ("sectors", sectors, 2, 64)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or not lo <= v <= hi:
            raise InputError(f"{name} = {v!r} must be an integer in [{lo}, {hi}]")
    if cells % 2:
        raise InputError(f"cells = {cells} must be even (the grid of mdr_adaptive)")
    if slip_lever not in SLIP_LEVERS:
        raise InputError(f"slip_lever = {slip_lever!r} is unknown; choose one of: {', '.join(SLIP_LEVERS)}")
    if not isinstance(stored, (bool, np.bool_)):
        raise InputError(f"stored = {stored!r} must be True (also return the stored energy) or False")
    if residual not in RESIDUAL_RULES:
        raise InputError(f"residual = {residual!r} is unknown; choose one of: {', '.join(RESIDUAL_RULES)}")
    cols = [np.asarray(v, dtype=float) for v in (ux, uy, beta)]
    if any(c.ndim != 1 for c in cols) or len({c.size for c in cols}) != 1 or cols[0].size < 1:
        raise InputError("ux, uy and beta must be 1D arrays of one length (at least one row)")
    if not all(np.all(np.isfinite(c)) for c in cols):
        raise InputError("ux, uy and beta must be finite")
    ux, uy, beta = cols
    rows = ux.size
    N = _per_row("N (normal force, N)", N, rows)
    a = _per_row("a (contact radius, m)", a, rows)
    touch = (N > 0.0) & (a**3 > 0.0)
    Tx, Ty, M, work, energy = (np.zeros(rows) for _ in range(5))
    out = (Tx, Ty, M, work, energy) if stored else (Tx, Ty, M, work)
    if not touch.any():
        return out
    ds = cell_width(float(a[touch].max()), cells, R_star)     # one grid: the cells cover the largest contact
    x0 = np.arange(cells) * ds
    phi = (np.arange(sectors) + 0.5) * (2.0 * math.pi / sectors)
    e = np.stack([-np.sin(phi), np.cos(phi)], axis=1)              # e_phi of each point, (K, 2)
    GM = 4.0 * G_star
    none, ones = np.zeros(cells), np.ones(cells)

    def state(t):
        """(a, l, w, u_max, lambda, rho) of row t's contact (all zero without contact)."""
        if not touch[t]:
            return 0.0, none, none, none, none, none
        l, w, umax, tmax = limits(G_star, G_c, mu, N[t], a[t], ds, cells)
        on = l > 0.0
        lam = np.where(on, umax / np.where(on, tmax, 1.0), 0.0)
        if slip_lever == "limits":
            rho = lam
        else:
            rho = np.where(on, ring_radius(0.5 * (x0 + np.minimum(x0 + ds, a[t])), a[t]), 0.0)
        return a[t], l, w, umax, lam, rho

    v = np.zeros((cells, sectors, 2))
    old = state(0)
    for t in range(1, rows):
        du = np.array([ux[t] - ux[t - 1], uy[t] - uy[t - 1]])
        db = beta[t] - beta[t - 1]
        new = state(t)
        _, l1, w1, umax, lam, rho = new
        if not touch[t]:
            v[:] = 0.0
        else:
            iu = it = ones
            if not (touch[t - 1] and N[t] == N[t - 1] and a[t] == a[t - 1]):
                v, iu, it = _renew(v, old, new, e, x0, ds, residual)      # another normal force
            dc = iu[:, None] * du[None, :]          # the increments of the cells (scaled where a cell grows)
            bt = it * db
            d = dc[:, None, :] + (lam * bt)[:, None, None] * e[None, :, :]
            U = umax[:, None]
            trial = v + d
            m = np.sqrt((trial * trial).sum(axis=2))
            over = m > U
            if over.any():
                if slip_lever == "rings":
                    # the fraction f of the step before the point reaches its circle (|v + f d| = u_max), then
                    # the rest with the lever rho: the point moves by du + (f lambda + (1 - f) rho) d(beta) e_k
                    # (du and d(beta) times the entry weights of a cell that grows). A point beyond its circle
                    # before the increment (its limit lowered) slides through the step, with the lever
                    # min(lambda, rho), unless that would leave it on the other side of the origin from its
                    # elastic trial (a step reversing it past the far side of its circle): then with lambda,
                    # the exact laws' order, so that the return of a pure twist is deresiewicz's in any step
                    dd = (d * d).sum(axis=2)
                    vd = (v * d).sum(axis=2)
                    vv = (v * v).sum(axis=2)
                    root = np.sqrt(np.maximum(vd * vd - dd * (vv - U * U), 0.0))
                    f = np.clip((root - vd) / np.where(dd > 0.0, dd, 1.0), 0.0, 1.0)
                    outside = vv > OUTSIDE * (U * U)
                    low = np.minimum(lam, rho)[:, None]
                    through = v + dc[:, None, :] + (low * bt[:, None])[:, :, None] * e[None, :, :]
                    across = (through * trial).sum(axis=2) < 0.0
                    lever = np.where(outside, np.where(across, lam[:, None], low),
                                     f * lam[:, None] + (1.0 - f) * rho[:, None])
                    slid = v + dc[:, None, :] + (lever * bt[:, None])[:, :, None] * e[None, :, :]
                    trial[over] = slid[over]
                    m = np.sqrt((trial * trial).sum(axis=2))
                trial[over] *= (np.broadcast_to(U, m.shape)[over] / m[over])[:, None]
            v = trial
        old = new
        if touch[t]:
            u = v.mean(axis=1)
            on = l1 > 0.0
            theta = np.where(on, (v * e[None]).sum(axis=2).mean(axis=1) / np.where(on, lam, 1.0), 0.0)
            Tx[t], Ty[t] = 2.0 * GM * (u * l1[:, None]).sum(axis=0)
            M[t] = 16.0 * G_c * (theta * w1).sum()
            energy[t] = GM * ((u * u).sum(axis=1) * l1).sum() + 8.0 * G_c * (theta * theta * w1).sum()
        work[t] = work[t - 1] + 0.5 * ((Tx[t - 1] + Tx[t]) * du[0] + (Ty[t - 1] + Ty[t]) * du[1]
                                       + (M[t - 1] + M[t]) * db)
    for v in (Tx, Ty, M):        # the cells' resistance: the force and moment on body 1 are its opposite
        np.negative(v, out=v)
    return out
