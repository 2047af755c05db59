"""``dem-contact impact3d``: a sphere-wall impact with any tangential velocity and spin vector (one impact
or a sweep over angles)."""
from __future__ import annotations

import csv
import math
import sys
import warnings

from ..errors import InputError
from ..impacts.impact3d import impact3d, sweep3d
from ..impacts.sweep import compile_notice, merge_warnings
from .common import (add_scene_options, add_torque_options, check_output_file, dump_json, model_line,
                     print_energy_and_warnings, scene_from_args, time_options, torque_laws)
from .sweep import parse_angles

ORDER = 2

FRAME = ("frame: z is the wall normal pointing into the wall (the approach direction, V_z = vn > 0), x and y "
         "span the wall plane; the planar impact (vt, spin) of 'dem-contact impact' is --vt VT 0 "
         "--spin-vector 0 SPIN 0")
COLUMNS = ("theta_deg", "Theta", "Theta_across", "e_n", "e_t", "f_over_mu", "f_across_over_mu", "Psi_r",
           "Psi_r_across", "Omega_r", "Omega_across_r", "slip_angle_i_deg", "slip_angle_r_deg",
           "rebound_angle_deg", "out_of_plane_angle_deg")

HELP = "sphere-wall impact with any tangential velocity and spin vector"
DESCRIPTION = ("Simulate a 3D impact of a sphere on a flat wall with a tangential velocity "
               "in the wall plane and an initial spin about any axis, and print the rebound "
               "velocity and spin vectors and the in-plane quantities (e_n, e_t, f/mu, "
               "Theta, Psi_r, Omega_r of the impact plane, spanned by the normal and the "
               "incident tangential velocity) with their components across the plane. "
               f"With --angles: a sweep at fixed --vn. {FRAME}. SI units.")


def add_options(p):
    add_scene_options(p)
    add_torque_options(p)
    g = p.add_argument_group("incident motion")
    g.add_argument("--vt", type=float, nargs=2, default=None, metavar=("VX", "VY"),
                   help="tangential velocity of the centre [m/s] (default: from --angle)")
    g.add_argument("--angle", type=float, default=None,
                   help="impact angle from the wall normal [deg]: |vt| = vn tan(angle) along --direction "
                        "(default 20)")
    g.add_argument("--angles", default=None, metavar="START:STOP:STEP",
                   help="a sweep over impact angles [deg] (STOP included) at fixed --vn, each with the same spin")
    g.add_argument("--direction", type=float, default=None,
                   help="direction of the tangential velocity in the wall plane, from x towards y [deg] "
                        "(with --angle or --angles; default 0)")
    g.add_argument("--spin-vector", type=float, nargs=3, default=[0.0, 0.0, 0.0], metavar=("WX", "WY", "WZ"),
                   help="initial angular velocity of the sphere [rad/s] (default 0 0 0)")
    g.add_argument("--fixed-frame", action="store_true",
                   help="keep the tangential history fixed in space instead of turning it with the mean spin "
                        "about the normal (as LAMMPS does)")
    p.add_argument("--json", action="store_true", help="print one JSON object (a list of them with --angles)")
    p.add_argument("--csv", default=None, metavar="FILE", help="with --angles: one row per impact to FILE")
    p.add_argument("--series", action="store_true", help="with --json (one impact): include the time series")


