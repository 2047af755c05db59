"""Prescribed loading paths: what a contact law does along a given history of the overlap and of the
tangential displacement vector.

A path is three arrays of equal length, one row per step: ``delta`` (normal overlap [m]; <= 0 means no
contact: the history is released) and ``ux, uy`` (tangential displacement of body 1 relative to body 2 at
the contact point, components in the tangent plane [m]). The contact starts unloaded and undisplaced
before the first row. ``run_path`` drives the 3D per-contact kernel (``dem.contact3d``) with the normal
n = +z, the relative velocity increment/dt and no rotation of the contact frame, and returns the normal
force N and the tangential force (Tx, Ty) on body 1 (it opposes the displacement: T = -k u in the elastic
limit). ``reference_path`` gives the same from the boundary-element reference (``reference.bem``).

Named paths at constant overlap (circle, load-circle, l-turn, figure-eight, load-unload; sizes in units of
the slip displacement mu delta / kappa) are built by ``reference.paths``.
"""
from __future__ import annotations

import csv
import math

import numpy as np
from numba import njit

from ..dem.contact3d import contact_force, history_size, new_histories, reset_contact
from ..errors import InputError, NumericalError, kernel_failed
from ..laws.model import Scene
from ..materials import check_finite

#: Columns of a path CSV.
COLUMNS = ("delta", "ux", "uy")


@njit(cache=True)
def _drive(nid, tid, params, H, delta, ux, uy, dt, N, Tx, Ty):
    """Advance one contact along the path (kernel calls of this module are here only)."""
    d0 = 0.0
    x0 = 0.0
    y0 = 0.0
    for k in range(delta.shape[0]):
        if delta[k] > 0.0:
            vx = (ux[k] - x0) / dt
            vy = (uy[k] - y0) / dt
            vz = (delta[k] - d0) / dt
            fx, fy, fz, tx, ty, tz = contact_force(nid, tid, params, 0, H, 0, 0.0, 0.0, 1.0, delta[k],
                                                   vx, vy, vz, 0.0, dt)
            N[k] = -fz
            Tx[k] = tx
            Ty[k] = ty
        else:
            reset_contact(H, 0)
            N[k] = 0.0
            Tx[k] = 0.0
            Ty[k] = 0.0
        d0 = delta[k]
        x0 = ux[k]
        y0 = uy[k]


def check_path(delta, ux, uy, scene: Scene | None = None):
    """The path as three float64 arrays of equal length (InputError naming the bad value); with ``scene``,
    every overlap below its effective radius R* (the contact laws hold for overlaps far below it)."""
    arrs = []
    for name, x in zip(COLUMNS, (delta, ux, uy)):
        a = np.ascontiguousarray(np.atleast_1d(np.asarray(x, dtype=float)))
        if a.ndim != 1 or a.size == 0:
            raise InputError(f"{name} must be a non-empty one-dimensional array")
        bad = np.flatnonzero(~np.isfinite(a))
        if bad.size:
            raise InputError(f"{name}[{bad[0]}] = {a[bad[0]]} is not finite")
        arrs.append(a)
    if not arrs[0].size == arrs[1].size == arrs[2].size:
        raise InputError(f"delta, ux and uy must have the same length (got {arrs[0].size}, {arrs[1].size}, "
                         f"{arrs[2].size})")
    if scene is not None:
        deep = np.flatnonzero(arrs[0] >= scene.pair.R_star)
        if deep.size:
            raise InputError(f"delta[{deep[0]}] = {arrs[0][deep[0]]:g} m is not below the pair's effective radius "
                             f"R* = {scene.pair.R_star:g} m (the contact laws hold for overlaps far below it)")
    return arrs


def path_scene(scene: Scene, delta_max: float) -> Scene:
    """The scene itself, or for the ``mdr`` law the same scene with springs covering the contact radius
    sqrt(R* delta_max) of the path (a path has no impact speed to place them)."""
    if scene.tangential != "mdr":
        return scene
    a = math.sqrt(scene.pair.R_star * max(delta_max, 0.0))
    if a <= 0.0:
        return scene
    return scene.replace(mdr_springs=scene.mdr_springs, mdr_max_radius=1.05 * a)


