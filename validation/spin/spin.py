"""Impacts with out-of-plane spin, EE scene of Wu, Thornton & Li (2009): steel on steel, R = 10 mm,
V_n = 5 m/s, mu = 0.3. Writes spin.csv, bem_cases.csv, spin.png and report.md beside this file.

    python validation/spin/spin.py [--quick] [--recompute]

The BEM impacts are stored in bem_spin_reference.csv (--recompute: about 1 minute more, with a grid check).
"""
import math
import pathlib
import sys
import time
import warnings

import numpy as np

from dem_contact.impacts.impact3d import impact3d
from dem_contact.impacts.presets import preset_scene
from dem_contact.impacts.sweep import sweep_theta
from dem_contact.plots import spin_figure
from dem_contact.studies.spin import (bem_spin_cases, bem_spin_reference, compare_spin_cases, law_scenes,
                                      read_bem_spin_reference, spin_sweep, write_rows)

HERE = pathlib.Path(__file__).parent
QUICK = "--quick" in sys.argv
VN = 5.0
ANGLES = (10.0, 30.0, 50.0)
THETA_ACROSS = np.linspace(-6.0, 6.0, 13 if QUICK else 49)
BEM_CASES = [(10.0, 1.5), (30.0, 0.0), (30.0, 1.5), (30.0, 4.0), (50.0, 1.5)] if not QUICK else [(30.0, 1.5)]
LAWS = ("mdr_adaptive", "mdr", "md", "md_rescale", "mindlin_total", "mindlin_incremental", "mindlin_rescale",
        "ddm", "linear")


