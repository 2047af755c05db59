"""Exact reference for the tangential problem: the method of dimensionality reduction (Popov & Hess 2015, chapter 6).

Popov & Hess map the axisymmetric Cattaneo-Mindlin problem (arbitrary histories of N and a
unidirectional T, constant mu, uncoupled normal/tangential response) onto a row of independent springs.
By symmetry only the half-line x >= 0 is stored, in ``n`` cells of width ``dx`` (cell i covers
[i dx, (i+1) dx]); the state of a cell is the mean tangential displacement u_i [m] of its part inside
the contact, stored in the history row at ``H_TANG_EXTRA + i``.

Per step, with the contact radius a (after) and a_old (before) given by the normal law:

- MDR profile: the line load q(x) that the normal law's pressure p(r) implies, the Abel transform
  q(x) = 2 int_x^a r p(r) / sqrt(r^2 - x^2) dr (Popov & Hess 2015, ch. 3), so that N = 2 int_0^a q dx.
  Elastic parts of the laws have a Hertz pressure and q(x) = E* c (a^2 - x^2): c = 1/R* for Hertz, and
  c = 1/R_p for a Thornton contact unloading or reloading with (R_p, delta_p), i.e.
  w = (delta - delta_p) - x^2/R_p. During Thornton's plastic loading the pressure is the Hertz
  pressure of the current overlap truncated at the limiting pressure, p = min(p_H(r), p_y): Thornton
  (1997) builds his force law from exactly this distribution, and its line load integrates to his F
  (``truncated_line_load``). The level is found from N (``truncation``), so it also holds for a p_y
  that varies during the contact (``traction_yield``). For the damped laws the Coulomb limit follows the
  total force N with a Hertz shape, c = 3 N / (4 E* a^3): a limit following the elastic part only would
  let a tangential force survive at N = 0, where the damped contact separates (delta > 0). The
  parameter P_MDR_PROFILE = 1 uses that Hertz shape scaled to N for every law (the Thornton variant
  compared in the validation).
- MDR relation: each spring of the half-line carries the local Coulomb limit mu q(x) (Popov & Hess).
  This holds for any axisymmetric pressure, elastic or not: over a slip annulus u = mu q / G_M, whose
  inverse Abel transform is the traction mu p(r).
- every point in contact takes the rigid increment u += d(delta_t); a point entering the contact
  during the step starts at u = 0 and takes the part of the increment after its entry time (a taken
  linear in time over the step); a point leaving the contact is released (u = 0);
- local Coulomb: |G_M u| <= mu q with G_M = 4 G*, applied to the cell mean with the cell mean of q;
- T = 2 G_M sum_i u_i l_i, l_i = length of cell i inside the contact.

Cell means (finite volumes) instead of point springs make T a continuous function of a, so the
quadrature error is O(dx^2) instead of O(dx). As n -> inf, dt -> 0 this is the exact MDR solution.

Parameters: P_NSPRING = n, P_DX = dx [m], P_ESTAR, P_GSTAR, P_MU. If a > n dx the springs do not cover
the contact: the kernel returns NaN (the integrator stops; ``impact`` reports the grid overflow).
"""
import math

from numba import njit

from .slots import (H_FSTAR, H_T, H_TANG_EXTRA, P_DX, P_ESTAR, P_GSTAR, P_MDR_PROFILE, P_MU, P_NSPRING, P_PY,
                    P_RSTAR)


@njit(cache=True)
def _cells(r, dx, n):
    """Number of cells overlapping [0, r)."""
    if r <= 0.0:
        return 0
    m = int(r / dx) + 1
    return m if m < n else n


@njit(cache=True)
def _release(h, k0, m):
    for i in range(m):
        h[k0 + i] = 0.0
    h[H_T] = 0.0


