"""Figures (matplotlib, Agg backend). The only module of the package that imports matplotlib.

``sweep_figure``: the rebound quantities of one sweep against Theta in the manner of Wu, Thornton & Li
(2009, figures 3-16) with the fitted, published, bilinear and rigid-body models.
``overlay_figure``: f/mu of several sweeps on one axis (laws, parameter studies, the RE collapse).
"""
from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .rebound import models as rm  # noqa: E402

DPI = 100
#: mathtext labels of the rebound quantities
LABELS = {"Theta": r"$\Theta$", "f_over_mu": r"$f/\mu$", "Psi_r": r"$\Psi_r$", "Omega_r": r"$\Omega_r$",
          "e_t": r"$e_t$", "e_n": r"$e_n$", "collapse": r"$\kappa\Theta/(7\kappa-1)$"}
#: style of the critical-angle lines: distinct colours and dash patterns
THETA_C_STYLES = {"fit": dict(color="C0", ls="--", lw=1.3), "simulation": dict(color="k", ls="-", lw=1.0),
                  "eq. 4.1": dict(color="C3", ls=":", lw=1.8), "criterion": dict(color="C3", ls=":", lw=1.8)}


def _save(fig, path, dpi=DPI):
    """Lay out ``fig``, write it as a PNG to ``path``, close it and return ``path``."""
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path


def _physical(m):
    """Blank the model curves where the fit is unphysical (f/mu < 0 near Theta = 0, which makes e_t > 1)."""
    bad = m["f_over_mu"] < 0.0
    if np.any(bad):
        m = {k: np.where(bad, np.nan, v) if k != "Theta" else v for k, v in m.items()}
    return m


def _model_curves(Theta_max, kappa, fit=None, published=None):
    """(label, style, model dict) of the curves drawn beside the points."""
    T = np.linspace(0.0, Theta_max, 600)
    curves = []
    if fit is not None:
        curves.append((rf"fit eq. 4.5 ($\Theta_c$ = {fit.Theta_c:.3f})", dict(color="C0", lw=1.6),
                       _physical(rm.wu(T, fit.c, fit.Theta_c))))
    if published is not None:
        curves.append((rf"published fit ($\Theta_c$ = {published['Theta_c_paper']:.4g})",
                       dict(color="k", ls="--", lw=1.2), _physical(rm.wu(T, published["c"]))))
    if kappa is not None:
        curves.append(("bilinear (eqs 5.1-5.6)", dict(color="C2", ls="-.", lw=1.0), rm.bilinear(T, kappa)))
    curves.append(("rigid body (eqs 5.7-5.9)", dict(color="C3", ls=":", lw=1.0), rm.rigid_body(T)))
    return curves


