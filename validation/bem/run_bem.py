"""Validation of the boundary-element reference (dem_contact.reference.bem): Cattaneo-Mindlin curves, the
planar MDR impact, grid and step convergence, time per step, and the named curved paths.

Usage (from the repository root, PYTHONPATH set to it):

    python validation/bem/run_bem.py cm        # Cattaneo-Mindlin loading/unloading, n = 16 ... 128
    python validation/bem/run_bem.py impact    # f/mu against the exact MDR reference, EE scene, 5 m/s
    python validation/bem/run_bem.py impact_nu0   # the same with nu = 0 (MDR exact for the model)
    python validation/bem/run_bem.py spin      # impacts with spin about the incident velocity (out of plane)
    python validation/bem/run_bem.py timing    # wall time per step at 32, 64, 128 elements across
    python validation/bem/run_bem.py paths     # the named curved paths at constant overlap
    python validation/bem/run_bem.py mdr_paths # a vector MDR (4000 springs) beside the BEM on those paths
    python validation/bem/run_bem.py report    # report.md and the figures from the saved results

Each section writes results/<section>.json next to this script; ``paths`` also writes the force
histories as CSV (paths/<shape>_<size>.csv: delta, ux, uy [m], N, Tx, Ty [N]) for comparisons with the
3D laws. ``all`` runs every section and the report.
"""
from __future__ import annotations

import json
import math
import os
import platform
import sys
import time

import numpy as np

import dem_contact as dc
from dem_contact.reference import bem as B
from dem_contact.reference.impact import bem_impact
from dem_contact.reference.paths import COMPARISON_SET, named_path

HERE = os.path.dirname(os.path.abspath(__file__))
RES = os.path.join(HERE, "results")
STEEL_E, STEEL_NU = 208e9, 0.3
MU = 0.3


def save(name, obj):
    os.makedirs(RES, exist_ok=True)
    with open(os.path.join(RES, f"{name}.json"), "w") as f:
        json.dump(obj, f, indent=None if name == "paths" else 1)


def load(name):
    path = os.path.join(RES, f"{name}.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def ee_scene(tangential="mdr"):
    return dc.Scene(dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL), mu=MU, tangential=tangential, v_ref=dc.reference_speed(5.0))


# -- Cattaneo-Mindlin ----------------------------------------------------------------------------------
def cattaneo_mindlin(nu, n, k=20, R=0.005, delta=2e-6):
    """Loading to 0.8 of the slip displacement in k steps, unloading to -0.8 in 2k steps, constant N:
    errors against Mindlin & Deresiewicz (1953; Johnson 1985 section 7.2) in units of mu N."""
    G = STEEL_E / (2 * (1 + nu))
    G_star = G / (2 * (2 - nu))
    E_star = STEEL_E / (2 * (1 - nu * nu))
    a = math.sqrt(R * delta)
    N = 4 / 3 * E_star * math.sqrt(R) * delta**1.5
    s = 3 * MU * N / (16 * G_star * a)
    u_load = np.linspace(0, 0.8 * s, k + 1)[1:]
    u_un = np.linspace(0.8 * s, -0.8 * s, 2 * k + 1)[1:]
    u = np.r_[u_load, u_un]
    t0 = time.perf_counter()
    _, Tx, Ty = B.bem_path(STEEL_E, nu, STEEL_E, nu, R, MU, np.full(u.size, delta), u, 0 * u, n_across=n)
    wall = time.perf_counter() - t0
    T_load = MU * N * (1 - (1 - u_load / s) ** 1.5)
    T_un = T_load[-1] - 2 * MU * N * (1 - (1 - (u_load[-1] - u_un) / (2 * s)) ** 1.5)
    err = (-Tx - np.r_[T_load, T_un]) / (MU * N)
    return {"nu": nu, "n_across": n, "err_load": float(np.abs(err[:k]).max()),
            "err_unload": float(np.abs(err[k:]).max()), "time_per_step": wall / u.size,
            "u_over_s": (u / s).tolist(), "T_over_muN": (-Tx / (MU * N)).tolist(),
            "T_cm_over_muN": (np.r_[T_load, T_un] / (MU * N)).tolist()}