@njit(inline="always", cache=True)
def truncation(profile, p_y, fstar, N, a, E, R):
    """Ratio k = p_t / p0 of the truncation level p_t to the Hertz peak pressure p0 = 2 E* a / (pi R*) of
    the contact radius a, during Thornton's plastic loading (1 otherwise: no truncation). ``profile``:
    P_MDR_PROFILE, ``fstar``: the largest force F* of the contact (written by the normal law in this step).

    The Hertz pressure truncated at p_t carries F = pi a^2 p_t (1 - k^2 / 3) (Thornton 1997); with
    F_H = (2/3) pi a^2 p0 this is k^3 - 3 k + 2 N / F_H = 0, whose root in [0, 1] is
    k = 2 cos(arccos(-N / F_H) / 3 - 2 pi / 3). Plastic loading: a thornton contact (p_y > 0) at its
    largest force (N = F*) below the Hertz force of R*."""
    if profile != 0.0 or p_y <= 0.0 or N < fstar:
        return 1.0
    ratio = 3.0 * N * R / (4.0 * E * a * a * a)    # N / F_H
    if ratio >= 1.0:
        return 1.0
    return 2.0 * math.cos(math.acos(-ratio) / 3.0 - 2.0 * math.pi / 3.0)


@njit(inline="always", cache=True)
def coulomb_per_w(mu, E, G, R, N, a, k):
    """Coulomb limit of a cell per unit of w: |u| <= mu q / G_M with q = E* c w (G_M = 4 G*). Untruncated
    (k >= 1): c = 3 N / (4 E* a^3), the Hertz shape scaled to N; truncated (k < 1): c = 1/R* and w is
    the integral of ``truncated_integral`` per unit length."""
    c = 3.0 * N / (4.0 * E * a * a * a) if k >= 1.0 else 1.0 / R
    return mu * E * c / (4.0 * G)


@njit(cache=True)
def truncated_integral(x, a, k):
    """int_0^x q(s) ds / (E*/R*) for the Hertz pressure of radius a truncated at k p0 (0 <= x <= a).

    q = (E*/R*)(a^2 - s^2) - dq, and for s < c = a sqrt(1 - k^2) the part cut off is
    dq / (E*/R*) = (2/pi) (a^2 - s^2) arctan(sqrt(c^2 - s^2) / b) - (2 k a / pi) sqrt(c^2 - s^2), b = k a:
    the Abel transform of p_H - k p0 on r < c, integrated in closed form."""
    b = k * a
    c2 = a * a - b * b
    c = math.sqrt(c2)
    if x >= c:       # the whole cut-off part (exact angles: no square root of a rounding error)
        s, r, asn, at = c, 0.0, 0.5 * math.pi, 0.5 * math.pi
    else:
        s = x
        r = math.sqrt(c2 - s * s)
        asn = math.asin(s / c)
        at = math.atan2(s * b, a * r)
    J = (a * a * s - s * s * s / 3.0) * math.atan2(r, b) + b / 3.0 * (
        (0.5 * c2 - 2.0 * a * a) * asn - 0.5 * s * r + 2.0 * a * a * a / b * at)
    cut = 2.0 / math.pi * J - k * a / math.pi * (s * r + c2 * asn)
    return a * a * x - x * x * x / 3.0 - cut


@njit(cache=True)
def _advance(p, h, k0, n, dx, N, a, a_old, dd):
    """Advance the cells h[k0 : k0 + n] of width dx [m] by one step (see the module docstring); return T."""
    GM = 4.0 * p[P_GSTAR]
    kt = truncation(p[P_MDR_PROFILE], p[P_PY], h[H_FSTAR], N, a, p[P_ESTAR], p[P_RSTAR])
    umax_per_w = coulomb_per_w(p[P_MU], p[P_ESTAR], p[P_GSTAR], p[P_RSTAR], N, a, kt)
    a2 = a * a
    da = a - a_old
    m = max(_cells(a, dx, n), _cells(a_old, dx, n))
    # cells inside the contact before and after the step: u += dd, then the cap
    full = min(int(min(a, a_old) / dx), m)
    dx2 = dx * dx / 3.0
    S = 0.0
    Q0 = 0.0      # truncated profile: int_0^x0 of the line load at the cell's lower edge x0 (x0 = 0 first)
    for i in range(full):
        k = k0 + i
        if kt < 1.0:
            Q1 = truncated_integral((i + 1) * dx, a, kt)
            umax = umax_per_w * (Q1 - Q0) / dx
            Q0 = Q1
        else:
            umax = umax_per_w * (a2 - dx2 * (3 * i * (i + 1) + 1))
        u = h[k] + dd
        if u > umax:
            u = umax
        elif u < -umax:
            u = -umax
        h[k] = u
        S += u
    T = S * dx
    for i in range(full, m):
        k = k0 + i
        x0 = i * dx
        l_new = min(max(a - x0, 0.0), dx)
        if l_new <= 0.0:
            h[k] = 0.0
            continue
        l_old = min(max(a_old - x0, 0.0), dx)
        if l_new > l_old:
            # part [x0 + l_old, x0 + l_new] entered during the step; a point x entered at the fraction
            # (x - a_old)/(a - a_old) of the step and takes the rest of the increment
            xm = x0 + 0.5 * (l_old + l_new)
            u = ((h[k] + dd) * l_old + dd * (a - xm) / da * (l_new - l_old)) / l_new
        else:
            u = h[k] + dd
        x1 = x0 + l_new
        if kt < 1.0:
            Q1 = truncated_integral(x1, a, kt)
            wbar = (Q1 - Q0) / l_new
            Q0 = Q1
        else:
            wbar = a2 - (x0 * x0 + x0 * x1 + x1 * x1) / 3.0   # mean of a^2 - x^2 over the cell's contact part
        umax = umax_per_w * wbar
        if u > umax:
            u = umax
        elif u < -umax:
            u = -umax
        h[k] = u
        T += u * l_new
    T *= 2.0 * GM
    h[H_T] = T
    return T


