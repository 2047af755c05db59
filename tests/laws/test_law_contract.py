"""The contract every law of the table passes (``laws.table``): a law added as one file plus one row gets
these tests without any edit here.

- the generated dispatch is that of the table, and every law declares what the table needs;
- the 3D form reduces to the planar one on planar paths (normal laws: on a load-unload path; tangential
  laws: in-plane motion with the overlap varying);
- objective under rigid rotations (of the pair, and spin about the normal);
- the Coulomb cap is never exceeded;
- no energy is created over closed elastic cycles;
- swapping the bodies twice is the identity; a history saved and loaded carries on bit for bit.
"""
import io
import math

import numpy as np
import pytest
from numba import njit

from dem_contact.dem.contact3d import contact_force, rotate_history, swap_bodies, tangential_work
from dem_contact.laws import generate, table
from dem_contact.laws.contact import contact_step, normal_force
from dem_contact.laws.dispatch import uses_rate
from conftest import _frame, _law_scene, scene_history
from dem_contact.laws.model import reference_speed

NORMAL = [m.NAME for m in table.FAMILIES["normal"]]
TANGENTIAL = [m.NAME for m in table.FAMILIES["tangential"]]


def test_the_generated_dispatch_is_that_of_the_table():
    """laws/slots.py, laws/dispatch.py and laws/dispatch3d.py are what ``python -m dem_contact.laws.generate``
    writes now."""
    assert generate.TARGET_SLOTS.read_text() == generate.slots_source(), "run python -m dem_contact.laws.generate"
    assert generate.TARGET.read_text() == generate.source(), "run python -m dem_contact.laws.generate"
    assert generate.TARGET_3D.read_text() == generate.source_3d(), "run python -m dem_contact.laws.generate"


@pytest.mark.parametrize("family", list(table.FAMILIES))
def test_every_law_declares_what_the_table_needs(family):
    """Name, family, source, parameters, state, options and kernels; a planar form for the normal and
    tangential laws; the flags of its family."""
    for m in table.FAMILIES[family]:
        assert m.FAMILY == family and isinstance(m.NAME, str) and m.SOURCE
        assert callable(m.configure) and callable(m.describe) and hasattr(m.vector, "py_func")
        if family in ("normal", "tangential"):
            assert hasattr(m.planar, "py_func")
        if family == "normal":
            assert isinstance(m.USES_RATE, bool) and isinstance(m.PLASTIC, bool) and callable(m.contact_time)
            assert hasattr(m.gap, "py_func") and len(m.STATE) <= table.MAX_NORMAL_STATE
        if family == "tangential":
            assert m.VECTOR_SLOTS >= 4 and all(0 < k < m.VECTOR_SLOTS for k in m.SWAP_NEGATE)


@pytest.mark.parametrize("normal", NORMAL)
def test_normal_3d_form_repeats_the_planar_one_and_declares_its_rate(normal):
    """On a load-unload-reload path with a varying rate, the 3D normal force equals the planar law's to
    1e-12 of its peak; the force depends on the overlap rate exactly when the law says so (USES_RATE)."""
    sc = _law_scene("mindlin_total", normal)
    P = sc.params[None, :]
    H = scene_history(sc)
    h = sc.new_history()
    n = np.array([0.0, 0.0, 1.0])
    delta0 = 5e-6
    s = np.linspace(0.0, 1.0, 301)
    path = delta0 * np.sin(np.pi * s) * (1.0 + 0.3 * np.sin(6 * np.pi * s))
    dt = 1e-7
    peak = err = 0.0
    for k in range(1, s.size):
        vel = (path[k] - path[k - 1]) / dt
        N, a, T = contact_step(sc.normal_id, sc.tangential_id, sc.params, h, path[k], vel, 0.0)
        out = contact_force(sc.normal_id, sc.tangential_id, P, 0, H, 0, *n, path[k], 0.0, 0.0, vel, 0.0, dt)
        peak = max(peak, abs(N))
        err = max(err, abs(-out[2] - N))
    assert peak > 0.0 and err <= 1e-12 * peak, (normal, err, peak)
    h = sc.new_history()
    slow = normal_force(sc.normal_id, sc.params, h.copy(), delta0, 0.0)[0]
    fast = normal_force(sc.normal_id, sc.params, h.copy(), delta0, 0.1)[0]
    assert (slow != fast) == sc.normal_law.USES_RATE == uses_rate(sc.normal_id)


