"""Sweeps: exact agreement with single impacts, momentum identities, universality, critical angle, CLI."""
import json
import math
import warnings

import numpy as np
import pytest

from dem_contact.rebound import models as rm
from dem_contact.cli import main
from dem_contact.impacts.presets import preset_scene
from dem_contact.errors import InputError
from dem_contact.impacts.impact import impact
from dem_contact.studies.wu2009 import UNIVERSALITY_TOL
from dem_contact.impacts.sweep import critical_angle, scene_with, sweep, sweep_angles, sweep_speed, sweep_theta

SPC = 200
ANGLES = [0.0, 10.0, 25.0, 40.0, 55.0, 70.0]


@pytest.fixture(scope="module")
def ee():
    return preset_scene("EE", 5.0)


@pytest.mark.parametrize("case", ["EE", "PE"])
def test_sweep_equals_single_impacts(case):
    scene = preset_scene(case, 5.0)
    res = sweep_angles(scene, ANGLES, 5.0, steps_per_contact=SPC)
    for a, r in zip(ANGLES, res.points):
        one = impact(scene, 5.0, 5.0 * math.tan(math.radians(a)), steps_per_contact=SPC)
        for key in ("vn_r", "vt_r", "omega_r", "normal_impulse", "tangential_impulse", "contact_time", "steps"):
            assert getattr(r, key) == getattr(one, key), key
        assert r.persistent_sliding == one.persistent_sliding


def test_sweep_with_spin_and_progress_equals_single_impacts(ee):
    vt = np.array([0.5, 1.0, 2.0])
    spin = np.array([-30.0, 0.0, 40.0])
    res = sweep(ee, 3.0, vt, spin, steps_per_contact=SPC, progress=True)
    for i in range(3):
        one = impact(ee, 3.0, vt[i], spin[i], steps_per_contact=SPC)
        assert res.points[i].omega_r == one.omega_r and res.points[i].vt_r == one.vt_r


@pytest.mark.parametrize("tangential, spc", [("mdr_adaptive", SPC), ("mindlin_total", 7)])
def test_sweep_arrays_and_flags_equal_the_impacts(ee, tangential, spc):
    """The arrays of a sweep (computed from the output rows together) are those of the ImpactResults of its
    impacts, flags and warnings included (7 steps per contact: every impact warns of coarse steps)."""
    scene = scene_with(ee, tangential=tangential)
    vt = np.array([0.0, 0.5, 2.0, 6.0])
    spin = np.array([0.0, -40.0, 0.0, 25.0])
    res = sweep(scene, 4.0, vt, spin, steps_per_contact=spc)
    for i in range(vt.size):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            one = impact(scene, 4.0, vt[i], spin[i], steps_per_contact=spc)
        for arr, key in (("theta_deg", "theta_i_deg"), ("Theta", "Theta"), ("f_over_mu", "f_over_mu"),
                         ("e_n", "e_n"), ("e_t", "e_t"), ("Psi_r", "Psi_r"), ("Omega_r", "Omega_r"),
                         ("Omega_i", "Omega_i"), ("persistent_sliding", "persistent_sliding"),
                         ("energy_created", "energy_created"), ("energy_gained", "energy_gained")):
            a, b = getattr(res, arr)[i], getattr(one, key)
            assert a == b or (math.isnan(a) and math.isnan(b)), (arr, i)
        assert res.points[i].warnings == one.warnings == [str(w.message) for w in caught]
        assert res.points[-len(vt) + i] is res.points[i]
    n_coarse = sum("steps per contact" in w for w in res.warnings)
    assert n_coarse == (1 if spc < 10 else 0)


def test_warmup_command(capsys):
    assert main(["warmup"]) == 0
    assert "kernels ready" in capsys.readouterr().out


def test_momentum_identities_of_sweep_points(ee):
    res = sweep_angles(ee, np.linspace(1.0, 80.0, 12), 5.0, steps_per_contact=SPC)
    fm, T = res.f_over_mu, res.Theta
    assert np.allclose(res.Omega_r, -fm, rtol=0, atol=1e-9)
    assert np.allclose(res.e_t, 1 - 2 * fm / T, rtol=0, atol=1e-9)
    assert np.allclose(res.Psi_r, T - 7 * fm, rtol=0, atol=1e-8)
    assert np.all(fm <= 1 + 1e-12)
    assert np.all(res.f_over_mu[res.persistent_sliding] == pytest.approx(1.0, abs=1e-9))


def test_sweep_speed_keeps_total_speed(ee):
    res = sweep_speed(ee, [10.0, 45.0, 80.0], speed=3.9, steps_per_contact=SPC)
    for a, r in zip([10.0, 45.0, 80.0], res.points):
        assert math.hypot(r.vn_i, r.vt_i) == pytest.approx(3.9)
        assert r.theta_i_deg == pytest.approx(a)


