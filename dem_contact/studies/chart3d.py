"""Speed-accuracy chart of the 3D tangential laws against the boundary-element reference on curved paths.

Scene: a steel sphere (R = 10 mm, E = 208 GPa, nu = 0.3) on a steel wall, mu = 0.3, at a constant overlap
(default 1e-5 m), driven along the comparison set of ``reference.paths`` (circle through the origin of
radius 0.3 and 0.6, straight load to 0.5 then a circle about the origin, L-turn after full slip,
figure-eight of size 0.6; sizes in units of the slip displacement mu delta / kappa). For every tangential
law of ``dem.contact3d`` the chart reports

- the error against the BEM reference: max over the rows of |T_law - T_BEM| / (mu N), the tangential
  force vectors compared (per path, and the max over the paths);
- the time per update of the 3D kernel along the path (warm JIT, the serial loop of ``paths.run_path``,
  best of ``repeats`` runs).

The reference forces are computed once (slow: ``reference_forces``) and can be stored and read back as
CSV (``write_reference`` / ``read_reference``).
"""
from __future__ import annotations

import csv
import math
import time
from dataclasses import dataclass

import numpy as np

from ..dem.contact3d import history_size, new_histories
from ..errors import InputError
from ..laws.model import TANGENTIAL_LAWS, Scene
from ..materials import STEEL, Sphere, Wall
from ..reference.bem import bem_path_scene
from ..reference.paths import COMPARISON_SET, scene_path
from .chart import write_csv  # noqa: F401  (re-exported: one CSV writer for both charts)
from .paths import _drive, check_path, path_scene, run_path

#: Constant overlap of the chart's paths [m].
DELTA = 1e-5
#: Steps per path.
PATH_STEPS = 400
#: BEM elements across the contact diameter of the reference.
N_ACROSS = 64
#: The laws charted: (label, tangential law, Scene options).
LAWS = tuple((t, t, {}) for t in TANGENTIAL_LAWS if t != "mdr") + (
    ("mdr", "mdr", {}), ("mdr (2000 springs)", "mdr", {"mdr_springs": 2000}),
    ("mdr_adaptive (64 cells)", "mdr_adaptive", {"mdr_springs": 64}))


def chart_scene(tangential: str = "mdr_adaptive", **options) -> Scene:
    """The chart's scene (steel on steel, R = 10 mm, mu = 0.3) with a tangential law."""
    return Scene(Sphere(0.01, STEEL), Wall(STEEL), mu=0.3, tangential=tangential, v_ref=5.0, **options)


def path_label(shape: str, size: float) -> str:
    return f"{shape} {size:g}"


def chart_paths(delta: float = DELTA, steps: int = PATH_STEPS, paths=COMPARISON_SET) -> dict:
    """label -> (delta, ux, uy) of the chart's paths."""
    sc = chart_scene()
    return {path_label(s, z): scene_path(s, z, steps, sc, delta) for s, z in paths}


def reference_forces(paths: dict, *, n_across: int = N_ACROSS, progress: bool = False) -> dict:
    """label -> (N, Tx, Ty) of the BEM reference along each path."""
    sc = chart_scene()
    out = {}
    for label, (d, x, y) in paths.items():
        t0 = time.perf_counter()
        out[label] = bem_path_scene(sc, d, x, y, n_across=n_across)
        if progress:
            print(f"  BEM {label}: {len(d)} steps, {time.perf_counter() - t0:.1f} s", flush=True)
    return out


def write_reference(path, paths: dict, forces: dict, n_across: int):
    """One row per step of every path: label, delta, ux, uy, N, Tx, Ty, n_across."""
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["path", "delta", "ux", "uy", "N", "Tx", "Ty", "n_across"])
        for label, (d, x, y) in paths.items():
            N, Tx, Ty = forces[label]
            for row in zip(d, x, y, N, Tx, Ty):
                w.writerow([label, *(repr(float(v)) for v in row), n_across])


def read_reference(path):
    """(paths, forces, n_across) from ``write_reference``'s CSV."""
    rows = {}
    n_across = None
    with open(path, newline="", encoding="utf-8-sig") as fh:   # BOM accepted
        for r in csv.DictReader(fh):
            rows.setdefault(r["path"], []).append([float(r[k]) for k in ("delta", "ux", "uy", "N", "Tx", "Ty")])
            n_across = int(r["n_across"])
    paths, forces = {}, {}
    for label, vals in rows.items():
        a = np.array(vals)
        paths[label] = (a[:, 0], a[:, 1], a[:, 2])
        forces[label] = (a[:, 3], a[:, 4], a[:, 5])
    return paths, forces, n_across


