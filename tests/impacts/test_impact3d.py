"""3D impacts with any spin vector: planar reduction, rotation about the normal, rolling, spin about the
normal, momentum identities across the impact plane, sweeps and bad input."""
import math

import numpy as np
import pytest

import dem_contact as dc
from dem_contact.errors import InputError
from dem_contact.impacts.impact3d import impact3d, sweep3d
from dem_contact.laws.slots import P_TY_NODES
from dem_contact.laws.model import reference_speed

LAWS = ["mdr_adaptive", "md", "mindlin_incremental"]
R = 0.01


def rot(phi, v):
    c, s = math.cos(phi), math.sin(phi)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


@pytest.fixture(scope="module")
def scenes(steel_sphere, steel_wall):
    return {t: dc.Scene(steel_sphere, steel_wall, mu=0.3, tangential=t, v_ref=reference_speed(5.0)) for t in LAWS}


@pytest.mark.parametrize("tangential", LAWS)
@pytest.mark.parametrize("scheme", ["located", "standard"])
def test_planar_reduction(scenes, tangential, scheme):
    """No out-of-plane spin: the planar integrator's results to 1e-10 (same law, dt and scheme)."""
    sc = scenes[tangential]
    for vt, spin in [(0.8, 0.0), (3.0, -120.0), (-2.0, 250.0)]:
        r = dc.impact(sc, 5.0, vt, spin, scheme=scheme)
        q = impact3d(sc, 5.0, (vt, 0.0), (0.0, spin, 0.0), scheme=scheme)
        s = math.copysign(1.0, vt)          # the impact plane's axis e1 follows the tangential velocity
        assert q.plane_axis == [s, 0.0]
        for a, b in [(r.vn_r, q.vn_r), (r.vt_r, q.vt_r[0]), (r.omega_r * R, q.spin_r[1] * R),
                     (r.e_n, q.e_n), (r.e_t, q.e_t), (r.f_over_mu, s * q.f_over_mu), (r.Theta, s * q.Theta),
                     (r.Psi_r, s * q.Psi_r), (r.Omega_r, s * q.Omega_r), (r.contact_time * 1e5, q.contact_time * 1e5)]:
            assert a == pytest.approx(b, abs=1e-10, rel=1e-10)
        assert q.vt_r[1] == 0.0 and q.spin_r[0] == 0.0 and q.spin_r[2] == 0.0 and q.f_across_over_mu == 0.0
        assert q.energy.friction == pytest.approx(r.energy.friction, rel=1e-10, abs=1e-12 * r.energy.initial)


def test_planar_reduction_two_spheres(steel_sphere):
    other = dc.Sphere(0.015, dc.STEEL)
    sc = dc.Scene(steel_sphere, other, mu=0.3)
    r = dc.impact(sc, 3.0, 1.0, 40.0, spin2=-90.0)
    q = impact3d(sc, 3.0, (1.0, 0.0), (0.0, 40.0, 0.0), spin2=(0.0, -90.0, 0.0))
    assert q.vt_r[0] == pytest.approx(r.vt_r, rel=1e-10)
    assert q.spin_r[1] == pytest.approx(r.omega_r, rel=1e-10)
    assert q.spin2_r[1] == pytest.approx(r.omega2_r, rel=1e-10)
    assert q.f_over_mu == pytest.approx(r.f_over_mu, rel=1e-10)


@pytest.mark.parametrize("tangential", LAWS)
def test_out_of_plane_spin_is_the_planar_impact_along_the_slip(scenes, tangential):
    """Wall: ds/dt = (1/m + R^2/I) F_t in every direction, so the slip stays on its incident line and the
    impulse is the planar impact's at the incident slip speed, along the slip (rounding error)."""
    sc = scenes[tangential]
    for V, w in [((1.5, 0.0), (60.0, 0.0, 0.0)), ((1.5, 0.0), (-300.0, -80.0, 0.0)),
                 ((0.7, -1.1), (120.0, 40.0, 0.0)), ((2.0, 0.5), (-500.0, 300.0, 0.0))]:
        q = impact3d(sc, 5.0, V, w)
        s = np.array([V[0] + R * w[1], V[1] - R * w[0]])
        speed = float(np.hypot(*s))
        r = dc.impact(sc, 5.0, speed, 0.0)
        e = s / speed
        P = np.array(q.tangential_impulse)
        # planar: impulse against the slip, f = P_t / P_n
        assert np.allclose(-P / q.normal_impulse, r.f * e, rtol=0, atol=1e-10 * 0.3)
        assert q.e_n == pytest.approx(r.e_n, rel=1e-12)
        s_r = np.array([q.vt_r[0] + R * q.spin_r[1], q.vt_r[1] - R * q.spin_r[0]])
        v_tr = r.vt_r + R * r.omega_r
        assert np.allclose(s_r, v_tr * e, rtol=0, atol=1e-10 * speed)
        assert q.spin_r[2] == w[2]


