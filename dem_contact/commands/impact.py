"""``dem-contact impact``: one oblique impact of a sphere on a wall."""
from __future__ import annotations

import sys
import warnings

from ..errors import InputError
from ..impacts.impact import impact, scene_constants
from ..impacts.sweep import compile_notice
from .common import (add_scene_options, angle_to_vt, dump_json, model_line, print_energy_and_warnings,
                     scene_from_args, time_options)

ORDER = 1
HELP = "simulate one oblique sphere-wall impact"
DESCRIPTION = ("Simulate one impact of a sphere on a flat wall and print e_n, e_t, the "
               "impulse ratio f, Theta, Psi_r, Omega_r, the contact time and the energy "
               "budget. SI units.")


def add_options(p):
    add_scene_options(p)
    g = p.add_argument_group("incident motion")
    g.add_argument("--vt", type=float, default=None,
                   help="tangential velocity of the centre [m/s] (default: from --angle)")
    g.add_argument("--angle", type=float, default=None,
                   help="impact angle from the wall normal [deg], vt = vn tan(angle) (default 20)")
    g.add_argument("--spin", type=float, default=0.0, help="initial angular velocity [rad/s] (default 0)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--series", action="store_true", help="with --json: include the time series")


def run(args) -> int:
    if args.series and not args.json:
        raise InputError("--series acts with --json only (the time series is printed in the JSON object)")
    if args.vt is not None and args.angle is not None:
        raise InputError("give either --vt or --angle, not both")
    scene = scene_from_args(args)
    vt = args.vt if args.vt is not None else angle_to_vt(args.vn, 20.0 if args.angle is None else args.angle)
    with compile_notice(sys.stderr.isatty()):     # (a terminal only: a log or a pipe gets no notice)
        scene_constants(scene)      # loads the integrator of the scene's laws from numba's cache, or compiles it
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the warnings are reported in the result
        r = impact(scene, args.vn, vt, args.spin, series=args.series, **time_options(args))
    if args.json:
        print(dump_json(r.to_dict(series=args.series)))
        return 0
    print(model_line(r))
    print(f"incident: vn = {r.vn_i:g} m/s, vt = {r.vt_i:g} m/s, spin = {r.omega_i:g} rad/s "
          f"(angle {r.theta_i_deg:.4g} deg, Theta = {r.Theta:.6g})" if r.Theta == r.Theta else
          f"(angle {r.theta_i_deg:.4g} deg, Theta undefined at mu = 0)")
    rows = [
        ("e_n", r.e_n, ""), ("e_t", r.e_t, ""), ("f", r.f, ""), ("f/mu", r.f_over_mu, ""),
        ("Psi_r", r.Psi_r, ""), ("Omega_r", r.Omega_r, ""), ("omega_r", r.omega_r, "rad/s"),
        ("rebound angle", r.rebound_angle_deg, "deg"), ("contact time", r.contact_time, "s"),
        ("max overlap", r.max_overlap, "m"), ("max force", r.max_force, "N"),
    ]
    undefined = {"e_t": "undefined (vt = 0)", "f/mu": "undefined (mu = 0)", "Psi_r": "undefined (mu = 0)",
                 "Omega_r": "undefined (mu = 0)"}
    for name, val, unit in rows:
        print(f"  {name:15s} {val:.8g} {unit}" if val == val else f"  {name:15s} {undefined[name]}")
    print(f"  persistent sliding: {'yes' if r.persistent_sliding else 'no'}; steps: {r.steps}")
    print_energy_and_warnings(r)
    return 0
