"""The one table of wall kinds, the packing of a list of walls into the rows the kernels read, and the
dispatch of the contract's kernels (``contract``) on the kind of each row.

``KINDS``: one row per kind, (kind id, module). The id is the row's index, stored in column
``contract.KIND`` of each packed wall; the module is ``walls/<kind>.py``, whose ``CLASS`` names its user
class.

Adding a kind: write ``walls/<kind>.py`` keeping the contract (its user class, ``N_DATA``, ``ELEMENTS``,
``CLASS`` naming the class, and the kernels ``contact``, ``velocity``, ``curvature``, ``element`` with the
contract's signatures), then add its row to ``KINDS``. Nothing else: ``pack`` accepts its class, ``ROW_SIZE``
grows to its numbers, and the dispatch functions here (``contact``, ``velocity``, ``curvature``,
``element``) are generated from ``KINDS`` when the module is imported: with one kind each is a direct call
of that kind's kernel; with several, a chain of ``if walls[w, KIND] == id`` branches, one per kind, each a
direct call (inlined: the callers compile the branches of every kind in the table).
"""
from __future__ import annotations

import inspect

import numpy as np
from numba import njit

from ..errors import InputError
from . import plane
from .contract import DATA, KEY_BASE, KIND, history_key  # noqa: F401  (history_key: part of the table's face)

#: The kinds of wall: (kind id = row index, module).
KINDS = (
    (0, plane),
)

#: the contract's per-kind kernels, dispatched on the kind of the row
KERNELS = ("contact", "velocity", "curvature", "element")

#: The user classes of the kinds, in the order of KINDS.
CLASSES = tuple(getattr(mod, mod.CLASS) for _, mod in KINDS)

#: Columns of a packed wall row: the kind, the key base and the largest kind's numbers.
ROW_SIZE = DATA + max(mod.N_DATA for _, mod in KINDS)


def pack(walls, n_materials=None):
    """float64[n, ROW_SIZE] rows (``contract``) and int64[n] material indices of a list of walls (checked:
    ``InputError`` naming ``walls[k]``). n_materials: the number of wall materials of the PairTable, if
    the material indices are to be checked against it."""
    try:
        walls = list(walls)
    except TypeError:
        raise InputError(f"walls must be a list of walls ({', '.join(c.__name__ for c in CLASSES)}), "
                         f"got {type(walls).__name__}") from None
    rows = np.zeros((len(walls), ROW_SIZE))
    mats = np.zeros(len(walls), dtype=np.int64)
    key = 0
    for k, wall in enumerate(walls):
        kid = next((i for i, c in enumerate(CLASSES) if isinstance(wall, c)), None)
        if kid is None:
            raise InputError(f"walls[{k}] must be a wall ({', '.join(c.__name__ for c in CLASSES)}), "
                             f"got {type(wall).__name__}")
        mod = KINDS[kid][1]
        data = wall.row_data(k)
        m = wall.wall
        if isinstance(m, bool) or not isinstance(m, (int, np.integer)) or m < 0 or (
                n_materials is not None and m >= n_materials):
            upper = "any" if n_materials is None else n_materials - 1
            raise InputError(f"walls[{k}].wall = {m!r} must index the table's walls (0 ... {upper})")
        rows[k, KIND] = KINDS[kid][0]
        rows[k, KEY_BASE] = key
        rows[k, DATA:DATA + mod.N_DATA] = data
        mats[k] = m
        key += mod.ELEMENTS
    return rows, mats


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
velocity = _dispatch("velocity", KINDS)
curvature = _dispatch("curvature", KINDS)
element = _dispatch("element", KINDS)