def test_universality_in_mu_and_speed():
    """Elastic curves f/mu(Theta) do not depend on mu or V_n (validation report: measured agreement
    well inside UNIVERSALITY_TOL for the default law)."""
    theta = [0.5, 1.5, 3.0, 4.5, 5.5, 7.0]
    a = sweep_theta(scene_with(preset_scene("EE", 5.0), mu=0.1), theta, 5.0, steps_per_contact=SPC)
    b = sweep_theta(scene_with(preset_scene("EE", 5.0), mu=0.5), theta, 5.0, steps_per_contact=SPC)
    c = sweep_theta(scene_with(preset_scene("EE", 2.0), mu=0.5), theta, 2.0, steps_per_contact=SPC)
    assert np.allclose(a.Theta, b.Theta, rtol=1e-12)
    assert np.max(np.abs(a.f_over_mu - b.f_over_mu)) < UNIVERSALITY_TOL
    assert np.max(np.abs(a.f_over_mu - c.f_over_mu)) < UNIVERSALITY_TOL
    assert a.f_over_mu[-1] == pytest.approx(1.0)


def test_scene_with_poisson_ratio():
    re = preset_scene("RE", 5.0, nu=0.0)
    for nu in (0.0, 0.3, 0.49):
        s = scene_with(re, nu=nu)
        assert s.pair.kappa == pytest.approx(float(rm.kappa_from_nu(nu)))
    assert scene_with(re, mu=0.1).mu == 0.1
    with pytest.raises(InputError):
        scene_with(re, nu=0.2, body="sphere")  # the RE sphere is rigid


def test_critical_angle_brackets_persistent_sliding(ee):
    c = critical_angle(ee, 5.0, steps_per_contact=SPC, tol_deg=1e-4)
    lo, hi = c.bracket_deg
    assert hi - lo <= 1e-4
    assert impact(ee, 5.0, 5.0 * math.tan(math.radians(hi)), steps_per_contact=SPC).persistent_sliding
    assert not impact(ee, 5.0, 5.0 * math.tan(math.radians(lo)), steps_per_contact=SPC).persistent_sliding


def test_md_critical_theta_is_maw_criterion():
    """Maw's criterion (eq. 4.1): sliding throughout the impact from Theta_c = (7 kappa - 1)/kappa."""
    scene = preset_scene("EE", 5.0, tangential="md")
    c = critical_angle(scene, 5.0, steps_per_contact=SPC, tol_deg=1e-5)
    assert c.Theta == pytest.approx(rm.theta_c_theory(scene.pair.kappa), rel=1e-3)


def test_sweep_rows_survive_a_fit_of_eq_4_5_that_fails(ee):
    """From Python the sweep and the fit are separate calls: zoomed on the critical angle the tanh of
    eq. 4.5 does not converge (NumericalError), all in persistent sliding there is nothing to fit
    (InputError); either way the rows are there and the simulated Theta_c is Maw's (eq. 4.1, e_n = 1)."""
    from dem_contact.errors import NumericalError
    from dem_contact.rebound.fit import fit_wu

    zoom = sweep_angles(ee, np.arange(55.0, 70.25, 0.5), 5.0)
    assert len(zoom.points) == 31 and np.all(np.isfinite(zoom.f_over_mu))
    with pytest.raises(NumericalError, match="eq. 4.5"):
        fit_wu(zoom.Theta, zoom.f_over_mu, zoom.persistent_sliding)
    sliding = sweep_angles(ee, [70.0, 75.0, 80.0, 85.0], 5.0)
    assert np.all(sliding.persistent_sliding) and np.all(sliding.f_over_mu == pytest.approx(1.0, abs=1e-12))
    with pytest.raises(InputError, match="at least 5 points"):
        fit_wu(sliding.Theta, sliding.f_over_mu, sliding.persistent_sliding)
    assert critical_angle(ee, 5.0).Theta == pytest.approx(rm.theta_c_theory(ee.pair.kappa), rel=2e-3)


def test_sweep_input_errors(ee):
    with pytest.raises(InputError, match="angle"):
        sweep_angles(ee, [10.0, 95.0])
    with pytest.raises(InputError, match="same length"):
        sweep(ee, [1.0, 2.0], [0.1, 0.2, 0.3])
    with pytest.raises(InputError, match="vn"):
        sweep(ee, [-1.0], [0.1])


def test_cli_json_and_csv(tmp_path, capsys):
    csv_path = tmp_path / "s.csv"
    rc = main(["sweep", "--angles", "0:66:6", "--steps-per-contact", "100", "--json", "--csv", str(csv_path),
               "--no-progress"])
    assert rc == 0
    d = json.loads(capsys.readouterr().out)
    assert [p["theta_deg"] for p in d["points"]] == pytest.approx(list(range(0, 67, 6)))
    assert d["points"][0]["e_t"] is None  # undefined at 0 deg
    for k in ("c1", "c2", "c3", "c4", "Theta_c", "c1_err", "Theta_c_err"):
        assert k in d["fit"]
    assert d["Theta_c_theory"] == pytest.approx(5.7857, abs=1e-4)
    assert d["Theta_c_sim"] > 4
    rows = csv_path.read_text().strip().splitlines()
    assert len(rows) == 1 + 12 and rows[0].startswith("theta_deg,")


def test_cli_default_writes_figure(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["sweep", "--angles", "0:80:8", "--steps-per-contact", "50", "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "figure written to sweep_EE.png" in out
    assert (tmp_path / "sweep_EE.png").stat().st_size > 10000


@pytest.mark.parametrize("bad", ["1:2", "a:b:c", "0:85:0", "50:10:1", "0:95:1"])
def test_cli_bad_angles(bad, capsys):
    assert main(["sweep", "--angles", bad, "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--angles" in err
