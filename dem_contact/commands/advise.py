"""``dem-contact advise``: the cheapest model of the rebound that meets a tolerance, from measured data."""
from __future__ import annotations

from .common import add_scene_options, dump_json, scene_from_args

ORDER = 5


def add_parser(sub):
    p = sub.add_parser("advise", help="recommend the cheapest model meeting a tolerance on the rebound",
                       description="Integrate a sample of the speed and angle ranges with the exact MDR "
                                   "reference, measure the error in f/mu (= error in Omega_r; e_t and Psi_r "
                                   "follow from it) and the time per impact of each candidate (rigid-body "
                                   "sliding, the Wu et al. model fitted to the sample, cheap laws at coarse "
                                   "steps, the reference itself) and recommend the cheapest within --tol.")
    add_scene_options(p)
    p.add_argument("--vn-range", nargs=2, type=float, default=[1.0, 5.0], metavar=("MIN", "MAX"),
                   help="normal speed range [m/s] (default 1 5)")
    p.add_argument("--angle-range", nargs=2, type=float, default=[0.0, 60.0], metavar=("MIN", "MAX"),
                   help="impact angle range from the normal [deg] (default 0 60)")
    p.add_argument("--spin", type=float, default=0.0, help="initial spin [rad/s] (default 0)")
    p.add_argument("--tol", type=float, default=0.01, help="tolerance on f/mu (default 0.01)")
    p.add_argument("--verify", action="store_true", help="run the recommendation against MDR on a random sample")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=run)


def run(args) -> int:
    from ..studies.advise import advise

    args.vn = args.vn_range[1]
    scene = scene_from_args(args)
    a = advise(scene, tuple(args.vn_range), tuple(args.angle_range), args.spin, args.tol, verify=args.verify)
    if args.json:
        print(dump_json(a.to_dict()))
        return 0
    print(f"{a.sample_points} sample impacts, tolerance {a.tolerance:g} on f/mu "
          f"(measured against converged MDR)")
    print(f"  {'candidate':22s} {'max |f/mu err|':>15s} {'us/impact':>10s}  meets  description")
    for c in a.candidates:
        print(f"  {c.name:22s} {c.error:15.3e} {c.time_us:10.3g}  {'yes' if c.meets else 'no ':3s}    {c.description}")
    if a.recommended is None:
        print("no candidate meets the tolerance: use mdr with more springs and steps")
        return 1
    print(f"recommended: {a.recommended.name} ({a.recommended.description})")
    if a.verification:
        v = a.verification
        print(f"verification on {v['points']} random impacts: max |f/mu error| = {v['max_error']:.3e} "
              f"-> {'passed' if v['passed'] else 'FAILED'}")
    return 0