@njit(cache=True)
def mdr(p, h, N, a, a_old, dd):
    """MDR tangential force T [N] in the direction of the increment ``dd`` [m] (Popov & Hess 2015, chapter 6), fixed grid.

    N >= 0: normal force after the step [N]; a, a_old: contact radius after and before the step [m].
    Reads and writes H_T and the cell displacements h[H_TANG_EXTRA : H_TANG_EXTRA + n]."""
    n = int(p[P_NSPRING])
    dx = p[P_DX]
    if N <= 0.0 or a * a * a <= 0.0:      # (a^3 underflows at the touch overlap 1e-300 m: no contact)
        _release(h, H_TANG_EXTRA, max(_cells(a, dx, n), _cells(a_old, dx, n)))
        return 0.0
    if a > n * dx:
        return math.nan
    return _advance(p, h, H_TANG_EXTRA, n, dx, N, a, a_old, dd)


@njit(inline="always", cache=True)
def merged(u0, u1, r, x0, dx):
    """Length-weighted mean of two neighbouring cells u0, u1 of width dx starting at x0 (lengths inside the
    contact of radius r): the value of the merged cell."""
    l0 = min(max(r - x0, 0.0), dx)
    l1 = min(max(r - x0 - dx, 0.0), dx)
    if l0 + l1 > 0.0:
        return (u0 * l0 + u1 * l1) / (l0 + l1)
    return 0.0


