"""Rebound models (Wu, Thornton & Li 2009, section 4): identities, limits, critical values."""
import numpy as np
import pytest

from dem_contact.rebound import models as rm

T = np.linspace(0.05, 15.0, 300)
EE = rm.PUBLISHED_FITS["EE"]


@pytest.mark.parametrize("model", [
    lambda t: rm.wu(t, EE["c"]),
    lambda t: rm.bilinear(t, 0.8235),
    lambda t: rm.rigid_body(t),
])
def test_momentum_identities(model):
    m = model(T)
    fm = m["f_over_mu"]
    assert np.allclose(m["e_t"], 1 - 2 * fm / T, rtol=0, atol=1e-14)
    assert np.allclose(m["Omega_r"], -fm, rtol=0, atol=1e-14)
    assert np.allclose(m["Psi_r"], T - 7 * fm, rtol=0, atol=1e-12)
    assert np.all(fm <= 1.0) and np.all(fm >= 0.0)


@pytest.mark.parametrize("vt, spin", [(2.0, 300.0), (6.0, 300.0), (2.0, -150.0), (6.0, -150.0)])
def test_models_with_initial_spin_match_spinning_impacts(vt, spin):
    """Elastic steel sphere, 5 m/s normal, both spin signs, below and above Theta_c: the models read at the
    patch Theta (eq. 7.1) give the simulated e_t and Psi_r to the published fit's own error, and with the
    simulated f/mu they give the simulation's e_t, Psi_r and Omega_r to rounding (the identities are exact)."""
    import dem_contact as dc

    scene = dc.Scene(dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL), mu=0.3)
    r = dc.impact(scene, vn=5.0, vt=vt, spin=spin)
    m = rm.wu(r.Theta, EE["c"], Omega_i=r.Omega_i)
    assert abs(m["e_t"] - r.e_t) <= 0.06 and abs(m["Psi_r"] - r.Psi_r) <= 0.3
    exact = rm.wu(r.Theta, (r.f_over_mu, 0.0, 0.0, 0.0), Omega_i=r.Omega_i)   # f/mu = the simulated value
    assert exact["e_t"] == pytest.approx(r.e_t, abs=1e-9)
    assert exact["Psi_r"] == pytest.approx(r.Psi_r, abs=1e-9)
    assert exact["Omega_r"] == pytest.approx(r.Omega_r, abs=1e-9)


def test_spin_identity_of_two_spheres():
    """Two identical spheres: Omega_r - Omega_i = -(m*/m1) f/mu = -f/(2 mu); e_t and Psi_r as on a wall."""
    import dem_contact as dc

    s = dc.Sphere(0.01, dc.STEEL)
    r = dc.impact(dc.Scene(s, s, mu=0.3), vn=5.0, vt=2.0, spin=100.0)
    exact = rm.wu(r.Theta, (r.f_over_mu, 0.0, 0.0, 0.0), Omega_i=r.Omega_i, mass_ratio=0.5)
    for key in ("e_t", "Psi_r", "Omega_r"):
        assert exact[key] == pytest.approx(getattr(r, key), abs=1e-9), key
    with pytest.raises(dc.InputError, match="mass_ratio"):
        rm.wu(1.0, EE["c"], mass_ratio=2.0)


@pytest.mark.parametrize("nu, expected", [(0.0, 6.0), (0.3, 5.786), (0.49, 5.520)])
def test_theta_c_eq_4_1(nu, expected):
    assert rm.theta_c_theory(rm.kappa_from_nu(nu)) == pytest.approx(expected, abs=6e-4)
    assert rm.collapse_variable(expected, rm.kappa_from_nu(nu)) == pytest.approx(1.0, abs=1e-4)


def test_theta_c_with_restitution():
    """7 - 2 e_n / (kappa (1 + e_n)): eq. 4.1 at e_n = 1, 7 at e_n = 0 (no rebound), rising as e_n falls."""
    k = rm.kappa_from_nu(0.3)
    assert rm.theta_c_theory(k, 1.0) == pytest.approx(rm.theta_c_theory(k), abs=1e-15)
    assert rm.theta_c_theory(k, 0.0) == 7.0
    e = np.linspace(0.0, 1.0, 11)
    assert np.all(np.diff(rm.theta_c_theory(k, e)) < 0)
    b = rm.regime_boundaries(k, 1.0)
    assert b["initial_sliding"] == pytest.approx(1.0 / k) and b["compression_sliding"] == 3.5
    with pytest.raises(rm.InputError, match="e_n"):
        rm.theta_c_theory(k, 1.2)


def test_persistent_sliding_limits():
    for m in (rm.wu(T, EE["c"]), rm.bilinear(T, 0.8235), rm.rigid_body(T)):
        hi = T >= 7.0
        assert np.all(m["f_over_mu"][hi] == 1.0)
        assert np.allclose(m["e_t"][hi], 1 - 2 / T[hi])
        assert np.allclose(m["Psi_r"][hi], T[hi] - 7)
        assert np.allclose(m["Omega_r"][hi], -1.0)
    ps = rm.persistent_sliding(T)
    assert np.allclose(ps["Psi_r"], T - 7) and np.allclose(ps["e_t"], 1 - 2 / T)


@pytest.mark.parametrize("kappa", [1.0, 0.8235, 0.6755])
def test_bilinear_model(kappa):
    beta = 1 / (7 * kappa - 1)
    tc = rm.theta_c_theory(kappa)
    m = rm.bilinear(T, kappa)
    lo = T < tc
    assert np.allclose(m["Psi_r"][lo], -beta * T[lo])
    assert np.allclose(m["e_t"][lo], 1 - 2 * (1 + beta) / 7)
    # continuous at Theta_c: -beta Theta_c = Theta_c - 7
    assert -beta * tc == pytest.approx(tc - 7)


