"""Speed of the 3D contact kernels: contact updates per second on one core.

Every law runs through ``contact3d.contact_forces_serial`` (the batch loop on one thread) over
N_CONTACTS contacts of random orientation, overlap and relative velocity; each round advances every
contact by one step.

Run: ``pytest tests/benchmarks/test_bench_contact3d.py --benchmark-only``; updates/s = N_CONTACTS / mean.
"""
import numpy as np
import pytest

from dem_contact.dem.contact3d import contact_forces_serial, new_histories
from dem_contact.materials import STEEL, Material, Sphere, Wall
from dem_contact.laws.model import NORMAL_LAWS, TANGENTIAL_LAWS
from dem_contact.dem.pairs import pair_table

N_CONTACTS = 100_000
DT = 2e-7


def _workload(tangential, normal="hertz", n=N_CONTACTS):
    spheres = [Sphere(2e-3, STEEL), Sphere(3e-3, Material(E=70e9, nu=0.33, rho=2700.0, yield_pressure=1e9))]
    tab = pair_table(spheres, [Wall(STEEL)], mu=0.4, normal=normal, tangential=tangential, e_n=0.8, v_ref=1.0)
    rng = np.random.default_rng(0)
    nrm = rng.normal(size=(n, 3))
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    vel = rng.normal(scale=0.05, size=(n, 3))
    delta = rng.uniform(1e-7, 3e-6, size=n)
    wn = rng.normal(scale=100.0, size=n)          # mean spin about the normal [rad/s]
    pair = rng.integers(0, tab.params.shape[0], size=n)
    H = new_histories(n, tab.history_size)
    return tab, pair, H, nrm, delta, vel, wn, np.zeros((n, 3)), np.zeros((n, 3))


def _run_numba(benchmark, tangential, normal="hertz"):
    tab, pair, H, nrm, delta, vel, wn, f, t = _workload(tangential, normal)
    args = (tab.normal_id, tab.tangential_id, tab.params, pair, H, nrm, delta, vel, wn, DT, f, t)
    contact_forces_serial(*args)              # compile / load and warm up
    benchmark.pedantic(contact_forces_serial, args=args, rounds=20, iterations=1, warmup_rounds=2)
    benchmark.extra_info["updates_per_s"] = N_CONTACTS / benchmark.stats.stats.mean
    return N_CONTACTS / benchmark.stats.stats.mean


@pytest.mark.benchmark(group="contact3d-tangential")
@pytest.mark.parametrize("tangential", list(TANGENTIAL_LAWS))
def test_bench_batch_tangential(benchmark, tangential):
    _run_numba(benchmark, tangential)


@pytest.mark.benchmark(group="contact3d-normal")
@pytest.mark.parametrize("normal", list(NORMAL_LAWS))
def test_bench_batch_normal(benchmark, normal):
    _run_numba(benchmark, "md", normal)
