"""3D speed-accuracy chart: every tangential law of dem_contact.dem.contact3d against the boundary-element
reference on the five curved paths at constant overlap. Writes chart3d.csv, chart3d.png and chart3d.md
beside this file; the BEM forces are read from bem_paths_n64.csv (recomputed with --recompute, about
a minute at 64 elements across; --check FILE compares with a finer reference written the same way) and the
spinning impacts from validation/spin/bem_spin_reference.csv (written by validation/spin/spin.py); the twist
paths (default tangential law, twist laws none, deresiewicz, marshall, sds) against the BEM histories with
twist at 128 elements across in validation/bem/paths/<shape>_<size>_n128_s400.csv (written by
validation/bem/twist.py paths), to chart3d_twist.csv.

    python validation/chart/chart3d.py [--recompute] [--check validation/chart/bem_paths_n128.csv]
    python validation/chart/chart3d.py --write-reference 128 validation/chart/bem_paths_n128.csv
"""
import pathlib
import sys

import numpy as np

from dem_contact.plots import chart3d_figure
from dem_contact.studies import chart3d as c
from dem_contact.studies.spin import read_bem_spin_reference

HERE = pathlib.Path(__file__).parent
REF = HERE / "bem_paths_n64.csv"
SPIN_REF = HERE.parent / "spin" / "bem_spin_reference.csv"
TWIST_REF = HERE.parent / "bem" / "paths"
#: The targets on the twist paths: (force [mu N], moment [mu N a]); None: no target.
TWIST_TARGETS = {"twist-cycle 2": (None, 0.01), "shear-twist 0.6": (0.03, 0.03), "circle-twist 0.4": (0.03, 0.03)}


def twist_section():
    """Rows of the twist chart and the lines of its section."""
    paths = c.twist_paths()
    refs = {}
    for shape, size in c.TWIST_SET:
        rpath, ref = c.read_twist_reference(TWIST_REF / f"{shape}_{size:g}_n128_s{c.PATH_STEPS}.csv")
        label = c.path_label(shape, size)
        if any(abs(a - b).max() > 1e-9 * abs(b).max() for a, b in zip(rpath, paths[label])):
            raise SystemExit(f"the BEM history of {label} is not on the chart's path")
        refs[label] = ref
    rows = c.twist_chart(paths, refs)
    sds = c.sds_hertz_values(c.chart_scene(), c.DELTA)
    labels = list(paths)
    lines = ["", "## Twist paths", "",
             f"The same scene (constant overlap {c.DELTA:g} m, {c.PATH_STEPS} steps per path) on the twist paths "
             "of `dem_contact.reference.paths.TWIST_SET` (twist in units of beta_1, the no-slip twist at unit "
             "moment): twist-cycle 2 (to 2 beta_1, back to -2 beta_1 and again to 2 beta_1, no displacement), "
             "shear-twist 0.6 (along x to 0.6 of slip, then at that displacement a twist out to beta_1 and "
             "back), circle-twist 0.4 (the circle of radius 0.4 through the origin with a twist 0.4 beta_1 "
             "sin 2 phi). Default tangential law (mdr_adaptive) with each twist law; `sds` given the Hertz "
             f"values at the path's overlap (`studies.chart3d.sds_hertz_values`): k_twist = (16/3) G_c a^3 = "
             f"{sds['k_twist']:.4g} N m/rad, mu_twist = (3 pi/16) mu a = {sds['mu_twist']:.4g} m, no dashpot. "
             "Reference: the BEM with twist at 128 elements across, 400 steps "
             "(`validation/bem/paths/*_n128_s400.csv`; its own grid error, 64 against 128 across, is at most "
             "1.5e-4 mu N and 2.5e-4 mu N a, `validation/bem/twist.md`). Force error: max |T - T_BEM| / (mu N); "
             "moment error: max |Mz - Mz_BEM| / (mu N a); time: one kernel update with the twist (serial loop, "
             "warm JIT, best of 5).", "",
             "| twist law | " + " | ".join(f"{p}: force / moment" for p in labels) + " | ns per update |",
             "|---|" + "---|" * (len(labels) + 1)]
    for law in c.TWIST_LAWS:
        per = {r.path: r for r in rows if r.twist == law}
        lines.append(f"| {law} | " + " | ".join(f"{per[p].force_error:.3f} / {per[p].moment_error:.3f}"
                                               for p in labels) +
                     f" | {max(per[p].time_per_update_ns for p in labels):.0f} |")
    # the shear-twist path in numbers: |T| / (mu N) before the twist, at the largest twist and at the end,
    # and the moment there, of the BEM and of the separate laws (deresiewicz)
    (d, x, y, t), (N, Tx, Ty, Mz) = paths["shear-twist 0.6"], refs["shear-twist 0.6"]
    sc = c.twist_scene("deresiewicz")
    a = (sc.pair.R_star * d) ** 0.5
    _, lx, ly, lm = c.run_path(sc, d, x, y, t)
    k0, k1 = int(np.argmax(t > 0)) - 1, int(np.argmax(t))
    T, LT = np.hypot(Tx, Ty) / (sc.mu * N), np.hypot(lx, ly) / (sc.mu * N)
    lines += ["", f"Shear-twist: in the BEM the twist and the shear share the local Coulomb limit, so the twist "
              f"takes the tangential force from {T[k0]:.3f} mu N (before the twist) to {T[k1]:.3f} at the "
              f"largest twist and it stays at {T[-1]:.3f} when the twist is undone (slip during the twist); the "
              f"separate laws keep {LT[k1]:.3f}. The moment at the largest twist is {abs(Mz[k1]) / (sc.mu * N[k1] * a[k1]):.3f} "
              f"mu N a in the BEM (the sheared contact has less room for twist traction) and "
              f"{abs(lm[k1]) / (sc.mu * N[k1] * a[k1]):.3f} with deresiewicz (Lubkin's value of the unsheared "
              "contact). The circle with twist shows the same coupling, smaller. The force and moment targets on "
              "these two paths need a law that couples twist and shear in one local state; the separate laws "
              "do not meet them (the coupled path law `laws.twist_shear` does: validation/twist/report.md; it is "
              "not a law of the 3D step charted here). Without a twist law the moment is simply missing (error = the BEM's moment); "
              "marshall (its stiffness from the tangential coefficient, slider (2/3) mu N a) and sds with the "
              "Hertz values (a linear spring up to Lubkin's full-slip moment) miss the hysteresis of the "
              "partial-slip annulus."]
    lines += ["", "Targets: " + "; ".join(
        f"{p}: " + ", ".join(f"{k} within {v:g}" for k, v in zip(("force", "moment"), TWIST_TARGETS[p]) if v)
        for p in labels) + ". Met (force, moment): " + "; ".join(
        f"{law}: " + ", ".join(
            f"{p} " + "/".join(("yes" if e <= v else "no") for e, v in
                               zip((r.force_error, r.moment_error), TWIST_TARGETS[p]) if v)
            for p in labels for r in rows if r.twist == law and r.path == p)
        for law in c.TWIST_LAWS) + "."]
    return rows, lines


