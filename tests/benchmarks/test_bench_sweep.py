"""Benchmarks: the 86-angle EE sweep (0-85 deg, 5 m/s, default law and time step) with its fit, warm JIT,
on 1 and 2 threads. Run: .venv/bin/pytest tests/benchmarks/test_bench_sweep.py --benchmark-only"""
import numba
import numpy as np
import pytest

from dem_contact.impacts.presets import preset_scene
from dem_contact.rebound.fit import fit_wu
from dem_contact.impacts.sweep import sweep_angles

ANGLES = np.arange(0.0, 85.5, 1.0)


def sweep_and_fit(scene):
    res = sweep_angles(scene, ANGLES, 5.0)
    return fit_wu(res.Theta, res.f_over_mu, res.persistent_sliding)


def _with_threads(benchmark, threads, group, fn, scene):
    if threads > numba.config.NUMBA_NUM_THREADS:
        pytest.skip(f"only {numba.config.NUMBA_NUM_THREADS} threads")
    fn(scene)  # warm the JIT
    old = numba.get_num_threads()
    numba.set_num_threads(threads)
    try:
        benchmark.group = group
        return benchmark(fn, scene)
    finally:
        numba.set_num_threads(old)


@pytest.mark.parametrize("threads", [1, 2])
def test_bench_ee_sweep_fit(benchmark, threads):
    fit = _with_threads(benchmark, threads, "EE 86-angle sweep + fit", sweep_and_fit, preset_scene("EE", 5.0))
    assert 5.0 < fit.Theta_c < 7.0


@pytest.mark.parametrize("threads", [1, 2])
def test_bench_ee_sweep_only(benchmark, threads):
    res = _with_threads(benchmark, threads, "EE 86-angle sweep", lambda s: sweep_angles(s, ANGLES, 5.0),
                        preset_scene("EE", 5.0))
    assert len(res) == 86
