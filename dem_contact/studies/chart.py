"""Speed-accuracy chart of the tangential laws against the exact reference (MDR, Popov & Hess 2015, chapter 6).

For each tangential law, normal law (hertz, thornton), integrator end (located / standard) and number of
steps per contact, the impacts of a Theta grid in [0, Theta_max] (EE steel scene of Wu et al. 2009 by
default, no spin, fixed normal speed) are integrated in a serial jitted loop; the chart reports

- the error against converged MDR (max over the grid of |error| in f/mu, e_t, Omega_r, e_n);
- its split into the model error (the law at its converged setting against converged MDR) and the
  discretisation error (the law at this setting against itself converged, same integrator end);
- the measured time per impact (warm JIT, best of ``repeats`` runs of the whole grid).

All laws see the same incident velocities (vt from the target Theta and the reference e_n). The Pareto
front (no other method is both faster and more accurate in f/mu) is marked per normal law.
"""
from __future__ import annotations

import csv
import time
from dataclasses import asdict, dataclass

import numpy as np
from numba import njit

from ..errors import InputError, kernel_failed
from ..impacts.impact import E_N_EXCESS_TOL, MAX_CONTACT_TIMES, body_inertia
from ..impacts.integrator import N_OUT, N_SERIES, O_PN, O_PT, O_SLID, O_STATUS, O_VN, O_VT, O_W1, integrate_impact, is_sliding
from ..materials import STEEL, Material, Sphere, Wall
from ..laws.model import TANGENTIAL_LAWS, Scene, law_of, reference_speed

#: Settings of the converged MDR reference.
REFERENCE_SPRINGS = 400
REFERENCE_STEPS = 4000
DEFAULT_STEPS = (5, 20, 100, 1000)
FULL_STEPS = (5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000)
NORMALS = ("hertz", "thornton")
SCHEMES = ("located", "standard")
#: thornton scenes are calibrated to this e_n at the impact speed.
THORNTON_E_N = 0.7


@njit(cache=True)
def run_grid(nid, tid, p, hist, vn, vt, spin, inv_m, R1, inv_I1, dt, max_steps, locate, out):
    """Serial loop over impacts on a wall at normal speed vn [m/s], tangential speeds vt[i] [m/s] and
    initial spin ``spin`` [rad/s]: hist: float64[n, n_hist] (zeroed here), out: float64[n, N_OUT]."""
    series = np.zeros((0, N_SERIES))
    for i in range(vt.shape[0]):
        hist[i, :] = 0.0
        integrate_impact(nid, tid, p, hist[i], vn, vt[i], spin, 0.0, inv_m, R1, 0.0, inv_I1, 0.0,
                         dt, max_steps, locate, out[i], series)


@dataclass
class GridRun:
    f_over_mu: np.ndarray
    e_t: np.ndarray
    Omega_r: np.ndarray
    e_n: np.ndarray
    seconds_per_impact: float
    persistent_sliding: np.ndarray | None = None


def run(scene: Scene, vn: float, vt: np.ndarray, spc: float, scheme: str, repeats: int = 1,
        spin: float = 0.0) -> GridRun:
    """Integrate the impacts of ``vt`` (wall, initial spin ``spin``) and time them (best of ``repeats``
    after a warm-up). Omega_r is relative to the reference (2 R omega_r / (5 (1 + e_n) mu vn))."""
    inv_m, R1, _, inv_I1, _ = body_inertia(scene)
    dt = scene.contact_time(vn) / spc
    max_steps = int(MAX_CONTACT_TIMES * spc) + 10
    hist = np.zeros((vt.size, scene.history_size))
    out = np.zeros((vt.size, N_OUT))
    args = (scene.normal_id, scene.tangential_id, scene.params, hist, vn, vt, spin, inv_m, R1, inv_I1, dt,
            max_steps, scheme == "located", out)
    best = np.inf
    for k in range(repeats + 1):        # the first run loads or compiles the kernel, untimed
        t0 = time.perf_counter()
        try:
            run_grid(*args)
        except Exception as e:      # a failure inside the compiled code: no result
            raise kernel_failed(e, f"the {scene.normal}/{scene.tangential} kernels at vn = {vn:g} m/s") from None
        if k:
            best = min(best, time.perf_counter() - t0)
    e_n = -out[:, O_VN] / vn
    # a failed impact, or an e_n that no passive normal law gives (impact.E_N_EXCESS_TOL): no result
    if np.any(out[:, O_STATUS] != 0) or not np.all((e_n >= 0.0) & (e_n <= 1.0 + E_N_EXCESS_TOL)):
        f = np.full(vt.size, np.nan)
        return GridRun(f, f, f, f, best / vt.size)
    mu = scene.mu
    fm = out[:, O_PT] / out[:, O_PN] / mu
    with np.errstate(divide="ignore", invalid="ignore"):
        e_t = np.where(vt != 0, out[:, O_VT] / vt, np.nan)
    Omega_r = 2.0 * R1 * out[:, O_W1] / (5.0 * (1.0 + e_n) * mu * vn)
    return GridRun(fm, e_t, Omega_r, e_n, best / vt.size, is_sliding(out[:, O_SLID]))


