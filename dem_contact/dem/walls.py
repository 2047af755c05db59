"""Contacts of spheres with walls for the 3D batch kernels (``contact3d``): the same wall kernels as the
LAMMPS plugin's ``fix dem/contact/wall`` (``dem_contact.walls``), so a DEM code gets the normals, overlaps and
wall velocities that the plugin computes, for any kind of wall of the table.

    contacts = wall_contacts(centres, radii, walls)
    rows = contacts.pair_rows(table, types)                  # table.wall_row[type, wall material]
    v = contacts.relative_velocities(velocities, spins)      # v_i + R_i w_i x n - v_wall
    contact_forces(nid, tid, table.params, rows, H, contacts.normals, contacts.overlaps, v,
                   contacts.frame_spin(spins), dt, forces, tforces, history_rows=...,
                   spins=contacts.relative_spins(spins), torques=...)   # (twist and rolling laws)
    loads = contacts.loads(forces)                            # each wall's force, torque, power

Body 1 is the sphere, body 2 the wall: ``normals`` point from the sphere toward the wall, ``forces`` is the
force on the sphere; its torque is R n x F_t (the arm of a wall contact is the full radius, as in LAMMPS's
``fix wall/gran``). ``keys`` identify each contact's history (one per wall, and for a mesh per side and set of
triangles joined across flat or convex edges: a contact that moves across a mesh's seams or over its convex
edges keeps its key) from one step to the next. Walls that move are placed at the
``time`` given (their pose at time 0 and their rigid motion: ``walls.contract``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..errors import InputError
from ..walls import table as W
from ..walls.search import near_elements


@njit(cache=True)
def _find(x, radius, walls):
    """The sphere-wall contacts (overlap > 0), in the order of the spheres, then the walls, then their
    elements (the elements near each sphere: ``walls.search.near_elements``)."""
    near = near_elements(x.shape[0], x, radius, walls, 0.0)
    gaps = np.empty((len(near), 4))
    m = 0
    for q in range(len(near)):
        i, w, e = near[q, 0], near[q, 1], near[q, 2]
        gaps[q, 0], gaps[q, 1], gaps[q, 2], gaps[q, 3] = W.contact_of(walls, w, e, x[i, 0], x[i, 1], x[i, 2], radius[i])
        if radius[i] - gaps[q, 0] > 0.0:
            m += 1
    ids = np.empty((m, 3), dtype=np.int64)
    keys = np.empty(m)
    normals = np.empty((m, 3))
    overlaps = np.empty(m)
    points = np.empty((m, 3))
    vel = np.empty((m, 3))
    curv = np.empty(m)
    k = 0
    for q in range(len(near)):
        i, w, e = near[q, 0], near[q, 1], near[q, 2]
        s, nx, ny, nz = gaps[q, 0], gaps[q, 1], gaps[q, 2], gaps[q, 3]
        delta = radius[i] - s
        if not delta > 0.0:
            continue
        cx = x[i, 0] + s * nx
        cy = x[i, 1] + s * ny
        cz = x[i, 2] + s * nz
        ids[k, 0] = i
        ids[k, 1] = w
        ids[k, 2] = e
        keys[k] = W.key_of(walls, w, e, x[i, 0], x[i, 1], x[i, 2])
        normals[k, 0] = nx
        normals[k, 1] = ny
        normals[k, 2] = nz
        overlaps[k] = delta
        points[k, 0] = cx
        points[k, 1] = cy
        points[k, 2] = cz
        vel[k, 0], vel[k, 1], vel[k, 2] = W.velocity(walls, w, cx, cy, cz)
        curv[k] = W.curvature(walls, w, e, cx, cy, cz)
        k += 1
    return ids, keys, normals, overlaps, points, vel, curv


def _points(name, a, n=None):
    try:
        arr = np.array(a, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be an array of numbers, got {type(a).__name__}") from None
    if n is None:
        if arr.ndim != 2 or arr.shape[1] != 3:
            raise InputError(f"{name} must have shape (n, 3) (one row per sphere), got {arr.shape}")
    elif arr.shape != (n, 3):
        raise InputError(f"{name} must have shape ({n}, 3) (one row per sphere), got {arr.shape}")
    bad = ~np.isfinite(arr).all(axis=1)
    if bad.any():
        raise InputError(f"{name}[{int(np.argmax(bad))}] must be finite, got {arr[np.argmax(bad)].tolist()}")
    return arr


@dataclass(frozen=True, eq=False)
class WallContacts:
    """The sphere-wall contacts of ``wall_contacts`` (m of them), body 1 the sphere, body 2 the wall.

    sphere, wall, element: int64[m] the sphere's index, the wall's index in the list, and the element of
    the wall touched (0 for a plane); material: int64[m] the wall's material (its ``wall``: the column of
    ``PairTable.wall_row``); keys: float64[m] the key of the contact's history (negative, one per wall and
    patch, ``walls.contract``; with the sphere's index it names the contact); normals: float64[m, 3] unit, from the sphere
    toward the wall; overlaps: float64[m] > 0 [m]; points: float64[m, 3] the contact points on the wall's
    surface [m]; wall_velocities: float64[m, 3] the wall's velocity there [m/s]; curvature: float64[m]
    1 / R2 of the wall there [1/m] (0 for a plane: R* = R of the sphere, as ``pairs.pair_table``'s
    sphere-wall rows); radii: float64[m] the spheres' radii; centres: float64[n_walls, 3] each wall's centre of
    rotation at this time (``loads`` takes torques about it); wall_spins: float64[m, 3] the wall's angular
    velocity [rad/s] (its rigid motion)."""

    sphere: np.ndarray
    wall: np.ndarray
    element: np.ndarray
    material: np.ndarray
    keys: np.ndarray
    normals: np.ndarray
    overlaps: np.ndarray
    points: np.ndarray
    wall_velocities: np.ndarray
    curvature: np.ndarray
    radii: np.ndarray
    n_spheres: int
    centres: np.ndarray = None
    wall_spins: np.ndarray = None

    def __post_init__(self):
        if self.wall_spins is None:      # (walls at rest)
            object.__setattr__(self, "wall_spins", np.zeros((len(self.overlaps), 3)))

    def __len__(self):
        return len(self.overlaps)

    def relative_velocities(self, velocities, spins) -> np.ndarray:
        """float64[m, 3]: the sphere's velocity at the contact relative to the wall's, v + R w x n - v_wall
        (the full radius, as LAMMPS's ``fix wall/gran`` and ``fix dem/contact/wall``). velocities, spins:
        float64[n, 3] of every sphere [m/s], [rad/s]."""
        v = _points("velocities", velocities, self.n_spheres)[self.sphere]
        w = _points("spins", spins, self.n_spheres)[self.sphere] * self.radii[:, None]
        n = self.normals
        out = np.empty((len(self), 3))
        out[:, 0] = v[:, 0] - self.wall_velocities[:, 0] + (w[:, 1] * n[:, 2] - w[:, 2] * n[:, 1])
        out[:, 1] = v[:, 1] - self.wall_velocities[:, 1] + (w[:, 2] * n[:, 0] - w[:, 0] * n[:, 2])
        out[:, 2] = v[:, 2] - self.wall_velocities[:, 2] + (w[:, 0] * n[:, 1] - w[:, 1] * n[:, 0])
        return out

    def frame_spin(self, spins) -> np.ndarray:
        """float64[m]: wn = 0.5 (w + W) . n, the spin of the contact frame about the normal (w the sphere's,
        W the wall's angular velocity); pass zeros instead to keep the history fixed in space (LAMMPS's
        granular models)."""
        w = _points("spins", spins, self.n_spheres)[self.sphere] + self.wall_spins
        n = self.normals
        return 0.5 * (w[:, 0] * n[:, 0] + w[:, 1] * n[:, 1] + w[:, 2] * n[:, 2])

    def relative_spins(self, spins) -> np.ndarray:
        """float64[m, 3]: w - W, the sphere's angular velocity relative to the wall's (the ``spins`` input of
        the twist and rolling laws: a sphere turning with a drum has none). Pass the spheres' own instead to
        count the walls as not turning (LAMMPS's ``fix wall/gran``)."""
        return _points("spins", spins, self.n_spheres)[self.sphere] - self.wall_spins

    def loads(self, forces, torques=None) -> "WallLoads":
        """Each wall's load from the contacts' forces on the spheres (float64[m, 3], as ``contact_forces``
        writes them; torques: float64[m, 3] the twist and rolling torques on the spheres, if any): the force
        on the wall, -sum F; its torque about its centre of rotation, sum (c - C) x (-F) - M (c: the contact
        point); and the power the wall gives the spheres, sum F . v_wall(c) [W] (a drum's drive power)."""
        f = np.asarray(forces, dtype=np.float64)
        if f.shape != (len(self), 3):
            raise InputError(f"forces must have shape ({len(self)}, 3) (one row per contact), got {f.shape}")
        nw = len(self.centres)
        force = np.zeros((nw, 3))
        torque = np.zeros((nw, 3))
        power = np.zeros(nw)
        arm = self.points - self.centres[self.wall]
        np.add.at(force, self.wall, -f)
        np.add.at(torque, self.wall, -np.cross(arm, f))
        if torques is not None:
            m = np.asarray(torques, dtype=np.float64)
            if m.shape != (len(self), 3):
                raise InputError(f"torques must have shape ({len(self)}, 3) (one row per contact), got {m.shape}")
            np.add.at(torque, self.wall, -m)
        np.add.at(power, self.wall, np.einsum("ij,ij->i", f, self.wall_velocities))
        return WallLoads(force, torque, power, self.centres.copy())

    def pair_rows(self, table, types) -> np.ndarray:
        """int64[m]: the parameter row of each contact, table.wall_row[types[sphere], material]. types: the
        sphere type (0-based: the table's spheres[k]) of every sphere."""
        wall_row = getattr(table, "wall_row", None)
        if not (isinstance(wall_row, np.ndarray) and wall_row.ndim == 2):
            raise InputError(f"table must be a PairTable (dem.pairs.pair_table), got {type(table).__name__}")
        nt, nm = wall_row.shape
        t = np.asarray(types)
        if t.shape != (self.n_spheres,) or not np.issubdtype(t.dtype, np.integer):
            raise InputError(f"types must be {self.n_spheres} integers (one per sphere), got shape {t.shape}, "
                             f"dtype {t.dtype}")
        if len(t) and (t.min() < 0 or t.max() >= nt):
            k = int(np.argmax((t < 0) | (t >= nt)))
            raise InputError(f"types[{k}] = {int(t[k])} must index the table's spheres (0 ... {nt - 1})")
        if len(self) and self.material.max() >= nm:
            k = int(np.argmax(self.material >= nm))
            raise InputError(f"walls[{int(self.wall[k])}].wall = {int(self.material[k])} must index the "
                             f"table's walls (0 ... {nm - 1})")
        check_curvatures(table, self.material, self.curvature, self.wall)
        return np.ascontiguousarray(wall_row[t[self.sphere], self.material], dtype=np.int64)


@dataclass(frozen=True, eq=False)
class WallLoads:
    """Loads of the walls (``WallContacts.loads``), one row per wall: force float64[n, 3] on the wall [N],
    torque float64[n, 3] on it about its centre of rotation [N m], power float64[n] it gives the spheres
    [W], centre float64[n, 3] that centre [m]. The torque about an axis u through the centre: torque @ u."""

    force: np.ndarray
    torque: np.ndarray
    power: np.ndarray
    centre: np.ndarray


def check_curvatures(table, material, curvature, wall):
    """InputError unless each contact's curvature (float64[m]) is that of its wall material in the table
    (``materials.Wall.curvature``), which its parameter row's R* was built with."""
    scenes = getattr(table, "scenes", ())
    nt, nm = table.wall_row.shape
    if not len(material) or not scenes:
        return
    have = np.array([scenes[table.wall_row[0, m]].body2.curvature for m in range(nm)])
    bad = np.flatnonzero(have[material] != curvature)
    if len(bad):
        k = bad[0]
        raise InputError(f"walls[{int(wall[k])}] has curvature {float(curvature[k])!r} 1/m at its contacts, but its "
                         f"material (the table's walls[{int(material[k])}]) has curvature {float(have[material[k]])!r}: "
                         f"build the table with Wall(material, curvature={float(curvature[k])!r}) for it, or give "
                         f"the wall curved=False (R* = R1)")


def wall_contacts(centres, radii, walls, time: float = 0.0) -> WallContacts:
    """The contacts of spheres (centres float64[n, 3] [m], radii float64[n] > 0 [m]) with ``walls`` (a list
    of walls of ``dem_contact.walls``: ``PlaneWall``, ``CylinderWall``, ``MeshWall``; or the (rows,
    materials) that ``walls.pack`` returned for them, packed once for every step: packing a mesh
    takes longer than finding its contacts) at ``time`` [s] (the walls' poses are those at time 0), as the batch
    kernels take them (``WallContacts``). Checked:
    ``InputError`` naming the parameter and its valid range. A mesh's triangles are binned into cells over the
    centres (``walls.search``): the cost grows with the spheres and the contacts, not with n x triangles."""
    x = _points("centres", centres)
    try:
        r = np.array(radii, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError(f"radii must be an array of numbers, got {type(radii).__name__}") from None
    if r.shape != (len(x),):
        raise InputError(f"radii must have shape ({len(x)},) (one per sphere), got {r.shape}")
    bad = ~(np.isfinite(r) & (r > 0.0))
    if bad.any():
        k = int(np.argmax(bad))
        raise InputError(f"radii[{k}] = {float(r[k])!r} must be finite and > 0 [m]")
    if isinstance(walls, tuple) and len(walls) == 2 and all(isinstance(a, np.ndarray) for a in walls):
        rows, mats = walls
        if not (rows.ndim == 2 and rows.shape[1] == W.ROW_SIZE and rows.dtype == np.float64
                and rows.flags.c_contiguous and mats.ndim == 1 and mats.dtype == np.int64
                and len(mats) == W.count(rows) <= rows.shape[0]):
            raise InputError("walls given packed must be the (rows, materials) that walls.pack returned")
    else:
        rows, mats = W.pack(walls)
    t = float(time)
    if not math.isfinite(t):
        raise InputError(f"time must be finite [s], got {time!r}")
    W.place_walls(rows, t)                 # (walls packed once are placed at each call's time)
    ids, keys, normals, overlaps, points, vel, curv = _find(x, r, rows)
    nw = len(mats)
    return WallContacts(ids[:, 0].copy(), ids[:, 1].copy(), ids[:, 2].copy(), mats[ids[:, 1]], keys, normals,
                        overlaps, points, vel, curv, r[ids[:, 0]], len(x), rows[:nw, W.CENTRE:W.CENTRE + 3].copy(),
                        np.ascontiguousarray(rows[ids[:, 1], W.OMEGA:W.OMEGA + 3]))
