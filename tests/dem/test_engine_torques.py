"""LAMMPS's twist and rolling engine models (``laws.twist.marshall``, ``laws.twist.sds``,
``laws.rolling.sds``) in the 3D kernels: their closed forms (stiffness, slider limit), the history slots
laid out before the tangential law's, bodies swapped (Newton's third law, the twist angle and the rolling
displacement kept), a rigid rotation of the whole contact (objectivity), and the checked settings. Their
equivalence with LAMMPS's own is tests/lammps/test_lammps.py (a pour against native pair granular)."""
import math

import numpy as np
import pytest

from dem_contact.dem.contact3d import (check_contacts, contact_forces, contact_forces_batch, contact_forces_serial,
                                      new_histories, rotate_history, swap_bodies, tangential_work)
from dem_contact.dem.pairs import pair_table
from dem_contact.errors import InputError
from dem_contact.laws import table
from dem_contact.laws.model import Scene
from dem_contact.materials import STEEL, Sphere, Wall

R = 1e-3
SDS = dict(twist="sds", k_twist=1.0, gamma_twist=0.0, mu_twist=1e-4, rolling="sds", k_roll=5e5, gamma_roll=0.0,
           mu_roll=0.05)


def _table(**laws):
    return pair_table([Sphere(R, STEEL)], [Wall(STEEL)], mu=0.3, tangential="mindlin_total", **laws)


def _steps(tab, H, n, w, steps, delta=1e-6, dt=1e-7, v=(0.0, 0.0, 0.0), row=0):
    """``steps`` steps of one contact (normal n, overlap delta, relative velocity v, relative spin w):
    the force and the torque of the twist and rolling laws on body 1 at the last."""
    one = lambda x: np.ascontiguousarray(np.asarray(x, dtype=float).reshape(1, 3))
    f, ft, m = np.zeros((1, 3)), np.zeros((1, 3)), np.zeros((1, 3))
    for _ in range(steps):
        contact_forces_serial(tab.normal_id, tab.tangential_id, tab.params, np.array([row]), H, one(n),
                              np.array([delta]), one(v), np.zeros(1), dt, f, ft, spins=one(w), torques=m)
    return f[0].copy(), m[0].copy()


def test_twist_and_rolling_slots_come_before_the_tangential_state():
    """Row layout: normal state, then the twist law's slots, then the rolling law's, then the tangential
    law's (so a twist or rolling law adds its slots and leaves the tangential state as it was)."""
    nid, tid = _table().normal_id, _table().tangential_id
    q, r = table.law_id("twist", "sds"), table.law_id("rolling", "sds")
    assert table.tangential_base(nid, q, r) == table.tangential_base(nid) + 1 + 3
    assert _table(**SDS).history_size == _table().history_size + 4
    tab = _table(**SDS)
    H = new_histories(1, tab.history_size)
    _steps(tab, H, [0.0, 0.0, 1.0], [0.3, 0.0, 2.0], 3)
    b = table.twist_base(nid)
    assert H[0, b] == pytest.approx(3 * 2.0 * 1e-7, rel=1e-12)                 # the twist angle
    assert H[0, b + 1:b + 4] == pytest.approx([0.0, -3 * 0.5 * R * 0.3 * 1e-7, 0.0], rel=1e-12)


def test_marshall_is_lammps_scaling_and_slips_at_two_thirds_mu_n_a():
    """twist marshall: M = -4 G* a^2 xi while it sticks (LAMMPS's 0.5 k_t a^2 with k_t = 8 G*, unscaled), and
    |M| = (2/3) mu N a when it slips, against the spin."""
    tab = _table(twist="marshall")
    sc = tab.scenes[0]
    delta = 1e-6
    a = math.sqrt(sc.pair.R_star * delta)
    N = 4.0 / 3.0 * sc.pair.E_star * math.sqrt(sc.pair.R_star) * delta ** 1.5
    H = new_histories(1, tab.history_size)
    f, m = _steps(tab, H, [0.0, 0.0, 1.0], [0.0, 0.0, 1e-4], 2, delta)
    assert f[2] == pytest.approx(-N, rel=1e-12)
    assert m[2] == pytest.approx(-4.0 * sc.pair.G_star * a * a * 2e-11, rel=1e-12)
    _, m = _steps(tab, H, [0.0, 0.0, 1.0], [0.0, 0.0, -50.0], 50, delta)
    assert m[2] == pytest.approx(2.0 / 3.0 * sc.mu * N * a, rel=1e-12)


