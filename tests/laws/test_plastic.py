"""Plastic contacts: the MDR Coulomb limit of Thornton's truncated pressure, first yield under sliding
traction (Hamilton 1983) and the traction-coupled Thornton law, the thornton2001 model."""
import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

import dem_contact as dc
from dem_contact.cli import main
from dem_contact.errors import InputError
from dem_contact.impacts.presets import preset_scene
from dem_contact.impacts.sweep import scene_with
from dem_contact.laws import closed_forms as cf
from dem_contact.laws import traction_yield as ty
from dem_contact.laws.contact import contact_step
from dem_contact.laws.normal.thornton import thornton
from dem_contact.laws.slots import (H_DP, H_N, H_RP, H_T, H_TANG_EXTRA, P_DELTA_Y, P_DX, P_ESTAR,
                                    P_GSTAR, P_MU, P_PY, P_RSTAR, P_TY_DMU, P_TY_NODES, P_TY_TABLE)

NU = 0.3


def angle_vt(vn, deg):
    return vn * math.tan(math.radians(deg))


# --- the truncated Hertz pressure and its MDR line load ---------------------------------------------

def test_truncated_line_load_is_the_abel_transform_and_carries_thorntons_force():
    """q(x) = 2 int_x^a r p(r)/sqrt(r^2 - x^2) dr of p = min(p_H, p_y), and 2 int q dx = Thornton's F."""
    E, R, py = 1e10, 1e-3, 1e8
    dy = cf.thornton_yield_overlap(E, R, py)
    Fy = cf.thornton_yield_force(E, R, py)
    for ratio in (1.3, 4.0, 50.0):
        delta = ratio * dy
        a = math.sqrt(R * delta)
        p0 = 2 * E * a / (math.pi * R)

        def p(r):
            return min(p0 * math.sqrt(max(1 - r * r / (a * a), 0.0)), py)

        for x in (0.0, 0.2 * a, 0.6 * a, 0.97 * a):
            # r = sqrt(x^2 + t^2) turns the Abel integral into 2 int_0^sqrt(a^2 - x^2) p dt
            abel = 2 * quad(lambda t: p(math.hypot(x, t)), 0, math.sqrt(a * a - x * x), epsabs=0, epsrel=1e-12,
                            limit=200)[0]
            assert cf.truncated_line_load(x, a, R, E, py) == pytest.approx(abel, rel=1e-9)
        force = 2 * quad(lambda x: float(cf.truncated_line_load(x, a, R, E, py)), 0, a, epsabs=0, epsrel=1e-13,
                         limit=200)[0]
        thornton_F = Fy + math.pi * py * R * (delta - dy)
        assert force == pytest.approx(thornton_F, rel=1e-10)


def pe_scene(tangential="mdr", vn=5.0, **kw):
    return preset_scene("PE", vn, tangential=tangential, **kw)


