"""Cylinder walls: an infinite circular cylinder (axis through a point, unit direction, radius) with the
spheres inside or outside it, moving by a prescribed rigid motion (``contract``; a drum: an angular
velocity along its axis, about a centre on it). End plates are plane walls (``PlaneWall`` turning with
the same angular velocity). One element, one history key.

Curvature of the contact (``curvature``): a sphere of radius R1 on a cylinder of radius Rc touches two
surfaces whose relative principal curvatures are 1/R1 -+ 1/Rc (across the axis) and 1/R1 (along it); the
sum of the relative curvatures is A + B = (1/2)(2/R1 -+ 1/Rc) (Johnson 1985, Contact Mechanics, eq. 4.3 and
section 4.2). The laws of this package are those of circular contacts, which take one radius: the
circular contact with the same A + B, 1/R* = 1/R1 -+ 1/(2 Rc), that is k = -+1/(2 Rc) (concave inside:
-, convex outside: +), the mean curvature of the cylinder. This is the choice of LAMMPS's ``fix
wall/gran/region`` for a region cylinder (its wall radius -2 Rc inside, +2 Rc outside: R* = R1 radj /
(R1 + radj)). It differs from the radius of Hertz's elliptical contact, sqrt(R' R'') (Johnson eq. 4.29a),
at second order in R1/Rc. ``curved=False`` takes the cylinder as flat at the contact (k = 0, R* = R1).

Row data (from column ``contract.DATA``): the axis point and unit direction now (3 + 3) and at time 0
(3 + 3), the radius, the side (+1 inside, -1 outside) and k.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from ..errors import InputError
from . import checks
from .contract import DATA, one_patch, place_point_vector, unbounded

CLASS = "CylinderWall"
N_DATA = 15
PAYLOAD_WIDTH = 0
_A = DATA           # point of the axis
_U = DATA + 3       # unit direction of the axis
_R = DATA + 12      # radius
_SIDE = DATA + 13   # +1 spheres inside, -1 outside
_K = DATA + 14      # curvature entering R*

#: a motion moves the cylinder unless velocity and angular velocity are along the axis and the centre on it,
#: to this relative tolerance
SURFACE_TOL = 1e-12


@dataclass(frozen=True)
class CylinderWall:
    """An infinite circular cylinder of ``radius`` [m] about the axis through ``point`` [m] along the unit
    vector ``axis`` (its pose at time 0), with the spheres ``inside`` (default) or outside it; ``wall``:
    index of its material in the PairTable's walls, whose ``Wall.curvature`` must be this wall's
    ``curvature_for_rstar`` (-1/(2 radius) inside, +1/(2 radius) outside, 0 with ``curved=False``; see the
    module's docstring). Rigid motion as ``PlaneWall``: ``velocity``, ``angular_velocity`` about ``centre``
    (default: ``point``); a drum turning at w rad/s: ``angular_velocity = w * axis``."""

    point: tuple
    axis: tuple
    radius: float
    inside: bool = True
    wall: int = 0
    velocity: tuple = (0.0, 0.0, 0.0)
    angular_velocity: tuple = (0.0, 0.0, 0.0)
    centre: tuple | None = None
    curved: bool = True

    @property
    def curvature_for_rstar(self) -> float:
        """k [1/m] of its contacts, R* = 1 / (1/R1 + k): the curvature its wall material must carry."""
        if not self.curved:
            return 0.0
        return (-0.5 if self.inside else 0.5) / float(self.radius)

    def packed(self, k: int):
        """(data, payload, n_elements, n_keys, moves): see ``contract`` (k: the wall's index, for messages)."""
        a = checks.vector(k, "point", self.point)
        u = checks.unit(k, "axis", self.axis)
        try:
            rc = float(self.radius)
        except (TypeError, ValueError):
            rc = math.nan
        if not (math.isfinite(rc) and rc > 0.0):
            raise InputError(f"walls[{k}].radius must be finite and > 0 [m], got {self.radius!r}")
        if not isinstance(self.inside, bool) or not isinstance(self.curved, bool):
            raise InputError(f"walls[{k}].inside and .curved must be True or False")
        v, om, c = checks.motion(k, self, a)
        off = tuple(ci - ai for ci, ai in zip(c, a))
        keeps = (checks.norm(checks.cross(v, u)) <= SURFACE_TOL * checks.norm(v)
                 and checks.norm(checks.cross(om, u)) <= SURFACE_TOL * checks.norm(om)
                 and (checks.norm(om) == 0.0 or checks.norm(checks.cross(off, u)) <= SURFACE_TOL * rc))
        side = 1.0 if self.inside else -1.0
        return a + u + a + u + (rc, side, self.curvature_for_rstar), None, 1, 1, not keeps


@njit(inline="always", cache=True)
def contact(walls, w, e, x, y, z, r):
    """(s, nx, ny, nz): the distance from the centre to the cylinder along the radial direction (> 0 on
    the spheres' side), and the radial unit vector from the sphere toward the wall."""
    dx = x - walls[w, _A]
    dy = y - walls[w, _A + 1]
    dz = z - walls[w, _A + 2]
    ux = walls[w, _U]
    uy = walls[w, _U + 1]
    uz = walls[w, _U + 2]
    t = dx * ux + dy * uy + dz * uz
    px = dx - t * ux
    py = dy - t * uy
    pz = dz - t * uz
    rho = math.sqrt(px * px + py * py + pz * pz)
    side = walls[w, _SIDE]
    s = side * (walls[w, _R] - rho)
    if rho == 0.0:
        # on the axis: any radial direction (a sphere of radius < Rc there does not touch)
        px, py, pz = (uy, -ux, 0.0) if abs(uz) < 0.9 else (0.0, uz, -uy)
        rho = math.sqrt(px * px + py * py + pz * pz)
    q = side / rho
    return s, px * q, py * q, pz * q


@njit(inline="always", cache=True)
def distance(walls, w, e, x, y, z):
    """The signed distance of ``contact``."""
    return contact(walls, w, e, x, y, z, 0.0)[0]


@njit(inline="always", cache=True)
def curvature(walls, w, e, cx, cy, cz):
    """-1/(2 Rc) inside, +1/(2 Rc) outside, 0 if taken flat (module docstring)."""
    return walls[w, _K]


#: a cylinder is unbounded (infinite along its axis) and one patch, placed by its point and axis
bounds, patch, place = unbounded, one_patch, place_point_vector


def example(**motion) -> CylinderWall:
    """A typical wall of this kind, with the rigid motion ``motion`` (the contract tests use it)."""
    return CylinderWall((0.1, -0.2, 0.3), (0.0, 0.6, 0.8), 1.0, **motion)


def sample(wall: CylinderWall, n: int, rng):
    """(surface points float[m, 3], sphere centres float[n, 3]) of ``wall`` at time 0: points covering the
    surface around the centres densely, and centres on the spheres' side, 0.1 to 0.5 m from it, whose closest
    point is among them (the contract tests' brute force)."""
    import numpy as np

    p, u = np.array(wall.point, float), np.array(wall.axis, float)
    e1 = np.cross(u, [1.0, 0.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(u, e1)

    def at(radius, angle, height):
        return p + radius[:, None] * (np.cos(angle)[:, None] * e1 + np.sin(angle)[:, None] * e2) + height[:, None] * u

    m = 600_000
    surface = at(np.full(m, wall.radius), rng.uniform(0.0, 2.0 * np.pi, m), rng.uniform(-1.0, 1.0, m))
    side = -1.0 if wall.inside else 1.0
    centres = at(wall.radius + side * rng.uniform(0.1, 0.5, n), rng.uniform(0.0, 2.0 * np.pi, n),
                 rng.uniform(-0.3, 0.3, n))
    return surface, centres