def sweep_figure(res, path, *, fit=None, published=None, kappa=None, title=None, Theta_c=None,
                 Theta_max: float | None = None):
    """Six panels: f/mu vs Theta; f/mu vs kappa Theta/(7 kappa - 1); Psi_r, Omega_r, e_t vs Theta;
    e_n vs impact angle. ``res``: SweepResult; ``fit``: fit.WuFit; ``published``: a row of
    rebound_models.PUBLISHED_FITS; ``Theta_c``: optional dict label -> value drawn as vertical lines.
    Points with Theta > ``Theta_max`` (default: none) are not drawn. Writes a PNG to ``path``."""
    kappa = res.model.get("kappa") if kappa is None else kappa
    T = res.Theta
    finite = T[np.isfinite(T)]
    tmax = float(finite.max()) if finite.size else 10.0
    if Theta_max is not None:
        tmax = min(tmax, Theta_max)
    sel = T <= tmax
    curves = _model_curves(tmax, kappa, fit, published)
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5))
    sl = res.persistent_sliding[sel]
    panels = [(k, LABELS[k], ax) for k, ax in (("f_over_mu", axes[0, 0]), ("Psi_r", axes[0, 2]),
                                                ("Omega_r", axes[1, 0]), ("e_t", axes[1, 1]))]
    for key, lab, ax in panels:
        y = getattr(res, key)[sel]
        ax.plot(T[sel][~sl], y[~sl], "o", ms=3.5, mfc="none", color="C1", label="simulation")
        ax.plot(T[sel][sl], y[sl], "s", ms=3.0, mfc="none", color="C4", label="simulation, persistent sliding")
        for name, style, m in curves:
            ax.plot(m["Theta"], m[key], label=name, **style)
        ax.set_xlabel(LABELS["Theta"])
        ax.set_ylabel(lab)
        ax.set_xlim(0, tmax)
        ax.grid(alpha=0.3)
    if Theta_c:
        for i, (name, v) in enumerate(Theta_c.items()):
            if v is not None and np.isfinite(v):
                style = THETA_C_STYLES.get(name.split(" (")[0], dict(color=f"C{5 + i}", ls="-.", lw=1.0))
                axes[0, 0].axvline(v, alpha=0.9, label=rf"$\Theta_c$ {name} = {v:.3f}", **style)
    axes[0, 0].set_ylim(0, 1.08)
    axes[0, 0].legend(fontsize=7, loc="lower right")
    ax = axes[0, 1]
    if kappa is not None:
        x = rm.collapse_variable(T[sel], kappa)
        ax.plot(x, res.f_over_mu[sel], "o", ms=3.5, mfc="none", color="C1", label="simulation")
        for name, style, m in curves:
            ax.plot(rm.collapse_variable(m["Theta"], kappa), m["f_over_mu"], label=name, **style)
        ax.set_xlabel(LABELS["collapse"])
        ax.set_ylabel(LABELS["f_over_mu"])
        ax.set_xlim(0, rm.collapse_variable(tmax, kappa))
        ax.set_ylim(0, 1.08)
        ax.grid(alpha=0.3)
    ax = axes[1, 2]
    ax.plot(res.theta_deg, res.e_n, "o-", ms=3, mfc="none", color="C1")
    ax.set_xlabel(r"impact angle $\theta_i$ [deg]")
    ax.set_ylabel(LABELS["e_n"])
    lo, hi = float(np.nanmin(res.e_n)), float(np.nanmax(res.e_n))
    pad = max(0.02, 0.1 * (hi - lo))
    ax.set_ylim(lo - pad, min(hi + pad, 1.05))
    ax.grid(alpha=0.3)
    m = res.model
    fig.suptitle(title or (f"{m['normal_law']} / {m['tangential_law']}, mu = {m['mu']:g}, "
                           f"kappa = {m['kappa']:.4f}"), fontsize=11)
    return _save(fig, path)


def overlay_figure(results: dict, path, *, quantity: str = "f_over_mu", collapse: bool = False,
                   published=None, kappa=None, title=None, Theta_max: float = 8.0, ylabel=None):
    """``quantity`` of several sweeps (label -> SweepResult) against Theta, or against
    kappa Theta/(7 kappa - 1) of each sweep's own kappa when ``collapse``. ``published``: optional dict
    label -> PUBLISHED_FITS row drawn as dashed curves; ``kappa``: draws the bilinear model of that kappa."""
    fig, ax = plt.subplots(figsize=(7, 5))
    for i, (label, res) in enumerate(results.items()):
        T = res.Theta
        sel = T <= Theta_max
        x = rm.collapse_variable(T[sel], res.model["kappa"]) if collapse else T[sel]
        ax.plot(x, getattr(res, quantity)[sel], "o-", ms=3, lw=0.8, mfc="none", color=f"C{i}", label=label)
    Tm = np.linspace(0, Theta_max, 600)
    for i, (label, row) in enumerate((published or {}).items()):
        k = float(rm.kappa_from_nu(row["nu"]))
        m = rm.wu(Tm, row["c"])
        x = rm.collapse_variable(Tm, k) if collapse else Tm
        ax.plot(x, m[quantity], ls="--", lw=1.0, color=f"C{i}" if len(results) == len(published) else "k",
                label=f"published {label}")
    if kappa is not None and not collapse:
        m = rm.bilinear(Tm, kappa)
        ax.plot(Tm, m[quantity], ls="-.", lw=1.0, color="gray", label="bilinear")
    ax.set_xlabel(LABELS["collapse"] if collapse else LABELS["Theta"])
    ax.set_ylabel(ylabel or LABELS.get(quantity, quantity))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    if title:
        ax.set_title(title, fontsize=10)
    return _save(fig, path)


