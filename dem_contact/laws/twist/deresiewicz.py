"""Twist of a Hertz contact about its normal, exact: Lubkin (1951) on loading, Deresiewicz (1954) on
unloading and reversal, and any history of twist and normal force, by a reduction to independent springs.

The problem. A relative rotation beta of the bodies about the common normal of a contact of radius a and
normal pressure p(r) (axisymmetric) is resisted by a circumferential traction q(r) with |q| <= mu p
(Coulomb, pointwise). The circumferential traction raises no normal displacement, so the twist is
uncoupled from the normal problem for any pair of materials, and its compliance is that of the shear
moduli alone: 1/G_c = 1/G1 + 1/G2 (a rigid body adds nothing).

Flat-punch superposition (Jaeger 1995, Arch. Appl. Mech. 65:478; Popov & Hess 2015, "Method of
Dimensionality Reduction in Contact Mechanics and Friction", the superposition of rigid flat punches
behind their tangential and torsional solutions). A rigid flat punch of radius s twisted by phi is
held by the traction tau = (4 G_c phi / pi) r / sqrt(s^2 - r^2) on r < s (Reissner & Sagoci 1944), and
turns every point r < s rigidly by phi; its torque is (16/3) G_c s^3 phi (the no-slip stiffness of
Johnson 1985, eq. 7.43, with 1/G_c = 1/G1 + 1/G2). Write any axisymmetric circumferential traction as a
sum of such punches, q(r) = r int_r^a g(s) / sqrt(s^2 - r^2) ds, and let h(s) = int_s^a g(t) dt. Then

- the twist of the points r < c is rigid (the same angle) exactly when g = 0 on s < c, i.e. h is constant
  there, and that angle is beta = pi h(c) / (4 G_c): h(s) = k theta(s) with k = 4 G_c / pi, the spring
  law of a row of independent springs over the punch radius s, each turned by the rigid twist beta while
  it sticks;
- the traction is q = mu p on r > c exactly when h = mu L on s > c, with L the same transform of p:
  L(s) = (2/pi) int_s^a p(t) / sqrt(t^2 - s^2) dt (Abel inversion). For the Hertz pressure
  p = p0 sqrt(1 - r^2/a^2), L(s) = (2 p0 / pi) (K(k) - E(k)), k^2 = 1 - s^2/a^2 (complete elliptic
  integrals: the integrals of Lubkin's solution); L grows without bound (logarithmically) at s -> 0:
  the centre never slips;
- the moment is M = 4 pi int_0^a s^2 h(s) ds (integrating the punch torques by parts).

So the torsion problem maps onto springs over s with stiffness k and local Coulomb limit |h(s)| <= mu L(s)
(the torsional form of the method of dimensionality reduction: the same independent springs as for the
tangential problem, with another coordinate, s, another weight, 4 pi s^2, and another limit profile, L
instead of the MDR line load). Monotonic twist: the springs s < c stick (h = k beta), those s > c slide
(h = mu L), with k beta = mu L(c): Lubkin's stick radius, beta = 3 mu N (K - E) / (4 pi a^2 G_c) at
k^2 = 1 - c^2/a^2, and his moment-twist curve (``lubkin``). No slip: M = (16/3) G_c a^3 beta; full slip:
M = 4 pi mu int s^2 L ds = (3 pi / 16) mu N a. Unloading from (beta*, M*): each spring is elastic-plastic,
so the row obeys Masing's rule M = M* - 2 M_L((beta* - beta) / 2) (Deresiewicz 1954), and any later
reversal its extension, with the slip annuli nested from the edge inwards as the exact solution has
them. A varying normal force changes the limit profile mu L(s) under the springs: springs entering the
contact start unstrained, springs leaving it are released, springs above a lowered limit slide. This is
the spring-by-spring memory of the MDR tangential laws (``laws.tangential.mdr``). It is exact where the
3D solution is a stick disc inside nested annuli each at +-mu p or frozen (loading, unloading and
reversal at constant N, a normal force raised at fixed twist: the cases checked in the tests); for
general histories of N the springs keep |h| <= mu L everywhere, which implies the pointwise 3D Coulomb
inequality only for such nested states: that is the approximation, to be measured against the
boundary-element reference with twist. The springs never create energy (each is elastic-perfectly
plastic; a spring leaving the contact takes its energy with it).

What is not ring-local: the traction at a ring r depends on the springs s >= r (Lubkin's stick traction
carries the 1/sqrt edge of every punch s > c); cells over r with memory per ring would not be exact.
The cells here are over s.

Discretisation (as ``laws.tangential.mdr_adaptive``): n cells of width ds on 0 <= s < n ds, the width a
power of 2 times R* chosen at first contact and halved or doubled as the contact shrinks or grows (cells
merged with the weight s^2 and split into halves at the cell's rotation, M kept; a cell cut by a shrinking
edge keeps its rotation on its part inside). Neither raises the springs' energy 8 G_c sum theta_i^2 w_i (a
half or a part above its lower limit then slides), so the cells never give back more work than they
stored: over any loop of twist and overlap, the work absorbed less the change of that energy is >= 0.
The state of a cell is the s^2-weighted mean theta_i of the spring rotation over its part inside the
contact, its limit the s^2-weighted mean of mu L / k, computed exactly from
J(u) = int_0^u t^2 (K - E)(1 - t^2) dt (a table of ``TABLE_NODES`` values with Hermite interpolation,
built at import from the arithmetic-geometric mean): theta_i max = 3 mu N a (J(u1) - J(u0)) / (4 pi G_c w_i),
w_i = int s^2 ds over the cell's part in contact. M = 16 G_c sum theta_i w_i. A contact stuck everywhere and
one sliding everywhere are then exact for any cell count; partial slip converges at second order in ds.
The limit profile is the Hertz pressure scaled to N (p0 = 3 N / (2 pi a^2)) for every normal law (as
the MDR laws' ``scaled`` profile; during Thornton's plastic loading the true pressure is truncated).

3D slots (relative to the law's base b): the moment M [N m] (the torque on body 1 is -M n, beta turning
body 1 by (w1 - w2) . n dt), the work absorbed int M d beta [J], the cell width [m], then the cells [rad].
Swapping the bodies negates n and w1 - w2, so beta and every slot keep their sign.
"""
import math