def test_two_spheres_out_of_plane_spins(steel_sphere):
    """Two spheres: ds/dt = (1/m* + R1^2/I1 + R2^2/I2) F_t, again the same in every direction: spins of both
    bodies about any in-plane axes give the planar impact at the incident slip speed, along the slip."""
    other = dc.Sphere(0.02, dc.STEEL)
    sc = dc.Scene(steel_sphere, other, mu=0.3)
    V, w1, w2 = (0.8, 0.3), (150.0, -40.0, 0.0), (-60.0, 90.0, 0.0)
    q = impact3d(sc, 3.0, V, w1, spin2=w2)
    s = np.array([V[0] + R * w1[1] + 0.02 * w2[1], V[1] - R * w1[0] - 0.02 * w2[0]])
    speed = float(np.hypot(*s))
    r = dc.impact(sc, 3.0, speed, 0.0)
    P = np.array(q.tangential_impulse)
    assert np.allclose(-P / q.normal_impulse, r.f * s / speed, rtol=0, atol=1e-10 * 0.3)


@pytest.mark.parametrize("tangential", LAWS)
def test_rotation_about_the_normal(scenes, tangential):
    """Turning the whole incident state about the normal turns every rebound vector with it."""
    sc = scenes[tangential]
    V, w = np.array([1.2, 0.4]), np.array([150.0, -60.0, 0.0])
    a = impact3d(sc, 5.0, V, w)
    for phi in [0.3, 2.0, -2.9]:
        wr = np.concatenate([rot(phi, w[:2]), [0.0]])
        b = impact3d(sc, 5.0, rot(phi, V), wr)
        assert np.allclose(b.vt_r, rot(phi, a.vt_r), rtol=0, atol=1e-11)
        assert np.allclose(b.spin_r[:2], rot(phi, a.spin_r[:2]), rtol=0, atol=1e-9)
        assert b.f_over_mu == pytest.approx(a.f_over_mu, abs=1e-11)
        assert b.f_across_over_mu == pytest.approx(a.f_across_over_mu, abs=1e-11)


@pytest.mark.parametrize("tangential", LAWS)
def test_rolling_without_slip_stays_rolling(scenes, tangential):
    sc = scenes[tangential]
    for V in [(2.0, 0.0), (-0.6, 1.3)]:
        w = (V[1] / R, -V[0] / R, 25.0)           # V + R w x n = 0
        q = impact3d(sc, 5.0, V, w, series=True)
        assert np.max(np.abs(q.series["tangential_force_x"])) == 0.0
        assert np.max(np.abs(q.series["tangential_force_y"])) == 0.0
        assert np.allclose(q.vt_r, V, rtol=0, atol=1e-14) and np.allclose(q.spin_r, w, rtol=0, atol=1e-12)
        assert q.f_over_mu == 0.0 and q.energy.friction == 0.0
        assert q.e_n == pytest.approx(dc.impact(sc, 5.0).e_n, rel=1e-14)


@pytest.mark.parametrize("tangential", LAWS)
def test_spin_about_the_normal_is_kept(scenes, tangential):
    """No torque about the normal: the spin about it is kept exactly. Without tangential velocity the
    trajectory is the normal impact's; with it and a history fixed in space (frame_spin=False) it is the
    impact without the spin."""
    sc = scenes[tangential]
    q = impact3d(sc, 5.0, (0.0, 0.0), (0.0, 0.0, 700.0))
    r = dc.impact(sc, 5.0)
    assert q.spin_r == [0.0, 0.0, 700.0] and q.vt_r == [0.0, 0.0]
    assert q.vn_r == r.vn_r and q.contact_time == r.contact_time
    q = impact3d(sc, 5.0, (1.0, 0.0), (0.0, -30.0, 700.0), frame_spin=False)
    r = dc.impact(sc, 5.0, 1.0, -30.0)
    assert q.spin_r[2] == 700.0 and q.spin_r[0] == 0.0 and q.vt_r[1] == 0.0
    assert q.vt_r[0] == pytest.approx(r.vt_r, rel=1e-12) and q.spin_r[1] == pytest.approx(r.omega_r, rel=1e-12)
    assert q.vn_r == r.vn_r
    q = impact3d(sc, 5.0, (1.0, 0.0), (0.0, -30.0, 700.0))
    assert q.spin_r[2] == 700.0


