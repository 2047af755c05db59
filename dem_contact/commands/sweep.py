"""``dem-contact sweep``: an impact-angle sweep, the fit of eq. 4.5 and the three critical Theta."""
from __future__ import annotations

import csv
import math
import sys
import warnings

import numpy as np

from ..errors import InputError, NumericalError
from ..rebound.fit import critical_theta, fit_wu
from ..materials import check_finite
from ..rebound.models import PUBLISHED_FITS, eq_4_1, max_curve_difference, theta_c_theory
from ..impacts.sweep import critical_angle, sweep_angles, sweep_speed
from .common import (SCENE_OPTIONS, add_scene_options, check_output_file, default, dest, dump_json,
                     scene_from_args)

ORDER = 2

DEFAULT_ANGLES = "0:85:1"
DEFAULT_VN = 5.0
MAX_IMPACTS = 100000
CSV_COLUMNS = ("theta_deg", "vn_i", "vt_i", "Theta", "e_n", "e_t", "f_over_mu", "Psi_r", "Omega_r", "omega_r",
               "rebound_angle_deg", "contact_time", "max_force", "persistent_sliding")

HELP = "sweep the impact angle, fit the Wu et al. model, find Theta_c"
DESCRIPTION = ("Simulate impacts at a range of angles (at fixed normal speed --vn, the "
               "protocol of Wu, Thornton & Li 2009, or at fixed total speed --speed), fit "
               "f/mu = c1 + c2 tanh(c3 + c4 Theta) below persistent sliding, and report "
               "Theta_c from the fit, from the simulation (bisection in angle) and from "
               "eq. 4.1. Without options: the EE steel scene at 5 m/s, 0-85 deg, figure "
               "written to sweep_EE.png.")


def add_options(p):
    add_scene_options(p)
    g = p.add_argument_group("sweep")
    g.add_argument("--angles", default=DEFAULT_ANGLES, metavar="START:STOP:STEP",
                   help=f"impact angles from the normal [deg], STOP included (default {DEFAULT_ANGLES})")
    g.add_argument("--speed", type=float, default=None,
                   help="fixed total speed [m/s] instead of fixed normal speed --vn")
    o = p.add_argument_group("output")
    o.add_argument("--json", action="store_true", help="print one JSON object")
    o.add_argument("--csv", metavar="PATH", default=None, help="write one row per impact to PATH")
    o.add_argument("--plot", metavar="PATH.png", default=None,
                   help="write the figure to PATH.png (default when neither --json nor --csv is given: "
                        "sweep_<CASE>.png in the current directory)")
    o.add_argument("--no-plot", action="store_true", help="write no figure")
    o.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.set_defaults(vn=None)        # None: --vn not given (it cannot act with --speed)


def parse_angles(text: str) -> np.ndarray:
    """START:STOP:STEP (degrees, STOP included) -> array of angles in [0, 90)."""
    parts = text.split(":")
    try:
        if len(parts) != 3:
            raise ValueError
        start, stop, step = (float(x) for x in parts)
    except ValueError:
        raise InputError(f"--angles {text!r} must be START:STOP:STEP in degrees, e.g. {DEFAULT_ANGLES}") from None
    if not all(math.isfinite(x) for x in (start, stop, step)) or step <= 0:
        raise InputError(f"--angles {text!r}: STEP must be > 0 and all values finite")
    if not (0.0 <= start <= stop < 90.0):
        raise InputError(f"--angles {text!r}: need 0 <= START <= STOP < 90 degrees")
    n = int(math.floor((stop - start) / step + 1e-9)) + 1
    if n > MAX_IMPACTS:
        raise InputError(f"--angles {text!r} gives {n} impacts; at most {MAX_IMPACTS}")
    return start + step * np.arange(n)


#: Scene options that a published fit leaves free: the case, nu and vn are matched against its row, and the
#: tangential settings are what a sweep compares with it; every other scene option must be at its default.
PUBLISHED_FREE = ("--case", "--nu", "--vn", "--tangential", "--model", "--traction-yield", "--mdr-profile")


def published_key(args):
    """The PUBLISHED_FITS row that the options reproduce (preset scene, defaults, a published speed)."""
    if args.speed is not None or any(getattr(args, dest(flag)) != default(kwargs)
                                     for flag, kwargs in SCENE_OPTIONS if flag not in PUBLISHED_FREE):
        return None
    for key, row in PUBLISHED_FITS.items():
        nu_ok = (args.nu is None and row["nu"] == 0.3) or (args.case == "RE" and args.nu == row["nu"])
        if row["case"] == args.case and nu_ok and args.vn in row["vn"]:
            return key
    return None