import numpy as np
from numba import njit

from ..declare import MU, RSTAR, Param
from ..slots import P_G_TWIST, P_MU, P_RSTAR
from ..tangential.mdr import initial_width_ldexp
from ..vector import JIT, V_A

NAME, FAMILY = "deresiewicz", "twist"
SOURCE = ("Lubkin 1951 (J. Appl. Mech. 18:183), Deresiewicz 1954 (J. Appl. Mech. 21:52): exact, by flat-punch "
          "superposition (Jaeger 1995) on springs over the punch radius")
PARAMETERS = (Param("G_c", "P_G_TWIST", "shear modulus of the twist G_c, 1/G_c = 1/G1 + 1/G2", "Pa"), MU, RSTAR)
STATE = ("M", "work", "ds", "cells")

#: cells over the punch radius s (the contact covers between n/4 and n of them)
TWIST_CELLS = 32
# slots relative to the law's base
Q_M = 0
Q_WORK = 1
Q_DS = 2
Q_CELLS = 3
VECTOR_SLOTS = Q_CELLS + TWIST_CELLS
#: nodes of the table of J(u) on 0 <= u <= 1
TABLE_NODES = 1025
#: margin of the table-free stick test (below the table's rounding, so that it never changes a result)
CLEAR = 1.0 - 1e-9
#: the Scene settings of a typical contact of this law (the contract tests use them)
EXAMPLE = {}


def max_torque(p, N, a):
    """Lubkin's full-slip moment (3 pi / 16) mu N a [N m] (parameter row p, normal force N [N], contact radius
    a [m]): the exact law's moment never exceeds it."""
    return 3.0 * math.pi / 16.0 * p[P_MU] * N * a


def _k_minus_e(u):
    """K(m) - E(m) at m = 1 - u^2 (complete elliptic integrals, parameter m), 0 < u <= 1: the
    arithmetic-geometric mean (Abramowitz & Stegun 17.6)."""
    u = np.asarray(u, dtype=float)
    x, y = np.ones_like(u), u.copy()
    csum = 0.5 * (1.0 - u * u)
    w = 0.5
    for _ in range(40):
        c = 0.5 * (x - y)
        x, y = 0.5 * (x + y), np.sqrt(x * y)
        w *= 2.0
        csum += w * c * c
        if np.all(np.abs(c) < 1e-17):
            break
    K = math.pi / (2.0 * x)
    return K * csum          # K - E = K sum 2^(n-1) c_n^2