@njit(cache=True)
def _merge(h, k0, n, dx, r):
    """Halve the resolution: cell j takes the length-weighted mean of cells 2j, 2j+1 (lengths inside the
    contact of radius r); the upper half of the cells is cleared."""
    for j in range(n // 2):
        h[k0 + j] = merged(h[k0 + 2 * j], h[k0 + 2 * j + 1], r, 2 * j * dx, dx)
    for j in range(n // 2, n):
        h[k0 + j] = 0.0


@njit(inline="always", cache=True)
def _wbar(r, x0, x1):
    """Mean of r^2 - x^2 over [x0, x1]."""
    return r * r - (x0 * x0 + x0 * x1 + x1 * x1) / 3.0


@njit(inline="always", cache=True)
def halves(u, r, x0, hdx):
    """The two halves (width hdx) of a cell u starting at x0 (contact radius r): u times the ratio of
    their mean of w = r^2 - x^2 to the cell's (lengths inside the contact)."""
    l0 = min(max(r - x0, 0.0), hdx)
    l1 = min(max(r - x0 - hdx, 0.0), hdx)
    u0 = 0.0
    u1 = 0.0
    if u != 0.0 and l0 > 0.0:
        wc = _wbar(r, x0, x0 + l0 + l1)
        if wc > 0.0:
            u0 = u * _wbar(r, x0, x0 + l0) / wc
            if l1 > 0.0:
                u1 = u * _wbar(r, x0 + hdx, x0 + hdx + l1) / wc
        else:
            u0 = u
    return u0, u1


@njit(cache=True)
def _split(h, k0, n, dx, r):
    """Double the resolution of the lower half of the cells (width dx, contact radius r): the halves of a
    cell take its mean times the ratio of their mean of w = r^2 - x^2 to the cell's (``halves``). The
    length-weighted mean is kept, and a cell at the Coulomb limit (u proportional to w) splits into two
    halves at their own limits, so splitting never relieves a sliding contact."""
    hdx = 0.5 * dx
    for j in range(n // 2 - 1, -1, -1):
        u0, u1 = halves(h[k0 + j], r, j * dx, hdx)
        h[k0 + 2 * j] = u0
        h[k0 + 2 * j + 1] = u1


@njit(inline="always", cache=True)
def shrink_edge(n, dx, a, a_old):
    """Before a step in which the contact shrinks from a_old to a: the cell that the new edge cuts keeps
    only its part inside a, so its mean is carried to that part with the profile w = a_old^2 - x^2 (the
    released outer part is the one nearest the old edge, where |u| <= mu E* w / G_M is smallest). A cell at
    the Coulomb limit stays at it, as every point of the continuous MDR does. Returns (i, f): cell i is
    multiplied by f (i = -1: no cell changes)."""
    i = int(a / dx)
    if i < n:
        x0 = i * dx
        l_new = a - x0
        l_old = min(a_old - x0, dx)
        if l_new > 0.0 and l_old > l_new:
            w_old = _wbar(a_old, x0, x0 + l_old)
            if w_old > 0.0:
                return i, _wbar(a_old, x0, a) / w_old
    return -1, 1.0


@njit(inline="always", cache=True)
def initial_width(a, n, R):
    """Cell width of mdr_adaptive at first contact: R* times the power of 2 with n dx / 2 <= a < n dx
    (scale-free, independent of the time step)."""
    L = R if R > 0.0 else 1.0
    return L * 2.0 ** math.floor(math.log2(2.0 * a / (n * L)))


@njit(inline="always", cache=True)
def mdr_adaptive(p, h, N, a, a_old, dd):
    """MDR with few cells on a grid that follows the contact (no grid to set up; Popov & Hess 2015, chapter 6).

    Same cells as ``mdr`` (n = P_NSPRING, even), but the cell width dx, stored in h[H_TANG_EXTRA], is set
    at first contact to R* times the power of 2 in (a / n, 2 a / n] (scale-free: problems with the same
    dimensionless groups get the same grid in units of R*, and the grid does not depend on the time step)
    and halved or doubled as the contact shrinks or grows, so the contact always spans between n/4 and n
    cells (n/2 to n while it grows): when a > n dx, pairs of cells merge into their length-weighted mean
    (exact for the integral of u, and cells at the Coulomb limit stay at it); when both a and
    a_old < n dx / 4, every cell splits in two halves (``_split``: mean kept, cells at the Coulomb limit
    stay at it); when the contact shrinks, the cell cut by the new edge keeps the mean of its remaining
    part (``shrink_edge``). Cell displacements: h[H_TANG_EXTRA + 1 + i].
    With n = 16, f/mu of an oblique impact is within about 1e-3 of the converged MDR value."""
    n = int(p[P_NSPRING])
    k0 = H_TANG_EXTRA + 1
    dx = h[H_TANG_EXTRA]
    if N <= 0.0 or a * a * a <= 0.0:      # (a^3 underflows at the touch overlap 1e-300 m: no contact)
        if dx > 0.0:
            _release(h, k0, max(_cells(a, dx, n), _cells(a_old, dx, n)))
        h[H_TANG_EXTRA] = 0.0
        h[H_T] = 0.0
        return 0.0
    if dx <= 0.0 or a_old <= 0.0:
        _release(h, k0, n)
        a_old = 0.0
        dx = initial_width(a, n, p[P_RSTAR])
    while a > n * dx:
        _merge(h, k0, n, dx, a_old)
        dx *= 2.0
    while 4.0 * a < n * dx and 4.0 * a_old < n * dx:
        _split(h, k0, n, dx, a_old)
        dx *= 0.5
    h[H_TANG_EXTRA] = dx
    if a < a_old:
        i, f = shrink_edge(n, dx, a, a_old)
        if i >= 0:
            h[k0 + i] *= f
    return _advance(p, h, k0, n, dx, N, a, a_old, dd)