@pytest.mark.parametrize("tangential", LAWS)
def test_momentum_identities_in_both_directions(scenes, tangential):
    """Eqs 2.21-2.23 along the impact plane and across it; energy balance."""
    sc = scenes[tangential]
    for V, w in [((1.0, 0.0), (200.0, -50.0, 10.0)), ((0.3, 0.9), (-400.0, 90.0, 0.0))]:
        q = impact3d(sc, 5.0, V, w)
        assert q.Omega_r == pytest.approx(q.Omega_i - q.f_over_mu, abs=1e-9)
        assert q.Omega_across_r == pytest.approx(q.Omega_across_i - q.f_across_over_mu, abs=1e-9)
        # Theta of the contact patch (eq. 7.1): Psi_r = Theta + 7 (Omega_r - Omega_i) = Theta - 7 f/mu
        assert q.Psi_r == pytest.approx(q.Theta + 7 * (q.Omega_r - q.Omega_i), abs=1e-9)
        assert q.Psi_r_across == pytest.approx(q.Theta_across + 7 * (q.Omega_across_r - q.Omega_across_i),
                                               abs=1e-9)
        assert math.hypot(q.f_over_mu, q.f_across_over_mu) <= 1.0 + 1e-12
        assert abs(q.energy.error) < 1e-4 * q.energy.initial      # trapezoid works, as in the planar test
        assert q.energy.friction >= 0.0


def test_sweep3d_matches_single_impacts(scenes):
    sc = scenes["mdr_adaptive"]
    res = sweep3d(sc, [10.0, 40.0], vn=5.0, spin=(100.0, 0.0, 0.0), direction_deg=30.0)
    v = 5.0 * math.tan(math.radians(40.0))
    one = impact3d(sc, 5.0, (v * math.cos(math.radians(30)), v * math.sin(math.radians(30))), (100.0, 0.0, 0.0))
    assert res[1].vt_r == one.vt_r and res[1].f_over_mu == one.f_over_mu
    assert res[0].plane_axis == pytest.approx([math.cos(math.radians(30)), math.sin(math.radians(30))])


def test_bad_input(scenes):
    sc = scenes["mdr_adaptive"]
    with pytest.raises(InputError, match="vt"):
        impact3d(sc, 5.0, (1.0, 0.0, 0.0))
    with pytest.raises(InputError, match=r"spin\[1\]"):
        impact3d(sc, 5.0, (1.0, 0.0), (0.0, math.nan, 0.0))
    with pytest.raises(InputError, match="spin2"):
        impact3d(sc, 5.0, (1.0, 0.0), spin2=(0.0, 1.0, 0.0))
    with pytest.raises(InputError, match="vn"):
        impact3d(sc, -1.0)
    with pytest.raises(InputError, match="angle"):
        sweep3d(sc, [95.0])


def test_command(tmp_path, capsys):
    import json

    from dem_contact.cli import main

    assert main(["impact3d", "--vt", "1", "0", "--spin-vector", "0", "30", "0", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    r = dc.impact(dc.Scene(dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL), mu=0.3), 5.0, 1.0, 30.0)
    assert d["f_over_mu"] == pytest.approx(r.f_over_mu, rel=1e-12) and d["spin_r"][1] == pytest.approx(r.omega_r)
    assert main(["impact3d", "--angles", "10:30:10", "--spin-vector", "100", "0", "0", "--direction", "90",
                 "--csv", str(tmp_path / "s.csv")]) == 0
    rows = (tmp_path / "s.csv").read_text().splitlines()
    assert len(rows) == 4 and rows[0].startswith("theta_deg,Theta,Theta_across")
    capsys.readouterr()
    for argv in (["impact3d", "--vt", "1", "0", "--angle", "3"], ["impact3d", "--csv", "x.csv"],
                 ["impact3d", "--spin-vector", "1", "nan", "0"], ["impact3d", "--vt", "1", "0", "--direction", "3"]):
        assert main(argv) == 2, argv
        assert capsys.readouterr().err.count("\n") == 1


def test_magnitudes_beyond_double_precision_are_refused():
    """A spin or tangential speed whose kinetic energy overflows is an InputError naming it (as in impact())."""
    import dem_contact as dc
    from dem_contact.impacts.impact3d import impact3d

    sc = dc.Scene(dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL), mu=0.3)
    with pytest.raises(dc.InputError, match="spin"):
        impact3d(sc, 5.0, (1.0, 0.0), (1e300, 0.0, 0.0))
    with pytest.raises(dc.InputError, match="vt"):
        impact3d(sc, 5.0, (1e300, 1e300), (0.0, 0.0, 0.0))


