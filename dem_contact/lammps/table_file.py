"""The table file of ``pair_style dem/contact``: a ``PairTable`` and what the plugin needs of its Scenes,
written as JSON (``pair_coeff * * FILE``).

``save(table, path)`` writes it; ``load(path)`` reads it back and refuses a file of another format or package
version, or one whose laws this version lacks (``InputError``, naming what to do). The file holds the
parameter rows exactly (JSON numbers round-trip float64), the law names of the rows, each type's radius and
mass, whether the laws take atoms of any radius (``size_free``) and the rows' size and contact-time
information (``row_info`` at 1 m/s, with the exponent of the speed), and a description of every row for
people.
"""
from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass

import numpy as np

from ..version import __version__
from ..dem.pairs import PairTable
from ..errors import InputError
from ..laws import table as LT
from ..laws.slots import N_PARAMS, P_MSTAR, P_NORMAL_LAW, P_ROLLING_LAW, P_RSTAR, P_TANGENTIAL_LAW, P_TWIST_LAW
from . import contact_terms as T

#: the file's format name
FORMAT = "dem_contact pair table"

#: the per-row law slots and their families
_LAW_SLOTS = (("normal", P_NORMAL_LAW), ("tangential", P_TANGENTIAL_LAW), ("twist", P_TWIST_LAW),
              ("rolling", P_ROLLING_LAW))


#: the sizes the laws' rows are checked at: the first body's radius times this, the second's times the next
_SIZE_PROBE = (1.7, 0.6)


def size_free(table) -> tuple:
    """(whether every row of the table takes atoms of any radius, why not): the parameter row of the pair of
    types built for other radii (a Scene with the first body 1.7 times larger and the second 0.6 times) must
    be the row with that pair's R* and m* (``contact_terms.contact_row``: the slots of ``contact_terms.SIZE_SLOTS``
    scaled by powers of R*, the rest unchanged), and its contact time must scale as Hertz's
    (``contact_terms.size_factor``)."""
    from ..materials import Sphere

    for row, sc in enumerate(table.scenes):
        name = f"{sc.normal} + {sc.tangential}"
        s2 = sc.body2
        one = Sphere(sc.sphere.radius * _SIZE_PROBE[0], sc.sphere.material)
        two = Sphere(s2.radius * _SIZE_PROBE[1], s2.material) if isinstance(s2, Sphere) else s2
        try:
            other = sc.replace(sphere=one, body2=two)
        except InputError as e:
            return False, f"{name} for other radii: {e}"
        p, q = sc.params, other.params
        expect = p.copy()
        ratio = other.pair.R_star / sc.pair.R_star
        expect[P_RSTAR] = other.pair.R_star
        expect[P_MSTAR] = other.pair.m_star
        for slot, power in T.SIZE_SLOTS:
            expect[slot] = p[slot] * ratio**power
        if not np.allclose(q, expect, rtol=1e-12, atol=0.0):
            return False, f"the parameters of {name} depend on the radii otherwise than through R* and m*"
        scale = (other.pair.m_star**2 / other.pair.R_star / (sc.pair.m_star**2 / sc.pair.R_star)) ** 0.2
        v = 1.0
        if not math.isclose(other.contact_time(v) / sc.contact_time(v), scale, rel_tol=1e-9):
            return False, f"the contact time of {name} does not scale with the sizes as Hertz's"
    return True, ""


def row_info(table, v_max) -> np.ndarray:
    """float64[n_rows, contact_terms.N_ROWINFO]: per row of the table, R*, m*^2 / R*, the contact time at v_max and
    its exponent of the speed (t_c(v) = t_c(v_max) (v_max / v)^alpha, from t_c(2 v_max)), the overlap of a
    head-on impact at v_max (the normal law's own), a wall row's curvature (``materials.Wall.curvature``), and
    the exponent of the speed in that overlap (from the overlap at 2 v_max)."""
    info = np.zeros((len(table.scenes), T.N_ROWINFO))
    for row, sc in enumerate(table.scenes):
        tc = sc.contact_time(v_max)
        info[row, T.RI_RSTAR] = sc.pair.R_star
        info[row, T.RI_Q] = sc.pair.m_star**2 / sc.pair.R_star
        info[row, T.RI_TC] = tc
        info[row, T.RI_ALPHA] = math.log(tc / sc.contact_time(2.0 * v_max)) / math.log(2.0)
        info[row, T.RI_DEEPEST] = sc.max_contact_radius(v_max) ** 2 / sc.pair.R_star
        info[row, T.RI_DEEP_ALPHA] = math.log(sc.max_contact_radius(2.0 * v_max) ** 2 / sc.pair.R_star
                                              / info[row, T.RI_DEEPEST]) / math.log(2.0)
        info[row, T.RI_CURV] = getattr(sc.body2, "curvature", 0.0)
    return info


@dataclass(frozen=True)
class TableFile:
    """A table file read back: the PairTable (without Scenes), and per type (float64[n_types, 2]) radius and
    mass (its density follows), size_free, rowinfo float64[n_rows, contact_terms.N_ROWINFO] at 1 m/s, the
    contact time of each row at 1 m/s ``tc_unit`` and its exponent of the speed ``alpha`` (t_c(v) =
    tc_unit v^-alpha), and ``laws``: the rows' law names, for messages."""

    table: PairTable
    type_size: np.ndarray
    size_free: bool
    rowinfo: np.ndarray
    tc_unit: np.ndarray
    alpha: np.ndarray
    laws: str


