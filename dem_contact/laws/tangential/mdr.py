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
from types import MappingProxyType

import numpy as np
from numba import njit

from ...errors import InputError
from ...materials import check_finite
from ..declare import ESTAR, GSTAR, MU, RSTAR, V_REF, Option, Param
from ..slots import (H_FSTAR, H_T, H_TANG_EXTRA, P_DX, P_ESTAR, P_GSTAR, P_MDR_PROFILE, P_MU, P_NSPRING, P_PY,
                     P_RSTAR)
from ..vector import JIT, V_A, W_WORK, W_X, W_Y, W_Z, at, carry_unit, put, renamed

NAME, FAMILY = "mdr", "tangential"
SOURCE = "exact reference: method of dimensionality reduction (Popov & Hess), springs on a half-line"
PARAMETERS = (ESTAR, GSTAR, RSTAR, MU,
              Param("p_y", "P_PY", "the normal law's limiting contact pressure (0: none)", "Pa"),
              Param("n", "P_NSPRING", "number of cells (springs) of the MDR laws"),
              Param("dx", "P_DX", "cell width of the fixed MDR grid", "m"),
              Param("profile", "P_MDR_PROFILE", "Coulomb-limit profile of the MDR laws: 0 the pressure the normal "
                    "law implies (Hertz truncated at p_y during Thornton's plastic loading), 1 a Hertz shape "
                    "scaled to N"))
STATE = ("T", "cells")
#: the state has a cell part sized by the cell count (the parameter n): one slot per cell in the plane,
#: two in 3D (a displacement in the frame e1, e2)
CELLS = True
#: planar slots before the cells (none: the grid is fixed)
CELL_HEADER = 0

#: Default number of MDR springs (cells on the half-line x >= 0): with MDR_STEPS_PER_CONTACT steps per
#: contact, f/mu of an oblique impact is within 1e-5 of the converged MDR value (4 significant digits).
MDR_SPRINGS = 200
#: Steps per contact for 4-digit MDR results (see MDR_SPRINGS).
MDR_STEPS_PER_CONTACT = 1000
#: The MDR grid covers this multiple of the largest contact radius expected at v_ref.
MDR_RADIUS_MARGIN = 1.05
#: Steps per contact at which f/mu of an oblique impact is converged (second order in the step: the chart's
#: reference, ``studies.chart``, takes it with 400 springs).
CONVERGED_STEPS = 4000
#: Coulomb-limit profiles during plastic loading (``Scene(mdr_profile=...)``, see above).
MDR_PROFILES = MappingProxyType({"truncated": 0.0, "scaled": 1.0})

# 3D slots relative to the tangential base b: the work, the frame's first axis e1 (W_X, W_Y, W_Z), then
R_T1 = 4        # T in the frame (e1, e2 = n x e1) [N]
R_T2 = 5
R_DX = 6        # cell width [m] (adaptive grid)
R_CELLS = 7     # cell i: its displacement in the frame at b + R_CELLS + 2 i (+1) (fixed grid)
# the adaptive grid's sticking zone: cells 0 ... lazy - 1, known to stick, hold v = u - D and take a step's
# increment through D alone (``_vector``)
R_LAZY = 7      # lazy: the number of cells of the zone (0: none)
R_D1 = 8        # D, the increment common to the zone since it was set up, in the frame
R_D2 = 9
R_SV1 = 10      # the sum of v over the zone
R_SV2 = 11
R_KS = 12       # umax per w (``coulomb_per_w``) when the zone was set up
R_G0 = 13       # K_s a_s^2 - min over the zone of (umax - |u|) when it was set up
R_CELLS_ADAPTIVE = 14
#: fixed 3D slots; swapping the bodies negates e1 and (n -> -n keeps e2 = n x e1) the second components
VECTOR_SLOTS = R_CELLS
SWAP_NEGATE = (W_X, W_Y, W_Z, R_T2)
#: the adaptive grid's (``mdr_adaptive``)
VECTOR_SLOTS_ADAPTIVE = R_CELLS_ADAPTIVE
SWAP_NEGATE_ADAPTIVE = (W_X, W_Y, W_Z, R_T2, R_D2, R_SV2)
#: a sticking zone is set up when it spans at least this many cells
LAZY_MIN = 2
#: the zone's cells stay within this fraction of their Coulomb radius (below NEAR: none is ever near)
QNEAR = 1.0 - 1e-9
SWAP_NEGATE_CELL = 1
#: said when a force is not finite: the contact outgrew the fixed grid
NAN_HINT = "beyond the fixed MDR grid?"