def _random_path(steps, seed, amp_t=1.0, amp_n=0.0):
    """A smooth random closed path: overlap (in units of delta0) and tangential displacement (in units of
    the slip displacement) as Fourier sums that return to their start."""
    rng = np.random.default_rng(seed)
    s = np.linspace(0.0, 1.0, steps + 1)
    ux = np.zeros_like(s)
    uy = np.zeros_like(s)
    dn = np.zeros_like(s)
    for k in range(1, 4):
        a, b, c, d, e = rng.normal(size=5) / k
        ux += a * np.sin(2 * np.pi * k * s) + b * (1 - np.cos(2 * np.pi * k * s))
        uy += c * np.sin(2 * np.pi * k * s) + d * (1 - np.cos(2 * np.pi * k * s))
        dn += e * np.sin(2 * np.pi * k * s)
    return amp_t * ux, amp_t * uy, 1.0 + amp_n * dn / max(np.abs(dn).max(), 1e-300)


@pytest.mark.parametrize("tangential", TANGENTIAL)
def test_in_plane_motion_repeats_the_planar_law(tangential):
    """Tangential motion along one axis of an arbitrary tangent plane, with the overlap varying: the 3D
    kernel's force equals the planar law's T (laws.contact.contact_step) to 1e-12 of mu N, every law."""
    for normal in ("hertz", "thornton"):
        sc = _law_scene(tangential, normal)
        P = sc.params[None, :]
        H = scene_history(sc)
        h = sc.new_history()
        m_wall, e1, _ = _frame(True)
        n = -m_wall
        delta0 = 2e-6
        muN0 = sc.mu * 4.0 / 3.0 * sc.pair.E_star * math.sqrt(sc.pair.R_star) * delta0 ** 1.5
        slip = 3.0 * sc.mu * delta0 / 2.0          # order of the slip displacement 3 mu N / (16 G* a)
        ux, _, dn = _random_path(400, 11, amp_t=slip, amp_n=0.5)
        dt = 1e-7
        err = 0.0
        for k in range(1, ux.size):
            dd = ux[k] - ux[k - 1]
            delta = delta0 * dn[k]
            vel = delta0 * (dn[k] - dn[k - 1]) / dt
            N, a, T = contact_step(sc.normal_id, sc.tangential_id, sc.params, h, delta, vel, dd)
            v = vel * n + dd / dt * e1
            out = contact_force(sc.normal_id, sc.tangential_id, P, 0, H, 0, *n, delta, *v, 0.0, dt)
            err = max(err, np.linalg.norm(np.array(out[3:]) + T * e1) / muN0)
        assert err < 1e-12, (normal, err)


def _rotation(rng, angle=None):
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    ang = rng.uniform(0, 2 * np.pi) if angle is None else angle
    K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(ang) * K + (1 - math.cos(ang)) * K @ K


