"""Normal laws against closed forms (Johnson 1985, section 11.4; Thornton 1997; Tsuji, Tanaka & Ishida 1992)."""
import math

import numpy as np
import pytest

import dem_contact as dc
from dem_contact.laws import closed_forms as cf
from dem_contact.laws.normal import thornton as normal_thornton
from dem_contact.laws.slots import H_DP, H_RP, N_HIST_BASE, P_KN


def test_steel_pair_properties(steel_sphere, steel_wall):
    pr = dc.pair_properties(steel_sphere, steel_wall)
    assert pr.E_star == pytest.approx(114.29e9, rel=1e-4)
    assert pr.G_star == pytest.approx(23.53e9, rel=1e-3)
    assert pr.kappa == pytest.approx(2 * (1 - 0.3) / (2 - 0.3), rel=1e-12)
    assert steel_sphere.mass == pytest.approx(0.032882, rel=1e-4)


@pytest.mark.parametrize("nu", [0.0, 0.23, 0.3, 0.49])
def test_kappa_rigid_on_elastic(nu):
    """kappa = 2(1 - nu)/(2 - nu) for a rigid body on an elastic one (Johnson 1985, section 4.2; Wu, Thornton & Li 2009, section 2)."""
    pr = dc.pair_properties(dc.Sphere(0.01, dc.Material.rigid()), dc.Wall(dc.Material(208e9, nu, 7850)))
    assert pr.kappa == pytest.approx(2 * (1 - nu) / (2 - nu), rel=1e-12)


@pytest.mark.parametrize("vn", [2.0, 5.0])
def test_hertz_elastic_impact(steel_sphere, steel_wall, vn):
    """e_n = 1 within 1e-4; contact time, max overlap and max force within 0.5% of Hertz (default steps)."""
    sc = dc.Scene(steel_sphere, steel_wall, mu=0.3)
    r = dc.impact(sc, vn, 0.3 * vn)
    pr = sc.pair
    assert abs(r.e_n - 1.0) < 1e-4
    assert r.contact_time == pytest.approx(cf.hertz_contact_time(pr.E_star, pr.R_star, pr.m_star, vn), rel=5e-3)
    assert r.max_overlap == pytest.approx(cf.hertz_max_overlap(pr.E_star, pr.R_star, pr.m_star, vn), rel=5e-3)
    assert r.max_force == pytest.approx(cf.hertz_max_force(pr.E_star, pr.R_star, pr.m_star, vn), rel=5e-3)


def test_hertz_published_steel_numbers(steel_sphere, steel_wall):
    """Johnson 1985, section 11.4: t_c = 50.28 us, delta_max = 85.42 um, F_max = 12.03 kN at 5 m/s; 60.40 us at 2 m/s."""
    pr = dc.pair_properties(steel_sphere, steel_wall)
    args = (pr.E_star, pr.R_star, pr.m_star)
    assert cf.hertz_contact_time(*args, 5.0) == pytest.approx(50.28e-6, rel=2e-4)
    assert cf.hertz_max_overlap(*args, 5.0) == pytest.approx(85.42e-6, rel=2e-4)
    assert cf.hertz_max_force(*args, 5.0) == pytest.approx(12.03e3, rel=5e-4)
    assert cf.hertz_contact_time(*args, 2.0) == pytest.approx(60.40e-6, rel=2e-4)


# Thornton (1997) closed forms, test vector: sphere on rigid wall, R = 1 mm, rho = 2500, E* = 1e10, p_y = 1e8
UNIT = dict(R=1e-3, rho=2500.0, E_star=1e10, p_y=1e8)


def unit_scene():
    mat = dc.Material(E=UNIT["E_star"], nu=0.0, rho=UNIT["rho"], yield_pressure=UNIT["p_y"])
    return dc.Scene(dc.Sphere(UNIT["R"], mat), dc.Wall.rigid(), mu=0.3, normal="thornton")


def test_thornton_unit_vector_closed_forms():
    sc = unit_scene()
    E, R, m, py = sc.pair.E_star, sc.pair.R_star, sc.pair.m_star, UNIT["p_y"]
    assert E == pytest.approx(1e10, rel=1e-15)
    assert cf.thornton_yield_overlap(E, R, py) == pytest.approx(2.467401e-7, rel=1e-6)
    assert cf.thornton_yield_force(E, R, py) == pytest.approx(5.167713e-2, rel=1e-6)
    vy = cf.thornton_yield_velocity(E, R, m, py)
    assert vy == pytest.approx(3.121043e-2, rel=1e-6)
    d_star = cf.thornton_max_overlap(E, R, m, py, 5 * vy)
    assert d_star == pytest.approx(9.802060e-7, rel=1e-6)
    F, Rp, dp = cf.thornton_unloading(E, R, py, d_star)
    assert F == pytest.approx(0.2821022, rel=1e-6)
    assert Rp / R == pytest.approx(1.450468, rel=1e-6)
    assert dp == pytest.approx(3.044201e-7, rel=1e-6)
    assert cf.thornton_restitution_ratio(0.2) == pytest.approx(0.773337, rel=1e-6)


