"""Twist with shear from one local state (dem_contact.laws.twist_shear) against the boundary-element reference
with twist, the full-slip limit surface of the Hertz disc, and closed loops.

Writes validation/twist/twist_shear.json and twist_shear.png:

- the errors on the stored BEM histories of the twist paths (``reference.paths.TWIST_SET``, 128 elements
  across, 400 steps, ``validation/bem/paths``; steel sphere R = 10 mm on a steel wall, overlap 1e-5 m,
  mu = 0.3): max |T - T_BEM| / (mu N) and max |M - M_BEM| / (mu N a), by cells and points per ring, and the
  spread over the orientation of the points (the path turned by psi, the forces turned back);
- full slip under a steady sliding and spin (v, w): the law's (T, M) after a long drive against the exact
  limit surface of the Hertz disc, F = mu int p t dA, M = mu int p (r x t) dA with t the unit sliding
  direction of the rigid motion (numerical quadrature on a polar grid);
- the work of random closed loops in (ux, uy, beta) after random histories at constant N;
- both slip levers of the law, the separate laws (``separate_path``) and the simpler formulations tried
  first (``candidate_path``): one state per cell, (x, z) = (u / u_max, theta / theta_max), with a combined
  limit |x|^q + |z|^q <= 1 (q = 1: the largest traction around the ring, |q_t| + |q_theta| <= mu p; q = 2:
  its mean square) or the limit curve of a ring sliding under translation and spin, each with the radial
  return in (x, z) or the closest point in the cell's energy norm (associated flow), 128 cells, on every
  reference path;
- with --bem-extra, first the BEM (64 elements across, 400 steps, about 25 s in all) on paths that the law
  was not built on, written to bem_extra/<label>_n64_s400.csv and then compared like the others: a twist to
  beta_1 then a shear cycle at that twist, sliding with spin into combined full slip at two ratios, and a
  random smooth path in (ux, uy, beta).

    python validation/twist/run_twist_shear.py [--bem-extra]
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

from dem_contact.laws.twist_shear import cell_width, limits, twist_shear_path  # noqa: E402
from dem_contact.materials import STEEL  # noqa: E402
from dem_contact.reference.paths import TWIST_SET  # noqa: E402
from dem_contact.studies.chart3d import read_twist_reference  # noqa: E402

HERE = pathlib.Path(__file__).parent
PATHS = HERE.parent / "bem" / "paths"
MU, R, DELTA = 0.3, 0.01, 1e-5
E, NU = STEEL.E, STEEL.nu
G = E / (2 * (1 + NU))
G_STAR = G / (2 * (2 - NU))              # 1/G* = (2 - nu1)/G1 + (2 - nu2)/G2
G_C = G / 2
E_STAR = E / (2 * (1 - NU**2))
A = math.sqrt(R * DELTA)
N = 4 / 3 * E_STAR * math.sqrt(R) * DELTA**1.5


def law(ux, uy, tw, cells, sectors, psi=0.0, lever="limits"):
    """The law's resistance (minus the force and moment on body 1) along the path turned by psi; forces turned
    back."""
    c, s = math.cos(psi), math.sin(psi)
    Tx, Ty, M, W = twist_shear_path(G_STAR, G_C, MU, R, N, A, c * ux - s * uy, s * ux + c * uy, tw,
                                    cells=cells, sectors=sectors, slip_lever=lever)
    return -(c * Tx + s * Ty), s * Tx - c * Ty, -M, W


def bem_errors(lever="limits"):
    out = {}
    curves = {}
    for shape, size in TWIST_SET:
        (d, ux, uy, tw), (Nr, Txr, Tyr, Mzr) = read_twist_reference(PATHS / f"{shape}_{size:g}_n128_s400.csv")
        assert np.allclose(d, DELTA) and np.allclose(Nr[1:], N, rtol=1e-9)
        label = f"{shape} {size:g}"
        rows = {}
        for cells in (16, 32, 64):
            for sectors in (4, 8):
                errs = []
                for psi in np.linspace(0.0, 2 * math.pi / sectors, 5)[:-1]:
                    Tx, Ty, M, _ = law(ux, uy, tw, cells, sectors, psi, lever)
                    fe = float(np.max(np.hypot(-Tx - Txr, -Ty - Tyr)[1:]) / (MU * N))
                    me = float(np.max(np.abs(-M - Mzr)[1:]) / (MU * N * A))
                    errs.append((fe, me))
                    if psi == 0.0 and cells == 32 and sectors == 8:
                        curves[label] = (tw, ux, uy, Txr, Tyr, Mzr, Tx, Ty, M)
                e = np.array(errs)
                rows[f"{cells} cells, {sectors} points"] = {
                    "force": errs[0][0], "moment": errs[0][1],
                    "force, worst orientation": float(e[:, 0].max()), "moment, worst orientation": float(e[:, 1].max())}
        out[label] = rows
    return out, curves


def disc_limit_surface(angles):
    """Exact (F / (mu N), M / (mu N a)) of the Hertz disc sliding with (v, w a) = (cos t, sin t)."""
    nr, nt = 400, 720
    r = (np.arange(nr) + 0.5) / nr * A
    th = (np.arange(nt) + 0.5) / nt * 2 * np.pi
    rr, tt = np.meshgrid(r, th, indexing="ij")
    x, y = rr * np.cos(tt), rr * np.sin(tt)
    p = 3 * N / (2 * np.pi * A * A) * np.sqrt(1 - (rr / A) ** 2)
    dA = rr * (A / nr) * (2 * np.pi / nt)
    out = []
    for t in angles:
        v, w = math.cos(t), math.sin(t) / A
        vx, vy = v - w * y, w * x
        m = np.hypot(vx, vy)
        out.append(((p * vx / m * dA).sum() / N, (p * (x * vy - y * vx) / m * dA).sum() / (N * A)))
    return np.array(out)


def ray_deviation(law_pts, exact_pts):
    """The law's full-slip points: their distance from the origin over that of the exact surface along the
    same ray, less 1, in the plane (T / (mu N), M / ((3 pi/16) mu N a))."""
    full = 3 * math.pi / 16
    ex = exact_pts / [1.0, full]
    lw = law_pts / [1.0, full]
    ang_e = np.arctan2(ex[:, 1], ex[:, 0])
    order = np.argsort(ang_e)
    r_e = np.interp(np.arctan2(lw[:, 1], lw[:, 0]), ang_e[order], np.hypot(ex[:, 0], ex[:, 1])[order])
    return np.hypot(lw[:, 0], lw[:, 1]) / r_e - 1.0


def law_limit_surface(angles, cells=32, sectors=8, steps=400, lever="limits"):
    """The law after a drive of 40 slip lengths at (v, w a) = (cos t, sin t)."""
    s = 3 * MU * N / (16 * G_STAR * A)       # the slip displacement of Mindlin's full slip
    b1 = 3 * MU * N / (16 * G_C * A * A)
    out = []
    for t in angles:
        k = np.linspace(0.0, 1.0, steps + 1)
        L = 40 * max(s, b1 * A)
        Tx, Ty, M, _ = twist_shear_path(G_STAR, G_C, MU, R, N, A, L * math.cos(t) * k, 0 * k, L * math.sin(t) * k / A,
                                        cells=cells, sectors=sectors, slip_lever=lever)
        out.append((-Tx[-1] / (MU * N), -M[-1] / (MU * N * A)))     # the resistance
    return np.array(out)


def loops(count=200, seed=1, cells=32, sectors=8, lever="limits"):
    """Random histories, then a closed loop (two harmonics in ux, uy, beta, amplitude 10^-2.5 ... 2 slip
    lengths); the loop's work in mu N s times the amplitude."""
    rng = np.random.default_rng(seed)
    s = 3 * MU * N / (16 * G_STAR * A)
    b1 = 3 * MU * N / (16 * G_C * A * A)
    works = []
    for _ in range(count):
        pre = np.cumsum(rng.normal(0, 0.4, (40, 3)), axis=0)
        pre[0] = 0.0
        amp = 10 ** rng.uniform(-2.5, 0.3)
        t = np.linspace(0, 2 * np.pi, 81)
        loop = np.zeros((81, 3))
        for h in (1, 2):
            c = rng.normal(0, 0.8, (2, 3)) * amp / h
            loop += np.outer(np.sin(h * t), c[0]) + np.outer(1 - np.cos(h * t), c[1])
        path = np.vstack([pre, pre[-1] + loop[1:]])
        Tx, Ty, M, W = twist_shear_path(G_STAR, G_C, MU, R, N, A, s * path[:, 0], s * path[:, 1], b1 * path[:, 2],
                                        cells=cells, sectors=sectors, slip_lever=lever)
        works.append((W[-1] - W[39]) / (MU * N * s * amp))
    w = np.array(works)
    return {"loops": count, "negative work": int((w < 0).sum()), "least loop work / (mu N s amplitude)": float(w.min())}


