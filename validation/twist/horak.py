"""Horak's spinning impact: a steel sphere spinning about the vertical at w0, dropped at vn on a steel plane
(no tangential velocity), with the exact twist law (deresiewicz), LAMMPS's engine models (marshall; sds with the Hertz values at the
largest force) and with no twist law; and an oblique impact
with spin about the normal.

The spin lost in the impact, 1 - w_r / w0, against Psi = w0 t_c / beta_1, the twist over the contact time in
units of the no-slip twist at unit moment at the largest force (beta_1 = mu N a / ((16/3) G_c a^3)). Small
Psi: the contact sticks and acts as a torsional spring (a loss independent of w0, set by the contact time
and the torsional stiffness against the inertia); large Psi: full slip, the angular impulse of Lubkin's
moment (3 pi/16) mu int N a dt, so 1 - w_r / w0 = (3 pi/16) mu int N a dt / (I w0) (drawn).

The laws run at LAW_STEPS steps per contact (their time step converged). The exact reference is the
boundary-element impact (``reference.impact.bem_impact``: Hertz normal motion, the 3D tangential and twist
contact solved on the contact area; Horak 1948's experiment without the axisymmetric assumption of Lubkin
1951 and Deresiewicz 1954), at every other Psi of the laws' grid. Its error is first order in the step and
in the element (``--convergence``), so it is given extrapolated in both (Richardson): L(n, s) at n =
BEM_N / 2 and BEM_N elements across the largest contact and s = BEM_STEPS / 2 and BEM_STEPS steps, L(n) =
2 L(n, BEM_STEPS) - L(n, BEM_STEPS / 2), L = 2 L(BEM_N) - L(BEM_N / 2). The deresiewicz law is also run
with more cells than the kernel's TWIST_CELLS (``law_cells_lost``). ``--convergence`` refines the BEM at
Psi = 0.01, 1, 100 (vn = 2 m/s) instead and writes horak_bem_convergence.json.

    python validation/twist/horak.py [--convergence] [--bem-n 64] [--bem-steps 400]

Writes validation/twist/horak.png and horak.json (about 10 minutes on one core, nearly all in the BEM;
--convergence about 10).
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

from dem_contact.impacts.impact3d import impact3d  # noqa: E402
from dem_contact.laws.model import Scene  # noqa: E402
from dem_contact.laws.twist import deresiewicz as d  # noqa: E402
from dem_contact.materials import STEEL, Sphere, Wall  # noqa: E402
from dem_contact.reference.impact import bem_impact  # noqa: E402

HERE = pathlib.Path(__file__).parent
R, MU = 5e-3, 0.3
#: Steps per contact of the laws' impacts.
LAW_STEPS = 2000
#: Elements across the largest contact and steps per contact of the BEM impacts.
BEM_N, BEM_STEPS = 64, 400
#: Cells of the deresiewicz law's springs in ``law_cells_lost`` (the kernel has TWIST_CELLS).
LAW_CELLS = (32, 64, 128, 256)
#: The BEM refinement at vn = 2 m/s: Psi values, (steps, elements across).
CONV_PSI = (0.01, 1.0, 100.0)
CONV_GRID = ((100, 32), (200, 32), (400, 32), (800, 32), (200, 48), (400, 48), (200, 64), (400, 64), (200, 96),
             (400, 96), (200, 128))


def scene():
    return Scene(Sphere(R, STEEL), Wall(STEEL), mu=MU, twist="deresiewicz")


def scales(sc, vn):
    """(t_c, beta_1 at the largest force, the Hertz impact at LAW_STEPS) of the drop at vn."""
    base = impact3d(sc, vn, series=True, steps_per_contact=LAW_STEPS)
    Gc = d.twist_modulus(sc.sphere, sc.body2)
    Nmax, amax = base.max_force, math.sqrt(sc.pair.R_star * base.max_overlap)
    return base.contact_time, MU * Nmax * amax / (16 / 3 * Gc * amax**3), base


def bem_lost(sc, vn, w0, steps, n):
    """1 - w_r / w0 of the BEM impact."""
    return 1.0 - bem_impact(sc, vn, 0.0, spin=(0.0, 0.0, w0), n_across=n, steps=steps).omega_r[2] / w0


def bem_extrapolated(sc, vn, w0, n, steps):
    """The BEM's spin loss extrapolated in the step and the element (module text), and its four runs."""
    runs = {(m, st): bem_lost(sc, vn, w0, st, m) for m in (n // 2, n) for st in (steps // 2, steps)}
    by_n = {m: 2 * runs[m, steps] - runs[m, steps // 2] for m in (n // 2, n)}
    return 2 * by_n[n] - by_n[n // 2], runs


def law_cells_lost(sc, vn, w0, cells, steps=4000):
    """1 - w_r / w0 of the deresiewicz law with ``cells`` cells (its ``twist_path``) in the drop at vn: the
    Hertz history on ``steps`` equal steps (DOP853, as the BEM impact's), the spin by a fixed point (the
    twist, the trapezoid of the spin, gives the moments; their angular impulse, the spin) to 1e-13 w0.
    The spin about the normal is uncoupled from the rest in this impact (no tangential force)."""
    from dem_contact.reference.impact import hertz_overlap_history
    pr = sc.pair
    _, tc, _, _ = hertz_overlap_history(pr.E_star, pr.R_star, pr.m_star, vn, None)
    t = np.linspace(0.0, tc, steps + 1)
    delta, _, _, _ = hertz_overlap_history(pr.E_star, pr.R_star, pr.m_star, vn, t)
    delta[0] = delta[-1] = 0.0
    N = 4 / 3 * pr.E_star * math.sqrt(pr.R_star) * delta**1.5
    a = np.sqrt(pr.R_star * delta)
    Gc, dt = d.twist_modulus(sc.sphere, sc.body2), tc / steps
    w = np.full(steps + 1, w0)
    for _ in range(100):
        beta = np.r_[0.0, np.cumsum(0.5 * (w[1:] + w[:-1]) * dt)]
        M, _ = d.twist_path(Gc, MU, pr.R_star, N, a, beta, cells)
        new = w0 - np.r_[0.0, np.cumsum(0.5 * (M[1:] + M[:-1]) * dt)] / sc.sphere.inertia
        done = np.max(np.abs(new - w)) < 1e-13 * abs(w0)
        w = new
        if done:
            return 1.0 - w[-1] / w0
    raise RuntimeError("the spin's fixed point did not converge")


def convergence():
    sc = scene()
    tc, beta1, _ = scales(sc, 2.0)
    rows = []
    for Psi in CONV_PSI:
        w0 = Psi * beta1 / tc
        law = 1 - impact3d(sc, 2.0, (0.0, 0.0), (0.0, 0.0, w0), steps_per_contact=LAW_STEPS).spin_r[2] / w0
        for steps, n in CONV_GRID:
            t0 = time.perf_counter()
            lost = bem_lost(sc, 2.0, w0, steps, n)
            rows.append(dict(Psi=Psi, steps=steps, n_across=n, lost_bem=lost, lost_deresiewicz=law,
                             seconds=time.perf_counter() - t0))
            print(f"Psi {Psi:g} steps {steps} n {n}: BEM {lost:.6g} (deresiewicz {law:.6g}), "
                  f"{rows[-1]['seconds']:.1f} s", flush=True)
    cells = [dict(Psi=Psi, cells=c, lost=law_cells_lost(sc, 2.0, Psi * beta1 / tc, c)) for Psi in CONV_PSI
             for c in LAW_CELLS]
    (HERE / "horak_bem_convergence.json").write_text(json.dumps(
        {"vn": 2.0, "law_steps": LAW_STEPS, "rows": rows, "law_cells": cells}, indent=1, default=float))


def main(bem_n=BEM_N, bem_steps=BEM_STEPS):
    out = {"sphere": "steel R 5 mm on a steel plane", "mu": MU, "law_steps_per_contact": LAW_STEPS,
           "bem": {"n_across": bem_n, "steps": bem_steps,
                   "lost_bem": "Richardson extrapolation in the step and the element: 2 L(n) - L(n / 2), "
                               "L(n) = 2 L(n, steps) - L(n, steps / 2)"}, "runs": []}
    t_bem = 0.0
    fig, axs = plt.subplots(1, 2, figsize=(11, 4.2))
    for vn, mark in ((0.2, "o"), (2.0, "s")):
        sc = scene()
        tc, beta1, base = scales(sc, vn)
        s = base.series
        a = np.sqrt(sc.pair.R_star * np.clip(s["overlap"], 0.0, None))
        Na = np.trapezoid(np.clip(s["normal_force"], 0, None) * a, s["t"])
        I = 0.4 * sc.sphere.mass * R * R
        dw_slip = 3 * math.pi / 16 * MU * Na / I          # the spin lost in full slip
        Gc = d.twist_modulus(sc.sphere, sc.body2)
        amax = math.sqrt(sc.pair.R_star * base.max_overlap)
        # the engine models: marshall as LAMMPS derives it; sds with the Hertz values at the largest force
        # (Lubkin's no-slip stiffness and full-slip moment per unit N), no dashpot
        engines = {"marshall": sc.replace(twist="marshall"),
                   "sds (Hertz values at F_max)": sc.replace(twist="sds", k_twist=16 / 3 * Gc * amax**3,
                                                             gamma_twist=0.0, mu_twist=3 * math.pi / 16 * MU * amax)}
        rows = []

        def law(s, w0):
            return impact3d(s, vn, (0.0, 0.0), (0.0, 0.0, w0), steps_per_contact=LAW_STEPS)
        for i, Psi in enumerate(np.geomspace(0.01, 1000.0, 21)):
            w0 = Psi * beta1 / tc
            r = law(sc, w0)
            r0 = law(sc.replace(twist="none"), w0)
            rows.append(dict(Psi=Psi, w0=w0, lost=1 - r.spin_r[2] / w0, lost_none=1 - r0.spin_r[2] / w0,
                             lost_full_slip=dw_slip / w0, energy_error=r.energy.error / r.energy.initial,
                             twist_work=r.energy.friction,
                             **{f"lost {k}": 1 - law(e, w0).spin_r[2] / w0 for k, e in engines.items()}))
            if i % 2 == 0:              # the BEM at every other Psi
                t0 = time.perf_counter()
                lost, runs = bem_extrapolated(sc, vn, w0, bem_n, bem_steps)
                t_bem += time.perf_counter() - t0
                rows[-1].update({"lost_bem": lost, "lost deresiewicz 256 cells": law_cells_lost(sc, vn, w0, 256),
                                 **{f"lost_bem_{st}_steps_{m}_across": v for (m, st), v in runs.items()}})
                print(f"vn {vn} Psi {Psi:.4g}: BEM {lost:.6g} (deresiewicz {rows[-1]['lost']:.6g}, "
                      f"256 cells {rows[-1]['lost deresiewicz 256 cells']:.6g})", flush=True)
        out["runs"].append({"vn": vn, "int_N_a_dt": Na, "full_slip_spin_loss": dw_slip, "beta_1_at_max_force": beta1,
                            "contact_time": tc, "rows": rows})
        P = np.array([x["Psi"] for x in rows])
        axs[0].loglog(P, [x["lost"] for x in rows], mark, label=f"deresiewicz, vn = {vn} m/s")
        bem = [x for x in rows if "lost_bem" in x]
        axs[0].loglog([x["Psi"] for x in bem], [x["lost_bem"] for x in bem], mark, ms=11, mfc="none", mec="k",
                      label=f"BEM (exact), vn = {vn} m/s")
        axs[0].loglog(P, [x["lost_full_slip"] for x in rows], "-", lw=0.8,
                      label=f"full slip throughout, vn = {vn} m/s")
        for k, st in zip(engines, ("x", "+")):
            axs[0].loglog(P, [x[f"lost {k}"] for x in rows], st, ms=5, label=f"{k}, vn = {vn} m/s")
    axs[0].set_xlabel("Psi = w0 t_c / beta_1 (beta_1 at the largest force)")
    axs[0].set_ylabel("1 - w_r / w0 (spin about the normal lost)")
    axs[0].set_title("Horak: a spinning sphere dropped on a plane (no twist law: no loss)")
    axs[0].legend(fontsize=6)
    out["bem"]["seconds"] = t_bem
    out["comparison"] = comparison(out)
    # oblique impact with spin about the normal: the spin plane turns
    sc = Scene(Sphere(R, STEEL), Wall(STEEL), mu=MU, twist="deresiewicz")
    obl = {}
    for tw in ("none", "deresiewicz"):
        r = impact3d(sc.replace(twist=tw), 1.0, (0.5, 0.0), (0.0, 0.0, 2000.0), series=True)
        s = r.series
        ang = np.degrees(np.arctan2(s["tangential_force_y"], s["tangential_force_x"]))
        axs[1].plot(s["t"] * 1e6, s["spin_z"], label=f"spin about the normal, {tw}")
        obl[tw] = {"spin_r": r.spin_r, "vt_r": r.vt_r, "out_of_plane_angle_deg": r.out_of_plane_angle_deg,
                   "force_angle_deg_at_end": float(ang[len(ang) // 2]), "energy_error": r.energy.error / r.energy.initial}
    axs[1].set_xlabel("t [us]")
    axs[1].set_ylabel("w_z [rad/s]")
    axs[1].set_title("oblique impact, vt 0.5 m/s, vn 1 m/s, w_z 2000 rad/s")
    axs[1].legend(fontsize=7)
    out["oblique"] = obl
    fig.tight_layout()
    fig.savefig(HERE / "horak.png", dpi=120)
    (HERE / "horak.json").write_text(json.dumps(out, indent=1, default=float))
    print(json.dumps(out, indent=1, default=float))


def comparison(out):
    """Relative differences of the laws from the BEM, (law - BEM) / BEM, per vn: rows at Psi and the largest
    |difference| of each law over the BEM's Psi."""
    res = {}
    keys = {"deresiewicz": "lost", "deresiewicz 256 cells": "lost deresiewicz 256 cells",
            **{k.split()[0]: f"lost {k}" for k in ("marshall", "sds (Hertz values at F_max)")}}
    for run in out["runs"]:
        bem = [x for x in run["rows"] if "lost_bem" in x]
        rel = {name: [x[k] / x["lost_bem"] - 1 for x in bem] for name, k in keys.items()}
        res[str(run["vn"])] = {"Psi": [x["Psi"] for x in bem], "relative_difference": rel,
                               "max_abs_relative_difference": {k: max(map(abs, v)) for k, v in rel.items()}}
    return res


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--convergence", action="store_true",
                    help="refine the BEM at Psi = 0.01, 1, 100 (vn = 2 m/s) instead; writes horak_bem_convergence.json")
    ap.add_argument("--bem-n", type=int, default=BEM_N,
                    help=f"BEM elements across the largest contact, even ({BEM_N}; half as many too, for the extrapolation)")
    ap.add_argument("--bem-steps", type=int, default=BEM_STEPS,
                    help=f"BEM steps per contact, even ({BEM_STEPS}; half as many too, for the extrapolation)")
    args = ap.parse_args()
    if args.bem_steps % 2 or args.bem_steps < 8:
        ap.error(f"--bem-steps {args.bem_steps} must be an even integer >= 8")
    if args.bem_n % 2 or not 8 <= args.bem_n <= 1024:
        ap.error(f"--bem-n {args.bem_n} must be an even integer in [8, 1024]")
    if args.convergence:
        if (args.bem_n, args.bem_steps) != (BEM_N, BEM_STEPS):
            ap.error("--convergence runs its own grids and steps: give it without --bem-n and --bem-steps")
        convergence()
    else:
        main(args.bem_n, args.bem_steps)
