"""One 3D impact (warm JIT) beside the planar one, same scene and steps: the bare integrator kernels,
default law and the exact reference. Run with ``pytest tests/benchmarks --benchmark-only``."""
import numpy as np
import pytest

import dem_contact as dc
from dem_contact.impacts.impact import body_inertia, time_step
from dem_contact.impacts.impact3d import N_OUT3, N_SERIES3, integrate_impact3d, new_contact_state
from dem_contact.impacts.integrator import N_OUT, N_SERIES, integrate_impact
from dem_contact.laws.model import reference_speed


def _setup(tangential):
    """The scene, time step, steps per contact and inertia of both benchmarks (5 m/s)."""
    sc = dc.Scene(dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL), mu=0.3, tangential=tangential, v_ref=reference_speed(5.0))
    return (sc, *time_step(sc, 5.0), body_inertia(sc))


@pytest.mark.benchmark(group="one impact, planar vs 3D kernel")
@pytest.mark.parametrize("tangential", ["mdr_adaptive", "md"])
def test_bench_planar_kernel(benchmark, tangential):
    sc, dt, spc, (inv_m, R1, R2, iI1, iI2) = _setup(tangential)
    out, ser, h = np.zeros(N_OUT), np.zeros((0, N_SERIES)), sc.new_history()

    def run():
        h[:] = 0.0
        integrate_impact(sc.normal_id, sc.tangential_id, sc.params, h, 5.0, 2.0, -50.0, 0.0,
                         inv_m, R1, R2, iI1, iI2, dt, int(50 * spc), True, out, ser)

    run()
    benchmark(run)
    assert out[0] < 0


@pytest.mark.benchmark(group="one impact, planar vs 3D kernel")
@pytest.mark.parametrize("tangential", ["mdr_adaptive", "md"])
def test_bench_3d_kernel(benchmark, tangential):
    sc, dt, spc, (inv_m, R1, R2, iI1, iI2) = _setup(tangential)
    out, ser = np.zeros(N_OUT3), np.zeros((0, N_SERIES3))
    params, H = new_contact_state(sc)
    w1, w2 = np.array([300.0, -50.0, 20.0]), np.zeros(3)

    def run():
        H[:] = 0.0
        integrate_impact3d(sc.normal_id, sc.tangential_id, params, H, 5.0, 2.0, 0.5, w1, w2, inv_m, R1, R2,
                           iI1, iI2, dt, int(50 * spc), True, True, out, ser)

    run()
    benchmark(run)
    assert out[2] < 0