def limit_curve(kind, points=4001):
    """Points (|x|, |z|) of a combined limit, from (1, 0) to (0, 1): ``q<q>`` the curve |x|^q + |z|^q = 1;
    ``ring``: force and moment of a ring of unit radius and unit capacity sliding under (v, w), in units of
    their separate limits."""
    t = np.linspace(0, np.pi / 2, points)
    if kind == "ring":
        ph = (np.arange(2000) + 0.5) * np.pi / 1000
        c, s = np.cos(ph), np.sin(ph)
        out = []
        for v, w in zip(np.cos(t), np.sin(t)):
            vx, vy = v - w * s, w * c
            m = np.hypot(vx, vy)
            out.append((np.mean(vx / m), np.mean((c * vy - s * vx) / m)))
        return np.array(out)
    q = float(kind[1:])
    return np.stack([np.cos(t) ** (2 / q), np.sin(t) ** (2 / q)], axis=1)


def candidate_path(kind, rule, ux, uy, tw, cells=128):
    """One state (x, z) per cell with the combined limit ``kind`` and the return ``rule`` (``radial`` or
    ``energy``); returns (Tx, Ty, M)."""
    ds = cell_width(A, cells, R)
    l, w, umax, tmax = limits(G_STAR, G_C, MU, N, A, ds, cells)
    on = l > 0
    umax, tmax, l, w = umax[on], tmax[on], l[on], w[on]
    Ae, Be = 4 * G_STAR * l * umax**2, 8 * G_C * w * tmax**2     # the cell's energy at each separate limit
    C = limit_curve(kind)
    ang = np.arctan2(C[:, 1], C[:, 0])
    rad = np.hypot(C[:, 0], C[:, 1])
    x = np.zeros((umax.size, 2))
    z = np.zeros(umax.size)
    T, M = np.zeros((ux.size, 2)), np.zeros(ux.size)
    for t in range(1, ux.size):
        x += np.array([ux[t] - ux[t - 1], uy[t] - uy[t - 1]])[None, :] / umax[:, None]
        z += (tw[t] - tw[t - 1]) / tmax
        r = np.hypot(x[:, 0], x[:, 1])
        az = np.abs(z)
        out = np.hypot(r, az) > np.interp(np.arctan2(az, r), ang, rad)
        if out.any():
            rn, zn = r.copy(), az.copy()
            if rule == "radial":
                f = np.interp(np.arctan2(az[out], r[out]), ang, rad) / np.hypot(r[out], az[out])
                rn[out], zn[out] = r[out] * f, az[out] * f
            else:
                k = (Ae[out, None] * (C[None, :, 0] - r[out, None]) ** 2
                     + Be[out, None] * (C[None, :, 1] - az[out, None]) ** 2).argmin(axis=1)
                rn[out], zn[out] = C[k, 0], C[k, 1]
            x *= np.where(r > 0, rn / np.where(r > 0, r, 1.0), 0.0)[:, None]
            z = np.sign(z) * zn
        T[t] = 8 * G_STAR * (x * (umax * l)[:, None]).sum(axis=0)
        M[t] = 16 * G_C * (z * tmax * w).sum()
    return T[:, 0], T[:, 1], M


