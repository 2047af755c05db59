"""One impact with the default tangential law at default settings, and one with the exact reference (mdr)
at its 4-digit settings (bare integrator kernel, warm JIT). EE steel scene, vn = 5 m/s, Theta = 1.

Run: ``pytest tests/benchmarks/test_bench_laws.py --benchmark-only``.
"""
import numpy as np
import pytest

import dem_contact as dc
from dem_contact.impacts.impact import DEFAULT_STEPS_PER_CONTACT, body_inertia
from dem_contact.impacts.integrator import N_OUT, N_SERIES, integrate_impact
from dem_contact.laws.model import MDR_STEPS_PER_CONTACT

VN = 5.0
VT = 0.3 * VN   # Theta = 1 with e_n = 1


def _kernel(scene, spc):
    inv_m, R1, R2, iI1, iI2 = body_inertia(scene)
    dt = scene.contact_time(VN) / spc
    out = np.zeros(N_OUT)
    ser = np.zeros((0, N_SERIES))
    h = scene.new_history()

    def run():
        h[:] = 0.0
        integrate_impact(scene.normal_id, scene.tangential_id, scene.params, h, VN, VT, 0.0, 0.0,
                         inv_m, R1, R2, iI1, iI2, dt, int(50 * spc), True, out, ser)

    run()
    return run, out


@pytest.mark.benchmark(group="tangential laws: one impact")
def test_bench_default_law(benchmark):
    sc = dc.Scene(dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL), mu=0.3)
    run, out = _kernel(sc, DEFAULT_STEPS_PER_CONTACT)
    benchmark(run)
    assert out[0] < 0


@pytest.mark.benchmark(group="tangential laws: one impact")
def test_bench_mdr_4_digits(benchmark):
    sc = dc.Scene(dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL), mu=0.3, tangential="mdr", v_ref=VN)
    run, out = _kernel(sc, MDR_STEPS_PER_CONTACT)
    benchmark(run)
    assert out[0] < 0


@pytest.mark.benchmark(group="tangential laws: one impact")
def test_bench_md_1000_steps(benchmark):
    sc = dc.Scene(dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL), mu=0.3, tangential="md")
    run, out = _kernel(sc, 1000)
    benchmark(run)
    assert out[0] < 0