def run_cm():
    out = []
    for nu in (0.0, 0.3):
        for n in (16, 32, 64, 128):
            r = cattaneo_mindlin(nu, n)
            print(f"CM nu={nu} n={n}: load {r['err_load']:.2e} unload {r['err_unload']:.2e} mu N "
                  f"({r['time_per_step'] * 1e3:.0f} ms/step)", flush=True)
            out.append(r)
            save("cm", out)


# -- planar impact --------------------------------------------------------------------------------------
IMPACT_ANGLES = (5.0, 10.0, 20.0, 30.0, 45.0, 55.0)


def run_impact():
    scene = ee_scene()
    out = {"angles": list(IMPACT_ANGLES), "mdr": [], "Theta": [], "bem": {}}
    for ang in IMPACT_ANGLES:
        r = dc.impact(scene, 5.0, 5.0 * math.tan(math.radians(ang)), steps_per_contact=2000)
        out["mdr"].append(r.f_over_mu)
        out["Theta"].append(r.Theta)
    save("impact", out)
    runs = [(16, 200), (32, 200), (32, 400), (64, 200), (128, 200)]
    for n, steps in runs:
        key = f"{n}/{steps}"
        out["bem"][key] = []
        for ang, fm_ref in zip(IMPACT_ANGLES, out["mdr"]):
            if n == 128 and ang not in (10.0, 30.0):
                continue
            t0 = time.perf_counter()
            b = bem_impact(scene, 5.0, 5.0 * math.tan(math.radians(ang)), n_across=n, steps=steps)
            wall = time.perf_counter() - t0
            out["bem"][key].append({"angle": ang, "f_over_mu": b.f_over_mu, "diff": b.f_over_mu - fm_ref,
                                    "wall": wall})
            print(f"impact n={n} steps={steps} angle={ang}: f/mu {b.f_over_mu:.5f} mdr {fm_ref:.5f} "
                  f"diff {b.f_over_mu - fm_ref:+.2e} ({wall:.0f} s)", flush=True)
            save("impact", out)


def run_impact_nu0():
    """The same comparison with nu = 0 for both bodies: MDR is then exact for the BEM's model (the
    Cattaneo-Mindlin field is exactly axisymmetric), so the difference must converge to zero."""
    nu0 = dc.Material(E=STEEL_E, nu=0.0, rho=dc.STEEL.rho)
    scene = dc.Scene(dc.Sphere(0.01, nu0), dc.Wall(nu0), mu=MU, tangential="mdr", v_ref=5.0)
    angles = (10.0, 20.0, 30.0)
    out = {"angles": list(angles), "mdr": [], "Theta": [], "bem": {}}
    for ang in angles:
        r = dc.impact(scene, 5.0, 5.0 * math.tan(math.radians(ang)), steps_per_contact=2000)
        out["mdr"].append(r.f_over_mu)
        out["Theta"].append(r.Theta)
    runs = ((16, 200), (32, 200), (64, 200), (128, 200), (64, 400), (128, 400), (32, 800), (64, 800), (128, 800))
    for n, steps in runs:
        key = f"{n}/{steps}"
        out["bem"][key] = []
        for ang, fm_ref in zip(angles, out["mdr"]):
            if (n == 128 or steps > 200) and ang == 30.0 or steps == 800 and ang != 20.0:
                continue
            b = bem_impact(scene, 5.0, 5.0 * math.tan(math.radians(ang)), n_across=n, steps=steps)
            out["bem"][key].append({"angle": ang, "f_over_mu": b.f_over_mu, "diff": b.f_over_mu - fm_ref})
            print(f"impact nu=0 n={n} steps={steps} angle={ang}: f/mu {b.f_over_mu:.5f} mdr {fm_ref:.5f} "
                  f"diff {b.f_over_mu - fm_ref:+.2e}", flush=True)
            save("impact_nu0", out)


SPIN_RATES = (0.0, 50.0, 100.0, 200.0, 400.0)     # rad/s about x (along the incident velocity)


