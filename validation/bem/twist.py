"""Validation of the boundary-element reference with twist about the normal (dem_contact.reference.bem):
closed forms, grid convergence, the named twist paths and the time per step.

Usage (from the repository root, PYTHONPATH set to it):

    python validation/bem/twist.py closed    # stiffness, full slip, Lubkin + Deresiewicz-Masing, n = 16 ... 256
    python validation/bem/twist.py paths     # the named twist paths at 32, 64, 128 elements across, 400 steps
    python validation/bem/twist.py report    # twist.md and bem_twist.png from the saved results
    python validation/bem/twist.py all

Closed forms (steel on steel, and steel on aluminium, and steel on a rigid wall; 1/G_c = 1/G1 + 1/G2):
no-slip moment (16/3) G_c a^3 beta (Johnson 1985, section 7.4); full slip (3 pi/16) mu N a (Lubkin 1951);
the monotonic twist with a slip annulus c < r < a (Lubkin 1951), here from the superposition of twisted
flat punches of radius b in [c, a] (Reissner-Sagoci traction (4 G_c phi_b / pi) r / sqrt(b^2 - r^2)):
with k = sqrt(1 - c^2/a^2), beta = mu p0 (K(k) - E(k)) / (2 G_c) and M = (8/3) mu p0 integral_c^a b^2 E(k_b) db
(K, E complete elliptic integrals of modulus k); unloading and reloading by the Masing rule
M = M* - 2 M_L((beta* - beta)/2) (Deresiewicz 1954). Results go to results/twist_*.json, the BEM histories
of the named paths at 128 across to paths/<shape>_<size>_n128_s400.csv (delta, ux, uy, twist, N, Tx, Ty, Mz).
"""
from __future__ import annotations

import json
import math
import os
import sys
import time

import numpy as np
from scipy import integrate, optimize, special

import dem_contact as dc
from dem_contact.reference import bem as B
from dem_contact.reference.paths import TWIST_SET, no_slip_twist, scene_path, twist_modulus

HERE = os.path.dirname(os.path.abspath(__file__))
RES = os.path.join(HERE, "results")
MU, R_STAR, DELTA = 0.3, 0.005, 2e-6           # closed-form runs: R* = 5 mm, a = 0.1 mm
STEEL = (208e9, 0.3)
PAIRS = {"steel-steel": STEEL, "steel-aluminium": (70e9, 0.33), "steel-rigid": (math.inf, 0.0)}
GRIDS = (16, 32, 64, 128, 256)
PATH_DELTA = 1e-5                              # named paths: steel sphere R = 10 mm on a steel wall
PATH_STEPS = 400
PATH_GRIDS = (32, 64, 128)
#: (elements across, steps) of the path runs: the grid at 400 steps, and the step at 64 across
PATH_RUNS = tuple((n, PATH_STEPS) for n in PATH_GRIDS) + ((64, 2 * PATH_STEPS),)


def save(name, obj):
    os.makedirs(RES, exist_ok=True)
    with open(os.path.join(RES, f"{name}.json"), "w") as f:
        json.dump(obj, f, indent=None if name == "twist_paths" else 1)


def load(name):
    path = os.path.join(RES, f"{name}.json")
    return json.load(open(path)) if os.path.exists(path) else None


def short(values):
    """A list of floats to 9 significant digits (the JSON results)."""
    return [float(f"{v:.9g}") for v in values]


def contact(E2, nu2):
    E1, nu1 = STEEL
    E_star = 1 / sum((1 - nu**2) / e for e, nu in ((E1, nu1), (E2, nu2)) if not math.isinf(e))
    a = math.sqrt(R_STAR * DELTA)
    N = 4 / 3 * E_star * math.sqrt(R_STAR) * DELTA**1.5
    Gc = twist_modulus(E1, nu1, E2, nu2)
    return E_star, Gc, a, N, no_slip_twist(DELTA, MU, R_STAR, E_star, Gc)


def lubkin(beta, Gc, a, N, mu=MU):
    """M(beta) of the monotonic twist [N m] (the module text)."""
    if beta <= 0:
        return 0.0
    p0 = 3 * N / (2 * math.pi * a * a)

    def kme(c):
        k2 = 1 - c * c
        return special.ellipk(k2) - special.ellipe(k2)
    c = optimize.brentq(lambda c: mu * p0 / (2 * Gc) * kme(c) - beta, 1e-300, 1 - 1e-16, xtol=1e-16, rtol=1e-15)
    m = integrate.quad(lambda t: t * t * special.ellipe(1 - t * t), c, 1, epsabs=1e-15, epsrel=1e-13)[0]
    return 8 / 3 * mu * p0 * a**3 * m