def _law_names(params) -> list:
    """Per row, {family: law name} of its law slots (id + 1; 0: none)."""
    rows = []
    for p in params:
        names = {}
        for family, slot in _LAW_SLOTS:
            k = int(p[slot]) - 1
            names[family] = LT.FAMILIES[family][k].NAME if k >= 0 else None
        rows.append(names)
    return rows


def save(table: PairTable, path) -> str:
    """Write ``table`` (``dem.pairs.pair_table``) to the table file ``path`` (JSON) for ``pair_coeff * *
    path``; returns the path. Every sphere-sphere row of the table is written: its atom types are the
    table's spheres, in order (type k is spheres[k - 1])."""
    if not isinstance(table, PairTable):
        raise InputError("table must be a PairTable (dem_contact.dem.pairs.pair_table)")
    if not table.scenes:
        raise InputError("the table has no Scenes (a table read from a file): save the one pair_table built")
    nt = table.sphere_row.shape[0]
    spheres = [table.scenes[table.sphere_row[k, k]].sphere for k in range(nt)]
    free, why = size_free(table)
    info = row_info(table, 1.0)
    alpha = info[:, T.RI_ALPHA].copy()
    doc = dict(
        format=FORMAT, version=__version__,
        normal=LT.FAMILIES["normal"][table.normal_id].NAME,
        tangential=LT.FAMILIES["tangential"][table.tangential_id].NAME,
        laws=_law_names(table.params), params=table.params.tolist(), sphere_row=table.sphere_row.tolist(),
        wall_row=table.wall_row.tolist(), history_size=int(table.history_size),
        radius=[s.radius for s in spheres], mass=[s.mass for s in spheres], size_free=bool(free), size_free_why=why,
        rowinfo=info.tolist(), tc_unit=info[:, T.RI_TC].tolist(), alpha=alpha.tolist(),
        rows=[str(d) for d in table.describe()])
    path = os.fspath(path)
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
    return path


def _array(doc, name, dtype, shape, path):
    try:
        a = np.array(doc[name], dtype=dtype)
    except (KeyError, TypeError, ValueError):
        raise InputError(f"the table file {path} is corrupt (its {name!r} is missing or not numbers): write it "
                         f"again with dem_contact.lammps.table_file.save") from None
    if a.shape != shape or (a.dtype.kind == "f" and not np.all(np.isfinite(a))):
        raise InputError(f"the table file {path} is corrupt ({name!r} has shape {a.shape}, expected {shape}, or "
                         f"values that are not finite): write it again with dem_contact.lammps.table_file.save")
    return np.ascontiguousarray(a)


def load(path) -> TableFile:
    """Read the table file ``path`` (``save``); InputError if it is missing, corrupt, of another format or
    package version, or names laws this version lacks."""
    path = os.fspath(path)
    try:
        with open(path) as f:
            doc = json.load(f)
    except FileNotFoundError:
        raise InputError(f"the table file {path} does not exist: write it with "
                         f"dem_contact.lammps.table_file.save (or `dem-contact lammps-table`)") from None
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as e:
        raise InputError(f"the table file {path} cannot be read as JSON ({e}): write it again with "
                         f"dem_contact.lammps.table_file.save") from None
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise InputError(f"{path} is not a dem_contact pair table (its 'format' is not {FORMAT!r})")
    if doc.get("version") != __version__:
        raise InputError(f"the table file {path} was written by dem_contact {doc.get('version')}; this is "
                         f"{__version__}: write it again with this version (table_file.save)")
    laws = doc.get("laws")
    if not isinstance(laws, list):
        raise InputError(f"the table file {path} is corrupt (no 'laws' list)")
    for r, names in enumerate(laws):
        for family, slot in _LAW_SLOTS:
            name = names.get(family) if isinstance(names, dict) else None
            known = [m.NAME for m in LT.FAMILIES[family]]
            if name is not None and name not in known:
                raise InputError(f"the table file {path} needs the {family} law {name!r} (row {r}), which "
                                 f"dem_contact {__version__} lacks (it has {', '.join(known)})")
    params = _array(doc, "params", float, (len(laws), N_PARAMS), path)
    # the law ids of the rows are those of this version's names
    for r, names in enumerate(laws):
        for family, slot in _LAW_SLOTS:
            name = names.get(family)
            params[r, slot] = 0.0 if name is None else 1.0 + LT.ids(family)[name]
    nt = len(doc.get("radius", []))
    sphere_row = _array(doc, "sphere_row", np.int64, (nt, nt), path)
    wall_row = _array(doc, "wall_row", np.int64, (nt, len(doc["wall_row"][0]) if nt and doc.get("wall_row") else 0),
                      path)
    try:
        table = PairTable(params=params, normal_id=LT.ids("normal")[doc["normal"]],
                          tangential_id=LT.ids("tangential")[doc["tangential"]], sphere_row=sphere_row,
                          wall_row=wall_row, history_size=int(doc["history_size"]))
    except (KeyError, TypeError, ValueError, InputError) as e:
        raise InputError(f"the table file {path} is corrupt ({e}): write it again with "
                         f"dem_contact.lammps.table_file.save") from None
    size = np.stack([_array(doc, "radius", float, (nt,), path), _array(doc, "mass", float, (nt,), path)], axis=1)
    n_rows = len(laws)
    return TableFile(table=table, type_size=np.ascontiguousarray(size),
                     size_free=bool(doc.get("size_free")),
                     rowinfo=_array(doc, "rowinfo", float, (n_rows, T.N_ROWINFO), path),
                     tc_unit=_array(doc, "tc_unit", float, (n_rows,), path),
                     alpha=_array(doc, "alpha", float, (n_rows,), path),
                     laws=f"{doc['normal']} + {doc['tangential']}")
