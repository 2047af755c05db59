"""Time per step of the boundary-element reference (dem_contact.reference.bem): a partial-slip step at
constant overlap, steel on steel, warm-started from the previous step, at 32, 64 and 128 elements across,
for a tangential displacement step and for a twist step about the normal.

Run: ``pytest tests/benchmarks/test_bench_bem.py --benchmark-only``.
"""
import math

import pytest

from dem_contact.reference.bem import TangentialBEM
from dem_contact.reference.paths import no_slip_twist, twist_modulus

E, NU, R, MU, DELTA = 208e9, 0.3, 0.005, 0.3, 2e-6


@pytest.mark.benchmark(group="BEM: one partial-slip step")
@pytest.mark.parametrize("load", ["shear", "twist"])
@pytest.mark.parametrize("n_across", [32, 64, 128])
def test_bench_bem_step(benchmark, n_across, load):
    solver = TangentialBEM(E, NU, E, NU, R, MU, math.sqrt(R * DELTA), n_across=n_across)
    if load == "shear":             # steps of the slip displacement
        unit = MU * DELTA * solver.E_star / (4 * solver.G_star)
        inc = (0.3 * unit, 0.0, 0.0)
        step = (0.02 * unit, 0.0, 0.0)
    else:                           # steps of the no-slip twist at unit moment beta_1 (comparable partial slip)
        unit = no_slip_twist(DELTA, MU, R, solver.E_star, twist_modulus(E, NU, E, NU))
        inc = (0.0, 0.0, 0.3 * unit)
        step = (0.0, 0.0, 0.02 * unit)
    state = {"u": 0.0}

    def setup():                # load to 0.3 units, then time the next step of 0.02 (reset every 20 steps)
        if state["u"] == 0.0 or state["u"] > 0.7 * unit:
            solver.reset()
            solver.step(DELTA, 0.0, 0.0)
            solver.step(DELTA, *inc)
            state["u"] = 0.3 * unit
        state["u"] += 0.02 * unit

    benchmark.pedantic(lambda: solver.step(DELTA, *step), setup=setup, rounds=10, warmup_rounds=1)
    assert solver.iterations > 0