#: the settings of the MDR laws (``mdr_adaptive`` takes the cell count and the profile)
SPRINGS = Option("mdr_springs", "number of MDR springs (cells on the half-line; mdr_adaptive: an even cell count)",
                 per_law=True)
MAX_RADIUS = Option("mdr_max_radius", "largest contact radius the MDR springs must cover (default: that of a "
                    "normal impact at v_ref, times MDR_RADIUS_MARGIN)", "m", per_law=True)
PROFILE = Option("mdr_profile", "Coulomb limit of the MDR laws during Thornton's plastic loading: truncated, mu "
                 "times the line load of the Hertz pressure truncated at p_y; scaled, a Hertz shape scaled to mu N",
                 default="truncated", choices=MDR_PROFILES, cli={})
OPTIONS = (SPRINGS, MAX_RADIUS, PROFILE, V_REF)


def set_profile(scene, p):
    p[P_MDR_PROFILE] = MDR_PROFILES[scene.mdr_profile]


def configure(scene, p):
    """The fixed grid: mdr_springs cells covering mdr_max_radius, or the largest contact radius of a normal
    impact at v_ref times MDR_RADIUS_MARGIN."""
    set_profile(scene, p)
    springs, max_radius = scene.arguments["mdr_springs"], scene.arguments["mdr_max_radius"]
    n = MDR_SPRINGS if springs is None else springs
    if isinstance(n, bool) or int(n) != n or not 2 <= n <= 10**6:
        raise InputError(f"mdr_springs = {n!r} must be an integer in [2, 1e6]")
    n = int(n)
    if max_radius is not None:
        r = check_finite("mdr_max_radius (largest contact radius, m)", max_radius, lo=0.0)
    elif scene.v_ref is not None:
        r = MDR_RADIUS_MARGIN * scene.max_contact_radius(scene.v_ref)
    else:
        raise InputError("the mdr tangential law needs v_ref (largest normal speed expected, m/s, > 0) or "
                         "mdr_max_radius (largest contact radius, m) to place its springs")
    scene.mdr_springs = n
    scene.mdr_max_radius = r
    p[P_NSPRING] = n
    p[P_DX] = r / n


def max_radius(scene):
    """The extent of the springs: a contact that grows past it has no cells to slip in."""
    return scene.mdr_max_radius


def describe(scene, p):
    return dict(mdr_profile=scene.mdr_profile, mdr_springs=scene.mdr_springs, mdr_max_radius=scene.mdr_max_radius,
                mdr_dx=p[P_DX])