def _table(nodes):
    """J(u) = int_0^u t^2 (K - E)(1 - t^2) dt and its derivative at u = i / (nodes - 1): 8-point Gauss on
    each interval."""
    g, wg = np.polynomial.legendre.leggauss(8)
    u = np.linspace(0.0, 1.0, nodes)
    h = u[1] - u[0]
    t = u[:-1, None] + 0.5 * h * (g[None, :] + 1.0)
    parts = (0.5 * h * wg[None, :] * t * t * _k_minus_e(t)).sum(axis=1)
    J = np.concatenate([[0.0], np.cumsum(parts)])
    d = np.zeros(nodes)
    d[1:] = u[1:] ** 2 * _k_minus_e(u[1:])
    return J, d


_J, _DJ = _table(TABLE_NODES)
#: J(1) = pi^2 / 64 (the full-slip moment (3 pi / 16) mu N a)
J_ONE = float(_J[-1])


@njit(inline="always", **JIT)
def jtab(u):
    """J(u) (cubic Hermite in the table; J(1) for u >= 1)."""
    if u >= 1.0:
        return _J[TABLE_NODES - 1]
    x = u * (TABLE_NODES - 1)
    i = int(x)
    t = x - i
    h = 1.0 / (TABLE_NODES - 1)
    t2 = t * t
    t3 = t2 * t
    return ((2.0 * t3 - 3.0 * t2 + 1.0) * _J[i] + (t3 - 2.0 * t2 + t) * h * _DJ[i]
            + (3.0 * t2 - 2.0 * t3) * _J[i + 1] + (t3 - t2) * h * _DJ[i + 1])


@njit(inline="always", **JIT)
def weight(s0, ds, r):
    """int s^2 ds over the part of the cell [s0, s0 + ds] inside the radius r."""
    s1 = min(s0 + ds, r)
    if s1 <= s0:
        return 0.0
    return (s1 * s1 * s1 - s0 * s0 * s0) / 3.0


