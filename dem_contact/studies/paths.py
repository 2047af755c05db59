"""Prescribed loading paths: what a contact law does along a given history of the overlap, of the
tangential displacement vector and of the twist about the normal.

A path is three or four arrays of equal length, one row per step: ``delta`` (normal overlap [m]; <= 0 means
no contact: the history is released), ``ux, uy`` (tangential displacement of body 1 relative to body 2 at
the contact point, components in the tangent plane [m]) and, optionally, ``twist`` (rotation of body 1
relative to body 2 about the normal n from body 1 to body 2, right-handed [rad]). The contact starts
unloaded and undisplaced before the first row. ``run_path`` drives the 3D per-contact kernel
(``dem.contact3d.contact_force_torque``) with the normal n = +z, the relative velocity increment/dt, the
relative spin (0, 0, d twist/dt) (a twist increment is a relative rotation about the normal) and no
rotation of the contact frame (the mean spin of the bodies about the normal is zero: the displacements
are measured in the mean frame, as the reference measures them). It returns the normal force N, the
tangential force (Tx, Ty) on body 1 (it opposes the displacement: T = -k u in the elastic limit) and, for a
path with a twist, the moment Mz on body 1 about the normal from the scene's twist law (it opposes the
twist; 0 with the twist law ``none``). ``reference_path`` gives the same from the boundary-element
reference (``reference.bem``), whose moment is that of the exact traction field.

Named paths at constant overlap (circle, load-circle, l-turn, figure-eight, load-unload; twist-cycle,
shear-twist, circle-twist; sizes in units of the slip displacement mu delta / kappa and of the no-slip
twist at unit moment) are built by ``reference.paths``.
"""
from __future__ import annotations

import csv
import math

import numpy as np
from numba import njit

from ..dem.contact3d import contact_force_torque, history_size, new_histories, reset_contact
from ..errors import InputError, NumericalError, kernel_failed
from ..laws.model import Scene
from ..materials import check_finite

#: Columns of a path CSV (``twist`` is optional).
COLUMNS = ("delta", "ux", "uy")
#: The optional twist column of a path CSV [rad].
TWIST_COLUMN = "twist"


@njit(cache=True)
def _drive(nid, tid, params, H, delta, ux, uy, twist, dt, N, Tx, Ty, Mz):
    """Advance one contact along the path (kernel calls of this module are here only)."""
    d0 = 0.0
    x0 = 0.0
    y0 = 0.0
    b0 = 0.0
    for k in range(delta.shape[0]):
        if delta[k] > 0.0:
            vx = (ux[k] - x0) / dt
            vy = (uy[k] - y0) / dt
            vz = (delta[k] - d0) / dt
            wz = (twist[k] - b0) / dt
            fx, fy, fz, tx, ty, tz, mx, my, mz = contact_force_torque(nid, tid, params, 0, H, 0, 0.0, 0.0, 1.0,
                                                                      delta[k], vx, vy, vz, 0.0, 0.0, wz, 0.0, dt)
            N[k] = -fz
            Tx[k] = tx
            Ty[k] = ty
            Mz[k] = mz
        else:
            reset_contact(H, 0)
            N[k] = 0.0
            Tx[k] = 0.0
            Ty[k] = 0.0
            Mz[k] = 0.0
        d0 = delta[k]
        x0 = ux[k]
        y0 = uy[k]
        b0 = twist[k]


def check_path(delta, ux, uy, scene: Scene | None = None, *, twist=None):
    """The path as float64 arrays of equal length, (delta, ux, uy) or with ``twist`` (delta, ux, uy,
    twist) (InputError naming the bad value); with ``scene``, every overlap below its effective radius R*
    (the contact laws hold for overlaps far below it)."""
    names = COLUMNS + (() if twist is None else (TWIST_COLUMN,))
    arrs = []
    for name, x in zip(names, (delta, ux, uy, twist)):
        a = np.ascontiguousarray(np.atleast_1d(np.asarray(x, dtype=float)))
        if a.ndim != 1 or a.size == 0:
            raise InputError(f"{name} must be a non-empty one-dimensional array")
        bad = np.flatnonzero(~np.isfinite(a))
        if bad.size:
            raise InputError(f"{name}[{bad[0]}] = {a[bad[0]]} is not finite")
        arrs.append(a)
    if len({a.size for a in arrs}) != 1:
        raise InputError(f"{', '.join(names[:-1])} and {names[-1]} must have the same length (got "
                         f"{', '.join(str(a.size) for a in arrs)})")
    if scene is not None:
        deep = np.flatnonzero(arrs[0] >= scene.pair.R_star)
        if deep.size:
            raise InputError(f"delta[{deep[0]}] = {arrs[0][deep[0]]:g} m is not below the pair's effective radius "
                             f"R* = {scene.pair.R_star:g} m (the contact laws hold for overlaps far below it)")
    return arrs


