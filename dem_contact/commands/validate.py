"""``dem-contact validate``: reproduce the published cases of Wu, Thornton & Li (2009) and write a report."""
from __future__ import annotations

from .common import add_out_dir, check_output_dir

ORDER = 3
HELP = "reproduce the published oblique-impact cases, write a report"
DESCRIPTION = ("Simulate every published case of Wu, Thornton & Li (2009) (RE, EE, PE), "
               "fit eq. 4.5, compare with the published fits, compare all tangential laws "
               "on EE 5 m/s, check universality in mu and V_n, and write OUT/report.md "
               "with figures in OUT/figures/.")


def add_options(p):
    add_out_dir(p, "validation")
    p.add_argument("--quick", action="store_true",
                   help="coarser grids (impact angles every 5 deg instead of 1, 17 instead of 81 values of Theta "
                        "in the universality check, 2 instead of 5 time steps): every section in a fraction of "
                        "the time, with wider fit uncertainties; the report states the grids")


def run(args) -> int:
    from ..studies.wu2009 import FULL, QUICK, run_validation

    check_output_dir("--out", args.out)
    print(f"report written to {run_validation(args.out, grids=QUICK if args.quick else FULL)}")
    return 0
