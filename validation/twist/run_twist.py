"""The exact twist law of Hertz contacts (dem_contact.laws.twist.deresiewicz) against its closed forms and,
with --bem, the boundary-element reference with twist.

Writes validation/twist/twist.png (Lubkin's loading curve and a Deresiewicz cycle, the law at three cell
counts), twist_results.json (errors in units of mu N a, the convergence with the cells in contact, the
energy balance of closed loops at constant and varying N) and, with --bem, the BEM comparison of a twist
cycle at constant overlap (steel on steel, mu 0.3).

    python validation/twist/run_twist.py [--bem] [--n-across 64] [--steps 200]
"""
import argparse
import json
import math
import pathlib
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from dem_contact.laws import closed_forms as cf  # noqa: E402
from dem_contact.laws.twist import deresiewicz as d  # noqa: E402
from dem_contact.materials import STEEL, Sphere  # noqa: E402

HERE = pathlib.Path(__file__).parent
MU, R, DELTA = 0.3, 5e-3, 1e-6


def setup():
    G = STEEL.E / (2 * (1 + STEEL.nu))
    Gc = d.twist_modulus(Sphere(R, STEEL), Sphere(R, STEEL))
    assert math.isclose(Gc, G / 2)
    Es = STEEL.E / (2 * (1 - STEEL.nu**2))
    a = math.sqrt(R * DELTA)
    N = 4 / 3 * Es * math.sqrt(R) * DELTA**1.5
    return Gc, N, a, MU * N * a / (16 / 3 * Gc * a**3)


def on_grid(Gc, N, a, beta, cells_in, n):
    """The law along beta at constant N, a with the cell width a / cells_in (n cells)."""
    H = np.zeros((1, d.Q_CELLS + n))
    H[0, d.Q_DS] = a / cells_in
    M = np.zeros(beta.size)
    for t in range(1, beta.size):
        M[t] = d.advance(H, 0, 0, n, Gc, MU, R, N, a, a, beta[t] - beta[t - 1])
    return M


def cycle(b1, steps):
    """0 -> 2 beta_1 -> -2 beta_1 -> 2 beta_1."""
    return np.concatenate([np.linspace(0, 2 * b1, steps + 1), np.linspace(2 * b1, -2 * b1, 2 * steps + 1)[1:],
                           np.linspace(-2 * b1, 2 * b1, 2 * steps + 1)[1:]])


def masing(beta, b1, Gc, N, a, steps):
    """Closed form along ``cycle``: Lubkin's loading, then Deresiewicz's branches (Masing's rule)."""
    ML = lambda x: cf.lubkin_moment(x, Gc, MU, N, a)  # noqa: E731
    Ms = ML(2 * b1)
    out = []
    for i, x in enumerate(beta):
        if i <= steps:
            out.append(ML(x))
        elif i <= 3 * steps:
            out.append(Ms - 2 * ML((2 * b1 - x) / 2))
        else:
            out.append(-Ms + 2 * ML((x + 2 * b1) / 2))
    return np.array(out)


def spring_energy(h, n, Gc, a):
    """Energy of the springs: 4 pi int s^2 h^2 / (2 k) ds = 8 G_c sum theta_i^2 w_i (cells inside a)."""
    ds = h[d.Q_DS]
    U = 0.0
    for i in range(n):
        x0, x1 = i * ds, min((i + 1) * ds, a)
        if x1 > x0:
            U += 8 * Gc * h[d.Q_CELLS + i] ** 2 * (x1**3 - x0**3) / 3
    return U