def run_path(scene: Scene, delta, ux, uy, *, dt: float = 1.0):
    """Forces of the scene's laws along the path: (N, Tx, Ty), float arrays [N], one per row.

    dt: time per row [s] (the relative velocity is increment / dt; only dashpots see it, default 1 s:
    quasi-static). For the ``mdr`` law the springs are placed for the path's largest overlap."""
    if not isinstance(scene, Scene):
        raise InputError("scene must be a Scene")
    delta, ux, uy = check_path(delta, ux, uy, scene)
    dt = check_finite("dt (time per row, s)", dt, lo=0.0)
    sc = path_scene(scene, float(delta.max()))
    H = new_histories(1, history_size(sc.normal_id, sc.tangential_id, sc.mdr_springs))
    N, Tx, Ty = np.zeros(delta.size), np.zeros(delta.size), np.zeros(delta.size)
    try:
        _drive(sc.normal_id, sc.tangential_id, np.ascontiguousarray(sc.params[None, :]), H, delta, ux, uy, dt, N,
               Tx, Ty)
    except Exception as e:      # a failure inside the compiled code: no result
        raise kernel_failed(e, f"the {sc.normal}/{sc.tangential} kernels along the path") from None
    if not (np.all(np.isfinite(N)) and np.all(np.isfinite(Tx)) and np.all(np.isfinite(Ty))):
        raise NumericalError(f"non-finite force along the path ({sc.normal}/{sc.tangential})")
    return N, Tx, Ty


def reference_path(scene: Scene, delta, ux, uy, *, n_across: int = 64):
    """(N, Tx, Ty) of the boundary-element reference along the path (``reference.bem``: Hertz pressure, the
    Cattaneo-Mindlin tangential problem solved on ``n_across`` elements across the largest contact)."""
    from ..reference.bem import bem_path_scene

    delta, ux, uy = check_path(delta, ux, uy, scene)
    return bem_path_scene(scene, delta, ux, uy, n_across=n_across)


def read_path_csv(path) -> tuple:
    """Read a path CSV: a header naming the columns delta, ux, uy (any order, other columns ignored,
    lines starting with # skipped), then one row per step [m]; UTF-8, with or without a byte-order mark (as
    spreadsheets write it). Returns (delta, ux, uy)."""
    try:
        with open(path, newline="", encoding="utf-8-sig") as fh:
            rows = [r for r in csv.reader(fh) if r and not r[0].lstrip().startswith("#")]
    except OSError as e:
        raise InputError(f"cannot read the path CSV {path}: {e.strerror}") from None
    except UnicodeDecodeError as e:
        raise InputError(f"the path CSV {path} is not UTF-8 text (byte {e.start}): save it as UTF-8 CSV") from None
    if not rows:
        raise InputError(f"the path CSV {path} is empty: it needs a header delta,ux,uy and one row per step")
    header = [h.strip() for h in rows[0]]
    missing = [c for c in COLUMNS if c not in header]
    if missing:
        raise InputError(f"the path CSV {path} lacks the column(s) {', '.join(missing)} in its header "
                         f"(got: {','.join(header)}); expected delta,ux,uy")
    idx = [header.index(c) for c in COLUMNS]
    if len(rows) < 2:
        raise InputError(f"the path CSV {path} has a header but no rows")
    out = np.empty((len(rows) - 1, 3))
    for i, r in enumerate(rows[1:]):
        for j, c in enumerate(idx):
            try:
                out[i, j] = float(r[c])
            except (IndexError, ValueError):
                raise InputError(f"{path}, data row {i + 1}: column {COLUMNS[j]} = "
                                 f"{r[c] if c < len(r) else '(missing)'!r} is not a number") from None
    return check_path(out[:, 0], out[:, 1], out[:, 2])


def write_path_csv(path, delta, ux, uy, N, Tx, Ty):
    """One row per step: delta, ux, uy [m], N, Tx, Ty [N]."""
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["delta", "ux", "uy", "N", "Tx", "Ty"])
        for row in zip(delta, ux, uy, N, Tx, Ty):
            w.writerow([repr(float(v)) for v in row])