def run_closed():
    out = {}
    for n in GRIDS:
        row = {}
        for name, (E2, nu2) in PAIRS.items():
            _, Gc, a, N, b1 = contact(E2, nu2)
            _, _, _, Mz = B.bem_path(*STEEL, E2, nu2, R_STAR, 1e6, [DELTA, DELTA], [0, 0], [0, 0], [0, b1], n_across=n)
            row[f"stiffness {name}"] = -Mz[1] / b1 / (16 / 3 * Gc * a**3) - 1
        _, Gc, a, N, b1 = contact(*STEEL)
        full = 3 * math.pi / 16 * MU * N * a
        _, _, _, Mz = B.bem_path(*STEEL, *STEEL, R_STAR, MU, np.full(5, DELTA), np.zeros(5), np.zeros(5),
                                 np.linspace(0, 12 * b1, 5), n_across=n)
        row["full slip (12 beta_1)"] = -Mz[-1] / full - 1
        row["exact at 12 beta_1"] = lubkin(12 * b1, Gc, a, N) / full - 1
        # the twist cycle 0 -> 2 beta_1 -> -2 beta_1 -> 2 beta_1, 20 steps per beta_1 ... in 80 steps
        tw = b1 * np.r_[np.linspace(0, 2, 21), np.linspace(2, -2, 41)[1:], np.linspace(-2, 2, 41)[1:]]
        t0 = time.perf_counter()
        _, _, _, Mz = B.bem_path(*STEEL, *STEEL, R_STAR, MU, np.full(tw.size, DELTA), 0 * tw, 0 * tw, tw,
                                 n_across=n)
        wall = time.perf_counter() - t0
        ms = lubkin(2 * b1, Gc, a, N)
        exact = np.r_[[lubkin(b, Gc, a, N) for b in tw[:21]],
                      [ms - 2 * lubkin((2 * b1 - b) / 2, Gc, a, N) for b in tw[21:61]],
                      [-ms + 2 * lubkin((b + 2 * b1) / 2, Gc, a, N) for b in tw[61:]]]
        err = np.abs(-Mz - exact) / (MU * N * a)
        row["Lubkin loading (mu N a)"] = float(err[:21].max())
        row["Masing cycle (mu N a)"] = float(err.max())
        row["cycle time per step [s]"] = wall / tw.size
        if n == 64:
            row["cycle"] = {"twist_over_beta1": short(tw / b1), "M_over_muNa": short(-Mz / (MU * N * a)),
                            "exact": short(exact / (MU * N * a))}
        out[str(n)] = row
        print(n, {k: (f"{v:+.2e}" if isinstance(v, float) else "...") for k, v in row.items()}, flush=True)
        save("twist_closed", out)


def path_scene():
    return dc.Scene(dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL), mu=MU)


def run_paths():
    sc = path_scene()
    out = load("twist_paths") or {}
    for n, steps in PATH_RUNS:
        for shape, size in TWIST_SET:
            key = f"{shape}:{size}:{n}" + ("" if steps == PATH_STEPS else f":{steps}")
            if key in out:
                continue
            d, ux, uy, tw = scene_path(shape, size, steps, sc, PATH_DELTA)
            t0 = time.perf_counter()
            N, Tx, Ty, Mz = B.bem_path_scene(sc, d, ux, uy, tw, n_across=n)
            wall = time.perf_counter() - t0
            a = math.sqrt(sc.pair.R_star * PATH_DELTA)
            out[key] = {"shape": shape, "size": size, "n_across": n, "steps": steps, "wall": wall,
                        "time_per_step": wall / d.size,
                        "Tx_over_muN": short(Tx / (MU * N)), "Ty_over_muN": short(Ty / (MU * N)),
                        "Mz_over_muNa": short(Mz / (MU * N * a))}
            print(f"{shape} {size} n={n} steps={steps}: {wall:.1f} s ({1e3 * wall / d.size:.1f} ms/step)", flush=True)
            save("twist_paths", out)
            if n == PATH_GRIDS[-1] and steps == PATH_STEPS:
                os.makedirs(os.path.join(HERE, "paths"), exist_ok=True)
                np.savetxt(os.path.join(HERE, "paths", f"{shape}_{size:g}_n{n}_s{steps}.csv"),
                           np.column_stack([d, ux, uy, tw, N, Tx, Ty, Mz]), delimiter=",",
                           header="delta,ux,uy,twist,N,Tx,Ty,Mz", comments="", fmt="%.12e")


def step_error(paths, shape, size):
    """The 400-step run at 64 across against 800 steps, at the common rows (every second of 800)."""
    p, q = paths.get(f"{shape}:{size}:64"), paths.get(f"{shape}:{size}:64:{2 * PATH_STEPS}")
    if p is None or q is None:
        return None
    sub = slice(None, None, 2)
    dT = np.hypot(np.subtract(p["Tx_over_muN"], q["Tx_over_muN"][sub]),
                  np.subtract(p["Ty_over_muN"], q["Ty_over_muN"][sub]))
    dM = np.abs(np.subtract(p["Mz_over_muNa"], q["Mz_over_muNa"][sub]))
    return float(dT.max()), float(dM.max())


def grid_error(paths, shape, size, n, ref):
    """max |T_n - T_ref| / (mu N) and max |M_n - M_ref| / (mu N a) along the path."""
    p, q = paths[f"{shape}:{size}:{n}"], paths[f"{shape}:{size}:{ref}"]
    dT = np.hypot(np.subtract(p["Tx_over_muN"], q["Tx_over_muN"]), np.subtract(p["Ty_over_muN"], q["Ty_over_muN"]))
    dM = np.abs(np.subtract(p["Mz_over_muNa"], q["Mz_over_muNa"]))
    return float(dT.max()), float(dM.max())