def main():
    lines = ["# Impacts with out-of-plane spin", "",
             "EE scene of Wu, Thornton & Li (2009): steel sphere (R = 10 mm, E = 208 GPa, nu = 0.3, rho = 7850) "
             "on a steel wall, mu = 0.3, V_n = 5 m/s, hertz normal law. The sphere's centre moves along x at the "
             "impact angle; a spin wx about x (the incident tangential direction) gives the contact point a "
             "velocity across the impact plane, s_y = -R wx, measured by Theta_across = 2 s_y / ((1 + e_n) mu V_n). "
             "Frame of `dem_contact.impacts.impact3d`: z into the wall.", "",
             "Regenerate: `python validation/spin/spin.py` (about a minute; the BEM impacts are "
             "read from `bem_spin_reference.csv`, `--recompute` recomputes them with a grid check, about 2 minutes "
             "more).", ""]
    sc = preset_scene("EE", VN)
    t0 = time.perf_counter()
    rows = spin_sweep(sc, VN, ANGLES, THETA_ACROSS)
    write_rows(rows, HERE / "spin.csv")
    lines += ["## The impact is the planar impact along the incident slip", "",
              "For a sphere on a flat wall the slip velocity obeys ds/dt = (1/m + R^2/I) F_t with the same factor in "
              "every tangential direction, and a law whose force follows a straight displacement path keeps the "
              "slip on a straight line: an out-of-plane spin does not turn the slip during the impact. The 3D "
              "impact is then the planar impact at the incident slip speed, turned to the incident slip "
              "direction. Measured: the largest |f vector/mu - planar f/mu along the slip| over "
              f"{len(rows)} impacts ({len(ANGLES)} angles x {len(THETA_ACROSS)} values of Theta_across in [-6, 6]), "
              "per law:", "", "| law | max deviation from the planar impact along the slip |", "|---|---|"]
    for law in LAWS:
        s = preset_scene("EE", VN, tangential=law)
        r = spin_sweep(s, VN, ANGLES, THETA_ACROSS[::4] if not QUICK else THETA_ACROSS[::3], label=law)
        lines.append(f"| {law} | {max(x.planar_deviation for x in r):.1e} |")
    lines += ["", "So f/mu and the rebound depend on the out-of-plane spin only through the incident slip vector: "
              "|f|/mu is the planar f/mu of |Theta vector| = hypot(Theta, Theta_across), along the slip. In the "
              "impact plane f/mu = (planar f/mu)(|Theta|) Theta/|Theta|: at a small angle it first grows with "
              "|Theta_across| (|f| grows along the planar curve), then falls as the impulse turns across the "
              "plane; the rebound velocity leaves the plane by up to 30 degrees, and e_t follows the in-plane "
              "impulse (e_t = 1 - 2 (f/mu)/Theta of the centre, eq. 2.22).", ""]
    # the planar curve for the collapse panel
    Th = np.linspace(0.0, 9.0, 91)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        pl = sweep_theta(sc, Th, VN)
    planar = (pl.Theta, pl.f_over_mu)
    # spin about the normal
    lines += ["## Spin about the normal", "",
              "No torque acts about the normal (the contact force passes through the axis), so a spin about it "
              "is kept exactly. With the contact frame turning with the mean spin of the two bodies about the "
              "normal (the kernel's objective frame, wn = 0.5 (w1 + w2).n, here w2 = 0), the tangential history "
              "turns at wz/2 while the slip does not, which gives a small impulse across the plane; with the frame "
              "fixed (`frame_spin=False`, LAMMPS's choice) the trajectory is that without the spin, to rounding "
              "error. "
              "Impact at 11.3 deg (vt = 1 m/s), no other spin:", "",
              "| wz [rad/s] | wz t_c [rad] | f/mu (turning frame) | f/mu (fixed frame) | f_across/mu (turning) | "
              "rebound out of plane [deg] |", "|---|---|---|---|---|---|"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for wz in (0.0, 100.0, 1000.0, 10000.0):
            a = impact3d(sc, VN, (1.0, 0.0), (0.0, 0.0, wz))
            b = impact3d(sc, VN, (1.0, 0.0), (0.0, 0.0, wz), frame_spin=False)
            lines.append(f"| {wz:g} | {wz * a.contact_time:.3g} | {a.f_over_mu:.8f} | {b.f_over_mu:.8f} | "
                         f"{a.f_across_over_mu:.2e} | {a.out_of_plane_angle_deg:.2e} |")
    # BEM cases
    ref_path = HERE / "bem_spin_reference.csv"
    if "--recompute" in sys.argv or QUICK or not ref_path.exists():
        ref = bem_spin_reference(sc, BEM_CASES, VN, n_across=32, steps=200)
        if not QUICK:
            write_rows(ref, ref_path)
    else:
        ref = read_bem_spin_reference(ref_path)
    bem = compare_spin_cases(law_scenes(sc, ("mdr_adaptive", "mdr", "md"), VN), ref, VN)
    write_rows(bem, HERE / "bem_cases.csv")
    lines += ["", "## Against the boundary-element reference", "",
              "`dem_contact.reference.impact.bem_impact` (Hertz normal motion, 3D Cattaneo-Mindlin tangential "
              "contact solved on the contact area, 32 elements across the largest contact, 200 velocity-Verlet "
              "steps) with the same spin vector, against each law's `impact3d` at 200 steps per contact. "
              "Error: |f vector (law) - f vector (BEM)| / mu.", "",
              "| angle [deg] | Theta | Theta_across | law | f/mu | f_across/mu | BEM f/mu | BEM f_across/mu | error | "
              "out of plane [deg] | BEM [deg] |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for b in bem:
        lines.append(f"| {b.angle_deg:g} | {b.Theta:.3f} | {b.Theta_across:.3f} | {b.law} | {b.f_over_mu:.5f} | "
                     f"{b.f_across_over_mu:.5f} | {b.bem_f_over_mu:.5f} | {b.bem_f_across_over_mu:.5f} | "
                     f"{b.error:.1e} | {b.out_of_plane_angle_deg:.3f} | {b.bem_out_of_plane_angle_deg:.3f} |")
    if "--recompute" in sys.argv:
        conv = bem_spin_cases(sc, [(30.0, 1.5)], VN, n_across=64, steps=200, laws=("mdr_adaptive",))[0]
        b32 = next(b for b in bem if b.angle_deg == 30.0 and abs(b.Theta_across - 1.5) < 0.01
                   and b.law == "mdr_adaptive")
        d = math.hypot(conv.bem_f_over_mu - b32.bem_f_over_mu, conv.bem_f_across_over_mu - b32.bem_f_across_over_mu)
        lines += ["", f"BEM grid: at 30 deg, Theta_across = 1.5 the f vector/mu changes by {d:.1e} from 32 to 64 "
                  f"elements across ({b32.bem_seconds:.0f} s and {conv.bem_seconds:.0f} s per impact here)."]
    spin_figure(rows, HERE / "spin.png", bem_rows=[b for b in bem if b.law == "mdr_adaptive"], planar=planar,
                title="EE, V_n = 5 m/s, mu = 0.3: impacts with a spin about the incident tangential direction "
                      "(mdr_adaptive; squares: BEM)")
    lines += ["", "![out-of-plane spin](spin.png)", "",
              "Top left: f/mu in the impact plane (solid) and across it (dashed) against Theta_across for three "
              "impact angles; markers: the BEM. Top right: |f|/mu against |Theta vector|, every impact on the "
              "planar curve. Bottom: the rebound velocity's angle out of the impact plane, and e_t.", "",
              f"({time.perf_counter() - t0:.0f} s)"]
    (HERE / "report.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
