"""One impact at default settings (warm JIT): the Python call and the bare integrator kernel.

Run with ``pytest tests/benchmarks --benchmark-only``.
"""
import numpy as np
import pytest

import dem_contact as dc
from dem_contact.impacts.impact import body_inertia, time_step
from dem_contact.impacts.integrator import N_OUT, N_SERIES, integrate_impact
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
    """The bare integrator on one impact of ``sc`` (vn = 5, vt = 2 m/s), run once (warm JIT); returns
    (run, out)."""
    dt, spc = time_step(sc, 5.0)
    inv_m, R1, R2, iI1, iI2 = body_inertia(sc)
    out = np.zeros(N_OUT)
    ser = np.zeros((0, N_SERIES))
    h = sc.new_history()

    def run():
        h[:] = 0.0
        integrate_impact(sc.normal_id, sc.tangential_id, sc.params, h, 5.0, 2.0, 0.0, 0.0,
                         inv_m, R1, R2, iI1, iI2, dt, int(50 * spc), True, out, ser)
    run()
    return run, out


@pytest.mark.benchmark(group="one impact")
def test_bench_impact_kernel(benchmark, scene):
    run, out = _kernel(scene)
    benchmark(run)
    assert out[0] < 0


@pytest.mark.benchmark(group="plastic impact, mdr_adaptive Coulomb-limit profile")
@pytest.mark.parametrize("profile", ["truncated", "scaled"])
def test_bench_pe_profile(benchmark, profile):
    """PE at 5 m/s (plastic loading): the truncated pressure's line load against the Hertz shape."""
    run, out = _kernel(preset_scene("PE", 5.0, mdr_profile=profile))
    benchmark(run)
    assert out[0] < 0