def energy_counts(Gc, N0, a0, b1, loops=200, seed=1):
    """Closed loops (twist and overlap back to their start, after a random history) at constant and at
    varying N: how many absorb negative work (the energy the contact would create)."""
    rng = np.random.default_rng(seed)
    Es = STEEL.E / (2 * (1 - STEEL.nu**2))
    res = {}
    for varying in (False, True):
        neg = 0
        worst = 0.0
        least_dissipated = math.inf
        for _ in range(loops):
            k = 60
            b_pre = b1 * np.cumsum(rng.normal(0, 0.3, k))
            b_pre[0] = 0.0
            b_loop = b_pre[-1] + b1 * rng.uniform(0.3, 2.0) * np.sin(np.linspace(0, 2 * np.pi, 81)) \
                * rng.choice([-1, 1])
            beta = np.concatenate([b_pre, b_loop[1:]])
            if varying:
                dl = DELTA * (1 + 0.5 * np.sin(np.linspace(0, 2 * np.pi, 81) * rng.integers(1, 3)
                                               + rng.uniform(0, 6.3)))
                dl = np.concatenate([np.full(k, dl[0]), dl[1:]])
            else:
                dl = np.full(beta.size, DELTA)
            N = 4 / 3 * Es * math.sqrt(R) * dl**1.5
            a = np.sqrt(R * dl)
            n = d.TWIST_CELLS
            H = np.zeros((1, d.Q_CELLS + n))
            U = []
            W = []
            for t in range(1, beta.size):
                d.advance(H, 0, 0, n, Gc, MU, R, N[t], a[t], a[t - 1], beta[t] - beta[t - 1])
                W.append(H[0, d.Q_WORK])
                U.append(spring_energy(H[0], n, Gc, a[t]))
            loop = W[-1] - W[k - 2]
            dissipated = loop - (U[-1] - U[k - 2])
            unit = MU * N0 * a0 * b1
            worst = min(worst, loop / unit)
            least_dissipated = min(least_dissipated, dissipated / unit)
            neg += loop < -1e-12 * unit
        res["varying N" if varying else "constant N"] = {"loops": loops, "negative work": int(neg),
                                                         "most negative loop work / (mu N a beta_1)": worst,
                                                         "least dissipation (work less the change of the springs' "
                                                         "energy) / (mu N a beta_1)": least_dissipated}
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bem", action="store_true", help="compare with the BEM reference with twist")
    ap.add_argument("--n-across", type=int, default=64, help="BEM elements across the contact (default 64)")
    ap.add_argument("--steps", type=int, default=200, help="steps of the BEM twist cycle (default 200)")
    args = ap.parse_args()
    Gc, N, a, b1 = setup()
    scale = MU * N * a
    steps = 100
    beta = cycle(b1, steps)
    exact = masing(beta, b1, Gc, N, a, steps)
    out = {"pair": "steel on steel", "mu": MU, "R_star": R, "delta": DELTA, "beta_1": b1, "N": N, "a": a,
           "full_slip_M/(mu N a)": 3 * math.pi / 16}
    conv = {}
    fig, axs = plt.subplots(1, 2, figsize=(11, 4.2))
    axs[0].plot(beta / b1, exact / scale, "k-", lw=2.5, label="Lubkin / Deresiewicz (closed form)")
    for cells_in, style in ((8, "--"), (16, "-."), (32, ":")):
        M = on_grid(Gc, N, a, beta, cells_in, max(cells_in, 16))
        err = np.abs(M - exact).max() / scale
        conv[cells_in] = err
        axs[0].plot(beta / b1, M / scale, style, label=f"law, {cells_in} cells in contact (max err {err:.1e})")
    for cells_in in (64, 128):
        conv[cells_in] = np.abs(on_grid(Gc, N, a, beta, cells_in, cells_in) - exact).max() / scale
    out["cycle max error / (mu N a) by cells in contact"] = conv
    axs[0].set_xlabel("twist / beta_1")
    axs[0].set_ylabel("M / (mu N a)")
    axs[0].set_title("twist cycle at constant N")
    axs[0].legend(fontsize=7)
    cells = np.array(sorted(conv))
    axs[1].loglog(cells, [conv[c] for c in cells], "o-", label="law vs closed form")
    axs[1].loglog(cells, conv[16] * (16 / cells) ** 2, "k:", label="second order")
    if args.bem:
        from dem_contact.reference import bem, paths
        E, nu = STEEL.E, STEEL.nu
        dl, ux, uy, tw = paths.named_path("twist-cycle", 2.0, args.steps, delta=DELTA, mu=MU, kappa=1.0, twist_unit=b1)
        t0 = time.time()
        _, _, _, Mz = bem.bem_path(E, nu, E, nu, R, MU, dl, ux, uy, tw, n_across=args.n_across)
        bem_s = time.time() - t0
        bb = np.concatenate([[0.0], tw])
        berr = {}
        for n in (16, 32, 64, 128):
            M, _ = d.twist_path(Gc, MU, R, np.full(bb.size, N), np.full(bb.size, a), bb, n)
            berr[n] = float(np.abs(-M[1:] - Mz).max() / scale)
        out["bem"] = {"n_across": args.n_across, "steps": args.steps, "seconds": bem_s,
                      "max |M_law - M_bem| / (mu N a) by law cells": berr}
        axs[0].plot(tw / b1, -Mz / scale, "r.", ms=2, label=f"BEM {args.n_across} across")
        axs[0].legend(fontsize=7)
    axs[1].set_xlabel("cells in contact")
    axs[1].set_ylabel("max |M - M_exact| / (mu N a)")
    axs[1].set_title("convergence")
    axs[1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(HERE / "twist.png", dpi=120)
    out["energy"] = energy_counts(Gc, N, a, b1)
    (HERE / "twist_results.json").write_text(json.dumps(out, indent=1, default=float))
    print(json.dumps(out, indent=1, default=float))


if __name__ == "__main__":
    main()