def extra_paths(steps=400):
    """label -> (ux, uy, beta) [m, m, rad] of the paths of --bem-extra (first row: rest)."""
    s = 3 * MU * N / (16 * G_STAR * A)
    b1 = 3 * MU * N / (16 * G_C * A * A)
    q = steps // 4
    k = np.linspace(0.0, 1.0, q + 1)[1:]
    ux = np.concatenate([[0.0], 0 * k, 0.8 * k, 0.8 - 1.6 * np.linspace(0, 1, 2 * q + 1)[1:]])
    tw = np.concatenate([[0.0], k, np.ones(3 * q)])
    out = {"twist 1 then shear cycle 0.8": (s * ux, 0 * ux, b1 * tw)}
    k = np.linspace(0.0, 1.0, steps + 1)
    out["slide 2 with spin 2"] = (2 * s * k, 0 * k, 2 * b1 * k)
    out["slide 2 with spin 4"] = (2 * s * k, 0 * k, 4 * b1 * k)
    rng = np.random.default_rng(11)
    t = 2 * np.pi * k
    cols = []
    for _ in range(3):
        c = rng.normal(0, 0.5, (3, 2))
        cols.append(sum(c[h, 0] * np.sin((h + 1) * t) + c[h, 1] * (1 - np.cos((h + 1) * t)) for h in range(3)))
    out["random smooth"] = (s * cols[0], s * cols[1], b1 * cols[2])
    return out