def check_rows(params):
    """(bad rows, why) of a parameter table that this law cannot run (the checked 3D entries)."""
    cells = params[:, P_NSPRING]
    return [(~((cells >= 2) & (cells <= 10**6) & (cells == np.floor(cells))),
             f"has no MDR cell count (params[:, P_NSPRING] in [2, 1e6]), which the {NAME} law needs"),
            (~(params[:, P_DX] > 0.0), f"has no MDR cell width (params[:, P_DX] > 0), which the {NAME} law needs")]


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
    the integral of ``truncated_integral`` per unit length. (Written with one division: mu E* c / G_M is
    3 mu N / (16 G* a^3) untruncated, mu E* / (4 G* R*) truncated.)"""
    if k >= 1.0:
        return 3.0 * mu * N / (16.0 * G * a * a * a)
    return mu * E / (4.0 * G * R)


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


#: ``truncated_integral`` inlined into the 3D kernels with their numba options, under a name of its own
#: (numba names compiled code by the function's qualified name; this copy has other flags)
truncated_integral_vector = njit(inline="always", **dict(JIT, cache=False))(
    renamed(truncated_integral.py_func, "truncated_integral_vector"))


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
    """Cell width of the adaptive grid at first contact: R* times the power of 2 with n dx / 2 <= a < n dx
    (scale-free, independent of the time step)."""
    L = R if R > 0.0 else 1.0
    return L * 2.0 ** math.floor(math.log2(2.0 * a / (n * L)))


@njit(inline="always", cache=True)
def planar(p, h, N, dN, a, a_old, dd):
    return mdr(p, h, N, a, a_old, dd)


@njit(inline="always", **JIT)
def cells(r, dx, n):
    """Number of MDR cells of width dx overlapping [0, r) (at most n)."""
    if r <= 0.0:
        return 0
    m = int(r / dx) + 1
    return m if m < n else n


@njit(inline="always", **JIT)
def cells_q(r, q, n):
    """``cells`` given q = r / dx."""
    if r <= 0.0:
        return 0
    m = int(q) + 1
    return m if m < n else n


@njit(inline="always", **JIT)
def shrink_factor(x0, dx, a, a_old):
    """The factor of ``shrink_edge`` for the cell [x0, x0 + dx] that the new edge a < a_old cuts
    (x0 = int(a / dx) dx), the ratio of the same means, both times 3 (one division); 1 where the cell keeps its
    value."""
    l_new = a - x0
    l_old = min(a_old - x0, dx)
    if l_new > 0.0 and l_old > l_new:
        w_old = 3.0 * a_old * a_old - (x0 * x0 + x0 * (x0 + l_old) + (x0 + l_old) * (x0 + l_old))
        if w_old > 0.0:
            return (3.0 * a_old * a_old - (x0 * x0 + x0 * a + a * a)) / w_old
    return 1.0


@njit(inline="always", **JIT)
def initial_width_ldexp(a, n, R):
    """``initial_width`` (R* times the power of 2 with n dx / 2 <= a < n dx) by ``ldexp``: the same value,
    without numba's integer power (a call that could raise, which would keep the array reference counts
    of the 3D kernels)."""
    L = R if R > 0.0 else 1.0
    return math.ldexp(L, int(math.floor(math.log2(2.0 * a / (n * L)))))


#: a cell with |u|^2 > NEAR umax^2 may be beyond its Coulomb circle (the margin covers the rounding of |u|^2)
NEAR = 1.0 - 1e-9


@njit(inline="always", **JIT)
def radial(u1, u2, umax):
    """Local Coulomb circle |u| <= umax of an MDR cell: radial return (direction kept)."""
    m2 = u1 * u1 + u2 * u2
    if m2 > umax * umax:
        s = umax / math.sqrt(m2)
        return u1 * s, u2 * s
    return u1, u2


@njit(inline="always", **JIT)
def new_frame(nx, ny, nz, ddx, ddy, ddz):
    """First axis of a new frame of the tangent plane: along the slip, or any axis of the plane."""
    ex, ey, ez = carry_unit(ddx, ddy, ddz, nx, ny, nz, 1.0, 0.0)
    if ex == 0.0 and ey == 0.0 and ez == 0.0:
        if abs(nx) < 0.9:
            ex, ey, ez = carry_unit(1.0, 0.0, 0.0, nx, ny, nz, 1.0, 0.0)
        else:
            ex, ey, ez = carry_unit(0.0, 1.0, 0.0, nx, ny, nz, 1.0, 0.0)
    return ex, ey, ez


@njit(inline="always", **JIT)
def mdr_frame(ex, ey, ez, nx, ny, nz, ddx, ddy, ddz, cs, sn):
    """Frame (e1, e2 = n x e1) of the vector MDR cells: e1 carried into the current plane and turned with
    the contact, which carries the whole cell field rigidly; a new frame (e1 = 0) is along the slip, or
    any axis of the tangent plane. Returns (e1, e2, dd . e1, dd . e2)."""
    ex, ey, ez = carry_unit(ex, ey, ez, nx, ny, nz, cs, sn)
    if ex == 0.0 and ey == 0.0 and ez == 0.0:
        ex, ey, ez = new_frame(nx, ny, nz, ddx, ddy, ddz)
    fx = ny * ez - nz * ey
    fy = nz * ex - nx * ez
    fz = nx * ey - ny * ex
    return ex, ey, ez, fx, fy, fz, ddx * ex + ddy * ey + ddz * ez, ddx * fx + ddy * fy + ddz * fz


@njit(inline="always", **JIT)
def _released(H, c, b, k0, a, a_old, dx, n):
    """The contact is over: its cells, frame, force and work (the slots b + W_X ... k0 - 1) cleared."""
    if dx > 0.0:
        for j in range(2 * max(cells(a, dx, n), cells(a_old, dx, n))):
            put(H, c, k0 + j, 0.0)
    for j in range(b + W_X, k0):
        put(H, c, j, 0.0)


@njit(inline="always", **JIT)
def _zone_dissolved(H, c, b, k0, lazy, D1, D2):
    """The sticking zone's cells take their displacement u = v + D, and the zone is cleared."""
    for i in range(lazy):
        put(H, c, k0 + 2 * i, at(H, c, k0 + 2 * i) + D1)
        put(H, c, k0 + 2 * i + 1, at(H, c, k0 + 2 * i + 1) + D2)
    for j in range(R_LAZY, R_CELLS_ADAPTIVE):
        put(H, c, b + j, 0.0)


