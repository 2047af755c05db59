"""``dem-contact warmup``: compile the impact and sweep kernels once, into numba's cache."""
from __future__ import annotations

import time

ORDER = 90


def add_parser(sub):
    p = sub.add_parser("warmup", help="compile the impact and sweep kernels once (after installing)",
                       description="Compile the kernels of single impacts and sweeps (every normal and tangential "
                                   "law: the law is chosen when a kernel runs) and store them in numba's cache, so "
                                   "that the first `dem-contact impact` or `sweep` starts at once. Run it once "
                                   "after installing; it takes seconds to tens of seconds.")
    p.set_defaults(run=run)


def run(args) -> int:
    from ..impacts.presets import preset_scene
    from ..impacts.sweep import sweep_kernel, sweep_angles

    t0 = time.perf_counter()
    sweep_angles(preset_scene("EE", 5.0), [0.0, 30.0], 5.0)
    print(f"impact and sweep kernels ready ({len(sweep_kernel.signatures)} compiled) in "
          f"{time.perf_counter() - t0:.1f} s")
    return 0
