"""Parameter rows for every pair of particle types and walls of a DEM simulation.

A particle type is a ``Sphere`` (radius and material); a wall is a ``Wall`` with its own material.
``pair_table`` builds one parameter row (``laws.slots``) per unordered sphere-sphere pair of types and per
sphere-wall pair, with the same effective properties and calibration as ``model.Scene`` (each row is the
``params`` of the Scene of that pair), and returns them as one 2D table plus the law ids that the 3D
kernels (``contact3d``) take.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from ..materials import Sphere, Wall
from ..laws.model import Scene
from ..laws.slots import P_NSPRING
from ..laws.table import vector_history_size as history_size


@dataclass(frozen=True, eq=False)
class PairTable:
    """Parameter table of a DEM simulation.

    params: float64[n_rows, N_PARAMS]; normal_id, tangential_id: the law ids the table is built for (every
    row records them, in its P_NORMAL_LAW and P_TANGENTIAL_LAW slots, and the checked entries of
    ``contact3d`` refuse the table with other ids); sphere_row: int64[n_types, n_types] row of each
    sphere-sphere pair (symmetric); wall_row: int64[n_types, n_walls] row of each sphere-wall pair;
    history_size: length of a 3D history row (``contact3d``, layout in ``laws.table``) for the laws (the
    twist and rolling laws of the rows included) and the largest MDR cell count of the table; scenes: the
    Scene of each row (a tuple).

    The table is immutable (its attributes cannot be assigned; the Scenes are immutable too): for other
    settings build another with ``pair_table``. Its arrays are the kernels' inputs, passed without copies."""

    params: np.ndarray
    normal_id: int
    tangential_id: int
    sphere_row: np.ndarray
    wall_row: np.ndarray
    history_size: int
    scenes: tuple = field(repr=False, default=())

    def __post_init__(self):
        """A table is consistent: its rows record its laws, its history rows fit them, its row indices
        are rows of params (a table built by hand, or by ``dataclasses.replace``, is checked too)."""
        from .contact3d import _check_table, _valid_ids

        nid, tid = _valid_ids(self.normal_id, self.tangential_id)
        need = _check_table(nid, tid, self.params)
        if isinstance(self.history_size, bool) or not isinstance(self.history_size, (int, np.integer)) \
                or self.history_size < need:
            raise InputError(f"history_size = {self.history_size!r}: the table's laws and rows need at least {need}")
        for name in ("sphere_row", "wall_row"):
            a = getattr(self, name)
            if not (isinstance(a, np.ndarray) and a.dtype == np.int64 and a.ndim == 2):
                raise InputError(f"{name} must be an int64 2D array")
            if a.size and (a.min() < 0 or a.max() >= len(self.params)):
                raise InputError(f"{name} holds rows outside params (valid: 0 to {len(self.params) - 1})")

    def describe(self) -> list:
        """``Scene.describe()`` of every row."""
        return [s.describe() for s in self.scenes]


def pair_table(spheres, walls=(), *, mu=0.3, normal: str = "hertz", tangential: str | None = None,
               e_n: float | None = None, v_ref: float | None = None, **scene_options) -> PairTable:
    """Parameter rows for all pairs of the particle types ``spheres`` (a sequence of Sphere) and the
    ``walls`` (a sequence of Wall).

    mu: one friction coefficient, or a float array of shape (n_types, n_types + n_walls): column j <
    n_types is the pair (i, j) (must be symmetric), column n_types + w the pair (i, wall w).
    normal, tangential (default: Scene's default), e_n, v_ref and ``scene_options`` (e.g. mdr_springs):
    as for ``Scene``, the same laws for every pair.
    Sphere-sphere rows use both radii and masses (1/R* = 1/R1 + 1/R2, 1/m* = 1/m1 + 1/m2); sphere-wall
    rows the wall's own material with 1/R2 = 0, 1/m2 = 0 (Johnson 1985, Contact Mechanics, section 4.2).
    """
    spheres = list(spheres)
    walls = list(walls)
    if not spheres:
        raise InputError("spheres must list at least one particle type (Sphere)")
    for i, s in enumerate(spheres):
        if not isinstance(s, Sphere):
            raise InputError(f"spheres[{i}] must be a Sphere")
    for w, wall in enumerate(walls):
        if not isinstance(wall, Wall):
            raise InputError(f"walls[{w}] must be a Wall")
    nt, nw = len(spheres), len(walls)
    mu_arr = np.asarray(mu, dtype=float)
    if mu_arr.ndim == 0:
        mu_arr = np.full((nt, nt + nw), float(mu_arr))
    if mu_arr.shape != (nt, nt + nw):
        raise InputError(f"mu must be a number or an array of shape (n_types, n_types + n_walls) = "
                         f"({nt}, {nt + nw}), got shape {mu_arr.shape}")
    if not np.all(np.isfinite(mu_arr)):
        raise InputError(f"mu (friction coefficient) must be finite, got {mu!r}")
    if not np.array_equal(mu_arr[:, :nt], mu_arr[:, :nt].T):
        raise InputError("mu[:, :n_types] (sphere-sphere friction) must be symmetric")
    laws = dict(scene_options, normal=normal, e_n=e_n, v_ref=v_ref)
    if tangential is not None:
        laws["tangential"] = tangential
    rows, scenes = [], []
    sphere_row = np.zeros((nt, nt), dtype=np.int64)
    wall_row = np.zeros((nt, nw), dtype=np.int64)
    for i in range(nt):
        for j in range(i, nt):
            sc = Scene(spheres[i], spheres[j], mu=mu_arr[i, j], **laws)
            sphere_row[i, j] = sphere_row[j, i] = len(rows)
            rows.append(sc.params)
            scenes.append(sc)
    for i in range(nt):
        for w in range(nw):
            sc = Scene(spheres[i], walls[w], mu=mu_arr[i, nt + w], **laws)
            wall_row[i, w] = len(rows)
            rows.append(sc.params)
            scenes.append(sc)
    params = np.ascontiguousarray(np.array(rows))
    nid, tid = scenes[0].normal_id, scenes[0].tangential_id
    cells = int(params[:, P_NSPRING].max())
    size = max(history_size(nid, tid, cells, sc.twist_id, sc.rolling_id) for sc in scenes)
    return PairTable(params=params, normal_id=nid, tangential_id=tid, sphere_row=sphere_row, wall_row=wall_row,
                     history_size=size, scenes=tuple(scenes))