EXTRA = HERE / "bem_extra"


def bem_extra(n_across=64):
    """The BEM along ``extra_paths``, written to bem_extra/<label>_n64_s400.csv (the columns of the stored
    twist references)."""
    from dem_contact.reference.bem import bem_path
    EXTRA.mkdir(exist_ok=True)
    for label, (ux, uy, tw) in extra_paths().items():
        t0 = time.time()
        d = np.full(ux.size, DELTA)
        Nr, Txr, Tyr, Mzr = bem_path(E, NU, E, NU, R, MU, d, ux, uy, tw, n_across=n_across)
        print(f"{label}: BEM {time.time() - t0:.1f} s", flush=True)
        np.savetxt(EXTRA / f"{label.replace(' ', '_')}_n{n_across}_s400.csv",
                   np.column_stack([d, ux, uy, tw, Nr, Txr, Tyr, Mzr]), delimiter=",", fmt="%.12e",
                   header="delta,ux,uy,twist,N,Tx,Ty,Mz", comments="")


def all_references():
    """label -> (ux, uy, beta, Tx, Ty, Mz) of the stored twist paths (128 across) and, where written, the
    paths of --bem-extra (64 across)."""
    out = {}
    for shape, size in TWIST_SET:
        (d, ux, uy, tw), (Nr, Txr, Tyr, Mzr) = read_twist_reference(PATHS / f"{shape}_{size:g}_n128_s400.csv")
        out[f"{shape} {size:g}"] = (ux, uy, tw, Txr, Tyr, Mzr)
    for label in extra_paths():
        f = EXTRA / f"{label.replace(' ', '_')}_n64_s400.csv"
        if f.exists():
            (d, ux, uy, tw), (Nr, Txr, Tyr, Mzr) = read_twist_reference(f)
            out[label + " (64 across)"] = (ux, uy, tw, Txr, Tyr, Mzr)
    return out


def separate_path(ux, uy, tw, cells=32):
    """The separate laws on the same cells: each cell's u returned to |u| <= u_max and theta to |theta| <=
    theta_max on its own (the vector MDR law and deresiewicz); returns (Tx, Ty, M)."""
    ds = cell_width(A, cells, R)
    l, w, umax, tmax = limits(G_STAR, G_C, MU, N, A, ds, cells)
    u, th = np.zeros((cells, 2)), np.zeros(cells)
    T, M = np.zeros((ux.size, 2)), np.zeros(ux.size)
    for t in range(1, ux.size):
        u += np.array([ux[t] - ux[t - 1], uy[t] - uy[t - 1]])[None, :]
        m = np.hypot(u[:, 0], u[:, 1])
        u *= np.where(m > umax, umax / np.where(m > 0, m, 1.0), 1.0)[:, None]
        th = np.clip(th + tw[t] - tw[t - 1], -tmax, tmax)
        T[t] = 8 * G_STAR * (u * l[:, None]).sum(axis=0)
        M[t] = 16 * G_C * (th * w).sum()
    return T[:, 0], T[:, 1], M


