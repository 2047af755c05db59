"""First yield of a Hertz contact carrying a tangential traction, for the traction-coupled Thornton law.

A Hertz pressure p = p0 sqrt(1 - r^2/a^2) with a tangential traction q in the x direction loads an
elastic half-space. The stresses of q = q0 sqrt(1 - r^2/a^2) are Hamilton's closed forms (G. M. Hamilton,
"Explicit equations for the stresses beneath a sliding spherical contact", Proc. IMechE 197C (1983)
53-59), evaluated here in units of a and p0. First yield (von Mises, uniaxial yield stress Y) happens
at the largest equivalent stress in the body: p0_first = Y / max sigma_vM(x, y, z) / p0. The
traction-coupled Thornton law scales its limiting pressure by g = p0_first(traction) / p0_first(none),
tabulated against mu_eff = |T| / N, the only measure of the traction the normal law sees. Two
distributions of the traction carrying |T| are tabulated; nothing in either is fitted.

- ``"proportional"``: q = mu_eff p. Exact in gross sliding (mu_eff = mu) and for loading in which T and
  N grow in proportion with dT/dN < mu: no point slips and every increment of traction is (dT/dN) times
  the increment of pressure (Mindlin & Deresiewicz, J. Appl. Mech. 20 (1953) 327; Johnson, Contact
  Mechanics, 1985, section 7.3).
- ``"partial_slip"``: the Cattaneo-Mindlin traction of a partly slipping contact,
  q = mu (p(r; a) - p(r; c)), p(r; c) = p0 (c/a) sqrt(1 - r^2/c^2) the Hertz pressure of radius c,
  with the stick radius c/a = (1 - |T|/(mu N))^(1/3) (Cattaneo 1938; Mindlin, J. Appl. Mech. 16 (1949)
  259). Its field is Hamilton's field of radius a less his field of radius c (exact: two Hertz-shaped
  tractions). It is exact for a tangential force growing at constant N, and for T and N growing together
  with dT/dN > mu after a slip annulus has formed (Mindlin & Deresiewicz 1953); the centre, where first
  yield of a frictionless contact happens (depth 0.48 a), carries mu p0 (1 - c/a).

What the impact's loading phase carries: it starts from T = N = 0, so it either sticks at every point
(kappa v_t < mu d(delta)/dt: Theta below 2 / (kappa (1 + e_n)), the increments are proportional to the
pressure increments and the centre carries traction) or slides as a whole (q = mu p); a partly slipping
annulus of Cattaneo's kind forms only when the tangential rate later exceeds mu times the normal one
(Maw, Barber & Fawcett, Wear 38 (1976) 101). So ``"partial_slip"`` is exact at the two ends (no
traction: g = 1; gross sliding: g(mu), the same as ``"proportional"``) and an approximation in between,
where it places the traction in an annulus that the tangential law need not have; during a stuck
loading with varying dT/dN the true distribution is a sum of Hertz-shaped increments of all radii up to
a, which neither table represents: at small angles the centre keeps the traction of the early loading
while |T| has fallen (the exact reference at maximum compression, measured in the validation report,
section "The e_n dip with the impact angle"). Unloading and reversals do not enter: Thornton's law
yields only on loading.

Why not the plastic junction. A fully plastic junction under pressure p and shear tau flows at
p^2 + 3 tau^2 = p_m^2 (von Mises; junction growth: McFarlane & Tabor, Proc. R. Soc. A 202 (1950) 244),
which would lower the limiting pressure by 1 - 1/sqrt(1 + 3 mu^2) (11.3% at mu = 0.3). It needs a plastic
zone that has reached the surface, i.e. a fully plastic indentation: for a sphere from E* a / (Y R) of
about 30, some 400 times the first-yield load (Johnson 1985, section 6.3). A steel sphere of
Y = 1.85 GPa on steel at 5 m/s reaches E* a / (Y R) of about 6 (Hertz radius of the overlap), at 2 m/s
about 4: contained elastic-plastic contacts, for which first yield is the result that applies, so the
junction argument is not used.

The field is checked in ``tests/laws/test_plastic.py`` (equilibrium, Beltrami-Michell compatibility and the
surface tractions by finite differences; the trailing-edge surface stress
sigma_x = p0 ((1 - 2 nu)/3 + (4 + nu) pi mu / 8) of Hamilton & Goodman 1966; the surface shear of the
partly slipping traction).
"""
from __future__ import annotations