def _maxabs(x, y):
    d = np.abs(np.asarray(x) - np.asarray(y))
    d = d[np.isfinite(np.asarray(y))]
    if d.size == 0:
        return np.nan
    return float(np.nan if np.any(np.isnan(d)) else d.max())


@dataclass
class ChartRow:
    normal: str
    tangential: str
    scheme: str
    steps_per_contact: float
    err_f_over_mu: float
    err_e_t: float
    err_Omega_r: float
    err_e_n: float
    model_err_f_over_mu: float
    discretisation_err_f_over_mu: float
    time_per_impact_us: float
    pareto: bool = False


def chart_scene(normal: str, tangential: str, vn: float, mu: float = 0.3, nu: float = 0.3, e_n: float = THORNTON_E_N,
                **kw) -> Scene:
    """The EE steel scene (R = 10 mm, steel on steel) with the given laws; thornton calibrated to e_n at vn."""
    mat = Material(STEEL.E, nu, STEEL.rho)
    extra = {"e_n": e_n} if law_of("normal", normal).TAKES_E_N else {}
    return Scene(Sphere(0.01, mat), Wall(mat), mu=mu, normal=normal, tangential=tangential, v_ref=reference_speed(vn),
                 **extra, **kw)


def reference(normal: str, vn: float, Theta, **scene_kw):
    """Converged MDR on the Theta grid: (vt, GridRun)."""
    sc = chart_scene(normal, "mdr", vn, mdr_springs=REFERENCE_SPRINGS, **scene_kw)
    # e_n does not depend on the tangential law: take it from a head-on impact
    e_n = run(sc, vn, np.zeros(1), REFERENCE_STEPS, "located").e_n[0]
    vt = np.asarray(Theta, float) * (1.0 + e_n) * sc.mu * vn / 2.0
    return vt, run(sc, vn, vt, REFERENCE_STEPS, "located")


def chart(laws=None, normals=NORMALS, schemes=SCHEMES, steps=DEFAULT_STEPS, Theta_max: float = 10.0,
          n_theta: int = 11, vn: float = 5.0, repeats: int = 3, progress=None) -> list:
    """All rows of the chart (list of ChartRow), Pareto points marked."""
    laws = list(TANGENTIAL_LAWS) if laws is None else list(laws)
    for name in laws:
        if name not in TANGENTIAL_LAWS:
            raise InputError(f"tangential law {name!r} is unknown; choose among {', '.join(TANGENTIAL_LAWS)}")
    if not 2 <= n_theta <= 1000:
        raise InputError("n_theta must be in [2, 1000]")
    if not 0.0 < Theta_max <= 100.0:
        raise InputError("Theta_max must be in (0, 100]")
    steps = sorted(float(s) for s in steps)
    if steps[0] < 2:
        raise InputError("steps per contact must be >= 2")
    Theta = np.linspace(0.0, Theta_max, n_theta)
    rows = []
    for normal in normals:
        vt, ref = reference(normal, vn, Theta)
        for law in laws:
            sc = chart_scene(normal, law, vn)
            for scheme in schemes:
                conv_steps = law_of("tangential", law).CONVERGED_STEPS
                conv = run(sc, vn, vt, conv_steps, scheme)
                model_err = _maxabs(conv.f_over_mu, ref.f_over_mu)
                for spc in steps:
                    if progress:
                        progress(f"{normal} {law} {scheme} {spc:g}")
                    r = run(sc, vn, vt, spc, scheme, repeats)
                    rows.append(ChartRow(
                        normal, law, scheme, spc,
                        _maxabs(r.f_over_mu, ref.f_over_mu), _maxabs(r.e_t, ref.e_t),
                        _maxabs(r.Omega_r, ref.Omega_r), _maxabs(r.e_n, ref.e_n),
                        model_err, _maxabs(r.f_over_mu, conv.f_over_mu), 1e6 * r.seconds_per_impact))
    mark_pareto(rows)
    return rows


def mark_pareto(rows):
    """Mark, per normal law, the rows that no other row beats in both time and f/mu error."""
    for normal in {r.normal for r in rows}:
        pts = [r for r in rows if r.normal == normal and np.isfinite(r.err_f_over_mu)]
        pts.sort(key=lambda r: (r.time_per_impact_us, r.err_f_over_mu))
        best = np.inf
        for r in pts:
            if r.err_f_over_mu < best:
                r.pareto = True
                best = r.err_f_over_mu


def write_csv(rows, path):
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(asdict(rows[0])))
        w.writeheader()
        for r in rows:
            w.writerow(asdict(r))


def read_csv(path) -> list:
    rows = []
    with open(path, newline="", encoding="utf-8-sig") as fh:   # BOM accepted
        for d in csv.DictReader(fh):
            rows.append(ChartRow(d["normal"], d["tangential"], d["scheme"], float(d["steps_per_contact"]),
                                 *(float(d[k]) for k in ("err_f_over_mu", "err_e_t", "err_Omega_r", "err_e_n",
                                                         "model_err_f_over_mu", "discretisation_err_f_over_mu",
                                                         "time_per_impact_us")),
                                 d["pareto"] == "True"))
    return rows
