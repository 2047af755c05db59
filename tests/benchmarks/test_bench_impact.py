"""One impact at default settings (warm JIT): the Python call and the bare integrator kernel.

Run with ``pytest tests/benchmarks --benchmark-only``.
"""
import numpy as np
import pytest

import dem_contact as dc
from dem_contact.impacts.impact import body_row, max_steps, time_step
from dem_contact.impacts.integrator import N_OUT, N_SERIES, impact_kernel
from dem_contact.impacts.presets import preset_scene


@pytest.fixture(scope="module")
def scene():
    return dc.Scene(dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL), mu=0.3)


@pytest.mark.benchmark(group="one impact")
def test_bench_impact_python(benchmark, scene):
    dc.impact(scene, 5.0, 2.0)  # warm the JIT
    r = benchmark(dc.impact, scene, 5.0, 2.0)
    assert abs(r.e_n - 1) < 1e-4


def _kernel(sc):
    """The jitted kernel of ``impact`` on one impact of ``sc`` (vn = 5, vt = 2 m/s) from a clean history, run
    once (warm JIT); returns (args, out): ``impact_kernel(*args)`` runs it."""
    dt, spc = time_step(sc, 5.0)
    out = np.zeros(N_OUT)
    ser = np.zeros((0, N_SERIES))
    args = (body_row(sc), sc.params, sc.new_history(), 5.0, 2.0, 0.0, 0.0, dt, max_steps(spc), True, out, ser)
    impact_kernel(*args)
    return args, out


@pytest.mark.benchmark(group="one impact")
def test_bench_impact_kernel(benchmark, scene):
    args, out = _kernel(scene)
    benchmark(impact_kernel, *args)
    assert out[0] < 0


@pytest.mark.benchmark(group="plastic impact, mdr_adaptive Coulomb-limit profile")
@pytest.mark.parametrize("profile", ["truncated", "scaled"])
def test_bench_pe_profile(benchmark, profile):
    """PE at 5 m/s (plastic loading): the truncated pressure's line load against the Hertz shape."""
    args, out = _kernel(preset_scene("PE", 5.0, mdr_profile=profile))
    benchmark(impact_kernel, *args)
    assert out[0] < 0
