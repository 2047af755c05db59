"""Checks of the walls' user input shared by the kinds: vectors, unit vectors, the rigid motion."""
from __future__ import annotations

import math

from ..errors import InputError

#: tolerance on |unit vector| - 1
UNIT_TOL = 1e-12


def vector(k, name, value):
    """3 finite numbers (a tuple of floats), else InputError naming walls[k].name."""
    try:
        t = tuple(float(c) for c in value)
    except (TypeError, ValueError):
        raise InputError(f"walls[{k}].{name} must be 3 finite numbers, got {value!r}") from None
    if len(t) != 3 or not all(math.isfinite(c) for c in t):
        raise InputError(f"walls[{k}].{name} must be 3 finite numbers, got {value!r}")
    return t


def unit(k, name, value):
    """A unit vector (| |n| - 1 | <= UNIT_TOL), else InputError."""
    n = vector(k, name, value)
    norm = math.sqrt(sum(c * c for c in n))
    if abs(norm - 1.0) > UNIT_TOL:
        raise InputError(f"walls[{k}].{name} must be a unit vector (| |n| - 1 | <= {UNIT_TOL:g}), |n| = {norm!r}")
    return n


def motion(k, wall, default_centre):
    """(velocity, angular_velocity, centre) of a wall's rigid motion, checked; centre None: default_centre."""
    v = vector(k, "velocity", wall.velocity)
    om = vector(k, "angular_velocity", wall.angular_velocity)
    c = default_centre if wall.centre is None else vector(k, "centre", wall.centre)
    return v, om, c


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(dot(a, a))
