"""Time per step of the boundary-element reference (dem_contact.reference.bem): a partial-slip step at
constant overlap, steel on steel, warm-started from the previous step, at 32, 64 and 128 elements across.

Run: ``pytest tests/benchmarks/test_bench_bem.py --benchmark-only``.
"""
import math

import pytest

from dem_contact.reference.bem import TangentialBEM

E, NU, R, MU, DELTA = 208e9, 0.3, 0.005, 0.3, 2e-6


@pytest.mark.benchmark(group="BEM: one partial-slip step")
@pytest.mark.parametrize("n_across", [32, 64, 128])
def test_bench_bem_step(benchmark, n_across):
    solver = TangentialBEM(E, NU, E, NU, R, MU, math.sqrt(R * DELTA), n_across=n_across)
    s = MU * DELTA * solver.E_star / (4 * solver.G_star)      # slip displacement
    state = {"u": 0.0}

    def setup():                # load to 0.3 s, then time the next step of 0.02 s (reset every 20 steps)
        if state["u"] == 0.0 or state["u"] > 0.7 * s:
            solver.reset()
            solver.step(DELTA, 0.0, 0.0)
            solver.step(DELTA, 0.3 * s, 0.0)
            state["u"] = 0.3 * s
        state["u"] += 0.02 * s

    benchmark.pedantic(lambda: solver.step(DELTA, 0.02 * s, 0.0), setup=setup, rounds=10, warmup_rounds=1)
    assert solver.iterations > 0
