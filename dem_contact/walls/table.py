"""The one table of wall kinds, the packing of a list of walls into the rows the kernels read, and the
dispatch of the contract's kernels (``contract``) on the kind of each row.

``KINDS``: one row per kind, (kind id, module). The id is the row's index, stored in column
``contract.KIND`` of each packed wall; the module is ``walls/<kind>.py``, whose ``CLASS`` names its user
class.

Adding a kind: write ``walls/<kind>.py`` keeping the contract (its user class, ``N_DATA``,
``PAYLOAD_WIDTH``, ``CLASS`` naming the class, and the kernels ``contact``, ``distance``, ``curvature``,
``patch``, ``bounds``, ``place`` with the contract's signatures), then add its row to ``KINDS``. Nothing else:
``pack`` accepts its class, ``ROW_SIZE`` grows to its numbers, and the dispatch functions here (``contact``,
``distance``, ``curvature``, ``patch``, ``bounds``, ``place``) are generated from ``KINDS`` when the module is imported: a chain of ``if walls[w,
KIND] == id`` branches, one per kind, each a direct call (inlined: the callers compile the branches of
every kind in the table). ``history_key`` and ``place_walls`` are written on them; ``contact_of`` and ``key_of``
are ``contact`` and ``history_key`` compiled once, which the per-contact kernels call.
"""
from __future__ import annotations

import inspect

import numpy as np
from numba import njit

from ..errors import InputError
from . import cylinder, mesh, plane
from .contract import (CENTRE, CENTRE0, DATA, FIRST, KEY_BASE, KIND, MOVES, NELEM, OMEGA, PAYLOAD, VEL,  # noqa: F401
                       count, elements, velocity)

#: The kinds of wall: (kind id = row index, module).
KINDS = (
    (0, plane),
    (1, cylinder),
    (2, mesh),
)

#: the contract's per-kind kernels, dispatched on the kind of the row
KERNELS = ("contact", "distance", "curvature", "patch", "bounds", "place")

#: The user classes of the kinds, in the order of KINDS.
CLASSES = tuple(getattr(mod, mod.CLASS) for _, mod in KINDS)

#: Columns of a packed wall row: the contract's and the largest kind's numbers (or payload row).
ROW_SIZE = max(max(DATA + mod.N_DATA for _, mod in KINDS), 1 + max(mod.PAYLOAD_WIDTH for _, mod in KINDS))


def pack(walls, n_materials=None):
    """float64[n + p, ROW_SIZE] rows (``contract``: the n walls' rows, then their p payload rows) and
    int64[n] material indices of a list of walls (checked: ``InputError`` naming ``walls[k]``).
    n_materials: the number of wall materials of the PairTable, if the material indices are to be checked
    against it."""
    try:
        walls = list(walls)
    except TypeError:
        raise InputError(f"walls must be a list of walls ({', '.join(c.__name__ for c in CLASSES)}), "
                         f"got {type(walls).__name__}") from None
    names = ", ".join(c.__name__ for c in CLASSES)
    rows = np.zeros((len(walls), ROW_SIZE))
    mats = np.zeros(len(walls), dtype=np.int64)
    payloads = []
    key = 0
    first = len(walls)
    for k, wall in enumerate(walls):
        kid = next((i for i, c in enumerate(CLASSES) if isinstance(wall, c)), None)
        if kid is None:
            raise InputError(f"walls[{k}] must be a wall ({names}), got {type(wall).__name__}")
        mod = KINDS[kid][1]
        data, payload, n_elements, n_keys, moves = wall.packed(k)
        m = wall.wall
        if isinstance(m, bool) or not isinstance(m, (int, np.integer)) or m < 0 or (
                n_materials is not None and m >= n_materials):
            upper = "any" if n_materials is None else n_materials - 1
            raise InputError(f"walls[{k}].wall = {m!r} must index the table's walls (0 ... {upper})")
        v, om, c = (tuple(float(q) for q in a) for a in (wall.velocity, wall.angular_velocity,
                                                          wall.centre if wall.centre is not None else (0, 0, 0)))
        if wall.centre is None:
            # (the kind's default centre: the one its packed() used)
            c = _default_centre(mod, data, payload)
        rows[k, KIND] = KINDS[kid][0]
        rows[k, KEY_BASE] = key
        rows[k, NELEM] = n_elements
        rows[k, MOVES] = 1.0 if moves else 0.0
        rows[k, VEL:VEL + 3] = v
        rows[k, OMEGA:OMEGA + 3] = om
        rows[k, CENTRE:CENTRE + 3] = c
        rows[k, CENTRE0:CENTRE0 + 3] = c
        rows[k, FIRST] = -1.0
        rows[k, DATA:DATA + mod.N_DATA] = data
        if payload is not None:
            rows[k, FIRST] = first
            block = np.zeros((len(payload), ROW_SIZE))
            block[:, KIND] = PAYLOAD
            block[:, 1:1 + payload.shape[1]] = payload
            payloads.append(block)
            first += len(payload)
        mats[k] = m
        key += n_keys
    if payloads:
        rows = np.concatenate([rows] + payloads)
    return np.ascontiguousarray(rows), mats