@njit(inline="always", **JIT)
def advance(H, c, b, n, Gc, mu, R, N, a, a_old, dbeta):
    """One step of the twist springs in the row ``H[c]`` from its slot ``b`` (see the module docstring):
    n cells, G_c [Pa], mu, R* [m] (the grid's scale), normal force N [N] and contact radius a [m] after the
    step, a_old before it, twist increment dbeta [rad]. Returns the moment M [N m] resisting the twist."""
    k0 = b + Q_CELLS
    ds = H[c, b + Q_DS]
    M = 0.0
    if N <= 0.0 or a * a * a <= 0.0:      # no contact: every spring released
        for j in range(n):
            H[c, k0 + j] = 0.0
        H[c, b + Q_DS] = 0.0
    else:
        if ds <= 0.0:                     # first step in contact: a new grid, the springs unstrained
            for j in range(n):
                H[c, k0 + j] = 0.0
            ds = initial_width_ldexp(a, n, R)
        while a > n * ds:                 # the contact outgrows the grid: pairs merged (weight s^2)
            for j in range(n // 2):
                x0 = 2 * j * ds
                w0 = weight(x0, ds, a_old)
                w1 = weight(x0 + ds, ds, a_old)
                v = 0.0
                if w0 + w1 > 0.0:
                    v = (H[c, k0 + 2 * j] * w0 + H[c, k0 + 2 * j + 1] * w1) / (w0 + w1)
                H[c, k0 + j] = v
            for j in range(n // 2, n):
                H[c, k0 + j] = 0.0
            ds *= 2.0
        while 4.0 * a < n * ds and 4.0 * a_old < n * ds:   # much smaller: the lower half split
            # both halves at the cell's rotation (M and the springs' energy kept: an uneven split would
            # raise the energy); a half above its limit slides in the step below
            hd = 0.5 * ds
            for j in range(n // 2 - 1, -1, -1):
                v = H[c, k0 + j]
                H[c, k0 + 2 * j] = v
                H[c, k0 + 2 * j + 1] = v if min((j + 1) * ds, a_old) > j * ds + hd else 0.0
            ds = hd
        H[c, b + Q_DS] = ds
        # the cell cut by a shrinking edge keeps its rotation on its part inside a (the released part takes
        # its energy with it; the part kept slides below if its limit is lower)
        # the springs: + dbeta, entering parts with the part of the increment after their entry, then the
        # limit theta_max = C (J(u1) - J(u0)) / w, C = 3 mu N a / (4 pi G_c) (module docstring)
        C = 3.0 * mu * N * a / (4.0 * math.pi * Gc)
        ia = 1.0 / a
        # a cell sticks without the table when |theta| <= CLEAR C (pi/4)(1 - u1^2) / a^3: K - E >= (pi/4) m
        # (series with positive terms) and the profile decreases, so (pi/4)(1 - u1^2) is below the cell's
        # mean limit (K - E)(1 - u^2) (u1: the cell's outer end over a)
        lo = CLEAR * 0.25 * math.pi * C * ia * ia * ia
        da = a - a_old
        m = int(max(a, a_old) / ds) + 1
        if m > n:
            m = n
        S = 0.0
        J0 = 0.0
        known = True        # J0 = J(x0 / a) of the current cell is known
        for i in range(m):
            k = k0 + i
            x0 = i * ds
            x1 = min(x0 + ds, a)
            if x1 <= x0:
                H[c, k] = 0.0
                continue
            w = (x1 * x1 * x1 - x0 * x0 * x0) / 3.0
            xo = min(x0 + ds, max(a_old, x0))     # end of the part in contact before the step
            th = H[c, k] + dbeta
            if x1 > xo:
                # part [xo, x1] entered during the step: a point entered at the fraction (x - a_old) / da
                wo = (xo * xo * xo - x0 * x0 * x0) / 3.0
                xm = 0.5 * (xo + x1)
                th = (th * wo + dbeta * (a - xm) / da * (w - wo)) / w
            u1 = x1 * ia
            if abs(th) > lo * (1.0 - u1 * u1):
                if not known:
                    J0 = jtab(x0 * ia)
                J1 = jtab(u1)
                tmax = C * (J1 - J0) / w
                J0 = J1
                known = True
                if th > tmax:
                    th = tmax
                elif th < -tmax:
                    th = -tmax
            else:
                known = False
            H[c, k] = th
            S += th * w
        M = 16.0 * Gc * S
        H[c, b + Q_WORK] += 0.5 * (H[c, b + Q_M] + M) * dbeta
    H[c, b + Q_M] = M
    return M


@njit(**JIT)
def twist_path(Gc, mu, R, N, a, beta, n):
    """Moments M [N m] along a path of normal forces N [N], contact radii a [m] and twists beta [rad]
    (arrays, the first row the state before the path, from rest), with n cells; returns (M, work)."""
    H = np.zeros((1, Q_CELLS + n))
    out = np.zeros(N.size)
    work = np.zeros(N.size)
    for t in range(1, N.size):
        out[t] = advance(H, 0, 0, n, Gc, mu, R, N[t], a[t], a[t - 1], beta[t] - beta[t - 1])
        work[t] = H[0, Q_WORK]
    return out, work


@njit(inline="always", **JIT)
def vector(params, row, H, c, b, N, a, nx, ny, nz, wx, wy, wz, dt):
    """Torque on body 1 (x, y, z) [N m], -M n, from the relative spin w = w1 - w2 [rad/s]: the twist
    increment (w . n) dt on the springs of ``advance`` (the contact radius before the step is the row's
    V_A, written after the twist law)."""
    Gc = params[row, P_G_TWIST]
    mu = params[row, P_MU]
    R = params[row, P_RSTAR]
    M = advance(H, c, b, TWIST_CELLS, Gc, mu, R, N, a, H[c, V_A], (wx * nx + wy * ny + wz * nz) * dt)
    return -M * nx, -M * ny, -M * nz


def twist_modulus(body1, body2):
    """G_c [Pa] of a sphere against a sphere or a wall: 1/G_c = 1/G1 + 1/G2 (a rigid body adds nothing)."""
    comp = sum(0.0 if m.is_rigid else 1.0 / m.G for m in (body1.material, body2.material))
    return 1.0 / comp


def configure(scene, p):
    p[P_G_TWIST] = twist_modulus(scene.sphere, scene.body2)


def describe(scene, p):
    return dict(twist_G_c=p[P_G_TWIST], twist_cells=TWIST_CELLS)