def test_sds_springs_and_sliders():
    """twist sds: M = -k_twist xi, at most mu_twist N; rolling sds: torque R* (n x F) with F = -k_roll h,
    h = R* (w x n) t, at most mu_roll R* N."""
    tab = _table(**SDS)
    sc = tab.scenes[0]
    Rs = sc.pair.R_star
    n = [0.0, 0.0, 1.0]
    H = new_histories(1, tab.history_size)
    f, m = _steps(tab, H, n, [1e-3, 0.0, 1e-3], 4)
    N = -f[2]
    t = 4e-7
    assert m[2] == pytest.approx(-SDS["k_twist"] * 1e-3 * t, rel=1e-12)
    # h = R* (w x n) t = (0, -R* 1e-3 t, 0); torque = R* n x (-k h) = (-R*^2 k 1e-3 t, 0, 0)
    assert m[0] == pytest.approx(-Rs * Rs * SDS["k_roll"] * 1e-3 * t, rel=1e-12)
    _, m = _steps(tab, H, n, [-300.0, 0.0, -300.0], 100)
    assert m[2] == pytest.approx(SDS["mu_twist"] * N, rel=1e-12)
    assert m[0] == pytest.approx(SDS["mu_roll"] * Rs * N, rel=1e-12)


MARSHALL = {k: v for k, v in SDS.items() if not k.endswith("_twist")} | {"twist": "marshall"}
DERESIEWICZ = {"twist": "deresiewicz"}
ROLLING = {k: v for k, v in SDS.items() if k.endswith("_roll")} | {"rolling": "sds"}


@pytest.mark.parametrize("laws", [SDS, MARSHALL, DERESIEWICZ, ROLLING])
def test_swapped_bodies_feel_the_opposite_torque(laws):
    """Contact stepped, then bodies swapped (swap_bodies reads the row's twist and rolling laws: their
    slots keep their sign) and stepped with n, v and w = w1 - w2 reversed: exactly the opposite force and
    torque of the same step unswapped (Newton's third law)."""
    tab = _table(**laws)
    sc = tab.scenes[0]
    n = np.array([0.6, 0.0, 0.8])
    v = np.array([0.8, 0.1, -0.6]) * 1e-3
    w = np.array([3.0, -2.0, 5.0])
    H = new_histories(1, tab.history_size)
    _steps(tab, H, n, w, 20, v=v)
    Hs = H.copy()
    f, m = _steps(tab, H, n, 0.5 * w, 1, v=v)
    swap_bodies(tab.normal_id, tab.tangential_id, tab.params, 0, Hs, 0)
    fs, ms = _steps(tab, Hs, -n, -0.5 * w, 1, v=-v)
    assert np.array_equal(fs, -f) and np.array_equal(ms, -m) and np.abs(m).max() > 0.0


@pytest.mark.parametrize("laws", [SDS, DERESIEWICZ, ROLLING])
def test_a_rotated_contact_has_rotated_torques(laws):
    """The contact and its history turned rigidly by Q (rotate_history turns the tangential force and the
    rolling displacement, wherever the row's twist and rolling laws put them): the next step's force and
    torque are Q times the unturned ones (objectivity)."""
    tab = _table(**laws)
    n = np.array([0.0, 0.6, 0.8])
    v = np.array([0.8, 0.1, -0.6]) * 1e-3
    w = np.array([2.0, 1.0, -4.0])
    H = new_histories(1, tab.history_size)
    _steps(tab, H, n, w, 10, v=v)
    th = 0.7
    Q = np.array([[math.cos(th), -math.sin(th), 0.0], [math.sin(th), math.cos(th), 0.0], [0.0, 0.0, 1.0]])
    HQ = H.copy()
    rotate_history(tab.normal_id, tab.tangential_id, tab.params, 0, HQ, 0, Q)
    f, m = _steps(tab, H, n, 0.3 * w, 1, v=v)
    fq, mq = _steps(tab, HQ, Q @ n, Q @ (0.3 * w), 1, v=Q @ v)
    assert np.abs(m).max() > 0.0
    assert np.allclose(mq, Q @ m, rtol=0.0, atol=1e-12 * np.abs(m).max())
    assert np.allclose(fq, Q @ f, rtol=0.0, atol=1e-12 * np.abs(f).max())


