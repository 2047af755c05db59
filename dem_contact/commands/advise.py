"""``dem-contact advise``: the cheapest model of the rebound that meets a tolerance, from measured data."""
from __future__ import annotations

import argparse
import math

from ..errors import InputError
from .common import add_scene_options, dump_json, scene_from_args

ORDER = 5
HELP = "recommend the cheapest model meeting a tolerance on the rebound"
DESCRIPTION = ("Integrate a sample of the speed and angle ranges with the exact MDR "
               "reference, measure the error in f/mu (= error in Omega_r; e_t and Psi_r "
               "follow from it) and the time per impact of each candidate (rigid-body "
               "sliding, the Wu et al. model fitted to the sample, cheap laws at coarse "
               "steps, the reference itself) and recommend the cheapest within --tol. "
               "--tangential, --steps-per-contact and --model add that law at that time "
               "step as a candidate; --scheme sets the integrator end of the law "
               "candidates.")


def add_options(p):
    add_scene_options(p)
    # options of one impact that advise takes otherwise: None marks "not given" (see run); --vn and --dt
    # cannot act (refused in run) and are not listed in the help
    p.set_defaults(vn=None, dt=None, scheme=None)
    for a in p._actions:
        if a.dest in ("vn", "dt"):
            a.help = argparse.SUPPRESS
    p.add_argument("--vn-range", nargs=2, type=float, default=[1.0, 5.0], metavar=("MIN", "MAX"),
                   help="normal speed range [m/s] (default 1 5)")
    p.add_argument("--angle-range", nargs=2, type=float, default=[0.0, 60.0], metavar=("MIN", "MAX"),
                   help="impact angle range from the normal [deg] (default 0 60)")
    p.add_argument("--spin", type=float, default=0.0, help="initial spin [rad/s] (default 0)")
    p.add_argument("--tol", type=float, default=0.01, help="tolerance on f/mu (default 0.01)")
    p.add_argument("--verify", action="store_true", help="run the recommendation against MDR on a random sample")
    p.add_argument("--json", action="store_true", help="print one JSON object")


def run(args) -> int:
    from ..impacts.impact import default_steps_per_contact
    from ..studies.advise import advise

    if args.vn is not None:
        raise InputError("--vn does not apply to advise: it samples the normal speeds of --vn-range MIN MAX")
    if args.dt is not None:
        raise InputError("--dt does not apply to advise: every sampled speed has its own contact time; give "
                         "--steps-per-contact")
    args.vn = args.vn_range[1]
    scene = scene_from_args(args)
    extra = []
    if args.tangential is not None or args.steps_per_contact is not None or args.model is not None:
        extra.append((scene.tangential, args.steps_per_contact if args.steps_per_contact is not None
                      else default_steps_per_contact(scene)))
    a = advise(scene, tuple(args.vn_range), tuple(args.angle_range), args.spin, args.tol, verify=args.verify,
               scheme=args.scheme or "located", candidates=extra)
    if args.json:
        print(dump_json(a.to_dict()))
        return 0
    print(f"{a.sample_points} sample impacts, tolerance {a.tolerance:g} on f/mu "
          f"(measured against converged MDR)")
    print(f"  {'candidate':22s} {'max |f/mu err|':>15s} {'us/impact':>10s}  meets  description")
    for c in a.candidates:
        err = f"{c.error:15.3e}" if math.isfinite(c.error) else f"{'failed':>15s}"
        print(f"  {c.name:22s} {err} {c.time_us:10.3g}  {'yes' if c.meets else 'no ':3s}    {c.description}")
    if any(not math.isfinite(c.error) for c in a.candidates):
        print("  (failed: the candidate failed numerically on the sample, a blow-up or an e_n outside [0, 1])")
    for w in a.warnings:
        print(f"warning: {w}")
    if a.recommended is None:
        print("no candidate meets the tolerance: use mdr with more springs and steps")
        return 1
    print(f"recommended: {a.recommended.name} ({a.recommended.description})")
    if a.verification:
        v = a.verification
        print(f"verification on {v['points']} random impacts: max |f/mu error| = {v['max_error']:.3e} "
              f"-> {'passed' if v['passed'] else 'FAILED'}")
    return 0
