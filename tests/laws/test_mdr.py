"""The MDR reference (Popov & Hess 2015, chapter 6) and the adaptive MDR law: Cattaneo-Mindlin, Maw's critical angle,
convergence in springs and steps, grid checks."""
import math
import warnings

import numpy as np
import pytest

import dem_contact as dc
from dem_contact.errors import InputError, NumericalError
from dem_contact.laws.tangential.mdr import mdr
from dem_contact.laws.slots import N_HIST_BASE, N_PARAMS, P_DX, P_ESTAR, P_GSTAR, P_MU, P_NSPRING

from conftest import vt_for_Theta

MU = 0.3


def mdr_scene(nu=0.3, tangential="mdr", normal="hertz", **kw):
    mat = dc.Material(208e9, nu, 7850)
    kw.setdefault("v_ref", dc.reference_speed(5.0))
    return dc.Scene(dc.Sphere(0.01, mat), dc.Wall(mat), mu=MU, normal=normal, tangential=tangential, **kw)


def f_over_mu(scene, Theta, spc, vn=5.0, e_n=1.0):
    return dc.impact(scene, vn, vt_for_Theta(Theta, MU, vn, e_n), steps_per_contact=spc).f_over_mu


def constant_n_contact(n=200, kappa=0.8235, E=1e11, R=0.01, a=1e-4):
    p = np.zeros(N_PARAMS)
    p[P_ESTAR] = E
    p[P_GSTAR] = kappa * E / 4.0
    p[P_MU] = MU
    p[P_NSPRING] = n
    p[P_DX] = 1.01 * a / n
    N = 4.0 / 3.0 * E * a**3 / R
    dmax = MU * (a * a / R) / kappa   # delta_t,max = mu delta_n / kappa (Mindlin & Deresiewicz 1953; Johnson 1985, section 7.2)
    return p, np.zeros(N_HIST_BASE + n), N, a, dmax


def test_cattaneo_mindlin_loading_and_unloading():
    """Constant N (Mindlin & Deresiewicz 1953; Johnson 1985, section 7.2): T = mu N [1 - (1 - d/d_max)^(3/2)] on loading; Masing unloading
    T = T* - 2 mu N [1 - (1 - (d* - d)/(2 d_max))^(3/2)] from d* = 0.6 d_max down to -d*."""
    p, h, N, a, dmax = constant_n_contact()
    steps = 200
    for k in range(1, steps + 1):
        T = mdr(p, h, N, a, a, dmax / steps)
        d = k * dmax / steps
        assert T == pytest.approx(MU * N * (1 - (1 - d / dmax) ** 1.5), abs=1e-4 * MU * N)
    assert T == pytest.approx(MU * N, rel=1e-12)     # full slip at d_max
    h[:] = 0.0
    ds = 0.6 * dmax
    for k in range(steps):
        Ts = mdr(p, h, N, a, a, ds / steps)
    for k in range(1, 2 * steps + 1):
        T = mdr(p, h, N, a, a, -ds / steps)
        d = ds - k * ds / steps
        expected = Ts - 2 * MU * N * (1 - (1 - (ds - d) / (2 * dmax)) ** 1.5)
        assert T == pytest.approx(expected, abs=1e-4 * MU * N)
    assert T == pytest.approx(-Ts, abs=1e-4 * MU * N)   # Masing: the loop is symmetric


@pytest.mark.parametrize("nu", [0.0, 0.49])
def test_maw_critical_angle(nu):
    """e_n = 1, no spin: psi = kappa Theta, Psi_r = psi_2 / kappa (Wu, Thornton & Li 2009, section 4). At psi_1 = 7 kappa - 1
    (Theta_c = (7 kappa - 1)/kappa) the contact slides to the end and psi_2 = -1; below it, it sticks
    (f/mu < 1); above it f/mu = 1."""
    sc = mdr_scene(nu, mdr_springs=100)
    kappa = sc.pair.kappa
    Tc = (7 * kappa - 1) / kappa
    r = dc.impact(sc, 5.0, vt_for_Theta(Tc, MU, 5.0), steps_per_contact=400)
    assert r.e_n == pytest.approx(1.0, abs=1e-6)
    assert kappa * r.Psi_r == pytest.approx(-1.0, abs=2e-4)
    assert r.f_over_mu == pytest.approx(1.0, abs=3e-5)
    assert f_over_mu(sc, 0.9 * Tc, 400) < 1.0 - 2e-3
    assert f_over_mu(sc, 1.05 * Tc, 400) == pytest.approx(1.0, abs=5e-6)