def path_scene(scene: Scene, delta_max: float) -> Scene:
    """The scene itself, or for a law whose springs are placed (``mdr``: it takes ``mdr_max_radius``) the same
    scene with springs covering the contact radius sqrt(R* delta_max) of the path (a path has no impact speed
    to place them)."""
    if "mdr_max_radius" not in scene.tangential_law.OPTIONS:
        return scene
    a = math.sqrt(scene.pair.R_star * max(delta_max, 0.0))
    if a <= 0.0:
        return scene
    return scene.replace(mdr_springs=scene.mdr_springs, mdr_max_radius=1.05 * a)


def coupled_path(scene: Scene, delta, ux, uy, twist=None):
    """(N, Tx, Ty, Mz) [N, N m] along a path, as ``run_path``, with the tangential force and the moment of one
    local state: ``laws.twist_shear.twist_shear_path`` (the cells of the default tangential law and of the
    exact twist law ``deresiewicz`` sharing the Coulomb limit at points of each ring), for a Hertz contact
    (the scene's materials, mu and R*): the Hertz normal force and contact radius of each row's overlap
    (Johnson 1985, eq. 4.23; an overlap <= 0: no contact, the history released). The path starts from
    rest, out of contact, before its first row. InputError for another normal law."""
    from ..laws.closed_forms import hertz_force
    from ..laws.twist.deresiewicz import twist_modulus
    from ..laws.twist_shear import twist_shear_path

    if not isinstance(scene, Scene):
        raise InputError("scene must be a Scene")
    if scene.normal != "hertz":
        raise InputError(f"the coupled twist and shear law is for a Hertz contact (normal 'hertz'), got "
                         f"{scene.normal!r}")
    delta, ux, uy, tw = check_path(delta, ux, uy, scene, twist=np.zeros(np.size(delta)) if twist is None else twist)
    pr = scene.pair
    d = np.maximum(delta, 0.0)
    a = np.sqrt(pr.R_star * d)
    N = hertz_force(pr.E_star, pr.R_star, d)
    z = np.zeros(1)
    Tx, Ty, M, _ = twist_shear_path(pr.G_star, twist_modulus(scene.sphere, scene.body2), scene.mu, pr.R_star,
                                    np.concatenate([z, N]), np.concatenate([z, a]), np.concatenate([z, ux]),
                                    np.concatenate([z, uy]), np.concatenate([z, tw]))
    return N, Tx[1:], Ty[1:], M[1:]


def run_path(scene: Scene, delta, ux, uy, twist=None, *, dt: float = 1.0):
    """Forces of the scene's laws along the path: (N, Tx, Ty), float arrays [N], one per row; with
    ``twist`` [rad] per row, (N, Tx, Ty, Mz), Mz the moment on body 1 about the normal [N m] of the scene's
    twist law (``Scene(twist=...)``; 0 with ``none``: that law ignores the twist).

    dt: time per row [s] (the relative velocity is increment / dt and the relative spin twist increment /
    dt; only dashpots see it, default 1 s: quasi-static). For the ``mdr`` law the springs are placed for the
    path's largest overlap."""
    if not isinstance(scene, Scene):
        raise InputError("scene must be a Scene")
    cols = check_path(delta, ux, uy, scene, twist=twist)
    delta, ux, uy = cols[:3]
    tw = cols[3] if twist is not None else np.zeros(delta.size)
    dt = check_finite("dt (time per row, s)", dt, lo=0.0)
    sc = path_scene(scene, float(delta.max()))
    H = new_histories(1, history_size(sc.normal_id, sc.tangential_id, sc.mdr_springs, sc.twist_id, sc.rolling_id))
    out = N, Tx, Ty, Mz = (np.zeros(delta.size), np.zeros(delta.size), np.zeros(delta.size), np.zeros(delta.size))
    try:
        _drive(sc.normal_id, sc.tangential_id, np.ascontiguousarray(sc.params[None, :]), H, delta, ux, uy, tw, dt,
               N, Tx, Ty, Mz)
    except Exception as e:      # a failure inside the compiled code: no result
        raise kernel_failed(e, f"the {sc.normal}/{sc.tangential}/{sc.twist} kernels along the path") from None
    if not all(np.all(np.isfinite(v)) for v in out):
        raise NumericalError(f"non-finite force or moment along the path ({sc.normal}/{sc.tangential}/{sc.twist})")
    return out if twist is not None else out[:3]