# --------------------------------------------------------------------------------------------------
# Chung & Ooi (2011) benchmark figures

def _co_law_style(i, law):
    return dict(marker="os^vD<>px"[i % 9], ms=3.5, mfc="none", lw=0.8, color=f"C{i}", label=law)


def _co_normal(res, path):
    """Tests 1, 2: force-time and force-overlap of each case against the exact Hertz curves."""
    cases = list(res.data.items())
    fig, axes = plt.subplots(len(cases), 2, figsize=(11, 3.6 * len(cases)), squeeze=False)
    for row, (label, d) in zip(axes, cases):
        t, F = np.asarray(d["t"]), np.asarray(d["force"])
        step = max(1, len(t) // 60)
        row[0].plot(np.asarray(d["hertz_t"]) * 1e6, d["hertz_force"], "k-", lw=1.2, label="Hertz (exact)")
        row[0].plot(t[::step] * 1e6, F[::step], "o", ms=3, mfc="none", color="C1", label="simulation")
        row[0].set_xlabel("time [us]")
        row[0].set_ylabel("normal force [N]")
        row[0].set_title(f"{label}: force-time", fontsize=10)
        row[1].plot(np.asarray(d["hertz_overlap"]) * 1e6, d["hertz_force"], "k-", lw=1.2, label="Hertz")
        row[1].plot(np.asarray(d["overlap"])[::step] * 1e6, F[::step], "o", ms=3, mfc="none", color="C1",
                    label="simulation")
        row[1].set_xlabel("overlap [um]")
        row[1].set_ylabel("normal force [N]")
        row[1].set_title(f"{label}: force-overlap", fontsize=10)
        for ax in row:
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
    return fig


def _co_restitution(res, path):
    fig, ax = plt.subplots(figsize=(5.5, 5))
    ax.plot([0, 1], [0, 1], "k-", lw=1, label="e_n out = e_n in")
    for i, (label, d) in enumerate(res.data.items()):
        ax.plot(d["e_n_in"], d["e_n_out"], "os"[i % 2], ms=6, mfc="none", color=f"C{i}", label=label)
    ax.set_xlabel("e_n in")
    ax.set_ylabel("e_n out")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def _co_oblique_angle(res, path):
    """Test 4: e_t, rebound spin and patch rebound angle against the impact angle."""
    mats = list(res.data.items())
    fig, axes = plt.subplots(len(mats), 3, figsize=(15, 4.2 * len(mats)), squeeze=False)
    panels = [("e_t", "e_t"), ("omega_r", "rebound spin omega_r [rad/s]"),
              ("patch_angle_deg", "rebound angle of the contact patch [deg]")]
    for row, (label, d) in zip(axes, mats):
        rb = d["rigid_body"]
        laws = [k for k in d if k != "rigid_body"]
        for ax, (key, ylab) in zip(row, panels):
            ax.plot(rb["angle_deg"], rb[key], "k-", lw=1.2, label="rigid body")
            for i, law in enumerate(laws):
                ax.plot(d[law]["angle_deg"], d[law][key], **_co_law_style(i, law))
            ax.axvline(res.settings["sliding_angle_deg"], color="gray", ls=":", lw=0.8)
            ax.set_xlabel("impact angle [deg]")
            ax.set_ylabel(ylab)
            ax.set_title(label, fontsize=10)
            ax.grid(alpha=0.3)
        row[0].set_ylim(0.5, 1.05)
        row[0].legend(fontsize=7)
    return fig


def _co_theta(res, path):
    """Test 5: Psi_r, Omega_r and f/mu against Theta with the published EE fit and rigid-body model."""
    m = res.data["models"]
    T = np.asarray(m["Theta"])
    fw = np.asarray(m["wu_ee_f_over_mu"])
    fr = np.asarray(m["rigid_f_over_mu"])
    laws = res.settings["laws"]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    curves = {"f_over_mu": (fw, fr), "Psi_r": (T - 7 * fw, T - 7 * fr), "Omega_r": (-fw, -fr)}
    for ax, key in zip(axes, ("Psi_r", "Omega_r", "f_over_mu")):
        ax.plot(T, curves[key][0], "k--", lw=1.1, label="Wu et al. (2009) EE fit")
        ax.plot(T, curves[key][1], "k:", lw=1.1, label="rigid body")
        for i, law in enumerate(laws):
            ax.plot(res.data[law]["Theta"], res.data[law][key], **_co_law_style(i, law))
        ax.set_xlabel("Theta = 2 tan(theta_i) / ((1 + e_n) mu)")
        ax.set_ylabel(key.replace("_over_", " / "))
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    return fig


def _co_spin(res, path):
    """Tests 6, 8: beta and the recoil angle against chi."""
    rb = res.data["rigid_body"]
    laws = res.settings["laws"]
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    for ax, key, ylab in ((axes[0], "beta", "beta = -v_tr / v_ti"),
                          (axes[1], "recoil_angle_deg", "recoil angle [deg]")):
        ax.plot(rb["chi"], rb[key], "k-", lw=1.2, label="rigid body")
        for i, law in enumerate(laws):
            ax.plot(res.data[law]["chi"], res.data[law][key], **_co_law_style(i, law))
        ax.set_xscale("log")
        ax.axvline(1.0, color="gray", ls=":", lw=0.8)
        ax.set_xlabel("chi = 3.5 mu (1 + e_n) V_ni / v_ti")
        ax.set_ylabel(ylab)
        ax.grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=7)
    return fig


