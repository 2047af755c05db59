"""Named loading paths at constant overlap, for comparing tangential and twist laws with the BEM reference.

Sizes are in units of the slip displacement s = 3 mu N / (16 G* a) (Mindlin 1949; Johnson 1985 section 7.2:
the tangential displacement at which a monotonic Cattaneo-Mindlin loading reaches full slip), which for
Hertz contact is s = mu delta E*/(4 G*) = mu delta / kappa, and twists in units of the no-slip twist at
unit moment beta_1 = 3 mu N / (16 G_c a^2) = mu E* a / (4 G_c R*): the twist at which the no-slip moment
(16/3) G_c a^3 beta (Johnson 1985 section 7.4; 1/G_c = 1/G1 + 1/G2, a rigid body adding nothing) would
equal mu N a. (The moment of full slip is (3 pi/16) mu N a = 0.589 mu N a, Lubkin 1951; a monotonic twist
to beta_1 reaches 0.497 mu N a, to 2 beta_1 0.578 mu N a.) Every path starts at the origin (the state at
first contact: no traction, u = 0, no twist) and is sampled with ``steps`` equal arc-length increments
after it (arc length in these units, u/s and twist/beta_1 together), so it has steps + 1 rows.

Tangential shapes (``SHAPES``; rows delta, ux, uy):

- ``load-unload``: along x to +size, back to -size, and again to +size (a Cattaneo-Mindlin-Masing cycle);
- ``circle``: the circle through the origin of radius size, centre (size, 0), once round, counterclockwise
  (u = size (1 - cos phi, sin phi));
- ``load-circle``: along x to (size, 0), then once round the circle of radius size about the origin;
- ``l-turn``: along x to (size, 0), then along y to (size, size) (with size > 1: a turn after full slip);
- ``figure-eight``: the lemniscate of Gerono u = size (sin phi, sin phi cos phi), phi from 0 to 2 pi,
  through the origin, width 2 size.

Twist shapes (``TWIST_SHAPES``; rows delta, ux, uy, twist; the twist: rotation of body 1 relative to body 2 about
the normal n from body 1 to body 2, right-handed):

- ``twist-cycle``: no tangential displacement; the twist goes to +size beta_1, back to -size beta_1 and
  again to +size beta_1 (the Lubkin loading curve, then the Deresiewicz-Masing unloading and reloading
  branches; a closed loop from the first reversal on). Default size 2: "a twist cycle to twice the no-slip
  twist at unit moment and back";
- ``shear-twist``: along x to (size, 0) with no twist, then, at that u, a twist out to +beta_1 and back to
  0. Default size 0.6: "shear to 0.6 of slip, then a twist out and back" (the amplitude of the twist, one
  beta_1, is fixed; alone it would take the moment to 0.497 mu N a, 84% of full slip);
- ``circle-twist``: the ``circle`` shape of radius size (through the origin, once round) with the twist
  size beta_1 sin(2 phi): two twist oscillations per turn, of the same amplitude in its unit as the circle's
  radius. Default size 0.4: "a circle of radius 0.4 with a twist oscillating twice per turn".
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from ..materials import check_finite

SHAPES = ("load-unload", "circle", "load-circle", "l-turn", "figure-eight")
#: Named paths with a twist column (rows delta, ux, uy, twist).
TWIST_SHAPES = ("twist-cycle", "shear-twist", "circle-twist")
#: Size of each named path when none is given.
DEFAULT_SIZES = {"load-unload": 1.0, "circle": 0.6, "load-circle": 0.6, "l-turn": 1.5, "figure-eight": 0.6,
                 "twist-cycle": 2.0, "shear-twist": 0.6, "circle-twist": 0.4}
#: Sizes (in slip displacements) of the comparison set of curved paths.
COMPARISON_SET = (("circle", 0.3), ("circle", 0.6), ("load-circle", 0.5), ("l-turn", 1.5), ("figure-eight", 0.6))
#: The comparison set of twist paths (sizes in slip displacements and in beta_1).
TWIST_SET = (("twist-cycle", 2.0), ("shear-twist", 0.6), ("circle-twist", 0.4))

_DENSE = 20000


def slip_displacement(delta, mu, kappa):
    """Tangential displacement at full slip of a Hertz contact at overlap delta [m]: mu delta / kappa
    (= 3 mu N / (16 G* a), Johnson 1985 section 7.2), kappa = 4 G*/E*."""
    return mu * delta / kappa


def twist_modulus(E1, nu1, E2, nu2):
    """G_c [Pa] of the twist of two bodies: 1/G_c = 1/G1 + 1/G2, G = E / (2 (1 + nu)), a rigid body
    (E = inf) adding nothing (Johnson 1985 section 7.4: the twist traction is circumferential, Poisson's
    ratio does not enter)."""
    inv = sum(2.0 * (1.0 + nu) / E for E, nu in ((E1, nu1), (E2, nu2)) if not math.isinf(E))
    if inv <= 0.0:
        raise InputError("two rigid bodies have no twist stiffness")
    return 1.0 / inv


def no_slip_twist(delta, mu, R_star, E_star, G_c):
    """The twist [rad] at which the no-slip moment (16/3) G_c a^3 beta (Johnson 1985 section 7.4) of a
    Hertz contact at overlap delta [m] would equal mu N a: beta_1 = 3 mu N / (16 G_c a^2) = mu E* a / (4 G_c R*),
    a = sqrt(R* delta)."""
    return mu * E_star * math.sqrt(R_star * delta) / (4.0 * G_c * R_star)


def _pieces(shape, size):
    """The shape as smooth pieces (dense polylines, rows x, y[, twist]) in units of the slip displacement
    (and of beta_1); the corners between pieces are kept as sample points."""
    phi = np.linspace(0.0, 2.0 * math.pi, _DENSE)
    line = np.linspace(0.0, 1.0, 2)[:, None]
    if shape == "load-unload":
        return [line * [size, 0.0], [size, 0.0] - 2.0 * line * [size, 0.0], [-size, 0.0] + 2.0 * line * [size, 0.0]]
    if shape == "circle":
        return [size * np.column_stack([1.0 - np.cos(phi), np.sin(phi)])]
    if shape == "load-circle":
        return [line * [size, 0.0], size * np.column_stack([np.cos(phi), np.sin(phi)])]
    if shape == "l-turn":
        return [line * [size, 0.0], [size, 0.0] + line * [0.0, size]]
    if shape == "figure-eight":
        return [size * np.column_stack([np.sin(phi), np.sin(phi) * np.cos(phi)])]
    if shape == "twist-cycle":
        return [line * [0.0, 0.0, size], [0.0, 0.0, size] - 2.0 * line * [0.0, 0.0, size],
                [0.0, 0.0, -size] + 2.0 * line * [0.0, 0.0, size]]
    if shape == "shear-twist":
        return [line * [size, 0.0, 0.0], [size, 0.0, 0.0] + line * [0.0, 0.0, 1.0],
                [size, 0.0, 1.0] - line * [0.0, 0.0, 1.0]]
    if shape == "circle-twist":
        return [size * np.column_stack([1.0 - np.cos(phi), np.sin(phi), np.sin(2.0 * phi)])]
    raise InputError(f"shape {shape!r} is unknown; choose one of: {', '.join(SHAPES + TWIST_SHAPES)}")


def _sample(shape, size, steps):
    """Rows of the named path in its units: steps + 1 rows from the origin, 2 or 3 columns."""
    size = check_finite("size (path size, in slip displacements)", size, lo=0.0, hi=1e6)
    pieces = _pieces(shape, size)
    if isinstance(steps, bool) or int(steps) != steps or not len(pieces) <= steps <= 10**7:
        raise InputError(f"steps = {steps!r} must be an integer in [{len(pieces)}, 1e7] for {shape!r}")

    def arc(pc):
        return np.sqrt(np.sum(np.diff(pc, axis=0) ** 2, axis=1))
    lengths = np.array([arc(pc).sum() for pc in pieces])
    share = np.maximum(1, np.floor(steps * lengths / lengths.sum())).astype(int)
    order = np.argsort(-(steps * lengths / lengths.sum() - share))
    for i in range(int(steps) - share.sum()):
        share[order[i % len(pieces)]] += 1
    cols = pieces[0].shape[1]
    out = [np.zeros((1, cols))]
    for pc, k in zip(pieces, share):
        s = np.concatenate([[0.0], np.cumsum(arc(pc))])
        target = np.linspace(0.0, s[-1], k + 1)[1:]
        out.append(np.column_stack([np.interp(target, s, pc[:, j]) for j in range(cols)]))
    return np.vstack(out)


def unit_path(shape, size, steps):
    """(ux, uy) of the named tangential path in units of the slip displacement: steps + 1 rows from the
    origin. The steps are shared among the pieces of the path in proportion to their lengths (corners are
    rows), with equal arc-length increments within a piece. (``unit_twist_path`` for the twist shapes.)"""
    if shape in TWIST_SHAPES:
        raise InputError(f"shape {shape!r} has a twist: use unit_twist_path")
    rows = _sample(shape, size, steps)
    return rows[:, 0].copy(), rows[:, 1].copy()


def unit_twist_path(shape, size, steps):
    """(ux, uy, twist) of any named path, displacements in slip displacements and the twist in beta_1
    (zero for the tangential shapes): steps + 1 rows from the origin, equal arc-length increments in these
    units within each piece."""
    rows = _sample(shape, size, steps)
    if rows.shape[1] == 2:
        return rows[:, 0].copy(), rows[:, 1].copy(), np.zeros(rows.shape[0])
    return rows[:, 0].copy(), rows[:, 1].copy(), rows[:, 2].copy()


def named_path(shape, size, steps, *, delta, mu, kappa, twist_unit=None):
    """The named path at constant overlap ``delta`` [m]: steps + 1 rows, displacements scaled by the slip
    displacement mu delta / kappa. A tangential shape gives (delta, ux, uy) [m]; a twist shape (delta, ux,
    uy, twist) [m, rad], the twist scaled by ``twist_unit`` [rad] (beta_1, ``no_slip_twist``), which it
    needs."""
    delta = check_finite("delta (overlap, m)", delta, lo=0.0)
    mu = check_finite("mu (friction coefficient)", mu, lo=0.0)
    kappa = check_finite("kappa (tangential to normal stiffness ratio)", kappa, lo=0.0)
    s = slip_displacement(delta, mu, kappa)
    if shape in TWIST_SHAPES:
        if twist_unit is None:
            raise InputError(f"the path {shape!r} has a twist: give twist_unit (beta_1 [rad], no_slip_twist)")
        twist_unit = check_finite("twist_unit (no-slip twist at unit moment, rad)", twist_unit, lo=0.0)
        ux, uy, tw = unit_twist_path(shape, size, steps)
        return np.full(ux.size, delta), s * ux, s * uy, twist_unit * tw
    ux, uy = unit_path(shape, size, steps)
    return np.full(ux.size, delta), s * ux, s * uy


def scene_path(shape, size, steps, scene, delta):
    """``named_path`` with mu, kappa and (for a twist shape) beta_1 of a ``Scene`` (dem_contact.laws.model)."""
    twist_unit = None
    if shape in TWIST_SHAPES:
        m1, m2 = scene.sphere.material, scene.body2.material
        twist_unit = no_slip_twist(delta, scene.mu, scene.pair.R_star, scene.pair.E_star,
                                   twist_modulus(m1.E, m1.nu, m2.E, m2.nu))
    return named_path(shape, size, steps, delta=delta, mu=scene.mu, kappa=scene.pair.kappa, twist_unit=twist_unit)