@pytest.mark.parametrize("tangential", ["mdr", "mdr_adaptive"])
def test_full_slip_carries_mu_n_through_plastic_loading_and_unloading(tangential):
    """Every cell at its Coulomb limit: T = mu N to 1e-10 (the force identity of the line load), and
    each cell's limit is mu times the mean of the truncated line load over the cell."""
    s = pe_scene(tangential)
    p, h = s.params, s.new_history()
    dy = p[P_DELTA_Y]
    path = list(np.linspace(0.05, 6.0, 25) * dy) + list(np.linspace(5.9, 2.0, 10) * dy)
    GM = 4 * p[P_GSTAR]
    checked = False
    for k, delta in enumerate(path):
        N, a, T = contact_step(s.normal_id, s.tangential_id, p, h, delta, 0.0, 1.0 if k % 2 else -1.0)
        assert abs(T) == pytest.approx(p[P_MU] * N, rel=1e-10)
        if tangential == "mdr" and delta > 3 * dy and k < 25:      # plastic loading: cell by cell
            dx = p[P_DX]
            u = np.abs(h[H_TANG_EXTRA:H_TANG_EXTRA + int(a / dx)])
            for i in (0, len(u) // 2, len(u) - 1):
                mean_q = quad(lambda x: float(cf.truncated_line_load(x, a, p[P_RSTAR], p[P_ESTAR], p[P_PY])),
                              i * dx, (i + 1) * dx, epsabs=0, epsrel=1e-12)[0] / dx
                assert GM * u[i] == pytest.approx(p[P_MU] * mean_q, rel=1e-9)
            checked = True
    assert tangential != "mdr" or checked


def test_profiles_agree_for_elastic_contacts_and_differ_for_plastic_ones():
    """Hertz contacts and the elastic (unloading) part are untouched by the profile choice; plastic
    loading changes f/mu (the truncated pressure moves Coulomb limit from the centre to the edge)."""
    mat = dc.Material(208e9, NU, 7850)
    base = dc.Scene(dc.Sphere(0.01, mat), dc.Wall(mat), mu=0.3)
    scaled = scene_with(base, mdr_profile="scaled")
    r0, r1 = dc.impact(base, 5.0, 3.0), dc.impact(scaled, 5.0, 3.0)
    assert r0.f_over_mu == r1.f_over_mu and r0.e_t == r1.e_t
    pe = pe_scene("mdr_adaptive")
    a = dc.impact(pe, 5.0, angle_vt(5.0, 20))
    b = dc.impact(scene_with(pe, mdr_profile="scaled"), 5.0, angle_vt(5.0, 20))
    assert a.e_n == b.e_n                     # the normal law does not see the profile
    assert abs(a.f_over_mu - b.f_over_mu) > 1e-3


# --- first yield under sliding traction ---------------------------------------------------------------

FIELD_POINTS = [(0.3, 0.4, 0.5), (-0.7, 0.2, 0.3), (1.2, -0.5, 0.4), (0.5, 0.5, 1.0)]


def _tensor(f, x, y, z):
    sxx, syy, szz, sxy, sxz, syz = f(np.array(x), np.array(y), np.array(z), NU)
    return np.array([[sxx, sxy, sxz], [sxy, syy, syz], [sxz, syz, szz]])


@pytest.mark.parametrize("field", [ty.normal_stress, ty.tangential_stress])
def test_hamilton_fields_are_elastic_equilibrium_fields(field):
    """div sigma = 0 and Beltrami-Michell compatibility (no body force) by finite differences."""
    for P in FIELD_POINTS:
        P = np.array(P)
        h = 1e-4
        div = sum((_tensor(field, *(P + h * e))[:, j] - _tensor(field, *(P - h * e))[:, j]) / (2 * h)
                  for j, e in enumerate(np.eye(3)))
        assert np.abs(div).max() < 1e-6
        h = 1e-3
        tr = lambda q: np.trace(_tensor(field, *q))     # noqa: E731
        lap = sum((_tensor(field, *(P + h * e)) - 2 * _tensor(field, *P) + _tensor(field, *(P - h * e))) / h**2
                  for e in np.eye(3))
        hess = np.array([[(tr(P + h * ei + h * ej) - tr(P + h * ei - h * ej) - tr(P - h * ei + h * ej)
                           + tr(P - h * ei - h * ej)) / (4 * h * h) for ej in np.eye(3)] for ei in np.eye(3)])
        assert np.abs(lap + hess / (1 + NU)).max() < 1e-4


def test_hamilton_surface_tractions_and_trailing_edge():
    """At z = 0: sigma_zz = -p, sigma_xz = -q (traction +x on the body), zero outside the contact; the
    tensile stress at the trailing edge is p0 ((1 - 2 nu)/3 + (4 + nu) pi mu / 8) (Hamilton & Goodman)."""
    z = 1e-11
    for x, y in ((0.3, 0.2), (-0.5, 0.4), (1.3, 0.2)):
        p = math.sqrt(max(1 - x * x - y * y, 0.0))
        n = _tensor(ty.normal_stress, x, y, z)
        t = _tensor(ty.tangential_stress, x, y, z)
        assert n[2, 2] == pytest.approx(-p, abs=1e-8) and abs(n[0, 2]) < 1e-8 and abs(n[1, 2]) < 1e-8
        assert t[0, 2] == pytest.approx(-p, abs=1e-8) and abs(t[2, 2]) < 1e-8 and abs(t[1, 2]) < 1e-8
    edge_n = _tensor(ty.normal_stress, -1 - 1e-9, 1e-9, z)[0, 0]
    edge_t = _tensor(ty.tangential_stress, -1 - 1e-9, 1e-9, z)[0, 0]
    assert edge_n == pytest.approx((1 - 2 * NU) / 3, rel=1e-4)      # sqrt(z) approach to the edge value
    assert edge_t == pytest.approx((4 + NU) * math.pi / 8, rel=1e-4)


def test_first_yield_without_and_with_traction():
    """mu = 0: p0 = 1.60 Y (Johnson 1985, 4.2) at z = 0.48 a on the axis; traction lowers it; above
    mu of about 0.3 first yield is at the surface (Johnson 1985, 7.2)."""
    v0, x0, _, z0 = ty.max_von_mises(NU, 0.0)
    assert 1 / v0 == pytest.approx(1.60, rel=0.01)
    assert z0 == pytest.approx(0.48, abs=0.01) and abs(x0) < 0.03
    v2, _, _, z2 = ty.max_von_mises(NU, 0.2)
    v4, x4, _, z4 = ty.max_von_mises(NU, 0.4)
    assert v0 < v2 < v4
    assert z2 > 0.3                                # still below the surface
    assert z4 < 1e-6 and abs(abs(x4) - 1) < 1e-3   # at the surface, on the edge of the contact


# --- the traction-coupled Thornton law ----------------------------------------------------------------

def test_traction_yield_limits():
    """Head-on impacts carry no traction: e_n unchanged; mu = 0: the uncoupled law exactly; the table
    falls with mu_eff from 1; oblique impacts lose more energy, never create it."""
    for vn in (2.0, 5.0):
        plain = pe_scene("mdr_adaptive", vn)
        coupled = scene_with(plain, traction_yield=True)
        assert dc.impact(coupled, vn, 0.0).e_n == pytest.approx(dc.impact(plain, vn, 0.0).e_n, rel=1e-12)
        table = coupled.params[P_TY_TABLE:P_TY_TABLE + ty.TABLE_NODES]
        assert table[0] == 1.0 and np.all(np.diff(table) < 0)
        for deg in (20, 45, 80):
            rc, rp = dc.impact(coupled, vn, angle_vt(vn, deg)), dc.impact(plain, vn, angle_vt(vn, deg))
            assert rc.e_n < rp.e_n
            assert rc.energy.final < rc.energy.initial
            assert abs(rc.energy.error) < 1e-6 * rc.energy.initial
        free = scene_with(plain, mu=0.0, traction_yield=True)
        r0, r1 = dc.impact(free, vn, 3.0), dc.impact(scene_with(plain, mu=0.0), vn, 3.0)
        assert (r0.e_n, r0.e_t, r0.max_force) == (r1.e_n, r1.e_t, r1.max_force)


def test_traction_yield_in_persistent_sliding_is_thornton_at_the_lowered_pressure():
    """A contact that slides from the start carries mu_eff = mu (after its first step): e_n is Thornton's
    closed form at p_y g(mu)."""
    for vn in (2.0, 5.0):
        s = scene_with(pe_scene("mdr_adaptive", vn), traction_yield=True)
        g_mu = s.params[P_TY_TABLE + ty.TABLE_NODES - 1]
        pr = s.pair
        expected = cf.thornton_restitution(pr.E_star, pr.R_star, pr.m_star, s.p_y * g_mu, vn)
        r = dc.impact(s, vn, angle_vt(vn, 80), steps_per_contact=400)
        assert r.persistent_sliding
        assert r.e_n == pytest.approx(expected, rel=1e-5)     # the first step carries no traction yet


@settings(max_examples=30, deadline=None)
@given(st.lists(st.floats(0.0, 0.3), min_size=3, max_size=40), st.floats(1.5, 30.0))
def test_traction_yield_cycle_creates_no_energy(mu_effs, peak):
    """Loading to peak delta_y with any history of mu_eff, then unloading to separation: the work
    returned is at most the work done (trapezoid rule on fine steps)."""
    s = pe_scene("md", traction_yield=True)
    p, h = s.params, s.new_history()
    dy = p[P_DELTA_Y]
    up = np.linspace(0.0, peak * dy, 400)[1:]
    W_in, F_old, d_old = 0.0, 0.0, 0.0
    for k, d in enumerate(up):
        m = mu_effs[k * len(mu_effs) // len(up)]
        h[H_N], h[H_T] = 1.0, m                     # the law reads mu_eff = |T| / N of the last step
        F, _ = thornton(p, h, d)
        W_in += 0.5 * (F + F_old) * (d - d_old)
        F_old, d_old = F, d
    assert F_old <= 4 / 3 * p[P_ESTAR] * math.sqrt(p[P_RSTAR]) * d_old**1.5 * (1 + 1e-12)
    W_out = 0.0
    for d in np.linspace(d_old, h[H_DP], 2000)[1:]:
        F, _ = thornton(p, h, d)
        W_out += 0.5 * (F + F_old) * (d_old - d)
        F_old, d_old = F, d
    assert W_out <= W_in * (1 + 1e-6)


def test_traction_yield_follows_thornton_without_traction():
    """mu_eff = 0 throughout: the coupled loading branch is Thornton's law (to rounding)."""
    s = pe_scene("md", traction_yield=True)
    p, h, h0 = s.params, s.new_history(), s.new_history()
    p0 = p.copy()
    p0[P_TY_NODES] = 0.0      # no table: the plain law
    for d in np.linspace(0.01, 20.0, 300) * p[P_DELTA_Y]:
        assert thornton(p, h, d)[0] == pytest.approx(thornton(p0, h0, d)[0], rel=1e-12)
    assert h[H_RP] == pytest.approx(h0[H_RP], rel=1e-12) and h[H_DP] == pytest.approx(h0[H_DP], rel=1e-10)


# --- the partly slipping traction (traction_yield="partial_slip") -------------------------------------

def test_partial_slip_field_carries_the_cattaneo_traction():
    """At z = 0 the field of ``partial_slip_stress`` has sigma_xz = -(sqrt(1 - r^2) - c sqrt(1 - r^2/c^2))
    (the second term inside the stick radius c only), and with c = stick_ratio(s) that traction carries
    s times what the pressure carries (T = s mu N, Cattaneo-Mindlin)."""
    z = 1e-11
    for s in (0.2, 0.7):
        c = float(ty.stick_ratio(s))
        for r in (0.1, 0.5 * c, 0.98 * c, 0.5 * (1 + c), 1.2):
            q = math.sqrt(max(1 - r * r, 0.0)) - (c * math.sqrt(1 - (r / c) ** 2) if r < c else 0.0)
            sxz = ty.partial_slip_stress(np.array(r * 0.6), np.array(r * 0.8), np.array(z), NU, c)[4]
            assert -sxz == pytest.approx(q, abs=1e-7)

        def shear(r):
            return -float(ty.partial_slip_stress(np.array(r), np.array(1e-9), np.array(z), NU, c)[4]) * r

        carried = quad(shear, 0.0, c, limit=200)[0] + quad(shear, c, 1.0, limit=200)[0]
        assert carried / (1.0 / 3.0) == pytest.approx(s, rel=1e-5)     # int_0^1 sqrt(1 - r^2) r dr = 1/3
    assert ty.stick_ratio(0.0) == 1.0 and ty.stick_ratio(1.0) == 0.0


@pytest.fixture(scope="module")
def partial_slip_scenes():
    """PE at 2 and 5 m/s with traction_yield="partial_slip" (one table: it depends on nu and mu only)."""
    return {vn: pe_scene("mdr_adaptive", vn, traction_yield="partial_slip") for vn in (2.0, 5.0)}


def test_partial_slip_table_and_head_on_impacts(partial_slip_scenes):
    """The table runs from 1 (no traction: the stick zone is the whole contact) down to the first-yield
    ratio of a sliding contact (c = 0: the same traction as "proportional" at mu_eff = mu); a head-on
    impact carries no traction and keeps Thornton's e_n (to rounding: the coupled loading branch builds
    Thornton's force from its increments); the CLI takes the option."""
    for vn, coupled in partial_slip_scenes.items():
        table = coupled.params[P_TY_TABLE:P_TY_TABLE + ty.TABLE_NODES]
        assert table[0] == 1.0 and np.all(np.diff(table) < 0)
        assert table[-1] == ty.max_von_mises(NU, 0.0)[0] / ty.max_von_mises(NU, coupled.mu)[0]
        plain = scene_with(coupled, traction_yield=False)
        assert dc.impact(coupled, vn, 0.0).e_n == pytest.approx(dc.impact(plain, vn, 0.0).e_n, rel=1e-14)
    assert main(["impact", "--case", "PE", "--vn", "2", "--angle", "30", "--traction-yield", "partial_slip",
                 "--json"]) == 0


def test_partial_slip_leaves_elastic_impacts_unchanged(partial_slip_scenes):
    """Below the yield velocity at the lowest limiting pressure the law never leaves Hertz: every output
    of an oblique impact is the uncoupled law's, bit for bit."""
    coupled = partial_slip_scenes[5.0]
    plain = scene_with(coupled, traction_yield=False)
    pr = coupled.pair
    g_min = coupled.params[P_TY_TABLE + ty.TABLE_NODES - 1]
    vn = 0.9 * cf.thornton_yield_velocity(pr.E_star, pr.R_star, pr.m_star, coupled.p_y * g_min)
    for deg in (0, 20, 50, 80):
        a, b = dc.impact(coupled, vn, angle_vt(vn, deg)), dc.impact(plain, vn, angle_vt(vn, deg))
        assert (a.e_n, a.e_t, a.f_over_mu, a.max_force, a.Omega_r) == (b.e_n, b.e_t, b.f_over_mu, b.max_force,
                                                                       b.Omega_r)


def test_partial_slip_acts_in_3d_as_in_the_plane(partial_slip_scenes):
    """The 3D kernels read the same table (|T|/N of the last step in the fifth state slot): impact3d gives
    the e_n of the planar impact, below the uncoupled law's."""
    from dem_contact.impacts.impact3d import impact3d

    coupled = partial_slip_scenes[5.0]
    vt = angle_vt(5.0, 30)
    q = impact3d(coupled, 5.0, (vt, 0.0))
    assert q.e_n == pytest.approx(dc.impact(coupled, 5.0, vt).e_n, rel=1e-6, abs=0.0)
    assert q.e_n < impact3d(scene_with(coupled, traction_yield=False), 5.0, (vt, 0.0)).e_n - 0.005


@settings(max_examples=20, deadline=None)
@given(st.lists(st.floats(0.5, 1.0), min_size=ty.TABLE_NODES, max_size=ty.TABLE_NODES),
       st.lists(st.floats(0.0, 0.3), min_size=3, max_size=30), st.floats(1.5, 30.0))
def test_any_yield_table_cycle_creates_no_energy(table, mu_effs, peak):
    """The coupled loading never creates energy, whatever the table (so whatever the traction
    distribution it was computed for) and the history of mu_eff: loading to peak delta_y, unloading to
    separation, the work returned is at most the work done."""
    s = pe_scene("md")
    p, h = s.params, s.new_history()
    p[P_TY_NODES] = ty.TABLE_NODES
    p[P_TY_DMU] = s.mu / (ty.TABLE_NODES - 1)
    p[P_TY_TABLE:P_TY_TABLE + ty.TABLE_NODES] = [1.0] + sorted(table, reverse=True)[1:]
    dy = p[P_DELTA_Y]
    W_in, F_old, d_old = 0.0, 0.0, 0.0
    up = np.linspace(0.0, peak * dy, 300)[1:]
    for k, d in enumerate(up):
        h[H_N], h[H_T] = 1.0, mu_effs[k * len(mu_effs) // len(up)]
        F, _ = thornton(p, h, d)
        W_in += 0.5 * (F + F_old) * (d - d_old)
        F_old, d_old = F, d
    W_out = 0.0
    for d in np.linspace(d_old, h[H_DP], 1500)[1:]:
        F, _ = thornton(p, h, d)
        W_out += 0.5 * (F + F_old) * (d_old - d)
        F_old, d_old = F, d
    assert W_out <= W_in * (1 + 1e-6)


# --- options and the thornton2001 model ---------------------------------------------------------------

def test_options_are_checked():
    mat = dc.Material(208e9, NU, 7850)
    sph, wall = dc.Sphere(0.01, mat), dc.Wall(mat)
    with pytest.raises(InputError, match="traction_yield"):
        dc.Scene(sph, wall, traction_yield=True)
    with pytest.raises(InputError, match="traction_yield = 'cattaneo' is unknown"):
        dc.Scene(sph, wall, normal="thornton", e_n=0.8, v_ref=1.0, traction_yield="cattaneo")
    with pytest.raises(InputError, match="mdr_profile"):
        dc.Scene(sph, wall, mdr_profile="flat")
    with pytest.raises(InputError, match="mdr_profile"):
        dc.Scene(sph, wall, tangential="md", mdr_profile="scaled")
    with pytest.raises(InputError, match="model"):
        dc.Scene(sph, wall, model="walton")
    with pytest.raises(InputError, match="model"):
        dc.Scene(sph, wall, model="thornton2001", tangential="mindlin_total")


def test_thornton2001_model():
    """thornton + md (hertz when nothing yields), 1000 steps per contact unless told otherwise."""
    pe = preset_scene("PE", 5.0, model="thornton2001")
    ee = preset_scene("EE", 5.0, model="thornton2001")
    assert (pe.normal, pe.tangential, ee.normal, ee.tangential) == ("thornton", "md", "hertz", "md")
    r = dc.impact(pe, 5.0, 2.0)
    assert r.dt == pytest.approx(pe.contact_time(5.0) / 1000, rel=1e-12)
    plain = preset_scene("PE", 5.0, tangential="md")
    assert r.e_n == pytest.approx(dc.impact(plain, 5.0, 2.0, steps_per_contact=1000).e_n, rel=1e-12)
    assert scene_with(pe, mu=0.2).model == "thornton2001"


def test_cli_options(capsys):
    assert main(["impact", "--case", "PE", "--vn", "5", "--angle", "60", "--traction-yield", "--json"]) == 0
    coupled = json.loads(capsys.readouterr().out)
    assert main(["impact", "--case", "PE", "--vn", "5", "--angle", "60", "--json"]) == 0
    plain = json.loads(capsys.readouterr().out)
    assert coupled["e_n"] < plain["e_n"]
    assert main(["impact", "--model", "thornton2001", "--case", "PE", "--json"]) == 0
    assert main(["impact", "--traction-yield"]) == 2
