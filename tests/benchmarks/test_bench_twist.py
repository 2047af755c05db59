"""Cost of the exact twist law: 3D contact updates per second of Hertz + mdr_adaptive (the default) with no
twist law and with ``deresiewicz``, through ``contact3d.contact_forces_serial`` with relative spins (the
workload of ``test_bench_contact3d``: random orientation, overlap, velocity and spins).

Run: ``pytest tests/benchmarks/test_bench_twist.py --benchmark-only``; updates/s = N_CONTACTS / min
(compare minima of the same run).
"""
import numpy as np
import pytest

from dem_contact.dem.contact3d import contact_forces_serial, new_histories
from dem_contact.dem.pairs import pair_table
from dem_contact.materials import STEEL, Material, Sphere, Wall

N_CONTACTS = 100_000
DT = 2e-7
ROUNDS = 20


@pytest.mark.benchmark(group="contact3d-twist")
@pytest.mark.parametrize("twist", ["none", "deresiewicz"])
def test_bench_twist(benchmark, twist):
    spheres = [Sphere(2e-3, STEEL), Sphere(3e-3, Material(E=70e9, nu=0.33, rho=2700.0))]
    tab = pair_table(spheres, [Wall(STEEL)], mu=0.4, twist=twist)
    rng = np.random.default_rng(0)
    n = N_CONTACTS
    nrm = rng.normal(size=(n, 3))
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    vel = rng.normal(scale=0.05, size=(n, 3))
    delta = rng.uniform(1e-7, 3e-6, size=n)
    wn = rng.normal(scale=100.0, size=n)
    spins = rng.normal(scale=100.0, size=(n, 3))
    pair = rng.integers(0, tab.params.shape[0], size=n)
    H = new_histories(n, tab.history_size)
    f, t, q = np.zeros((n, 3)), np.zeros((n, 3)), np.zeros((n, 3))
    args = (tab.normal_id, tab.tangential_id, tab.params, pair, H, nrm, delta, vel, wn, DT, f, t)
    kw = dict(spins=spins, torques=q)
    contact_forces_serial(*args, **kw)              # compile / load and warm up
    benchmark.pedantic(contact_forces_serial, args=args, kwargs=kw, rounds=ROUNDS, iterations=1, warmup_rounds=2)
    benchmark.extra_info["updates_per_s"] = n / benchmark.stats.stats.min
    benchmark.extra_info["history_bytes_per_contact"] = H.shape[1] * 8
    assert np.all(np.isfinite(q))
    if twist == "none":
        assert not q.any()
    else:
        assert np.abs(q).max() > 0.0
