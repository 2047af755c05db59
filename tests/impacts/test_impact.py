"""Oblique impacts: momentum identities, persistent sliding, Coulomb, energy, convergence."""
import math
import warnings

import numpy as np
import pytest

import dem_contact as dc
from conftest import vt_for_Theta

CORE_LAWS = ["md", "md_rescale", "mindlin_total", "mindlin_incremental", "mindlin_rescale", "linear", "ddm"]
NORMALS = [("hertz", {}), ("thornton", {"e_n": 0.7}), ("hertz_damped", {"e_n": 0.8}), ("linear", {"e_n": 0.9})]


def scene(sphere, wall, **kw):
    kw.setdefault("v_ref", dc.reference_speed(5.0))
    return dc.Scene(sphere, wall, **kw)


@pytest.mark.parametrize("tangential", CORE_LAWS)
@pytest.mark.parametrize("normal,kw", NORMALS)
def test_momentum_identities(steel_sphere, steel_wall, tangential, normal, kw):
    """Eqs 2.21-2.23: Omega_r = Omega_i - f/mu, e_t = 1 - 2 (f/mu)/Theta (no spin), and
    Psi_r = Theta + 5 Omega_i - 7 f/mu, to 1e-9, for several angles, with and without spin."""
    sc = scene(steel_sphere, steel_wall, mu=0.3, normal=normal, tangential=tangential, **kw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for deg, spin in [(10, 0.0), (30, 0.0), (60, 0.0), (20, 150.0), (45, -300.0)]:
            r = dc.impact(sc, 5.0, 5.0 * math.tan(math.radians(deg)), spin, steps_per_contact=100)
            fm = r.f_over_mu
            # Theta of the centre velocity, 2 tan(theta_i) / ((1 + e_n) mu); r.Theta is that of the
            # contact patch (eq. 7.1): Theta_patch = Theta_centre + 5 Omega_i
            Theta_c = 2 * r.vt_i / ((1 + r.e_n) * 0.3 * r.vn_i)
            assert r.Theta == pytest.approx(Theta_c + 5 * r.Omega_i, abs=1e-9)
            assert r.Omega_r == pytest.approx(r.Omega_i - fm, abs=1e-9)
            assert r.e_t == pytest.approx(1 - 2 * fm / Theta_c, abs=1e-9)
            assert r.e_t == pytest.approx(1 + 2 * (r.Omega_r - r.Omega_i) / Theta_c, abs=1e-9)
            assert r.Psi_r == pytest.approx(Theta_c + 5 * r.Omega_i - 7 * fm, abs=1e-9)
            assert r.Psi_r == pytest.approx(Theta_c + 7 * r.Omega_r - 2 * r.Omega_i, abs=1e-9)
            # e_t = 1 - f (1 + e_n) / tan(theta_i) and omega_r = omega_i - 5 f (1 + e_n) V_ni / (2R)
            tan_i = r.vt_i / r.vn_i
            assert r.e_t == pytest.approx(1 - r.f * (1 + r.e_n) / tan_i, abs=1e-9)
            R = steel_sphere.radius
            assert r.omega_r * R == pytest.approx(r.omega_i * R - 2.5 * r.f * (1 + r.e_n) * r.vn_i, abs=1e-9)
            if normal != "linear":   # the linear dashpot pulls just before separation: P_n < integral of N+
                assert abs(r.f) <= 0.3 * (1 + 1e-12)


@pytest.mark.parametrize("tangential", CORE_LAWS)
@pytest.mark.parametrize("Theta", [8.0, 12.0])
def test_persistent_sliding(steel_sphere, steel_wall, tangential, Theta):
    """Well above Theta_c: f/mu = 1, e_t = 1 - 2/Theta, Omega_r = -1 (Wu, Thornton & Li 2009, section 4)."""
    sc = scene(steel_sphere, steel_wall, mu=0.3, tangential=tangential)
    r = dc.impact(sc, 5.0, vt_for_Theta(Theta, 0.3, 5.0), steps_per_contact=200)
    assert r.persistent_sliding
    assert r.f_over_mu == pytest.approx(1.0, abs=1e-4)
    assert r.e_t == pytest.approx(1 - 2 / r.Theta, abs=1e-4)
    assert r.Omega_r == pytest.approx(-1.0, abs=1e-4)
    assert r.Psi_r == pytest.approx(r.Theta - 7.0, abs=1e-4)


@pytest.mark.parametrize("tangential", CORE_LAWS)
def test_coulomb_every_step(steel_sphere, steel_wall, tangential):
    sc = scene(steel_sphere, steel_wall, mu=0.3, tangential=tangential)
    for Theta in (0.5, 2.0, 5.0, 7.0):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            r = dc.impact(sc, 5.0, vt_for_Theta(Theta, 0.3, 5.0), 100.0, steps_per_contact=100, series=True)
        s = r.series
        assert np.all(np.abs(s["tangential_force"]) <= 0.3 * np.maximum(s["normal_force"], 0) * (1 + 1e-12) + 1e-12)
        assert r.coulomb_violation == 0.0


@pytest.mark.parametrize("tangential", ["md", "md_rescale"])
@pytest.mark.parametrize("nu", [0.0, 0.3, 0.49])
def test_md_never_creates_energy(tangential, nu):
    mat = dc.Material(208e9, nu, 7850)
    sc = dc.Scene(dc.Sphere(0.01, mat), dc.Wall(mat), mu=0.3, tangential=tangential)
    for Theta in np.linspace(0.25, 8.0, 12):
        for spin in (0.0, -200.0):
            r = dc.impact(sc, 5.0, vt_for_Theta(Theta, 0.3, 5.0), spin, steps_per_contact=200)
            assert not r.energy_created
            assert r.energy.friction >= 0.0
            assert r.energy.final <= r.energy.initial * (1 + 1e-6)


def test_total_displacement_law_creation_is_flagged():
    """Thornton, Cummins & Cleary 2013: the total-displacement law creates energy for nu <= 0.2. With an elastic normal law
    the normal energy is conserved, so the tangential and rotational kinetic energy after the impact
    exceeding that before it is created energy, and the result must say so."""
    mat = dc.Material(208e9, 0.0, 7850)
    sc = dc.Scene(dc.Sphere(0.01, mat), dc.Wall(mat), mu=0.3, tangential="mindlin_total")
    found = False
    for Theta in np.linspace(0.2, 2.0, 10):
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            r = dc.impact(sc, 5.0, vt_for_Theta(Theta, 0.3, 5.0), steps_per_contact=400)
        m, R = sc.pair.m_star, 0.01
        I = 0.4 * m * R * R
        tang_before = 0.5 * m * r.vt_i**2
        tang_after = 0.5 * m * r.vt_r**2 + 0.5 * I * r.omega_r**2
        if tang_after > tang_before * (1 + 1e-5):
            found = True
            assert r.energy_created
            assert any("energy created" in str(x.message) for x in w)
    assert found, "no energy creation found for mindlin_total at nu = 0"


def test_energy_budget_balances(steel_sphere, steel_wall):
    sc = dc.Scene(steel_sphere, steel_wall, mu=0.3, normal="thornton", e_n=0.7, v_ref=5.0)
    r = dc.impact(sc, 5.0, 3.0, 50.0)
    e = r.energy
    assert abs(e.error) < 1e-4 * e.initial
    assert e.normal == pytest.approx(0.5 * sc.pair.m_star * 25.0 * (1 - r.e_n**2), rel=1e-4)


def test_converges_with_steps(steel_sphere, steel_wall):
    """f/mu and e_n errors against a fine reference fall as steps per contact grow."""
    sc = dc.Scene(steel_sphere, steel_wall, mu=0.3, normal="thornton", e_n=0.8, v_ref=5.0)
    vt = vt_for_Theta(2.0, 0.3, 5.0, 0.8)
    ref = dc.impact(sc, 5.0, vt, steps_per_contact=20000)
    errs = [abs(dc.impact(sc, 5.0, vt, steps_per_contact=n).f_over_mu - ref.f_over_mu) for n in (50, 200, 800)]
    assert errs[1] < errs[0] / 2 and errs[2] < errs[1] / 2


def test_located_separation_beats_standard_scheme(steel_sphere, steel_wall):
    """For a law with force at the instant of separation (linear spring-dashpot, closed-form e_n) the
    located end reaches 1e-3 in e_n with fewer steps than the standard DEM end."""
    sc = dc.Scene(steel_sphere, steel_wall, normal="linear", e_n=0.7, v_ref=5.0)

    def steps_needed(scheme):
        for n in (10, 20, 40, 80, 160, 320, 640, 1280):
            if abs(dc.impact(sc, 5.0, steps_per_contact=n, scheme=scheme).e_n - 0.7) < 1e-3:
                return n
        return math.inf

    assert steps_needed("located") < steps_needed("standard")


def test_standard_scheme_ends_on_a_step(steel_sphere, steel_wall):
    sc = dc.Scene(steel_sphere, steel_wall)
    r = dc.impact(sc, 5.0, 1.0, steps_per_contact=37.3, scheme="standard")
    assert r.contact_time / r.dt == pytest.approx(round(r.contact_time / r.dt), abs=1e-6)
    assert abs(r.e_n - 1) < 1e-3


def test_rebound_angle_and_json(steel_sphere, steel_wall):
    import json
    sc = dc.Scene(steel_sphere, steel_wall)
    r = dc.impact(sc, 5.0, 2.0)
    assert math.tan(math.radians(r.rebound_angle_deg)) == pytest.approx(r.e_t / r.e_n * 2.0 / 5.0, rel=1e-9)
    d = json.loads(json.dumps(r.to_dict()))
    for key in ("e_n", "e_t", "omega_r", "f", "f_over_mu", "Theta", "Psi_r", "Omega_r", "contact_time",
                "max_overlap", "max_force", "persistent_sliding", "steps"):
        assert key in d
    assert set(d["energy"]) == {"initial", "final", "friction", "normal", "error"}


@pytest.mark.parametrize("normal,kw", NORMALS)
def test_default_time_step_is_the_contact_time_over_the_steps(steel_sphere, steel_wall, normal, kw):
    """impact() at the default resolution steps exactly t_c / DEFAULT_STEPS_PER_CONTACT, t_c from
    Scene.contact_time, for every normal law and speed (as with an explicit steps_per_contact)."""
    sc = scene(steel_sphere, steel_wall, mu=0.3, normal=normal, **kw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for vn in (0.3, 2.0, 7.5):
            spc = dc.DEFAULT_STEPS_PER_CONTACT
            r = dc.impact(sc, vn, 1.0)
            assert r.dt == sc.contact_time(vn) / spc
            assert r.dt == dc.impact(sc, vn, 1.0, steps_per_contact=spc).dt
            assert r.settings["steps_per_contact"] == spc