def test_thornton_kernel_unit_vector():
    """The kernel, loaded to delta*, stores the unloading curve of the unit-test vector (1e-6)."""
    sc = unit_scene()
    h = np.zeros(N_HIST_BASE)
    d_star = 9.802060e-7
    for d in np.linspace(1e-9, d_star, 50):
        F, a = normal_thornton.thornton(sc.params, h, d)
    assert F == pytest.approx(0.2821022, rel=1e-6)
    assert h[H_RP] / UNIT["R"] == pytest.approx(1.450468, rel=1e-6)
    assert h[H_DP] == pytest.approx(3.044201e-7, rel=1e-6)
    # unloading is continuous in force and contact radius at delta*
    F2, a2 = normal_thornton.thornton(sc.params, h, d_star * (1 - 1e-12))
    assert F2 == pytest.approx(F, rel=1e-9)
    assert a2 == pytest.approx(math.sqrt(UNIT["R"] * d_star), rel=1e-9)
    # simulated impact at 5 V_y: maximum overlap and e_n
    vy = cf.thornton_yield_velocity(sc.pair.E_star, sc.pair.R_star, sc.pair.m_star, UNIT["p_y"])
    r = dc.impact(sc, 5 * vy, steps_per_contact=1000)
    assert r.max_overlap == pytest.approx(9.802060e-7, rel=1e-5)


@pytest.mark.parametrize("ratio", [1.5, 2, 5, 10, 30, 100])
def test_thornton_restitution_simulated(ratio):
    """Simulated e_n against Thornton's closed form within 0.2% (Thornton 1997)."""
    table = {1.5: 0.97124, 2: 0.93063, 5: 0.77334, 10: 0.65856, 30: 0.50439, 100: 0.37430}
    sc = unit_scene()
    vy = cf.thornton_yield_velocity(sc.pair.E_star, sc.pair.R_star, sc.pair.m_star, UNIT["p_y"])
    assert cf.thornton_restitution_ratio(1 / ratio) == pytest.approx(table[ratio], abs=1e-5)
    r = dc.impact(sc, ratio * vy)
    assert r.e_n == pytest.approx(table[ratio], rel=2e-3)


def test_thornton_calibration_from_restitution(steel_sphere, steel_wall):
    """p_y calibrated for e_n at v gives that e_n in simulation."""
    sc = dc.Scene(steel_sphere, steel_wall, normal="thornton", e_n=0.8, v_ref=3.0)
    assert dc.impact(sc, 3.0).e_n == pytest.approx(0.8, rel=2e-3)


def test_pe_case_restitution():
    """Wu, Thornton & Li 2009, section 4: with p_y = 1.6 Y (Y = 1.85 GPa), e_n = 0.856 at 2 m/s and 0.699 at 5 m/s."""
    sphere = dc.Sphere(0.01, dc.Material(208e9, 0.3, 7850, yield_stress=1.85e9))
    sc = dc.Scene(sphere, dc.Wall(dc.STEEL), normal="thornton")
    assert dc.impact(sc, 2.0).e_n == pytest.approx(0.856, abs=1e-3)
    assert dc.impact(sc, 5.0).e_n == pytest.approx(0.699, abs=1e-3)


@pytest.mark.parametrize("e_n", [0.3, 0.7, 0.95])
def test_damped_and_linear_restitution(steel_sphere, steel_wall, e_n):
    """hertz_damped (numerically calibrated) and linear (closed form) reach the target e_n."""
    sd = dc.Scene(steel_sphere, steel_wall, normal="hertz_damped", e_n=e_n)
    for v in (1.0, 5.0):   # damped Hertz: e_n independent of speed
        assert dc.impact(sd, v, steps_per_contact=1000).e_n == pytest.approx(e_n, abs=2e-4)
    sl = dc.Scene(steel_sphere, steel_wall, normal="linear", e_n=e_n, v_ref=5.0)
    r = dc.impact(sl, 5.0, steps_per_contact=1000)
    assert r.e_n == pytest.approx(e_n, abs=1e-5)
    assert r.contact_time == pytest.approx(cf.linear_contact_time(sl.params[P_KN], sl.pair.m_star,
                                                                  cf.linear_damping_ratio(e_n)), rel=1e-5)
