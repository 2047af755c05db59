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

Twist paths (``twist_chart``): the three paths of ``reference.paths.TWIST_SET`` (a twist cycle to 2 beta_1
and back; shear to 0.6 of slip then a twist out to beta_1 and back; a circle of radius 0.4 with a twist
0.4 beta_1 sin 2 phi) with the default tangential law and each twist law of ``TWIST_LAWS``, against the
BEM histories with twist (``read_twist_reference``): the force error max |T - T_BEM| / (mu N), the moment
error max |Mz - Mz_BEM| / (mu N a) and the time per update. The tangential and twist laws are separate
(each has its own Coulomb limit), while in the BEM the twist and the shear share the local limit
|q| <= mu p: on the shear-twist path the BEM's force falls as the contact is twisted and the separate laws'
does not, which the chart shows. The engine model ``sds`` needs coefficients: ``sds_hertz_values`` gives
the Hertz values at the path's overlap, the no-slip stiffness k = (16/3) G_c a^3 (Johnson 1985, section
7.4) and the slider mu_twist = (3 pi/16) mu a of Lubkin's (1951) full-slip moment, no dashpot.
"""
from __future__ import annotations

import csv
import math
import time
from dataclasses import dataclass

import numpy as np

from ..dem.contact3d import history_size, new_histories
from ..errors import InputError
from ..laws import table
from ..laws.model import TANGENTIAL_LAWS, Scene, law_of, reference_speed
from ..materials import STEEL, Sphere, Wall
from ..reference.bem import bem_path_scene
from ..reference.paths import COMPARISON_SET, TWIST_SET, scene_path, twist_modulus
from .chart import write_csv  # noqa: F401  (re-exported: one CSV writer for both charts)
from .paths import _drive, check_path, path_scene, run_path

#: Constant overlap of the chart's paths [m].
DELTA = 1e-5
#: Steps per path.
PATH_STEPS = 400
#: BEM elements across the contact diameter of the reference.
N_ACROSS = 64
#: The laws charted: (label, tangential law, Scene options).
LAWS = tuple((t, t, {}) for t in TANGENTIAL_LAWS) + (
    ("mdr (2000 springs)", "mdr", {"mdr_springs": 2000}),
    ("mdr_adaptive (64 cells)", "mdr_adaptive", {"mdr_springs": 64}))


def chart_scene(tangential: str = "mdr_adaptive", **options) -> Scene:
    """The chart's scene (steel on steel, R = 10 mm, mu = 0.3) with a tangential law."""
    return Scene(Sphere(0.01, STEEL), Wall(STEEL), mu=0.3, tangential=tangential, v_ref=reference_speed(5.0), **options)


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


def time_per_update(scene: Scene, delta, ux, uy, repeats: int = 5, twist=None) -> float:
    """Best time of one kernel update along the path [s] (warm JIT; the loop of ``run_path``), with the
    twist [rad] per row if given."""
    cols = check_path(delta, ux, uy, scene, twist=twist)
    delta, ux, uy = cols[:3]
    sc = path_scene(scene, float(delta.max()))
    params = np.ascontiguousarray(sc.params[None, :])
    n = delta.size
    N, Tx, Ty, Mz = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    twist = cols[3] if twist is not None else np.zeros(n)
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


#: The twist laws of the twist chart (with the default tangential law).
TWIST_LAWS = tuple(table.ids("twist"))


def contact_radius(scene: Scene, delta: float) -> float:
    """Hertz contact radius a = sqrt(R* delta) [m]."""
    return math.sqrt(scene.pair.R_star * delta)


def sds_hertz_values(scene: Scene, delta: float) -> dict:
    """Coefficients of the engine model twist ``sds`` equal to a Hertz contact's at overlap ``delta``: the
    no-slip twist stiffness k_twist = (16/3) G_c a^3 [N m/rad] (Johnson 1985, section 7.4; 1/G_c = 1/G1 +
    1/G2) and the slider mu_twist = (3 pi/16) mu a [m] (the limit mu_twist N is Lubkin's 1951 full-slip
    moment), no dashpot."""
    m1, m2 = scene.sphere.material, scene.body2.material
    a = contact_radius(scene, delta)
    Gc = twist_modulus(m1.E, m1.nu, m2.E, m2.nu)
    return {"k_twist": 16.0 / 3.0 * Gc * a**3, "gamma_twist": 0.0, "mu_twist": 3.0 * math.pi / 16.0 * scene.mu * a}


