"""``dem-contact warmup``: compile the impact and sweep kernels once, into numba's cache."""
from __future__ import annotations

import time

ORDER = 90
HELP = "compile the impact and sweep kernels once (after installing)"
DESCRIPTION = ("Compile the kernels of single impacts and sweeps and store them in numba's "
               "cache, so that the first `dem-contact impact` or `sweep` starts at once. The "
               "integrator is compiled per pair of laws (a run compiles only the laws it "
               "uses): by default for the default laws (hertz + mdr_adaptive), with --all "
               "for every normal x tangential pair (a few minutes). Run it once after "
               "installing.")


def add_options(p):
    p.add_argument("--all", action="store_true", help="every normal x tangential law pair, not only the default")


def run(args) -> int:
    from ..impacts.integrator import integrator_for
    from ..impacts.presets import preset_scene
    from ..impacts.sweep import sweep_angles
    from ..laws.model import NORMAL_LAWS, TANGENTIAL_LAWS

    t0 = time.perf_counter()
    sweep_angles(preset_scene("EE", 5.0), [0.0, 30.0], 5.0)
    pairs = [(n, t) for n in NORMAL_LAWS.values() for t in TANGENTIAL_LAWS.values()] if args.all else []
    for k, (nid, tid) in enumerate(pairs, start=1):
        integrator_for(nid, tid)
        print(f"\r{k} of {len(pairs)} law pairs", end="", flush=True)
    if pairs:
        print()
    print(f"impact and sweep kernels ready ({1 + len(pairs)} law pair{'s' if pairs else ''}) in "
          f"{time.perf_counter() - t0:.1f} s")
    return 0