@pytest.mark.parametrize("tangential", TANGENTIAL)
def test_objectivity_under_rigid_rotations(tangential):
    """Rotating the whole problem (history, normal, velocity) by a rotation Q, applied once at the start,
    once in the middle, or a little at every step, gives the rotated force within 1e-10 of |F|: the
    kernel is a covariant function of its vectors, every law."""
    sc = _law_scene(tangential)
    nid, tid, P = sc.normal_id, sc.tangential_id, sc.params[None, :]
    rng = np.random.default_rng(2)
    steps = 300
    delta0 = 2e-6
    slip = 3.0 * sc.mu * delta0 / 2.0
    ux, uy, dn = _random_path(steps, 3, amp_t=slip, amp_n=0.3)
    dt = 1e-7
    # a slowly turning normal and a spinning contact frame
    R_n = _rotation(rng, 0.3 / steps)
    n0 = rng.normal(size=3)
    n0 /= np.linalg.norm(n0)
    t1 = np.cross(n0, rng.normal(size=3))
    t1 /= np.linalg.norm(t1)
    t2 = np.cross(n0, t1)
    wn = rng.normal(scale=0.5 / (steps * dt), size=steps + 1)
    for mode in ("once", "middle", "every step"):
        HA, HB = scene_history(sc), scene_history(sc)
        Q = np.eye(3) if mode != "once" else _rotation(rng)
        n, a1, a2 = n0.copy(), t1.copy(), t2.copy()
        err, scale = 0.0, 0.0
        for k in range(1, steps + 1):
            if mode == "middle" and k == steps // 2:
                Qnew = _rotation(rng)
            elif mode == "every step":
                Qnew = _rotation(rng, 0.05) @ Q
            else:
                Qnew = Q
            rotate_history(nid, tid, P, 0, HB, 0, np.ascontiguousarray(Qnew @ Q.T))
            Q = Qnew
            n, a1, a2 = R_n @ n, R_n @ a1, R_n @ a2
            vel = delta0 * (dn[k] - dn[k - 1]) / dt
            v = vel * n + ((ux[k] - ux[k - 1]) * a1 + (uy[k] - uy[k - 1]) * a2) / dt
            FA = np.array(contact_force(nid, tid, P, 0, HA, 0, *n, delta0 * dn[k], *v, wn[k], dt))
            FB = np.array(contact_force(nid, tid, P, 0, HB, 0, *(Q @ n), delta0 * dn[k], *(Q @ v), wn[k], dt))
            err = max(err, np.abs(FB[:3] - Q @ FA[:3]).max(), np.abs(FB[3:] - Q @ FA[3:]).max())
            scale = max(scale, np.abs(FA[3:]).max())
        assert scale > 0.0
        assert err <= 1e-10 * scale, (mode, err / scale)


@pytest.mark.parametrize("tangential", TANGENTIAL)
def test_spin_about_the_normal(tangential):
    """A loaded pair turning rigidly about its normal (no slip, wn = Omega) sees its tangential force
    turn by 2 atan(Omega dt / 2) per step with its magnitude kept (to rounding); a twist (w1 = -w2,
    wn = 0) leaves it unchanged; a spin with no tangential load creates none."""
    sc = _law_scene(tangential)
    nid, tid, P = sc.normal_id, sc.tangential_id, sc.params[None, :]
    n = np.array([0.0, 0.6, 0.8])
    e1 = np.array([1.0, 0.0, 0.0])
    dt, delta = 1e-7, 2e-6
    H = scene_history(sc)
    for k in range(5):
        F0 = contact_force(nid, tid, P, 0, H, 0, *n, delta, *(2e-3 * e1), 0.0, dt)
    T0 = np.array(F0[3:])
    assert np.linalg.norm(T0) > 0.0
    Hk = H.copy()
    for k in range(50):                              # twist: no change
        F = contact_force(nid, tid, P, 0, Hk, 0, *n, delta, 0.0, 0.0, 0.0, 0.0, dt)
    assert np.abs(np.array(F[3:]) - T0).max() <= 1e-13 * np.linalg.norm(T0)
    Omega = 2e5
    steps = 100
    for k in range(steps):
        F = contact_force(nid, tid, P, 0, H, 0, *n, delta, 0.0, 0.0, 0.0, Omega, dt)
    ang = steps * 2.0 * math.atan(0.5 * Omega * dt)
    K = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    R = np.eye(3) + math.sin(ang) * K + (1 - math.cos(ang)) * K @ K
    assert np.abs(np.array(F[3:]) - R @ T0).max() <= 1e-11 * np.linalg.norm(T0)
    H = scene_history(sc)
    for k in range(20):
        F = contact_force(nid, tid, P, 0, H, 0, *n, delta, 0.0, 0.0, 0.0, Omega, dt)
        assert F[3:] == (0.0, 0.0, 0.0) or np.abs(F[3:]).max() == 0.0


