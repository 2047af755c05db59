"""Twist with shear from one local state (dem_contact.laws.twist_shear) under a varying normal force: against the
boundary-element reference with twist, and the energy of closed loops in (overlap, ux, uy, twist).

Steel sphere R = 10 mm on a steel wall, mu = 0.3; the overlap varies about delta_0 = 1e-5 m (units: the slip
displacement s = 3 mu N_0 / (16 G* a_0) and the twist beta_1 = 3 mu N_0 / (16 G_c a_0^2) at delta_0). Paths
(400 steps after the first row, the loaded contact at rest):

- "shear twist load unload": along x to 0.6 s, a twist to beta_1, the overlap loaded to 2 delta_0 at fixed
  displacement and twist, the twist back to 0, then unloaded to 0.7 delta_0 while shearing back to -0.3 s
  (80 steps each);
- "circle twist, overlap 40%": the circle of radius 0.4 s through the origin with the twist 0.4 beta_1
  sin 2 phi (the named path circle-twist 0.4) while the overlap oscillates delta_0 (1 + 0.4 sin 3 phi);
- "random smooth with overlap": three harmonics in ux, uy, beta (as run_twist_shear.py's random smooth
  path, another seed) and the overlap delta_0 exp(0.35 sin-cosine harmonics).

Compared (max over the rows of |T - T_BEM| / (mu N) and |M - M_BEM| / (mu N a), N and a the Hertz values of
each row): the coupled law (``studies.paths.coupled_path``: 32 cells, 8 points) with both slip levers and
the three residual rules, and the separate laws (the 3D kernel of the default tangential law mdr_adaptive
with the twist law deresiewicz, ``studies.paths.run_path``). The BEM (64 elements across the largest
contact, 400 steps; ``reference.bem.bem_path``) is stored in bem_extra/<label>_n64_s400.csv, and on the
first path at 96 across (its grid error); --bem recomputes them (about 45 s).

Energy: 200 random histories in (delta, ux, uy, beta), each followed by a closed loop (two harmonics per
coordinate); the loop's work (T . du + M d beta; the Hertz normal force is conservative and the loop closes
the overlap) and its dissipation, the work less the change of the stored energy of the force and moment
modes (``twist_shear_path(stored=True)``), and the least dissipation of one step of the loops (the work of
a step by the trapezoidal rule, which under-counts a step that turns from stick to slip); for
the coupled law and for the separate laws on the same cells (the coupled law run on the shear alone plus
on the twist alone: its exact reductions to the vector MDR and deresiewicz cells).

Diagnostics (``diagnostic_paths``, BEM stored the same way): the circle's shear alone and twist alone (the law
is there the exact laws' cells: their own error), the random path at a constant overlap, and a slide with
spin into full slip that then unloads and reloads; and |T| at the corners of the first path.

Writes validation/twist/twist_shear_varying.json and twist_shear_varying.png.

    python validation/twist/run_twist_shear_varying.py [--bem]
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

from dem_contact.laws.twist.deresiewicz import twist_modulus  # noqa: E402
from dem_contact.laws.twist_shear import RESIDUAL_RULES, SLIP_LEVERS, twist_shear_path  # noqa: E402
from dem_contact.materials import STEEL  # noqa: E402
from dem_contact.studies.chart3d import chart_scene, read_twist_reference, twist_scene  # noqa: E402
from dem_contact.studies.paths import coupled_path, run_path  # noqa: E402

HERE = pathlib.Path(__file__).parent
EXTRA = HERE / "bem_extra"
MU, R, DELTA = 0.3, 0.01, 1e-5
E, NU = STEEL.E, STEEL.nu
G = E / (2 * (1 + NU))
G_STAR = G / (2 * (2 - NU))              # 1/G* = (2 - nu1)/G1 + (2 - nu2)/G2
G_C = G / 2                              # 1/G_c = 1/G1 + 1/G2
E_STAR = E / (2 * (1 - NU**2))
A0 = math.sqrt(R * DELTA)
N0 = 4 / 3 * E_STAR * math.sqrt(R) * DELTA**1.5
SLIP = 3 * MU * N0 / (16 * G_STAR * A0)
BETA1 = 3 * MU * N0 / (16 * G_C * A0 * A0)
STEPS = 400
SEPARATE = "separate laws (mdr_adaptive 16 cells + deresiewicz 32 cells, 3D kernel)"


def hertz(delta):
    """(N, a) of the overlaps (Johnson 1985, eq. 4.23)."""
    d = np.maximum(delta, 0.0)
    return 4 / 3 * E_STAR * math.sqrt(R) * d**1.5, np.sqrt(R * d)


def paths():
    """label -> (delta, ux, uy, beta) [m, m, m, rad], STEPS + 1 rows, the first the loaded contact at rest."""
    q = STEPS // 5
    k = np.linspace(0.0, 1.0, q + 1)[1:]
    c = lambda v: np.full(q, float(v))  # noqa: E731
    d = np.concatenate([[1.0], c(1), c(1), 1 + k, c(2), 2 - 1.3 * k])
    x = np.concatenate([[0.0], 0.6 * k, c(0.6), c(0.6), c(0.6), 0.6 - 0.9 * k])
    b = np.concatenate([[0.0], c(0), k, c(1), 1 - k, c(0)])
    out = {"shear twist load unload": (DELTA * d, SLIP * x, 0 * x, BETA1 * b)}
    phi = np.linspace(0.0, 2 * np.pi, STEPS + 1)
    out["circle twist, overlap 40%"] = (DELTA * (1 + 0.4 * np.sin(3 * phi)), 0.4 * SLIP * (1 - np.cos(phi)),
                                        0.4 * SLIP * np.sin(phi), 0.4 * BETA1 * np.sin(2 * phi))
    rng = np.random.default_rng(12)
    cols = []
    for _ in range(4):
        h = rng.normal(0, 0.5, (3, 2))
        cols.append(sum(h[j, 0] * np.sin((j + 1) * phi) + h[j, 1] * (1 - np.cos((j + 1) * phi)) for j in range(3)))
    lnd = 0.35 * cols[3] / np.abs(cols[3]).max()
    out["random smooth with overlap"] = (DELTA * np.exp(lnd), SLIP * cols[0], SLIP * cols[1], BETA1 * cols[2])
    return out


def diagnostic_paths():
    """label -> (delta, ux, uy, beta) of the paths that separate the error's parts: the circle's shear alone and
    twist alone (where the law is the exact laws' cells), the random path at a constant overlap, and a slide
    with spin (2 s and 2 beta_1 per 100 steps) into full slip, then unloaded to 0.6 delta_0 and reloaded to
    1.2 delta_0 while it goes on (100 steps each)."""
    P = paths()
    d, ux, uy, tw = P["circle twist, overlap 40%"]
    out = {"circle twist, overlap 40%, shear alone": (d, ux, uy, 0 * tw),
           "circle twist, overlap 40%, twist alone": (d, 0 * ux, 0 * uy, tw)}
    d, ux, uy, tw = P["random smooth with overlap"]
    out["random smooth, constant overlap"] = (0 * d + DELTA, ux, uy, tw)
    k = np.linspace(0.0, 1.0, 101)[1:]
    x = np.concatenate([[0.0], 2 * k, 2 + k, 3 + k])
    d = np.concatenate([[1.0], 1 + 0 * k, 1 - 0.4 * k, 0.6 + 0.6 * k])
    out["slide and spin, unload, reload"] = (DELTA * d, SLIP * x, 0 * x, BETA1 * x)
    return out


def csv_name(label, n_across, steps=STEPS):
    return EXTRA / f"{label.replace(' ', '_').replace(',', '').replace('%', 'pct')}_n{n_across}_s{steps}.csv"


def run_bem():
    """The BEM along ``paths`` and ``diagnostic_paths`` at 64 across, and the first path at 96 across, written
    as CSV."""
    from dem_contact.reference.bem import bem_path
    EXTRA.mkdir(exist_ok=True)
    every = {**paths(), **diagnostic_paths()}
    jobs = [(label, 64) for label in every] + [(next(iter(paths())), 96)]
    for label, n in jobs:
        d, ux, uy, tw = every[label]
        t0 = time.time()
        Nr, Txr, Tyr, Mzr = bem_path(E, NU, E, NU, R, MU, d, ux, uy, tw, n_across=n)
        print(f"{label}, {n} across: BEM {time.time() - t0:.1f} s", flush=True)
        np.savetxt(csv_name(label, n, d.size - 1), np.column_stack([d, ux, uy, tw, Nr, Txr, Tyr, Mzr]),
                   delimiter=",", fmt="%.12e", header="delta,ux,uy,twist,N,Tx,Ty,Mz", comments="")


def coupled(d, ux, uy, tw, lever="rings", residual="scaled", cells=32, sectors=8):
    """(Tx, Ty, Mz) on body 1 of the coupled law along the path (as ``coupled_path``: from rest out of contact,
    the Hertz N and a of each row)."""
    N, a = hertz(d)
    z = np.zeros(1)
    Tx, Ty, M, _ = twist_shear_path(G_STAR, G_C, MU, R, np.r_[z, N], np.r_[z, a], np.r_[z, ux], np.r_[z, uy],
                                    np.r_[z, tw], cells=cells, sectors=sectors, slip_lever=lever, residual=residual)
    return Tx[1:], Ty[1:], M[1:]


def separate(d, ux, uy, tw):
    """(Tx, Ty, Mz) on body 1 of the 3D kernel: mdr_adaptive (16 cells) and deresiewicz (32 cells)."""
    return run_path(twist_scene("deresiewicz", float(d.max())), d, ux, uy, tw)[1:]


def errors(d, T, ref):
    """(max |T - T_BEM| / (mu N), max |M - M_BEM| / (mu N a)), N and a of each row."""
    N, a = hertz(d)
    Tx, Ty, M = T
    _, Txr, Tyr, Mzr = ref
    return (round(float(np.max(np.hypot(Tx - Txr, Ty - Tyr) / (MU * N))), 4),
            round(float(np.max(np.abs(M - Mzr) / (MU * N * a))), 4))


def bem_comparison():
    refs = {label: read_twist_reference(csv_name(label, 64)) for label in paths()}
    for label, ((d, ux, uy, tw), _) in refs.items():
        assert all(np.allclose(p, q, rtol=1e-9, atol=1e-20) for p, q in zip((d, ux, uy, tw), paths()[label]))
    forms = {f"coupled, {lever}, residual {rule}": (lambda *p, lever=lever, rule=rule: coupled(*p, lever, rule))
             for lever in SLIP_LEVERS[::-1] for rule in RESIDUAL_RULES}
    forms[SEPARATE] = separate
    table, curves = {}, {}
    for name, fn in forms.items():
        row = {}
        for label, (p, ref) in refs.items():
            T = fn(*p)
            row[label] = errors(p[0], T, ref)
            curves[(name, label)] = T
        table[name] = row
        print(name, row, flush=True)
    sc = chart_scene()
    for label, (p, _) in refs.items():    # the command's function is the law of the table's default row
        _, Tx, Ty, Mz = coupled_path(sc, *p)
        assert np.allclose(np.array([Tx, Ty, Mz]), np.array(curves[("coupled, rings, residual scaled", label)]),
                           rtol=1e-12, atol=1e-12 * MU * N0 * A0)
    first = next(iter(paths()))
    (d, *_), fine = read_twist_reference(csv_name(first, 96))
    grid = {f"{first}: BEM 64 against 96 across": errors(d, fine[1:], refs[first][1])}
    return table, grid, refs, curves


def loop_paths(count=200, seed=5, pre_n=40):
    """(N, a, ux, uy, beta, amplitude) of the random histories and closed loops (module docstring): pre_n rows
    of history, then a loop of 80 steps."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 2 * np.pi, 81)
    out = []
    for _ in range(count):
        pre = np.cumsum(rng.normal(0, 0.4, (pre_n, 4)), axis=0)
        pre[0] = 0.0
        pre[:, 0] = np.clip(0.4 * pre[:, 0], -0.7, 0.7)          # ln(delta / delta_0)
        amp = 10 ** rng.uniform(-2.5, 0.3)
        loop = np.zeros((t.size, 4))
        for h in (1, 2):
            c = rng.normal(0, 0.8, (2, 4)) * amp / h
            c[:, 0] *= 0.5
            loop += np.outer(np.sin(h * t), c[0]) + np.outer(1 - np.cos(h * t), c[1])
        p = np.vstack([pre, pre[-1] + loop[1:]])
        N, a = hertz(DELTA * np.exp(p[:, 0]))
        out.append((N, a, SLIP * p[:, 1], SLIP * p[:, 2], BETA1 * p[:, 3], amp))
    return out


def work_and_energy(form, N, a, ux, uy, tw, cells=32):
    """(work, stored energy) per row of the coupled law (form = (lever, residual rule)) or of the separate laws
    on the same cells (form = ("separate", None): the law on the shear alone plus on the twist alone)."""
    if form[0] == "separate":
        z = 0 * ux
        s1 = twist_shear_path(G_STAR, G_C, MU, R, N, a, ux, uy, z, cells=cells, stored=True)
        s2 = twist_shear_path(G_STAR, G_C, MU, R, N, a, z, z, tw, cells=cells, stored=True)
        return s1[3] + s2[3], s1[4] + s2[4]
    return twist_shear_path(G_STAR, G_C, MU, R, N, a, ux, uy, tw, cells=cells, slip_lever=form[0],
                            residual=form[1], stored=True)[3:]


def loops(count=200, pre_n=40):
    """Closed loops under a varying overlap after random histories (module docstring); and, on the loop with
    the least step dissipation of the default law, that least step dissipation with 32 and 128 cells, for the
    shear alone, the twist alone and both."""
    forms = [(lever, rule) for lever in SLIP_LEVERS[::-1] for rule in RESIDUAL_RULES] + [("separate", None)]
    stats = {f: {"negative loop work": 0, "negative loop dissipation": 0, "least loop work": math.inf,
                 "least loop dissipation": math.inf, "least step dissipation in a loop": math.inf} for f in forms}
    cases = loop_paths(count, pre_n=pre_n)
    worst = (math.inf, 0)
    for j, (N, a, ux, uy, tw, amp) in enumerate(cases):
        scale = MU * N0 * SLIP * amp
        for f in forms:
            W, En = work_and_energy(f, N, a, ux, uy, tw)
            i = pre_n - 1
            wl = (W[-1] - W[i]) / scale
            dl = (W[-1] - W[i] - En[-1] + En[i]) / scale
            step = float((np.diff(W - En)[i:] / (MU * N0 * SLIP)).min())         # the loop's steps
            s = stats[f]
            s["negative loop work"] += int(wl < 0)
            s["negative loop dissipation"] += int(dl < 0)
            s["least loop work"] = min(s["least loop work"], wl)
            s["least loop dissipation"] = min(s["least loop dissipation"], dl)
            s["least step dissipation in a loop"] = min(s["least step dissipation in a loop"], step)
            if f == ("rings", "scaled"):
                worst = min(worst, (step, j))
    out = {}
    for f, s in stats.items():
        name = "separate laws (the same cells)" if f[0] == "separate" else f"coupled, {f[0]}, residual {f[1]}"
        out[name] = {k: (v if isinstance(v, int) else float(f"{v:.3g}")) for k, v in s.items()}
        print(name, out[name], flush=True)
    N, a, ux, uy, tw, amp = cases[worst[1]]
    z = 0 * ux
    cells = {}
    for label, args in (("shear alone", (ux, uy, z)), ("twist alone", (z, z, tw)), ("shear and twist", (ux, uy, tw))):
        for n in (32, 128):
            W, En = work_and_energy(("rings", "scaled"), N, a, *args, cells=n)
            cells[f"{label}, {n} cells"] = float(f"{(np.diff(W - En)[pre_n - 1:] / (MU * N0 * SLIP)).min():.3g}")
    print(cells, flush=True)
    return {"loops": count, "units": "loop work and dissipation in mu N_0 s times the loop's amplitude; step "
            "dissipation in mu N_0 s", "by formulation": out,
            f"least step dissipation of loop {worst[1]} (the default law's least) by cells": cells}


def diagnostics(curves):
    """The parts of the error (``diagnostic_paths``), and |T| / (mu N) at the corners of the first path."""
    out = {}
    for label, p in diagnostic_paths().items():
        (d, *_), ref = read_twist_reference(csv_name(label, 64, p[0].size - 1))
        assert np.allclose(d, p[0], rtol=1e-9)
        out[f"{label}: default law (rings, scaled)"] = errors(d, coupled(*p), ref)
        out[f"{label}: separate laws"] = errors(d, separate(*p), ref)
        if label.startswith("slide"):
            N, a = hertz(d)
            rows = {}
            for form, T in (("BEM", ref[1:]), ("default law", coupled(*p)),
                            ("limits lever", coupled(*p, "limits"))):
                rows[form] = [[round(float(-T[0][i] / (MU * N[i])), 3), round(float(-T[2][i] / (MU * N[i] * a[i])), 3)]
                              for i in (100, 200, 300)]
            out[f"{label}: (T / (mu N), M / (mu N a)) at rows 100 (full slip), 200 (unloaded to 0.6), 300 "
                "(reloaded to 1.2)"] = rows
    first = next(iter(paths()))
    (d, *_), ref = read_twist_reference(csv_name(first, 64))
    N = hertz(d)[0]
    corners = {"BEM": ref[1:3]}
    for name, tag in (("coupled, rings, residual scaled", "default law"), (SEPARATE, "separate laws")):
        corners[tag] = curves[(name, first)][:2]
    out[f"{first}: |T| / (mu N) at rows 80 (sheared), 160 (twisted), 240 (loaded), 320 (twisted back)"] = {
        k: [round(float(np.hypot(Tx[i], Ty[i]) / (MU * N[i])), 3) for i in (80, 160, 240, 320)]
        for k, (Tx, Ty) in corners.items()}
    for k, v in out.items():
        print(k, v, flush=True)
    return out


def figure(refs, curves):
    fig, axs = plt.subplots(1, len(refs), figsize=(5 * len(refs), 4.2))
    for ax, (label, ((d, *_), ref)) in zip(axs, refs.items()):
        N, a = hertz(d)
        k = np.arange(d.size)
        ax.plot(k, np.hypot(ref[1], ref[2]) / (MU * N0), "k-", lw=2.5, label="|T| BEM 64 across")
        ax.plot(k, -ref[3] / (MU * N0 * A0), "b-", lw=2.5, alpha=0.5, label="M BEM")
        for name, color, ls, tag in (("coupled, rings, residual scaled", "r", "--", "coupled rings"),
                                     ("coupled, limits, residual scaled", "g", ":", "coupled limits"),
                                     (SEPARATE, "tab:orange", "-.", "separate")):
            Tx, Ty, M = curves[(name, label)]
            ax.plot(k, np.hypot(Tx, Ty) / (MU * N0), color=color, ls=ls, label=f"|T| {tag}")
            ax.plot(k, -M / (MU * N0 * A0), color=color, ls=ls, alpha=0.6, label=f"M {tag}")
        ax.plot(k, d / DELTA, color="0.6", lw=1, label="delta / delta_0")
        ax.set_xlabel("row")
        ax.set_ylabel("|T| / (mu N_0), M / (mu N_0 a_0), delta / delta_0")
        ax.set_title(label)
        ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(HERE / "twist_shear_varying.png", dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bem", action="store_true", help="recompute the BEM histories (bem_extra/*.csv) first")
    args = ap.parse_args()
    every = {**paths(), **diagnostic_paths()}
    if args.bem or not all(csv_name(label, 64, p[0].size - 1).exists() for label, p in every.items()):
        run_bem()
    table, grid, refs, curves = bem_comparison()
    out = {"scene": {"pair": "steel sphere R 10 mm on a steel wall", "mu": MU, "delta_0": DELTA, "N_0": N0,
                     "a_0": A0, "G_star": G_STAR, "G_c": float(twist_modulus(chart_scene().sphere,
                                                                             chart_scene().body2))},
           "BEM 64 across, max error (force / (mu N), moment / (mu N a)), N and a of each row": table,
           "BEM grid error (same units)": grid,
           "parts of the error (same units)": diagnostics(curves),
           "closed loops under a varying overlap": loops()}
    (HERE / "twist_shear_varying.json").write_text(json.dumps(out, indent=1))
    print(json.dumps(out, indent=1))
    figure(refs, curves)


if __name__ == "__main__":
    main()