CHECKED = {   # scenes and impacts that set off each check of impact(): (scene, vn, vt, steps per contact, scheme)
    "energy balance": (lambda: dc.Scene(dc.Sphere(R, dc.STEEL), dc.Wall(dc.STEEL)), 5.0, 1.0, 5, "located"),
    "validity": (lambda: dc.Scene(dc.Sphere(R, dc.Material(E=5e6, nu=0.45, rho=1100.0)), dc.Wall(dc.STEEL)),
                 20.0, 1.0, 50, "located"),
    "energy gained": (lambda: dc.Scene(dc.Sphere(R, dc.STEEL), dc.Wall(dc.STEEL)), 5.0, 1.0, 20, "standard"),
    "|f| > mu": (lambda: dc.Scene(dc.Sphere(R, dc.STEEL), dc.Wall(dc.STEEL), normal="linear", tangential="linear",
                                  e_n=0.3, v_ref=5.0), 5.0, 15.0, 50, "located"),
    "calibration": (lambda: dc.Scene(dc.Sphere(R, dc.STEEL), dc.Wall(dc.STEEL), normal="hertz_damped", e_n=0.01),
                    5.0, 1.0, 20, "located"),
}


@pytest.mark.parametrize("case", list(CHECKED))
def test_impact3d_has_the_checks_of_impact(case):
    """impact3d flags and warns as impact() does (a planar impact in 3D): energy gained, e_n > 1, energy
    balance, range of validity, |f| > mu, calibration miss; the same kinds of warning on both paths."""
    import warnings

    from dem_contact.impacts.sweep import _NUMBER

    make, vn, vt, spc, scheme = CHECKED[case]
    sc = make()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = dc.impact(sc, vn, vt, steps_per_contact=spc, scheme=scheme)
        q = impact3d(sc, vn, (vt, 0.0), steps_per_contact=spc, scheme=scheme)
    kinds = lambda ws: sorted(_NUMBER.sub("#", w) for w in ws)  # noqa: E731
    assert r.warnings and kinds(q.warnings) == kinds(r.warnings)
    assert q.energy_gained == r.energy_gained and q.energy_created == r.energy_created


def test_traction_yield_acts_in_3d_as_in_the_plane(capsys):
    """The traction-coupled Thornton law in the 3D kernels: an aluminium sphere (5 mm, p_y 1 GPa) on an
    aluminium wall at 5 m/s, 60 degrees from the normal, thornton + mdr_adaptive: impact3d gives the e_n of
    impact() (a planar path: the same law to rounding), and a lower e_n than without the coupling (the
    option acts); a pair table carries it to the batch kernels and LammpsContacts; the CLI runs it."""
    from dem_contact.cli import main
    from dem_contact.impacts.impact import impact
    from dem_contact.materials import Material, Sphere, Wall

    al = Material(E=70e9, nu=0.33, rho=2700.0, yield_pressure=1e9)
    sc = dc.Scene(Sphere(5e-3, al), Wall(al), mu=0.3, normal="thornton", traction_yield=True)
    vn, vt = 5.0 * math.cos(math.radians(60.0)), 5.0 * math.sin(math.radians(60.0))
    planar, q = impact(sc, vn, vt), impact3d(sc, vn, (vt, 0.0))
    plain = impact3d(sc.replace(traction_yield=False), vn, (vt, 0.0))
    assert q.e_n == pytest.approx(planar.e_n, rel=1e-6, abs=0.0)
    assert q.e_n < plain.e_n - 0.01
    from dem_contact.dem.pairs import pair_table
    tab = pair_table([sc.sphere], [sc.body2], normal="thornton", traction_yield=True)
    assert tab.params[0, P_TY_NODES] > 0.0
    assert main(["impact3d", "--case", "PE", "--traction-yield", "--angle", "30"]) == 0