def _default_centre(mod, data, payload):
    """The centre of rotation a kind takes when none is given: the plane's point, the cylinder's axis point,
    the mean of a mesh's triangles' corners."""
    if payload is not None:
        return tuple(payload[:, mesh._V0 - 1:mesh._V0 + 8].reshape(-1, 3).mean(axis=0).tolist())
    return tuple(data[:3])


def _dispatch(name, kinds):
    """The jitted function (inlined into its callers) that calls kernel ``name`` of the kind of the row
    ``walls[w]``: generated from ``kinds`` (rows as KINDS), one direct call per kind."""
    first = getattr(kinds[0][1], name)
    params = list(inspect.signature(first.py_func).parameters)
    if params[:2] != ["walls", "w"]:
        raise TypeError(f"{kinds[0][1].__name__}.{name}: a wall kernel takes (walls, w, ...)")
    for kid, mod in kinds:
        got = list(inspect.signature(getattr(mod, name).py_func).parameters)
        if got != params:
            raise TypeError(f"{mod.__name__}.{name}{tuple(got)} does not keep the contract's signature "
                            f"{tuple(params)}")
    args = ", ".join(params)
    lines = [f"def {name}({args}):"]
    for q, (kid, _) in enumerate(kinds[:-1]):
        lines += [f"    if walls[w, KIND] == {float(kid)!r}:", f"        return k{q}({args})"]
    lines.append(f"    return k{len(kinds) - 1}({args})")
    namespace = {"KIND": KIND, **{f"k{q}": getattr(mod, name) for q, (_, mod) in enumerate(kinds)}}
    exec(compile("\n".join(lines), f"<dem_contact.walls.table: {name}>", "exec"), namespace)
    func = namespace[name]
    func.__doc__ = (f"``{name}`` of the wall kind of row ``walls[w]`` (contract: ``walls.contract``); "
                    f"generated from the table of kinds ({', '.join(m.__name__ for _, m in kinds)}).")
    func.__module__ = __name__
    func.source = "\n".join(lines)
    # (not cached on disk: a generated function has no source file; it is inlined into its callers,
    # which are, and whose cache this file's and the kinds' sources key)
    return njit(inline="always")(func)


contact = _dispatch("contact", KINDS)
distance = _dispatch("distance", KINDS)
curvature = _dispatch("curvature", KINDS)
patch = _dispatch("patch", KINDS)
bounds = _dispatch("bounds", KINDS)
place = _dispatch("place", KINDS)


@njit(inline="always")
def history_key(walls, w, e, x, y, z):
    """Key of the history of a contact of the sphere centred at (x, y, z) with element e of wall w:
    -(first key of wall w + its patch + 1) (negative; ``contract``)."""
    return -(walls[w, KEY_BASE] + patch(walls, w, e, x, y, z) + 1.0)


@njit(cache=True)
def contact_of(walls, w, e, x, y, z, r):
    """``contact`` (s, nx, ny, nz) of the kind of wall w, compiled once for all its callers: the kinds'
    geometry (a mesh's edges and vertices) is the larger part of a wall kernel to compile, and a call per
    contact costs a few ns."""
    return contact(walls, w, e, x, y, z, r)


@njit(cache=True)
def key_of(walls, w, e, x, y, z):
    """``history_key`` of the kind of wall w, compiled once for all its callers (as ``contact_of``)."""
    return history_key(walls, w, e, x, y, z)


@njit(cache=True)
def place_walls(walls, t):
    """Every wall at time t [s] (in place): a wall whose motion moves its surface placed, and the centre of
    every wall carried to C0 + V t, also where the surface stays (a plane sliding in its own plane, a cylinder
    along its axis): its velocity at a point, V + Omega x (c - C(t)), and the torques of its loads are about
    the moved centre."""
    for w in range(count(walls)):
        if walls[w, MOVES] != 0.0:
            place(walls, w, t)
        else:
            for d in range(3):
                walls[w, CENTRE + d] = walls[w, CENTRE0 + d] + walls[w, VEL + d] * t