def force_error(N, Tx, Ty, ref, mu: float) -> float:
    """max over rows in contact of |T - T_ref| / (mu N_ref)."""
    Nr, Txr, Tyr = ref
    on = Nr > 0
    return float(np.max(np.hypot(Tx - Txr, Ty - Tyr)[on] / (mu * Nr[on])))


def time_per_update(scene: Scene, delta, ux, uy, repeats: int = 5) -> float:
    """Best time of one kernel update along the path [s] (warm JIT; the loop of ``run_path``)."""
    delta, ux, uy = check_path(delta, ux, uy, scene)
    sc = path_scene(scene, float(delta.max()))
    params = np.ascontiguousarray(sc.params[None, :])
    n = delta.size
    N, Tx, Ty, Mz, twist = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    hs = history_size(sc.normal_id, sc.tangential_id, sc.mdr_springs, sc.twist_id, sc.rolling_id)
    best = math.inf
    for _ in range(repeats + 1):            # the first run compiles or warms up
        H = new_histories(1, hs)
        t0 = time.perf_counter()
        _drive(sc.normal_id, sc.tangential_id, params, H, delta, ux, uy, twist, 1.0, N, Tx, Ty, Mz)
        best = min(best, time.perf_counter() - t0)
    return best / n


@dataclass
class Chart3DRow:
    law: str
    tangential: str
    path: str
    error: float              # max |T - T_BEM| / (mu N) along the path
    end_error: float          # the same at the last row
    time_per_update_ns: float


def chart3d(paths: dict, forces: dict, laws=LAWS, repeats: int = 5) -> list:
    """Rows of the chart: every law on every path (``paths``/``forces`` from ``chart_paths`` and
    ``reference_forces`` or ``read_reference``), plus a row per law with path "max" (the largest error,
    the mean time)."""
    rows = []
    for label, tangential, options in laws:
        if tangential not in TANGENTIAL_LAWS:
            raise InputError(f"tangential law {tangential!r} is unknown")
        sc = chart_scene(tangential, **options)
        per = []
        for pl, (d, x, y) in paths.items():
            N, Tx, Ty = run_path(sc, d, x, y)
            ref = forces[pl]
            Nr, Txr, Tyr = ref
            end = math.hypot(Tx[-1] - Txr[-1], Ty[-1] - Tyr[-1]) / (sc.mu * Nr[-1])
            per.append(Chart3DRow(label, tangential, pl, force_error(N, Tx, Ty, ref, sc.mu), end,
                                  1e9 * time_per_update(sc, d, x, y, repeats)))
        rows.extend(per)
        rows.append(Chart3DRow(label, tangential, "max", max(r.error for r in per), max(r.end_error for r in per),
                               float(np.mean([r.time_per_update_ns for r in per]))))
    return rows


@dataclass
class SpinImpactRow:
    law: str
    error: float              # max over the BEM spin cases of |f - f_BEM| / mu (impulse-ratio vectors)
    time_per_impact_us: float


def spin_impact_chart(reference, laws=LAWS, vn: float = 5.0, repeats: int = 20, scene: Scene | None = None) -> list:
    """Every law on the spinning impacts of ``reference`` (``studies.spin.bem_spin_reference``, of ``scene``,
    default the EE scene): the largest error of the impulse-ratio vector and the time of one impact (bare
    kernel, warm JIT) at the BEM's steps per contact, for the first case. Each law's scene is ``scene`` with
    that law and its options, reference speed vn, every other setting kept."""
    from ..impacts.presets import preset_scene
    from ..impacts.sweep import scene_with
    from .spin import compare_spin_cases, time_per_impact

    base = preset_scene("EE", vn) if scene is None else scene
    out = []
    for label, tangential, options in laws:
        sc = scene_with(base, tangential=tangential, v_ref=vn, **options)
        err = max(r.error for r in compare_spin_cases({label: sc}, reference, vn))
        b = reference[0]
        t = time_per_impact(sc, vn, (b.vt, 0.0), (b.spin_x, 0.0, 0.0), b.steps, repeats)
        out.append(SpinImpactRow(label, err, 1e6 * t))
    return out
