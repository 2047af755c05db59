"""Chung & Ooi (2011) benchmark tests against their analytic answers (Chung & Ooi 2011)."""
import math

import numpy as np
import pytest

from dem_contact.studies import chung_ooi as co
from dem_contact.laws import closed_forms as cf
from dem_contact.cli import main
from dem_contact.impacts.impact import impact
from dem_contact.materials import Sphere, Wall
from dem_contact.laws.model import Scene
from dem_contact.laws.model import reference_speed

DEFAULT = [co.default_tangential_law()]


def test_hertz_quadrature_reproduces_the_closed_form_contact_time():
    E, R, m, v = 1e10, 1e-3, 1e-5, 1.0
    t, F, d = co.hertz_force_time(E, R, m, v)
    assert t[-1] == pytest.approx(cf.hertz_contact_time(E, R, m, v), rel=1e-4)
    assert F.max() == pytest.approx(cf.hertz_max_force(E, R, m, v), rel=1e-12)


@pytest.mark.parametrize("n", [1, 2])
def test_elastic_normal_impacts_match_hertz(n):
    res = co.run_test(n)
    for d in res.data.values():
        assert d["peak_force"] == pytest.approx(d["hertz_peak_force"], rel=5e-3)
        assert d["contact_time"] == pytest.approx(d["hertz_contact_time"], rel=5e-3)
    assert all(c.passed for c in res.checks if "force-time" in c.name)


def test_prescribed_restitution_is_reproduced_including_zero():
    res = co.run_test(3)
    for d in res.data.values():
        assert d["e_n_in"][0] == 0.0
        np.testing.assert_allclose(d["e_n_out"], d["e_n_in"], atol=1e-3, rtol=0)


def test_oblique_constant_speed_sliding_branch_is_rigid_body():
    res = co.run_test(4, laws=DEFAULT)
    mu, e_n, R, speed = res.settings["mu"], res.settings["e_n"], 2.5e-3, 3.9
    n_sliding = 0
    for label in ("Al oxide", "Al alloy"):
        d = res.data[label][DEFAULT[0]]
        for ang, e_t, w_r in zip(d["angle_deg"], d["e_t"], d["omega_r"]):
            tan = math.tan(math.radians(ang))
            if tan < 3.5 * mu * (1 + e_n):
                continue
            n_sliding += 1
            vn = speed * math.cos(math.radians(ang))
            assert e_t == pytest.approx(1 - mu * (1 + e_n) / tan, rel=5e-3)
            assert w_r == pytest.approx(-2.5 * mu * (1 + e_n) * vn / R, rel=5e-3)
    assert n_sliding >= 10


@pytest.mark.parametrize("test", [6, 8])
def test_spinning_sphere_sliding_branch_is_rigid_body_sliding(test):
    """Tests 6 and 8: for chi <= 1 (the patch slides throughout) beta = chi - 1 and the recoil angle follow
    the rigid-body formulas within 0.5%."""
    res = co.run_test(test, laws=DEFAULT)
    d = res.data[DEFAULT[0]]
    chi = np.asarray(d["chi"])
    sliding = chi <= 1.0
    assert sliding.sum() >= 5
    ref = co.rigid_spin(chi[sliding], 0.4, 0.5)
    assert np.max(np.abs(np.asarray(d["beta"])[sliding] - ref["beta"])) < 5e-3
    np.testing.assert_allclose(np.asarray(d["recoil_angle_deg"])[sliding], ref["recoil_angle_deg"], rtol=5e-3)


def test_damped_hertz_misses_the_sliding_branch_independently_of_dt():
    """With hertz_damped the dashpot outruns the tangential spring at first touch: f/mu < 1 near chi = 1,
    the same at 1000 and 4000 steps per contact (a model property, not a time-step error)."""
    scene = Scene(Sphere(0.1, co.AL_ALLOY), Wall.rigid(), mu=0.4, normal="hertz_damped", e_n=0.5,
                  tangential=DEFAULT[0], v_ref=reference_speed(0.2))
    f = [impact(scene, 0.2, 0.0, 4.2 / 0.9, steps_per_contact=spc).f_over_mu for spc in (1000, 4000)]
    assert f[0] == pytest.approx(f[1], abs=1e-3)
    assert f[0] < 0.99


def test_sphere_pair_impulse_relations_use_both_inertias():
    """1/m* + R1^2/I1 + R2^2/I2 = 3.5/m*: v_tr = v_ti - 3.5 P_t/m*, w2_r = w2_i - R2 P_t/I2."""
    s1, s2 = Sphere(0.1, co.AL_ALLOY), Sphere(0.5, co.AL_ALLOY)
    scene = Scene(s1, s2, mu=0.4, normal="hertz_damped", e_n=0.5, tangential=DEFAULT[0], v_ref=reference_speed(0.2))
    w1, w2 = 10.0, -1.0
    r = impact(scene, 0.2, 0.05, w1, spin2=w2, steps_per_contact=co.STEPS_PER_CONTACT)
    Pt, m = r.tangential_impulse, scene.pair.m_star
    v_ti = 0.05 + 0.1 * w1 + 0.5 * w2
    v_tr = r.vt_r + 0.1 * r.omega_r + 0.5 * r.omega2_r
    assert v_tr == pytest.approx(v_ti - 3.5 * Pt / m, rel=1e-9)
    assert r.omega2_r == pytest.approx(w2 - 0.5 * Pt / s2.inertia, rel=1e-9)
    assert r.omega_r == pytest.approx(w1 - 0.1 * Pt / s1.inertia, rel=1e-9)


def test_equal_and_opposite_spins_do_not_slip():
    res = co.run_test(7, laws=DEFAULT)
    d = res.data[DEFAULT[0]]
    w = np.asarray(d["spin"])
    np.testing.assert_allclose(d["omega1_r"], w, rtol=1e-6)
    np.testing.assert_allclose(d["omega2_r"], -w, rtol=1e-6)
    assert np.all(np.abs(d["vt_r"]) <= 1e-6 * 0.1 * w)
    # the same sense of spin makes the patch slip at 2 R w: spins change
    scene = Scene(Sphere(0.1, co.AL_ALLOY), Sphere(0.1, co.AL_ALLOY), mu=0.4, normal="hertz_damped", e_n=0.5,
                  tangential=DEFAULT[0], v_ref=reference_speed(0.4))
    r = impact(scene, 0.4, 0.0, 5.0, spin2=5.0)
    assert abs(r.omega_r - 5.0) > 1e-2


def test_cli_bad_test_number_exits_2_with_one_line(capsys):
    assert main(["benchmark", "chung-ooi", "--test", "9"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "1-8" in err


def test_cli_runs_one_test(capsys):
    assert main(["benchmark", "chung-ooi", "--test", "3"]) == 0
    out = capsys.readouterr().out
    assert "checks passed" in out and "FAIL" not in out
