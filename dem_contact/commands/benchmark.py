"""``dem-contact benchmark chung-ooi``: the impact-level benchmark tests of Chung & Ooi (2011)."""
from __future__ import annotations

import os

from ..errors import InputError
from ..materials import check_finite
from .common import check_output_dir, check_output_file, dump_json

ORDER = 6

SUITES = ("chung-ooi",)

HELP = "run published benchmark suites (Chung & Ooi 2011)"
DESCRIPTION = ("Run the eight impact-level tests of Chung & Ooi (2011, Granular Matter "
               "13:643) and print one line per check against its analytic answer "
               "(pass/fail). SI units.")


def add_options(p):
    p.add_argument("suite", choices=SUITES, help="benchmark suite")
    p.add_argument("--test", type=int, action="append", default=None, metavar="N",
                   help="run test N (1-8) only; repeat for several (default: all)")
    p.add_argument("--steps-per-contact", type=float, default=None,
                   help="steps per elastic contact time (default 1000)")
    p.add_argument("--json", action="store_true", help="print one JSON object with the curves and checks")
    p.add_argument("--plot", metavar="DIR", default=None, help="write the figures (PNG) to DIR")
    p.add_argument("--report", metavar="FILE", default=None,
                   help="write a markdown report to FILE (with --plot: the figures are linked)")


def run(args) -> int:
    from ..studies import chung_ooi as co

    tests = args.test or list(co.TESTS)
    for n in tests:
        if n not in co.TESTS:
            raise InputError(f"--test {n} is not a Chung & Ooi test: valid tests 1-8")
    if args.steps_per_contact is not None:
        check_finite("--steps-per-contact", args.steps_per_contact, lo=2.0, lo_open=False)
    if args.plot:
        check_output_dir("--plot", args.plot)
    if args.report:
        check_output_file("--report", args.report)
    results = co.run_suite(tests, args.steps_per_contact)
    figures = {}
    if args.plot:
        from ..plots import chung_ooi_figure

        os.makedirs(args.plot, exist_ok=True)
        for res in results:
            figures[res.test] = chung_ooi_figure(res, os.path.join(args.plot, f"test{res.test}.png"))
    if args.report:
        base = os.path.dirname(os.path.abspath(args.report))
        rel = {t: [os.path.relpath(os.path.abspath(f), base) for f in fs] for t, fs in figures.items()}
        cmd = "dem-contact benchmark chung-ooi" + "".join(f" --test {n}" for n in (args.test or [])) + (
            f" --plot {args.plot}" if args.plot else "") + f" --report {args.report}"
        with open(args.report, "w") as fh:
            fh.write(co.report_markdown(results, rel, cmd))
    if args.json:
        print(dump_json({"suite": "chung-ooi", "tests": [r.to_dict() for r in results],
                         "passed": all(r.passed for r in results)}))
        return 0
    for line in co.summary_lines(results):
        print(line)
    for res in results:
        for note in res.notes:
            print(f"note (test {res.test}): {note}")
    return 0