def test_convergence_in_springs_and_steps():
    """f/mu at Theta = 1 converges with the number of springs (observed order >= 1.5) and of steps
    (order > 1)."""
    springs = [25, 50, 100]
    fs = [f_over_mu(mdr_scene(mdr_springs=n), 1.0, 500) for n in springs]
    assert abs(fs[0] - fs[1]) > 2.8 * abs(fs[1] - fs[2]) > 0
    sc = mdr_scene(mdr_springs=100)
    ft = [f_over_mu(sc, 1.0, s) for s in (100, 200, 400)]
    assert abs(ft[0] - ft[1]) > 2.2 * abs(ft[1] - ft[2]) > 0
    # the 4-digit defaults agree with a finer solution to 1e-5
    fine = f_over_mu(mdr_scene(mdr_springs=400), 1.0, 2000)
    default = f_over_mu(mdr_scene(), 1.0, dc.laws.model.MDR_STEPS_PER_CONTACT)
    assert default == pytest.approx(fine, abs=1e-5)


@pytest.mark.parametrize("profile", ["truncated", "scaled"])
def test_thornton_profile_keeps_coulomb_consistent(profile):
    """With the thornton law (plastic loading, then unloading with R_p, delta_p) the springs carry the
    normal law's own force: in persistent sliding |T| <= mu N at every step and f/mu = 1. With a
    Hertz-shaped limit throughout ("scaled") T = mu N at every step (f/mu = 1 to rounding); the truncated
    pressure of plastic loading switches to the Hertz (R_p) pressure at the start of unloading, which
    raises the limit of the central springs: they stick until the slip reaches it, briefly."""
    sc = mdr_scene(normal="thornton", e_n=0.6, mdr_springs=50, mdr_profile=profile)
    r = dc.impact(sc, 5.0, vt_for_Theta(12.0, MU, 5.0, 0.6), steps_per_contact=200, series=True)
    assert r.e_n == pytest.approx(0.6, abs=0.02)
    assert r.f_over_mu == pytest.approx(1.0, abs=1e-9 if profile == "scaled" else 2e-5)
    s = r.series
    assert np.all(np.abs(s["tangential_force"]) <= MU * s["normal_force"] * (1 + 1e-12))


def test_grid_needs_extent_and_reports_overflow():
    mat = dc.STEEL
    with pytest.raises(InputError, match="v_ref"):
        dc.Scene(dc.Sphere(0.01, mat), dc.Wall(mat), tangential="mdr")
    with pytest.raises(InputError, match="mdr_springs"):
        mdr_scene(mdr_springs=1)
    sc = mdr_scene(v_ref=2.0, mdr_springs=20)
    with pytest.raises(InputError, match="exceed the extent of the mdr springs"):
        dc.impact(sc, 5.0, 1.0, steps_per_contact=50)
    # an explicit extent that covers the contact works; the grid of v_ref covers impacts at v_ref
    ok = mdr_scene(v_ref=None, mdr_max_radius=1.1 * sc.max_contact_radius(5.0), mdr_springs=20)
    assert math.isfinite(dc.impact(ok, 5.0, 1.0, steps_per_contact=50).f_over_mu)
    assert math.isfinite(dc.impact(sc, 2.0, 1.0, steps_per_contact=50).f_over_mu)