def formulations():
    """BEM errors [force / (mu N), moment / (mu N a)] of the law, the separate laws and the one-state-per-cell
    formulations on every reference path."""
    refs = all_references()
    forms = {"twist_shear limits, 32 cells, 4 points": lambda *p: law(*p, 32, 4)[:3],
             "twist_shear limits, 32 cells, 8 points": lambda *p: law(*p, 32, 8)[:3],
             "twist_shear rings, 32 cells, 4 points": lambda *p: law(*p, 32, 4, lever="rings")[:3],
             "twist_shear rings, 32 cells, 8 points": lambda *p: law(*p, 32, 8, lever="rings")[:3],
             "separate laws (vector MDR and deresiewicz cells, 32)": separate_path}
    for kind in ("q1", "q1.5", "q2", "ring"):
        for rule in ("radial", "energy"):
            forms[f"one state per cell, {kind}, {rule} return (128 cells)"] = (
                lambda ux, uy, tw, kind=kind, rule=rule: candidate_path(kind, rule, ux, uy, tw))
    out = {}
    for name, fn in forms.items():
        row = {}
        for label, (ux, uy, tw, Txr, Tyr, Mzr) in refs.items():
            Tx, Ty, M = fn(ux, uy, tw)
            row[label] = [round(float(np.max(np.hypot(Tx + Txr, Ty + Tyr)) / (MU * N)), 4),
                          round(float(np.max(np.abs(M + Mzr)) / (MU * N * A)), 4)]
        out[name] = row
        print(name, row, flush=True)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bem-extra", action="store_true", help="also run the BEM on the paths the law was not built on")
    args = ap.parse_args()
    if args.bem_extra:
        bem_extra()
    errs, curves = bem_errors()
    errs_rings, curves_rings = bem_errors("rings")
    angles = np.linspace(0, np.pi / 2, 25)
    ex = disc_limit_surface(angles)
    surf = {"exact disc": ex.round(4).tolist()}
    for lever in ("limits", "rings"):
        lw = law_limit_surface(angles, lever=lever)
        surf[f"law ({lever}, 32 cells, 8 points)"] = lw.round(4).tolist()
        surf[f"{lever}: largest |law - exact| at the same (v, w a) [T, M]"] = (
            np.abs(lw - ex).max(axis=0).round(4).tolist())
        surf[f"{lever}: law's distance from the origin over the exact one's along the same ray, less 1 "
             "(M scaled by 3 pi/16)"] = ray_deviation(lw, ex).round(4).tolist()
        if lever == "limits":
            lw_limits = lw
        else:
            lw_rings = lw
    out = {"scene": {"pair": "steel sphere R 10 mm on a steel wall", "delta": DELTA, "mu": MU, "N": N, "a": A},
           "bem 128 across, max error (force / (mu N), moment / (mu N a)), slip lever limits": errs,
           "bem 128 across, max error, slip lever rings": errs_rings,
           "full slip: (T / (mu N), M / (mu N a)) at (v, w a) = (cos t, sin t), t = 0 ... pi/2": surf,
           "closed loops at constant N, limits": loops(),
           "closed loops at constant N, rings": loops(lever="rings"),
           "BEM errors [force / (mu N), moment / (mu N a)] by formulation and path": formulations()}
    (HERE / "twist_shear.json").write_text(json.dumps(out, indent=1))
    print(json.dumps(out, indent=1))
    fig, axs = plt.subplots(1, 3, figsize=(14, 4.2))
    for ax, label in zip(axs[:2], ("shear-twist 0.6", "circle-twist 0.4")):
        tw, ux, uy, Txr, Tyr, Mzr, Tx, Ty, M = curves[label]
        Rx, Ry, RM = curves_rings[label][6:]
        k = np.arange(tw.size)
        ax.plot(k, np.hypot(Txr, Tyr) / (MU * N), "k-", lw=2.5, label="|T| BEM 128 across")
        ax.plot(k, np.hypot(Tx, Ty) / (MU * N), "r--", label="|T| twist_shear, limits")
        ax.plot(k, np.hypot(Rx, Ry) / (MU * N), "g:", label="|T| twist_shear, rings")
        ax.plot(k, -Mzr / (MU * N * A), "b-", lw=2.5, alpha=0.5, label="M BEM")
        ax.plot(k, M / (MU * N * A), "c--", label="M twist_shear, limits")
        ax.plot(k, RM / (MU * N * A), "m:", label="M twist_shear, rings")
        ax.set_xlabel("row")
        ax.set_ylabel("|T| / (mu N), M / (mu N a)")
        ax.set_title(label)
        ax.legend(fontsize=7)
    axs[2].plot(ex[:, 0], ex[:, 1], "k-o", ms=3, label="exact Hertz disc")
    axs[2].plot(lw_limits[:, 0], lw_limits[:, 1], "r--s", ms=3, label="twist_shear, limits")
    axs[2].plot(lw_rings[:, 0], lw_rings[:, 1], "g--^", ms=3, label="twist_shear, rings")
    axs[2].set_xlabel("T / (mu N)")
    axs[2].set_ylabel("M / (mu N a)")
    axs[2].set_title("full slip under sliding and spin")
    axs[2].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(HERE / "twist_shear.png", dpi=110)


if __name__ == "__main__":
    main()