@pytest.mark.parametrize("tangential", TANGENTIAL)
def test_rigid_rotation_of_the_pair_about_any_axis(tangential):
    """A loaded pair rotating rigidly about an oblique axis (the normal turns, no relative motion,
    wn = Omega . n): the force follows the rotation, with an error that vanishes with the step (the carry
    into the new tangent plane is first order per unit turn)."""
    sc = _law_scene(tangential)
    nid, tid, P = sc.normal_id, sc.tangential_id, sc.params[None, :]
    n0 = np.array([0.0, 0.0, 1.0])
    axis = np.array([0.6, 0.0, 0.8])
    total = 0.5 * math.pi                            # quarter turn
    errs = []
    for steps in (100, 1000):
        H = scene_history(sc)
        dt = 1e-7
        for k in range(5):
            F0 = contact_force(nid, tid, P, 0, H, 0, *n0, 2e-6, 2e-3, 1e-3, 0.0, 0.0, dt)
        T0 = np.array(F0[3:])
        Omega = total / (steps * dt)
        K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
        for k in range(1, steps + 1):
            ang = k * total / steps
            R = np.eye(3) + math.sin(ang) * K + (1 - math.cos(ang)) * K @ K
            n = R @ n0
            F = contact_force(nid, tid, P, 0, H, 0, *n, 2e-6, 0.0, 0.0, 0.0, Omega * np.dot(axis, n), dt)
        errs.append(np.linalg.norm(np.array(F[3:]) - R @ T0) / np.linalg.norm(T0))
    assert errs[1] < 2e-3 and errs[1] < 0.2 * errs[0] + 1e-12, errs


@njit(cache=True)
def closed_loop_work(nid, tid, P, H, n, e1, e2, ux, uy, dn, delta0, dt):
    """Drive one contact along a closed path; returns (work absorbed by the tangential force from the
    kernel's work slot, the same by the trapezoid rule from the returned forces)."""
    W = 0.0
    tx0 = 0.0
    ty0 = 0.0
    tz0 = 0.0
    for k in range(1, ux.size):
        ddx = (ux[k] - ux[k - 1]) * e1[0] + (uy[k] - uy[k - 1]) * e2[0]
        ddy = (ux[k] - ux[k - 1]) * e1[1] + (uy[k] - uy[k - 1]) * e2[1]
        ddz = (ux[k] - ux[k - 1]) * e1[2] + (uy[k] - uy[k - 1]) * e2[2]
        vel = delta0 * (dn[k] - dn[k - 1]) / dt
        f = contact_force(nid, tid, P, 0, H, 0, n[0], n[1], n[2], delta0 * dn[k], ddx / dt + vel * n[0],
                          ddy / dt + vel * n[1], ddz / dt + vel * n[2], 0.0, dt)
        # F_t is the force on body 1; the contact absorbs -F_t . dd
        W -= 0.5 * ((tx0 + f[3]) * ddx + (ty0 + f[4]) * ddy + (tz0 + f[5]) * ddz)
        tx0 = f[3]
        ty0 = f[4]
        tz0 = f[5]
    return tangential_work(nid, tid, P, 0, H, 0), W


@pytest.mark.parametrize("tangential", TANGENTIAL)
def test_no_energy_created_on_closed_loops_at_constant_load(tangential):
    """Random closed 3D tangential loops at constant overlap: the work absorbed by the tangential force
    is >= 0 for every law (it is dissipated or stored), and the kernel's work slot equals the trapezoid
    rule on the returned forces."""
    sc = _law_scene(tangential)
    P = sc.params[None, :]
    delta0 = 2e-6
    muN = sc.mu * 4.0 / 3.0 * sc.pair.E_star * math.sqrt(sc.pair.R_star) * delta0 ** 1.5
    slip = 3.0 * sc.mu * delta0 / 2.0
    n, e1, e2 = _frame(True)
    for seed in range(30):
        ux, uy, dn = _random_path(300, 100 + seed, amp_t=slip * (0.2 + seed / 15))
        H = scene_history(sc)
        w_slot, w = closed_loop_work(sc.normal_id, sc.tangential_id, P, H, -n, e1, e2, ux, uy, dn, delta0, 1e-7)
        assert w >= -1e-12 * muN * slip, (seed, w)
        assert abs(w_slot - w) <= 1e-9 * max(abs(w), muN * slip * 1e-3), (seed, w_slot, w)