def run_spin():
    """Impacts with out-of-plane spin (about the incident tangential velocity, in the wall plane): the
    contact-point velocity has a component across the plane of incidence that the impact turns."""
    scene = ee_scene("mdr_adaptive")
    vt = 1.5
    out = []
    for n in (32, 64):
        for wx in SPIN_RATES:
            b = bem_impact(scene, 5.0, vt, spin=(wx, 0.0, 0.0), n_across=n, steps=200)
            Pm = b.tangential_impulse / (MU * b.normal_impulse)
            out.append({"n_across": n, "spin_x": wx, "Theta": b.Theta, "f_over_mu": b.f_over_mu,
                        "Px_over_muPn": Pm[0], "Py_over_muPn": Pm[1], "v_r": b.v_r.tolist(),
                        "omega_r": b.omega_r.tolist(), "v_cr": b.v_cr.tolist()})
            print(f"spin n={n} wx={wx}: P/(mu Pn) = ({Pm[0]:+.5f}, {Pm[1]:+.5f}) f/mu {b.f_over_mu:.5f}", flush=True)
            save("spin", out)


# -- timing ---------------------------------------------------------------------------------------------
def _machine():
    """The record of the machine that timed: CPU model and logical cores."""
    cpu = platform.processor() or "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next((ln.split(":", 1)[1].strip() for ln in f if ln.startswith("model name")), cpu)
    except OSError:
        pass
    return {"name": "machine", "cpu": cpu, "cores": os.cpu_count()}


def run_timing():
    out = [_machine()]
    for n in (32, 64, 128):
        for tol, inc, steps in ((B.DEFAULT_TOL, 0.08, 10), (1e-4, 0.08, 10), (B.DEFAULT_TOL, 0.01, 40)):
            t = B.time_per_step(n, steps, increment=inc, tol=tol)
            out.append({"n_across": n, "tol": tol, "increment": inc, "time_per_step": t})
            print(f"timing n={n} tol={tol:g} increment={inc}: {t * 1e3:.1f} ms/step", flush=True)
            save("timing", out)


# -- named paths ----------------------------------------------------------------------------------------
PATH_DELTA = 5e-5       # m: EE scene, R* = 10 mm (a = 0.71 mm); forces scale out in units of mu N
PATHS = (("load-unload", 0.8),) + COMPARISON_SET


#: (elements across, steps) of the path runs: grid convergence at 400 steps, step convergence at 64 across,
#: and the finest run (128 across, 800 steps) for comparisons with the 3D laws.
PATH_RUNS = ((32, 400), (64, 200), (64, 400), (64, 800), (128, 400), (64, 1600), (128, 800))


def run_paths(runs=PATH_RUNS):
    scene = ee_scene()
    m = scene.sphere.material
    out = load("paths") or {}
    os.makedirs(os.path.join(HERE, "paths"), exist_ok=True)
    for n, steps in runs:
        for shape, size in PATHS:
            key = f"{shape}:{size}:{n}:{steps}"
            if key in out:
                continue
            d, ux, uy = named_path(shape, size, steps, delta=PATH_DELTA, mu=MU, kappa=scene.pair.kappa)
            t0 = time.perf_counter()
            N, Tx, Ty = B.bem_path(m.E, m.nu, m.E, m.nu, scene.pair.R_star, MU, d, ux, uy, n_across=n)
            wall = time.perf_counter() - t0
            out[key] = {"shape": shape, "size": size, "n_across": n, "steps": steps, "wall": wall,
                        "Tx_over_muN": [float(f"{v:.9g}") for v in Tx / (MU * N)],
                        "Ty_over_muN": [float(f"{v:.9g}") for v in Ty / (MU * N)]}
            print(f"path {shape} {size} n={n} steps={steps}: {wall:.0f} s", flush=True)
            save("paths", out)
            if (n, steps) == PATH_RUNS[-1]:        # the finest run, for comparisons with the 3D laws
                np.savetxt(os.path.join(HERE, "paths", f"{shape}_{size:g}_n{n}_s{steps}.csv"),
                           np.column_stack([d, ux, uy, N, Tx, Ty]), delimiter=",",
                           header="delta,ux,uy,N,Tx,Ty", comments="", fmt="%.12e")