import functools

import numpy as np

from ..errors import InputError
from .slots import P_TY_TABLE_SIZE


def _aux(x, y, z):
    r2 = x * x + y * y
    A = r2 + z * z - 1.0
    S = np.sqrt(A * A + 4.0 * z * z)
    M = np.sqrt(0.5 * (S + A))
    N = np.sqrt(np.maximum(0.5 * (S - A), 0.0))
    phi = np.arctan2(1.0, M)
    return r2, A, S, M, N, phi


def normal_stress(x, y, z, nu):
    """Stresses (sxx, syy, szz, sxy, sxz, syz) / p0 under the Hertz pressure (lengths / a, z >= 0 into the
    body; compression negative). Hamilton (1983), normal load; the points must be off the axis x = y = 0."""
    r2, A, S, M, N, phi = _aux(x, y, z)
    G = M * M - N * N + z * M - N
    H = 2.0 * M * N + M + z * N
    common = (1.0 - nu) * N * z * z - (1.0 - 2.0 * nu) / 3.0 * (N * S + 2.0 * A * N + 1.0) - nu * M * z
    sxx = (1.0 + nu) * z * phi + ((y * y - x * x) / r2 * common - N * (x * x + 2.0 * nu * y * y)
                                  - M * x * x * z / S) / r2
    syy = (1.0 + nu) * z * phi + ((x * x - y * y) / r2 * common - N * (y * y + 2.0 * nu * x * x)
                                  - M * y * y * z / S) / r2
    szz = -N + z * M / S
    sxy = x * y / (r2 * r2) * ((1.0 - 2.0 * nu) * (-N * r2 + 2.0 / 3.0 * N * (S + 2.0 * A) - z * (z * N + M)
                                                  + 2.0 / 3.0) + z * (-M * r2 / S - z * N + M))
    t = z * z * H / (G * G + H * H) - z * N / S
    return sxx, syy, szz, sxy, x * t, y * t


def tangential_stress(x, y, z, nu):
    """Stresses / q0 under the traction q = q0 sqrt(1 - r^2/a^2) acting on the body in +x (Hamilton 1983,
    tangential load); same conventions as ``normal_stress``."""
    r2, A, S, M, N, phi = _aux(x, y, z)
    r4 = r2 * r2
    v = 1.0 - 2.0 * nu
    x2, y2, z2 = x * x, y * y, z * z
    fx = 1.5 - 2.0 * x2 / r2
    hx = 0.5 - 2.0 * x2 / r2
    hy = 0.5 - 2.0 * y2 / r2
    base = -S / 6.0 * v - A / 3.0 * v
    sxx = (-x * (nu / 4.0 + 1.0) * phi
           + x * M / r4 * (fx * (nu * S - 2.0 * nu * A + z2) + x2 * z2 / S + 1.75 * nu * r2 - 2.0 * nu * x2 + r2)
           + x * z * N / r4 * (fx * (base - 0.5 * (z2 + 3.0)) + x2 / S - 0.25 * nu * r2 - 1.75 * r2)
           + 4.0 * x * z / (3.0 * r4) * fx * v)
    syy = (-0.75 * nu * x * phi
           + x * M / r4 * (hy * (nu * (S - 2.0 * A + r2) + z2) + y2 * z2 / S + 0.75 * nu * r2)
           + x * z * N / r4 * (hy * (base - 0.5 * z2 - 1.5) + y2 / S - 0.75 * nu * r2 - 0.25 * r2)
           + 4.0 * x * z / (3.0 * r4) * hy * v)
    szz = 0.5 * x * z * N / r2 * (1.0 - (r2 + z2 + 1.0) / S)
    sxy = (0.5 * y * (0.5 * nu - 1.0) * phi
           + y * M / r4 * (x2 * z2 / S + nu * ((S - 2.0 * A) * hx - 2.0 * x2 + 0.25 * r2) + 0.5 * r2 + z2 * hx)
           + y * z * N / r4 * (hx * (-v * (S / 6.0 + A / 3.0) - 0.5 * z2 - 1.5 - 0.5 * r2) + 0.25 * nu * r2
                               + x2 / S - 0.5 * y2 - 1.5 * x2)
           + 4.0 * y * z / (3.0 * r4) * hx * v)
    sxz = (1.5 * z * phi + z * M / r2 * (1.0 + x2 / r2 - x2 / S)
           + N / r2 * (-0.75 * (S + 2.0 * A) + z2 - 0.75 - 0.25 * r2 + 0.5 * z2 * hx))
    syz = x * y * z / (2.0 * r4) * (M * (0.5 + (0.5 * z2 - 1.5 - 0.5 * r2) / S)
                                    + 0.5 * z * N * (-3.0 + (5.0 + z2 + r2) / S))
    return sxx, syy, szz, sxy, sxz, syz