def run(args) -> int:
    scene = scene_from_args(args)
    if torque_laws(args):
        scene = scene.replace(**torque_laws(args))
    given = [name for name, v in (("--vt", args.vt), ("--angle", args.angle), ("--angles", args.angles))
             if v is not None]
    if len(given) > 1:
        raise InputError(f"give one of --vt, --angle and --angles, not {' and '.join(given)}")
    if args.vt is not None and args.direction is not None:
        raise InputError("--direction applies to --angle and --angles, not to --vt")
    if args.angles is None and args.csv:
        raise InputError("--csv applies to --angles only")
    if args.csv:
        check_output_file("--csv", args.csv)        # before any impact is computed
    if args.series and (args.angles is not None or not args.json):
        raise InputError("--series applies to one impact with --json")
    opts = dict(time_options(args), frame_spin=not args.fixed_frame)
    direction = 0.0 if args.direction is None else args.direction
    with warnings.catch_warnings(), compile_notice(sys.stderr.isatty()):     # (the notice: in a terminal)
        warnings.simplefilter("ignore")  # the warnings are reported in the result
        if args.angles is not None:
            opts.pop("dt")
            if args.dt is not None:
                raise InputError("--dt applies to one impact; a sweep takes --steps-per-contact")
            angles = parse_angles(args.angles)
            res = sweep3d(scene, angles, args.vn, args.spin_vector, direction_deg=direction, **opts)
            return _print_sweep(args, scene, angles, res)
        if args.vt is not None:
            vt = args.vt
        else:
            angle = 20.0 if args.angle is None else args.angle
            if not -90.0 < angle < 90.0:
                raise InputError(f"--angle = {angle:g} deg is outside the valid range (-90, 90)")
            v = args.vn * math.tan(math.radians(angle))
            vt = (v * math.cos(math.radians(direction)), v * math.sin(math.radians(direction)))
        r = impact3d(scene, args.vn, vt, args.spin_vector, series=args.series, **opts)
    if args.json:
        print(dump_json(r.to_dict(series=args.series)))
        return 0
    print(f"{model_line(r)}; {'fixed' if args.fixed_frame else 'turning'} contact frame")
    print(FRAME)
    vec = lambda v: "(" + ", ".join(f"{x:.8g}" for x in v) + ")"  # noqa: E731
    print(f"incident: vn = {r.vn_i:g} m/s, vt = {vec(r.vt_i)} m/s, spin = {vec(r.spin_i)} rad/s")
    print(f"rebound:  vn = {r.vn_r:.8g} m/s, vt = {vec(r.vt_r)} m/s, spin = {vec(r.spin_r)} rad/s")
    print(f"impact plane axis e1 = {vec(r.plane_axis)}; in the plane / across it:")
    for name, a, b in [("Theta", r.Theta, r.Theta_across), ("f/mu", r.f_over_mu, r.f_across_over_mu),
                       ("Psi_r", r.Psi_r, r.Psi_r_across), ("Omega_r", r.Omega_r, r.Omega_across_r)]:
        print(f"  {name:10s} {_num(a, 12)} {_num(b, 12)}")
    rows = [("e_n", r.e_n, ""), ("e_t", r.e_t, ""), ("slip angle in", r.slip_angle_i_deg, "deg"),
            ("slip angle out", r.slip_angle_r_deg, "deg"), ("rebound angle", r.rebound_angle_deg, "deg"),
            ("out of plane", r.out_of_plane_angle_deg, "deg"), ("contact time", r.contact_time, "s")]
    for name, val, unit in rows:
        print(f"  {name:15s} {_num(val)} {unit}")
    if scene.mu == 0:
        print("  (f/mu, Theta, Psi_r and Omega_r are undefined at mu = 0)")
    print_energy_and_warnings(r)
    return 0


def _num(x: float, width: int = 0) -> str:
    """A number as %.8g, or "undefined" where it is NaN (e_t at vt = 0, the groups at mu = 0)."""
    return f"{x:{width}.8g}" if x == x else f"{'undefined':>{width}s}"


def _row(theta, r) -> dict:
    """One CSV row; an undefined quantity (NaN: e_t at vt = 0, the groups at mu = 0) is an empty cell, as in
    the CSV of ``sweep``."""
    d = {"theta_deg": float(theta)}
    for c in COLUMNS[1:]:
        v = getattr(r, c)
        d[c] = "" if v != v else v
    return d


def _print_sweep(args, scene, angles, res) -> int:
    if args.csv:
        with open(args.csv, "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(COLUMNS))
            w.writeheader()
            for a, r in zip(angles, res):
                w.writerow(_row(a, r))
    if args.json:
        print(dump_json([{"theta_deg": float(a), **r.to_dict()} for a, r in zip(angles, res)]))
        return 0
    print(f"model: {scene.normal} / {scene.tangential}, mu = {scene.mu:g}; vn = {args.vn:g} m/s, spin = "
          f"{tuple(args.spin_vector)} rad/s")
    print(FRAME)
    print(f"  {'angle':>6s} {'Theta':>8s} {'Theta_x':>8s} {'e_n':>7s} {'e_t':>8s} {'f/mu':>8s} {'f_x/mu':>8s} "
          f"{'Omega_r':>8s} {'slip_in':>8s} {'slip_out':>8s} {'out_deg':>8s}")
    for a, r in zip(angles, res):
        print(f"  {a:6.2f} {r.Theta:8.4f} {r.Theta_across:8.4f} {r.e_n:7.4f} {r.e_t:8.4f} {r.f_over_mu:8.4f} "
              f"{r.f_across_over_mu:8.4f} {r.Omega_r:8.4f} {r.slip_angle_i_deg:8.3f} {r.slip_angle_r_deg:8.3f} "
              f"{r.out_of_plane_angle_deg:8.3f}")
    print("(_x: across the impact plane; slip angles of the contact-point velocity from the impact plane; "
          "out_deg: rebound velocity out of the plane)")
    for w in merge_warnings([r.warnings for r in res], len(res)):
        print(f"warning: {w}")
    return 0