def main():
    if "--write-reference" in sys.argv:        # a reference at another grid, for --check (about 4 minutes at 128)
        i = sys.argv.index("--write-reference")
        n, out = int(sys.argv[i + 1]), sys.argv[i + 2]
        paths = c.chart_paths()
        c.write_reference(out, paths, c.reference_forces(paths, n_across=n, progress=True), n)
        return
    if "--recompute" in sys.argv or not REF.exists():
        paths = c.chart_paths()
        forces = c.reference_forces(paths, n_across=c.N_ACROSS, progress=True)
        c.write_reference(REF, paths, forces, c.N_ACROSS)
    paths, forces, n_across = c.read_reference(REF)
    rows = c.chart3d(paths, forces)
    c.write_csv(rows, HERE / "chart3d.csv")
    spin_ref = read_bem_spin_reference(SPIN_REF)
    spin_rows = c.spin_impact_chart(spin_ref)
    c.write_csv(spin_rows, HERE / "chart3d_spin.csv")
    twist_rows, twist_lines = twist_section()
    c.write_csv(twist_rows, HERE / "chart3d_twist.csv")
    chart3d_figure(rows, HERE / "chart3d.png", spin_rows=spin_rows, twist_rows=twist_rows,
                   twist_targets=TWIST_TARGETS,
                   title=f"3D laws against the BEM ({n_across} elements across), steel on steel, mu = 0.3, "
                         f"overlap {c.DELTA:g} m, {c.PATH_STEPS} steps per path")
    labels = list(paths)
    lines = ["# 3D laws against the boundary-element reference", "",
             f"Steel sphere (R = 10 mm) on a steel wall, mu = 0.3, constant overlap {c.DELTA:g} m; paths of "
             "`dem_contact.reference.paths.COMPARISON_SET` (sizes in slip displacements mu delta / kappa), "
             f"{c.PATH_STEPS} steps each, driven through `dem_contact.studies.paths.run_path` (the 3D kernel, "
             f"contact frame fixed). Reference: `dem_contact.reference.bem` with {n_across} elements across the "
             "contact. Error: max over the path of |T - T_BEM| / (mu N); time: one kernel update, serial loop, "
             "warm JIT, best of 5 runs (shared machine: compare ratios).", "",
             "Regenerate: `python validation/chart/chart3d.py` (a few seconds; the reference is "
             "read from `bem_paths_n64.csv`, `--recompute` rebuilds it, about a minute).", "",
             "| law | " + " | ".join(labels) + " | max | ns per update |",
             "|---|" + "---|" * (len(labels) + 2)]
    for law in dict.fromkeys(r.law for r in rows):
        per = {r.path: r for r in rows if r.law == law}
        lines.append(f"| {law} | " + " | ".join(f"{per[p].error:.3f}" for p in labels) +
                     f" | {per['max'].error:.3f} | {per['max'].time_per_update_ns:.0f} |")
    for arg in sys.argv:
        if arg.startswith("--check"):
            fine = pathlib.Path(sys.argv[sys.argv.index(arg) + 1])
            fpaths, fforces, fn = c.read_reference(fine)
            lines += ["", f"BEM grid: {n_across} against {fn} elements across, max |T_{n_across} - T_{fn}| / (mu N) "
                      "per path: " + ", ".join(
                          f"{p} {c.force_error(*forces[p], fforces[p], 0.3):.4f}" for p in labels if p in fforces)]
    b = spin_ref[0]
    lines += ["", "## Spinning impacts", "",
              f"EE scene (steel, R = 10 mm, V_n = 5 m/s, mu = 0.3), {len(spin_ref)} impacts with a spin about the "
              "incident tangential direction (`validation/spin/bem_spin_reference.csv`: angles and Theta_across "
              f"there), against the BEM impact ({b.n_across} elements across, {b.steps} steps); each law's "
              f"`impact3d` at {b.steps} steps per contact. Error: max |f - f_BEM| / mu of the impulse-ratio "
              "vectors; time: one impact in the bare kernel (warm JIT, best of 20).", "",
              "| law | error | us per impact |", "|---|---|---|"]
    for r in spin_rows:
        lines.append(f"| {r.law} | {r.error:.1e} | {r.time_per_impact_us:.1f} |")
    lines += twist_lines
    lines += ["", "![chart](chart3d.png)", ""]
    (HERE / "chart3d.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