def partial_slip_stress(x, y, z, nu, stick):
    """Stresses / q0 under the traction q0 (sqrt(1 - r^2/a^2) - (c/a) sqrt(1 - r^2/c^2)) in +x (the
    second term inside r < c only), c/a = ``stick`` in [0, 1]: Hamilton's field of radius a less his field
    of radius c, which is the unit field at (x, y, z) / c scaled by the peak traction q0 c/a. stick = 0 is
    ``tangential_stress``; same conventions."""
    st = tangential_stress(x, y, z, nu)
    if stick <= 0.0:
        return st
    sc = tangential_stress(x / stick, y / stick, z / stick, nu)
    return tuple(a - stick * b for a, b in zip(st, sc))


#: Closer to the axis than this (in units of a), the closed forms lose digits to cancellation (terms in
#: 1/r^4): the field is evaluated at this distance instead, in the same direction (it is smooth there).
AXIS_GUARD = 0.02


def von_mises(x, y, z, nu, mu_eff, stick=0.0):
    """Von Mises equivalent stress / p0 of the Hertz pressure plus the traction mu_eff p (in +x), less
    (``stick`` = c/a > 0) mu_eff times the Hertz pressure of radius c, p0 (c/a) sqrt(1 - r^2/c^2): the
    Cattaneo-Mindlin traction of a partly slipping contact of stick radius c (Hamilton's field of radius c
    is his unit field at (x, y, z) / c, scaled by its peak traction)."""
    x, y, z = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float), np.asarray(z, float))
    r = np.hypot(x, y)
    scale = AXIS_GUARD / np.maximum(r, 1e-300)
    near = r < AXIS_GUARD
    x = np.where(near, np.where(r > 0.0, x * scale, AXIS_GUARD), x)
    y = np.where(near, y * np.where(r > 0.0, scale, 0.0), y)
    sn = normal_stress(x, y, z, nu)
    st = partial_slip_stress(x, y, z, nu, stick)
    sxx, syy, szz, sxy, sxz, syz = (a + mu_eff * b for a, b in zip(sn, st))
    return np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2)
                   + 3.0 * (sxy * sxy + sxz * sxz + syz * syz))


#: Local maximisations per search: from the highest local maxima of the grid (the field has at most
#: two, below the surface and at the trailing edge; more starts guard against grid artefacts).
LOCAL_STARTS = 3
#: Relative step of the forward differences of the local maximisation.
FD_STEP = 1.5e-8


