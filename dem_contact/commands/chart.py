"""``dem-contact chart``: speed-accuracy chart of the tangential laws against converged MDR."""
from __future__ import annotations

import os
import sys

from ..errors import InputError
from ..laws.model import NORMAL_LAWS
from .common import add_out_dir, check_output_dir

ORDER = 4
HELP = "speed-accuracy chart of the tangential laws (error vs time per impact)"
DESCRIPTION = ("For every tangential law, the hertz and thornton normal laws and both "
               "integrator ends, integrate a grid of Theta in [0, 10] (EE steel scene, "
               "vn = 5 m/s) at several steps per contact; report the max error in f/mu, "
               "e_t, Omega_r and e_n against converged MDR, split into model and "
               "discretisation error, and the measured time per impact. Writes a CSV and "
               "a PNG. The default is a quick subset (about a minute); --full runs the "
               "whole chart.")


def add_options(p):
    add_out_dir(p, "chart")
    p.add_argument("--full", action="store_true",
                   help="all steps per contact from 5 to 1e4 and 41 values of Theta")
    p.add_argument("--laws", nargs="+", default=None, help="tangential laws (default: all)")
    p.add_argument("--normals", nargs="+", default=None, choices=list(NORMAL_LAWS),
                   help="normal laws (default: hertz thornton; the laws that take e_n are set for e_n = 0.7)")
    p.add_argument("--steps", nargs="+", type=float, default=None,
                   help="steps per contact (default 5 20 100 1000; --full: 5 ... 10000)")
    p.add_argument("--n-theta", type=int, default=None, help="number of Theta values (default 11; --full 41)")
    p.add_argument("--repeats", type=int, default=None, help="timing repeats, best kept (default 3)")
    p.add_argument("--stability", action="store_true",
                   help="instead: the stability map (every law and integrator end at extreme settings: "
                        "blow-up, energy creation, Coulomb excess, accuracy loss); writes stability.csv/png")


def run(args) -> int:
    from ..studies import chart
    from ..plots import speed_accuracy_figure

    if args.stability:
        given = [name for name, v in (("--full", args.full or None), ("--normals", args.normals),
                                      ("--steps", args.steps), ("--n-theta", args.n_theta),
                                      ("--repeats", args.repeats)) if v is not None]
        if given:
            raise InputError(f"{', '.join(given)} cannot act with --stability (the stability map has its own "
                             f"settings; it takes --laws)")
    check_output_dir("--out", args.out)
    if args.stability:
        return run_stability(args)
    steps = args.steps or (chart.FULL_STEPS if args.full else chart.DEFAULT_STEPS)
    n_theta = args.n_theta or (41 if args.full else 11)
    repeats = 3 if args.repeats is None else args.repeats
    if repeats < 1:
        raise InputError("--repeats must be >= 1")
    rows = chart.chart(laws=args.laws, normals=args.normals or list(chart.NORMALS), steps=steps, n_theta=n_theta,
                       repeats=repeats,
                       progress=lambda s: print(f"  {s}", file=sys.stderr, flush=True))
    os.makedirs(args.out, exist_ok=True)
    csv_path = os.path.join(args.out, "speed_accuracy.csv")
    chart.write_csv(rows, csv_path)
    png = speed_accuracy_figure(rows, os.path.join(args.out, "speed_accuracy.png"))
    print(f"{'normal':9s} {'tangential':20s} {'scheme':9s} {'steps':>7s} {'f/mu err':>9s} {'model':>9s} "
          f"{'discr.':>9s} {'e_n err':>9s} {'us/impact':>9s}")
    for r in rows:
        print(f"{r.normal:9s} {r.tangential:20s} {r.scheme:9s} {r.steps_per_contact:7g} {r.err_f_over_mu:9.2e} "
              f"{r.model_err_f_over_mu:9.2e} {r.discretisation_err_f_over_mu:9.2e} {r.err_e_n:9.2e} "
              f"{r.time_per_impact_us:9.3g}{'  Pareto' if r.pareto else ''}")
    print(f"wrote {csv_path} and {png}")
    return 0


def run_stability(args) -> int:
    from ..studies import chart
    from ..studies import stability
    from ..plots import stability_figure

    rows = stability.stability_map(laws=args.laws)
    os.makedirs(args.out, exist_ok=True)
    csv_path = os.path.join(args.out, "stability.csv")
    chart.write_csv(rows, csv_path)
    png = stability_figure(rows, os.path.join(args.out, "stability.png"))
    for r in rows:
        if r.outcome != "ok":
            print(f"{r.case:24s} {r.tangential:20s} {r.scheme:9s} {r.outcome:10s} {r.detail}")
    print(f"{sum(r.outcome == 'ok' for r in rows)} of {len(rows)} runs ok; wrote {csv_path} and {png}")
    return 0
