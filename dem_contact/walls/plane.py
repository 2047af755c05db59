"""Plane walls: a flat wall through a point with a unit normal into the region of the spheres, moving by a
prescribed rigid motion (``contract``): a velocity, and an angular velocity about a centre (default: the
point). One element, one history key.

Row data (from column ``contract.DATA``): the point and the unit normal now (3 + 3), and at time 0 (3 + 3).
"""
from __future__ import annotations

from dataclasses import dataclass

from numba import njit

from . import checks
from .contract import DATA, one_patch, place_point_vector, unbounded

CLASS = "PlaneWall"
N_DATA = 12
PAYLOAD_WIDTH = 0
_P = DATA           # point
_N = DATA + 3       # unit normal into the region of the spheres

#: a motion moves the plane unless |V . n| <= SURFACE_TOL |V| and |Omega x n| <= SURFACE_TOL |Omega|
SURFACE_TOL = 1e-12


@dataclass(frozen=True)
class PlaneWall:
    """A flat wall through ``point`` [m] with unit ``normal`` pointing into the region of the spheres (its
    pose at time 0); ``wall``: index of its material in the PairTable's walls. Rigid motion: ``velocity``
    [m/s] of its ``centre`` [m] (default: ``point``) and ``angular_velocity`` [rad/s] about it; the wall's
    velocity at a point c of its surface is velocity + angular_velocity x (c - centre(t)). A velocity in
    its plane and an angular velocity along its normal (a belt, a turning end plate) leave the surface
    where it is; any other motion moves it (placed at every step). A contact's relative velocity is the
    sphere's minus the wall's."""

    point: tuple
    normal: tuple
    wall: int = 0
    velocity: tuple = (0.0, 0.0, 0.0)
    angular_velocity: tuple = (0.0, 0.0, 0.0)
    centre: tuple | None = None

    @classmethod
    def axis(cls, axis: str, position: float, side: str, wall: int = 0, velocity: tuple = (0.0, 0.0, 0.0),
             angular_velocity: tuple = (0.0, 0.0, 0.0), centre: tuple | None = None) -> "PlaneWall":
        """Wall perpendicular to ``axis`` ('x', 'y' or 'z') at ``position``; side 'lo' keeps the spheres
        above it (normal +axis), 'hi' below it (normal -axis)."""
        from ..errors import InputError

        if axis not in ("x", "y", "z"):
            raise InputError(f"axis must be 'x', 'y' or 'z', got {axis!r}")
        if side not in ("lo", "hi"):
            raise InputError(f"side must be 'lo' or 'hi', got {side!r}")
        k = "xyz".index(axis)
        point = [0.0, 0.0, 0.0]
        point[k] = float(position)
        normal = [0.0, 0.0, 0.0]
        normal[k] = 1.0 if side == "lo" else -1.0
        return cls(tuple(point), tuple(normal), wall, velocity, angular_velocity, centre)

    def packed(self, k: int):
        """(data, payload, n_elements, n_keys, moves): see ``contract`` (k: the wall's index, for messages)."""
        p = checks.vector(k, "point", self.point)
        n = checks.unit(k, "normal", self.normal)
        v, om, _ = checks.motion(k, self, p)
        keeps = (abs(checks.dot(v, n)) <= SURFACE_TOL * checks.norm(v)
                 and checks.norm(checks.cross(om, n)) <= SURFACE_TOL * checks.norm(om))
        return p + n + p + n, None, 1, 1, not keeps


@njit(inline="always", cache=True)
def contact(walls, w, e, x, y, z, r):
    """(s, nx, ny, nz): signed distance from the centre to the plane along its normal, and the normal from
    the sphere toward the wall (minus the wall's normal)."""
    s = ((x - walls[w, _P]) * walls[w, _N] + (y - walls[w, _P + 1]) * walls[w, _N + 1]
         + (z - walls[w, _P + 2]) * walls[w, _N + 2])
    return s, -walls[w, _N], -walls[w, _N + 1], -walls[w, _N + 2]


@njit(inline="always", cache=True)
def distance(walls, w, e, x, y, z):
    """The signed distance of ``contact``."""
    return contact(walls, w, e, x, y, z, 0.0)[0]


@njit(inline="always", cache=True)
def curvature(walls, w, e, cx, cy, cz):
    """A plane is flat: 1 / R2 = 0."""
    return 0.0


#: a plane is unbounded and one patch, placed by its point and normal
bounds, patch, place = unbounded, one_patch, place_point_vector


def example(**motion) -> PlaneWall:
    """A typical wall of this kind, with the rigid motion ``motion`` (the contract tests use it)."""
    return PlaneWall((0.1, -0.2, 0.3), (1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0), **motion)


def sample(wall: PlaneWall, n: int, rng):
    """(surface points float[m, 3], sphere centres float[n, 3]) of ``wall`` at time 0: points covering the
    surface around the centres densely, and centres on the spheres' side, 0.1 to 0.5 m from it, whose closest
    point is among them (the contract tests' brute force)."""
    import numpy as np

    p, nrm = np.array(wall.point, float), np.array(wall.normal, float)
    e1 = np.cross(nrm, [1.0, 0.0, 0.0] if abs(nrm[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(nrm, e1)
    u = rng.uniform(-1.0, 1.0, (400_000, 2))
    surface = p + u[:, :1] * e1 + u[:, 1:] * e2
    v = rng.uniform(-0.3, 0.3, (n, 2))
    centres = p + v[:, :1] * e1 + v[:, 1:] * e2 + rng.uniform(0.1, 0.5, (n, 1)) * nrm
    return surface, centres