def _co_no_slip(res, path):
    """Test 7: rebound spins of both spheres against the incident spin (unchanged: w_r = w_i)."""
    laws = res.settings["laws"]
    fig, ax = plt.subplots(figsize=(6, 5))
    w = np.asarray(res.data[laws[0]]["spin"])
    ax.plot(w, w, "k-", lw=1, label="exact: sphere 1, w_r = w_i")
    ax.plot(w, -w, "k--", lw=1, label="exact: sphere 2, w_r = -w_i")
    for i, law in enumerate(laws):
        d = res.data[law]
        ax.plot(d["spin"], d["omega1_r"], **_co_law_style(i, law))
        ax.plot(d["spin"], d["omega2_r"], **{**_co_law_style(i, law), "label": None})
    ax.set_xlabel("incident spin of sphere 1 [rad/s]")
    ax.set_ylabel("rebound spin [rad/s]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    return fig


_CO_FIGURES = {1: _co_normal, 2: _co_normal, 3: _co_restitution, 4: _co_oblique_angle, 5: _co_theta,
               6: _co_spin, 7: _co_no_slip, 8: _co_spin}


def chung_ooi_figure(res, path) -> list:
    """Figure of one Chung & Ooi (2011) test (``chung_ooi.BenchmarkResult``) with its analytic curves;
    writes a PNG to ``path`` and returns ``[path]``."""
    fig = _CO_FIGURES[res.test](res, path)
    fig.suptitle(f"Chung & Ooi test {res.test}: {res.title}", fontsize=11)
    return [_save(fig, path)]


def speed_accuracy_figure(rows, path, *, quantity: str = "err_f_over_mu"):
    """Error against converged MDR versus time per impact (log-log), one panel per normal law, one line
    per tangential law and integrator end (solid: located, dashed: standard); the Pareto front is the
    black step line. ``rows``: ``chart.ChartRow`` list."""
    normals = sorted({r.normal for r in rows})
    laws = list(dict.fromkeys(r.tangential for r in rows))
    colors = plt.get_cmap("tab10")
    fig, axes = plt.subplots(1, len(normals), figsize=(6.5 * len(normals), 5.2), squeeze=False)
    for ax, normal in zip(axes[0], normals):
        for i, law in enumerate(laws):
            for scheme, ls in (("located", "-"), ("standard", "--")):
                pts = sorted((r for r in rows if r.normal == normal and r.tangential == law and r.scheme == scheme),
                             key=lambda r: r.steps_per_contact)
                pts = [r for r in pts if np.isfinite(getattr(r, quantity)) and getattr(r, quantity) > 0]
                if not pts:
                    continue
                ax.plot([r.time_per_impact_us for r in pts], [getattr(r, quantity) for r in pts], ls,
                        marker="o", ms=3, color=colors(i % 10), label=f"{law} ({scheme})" if scheme == "located"
                        else None)
        front = sorted((r for r in rows if r.normal == normal and r.pareto and getattr(r, quantity) > 0),
                       key=lambda r: r.time_per_impact_us)
        if front:
            ax.step([r.time_per_impact_us for r in front], [getattr(r, quantity) for r in front], "k-",
                    where="post", lw=2.5, alpha=0.35, label="Pareto front")
            placed = []       # label positions (log10 x, log10 y): labels closer than these are moved
            for r in front:
                x, y = r.time_per_impact_us, getattr(r, quantity)
                lx, ly = np.log10(x), np.log10(y)
                dy = 3
                while any(abs(lx - px) < 0.6 and abs(ly + dy / 40.0 - py) < 0.15 for px, py in placed):
                    dy -= 9
                placed.append((lx, ly + dy / 40.0))
                std = " std" if r.scheme == "standard" else ""
                ax.annotate(f"{r.tangential} {r.steps_per_contact:g}{std}", (x, y), fontsize=6, xytext=(3, dy),
                            textcoords="offset points",
                            arrowprops=dict(arrowstyle="-", lw=0.4, color="0.5") if dy != 3 else None)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("time per impact [us] (serial, warm JIT)")
        ax.set_ylabel(f"max |{quantity.replace('err_', '')} error| vs converged MDR, Theta in [0, 10]")
        ax.set_title(f"normal law: {normal} (solid located, dashed standard end)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, loc="lower left")
    return _save(fig, path, dpi=130)


def stability_figure(rows, path):
    """Outcome grid of ``stability.stability_map`` rows: one row per tangential law and integrator end,
    one column per case; colour = outcome (ok, inaccurate, coulomb, energy, blow-up, rejected)."""
    from matplotlib.colors import ListedColormap

    outcomes = ("ok", "inaccurate", "coulomb", "energy", "blow-up", "rejected")
    colours = ("#4caf50", "#ffd54f", "#ff9800", "#e53935", "#6a1b9a", "#9e9e9e")
    cases = list(dict.fromkeys(r.case for r in rows))
    methods = list(dict.fromkeys((r.tangential, r.scheme) for r in rows))
    grid = np.zeros((len(methods), len(cases)))
    for r in rows:
        grid[methods.index((r.tangential, r.scheme)), cases.index(r.case)] = outcomes.index(r.outcome)
    fig, ax = plt.subplots(figsize=(1.0 + 0.55 * len(cases), 1.2 + 0.28 * len(methods)))
    ax.imshow(grid, cmap=ListedColormap(colours), vmin=-0.5, vmax=len(outcomes) - 0.5, aspect="auto")
    ax.set_xticks(range(len(cases)))
    ax.set_xticklabels(cases, rotation=60, ha="right", fontsize=7)
    ax.set_yticks(range(len(methods)))
    ax.set_yticklabels([f"{t} ({s})" for t, s in methods], fontsize=7)
    handles = [plt.Rectangle((0, 0), 1, 1, color=c) for c in colours]
    ax.legend(handles, outcomes, fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.set_title("stability map (EE steel scene; accuracy: |f/mu or e_n error| vs MDR <= 0.02)", fontsize=9)
    return _save(fig, path, dpi=130)


# --------------------------------------------------------------------------------------------------
# Panels of curves (plastic contacts, model comparisons)

def curves_figure(panels, path, *, ncols: int = 2, title=None):
    """Panels of curves. ``panels``: list of dicts with ``title``, ``xlabel``, ``ylabel``, ``series`` (list
    of (x, y, label, style dict)) and optionally ``hlines`` (list of (y, label)). Returns ``path``."""
    nrows = (len(panels) + ncols - 1) // ncols
    fig, axes = plt.subplots(nrows, ncols, figsize=(5.2 * ncols, 3.9 * nrows), squeeze=False)
    for ax, panel in zip(axes.flat, panels):
        for x, y, label, style in panel["series"]:
            ax.plot(x, y, label=label, **{"lw": 0.9, **style})
        for y, label in panel.get("hlines", ()):
            ax.axhline(y, color="gray", ls=":", lw=1.0, label=label)
        ax.set_title(panel.get("title", ""), fontsize=9)
        ax.set_xlabel(panel.get("xlabel", ""))
        ax.set_ylabel(panel.get("ylabel", ""))
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6.5)
    for ax in list(axes.flat)[len(panels):]:
        ax.set_visible(False)
    if title:
        fig.suptitle(title, fontsize=10)
    return _save(fig, path)


def path_figure(delta, ux, uy, N, Tx, Ty, mu, path, *, title=None, reference=None, moment=None):
    """A prescribed path and the force along it: the tangential path (ux, uy) and the force vector
    -T/(mu N) drawn on it; Tx/(mu N), Ty/(mu N) and |T|/(mu N) against the row. ``reference``: optional
    (N, Tx, Ty) of a reference drawn dashed; ``moment``: optional Mz/(mu N a) per row (the moment about
    the normal, a the contact radius), drawn dotted."""
    N = np.asarray(N, dtype=float)
    muN = np.where(N > 0, mu * N, np.nan)
    rows = np.arange(len(N))
    fig, (a0, a1) = plt.subplots(1, 2, figsize=(11, 4.6))
    scale = 1e6
    a0.plot(np.asarray(ux) * scale, np.asarray(uy) * scale, "k-", lw=1.0, label="path")
    every = max(1, len(N) // 24)
    extent = max(np.ptp(np.asarray(ux)), np.ptp(np.asarray(uy)), 1e-300) * scale
    arrow = 0.2 * extent        # length of an arrow of magnitude mu N
    a0.quiver(np.asarray(ux)[::every] * scale, np.asarray(uy)[::every] * scale,
              (-np.asarray(Tx) / muN)[::every] * arrow, (-np.asarray(Ty) / muN)[::every] * arrow, color="C0",
              angles="xy", scale_units="xy", scale=1.0, width=0.004,
              label="-T/(mu N) (force on body 2; mu N = 0.2 of the path's extent)")
    a0.set_xlabel("ux [um]")
    a0.set_ylabel("uy [um]")
    a0.set_aspect("equal", adjustable="datalim")
    a0.legend(fontsize=8)
    for val, lab, c in [(np.asarray(Tx) / muN, "Tx/(mu N)", "C0"), (np.asarray(Ty) / muN, "Ty/(mu N)", "C1"),
                        (np.hypot(Tx, Ty) / muN, "|T|/(mu N)", "k")]:
        a1.plot(rows, val, color=c, lw=1.3, label=lab)
    if reference is not None:
        Nr, Txr, Tyr = (np.asarray(x, dtype=float) for x in reference)
        muNr = np.where(Nr > 0, mu * Nr, np.nan)
        a1.plot(rows, Txr / muNr, "C0--", lw=1.0, label="reference")
        a1.plot(rows, Tyr / muNr, "C1--", lw=1.0)
        a1.plot(rows, np.hypot(Txr, Tyr) / muNr, "k--", lw=1.0)
    if moment is not None:
        a1.plot(rows, np.asarray(moment, dtype=float), "C2:", lw=1.5, label="Mz/(mu N a)")
    a1.set_xlabel("row")
    a1.set_ylabel("on body 1: T / (mu N)" + (", Mz / (mu N a)" if moment is not None else ""))
    a1.axhline(0, color="0.7", lw=0.5)
    a1.legend(fontsize=8)
    if title:
        fig.suptitle(title, fontsize=10)
    _save(fig, path)


def spin_figure(rows, path, *, bem_rows=(), planar=None, title=None):
    """Impacts with out-of-plane spin (``studies.spin``): f/mu in the impact plane (solid) and across it
    (dashed) against Theta_across, one colour per impact angle, BEM cases as markers; |f|/mu against the
    magnitude of the Theta vector with the planar curve ``planar`` = (Theta, f/mu); the rebound angle out
    of the impact plane and e_t against Theta_across."""
    angles = sorted({r.angle_deg for r in rows})
    fig, ax = plt.subplots(2, 2, figsize=(11, 8.4))
    for i, ang in enumerate(angles):
        pts = sorted((r for r in rows if r.angle_deg == ang), key=lambda r: r.Theta_across)
        X = np.array([r.Theta_across for r in pts])
        c = f"C{i}"
        ax[0, 0].plot(X, [r.f_over_mu for r in pts], "-", color=c, label=f"{ang:g} deg (Theta = {pts[0].Theta:.2f})")
        ax[0, 0].plot(X, [r.f_across_over_mu for r in pts], "--", color=c)
        ax[0, 1].plot(np.hypot([r.Theta for r in pts], X), np.hypot([r.f_over_mu for r in pts],
                      [r.f_across_over_mu for r in pts]), "o", ms=3, color=c, label=f"{ang:g} deg")
        ax[1, 0].plot(X, [r.out_of_plane_angle_deg for r in pts], "-", color=c, label=f"{ang:g} deg")
        ax[1, 1].plot(X, [r.e_t for r in pts], "-", color=c, label=f"{ang:g} deg")
        for b in bem_rows:
            if b.angle_deg == ang:
                ax[0, 0].plot(b.Theta_across, b.bem_f_over_mu, "s", mfc="none", color=c, ms=8)
                ax[0, 0].plot(b.Theta_across, b.bem_f_across_over_mu, "D", mfc="none", color=c, ms=7)
                ax[1, 0].plot(b.Theta_across, b.bem_out_of_plane_angle_deg, "s", mfc="none", color=c, ms=8)
    if bem_rows:
        ax[0, 0].plot([], [], "ks", mfc="none", label="BEM: in plane")
        ax[0, 0].plot([], [], "kD", mfc="none", label="BEM: across")
        ax[1, 0].plot([], [], "ks", mfc="none", label="BEM")
    if planar is not None:
        ax[0, 1].plot(planar[0], planar[1], "k-", lw=1, label="planar impact, f/mu vs Theta")
    ax[0, 0].set_ylabel("f/mu: in the impact plane (solid), across it (dashed)")
    ax[0, 1].set_xlabel("|Theta vector| = 2 |v_slip,i| / ((1 + e_n) mu V_n)")
    ax[0, 1].set_ylabel("|f vector| / mu")
    ax[1, 0].set_ylabel("rebound velocity out of the impact plane [deg]")
    ax[1, 1].set_ylabel("e_t (in the impact plane)")
    for a in (ax[0, 0], ax[1, 0], ax[1, 1]):
        a.set_xlabel("Theta_across = 2 v_slip,across / ((1 + e_n) mu V_n)")
    for a in ax.flat:
        a.grid(True, alpha=0.3)
        a.legend(fontsize=7)
    if title:
        fig.suptitle(title, fontsize=10)
    return _save(fig, path)


def _shared_labels(ax, pts):
    """Annotate points (x, y, label), one label per cluster of coinciding points, alternately above and
    below."""
    clusters = []
    for x, y, law in pts:
        for cl in clusters:
            if abs(cl[1] / y - 1) < 0.03 and abs(math.log(cl[0] / x)) < 0.3:
                cl[2].append(law)
                break
        else:
            clusters.append([x, y, [law]])
    for j, (x, y, names) in enumerate(sorted(clusters)):
        below = j % 2 == 1
        ax.annotate(",\n".join(names), (x, y), fontsize=7, xytext=(5, -6 if below else 4), textcoords="offset points",
                    va="top" if below else "bottom")


def chart3d_figure(rows, path, *, title=None, spin_rows=None, twist_rows=None, twist_targets=None):
    """Error of each 3D law against the BEM (max over the curved paths, and per path) versus the time per
    kernel update. ``rows``: ``studies.chart3d.Chart3DRow`` list; ``spin_rows``: optional
    ``studies.chart3d.SpinImpactRow`` list (a third panel: spinning impacts, error vs time per impact);
    ``twist_rows``: optional ``studies.chart3d.TwistChartRow`` list (a fourth panel: force and moment error
    of each twist law per twist path, with ``twist_targets``, path -> (force, moment) target or None,
    drawn as marks). Laws at the same point share a label."""
    from matplotlib.ticker import LogLocator, NullFormatter, ScalarFormatter

    laws = list(dict.fromkeys(r.law for r in rows))
    paths = [p for p in dict.fromkeys(r.path for r in rows) if p != "max"]
    cmap = plt.get_cmap("tab20")
    n = 2 + bool(spin_rows) + bool(twist_rows)
    if n == 4:
        fig, axes = plt.subplots(2, 2, figsize=(13, 10.8))
        axes = axes.ravel()
    else:
        fig, axes = plt.subplots(1, n, figsize=(6.5 * n, 5.4))
    a0, a1 = axes[0], axes[1]
    points = []
    for i, law in enumerate(laws):
        m = next(r for r in rows if r.law == law and r.path == "max")
        a0.plot(m.time_per_update_ns, m.error, "o", color=cmap(i % 20), ms=7)
        points.append((m.time_per_update_ns, m.error, law))
        a1.plot(range(len(paths)), [next(r.error for r in rows if r.law == law and r.path == p) for p in paths],
                "o-", color=cmap(i % 20), label=law, ms=4)
    _shared_labels(a0, points)
    if spin_rows:
        a2 = axes[2]
        pts = []
        for r in spin_rows:
            i = laws.index(r.law) if r.law in laws else len(laws)
            a2.plot(r.time_per_impact_us, r.error, "o", color=cmap(i % 20), ms=7)
            pts.append((r.time_per_impact_us, r.error, r.law))
        _shared_labels(a2, pts)
        a2.set_xscale("log")
        a2.set_yscale("log")
        a2.set_xlabel("time per impact [us] (bare kernel, warm JIT)")
        a2.set_ylabel("max |f - f_BEM| / mu, spinning impacts (EE)")
        a2.grid(True, which="both", alpha=0.3)
    if twist_rows:
        a3 = axes[-1]
        tlaws = list(dict.fromkeys(r.twist for r in twist_rows))
        tpaths = list(dict.fromkeys(r.path for r in twist_rows))
        for i, law in enumerate(tlaws):
            per = {r.path: r for r in twist_rows if r.twist == law}
            ns = max(r.time_per_update_ns for r in per.values())
            x = [j + 0.08 * (i - (len(tlaws) - 1) / 2) for j in range(len(tpaths))]
            a3.plot(x, [max(per[p].force_error, 1e-3) for p in tpaths], "o", color=f"C{i}",
                    label=f"twist {law} ({ns:.0f} ns): force / (mu N)")
            a3.plot(x, [max(per[p].moment_error, 1e-3) for p in tpaths], "s", mfc="none", color=f"C{i}",
                    label=f"twist {law}: moment / (mu N a)")
        for j, p in enumerate(tpaths):
            for k, v in enumerate((twist_targets or {}).get(p, (None, None))):
                if v:
                    a3.hlines(v, j - 0.3, j + 0.3, colors="k", linestyles="-" if k == 0 else "--", lw=0.8)
        a3.set_xticks(range(len(tpaths)))
        a3.set_xticklabels(tpaths, fontsize=8)
        a3.set_xlim(-0.5, len(tpaths) - 0.5)
        a3.set_yscale("log")
        a3.set_ylabel("max error along the path (tangential law mdr_adaptive)")
        a3.set_title("twist paths against the BEM at 128 across: force (filled) and moment (open) error\n"
                     "(below 1e-3 drawn at 1e-3); targets: force -, moment --", fontsize=9)
        a3.grid(True, which="both", alpha=0.3)
        a3.set_ylim(1e-4, 3.0)
        a3.legend(fontsize=7, ncol=2, loc="lower right")
    a0.set_xscale("log")
    a0.set_yscale("log")
    a0.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
    a0.xaxis.set_major_formatter(ScalarFormatter())
    a0.xaxis.set_minor_formatter(NullFormatter())
    a0.set_xlabel("time per update of the 3D kernel [ns] (serial, warm JIT)")
    a0.set_ylabel("max |T - T_BEM| / (mu N) over the five curved paths")
    a1.set_xticks(range(len(paths)))
    a1.set_xticklabels(paths, rotation=20, fontsize=8)
    a1.set_yscale("log")
    a1.set_ylabel("max |T - T_BEM| / (mu N) along the path")
    for a in (a0, a1):
        a.grid(True, which="both", alpha=0.3)
    a1.legend(fontsize=7, ncol=2)
    if title:
        fig.suptitle(title, fontsize=10)
    return _save(fig, path)