def vector_mdr_path(d, ux, uy, E_star, G_star, R_star, mu, springs=4000):
    """Vector MDR (Popov & Hess 2015, with a 2D displacement and a Coulomb circle per spring, radial return)
    on a path at constant overlap: an independent approximate model to set beside the BEM. Springs on the
    half-line, doubled by symmetry; returns N, Tx, Ty (force on body 1)."""
    a = math.sqrt(R_star * d.max())
    dx = a / springs
    x = (np.arange(springs) + 0.5) * dx
    G_M = 4.0 * G_star
    u = np.zeros((springs, 2))
    out = np.zeros((d.size, 3))
    px = py = 0.0
    for k in range(d.size):
        w = d[k] - x * x / R_star
        inside = w > 0.0
        u[~inside] = 0.0
        u[inside] += (ux[k] - px, uy[k] - py)
        px, py = ux[k], uy[k]
        lim = mu * E_star * np.clip(w, 0.0, None) / G_M
        m = np.hypot(u[:, 0], u[:, 1])
        f = np.where(m > lim, lim / np.where(m > 0, m, 1.0), 1.0)
        u *= f[:, None]
        out[k] = (2 * E_star * np.sum(np.clip(w, 0.0, None)) * dx, *(-2 * G_M * dx * u.sum(axis=0)))
    return out.T


def run_mdr_paths():
    """Vector MDR against the BEM (128 across, 800 steps) on the named paths."""
    scene = ee_scene()
    pr = scene.pair
    paths = load("paths") or {}
    out = {}
    for shape, size in PATHS:
        v = paths.get(f"{shape}:{size}:128:800")
        if v is None:
            continue
        d, ux, uy = named_path(shape, size, 800, delta=PATH_DELTA, mu=MU, kappa=pr.kappa)
        N, Tx, Ty = vector_mdr_path(d, ux, uy, pr.E_star, pr.G_star, pr.R_star, MU)
        t_mdr = np.array([Tx, Ty]) / (MU * N)
        t_bem = np.array([v["Tx_over_muN"], v["Ty_over_muN"]])
        err = np.hypot(*(t_mdr - t_bem))
        out[f"{shape}:{size}"] = {"max": float(err.max()), "final": float(err[-1]),
                                  "final_bem": float(np.hypot(*t_bem[:, -1])),
                                  "final_mdr": float(np.hypot(*t_mdr[:, -1]))}
        print(f"vector MDR vs BEM {shape} {size}: max {err.max():.4f} final {err[-1]:.4f} mu N", flush=True)
    save("mdr_paths", out)


