"""Named tangential loading paths at constant overlap, for comparing tangential laws with the BEM reference.

Sizes are in units of the slip displacement s = 3 mu N / (16 G* a) (Mindlin 1949; Johnson 1985 section 7.2:
the tangential displacement at which a monotonic Cattaneo-Mindlin loading reaches full slip), which for
Hertz contact is s = mu delta E*/(4 G*) = mu delta / kappa. Every path starts at the origin (the state
at first contact: no traction, u = 0) and is sampled with ``steps`` equal arc-length increments after it,
so it has steps + 1 rows.

Shapes:

- ``load-unload``: along x to +size, back to -size, and again to +size (a Cattaneo-Mindlin-Masing cycle);
- ``circle``: the circle through the origin of radius size, centre (size, 0), once round, counterclockwise
  (u = size (1 - cos phi, sin phi));
- ``load-circle``: along x to (size, 0), then once round the circle of radius size about the origin;
- ``l-turn``: along x to (size, 0), then along y to (size, size) (with size > 1: a turn after full slip);
- ``figure-eight``: the lemniscate of Gerono u = size (sin phi, sin phi cos phi), phi from 0 to 2 pi,
  through the origin, width 2 size.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from ..materials import check_finite

SHAPES = ("load-unload", "circle", "load-circle", "l-turn", "figure-eight")
#: Sizes (in slip displacements) of the comparison set of curved paths.
COMPARISON_SET = (("circle", 0.3), ("circle", 0.6), ("load-circle", 0.5), ("l-turn", 1.5), ("figure-eight", 0.6))

_DENSE = 20000


def slip_displacement(delta, mu, kappa):
    """Tangential displacement at full slip of a Hertz contact at overlap delta [m]: mu delta / kappa
    (= 3 mu N / (16 G* a), Johnson 1985 section 7.2), kappa = 4 G*/E*."""
    return mu * delta / kappa


def _pieces(shape, size):
    """The shape as smooth pieces (dense polylines, rows x, y) in units of the slip displacement; the
    corners between pieces are kept as sample points."""
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
    raise InputError(f"shape {shape!r} is unknown; choose one of: {', '.join(SHAPES)}")


def unit_path(shape, size, steps):
    """(ux, uy) of the named path in units of the slip displacement: steps + 1 rows from the origin. The
    steps are shared among the pieces of the path in proportion to their lengths (corners are rows), with
    equal arc-length increments within a piece."""
    size = check_finite("size (path size, in slip displacements)", size, lo=0.0)
    pieces = _pieces(shape, size)
    if isinstance(steps, bool) or int(steps) != steps or not len(pieces) <= steps <= 10**7:
        raise InputError(f"steps = {steps!r} must be an integer in [{len(pieces)}, 1e7] for {shape!r}")
    lengths = np.array([np.hypot(*np.diff(pc, axis=0).T).sum() for pc in pieces])
    share = np.maximum(1, np.floor(steps * lengths / lengths.sum())).astype(int)
    order = np.argsort(-(steps * lengths / lengths.sum() - share))
    for i in range(int(steps) - share.sum()):
        share[order[i % len(pieces)]] += 1
    xs, ys = [np.zeros(1)], [np.zeros(1)]
    for pc, k in zip(pieces, share):
        s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pc, axis=0).T))])
        target = np.linspace(0.0, s[-1], k + 1)[1:]
        xs.append(np.interp(target, s, pc[:, 0]))
        ys.append(np.interp(target, s, pc[:, 1]))
    return np.concatenate(xs), np.concatenate(ys)


def named_path(shape, size, steps, *, delta, mu, kappa):
    """(delta, ux, uy) arrays [m] of the named path at constant overlap ``delta`` [m]: steps + 1 rows,
    displacements scaled by the slip displacement mu delta / kappa."""
    delta = check_finite("delta (overlap, m)", delta, lo=0.0)
    mu = check_finite("mu (friction coefficient)", mu, lo=0.0)
    kappa = check_finite("kappa (tangential to normal stiffness ratio)", kappa, lo=0.0)
    ux, uy = unit_path(shape, size, steps)
    s = slip_displacement(delta, mu, kappa)
    return np.full(ux.size, delta), s * ux, s * uy


def scene_path(shape, size, steps, scene, delta):
    """``named_path`` with mu and kappa of a ``Scene`` (dem_contact.laws.model)."""
    return named_path(shape, size, steps, delta=delta, mu=scene.mu, kappa=scene.pair.kappa)
