"""The contract every twist and rolling law of the table passes (``laws.table``, families ``twist`` and
``rolling``): a law added as one file plus one row gets these tests without an edit here, on a contact of
its declared ``EXAMPLE`` settings (a 2 mm steel sphere on a steel wall, Hertz and Mindlin's total law, the
overlap held, the bodies turning with a random relative spin):

- objective: a rigid rotation of the normal and the spins rotates the torque;
- no energy created: over a periodic spin history (each pass returns the twist and rolling angles to where
  they were), the work the torque absorbs per pass is never negative once the state repeats;
- its limit: the torque never exceeds the law's ``max_torque`` at the step's normal force and contact radius;
- swapping the bodies twice is the identity, and the swapped contact feels the opposite torque (action and
  reaction); a history saved and loaded carries on bit for bit.
"""
import io

import numpy as np
import pytest

from dem_contact.dem.contact3d import contact_force_torque, swap_bodies
from dem_contact.laws import table
from dem_contact.laws.model import Scene
from dem_contact.laws.vector import V_A
from dem_contact.materials import STEEL, Sphere, Wall
from conftest import scene_history

LAWS = [(family, m.NAME) for family in ("twist", "rolling") for m in table.FAMILIES[family] if m.NAME != "none"]
DELTA = 2e-6        # overlap [m]
DT = 1e-6           # time step [s]
STEPS = 150         # steps of one pass of the spin history


def _scene(family, name):
    law = table.law(family, name)
    return Scene(Sphere(2e-3, STEEL), Wall(STEEL), mu=0.3, tangential="mindlin_total", **{family: name},
                 **law.EXAMPLE)


def _spins(seed, scale=300.0):
    """float64[STEPS, 3]: a smooth periodic relative spin [rad/s] with no mean (its angle returns each pass)."""
    rng = np.random.default_rng(seed)
    s = np.arange(STEPS) / STEPS
    w = np.zeros((STEPS, 3))
    for k in range(1, 4):
        w += np.outer(np.sin(2 * np.pi * k * s), rng.normal(size=3)) + np.outer(np.cos(2 * np.pi * k * s),
                                                                                  rng.normal(size=3))
    return scale * w


def _unit(seed):
    n = np.random.default_rng(seed).normal(size=3)
    return n / np.linalg.norm(n)


def _step(sc, H, n, w):
    """One step of the contact (no sliding velocity): (force, torque) on body 1."""
    out = contact_force_torque(sc.normal_id, sc.tangential_id, sc.params[None, :], 0, H, 0, *n, DELTA,
                               0.0, 0.0, 0.0, *w, 0.0, DT)
    return np.array(out[:3]), np.array(out[6:])


def _run(sc, H, n, spins):
    return [_step(sc, H, n, w) for w in spins]


def _rotation(seed):
    rng = np.random.default_rng(seed)
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


@pytest.mark.parametrize("family,name", LAWS)
def test_torque_is_objective(family, name):
    sc = _scene(family, name)
    n, spins, Q = _unit(1), _spins(2), _rotation(3)
    a = _run(sc, scene_history(sc), n, spins)
    b = _run(sc, scene_history(sc), Q @ n, spins @ Q.T)
    scale = max(np.abs(m).max() for _, m in a)
    assert scale > 0.0
    err = max(np.abs(Q @ ma - mb).max() for (_, ma), (_, mb) in zip(a, b))
    assert err <= 1e-9 * scale, (name, err, scale)


@pytest.mark.parametrize("family,name", LAWS)
def test_no_energy_created_on_periodic_spin(family, name):
    """The work absorbed by the torque, sum of -M . w dt, over the last of several passes of a periodic
    spin history is >= 0 (to 1e-9 of the work that went through the contact in that pass)."""
    sc = _scene(family, name)
    n = _unit(4)
    for seed in (5, 6, 7):
        spins = _spins(seed)
        H = scene_history(sc)
        for _ in range(5):
            work = gross = 0.0
            for w in spins:
                _, m = _step(sc, H, n, w)
                work -= float(m @ w) * DT
                gross += abs(float(m @ w)) * DT
        assert gross > 0.0 and work >= -1e-9 * gross, (name, seed, work, gross)


@pytest.mark.parametrize("family,name", LAWS)
def test_torque_within_the_laws_limit(family, name):
    """|M| <= max_torque(p, N, a) at every step, with N and a of that step (a limit the run reaches)."""
    sc = _scene(family, name)
    law = table.law(family, name)
    n = _unit(8)
    H = scene_history(sc)
    p = sc.params
    worst = 0.0
    for w in np.vstack([_spins(9, scale=3e4)] * 2):
        f, m = _step(sc, H, n, w)
        N = -float(f @ n)
        cap = law.max_torque(p, N, H[0, V_A])
        assert np.linalg.norm(m) <= cap * (1.0 + 1e-12), (name, np.linalg.norm(m), cap)
        worst = max(worst, np.linalg.norm(m) / cap)
    assert worst > 0.99, (name, worst)              # the limit is reached: the check is not empty


@pytest.mark.parametrize("family,name", LAWS)
def test_swap_and_a_saved_history(family, name):
    sc = _scene(family, name)
    n, spins = _unit(10), _spins(11)
    H = scene_history(sc)
    _run(sc, H, n, spins[:60])
    H0 = H.copy()
    swap_bodies(sc.normal_id, sc.tangential_id, sc.params[None, :], 0, H, 0)
    swapped = H.copy()
    swap_bodies(sc.normal_id, sc.tangential_id, sc.params[None, :], 0, H, 0)
    assert np.array_equal(H, H0)
    # action and reaction: the swapped contact (normal -n, relative spin -w) feels -M
    for w in spins[60:90]:
        _, m1 = _step(sc, H, n, w)
        _, m2 = _step(sc, swapped, -n, -w)
        assert np.abs(m1 + m2).max() <= 1e-12 * max(np.abs(m1).max(), 1e-300), (name, m1, m2)
    # a history saved and loaded carries on bit for bit
    buf = io.BytesIO()
    np.save(buf, H)
    buf.seek(0)
    loaded = np.load(buf)
    a = _run(sc, H, n, spins[90:])
    b = _run(sc, loaded, n, spins[90:])
    assert all(np.array_equal(ma, mb) and np.array_equal(fa, fb) for (fa, ma), (fb, mb) in zip(a, b))