# -- report ---------------------------------------------------------------------------------------------
def _fig_cm(cm, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    r64 = next(r for r in cm if r["nu"] == 0.3 and r["n_across"] == 64)
    ax[0].plot(r64["u_over_s"], r64["T_cm_over_muN"], "k-", lw=1, label="Cattaneo-Mindlin-Masing")
    ax[0].plot(r64["u_over_s"], r64["T_over_muN"], "o", ms=3, mfc="none", label="BEM, 64 across, nu = 0.3")
    ax[0].set_xlabel("u / s (s = 3 mu N / (16 G* a))")
    ax[0].set_ylabel("-T / (mu N)")
    ax[0].legend()
    for nu, mk in ((0.0, "o-"), (0.3, "s-")):
        rs = [r for r in cm if r["nu"] == nu]
        ax[1].loglog([r["n_across"] for r in rs], [max(r["err_load"], r["err_unload"]) for r in rs], mk,
                     label=f"nu = {nu}")
    n = np.array([16, 128])
    ax[1].loglog(n, 1.5e-3 * (n / 32.0) ** -2, "k:", label="slope -2")
    ax[1].set_xlabel("elements across the contact")
    ax[1].set_ylabel("max |T - T_CM| / (mu N)")
    ax[1].legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def _fig_impact(imp, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    ax[0].plot(imp["Theta"], imp["mdr"], "k-", label="mdr (exact MDR, 200 springs, 2000 steps)")
    for key, mk in (("16/200", "^"), ("32/200", "s"), ("64/200", "o"), ("128/200", "D")):
        rows = imp["bem"].get(key, [])
        th = [imp["Theta"][imp["angles"].index(r["angle"])] for r in rows]
        ax[0].plot(th, [r["f_over_mu"] for r in rows], mk, mfc="none", label=f"BEM {key.split('/')[0]} across")
        ax[1].semilogy(th, [abs(r["diff"]) for r in rows], mk + "-", mfc="none", label=f"{key.split('/')[0]} across")
    ax[0].set_xlabel("Theta")
    ax[0].set_ylabel("f / mu")
    ax[0].legend(fontsize=8)
    ax[1].set_xlabel("Theta")
    ax[1].set_ylabel("|f/mu (BEM) - f/mu (mdr)|")
    ax[1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def _fig_paths(paths, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, len(PATHS), figsize=(3.2 * len(PATHS), 6.2))
    for j, (shape, size) in enumerate(PATHS):
        key = next((k for k in (f"{shape}:{size}:128:800", f"{shape}:{size}:128:400", f"{shape}:{size}:64:400")
                    if k in paths), None)
        if key is None:
            continue
        v = paths[key]
        from dem_contact.reference.paths import unit_path
        ux, uy = unit_path(shape, size, v["steps"])
        tx, ty = np.array(v["Tx_over_muN"]), np.array(v["Ty_over_muN"])
        axes[0, j].plot(ux, uy, "k-")
        every = max(1, len(ux) // 25)
        axes[0, j].quiver(ux[::every], uy[::every], tx[::every], ty[::every], color="C0", angles="xy",
                          scale_units="xy", scale=1.0 / (0.25 * size), width=0.006)
        axes[0, j].set_aspect("equal", adjustable="datalim")
        axes[0, j].set_title(f"{shape} {size:g}: path, force on body 1", fontsize=9)
        axes[0, j].set_xlabel("ux / s")
        axes[1, j].plot(np.hypot(tx, ty), label="|T| / mu N")
        axes[1, j].plot(tx, label="Tx / mu N", lw=0.8)
        axes[1, j].plot(ty, label="Ty / mu N", lw=0.8)
        axes[1, j].set_xlabel("step")
    axes[1, 0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def run_report():
    cm, imp, tim, paths = load("cm"), load("impact"), load("timing"), load("paths")
    lines = ["# Boundary-element reference: validation", "",
             "Generated by `python validation/bem/run_bem.py report` from the saved results of the other "
             "sections of the script (`all` reruns them; see its header). Steel on steel "
             "(E = 208 GPa, nu = 0.3 unless stated), mu = 0.3, solve tolerance "
             f"{B.DEFAULT_TOL:g} of the slip displacement.", ""]
    if cm:
        _fig_cm(cm, os.path.join(HERE, "bem_cattaneo_mindlin.png"))
        lines += ["## Cattaneo-Mindlin loading and unloading at constant N", "",
                  "Loading to 0.8 of the slip displacement s = 3 mu N/(16 G* a) in 20 steps, unloading to "
                  "-0.8 s in 40 steps; largest error against the Cattaneo-Mindlin-Masing curves "
                  "(Johnson 1985, section 7.2), in units of "
                  "mu N. With nu = 0 the analytic solution is exact for the model, and the error falls at "
                  "about second order; with nu = 0.3 Cattaneo-Mindlin is itself approximate (the slip is "
                  "not exactly parallel to T), and the BEM converges to a slightly different curve.", "",
                  "| nu | elements across | loading | unloading |", "|---|---|---|---|"]
        for r in cm:
            lines.append(f"| {r['nu']} | {r['n_across']} | {r['err_load']:.2e} | {r['err_unload']:.2e} |")
        lines += ["", "![Cattaneo-Mindlin](bem_cattaneo_mindlin.png)", ""]
    if imp:
        _fig_impact(imp, os.path.join(HERE, "bem_impact.png"))
        keys = list(imp["bem"])
        lines += ["## Planar oblique impact against the exact MDR reference", "",
                  "EE scene (R = 10 mm, 5 m/s, mu = 0.3), f/mu of `bem_impact` (Hertz normal motion, "
                  "velocity Verlet with the BEM tangential force) against the `mdr` law "
                  "(`dem_contact.impact`, 200 springs, 2000 steps per contact). Differences "
                  "f/mu(BEM) - f/mu(mdr); columns: elements across / steps per contact.", "",
                  "| angle | Theta | mdr f/mu | " + " | ".join(keys) + " |",
                  "|---|---|---|" + "---|" * len(keys)]
        for i, ang in enumerate(imp["angles"]):
            cells = []
            for k in keys:
                row = next((r for r in imp["bem"][k] if r["angle"] == ang), None)
                cells.append("" if row is None else f"{row['diff']:+.1e}")
            lines.append(f"| {ang:g} | {imp['Theta'][i]:.3f} | {imp['mdr'][i]:.5f} | " + " | ".join(cells) + " |")
        lines += ["", "The moving contact edge crosses element centres at times that depend on the step, so "
                  "on a coarse grid f/mu moves with the step count by about the grid error (32 across: up to "
                  "6e-4 between 200 and 400 steps).", "", "![impact](bem_impact.png)", ""]
    imp0 = load("impact_nu0")
    if imp0:
        keys = list(imp0["bem"])
        lines += ["With nu = 0 for both bodies (E = 208 GPa) MDR is exact for the BEM's model: the "
                  "difference falls from 2e-3 (16 across) to within 3e-4 (64 and 128 across) at 200 steps; it "
                  "moves with the step count, as the contact edge swallows element centres at discrete times, "
                  "and with many steps (800) it converges to zero at about order 1.5 in the element size "
                  "(1.1e-3, 4.0e-4, 1.3e-4 at 32, 64, 128 across). With "
                  "nu = 0.3 the converged BEM differs from MDR by a few 1e-4 more (the Poisson term of the "
                  "Cerruti kernel makes the tangential field slightly non-axisymmetric, which MDR neglects; "
                  "compare the Cattaneo-Mindlin errors above).", "",
                  "| angle | Theta | mdr f/mu | " + " | ".join(keys) + " |", "|---|---|---|" + "---|" * len(keys)]
        for i, ang in enumerate(imp0["angles"]):
            rows = [next((r for r in imp0["bem"][k] if r["angle"] == ang), None) for k in keys]
            cells = ["" if r is None else f"{r['diff']:+.1e}" for r in rows]
            lines.append(f"| {ang:g} | {imp0['Theta'][i]:.3f} | {imp0['mdr'][i]:.5f} | " + " | ".join(cells) + " |")
        lines.append("")
    spin = load("spin")
    if spin:
        lines += ["## Impacts with out-of-plane spin", "",
                  "EE scene, V_n = 5 m/s, V_t = 1.5 m/s along x (Theta = 1 without spin), initial spin omega_x "
                  "about the incident velocity (in the wall plane), so the contact point also slides across "
                  "the plane of incidence (v_cy = R omega_x), at an angle to the incident velocity of the centre. On a flat wall "
                  "the slip direction stays that incident angle through the impact (the tangential impulse ratio "
                  "Py/Px equals v_cy/v_cx). Tangential "
                  "impulse on the sphere over mu P_n, f/mu along the incident contact-point velocity, rebound "
                  "spin (x along V_t, z the wall normal towards the sphere; the planar omega of Wu et al. is "
                  "-omega_y); 200 steps; columns 32 and 64 elements across.", "",
                  "| omega_x [rad/s] | Theta | Px/(mu Pn) 32 | 64 | Py/(mu Pn) 32 | 64 | f/mu 64 | "
                  "omega_r (x, y) 64 [rad/s] |", "|---|---|---|---|---|---|---|---|"]
        for wx in sorted({r["spin_x"] for r in spin}):
            a = next((r for r in spin if r["spin_x"] == wx and r["n_across"] == 32), None)
            b = next((r for r in spin if r["spin_x"] == wx and r["n_across"] == 64), None)
            if a is None or b is None:
                continue
            lines.append(f"| {wx:g} | {b['Theta']:.3f} | {a['Px_over_muPn']:+.5f} | {b['Px_over_muPn']:+.5f} | "
                         f"{a['Py_over_muPn']:+.5f} | {b['Py_over_muPn']:+.5f} | {b['f_over_mu']:.5f} | "
                         f"({b['omega_r'][0]:.2f}, {b['omega_r'][1]:.2f}) |")
        lines.append("")
    if tim:
        lines += ["## Time per step", "",
                  "Partial-slip loading at constant overlap from the unloaded contact, in steps of 0.08 or 0.01 "
                  "slip displacements (10 or 40 steps, min of 3 runs), warm-started, one FFT thread, on the "
                  "machine of the record `name=machine` of timing.json (its CPU and cores; timings depend on it). "
                  "`pytest tests/benchmarks/test_bench_bem.py --benchmark-only` measures the same.", "",
                  "| elements across | tolerance | step [slip displacements] | ms per step |", "|---|---|---|---|"]
        for r in (r for r in tim if "n_across" in r):
            lines.append(f"| {r['n_across']} | {r['tol']:g} | {r.get('increment', 0.08):g} | "
                         f"{r['time_per_step'] * 1e3:.1f} |")
        lines.append("")
    if paths:
        _fig_paths(paths, os.path.join(HERE, "bem_paths.png"))

        def arclength(shape, size, steps):
            from dem_contact.reference.paths import unit_path
            ux, uy = unit_path(shape, size, steps)
            return np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(ux), np.diff(uy)))])

        def force(shape, size, n, steps, at=None):
            """T / (mu N) of a run, or interpolated (in arc length) at the rows of the run ``at`` (steps)."""
            v = paths.get(f"{shape}:{size}:{n}:{steps}")
            if v is None:
                return None
            t = np.array([v["Tx_over_muN"], v["Ty_over_muN"]])
            if at is None or at == steps:
                return t
            s_from, s_at = arclength(shape, size, steps), arclength(shape, size, at)
            return np.array([np.interp(s_at, s_from, t[0]), np.interp(s_at, s_from, t[1])])

        def diff(a, b):
            return "" if a is None or b is None else f"{np.max(np.hypot(*(a - b))):.1e}"
        lines += ["## Named curved paths at constant overlap", "",
                  f"delta = {PATH_DELTA:g} m on the EE scene (R* = 10 mm); sizes in slip displacements "
                  "(`dem_contact.reference.paths`). Entries: max over the path of |T_1 - T_2| / (mu N). Grid: "
                  "32 and 64 against 128 elements across, all at 400 steps. Steps (at 64 across): 200, 400 and "
                  "800 against 1600 steps (the finer run interpolated in arc length to the rows of the coarser). "
                  "The step error is first order (the "
                  "slip direction of a step is that of its increment); the grid error falls faster.", "",
                  "| path | size | 32 vs 128 | 64 vs 128 | 200 vs 1600 steps | 400 vs 1600 | 800 vs 1600 "
                  "| final |T|/mu N (128/800) |",
                  "|---|---|---|---|---|---|---|---|"]
        for shape, size in PATHS:
            ref = force(shape, size, 128, 400)
            best = force(shape, size, 128, 800)
            fin = "" if best is None else f"{np.hypot(*best[:, -1]):.4f}"
            steps = " | ".join(diff(force(shape, size, 64, k), force(shape, size, 64, 1600, at=k))
                               for k in (200, 400, 800))
            lines.append(f"| {shape} | {size:g} | {diff(force(shape, size, 32, 400), ref)} | "
                         f"{diff(force(shape, size, 64, 400), ref)} | {steps} | {fin} |")
        mdr = load("mdr_paths")
        if mdr:
            lines += ["", "A vector MDR (4000 springs on the half-line, each with a 2D displacement and its own "
                      "Coulomb circle, radial return; exact for straight paths, approximate when the path "
                      "turns) beside the BEM (128 across, 800 steps), same rows: largest and final |T_MDR - "
                      "T_BEM| / (mu N), and the final |T| / (mu N) of both.", "",
                      "| path | size | max | final | final BEM | final MDR |", "|---|---|---|---|---|---|"]
            for shape, size in PATHS:
                r = mdr.get(f"{shape}:{size}")
                if r:
                    lines.append(f"| {shape} | {size:g} | {r['max']:.4f} | {r['final']:.4f} | "
                                 f"{r['final_bem']:.4f} | {r['final_mdr']:.4f} |")
        lines += ["", "The force histories of the finest runs (128 across, 800 steps) are in `paths/*.csv` "
                  "(delta, ux, uy [m], N, Tx, Ty [N]).", "",
                  "![paths](bem_paths.png)", ""]
    with open(os.path.join(HERE, "report.md"), "w") as f:
        f.write("\n".join(lines))
    print("report written to", os.path.join(HERE, "report.md"))


SECTIONS = {"cm": run_cm, "impact": run_impact, "impact_nu0": run_impact_nu0, "spin": run_spin, "timing": run_timing,
            "paths": run_paths, "mdr_paths": run_mdr_paths, "report": run_report}

if __name__ == "__main__":
    todo = sys.argv[1:] or ["all"]
    for name in todo:
        if name == "all":
            for f in SECTIONS.values():
                f()
        elif name in SECTIONS:
            SECTIONS[name]()
        else:
            sys.exit(f"unknown section {name!r}; choose from: {', '.join(SECTIONS)}, all")