@njit(inline="always", **JIT)
def _regrid(H, c, b, k0, n, dx, a, a_old, R):
    """The adaptive grid of the planar law for the contact radius a (its merge, split and shrink-edge rules on
    both components; a grid set up at first contact): (dx, a_old), the cell width now and the old radius
    (0 for a new grid)."""
    if dx <= 0.0 or a_old <= 0.0:
        for j in range(2 * n):
            put(H, c, k0 + j, 0.0)
        a_old = 0.0
        dx = initial_width_ldexp(a, n, R)
        put(H, c, b + R_DX, dx)
    if a > n * dx or (4.0 * a < n * dx and 4.0 * a_old < n * dx):
        while a > n * dx:
            for j in range(n // 2):
                x0 = 2 * j * dx
                u1 = merged(at(H, c, k0 + 4 * j), at(H, c, k0 + 4 * j + 2), a_old, x0, dx)
                u2 = merged(at(H, c, k0 + 4 * j + 1), at(H, c, k0 + 4 * j + 3), a_old, x0, dx)
                put(H, c, k0 + 2 * j, u1)
                put(H, c, k0 + 2 * j + 1, u2)
            for j in range(2 * (n // 2), 2 * n):
                put(H, c, k0 + j, 0.0)
            dx *= 2.0
        while 4.0 * a < n * dx and 4.0 * a_old < n * dx:
            hdx = 0.5 * dx
            for j in range(n // 2 - 1, -1, -1):
                u10, u11 = halves(at(H, c, k0 + 2 * j), a_old, j * dx, hdx)
                u20, u21 = halves(at(H, c, k0 + 2 * j + 1), a_old, j * dx, hdx)
                put(H, c, k0 + 4 * j, u10)
                put(H, c, k0 + 4 * j + 1, u20)
                put(H, c, k0 + 4 * j + 2, u11)
                put(H, c, k0 + 4 * j + 3, u21)
            dx *= 0.5
        put(H, c, b + R_DX, dx)
    return dx, a_old


@njit(inline="always", **JIT)
def _truncated_cells(H, c, k0, full, dx, a, kt, umax_per_w, d1, d2):
    """The cells wholly in contact under the truncated profile: u += d, returned radially to the circle of the
    cell's mean line load. (S1, S2, Q0): the sums of u and the integral of the line load up to the cells'
    end."""
    S1 = 0.0
    S2 = 0.0
    Q0 = 0.0
    for i in range(full):
        k = k0 + 2 * i
        Q1 = truncated_integral_vector((i + 1) * dx, a, kt)
        umax = umax_per_w * (Q1 - Q0) / dx
        Q0 = Q1
        u1, u2 = radial(at(H, c, k) + d1, at(H, c, k + 1) + d2, umax)
        put(H, c, k, u1)
        put(H, c, k + 1, u2)
        S1 += u1
        S2 += u2
    return S1, S2, Q0


@njit(inline="always", **JIT)
def _zone_step(H, c, b, k0, lazy, umax_per_w, a2, dx2, d1, d2):
    """The sticking zone of ``lazy`` cells advanced by d in O(1) if it provably sticks (its test, see
    ``_vector``), else dissolved: (lazy, L1, L2), the zone's cells now and the sums of their u (0 if none)."""
    L1 = 0.0
    L2 = 0.0
    D1 = at(H, c, b + R_D1) + d1
    D2 = at(H, c, b + R_D2) + d2
    Ks = at(H, c, b + R_KS)
    G0 = at(H, c, b + R_G0)
    wl = 3.0 * (lazy - 1) * lazy + 1.0
    e = min(QNEAR * umax_per_w * (a2 - dx2) - G0 + Ks * dx2,
            QNEAR * umax_per_w * (a2 - dx2 * wl) - G0 + Ks * dx2 * wl)
    if e >= 0.0 and e * e >= D1 * D1 + D2 * D2:
        put(H, c, b + R_D1, D1)
        put(H, c, b + R_D2, D2)
        L1 = at(H, c, b + R_SV1) + lazy * D1
        L2 = at(H, c, b + R_SV2) + lazy * D2
    else:
        _zone_dissolved(H, c, b, k0, lazy, D1 - d1, D2 - d2)
        lazy = 0
    return lazy, L1, L2


@njit(inline="always", **JIT)
def _sticking_cells(H, c, k0, lazy, full, umax_per_w, a2, dx2, d1, d2):
    """The cells lazy ... full - 1 (wholly in contact, full profile) in a loop without square roots: u += d,
    and a flag for any cell near or beyond its circle; if flagged, the cells before the first such cell keep
    their values and the radial return acts from it on. The mean of a^2 - x^2 over cell i is a^2 - dx^2 w3 / 3
    with w3 = 3 i (i + 1) + 1 (exact in floating point). (S1, S2, i0): the sums of u and the first cell near
    its circle (full: none)."""
    S1 = 0.0
    S2 = 0.0
    w3 = 3.0 * lazy * (lazy + 1) + 1.0
    step = 6.0 * (lazy + 1)
    near = False
    i0 = full
    for i in range(lazy, full):
        k = k0 + 2 * i
        umax = umax_per_w * (a2 - dx2 * w3)
        w3 += step
        step += 6.0
        u1 = at(H, c, k) + d1
        u2 = at(H, c, k + 1) + d2
        put(H, c, k, u1)
        put(H, c, k + 1, u2)
        S1 += u1
        S2 += u2
        near |= u1 * u1 + u2 * u2 > NEAR * (umax * umax)
    if near:
        S1 = 0.0
        S2 = 0.0
        w3 = 3.0 * lazy * (lazy + 1) + 1.0
        step = 6.0 * (lazy + 1)
        i0 = lazy
        while i0 < full:
            k = k0 + 2 * i0
            u1 = at(H, c, k)
            u2 = at(H, c, k + 1)
            umax = umax_per_w * (a2 - dx2 * w3)
            if u1 * u1 + u2 * u2 > NEAR * (umax * umax):
                break
            w3 += step
            step += 6.0
            S1 += u1
            S2 += u2
            i0 += 1
        for i in range(i0, full):
            k = k0 + 2 * i
            umax = umax_per_w * (a2 - dx2 * w3)
            w3 += step
            step += 6.0
            u1, u2 = radial(at(H, c, k), at(H, c, k + 1), umax)
            put(H, c, k, u1)
            put(H, c, k + 1, u2)
            S1 += u1
            S2 += u2
    return S1, S2, i0


@njit(inline="always", **JIT)
def _new_zone(H, c, b, k0, i0, umax_per_w, a2, dx2):
    """A new sticking zone: the cells 0 ... i0 - 1 before the first one near its circle (``_vector``)."""
    smin = math.inf
    V1 = 0.0
    V2 = 0.0
    w3 = 1.0
    step = 6.0
    for i in range(i0):
        k = k0 + 2 * i
        umax = umax_per_w * (a2 - dx2 * w3)
        w3 += step
        step += 6.0
        u1 = at(H, c, k)
        u2 = at(H, c, k + 1)
        V1 += u1
        V2 += u2
        smin = min(smin, umax - math.sqrt(u1 * u1 + u2 * u2))
    put(H, c, b + R_LAZY, i0)
    put(H, c, b + R_D1, 0.0)
    put(H, c, b + R_D2, 0.0)
    put(H, c, b + R_SV1, V1)
    put(H, c, b + R_SV2, V2)
    put(H, c, b + R_KS, umax_per_w)
    put(H, c, b + R_G0, umax_per_w * a2 - smin)


@njit(inline="always", **JIT)
def _edge_cells(H, c, k0, full, m, dx, a, a_old, kt, umax_per_w, d1, d2, T1, T2, Q0):
    """The cells full ... m - 1, cut by the old or the new edge: the part entering during the step takes the
    increment after its entry (``mdr._advance``), each cell is returned radially to the circle of its mean
    line load over its part in contact. (T1, T2) with their sums of u times that part added."""
    a2 = a * a
    da = a - a_old
    for i in range(full, m):
        k = k0 + 2 * i
        x0 = i * dx
        l_new = min(max(a - x0, 0.0), dx)
        if l_new <= 0.0:
            put(H, c, k, 0.0)
            put(H, c, k + 1, 0.0)
            continue
        l_old = min(max(a_old - x0, 0.0), dx)
        u1 = at(H, c, k) + d1
        u2 = at(H, c, k + 1) + d2
        if l_new > l_old:
            xm = x0 + 0.5 * (l_old + l_new)
            f = (a - xm) / da * (l_new - l_old)
            il = 1.0 / l_new
            u1 = (u1 * l_old + d1 * f) * il
            u2 = (u2 * l_old + d2 * f) * il
        x1 = x0 + l_new
        if kt < 1.0:
            Q1 = truncated_integral_vector(x1, a, kt)
            wbar = (Q1 - Q0) / l_new
            Q0 = Q1
        else:
            wbar = a2 - (x0 * x0 + x0 * x1 + x1 * x1) / 3.0
        u1, u2 = radial(u1, u2, umax_per_w * wbar)
        put(H, c, k, u1)
        put(H, c, k + 1, u2)
        T1 += u1 * l_new
        T2 += u2 * l_new
    return T1, T2


def _vector(params, row, H, c, b, Np, a, fstar, nx, ny, nz, ddx, ddy, ddz, cs, sn):
    """Vector MDR (Popov & Hess 2015 with a displacement vector per cell), on the fixed grid of ``mdr`` or
    (the global ADAPTIVE, bound by ``vector_form``) the grid that follows the contact. Returns T (tx, ty, tz):
    NaN where the contact outgrows the fixed grid.

    The cells hold 2D displacements in a frame (e1, e2 = n x e1) of the tangent plane (``mdr_frame``).
    The slip increment in the frame, (dd . e1, dd . e2), is added to every cell in contact, with the entry
    and exit of ``mdr._advance``, and each cell is returned radially to its Coulomb circle |G_M u| <= mu q
    with the cell mean of the line load q of ``mdr._advance`` (the Hertz pressure truncated at p_y during
    Thornton's plastic loading, ``truncation``). The adaptive grid: that of the planar adaptive law (cell
    width in the history; ``merged``, ``halves``, ``shrink_factor`` and ``initial_width_ldexp``).

    Adaptive grid, sticking zone: the same arithmetic, with the inner cells that provably stick advanced
    in O(1). After a step that updated every cell, the cells 0 ... j - 1 before the first one near its
    circle (j >= LAZY_MIN) form a zone: each then holds v = u - D with D = 0, the history keeps the sum of
    v over the zone, K_s = umax per w (``coulomb_per_w``) and G0 = K_s a^2 - min (umax - |u|) over the
    zone. At a later step every cell of the zone is still inside the contact and |u_i| <= |u_i(set-up)| +
    |D + d|; its circle is umax_i = K (a^2 - dx^2 w_i / 3) (w_i = 3 i (i + 1) + 1), so the zone sticks if
    QNEAR K (a^2 - dx^2 w / 3) - G0 + K_s dx^2 w / 3 >= |D + d| at both ends w_0, w_(j-1) of the zone (the
    left side is linear in w): then D += d advances it (u += d of each cell, as the cell-by-cell loop
    does for a cell that sticks) and it adds sum v + j D to T. Otherwise, and before a regrid, a
    truncated profile or a contact that no longer covers the zone, each cell takes u = v + D and the zone
    is dissolved. In a dense packing most cells stick at most steps: they cost nothing then."""
    # Every parameter is read first and the history row last, on every path: numba's reference-count
    # pruning then removes the increments of the two arrays (which would cost two atomic operations per
    # contact); so the law has one exit and calls only functions that are inlined. The row is read and written
    # through ``at`` and ``put`` (every index here is >= 0, the row's values clamped where they give one: no
    # handling of negative ones in the cell loops).
    E = params[row, P_ESTAR]
    R = params[row, P_RSTAR]
    G = params[row, P_GSTAR]
    mu = params[row, P_MU]
    p_y = params[row, P_PY]
    profile = params[row, P_MDR_PROFILE]
    n = int(params[row, P_NSPRING])
    dx = params[row, P_DX]
    a_old = at(H, c, V_A)
    if a_old < 0.0:     # (only in a corrupted row)
        a_old = 0.0
    k0 = b + R_CELLS
    if ADAPTIVE:
        dx = at(H, c, b + R_DX)
    tx = 0.0
    ty = 0.0
    tz = 0.0
    if Np <= 0.0 or a * a * a <= 0.0:      # (a^3 underflows at the touch overlap 1e-300 m: no contact)
        _released(H, c, b, k0, a, a_old, dx, n)
    elif not ADAPTIVE and a > n * dx:
        tx = math.nan
        ty = math.nan
        tz = math.nan
    else:
        ex, ey, ez, fx, fy, fz, d1, d2 = mdr_frame(at(H, c, b + W_X), at(H, c, b + W_Y), at(H, c, b + W_Z),
                                                   nx, ny, nz, ddx, ddy, ddz, cs, sn)
        kt = truncation(profile, p_y, fstar, Np, a, E, R)
        lazy = 0
        if ADAPTIVE:
            lazy = min(max(int(at(H, c, b + R_LAZY)), 0), n)     # (in [0, n] unless the row was corrupted)
            if lazy > 0 and (kt < 1.0 or a > n * dx or 4.0 * a < n * dx or min(a, a_old) < lazy * dx):
                # the cells of the sticking zone take their displacement u = v + D before anything else acts
                _zone_dissolved(H, c, b, k0, lazy, at(H, c, b + R_D1), at(H, c, b + R_D2))
                lazy = 0
            dx, a_old = _regrid(H, c, b, k0, n, dx, a, a_old, R)
        # cells in contact: qa = a / dx and qo = a_old / dx give the cell counts and the cut cell
        idx = 1.0 / dx
        qa = a * idx
        qo = a_old * idx
        m = max(cells_q(a, qa, n), cells_q(a_old, qo, n))
        full = min(int(min(qa, qo)), m)
        if ADAPTIVE and a < a_old:
            # mdr.shrink_edge: the cell cut by the new edge (i = int(a / dx), the first partial cell)
            i = int(qa)
            if i < n:
                f = shrink_factor(i * dx, dx, a, a_old)
                if f != 1.0:
                    put(H, c, k0 + 2 * i, at(H, c, k0 + 2 * i) * f)
                    put(H, c, k0 + 2 * i + 1, at(H, c, k0 + 2 * i + 1) * f)
        # the cells: the arithmetic of mdr._advance with a 2D displacement per cell and radial return
        GM = 4.0 * G
        umax_per_w = coulomb_per_w(mu, E, G, R, Np, a, kt)
        a2 = a * a
        dx2 = dx * dx / 3.0
        Q0 = 0.0      # truncated profile: the integral of the line load up to the cell's lower edge
        if kt < 1.0:
            S1, S2, Q0 = _truncated_cells(H, c, k0, full, dx, a, kt, umax_per_w, d1, d2)
        else:
            L1 = 0.0
            L2 = 0.0
            if lazy > 0:
                lazy, L1, L2 = _zone_step(H, c, b, k0, lazy, umax_per_w, a2, dx2, d1, d2)
            S1, S2, i0 = _sticking_cells(H, c, k0, lazy, full, umax_per_w, a2, dx2, d1, d2)
            if ADAPTIVE and lazy == 0 and i0 >= LAZY_MIN:
                _new_zone(H, c, b, k0, i0, umax_per_w, a2, dx2)
            S1 += L1
            S2 += L2
        T1, T2 = _edge_cells(H, c, k0, full, m, dx, a, a_old, kt, umax_per_w, d1, d2, S1 * dx, S2 * dx, Q0)
        T1 *= 2.0 * GM
        T2 *= 2.0 * GM
        work = 0.5 * ((at(H, c, b + R_T1) + T1) * d1 + (at(H, c, b + R_T2) + T2) * d2)
        put(H, c, b + W_WORK, at(H, c, b + W_WORK) + work)
        put(H, c, b + W_X, ex)
        put(H, c, b + W_Y, ey)
        put(H, c, b + W_Z, ez)
        put(H, c, b + R_T1, T1)
        put(H, c, b + R_T2, T2)
        tx = T1 * ex + T2 * fx
        ty = T1 * ey + T2 * fy
        tz = T1 * ez + T2 * fz
    return tx, ty, tz


def vector_form(name, adaptive):
    """The 3D kernel of the law on the fixed grid, or (``adaptive``) on the grid that follows the contact."""
    return njit(inline="always", **JIT)(renamed(_vector, f"vector_{name}", ADAPTIVE=adaptive,
                                                R_CELLS=R_CELLS_ADAPTIVE if adaptive else R_CELLS))


#: the fixed grid
ADAPTIVE = False
vector = vector_form(NAME, ADAPTIVE)