def max_von_mises(nu: float, mu_eff: float, stick: float = 0.0):
    """(max sigma_vM / p0, x/a, y/a, z/a) over the half-space (``von_mises``): a grid search, then a
    bounded local maximisation from the best LOCAL_STARTS local maxima of the grid (the field is
    symmetric in y, so y >= 0)."""
    from scipy.optimize import minimize

    xs = np.linspace(-1.6, 1.6, 97)
    ys = np.linspace(0.0, 1.2, 25) + 1e-9
    zs = np.concatenate([[1e-9], np.linspace(0.02, 1.2, 60)])
    X, Y, Z = np.meshgrid(xs, ys, zs, indexing="ij")
    V = von_mises(X, Y, Z, nu, mu_eff, stick)
    padded = np.pad(V, 1, constant_values=-np.inf)
    neighbours = np.max([np.roll(np.roll(np.roll(padded, i, 0), j, 1), k, 2)[1:-1, 1:-1, 1:-1]
                         for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1) if (i, j, k) != (0, 0, 0)],
                        axis=0)
    peaks = np.flatnonzero(V >= neighbours)
    def objective(s):
        """-sigma_vM and its gradient by forward differences (one vectorised call)."""
        h = FD_STEP * np.maximum(1.0, np.abs(s))
        pts = s[:, None] + np.concatenate([np.zeros((3, 1)), np.diag(h)], axis=1)
        v = von_mises(pts[0], pts[1], pts[2], nu, mu_eff, stick)
        return -v[0], -(v[1:] - v[0]) / h

    best = (-1.0, 0.0, 0.0, 0.0)
    for idx in peaks[np.argsort(V.flat[peaks])][-LOCAL_STARTS:]:
        i = np.unravel_index(idx, V.shape)
        x0 = np.array([X[i], Y[i], Z[i]])
        res = minimize(objective, x0, jac=True, method="L-BFGS-B",
                       bounds=[(-2.0, 2.0), (1e-9, 1.5), (1e-9, 1.5)], options={"ftol": 1e-14, "gtol": 1e-11})
        val = -float(res.fun)
        if val > best[0]:
            best = (val, *map(float, res.x))
    return best


#: Number of uniform nodes of mu_eff in the first-yield table (the slots the parameter row has for it).
TABLE_NODES = P_TY_TABLE_SIZE


#: The traction distributions of the first-yield table, by name (``Scene(traction_yield=)``).
DISTRIBUTIONS = ("proportional", "partial_slip")


def stick_ratio(T_over_muN):
    """c/a of the Cattaneo-Mindlin traction that carries |T| = s mu N: (1 - s)^(1/3) (Cattaneo 1938;
    Mindlin 1949; Johnson 1985, chapter 7)."""
    return np.cbrt(1.0 - np.clip(T_over_muN, 0.0, 1.0))


@functools.lru_cache(maxsize=64)
def first_yield_ratio_table(nu: float, mu_max: float, distribution: str = "proportional") -> tuple:
    """p0_first / p0_first(no traction) at TABLE_NODES uniform nodes of mu_eff = |T|/N in [0, mu_max]
    (Poisson ratio nu of the yielding body, friction coefficient mu_max), for the traction
    ``distribution``: "proportional", q = mu_eff p; "partial_slip", the Cattaneo-Mindlin traction
    q = mu_max (p(r; a) - p(r; c)) with c/a = stick_ratio(mu_eff / mu_max) (module docstring). Computed
    once per (nu, mu_max, distribution) and cached."""
    if not 0.0 <= nu <= 0.5:
        raise InputError(f"nu = {nu:g}: the first-yield table needs a Poisson ratio in [0, 0.5]")
    if not mu_max > 0.0:
        raise InputError("mu must be > 0 for the first-yield table")
    if distribution not in DISTRIBUTIONS:
        raise InputError(f"traction distribution {distribution!r} is unknown; choose one of: "
                         f"{', '.join(DISTRIBUTIONS)}")
    mus = np.linspace(0.0, mu_max, TABLE_NODES)
    if distribution == "proportional":
        peak = np.array([max_von_mises(nu, m)[0] for m in mus])
    else:
        peak = np.array([max_von_mises(nu, mu_max, float(stick_ratio(m / mu_max)))[0] for m in mus])
    return tuple(peak[0] / peak)
