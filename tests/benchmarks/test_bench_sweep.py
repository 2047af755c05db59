"""Benchmarks: EE sweeps (5 m/s, default law and time step) with warm JIT: the 86-angle sweep (0-85 deg)
with and without its fit, 10,000 angles on 1 and 2 threads (the whole sweep: checks, kernel, result
arrays), 85,001 angles with progress, and the fit alone.
Run: pytest tests/benchmarks/test_bench_sweep.py --benchmark-only"""
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


@pytest.mark.parametrize("threads", [1, 2])
def test_bench_sweep_10k(benchmark, threads):
    angles = np.linspace(0.0, 85.0, 10000)
    res = _with_threads(benchmark, threads, "EE 10,000-angle sweep", lambda s: sweep_angles(s, angles, 5.0),
                        preset_scene("EE", 5.0))
    assert len(res) == 10000 and np.all(np.diff(res.Theta) > 0)


def test_bench_sweep_85001_progress(benchmark):
    scene = preset_scene("EE", 5.0)
    angles = np.linspace(0.0, 85.0, 85001)
    sweep_angles(scene, angles[:10], 5.0)
    benchmark.group = "EE 85,001-angle sweep"
    res = benchmark.pedantic(sweep_angles, args=(scene, angles, 5.0), kwargs=dict(progress=True), rounds=3)
    assert len(res) == 85001


def test_bench_fit_86(benchmark):
    scene = preset_scene("EE", 5.0)
    res = sweep_angles(scene, ANGLES, 5.0)
    benchmark.group = "fit of eq. 4.5, 86 angles"
    fit = benchmark(fit_wu, res.Theta, res.f_over_mu, res.persistent_sliding)
    assert 5.0 < fit.Theta_c < 7.0