def run_report():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    closed, paths = load("twist_closed"), load("twist_paths")
    lines = ["# Boundary-element reference with twist about the normal", "",
             "Generated by `python validation/bem/twist.py all` (the closed forms and the method are in the "
             "script's docstring). Steel (208 GPa, 0.3) on steel, on aluminium (70 GPa, 0.33) and on a rigid "
             "wall; mu = 0.3; constant overlap. Errors of the reference against closed forms, by elements "
             "across the contact diameter:", ""]
    if closed:
        keys = [k for k in next(iter(closed.values())) if k != "cycle"]
        lines += ["| elements across | " + " | ".join(keys) + " |", "|---" * (len(keys) + 1) + "|"]
        for n, row in closed.items():
            lines.append(f"| {n} | " + " | ".join(f"{row[k]:+.2e}" if "time" not in k else f"{row[k]:.3f}"
                                                  for k in keys) + " |")
        lines += ["", "Stiffness and full slip: relative error of the moment; the exact moment at 12 beta_1 "
                  "is below full slip by the amount shown (full slip is reached only as beta -> infinity). "
                  "Lubkin and Masing: largest |M_BEM - M_exact| / (mu N a) along the monotonic twist to "
                  "2 beta_1 and along the whole cycle to 2 beta_1, -2 beta_1 and 2 beta_1 (80 steps).", ""]
    if paths:
        lines += ["Named twist paths (`reference.paths.TWIST_SET`, steel sphere R = 10 mm on a steel wall, "
                  f"overlap {PATH_DELTA:g} m, {PATH_STEPS} steps): the reference's own grid error, its "
                  f"difference from the {PATH_GRIDS[-1]}-element run, and the wall time per step (one thread, "
                  "a shared machine):", "",
                  "| path | elements across | force error (mu N) | moment error (mu N a) | time per step [ms] |",
                  "|---|---|---|---|---|"]
        for shape, size in TWIST_SET:
            for n in PATH_GRIDS:
                p = paths.get(f"{shape}:{size}:{n}")
                if p is None:
                    continue
                e = grid_error(paths, shape, size, n, PATH_GRIDS[-1]) if n != PATH_GRIDS[-1] else (None, None)
                f = "-" if e[0] is None else f"{e[0]:.1e}"
                m = "-" if e[1] is None else f"{e[1]:.1e}"
                lines.append(f"| {shape} {size:g} | {n} | {f} | {m} | {1e3 * p['time_per_step']:.1f} |")
        lines.append("")
        st = [(f"{shape} {size:g}", step_error(paths, shape, size)) for shape, size in TWIST_SET]
        if all(e is not None for _, e in st):
            lines += [f"Step error at 64 across: {PATH_STEPS} steps against {2 * PATH_STEPS} (the same rows): "
                      + "; ".join(f"{k}: {e[0]:.1e} mu N, {e[1]:.1e} mu N a" for k, e in st) + ".", ""]
    lines += ["![twist](bem_twist.png)", ""]
    with open(os.path.join(HERE, "twist.md"), "w") as f:
        f.write("\n".join(lines))
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.4))
    if closed and "cycle" in closed.get("64", {}):
        c = closed["64"]["cycle"]
        ax[0].plot(c["twist_over_beta1"], c["exact"], "k-", lw=1, label="Lubkin / Deresiewicz-Masing")
        ax[0].plot(c["twist_over_beta1"], c["M_over_muNa"], "C0o", ms=3, label="BEM, 64 across")
        ax[0].axhline(3 * math.pi / 16, color="0.6", ls=":", lw=0.8)
        ax[0].axhline(-3 * math.pi / 16, color="0.6", ls=":", lw=0.8, label="full slip 3 pi/16")
        ax[0].set_xlabel("twist / beta_1")
        ax[0].set_ylabel("M / (mu N a) (moment on body 2)")
        ax[0].legend(fontsize=8)
    if paths:
        for i, (shape, size) in enumerate(TWIST_SET):
            p = paths.get(f"{shape}:{size}:{PATH_GRIDS[-1]}") or paths.get(f"{shape}:{size}:64")
            if p is None:
                continue
            rows = np.arange(len(p["Mz_over_muNa"]))
            ax[1].plot(rows, np.hypot(p["Tx_over_muN"], p["Ty_over_muN"]), f"C{i}-", lw=1,
                       label=f"{shape} {size:g}: |T|/(mu N)")
            ax[1].plot(rows, p["Mz_over_muNa"], f"C{i}--", lw=1, label="Mz/(mu N a)")
        ax[1].set_xlabel("row")
        ax[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, "bem_twist.png"), dpi=110)


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) > 1 else "all"
    for name, fn in (("closed", run_closed), ("paths", run_paths), ("report", run_report)):
        if what in (name, "all"):
            fn()