def run(args) -> int:
    if args.speed is not None and args.vn is not None:
        raise InputError("give either --vn (fixed normal speed) or --speed (fixed total speed), not both")
    if args.vn is None:
        args.vn = DEFAULT_VN
    angles = parse_angles(args.angles)
    if args.steps_per_contact is not None and args.dt is not None:
        raise InputError("give either --steps-per-contact or --dt, not both")
    if args.dt is not None:
        raise InputError("sweep takes --steps-per-contact, not --dt (each impact gets its own time step)")
    if args.speed is not None:
        check_finite("--speed (total impact speed, m/s)", args.speed, lo=0.0)
    if args.mu <= 0:
        raise InputError(f"--mu {args.mu:g}: a sweep needs mu > 0 (Theta, f/mu and the fit of eq. 4.5 are "
                         f"defined through mu); for a frictionless impact use dem-contact impact")
    if args.no_plot and args.plot is not None:
        raise InputError("--plot and --no-plot contradict each other")
    if args.csv:
        check_output_file("--csv", args.csv)
    if args.plot:
        check_output_file("--plot", args.plot, (".png",))
    # the largest normal speed of the sweep places the mdr springs and the calibrations
    scene = scene_from_args(args, v_ref=args.speed)
    opts = dict(steps_per_contact=args.steps_per_contact, scheme=args.scheme, progress=not args.no_progress)
    if args.speed is not None:
        res = sweep_speed(scene, angles, args.speed, **opts)
    else:
        res = sweep_angles(scene, angles, args.vn, **opts)
    kappa = scene.pair.kappa
    fit = None
    fit_error = None
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")         # the fit's warnings are in fit.warnings, reported below
            fit = fit_wu(res.Theta, res.f_over_mu, res.persistent_sliding)
    except (InputError, NumericalError) as e:     # too few points, or points eq. 4.5 cannot follow: rows kept
        fit_error = str(e)
    crit = None
    if args.speed is None and scene.mu > 0:
        crit = critical_angle(scene, args.vn, steps_per_contact=args.steps_per_contact, scheme=args.scheme)
    e_n_slide = _sliding_e_n(res, crit)
    theory = theta_c_theory(kappa, e_n_slide)
    key = published_key(args)
    pub = PUBLISHED_FITS.get(key) if key else None
    comparison = None
    if pub is not None and fit is not None:
        tmax = pub["Theta_c_eq41"] or pub["Theta_c_paper"]
        comparison = {"case": key, **{f"c{i + 1}": c for i, c in enumerate(pub["c"])},
                      "Theta_c_paper": pub["Theta_c_paper"], "Theta_c_eq41": pub["Theta_c_eq41"],
                      "max_curve_difference": max_curve_difference(fit.c, pub["c"], tmax),
                      "max_curve_difference_range": [0.0, tmax]}
    plot_path = None
    if not args.no_plot and (args.plot is not None or not (args.json or args.csv)):
        from ..plots import sweep_figure

        plot_path = args.plot or f"sweep_{args.case}.png"
        tc = {"fit": fit.Theta_c if fit else None, "simulation": crit.Theta if crit else None,
              _criterion_label(e_n_slide): theory}
        sweep_figure(res, plot_path, fit=fit, published=pub, kappa=kappa, Theta_c=tc,
                     title=f"{args.case}: {scene.normal} / {scene.tangential}, mu = {scene.mu:g}, "
                           + (f"|V| = {args.speed:g} m/s" if args.speed is not None else f"V_n = {args.vn:g} m/s"))
    if args.csv:
        with open(args.csv, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(CSV_COLUMNS)
            for i, r in enumerate(res.points):
                d = r.to_dict()
                d["theta_deg"] = float(angles[i])
                w.writerow(["" if d[c] is None else d[c] for c in CSV_COLUMNS])
    if args.json:
        points = []
        for i, d in enumerate(res.to_dicts()):
            d.pop("model")
            points.append({"theta_deg": float(angles[i]), **d})
        out = {"model": scene.describe(), "settings": {**res.settings, "angles_deg": args.angles},
               "points": points, "fit": fit.to_dict() if fit else None, "fit_error": fit_error,
               "Theta_c_sim": crit.Theta if crit else None,
               "Theta_c_sim_angle_deg": crit.angle_deg if crit else None,
               "Theta_c_theory": theory, "Theta_c_theory_e_n": e_n_slide, "Theta_c_eq41": eq_4_1(kappa),
               "published": comparison, "plot": plot_path,
               "warnings": res.warnings}
        why = {"fit": None if fit is not None else f"no fit: {fit_error}",
               "Theta_c_sim": None if crit else ("not run: a fixed-total-speed sweep (--speed) has no fixed normal "
                                                 "speed to bisect the angle at"),
               "published": None if comparison else "no published fit of Wu et al. (2009) for these options",
               "plot": None if plot_path else "no figure written (--no-plot, or --json/--csv without --plot)"}
        why["Theta_c_sim_angle_deg"] = why["Theta_c_sim"]
        for k, v in (out["fit"] or {}).items():
            if v is None:
                why[f"fit.{k}"] = "; ".join(fit.warnings) or "not defined for this fit"
        why = {k: v for k, v in why.items() if v is not None}
        if why:
            out["null_values"] = why
        print(dump_json(out))
        return 0
    _print_summary(args, scene, res, angles, fit, fit_error, crit, theory, e_n_slide, comparison, plot_path)
    return 0


def _sliding_e_n(res, crit) -> float:
    """The e_n of the sliding impacts, for the criterion Theta_c = 7 - 2 e_n / (kappa (1 + e_n)): that of the
    first persistently sliding impact of the bisection, else of the sweep, else of its last impact (clipped to
    [0, 1])."""
    if crit is not None:
        e = crit.e_n
    else:
        idx = np.flatnonzero(res.persistent_sliding)
        e = res.e_n[idx[0] if idx.size else -1]
    return min(max(float(e), 0.0), 1.0)


def _criterion_label(e_n: float) -> str:
    return "eq. 4.1" if e_n == 1.0 else f"criterion (e_n = {e_n:.3f})"


def _print_summary(args, scene, res, angles, fit, fit_error, crit, theory, e_n_slide, comparison, plot_path):
    s = res.settings
    speed = f"|V| = {args.speed:g} m/s" if args.speed is not None else f"V_n = {args.vn:g} m/s"
    print(f"{args.case} scene: normal {scene.normal}, tangential {scene.tangential}, mu = {scene.mu:g}, "
          f"kappa = {scene.pair.kappa:.4f}; {speed}; {len(res)} impacts, {s['scheme']} scheme, "
          f"{s['steps_per_contact'] or 'per-impact'} steps per contact")
    step = max(1, len(res) // 12)
    print(f"  {'angle':>6} {'Theta':>8} {'e_n':>7} {'e_t':>8} {'f/mu':>7} {'Psi_r':>8} {'Omega_r':>8}  sliding")
    for i in list(range(0, len(res), step)) + ([len(res) - 1] if (len(res) - 1) % step else []):
        r = res.points[i]
        print(f"  {angles[i]:6.2f} {r.Theta:8.4f} {r.e_n:7.4f} {r.e_t:8.4f} {r.f_over_mu:7.4f} "
              f"{r.Psi_r:8.4f} {r.Omega_r:8.4f}  {'yes' if r.persistent_sliding else 'no'}")
    if fit is not None:
        c = ", ".join(f"c{i + 1} = {v:.4f} +/- {e:.4f}" for i, (v, e) in enumerate(zip(fit.c, fit.c_err)))
        print(f"fit of eq. 4.5 ({fit.n_points} points below persistent sliding, residual RMS {fit.rms:.4f}): {c}")
    else:
        print(f"no fit: {fit_error}")
    tc = critical_theta(fit, scene.pair.kappa, crit.Theta if crit else None, e_n_slide) if fit else None
    print("Theta_c: " + "; ".join([
        (f"fit crossing 1 = {tc.fit:.4f} +/- {fit.Theta_c_err:.4f} (statistical) +/- "
         f"{fit.Theta_c_model_err:.2g} (model form of eq. 4.5){' EXTRAPOLATED' if fit.extrapolated else ''} "
         f"(0.99 at {tc.fit_099:.4f})") if tc else "fit: none",
        f"simulation = {crit.Theta:.4f} (angle {crit.angle_deg:.4f} deg)" if crit else "simulation: not run "
        "(fixed total speed)",
        f"criterion 7 - 2 e_n/(kappa (1 + e_n)) with the sliding e_n = {e_n_slide:.4f}: {theory:.4f} (eq. 4.1, "
        f"e_n = 1: {theta_c_theory(scene.pair.kappa):.4f})"]))
    if comparison:
        print(f"published fit ({comparison['case']}): Theta_c (paper) = {comparison['Theta_c_paper']:g}; "
              f"max |f/mu - published| over 0 <= Theta <= {comparison['max_curve_difference_range'][1]:g}: "
              f"{comparison['max_curve_difference']:.4f}")
    for w in res.warnings + (fit.warnings if fit is not None else []):
        print(f"warning: {w}")
    if plot_path:
        print(f"figure written to {plot_path}")
    sys.stdout.flush()