@pytest.mark.parametrize("laws", [DERESIEWICZ, ROLLING])
def test_tangential_work_is_that_of_the_tangential_law(laws):
    """The twist and rolling laws do not act on the tangential force: along the same path, the tangential
    work that tangential_work reads (after the row's twist and rolling states) is that of the table without
    them, bit for bit, and positive."""
    n = np.array([0.0, 0.6, 0.8])
    w = np.array([2.0, 1.0, -4.0])
    works = []
    for tab in (_table(**laws), _table()):
        H = new_histories(1, tab.history_size)
        for k in range(12):
            _steps(tab, H, n, w, 1, v=np.array([0.8, 0.1, -0.6]) * 1e-3 * math.cos(0.5 * k))
        works.append(tangential_work(tab.normal_id, tab.tangential_id, tab.params, 0, H, 0))
    assert works[0] == works[1] and works[1] > 0.0


def test_engine_model_settings_are_checked():
    """The sds laws need their coefficients (k > 0: LAMMPS divides by it), and they apply to these laws only."""
    body = Sphere(R, STEEL)
    with pytest.raises(InputError, match=r"^twist='sds' needs k_twist, gamma_twist, mu_twist"):
        Scene(body, body, twist="sds")
    with pytest.raises(InputError, match=r"^rolling='sds' needs mu_roll"):
        Scene(body, body, rolling="sds", k_roll=1.0, gamma_roll=0.0)
    with pytest.raises(InputError, match=r"^k_twist \(twist spring, N m/rad\) = 0 is outside the valid range"):
        Scene(body, body, **dict(SDS, k_twist=0.0))
    with pytest.raises(InputError, match=r"^k_roll applies to the laws sds \(rolling\) only"):
        Scene(body, body, k_roll=1.0)
    marshall = Scene(body, body, twist="marshall")
    assert marshall.describe()["twist_k_t"] == pytest.approx(8.0 * marshall.pair.G_star)


@pytest.mark.parametrize("laws, law", [(DERESIEWICZ, "twist law deresiewicz"), (ROLLING, "rolling law sds")])
def test_a_torque_law_needs_spins_and_torques(laws, law):
    """Without spins a twist or rolling law never acts, without torques its moment is lost: every checked
    batch entry refuses the table (InputError naming the argument and the law) and writes nothing; nor do spins
    that turn the bodies a radian in one step."""
    tab = _table(**laws)
    one = lambda x: np.ascontiguousarray(np.asarray(x, dtype=float).reshape(1, 3))
    H = new_histories(1, tab.history_size)
    f, ft = np.zeros((1, 3)), np.zeros((1, 3))
    args = (tab.normal_id, tab.tangential_id, tab.params, np.array([0]), H, one([0.0, 0.6, 0.8]), np.array([1e-6]),
            one([1e-3, 0.0, 0.0]), np.zeros(1), 1e-7, f, ft)
    for entry in (contact_forces, contact_forces_batch, contact_forces_serial, check_contacts):
        for kw, name in (({}, "spins"), ({"torques": np.zeros((1, 3))}, "spins"), ({"spins": one([0.0, 0.0, 5.0])},
                                                                                   "torques")):
            with pytest.raises(InputError, match=rf"^{name} is required: params\[0\] has the {law}"):
                entry(*args, **kw)
    assert not H.any() and not f.any()
    # spins that turn the bodies by 1 rad or more in a step are refused where the values are checked
    with pytest.raises(InputError, match=r"^spins\[0\] turns the bodies by 1\.5 rad against each other in one step"):
        contact_forces(*args, spins=one([0.0, 0.0, 1.5e7]), torques=np.zeros((1, 3)))