def twist_scene(twist: str, delta: float = DELTA, tangential: str = "mdr_adaptive") -> Scene:
    """The chart's scene with a twist law (``sds`` with ``sds_hertz_values`` at ``delta``)."""
    sc = chart_scene(tangential)
    opts = sds_hertz_values(sc, delta) if "k_twist" in law_of("twist", twist).OPTIONS else {}
    return chart_scene(tangential, twist=twist, **opts)


def twist_paths(delta: float = DELTA, steps: int = PATH_STEPS, paths=TWIST_SET) -> dict:
    """label -> (delta, ux, uy, twist) of the chart's twist paths."""
    sc = chart_scene()
    return {path_label(s, z): scene_path(s, z, steps, sc, delta) for s, z in paths}


def read_twist_reference(path):
    """((delta, ux, uy, twist), (N, Tx, Ty, Mz)) of a BEM history with twist written as CSV with the header
    delta,ux,uy,twist,N,Tx,Ty,Mz (``validation/bem/twist.py``)."""
    with open(path, newline="", encoding="utf-8-sig") as fh:
        r = csv.reader(fh)
        head = next(r)
        a = np.array([[float(v) for v in row] for row in r])
    cols = ("delta", "ux", "uy", "twist", "N", "Tx", "Ty", "Mz")
    if tuple(h.strip() for h in head) != cols or a.ndim != 2 or a.shape[1] != 8:
        raise InputError(f"{path}: a BEM history with twist needs the columns {','.join(cols)}")
    return tuple(a[:, j] for j in range(4)), tuple(a[:, j] for j in range(4, 8))


@dataclass
class TwistChartRow:
    twist: str                # the twist law (tangential law: the default)
    path: str
    force_error: float        # max |T - T_BEM| / (mu N) along the path
    moment_error: float       # max |Mz - Mz_BEM| / (mu N a) along the path
    time_per_update_ns: float


def twist_chart(paths: dict, references: dict, twist_laws=TWIST_LAWS, repeats: int = 5) -> list:
    """Rows of the twist chart: every twist law (default tangential law) on every path. ``paths``: label ->
    (delta, ux, uy, twist) (``twist_paths``); ``references``: label -> (N, Tx, Ty, Mz) of the BEM on the
    same rows. The moment error is scaled by mu N a of the reference's row (a = sqrt(R* delta))."""
    rows = []
    for law in twist_laws:
        for pl, (d, x, y, t) in paths.items():
            sc = twist_scene(law, float(np.max(d)))
            N, Tx, Ty, Mz = run_path(sc, d, x, y, t)
            Nr, Txr, Tyr, Mzr = references[pl]
            if Nr.size != d.size:
                raise InputError(f"the reference of {pl!r} has {Nr.size} rows, the path {d.size}")
            on = Nr > 0
            a = np.sqrt(sc.pair.R_star * d[on])
            m_err = float(np.max(np.abs(Mz - Mzr)[on] / (sc.mu * Nr[on] * a)))
            rows.append(TwistChartRow(law, pl, force_error(N, Tx, Ty, (Nr, Txr, Tyr), sc.mu), m_err,
                                      1e9 * time_per_update(sc, d, x, y, repeats, twist=t)))
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
        sc = scene_with(base, tangential=tangential, v_ref=reference_speed(vn), **options)
        err = max(r.error for r in compare_spin_cases({label: sc}, reference, vn))
        b = reference[0]
        t = time_per_impact(sc, vn, (b.vt, 0.0), (b.spin_x, 0.0, 0.0), b.steps, repeats)
        out.append(SpinImpactRow(label, err, 1e6 * t))
    return out