@pytest.mark.parametrize("tangential", TANGENTIAL)
def test_coulomb_cap_is_never_exceeded(tangential):
    """Random 3D paths with the overlap varying (loading, unloading, turning): |F_t| <= mu N (1 + 1e-12)
    at every step, for every normal law."""
    for normal in NORMAL:
        sc = _law_scene(tangential, normal)
        P = sc.params[None, :]
        H = scene_history(sc)
        delta0 = 2e-6
        slip = 3.0 * sc.mu * delta0
        n, e1, e2 = _frame(True)
        ux, uy, dn = _random_path(200, 7, amp_t=slip, amp_n=0.6)
        dt = 1e-7
        for k in range(1, ux.size):
            dd = (ux[k] - ux[k - 1]) * e1 + (uy[k] - uy[k - 1]) * e2
            vel = delta0 * (dn[k] - dn[k - 1]) / dt
            f = np.array(contact_force(sc.normal_id, sc.tangential_id, P, 0, H, 0, *-n, delta0 * dn[k],
                                       *(dd / dt - vel * n), 0.0, dt))
            N = -np.dot(f[:3], -n)
            assert np.linalg.norm(f[3:]) <= sc.mu * max(N, 0.0) * (1 + 1e-12) + 1e-300, (normal, k)


def _drive(sc, H, steps, seed):
    """Forces of ``steps`` random steps of contact 0 (from H's current state)."""
    P = sc.params[None, :]
    rng = np.random.default_rng(seed)
    n = np.array([0.0, 0.0, 1.0])
    out = []
    for k in range(steps):
        v = rng.normal(scale=0.05, size=3)
        out.append(contact_force(sc.normal_id, sc.tangential_id, P, 0, H, 0, *n, 2e-6 * (1 + 0.2 * math.sin(k)),
                                 *v, 30.0, 1e-7))
    return np.array(out)


@pytest.mark.parametrize("tangential", TANGENTIAL)
def test_swapping_twice_is_the_identity_and_a_saved_history_carries_on(tangential):
    """swap_bodies twice leaves the history bit for bit; a history written to a file (np.save) and read
    back carries on with the same forces, bit for bit, as the one kept in memory."""
    for normal in NORMAL:
        sc = _law_scene(tangential, normal)
        H = scene_history(sc)
        _drive(sc, H, 30, 1)
        before = H.copy()
        swap_bodies(sc.normal_id, sc.tangential_id, sc.params[None, :], 0, H, 0)
        assert not np.array_equal(H, before) or not np.any(before[0, 2:])
        swap_bodies(sc.normal_id, sc.tangential_id, sc.params[None, :], 0, H, 0)
        assert np.array_equal(H, before)
        buf = io.BytesIO()
        np.save(buf, H)
        buf.seek(0)
        loaded = np.load(buf)
        assert np.array_equal(_drive(sc, loaded, 20, 2), _drive(sc, H, 20, 2))
        assert np.array_equal(loaded, H)


def test_the_3d_kernel_takes_the_relative_spin_and_returns_the_torque_of_the_twist_and_rolling_laws():
    """Every table records its twist and rolling laws (Scene(twist=..., rolling=...), "none" by default); the 3D
    kernel takes the relative spin of the bodies and returns their torque on body 1 (zero for "none"), its
    force equal to contact_force's; the batch entries carry spins and torques; an unknown law name is refused."""
    from dem_contact.dem.contact3d import contact_force_torque, contact_forces
    from dem_contact.dem.pairs import pair_table
    from dem_contact.errors import InputError
    from dem_contact.laws.slots import P_ROLLING_LAW, P_TWIST_LAW
    from dem_contact.materials import STEEL, Sphere, Wall

    sc = _law_scene("mindlin_total")
    assert (sc.twist, sc.rolling) == ("none", "none") and sc.describe()["twist_law"] == "none"
    assert sc.params[P_TWIST_LAW] == table.law_id("twist", "none") + 1
    assert sc.params[P_ROLLING_LAW] == table.law_id("rolling", "none") + 1
    with pytest.raises(InputError, match="twist law 'spring' is unknown"):
        sc.replace(twist="spring")
    P = sc.params[None, :]
    H1, H2 = scene_history(sc), scene_history(sc)
    for k in range(5):
        a = contact_force(sc.normal_id, sc.tangential_id, P, 0, H1, 0, 0.0, 0.0, 1.0, 1e-6, 0.1, 0.02, 0.0, 5.0, 1e-7)
        b = contact_force_torque(sc.normal_id, sc.tangential_id, P, 0, H2, 0, 0.0, 0.0, 1.0, 1e-6, 0.1, 0.02, 0.0,
                                 30.0, -20.0, 10.0, 5.0, 1e-7)
        assert a == b[:6] and b[6:] == (0.0, 0.0, 0.0)
    tab = pair_table([Sphere(1e-3, STEEL)], [Wall(STEEL)], tangential="mindlin_total")
    n = 3
    torques = np.full((n, 3), np.nan)
    contact_forces(tab.normal_id, tab.tangential_id, tab.params, np.zeros(n, np.int64),
                   np.zeros((n, tab.history_size)), np.tile([0.0, 0.0, 1.0], (n, 1)), np.full(n, 1e-7),
                   np.full((n, 3), 0.01), np.zeros(n), 1e-7, np.zeros((n, 3)), np.zeros((n, 3)),
                   spins=np.ones((n, 3)), torques=torques)
    assert np.all(torques == 0.0)
    with pytest.raises(InputError, match=r"^spins must have shape"):
        contact_forces(tab.normal_id, tab.tangential_id, tab.params, np.zeros(n, np.int64),
                       np.zeros((n, tab.history_size)), np.tile([0.0, 0.0, 1.0], (n, 1)), np.full(n, 1e-7),
                       np.full((n, 3), 0.01), np.zeros(n), 1e-7, np.zeros((n, 3)), np.zeros((n, 3)),
                       spins=np.ones((n + 1, 3)))