def reference_path(scene: Scene, delta, ux, uy, twist=None, *, n_across: int = 64):
    """(N, Tx, Ty) of the boundary-element reference along the path (``reference.bem``: Hertz pressure, the
    Cattaneo-Mindlin tangential problem with the twist, solved on ``n_across`` elements across the largest
    contact); with ``twist``, (N, Tx, Ty, Mz)."""
    from ..reference.bem import bem_path_scene

    cols = check_path(delta, ux, uy, scene, twist=twist)
    return bem_path_scene(scene, *cols, n_across=n_across)


def read_path_csv(path) -> tuple:
    """Read a path CSV: a header naming the columns delta, ux, uy and optionally twist (any order, other
    columns ignored, lines starting with # skipped), then one row per step [m, rad]; UTF-8, with or without
    a byte-order mark (as spreadsheets write it). Returns (delta, ux, uy), or (delta, ux, uy, twist) when
    the header has a twist column."""
    try:
        with open(path, newline="", encoding="utf-8-sig") as fh:
            rows = [r for r in csv.reader(fh) if r and not r[0].lstrip().startswith("#")]
    except OSError as e:
        raise InputError(f"cannot read the path CSV {path}: {e.strerror}") from None
    except UnicodeDecodeError as e:
        raise InputError(f"the path CSV {path} is not UTF-8 text (byte {e.start}): save it as UTF-8 CSV") from None
    if not rows:
        raise InputError(f"the path CSV {path} is empty: it needs a header delta,ux,uy[,twist] and one row per step")
    header = [h.strip() for h in rows[0]]
    missing = [c for c in COLUMNS if c not in header]
    if missing:
        raise InputError(f"the path CSV {path} lacks the column(s) {', '.join(missing)} in its header "
                         f"(got: {','.join(header)}); expected delta,ux,uy and optionally twist")
    names = COLUMNS + ((TWIST_COLUMN,) if TWIST_COLUMN in header else ())
    idx = [header.index(c) for c in names]
    if len(rows) < 2:
        raise InputError(f"the path CSV {path} has a header but no rows")
    out = np.empty((len(rows) - 1, len(names)))
    for i, r in enumerate(rows[1:]):
        for j, c in enumerate(idx):
            try:
                out[i, j] = float(r[c])
            except (IndexError, ValueError):
                raise InputError(f"{path}, data row {i + 1}: column {names[j]} = "
                                 f"{r[c] if c < len(r) else '(missing)'!r} is not a number") from None
    return tuple(check_path(*out.T[:3], twist=out[:, 3] if len(names) == 4 else None))


def write_path_csv(path, delta, ux, uy, N, Tx, Ty, *, twist=None, Mz=None):
    """One row per step: delta, ux, uy [m], N, Tx, Ty [N]; with ``twist`` and ``Mz``, delta, ux, uy [m],
    twist [rad], N, Tx, Ty [N], Mz [N m]."""
    if (twist is None) != (Mz is None):
        raise InputError("give both twist and Mz, or neither")
    header = ["delta", "ux", "uy", "N", "Tx", "Ty"]
    cols = [delta, ux, uy, N, Tx, Ty]
    if twist is not None:
        header = ["delta", "ux", "uy", "twist", "N", "Tx", "Ty", "Mz"]
        cols = [delta, ux, uy, twist, N, Tx, Ty, Mz]
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        for row in zip(*cols):
            w.writerow([repr(float(v) + 0.0) for v in row])