def test_rigid_body_model():
    m = rm.rigid_body(T)
    lo = T < 7
    assert np.allclose(m["e_t"][lo], 5 / 7)
    assert np.allclose(m["Psi_r"][lo], 0.0, atol=1e-12)
    assert np.allclose(m["Omega_r"][lo], -T[lo] / 7)


def test_wu_crossing_and_published_levels():
    for row in rm.PUBLISHED_FITS.values():
        tc = rm.wu_crossing(row["c"])
        assert rm.wu_curve(tc, row["c"]) == pytest.approx(1.0, abs=1e-12)
        # f/mu = 1 from the crossing on, continuous there
        assert rm.wu_f_over_mu(tc + 1e-9, row["c"]) == 1.0
        assert rm.wu_f_over_mu(tc - 1e-9, row["c"]) == pytest.approx(1.0, abs=1e-8)
    # Wu, Thornton & Li (2009): the printed EE curve crosses 1 at 5.85; printed Theta_c sit where the curve is ~0.99
    assert rm.wu_crossing(EE["c"]) == pytest.approx(5.85, abs=0.01)
    for row in rm.PUBLISHED_FITS.values():
        level = rm.wu_curve(row["Theta_c_paper"], row["c"])
        assert level == pytest.approx(0.99, abs=0.01)
        assert level < 1.0 and row["Theta_c_paper"] < rm.wu_crossing(row["c"])
    assert rm.wu_crossing((0.0, -0.5, 1.0, -0.5)) == np.inf


def test_max_curve_difference():
    assert rm.max_curve_difference(EE["c"], EE["c"], 6.0) == 0.0
    shifted = (EE["c"][0] + 0.01,) + tuple(EE["c"][1:])
    assert rm.max_curve_difference(EE["c"], shifted, 5.0) == pytest.approx(0.01, abs=1e-12)


def _linear_impact(kappa, Theta, mu=0.3, steps=4000):
    """An independent oblique impact of a solid sphere (m = R = 1, I = 2/5) on a wall with linear springs
    k_n = 1, k_t = kappa and a Coulomb slider (e_n = 1, no spin): whether the contact slides at every step,
    at every step of the compression. Theta = v_ti / (mu V_ni) at e_n = 1."""
    dt = np.pi / steps                          # contact time pi sqrt(m / k_n)
    delta, vn, vt, w, F = 0.0, 1.0, Theta * mu, 0.0, 0.0
    slid, slid_compression = True, True
    while True:
        delta += vn * dt
        if delta <= 0.0:
            return slid, slid_compression
        N = delta
        trial = F - kappa * (vt + w) * dt       # patch slip velocity vt + R w
        sliding = abs(trial) >= mu * N
        F = np.sign(trial) * mu * N if sliding else trial
        slid &= sliding
        if vn > 0.0:
            slid_compression &= sliding
        vn -= N * dt
        vt += F * dt
        w += F / 0.4 * dt


@pytest.mark.parametrize("kappa", [0.2, 0.25, 0.5, 0.8235])
def test_regime_boundaries_against_an_impact(kappa):
    """The three boundaries against an independent linear spring-slider impact with k_t/k_n = kappa,
    just above and below each, on both sides of kappa = 2/7 (below it all three are the initial-sliding
    one: the margin kappa v_t - mu d(delta)/dt rises while the contact slides)."""
    b = rm.regime_boundaries(kappa, 1.0)
    assert b["initial_sliding"] <= b["compression_sliding"] <= b["persistent_sliding"]
    assert b["persistent_sliding"] == rm.theta_c_theory(kappa, 1.0)
    for fac in (1.02, 0.98):
        slid, slid_compression = _linear_impact(kappa, fac * b["persistent_sliding"])
        assert slid == (fac > 1.0), (kappa, fac)
        slid, slid_compression = _linear_impact(kappa, fac * b["compression_sliding"])
        assert slid_compression == (fac > 1.0), (kappa, fac)


def test_regime_boundaries_ordered():
    """Increasing in the order of the regimes for every kappa and e_n; continuous at kappa = 2/7."""
    for kappa in np.linspace(0.05, 1.4, 55):
        for e_n in (0.0, 0.3, 0.7, 1.0):
            b = rm.regime_boundaries(kappa, e_n)
            assert b["initial_sliding"] <= b["compression_sliding"] <= b["persistent_sliding"], (kappa, e_n)
    lo, hi = rm.theta_c_theory(2 / 7 - 1e-12), rm.theta_c_theory(2 / 7 + 1e-12)
    assert lo == pytest.approx(3.5, abs=1e-9) and hi == pytest.approx(3.5, abs=1e-9)
    with pytest.raises(rm.InputError, match="kappa"):
        rm.theta_c_theory(0.0)


@pytest.mark.parametrize("model", ["wu", "bilinear", "rigid_body", "persistent_sliding"])
def test_models_refuse_nan_theta(model):
    args = {"wu": (EE["c"],), "bilinear": (0.8235,), "rigid_body": (), "persistent_sliding": ()}[model]
    with pytest.raises(rm.InputError, match="Theta"):
        getattr(rm, model)(np.array([1.0, np.nan]), *args)
    with pytest.raises(rm.InputError, match="Theta"):
        getattr(rm, model)(np.inf, *args)