@pytest.mark.parametrize("tangential", TANGENTIAL)
def test_the_batch_loop_is_the_single_contact_step(tangential):
    """The batch loops write the step of laws.compose out in their body: for every law, with hertz and with
    the traction-coupled thornton law (its fifth state slot), and with the twist and rolling engine models
    (their slots between the normal and the tangential state), a serial batch equals contact_force_torque
    contact by contact, bit for bit, forces, torques and histories."""
    from dem_contact.dem.contact3d import contact_force_torque, contact_forces_serial
    from dem_contact.laws.model import Scene
    from dem_contact.materials import STEEL, Material, Sphere, Wall

    al = Material(E=70e9, nu=0.33, rho=2700.0, yield_pressure=1e9)
    sds = dict(twist="sds", k_twist=1e-3, gamma_twist=1e-9, mu_twist=1e-4, rolling="sds", k_roll=1e4,
               gamma_roll=1e-3, mu_roll=0.1)
    for sc in (Scene(Sphere(2e-3, STEEL), Wall(STEEL), mu=0.3, tangential=tangential, v_ref=reference_speed(1.0)),
               Scene(Sphere(2e-3, al), Wall(al), mu=0.3, normal="thornton", tangential=tangential, v_ref=1.0,
                     traction_yield=True, **sds),
               Scene(Sphere(2e-3, STEEL), Wall(STEEL), mu=0.3, tangential=tangential, v_ref=reference_speed(1.0), twist="marshall",
                     rolling="sds", k_roll=1e4, gamma_roll=1e-3, mu_roll=0.1)):
        P = sc.params[None, :]
        n = 6
        rng = np.random.default_rng(4)
        nrm = rng.normal(size=(n, 3))
        nrm /= np.linalg.norm(nrm, axis=1)[:, None]
        spins = rng.normal(scale=50.0, size=(n, 3))
        wn = rng.normal(scale=100.0, size=n)
        Hb = np.zeros((n, scene_history(sc).shape[1]))
        Hs = Hb.copy()
        f, t, m = np.zeros((n, 3)), np.zeros((n, 3)), np.zeros((n, 3))
        for step in range(8):
            d = 2e-6 * (1.0 + 0.5 * math.sin(step)) * np.ones(n)
            v = rng.normal(scale=0.05, size=(n, 3))
            contact_forces_serial(sc.normal_id, sc.tangential_id, P, np.zeros(n, np.int64), Hb, nrm, d, v, wn,
                                  1e-7, f, t, spins=spins, torques=m)
            for c in range(n):
                out = contact_force_torque(sc.normal_id, sc.tangential_id, P, 0, Hs, c, *nrm[c], d[c], *v[c],
                                           *spins[c], wn[c], 1e-7)
                assert out == (*f[c], *t[c], *m[c])
            assert np.array_equal(Hb, Hs)
        assert np.abs(t).max() > 0.0 and (sc.twist == "none" or np.abs(m).max() > 0.0)
