"""One impact at default settings (warm JIT): the Python call and the bare integrator kernel.

Run with ``pytest tests/benchmarks --benchmark-only``.
"""
import numpy as np
import pytest

import dem_contact as dc
from dem_contact.impacts.impact import body_row, max_steps, time_step
from dem_contact.impacts.integrator import N_OUT, N_SERIES, integrator_for
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
    """The jitted kernel of ``impact`` (``integrator_for`` the scene's laws: it zeroes the history, then
    integrates) on one impact of ``sc`` (vn = 5, vt = 2 m/s), run once (warm JIT); returns (kernel, args,
    out): ``kernel(*args)`` runs it."""
    dt, spc = time_step(sc, 5.0)
    out = np.zeros(N_OUT)
    ser = np.zeros((0, N_SERIES))
    kernel = integrator_for(sc.normal_id, sc.tangential_id)
    args = (sc.params, sc.new_history(), body_row(sc), 5.0, 2.0, 0.0, 0.0, dt, max_steps(spc), True, out, ser)
    kernel(*args)
    return kernel, args, out


@pytest.mark.benchmark(group="one impact")
def test_bench_impact_kernel(benchmark, scene):
    kernel, args, out = _kernel(scene)
    benchmark(kernel, *args)
    assert out[0] < 0


@pytest.mark.benchmark(group="plastic impact, mdr_adaptive Coulomb-limit profile")
@pytest.mark.parametrize("profile", ["truncated", "scaled"])
def test_bench_pe_profile(benchmark, profile):
    """PE at 5 m/s (plastic loading): the truncated pressure's line load against the Hertz shape."""
    kernel, args, out = _kernel(preset_scene("PE", 5.0, mdr_profile=profile))
    benchmark(kernel, *args)
    assert out[0] < 0