@pytest.mark.parametrize("normal,e_n,nu", [("hertz", 1.0, 0.3), ("thornton", 0.6, 0.0), ("hertz_damped", 0.5, 0.49)])
def test_adaptive_law_close_to_reference(normal, e_n, nu):
    """mdr_adaptive (16 cells, grid following the contact, no set-up) stays within 0.003 of the
    reference in f/mu, and never creates energy."""
    kw = {} if normal == "hertz" else {"e_n": e_n}
    ref = mdr_scene(nu, normal=normal, mdr_springs=100, **kw)
    fast = mdr_scene(nu, tangential="mdr_adaptive", normal=normal, **kw)
    for Theta in (0.5, 1.5, 3.0, 5.0):
        vt = vt_for_Theta(Theta, MU, 5.0, e_n)
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            r = dc.impact(fast, 5.0, vt, steps_per_contact=100)
        assert not r.energy_created
        assert r.f_over_mu == pytest.approx(dc.impact(ref, 5.0, vt, steps_per_contact=400).f_over_mu, abs=3e-3)


def test_adaptive_grid_follows_the_contact():
    """The adaptive law needs no extent: the same scene serves speeds four decades apart, and its
    history row holds the cell width and the cells."""
    sc = mdr_scene(tangential="mdr_adaptive", v_ref=None)
    assert sc.history_size == N_HIST_BASE + 1 + dc.laws.model.MDR_ADAPTIVE_CELLS
    for vn in (1e-3, 10.0):
        ref = mdr_scene(mdr_springs=100, v_ref=vn)
        vt = vt_for_Theta(1.0, MU, vn)
        assert dc.impact(sc, vn, vt, steps_per_contact=100).f_over_mu == pytest.approx(
            dc.impact(ref, vn, vt, steps_per_contact=400).f_over_mu, abs=3e-3)


def test_sticking_zone_of_the_3d_law_repeats_the_cell_by_cell_update():
    """The 3D default law advances the inner cells that provably stick through one common displacement
    (``mdr._vector``, sticking zone). On a 3D path that loads, unloads, reverses and turns (the zone set up,
    used and dissolved many times) its forces are those of the same law updating every cell (the zone
    disabled), to rounding."""
    from dem_contact.dem.contact3d import contact_force, history_size
    from dem_contact.laws.tangential import mdr as M
    from dem_contact.laws.vector import V_A, V_N, renamed
    sc = mdr_scene(tangential="mdr_adaptive", v_ref=None)
    P = sc.params[None, :]
    cell_by_cell = renamed(M._vector, "cell_by_cell", ADAPTIVE=True, R_CELLS=M.R_CELLS_ADAPTIVE, LAZY_MIN=10**9)
    H = np.zeros((1, history_size(sc.normal_id, sc.tangential_id, int(sc.params[P_NSPRING]))))
    Hc = H.copy()
    b = 2
    E, R = sc.params[P_ESTAR], sc.params[2]
    n = np.array([0.0, 0.0, 1.0])
    dt, steps, used, err, scale = 1e-7, 400, 0, 0.0, 0.0
    for k in range(steps):
        delta = 2e-6 * (1.0 + 0.15 * math.sin(0.11 * k))
        v = 0.02 * np.array([math.cos(0.05 * k), 0.6 * math.sin(0.13 * k), 0.3])
        wn = 200.0 * math.sin(0.07 * k)
        f = contact_force(sc.normal_id, sc.tangential_id, P, 0, H, 0, *n, delta, *v, wn, dt)
        used += H[0, b + M.R_LAZY] > 0
        a = math.sqrt(R * delta)
        N = 4.0 / 3.0 * E * a * delta
        q = 0.5 * wn * dt
        t = cell_by_cell(P, 0, Hc, 0, b, N, a, 0.0, *n, v[0] * dt, v[1] * dt, 0.0, (1 - q * q) / (1 + q * q),
                         2 * q / (1 + q * q))
        Hc[0, V_N], Hc[0, V_A] = N, a
        err = max(err, np.abs(np.array(f[3:]) + np.array(t)).max())
        scale = max(scale, sc.mu * N)
    assert used > steps // 4, used
    assert err <= 1e-12 * scale, (err, scale)
