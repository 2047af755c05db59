"""Plane walls: a flat wall through a point with a unit normal into the region of the spheres, at rest or
sliding in its own plane at a prescribed velocity (a plane that moves along its normal is another kind,
later). One element: a contact with the plane keeps one history.

Row data (from column ``contract.DATA``): the point (3), the unit normal (3), the velocity (3).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from ..errors import InputError
from .contract import DATA

CLASS = "PlaneWall"
N_DATA = 9
ELEMENTS = 1
_P = DATA           # point
_N = DATA + 3       # unit normal into the region of the spheres
_V = DATA + 6       # velocity (in the plane)

#: tolerance on |normal| - 1, and on the normal part of the velocity relative to |velocity|
UNIT_TOL = 1e-12
IN_PLANE_TOL = 1e-9


def _vector(k, name, value):
    try:
        t = tuple(float(c) for c in value)
    except (TypeError, ValueError):
        raise InputError(f"walls[{k}].{name} must be 3 finite numbers, got {value!r}") from None
    if len(t) != 3 or not all(math.isfinite(c) for c in t):
        raise InputError(f"walls[{k}].{name} must be 3 finite numbers, got {value!r}")
    return t


@dataclass(frozen=True)
class PlaneWall:
    """A flat wall through ``point`` [m] with unit ``normal`` pointing into the region of the spheres;
    ``wall``: index of its material in the PairTable's walls; ``velocity`` [m/s]: the wall's velocity,
    which must lie in its plane (|v . n| <= 1e-9 |v|; the wall slides in its plane, its surface stays
    where it is), default at rest. A contact's relative velocity is the sphere's minus the wall's."""

    point: tuple
    normal: tuple
    wall: int = 0
    velocity: tuple = (0.0, 0.0, 0.0)

    @classmethod
    def axis(cls, axis: str, position: float, side: str, wall: int = 0,
             velocity: tuple = (0.0, 0.0, 0.0)) -> "PlaneWall":
        """Wall perpendicular to ``axis`` ('x', 'y' or 'z') at ``position``; side 'lo' keeps the spheres
        above it (normal +axis), 'hi' below it (normal -axis)."""
        if axis not in ("x", "y", "z"):
            raise InputError(f"axis must be 'x', 'y' or 'z', got {axis!r}")
        if side not in ("lo", "hi"):
            raise InputError(f"side must be 'lo' or 'hi', got {side!r}")
        k = "xyz".index(axis)
        point = [0.0, 0.0, 0.0]
        point[k] = float(position)
        normal = [0.0, 0.0, 0.0]
        normal[k] = 1.0 if side == "lo" else -1.0
        return cls(tuple(point), tuple(normal), wall, velocity)

    def row_data(self, k: int) -> tuple:
        """The N_DATA numbers of the packed row (checked; k: the wall's index, for the messages)."""
        p = _vector(k, "point", self.point)
        n = _vector(k, "normal", self.normal)
        v = _vector(k, "velocity", self.velocity)
        norm = math.sqrt(sum(c * c for c in n))
        if abs(norm - 1.0) > UNIT_TOL:
            raise InputError(f"walls[{k}].normal must be a unit vector (| |n| - 1 | <= {UNIT_TOL:g}), "
                             f"|n| = {norm!r}")
        vn = sum(a * b for a, b in zip(v, n))
        speed = math.sqrt(sum(c * c for c in v))
        if abs(vn) > IN_PLANE_TOL * speed:
            raise InputError(f"walls[{k}].velocity must lie in the wall's plane (|v . n| <= {IN_PLANE_TOL:g} "
                             f"|v|), got v . n = {vn!r} m/s: a plane moving along its normal is not a "
                             f"PlaneWall")
        # (the normal part within the tolerance removed: the surface stays where it is)
        v = tuple(a - vn * b for a, b in zip(v, n)) if vn != 0.0 else v
        return p + n + v


@njit(inline="always", cache=True)
def contact(walls, w, x, y, z, r):
    """(s, nx, ny, nz): signed distance from the centre to the plane along its normal, and the normal from
    the sphere toward the wall (minus the wall's normal)."""
    s = ((x - walls[w, _P]) * walls[w, _N] + (y - walls[w, _P + 1]) * walls[w, _N + 1]
         + (z - walls[w, _P + 2]) * walls[w, _N + 2])
    return s, -walls[w, _N], -walls[w, _N + 1], -walls[w, _N + 2]


@njit(inline="always", cache=True)
def velocity(walls, w, cx, cy, cz):
    """The prescribed velocity, the same at every point of the plane."""
    return walls[w, _V], walls[w, _V + 1], walls[w, _V + 2]


@njit(inline="always", cache=True)
def curvature(walls, w, cx, cy, cz):
    """A plane is flat: 1 / R2 = 0."""
    return 0.0


@njit(inline="always", cache=True)
def element(walls, w, x, y, z):
    """A plane is one element."""
    return 0
