"""The exact twist law of Hertz contacts (laws.twist.deresiewicz) against the closed forms of Johnson
(1985, eq. 7.43), Lubkin (1951) and Deresiewicz (1954), its energy balance and its convergence."""
import math

import numpy as np
import pytest

from dem_contact.laws import closed_forms as cf
from dem_contact.laws.twist import deresiewicz as d
from dem_contact.materials import STEEL, Material, Sphere, Wall

GLASS = Material(E=70e9, nu=0.22, rho=2500.0)
R = 5e-3
MU = 0.3


def hertz(E_star, delta):
    """(N, a) of a Hertz contact of R at the overlap delta."""
    return 4.0 / 3.0 * E_star * math.sqrt(R) * delta**1.5, np.sqrt(R * delta)


def e_star(m1, m2):
    return 1.0 / sum(0.0 if m.is_rigid else (1.0 - m.nu**2) / m.E for m in (m1, m2))


PAIRS = {"steel-steel": (STEEL, Sphere(R, STEEL)), "steel-glass": (STEEL, Sphere(R, GLASS)),
         "glass-rigid wall": (GLASS, Wall.rigid())}


def run(Gc, N, a, beta, n=64):
    N = np.broadcast_to(np.asarray(N, float), beta.shape).copy()
    a = np.broadcast_to(np.asarray(a, float), beta.shape).copy()
    return d.twist_path(Gc, MU, R, N, a, np.asarray(beta, float), n)


def unit(Gc, N, a):
    """beta_1: the twist at which the no-slip moment would equal mu N a."""
    return MU * N * a / (16.0 / 3.0 * Gc * a**3)


@pytest.mark.parametrize("pair", PAIRS)
def test_no_slip_and_full_slip_closed_forms(pair):
    m1, body2 = PAIRS[pair]
    Gc = d.twist_modulus(Sphere(R, m1), body2)
    G1 = m1.E / (2 * (1 + m1.nu))
    G2 = math.inf if body2.material.is_rigid else body2.material.E / (2 * (1 + body2.material.nu))
    assert Gc == pytest.approx(1.0 / (1.0 / G1 + 1.0 / G2), rel=1e-12)
    N, a = hertz(e_star(m1, body2.material), 1e-6)
    b1 = unit(Gc, N, a)
    # the initial slope (the slip annulus of Lubkin's solution takes ~0.75 beta / beta_1 off it)
    beta = np.array([0.0, 1e-5 * b1])
    M, _ = run(Gc, N, a, beta)
    assert M[-1] / cf.twist_no_slip_moment(Gc, a, beta[-1]) == pytest.approx(1.0, abs=1e-3)
    # far beyond beta_1 the centre's stick disc is negligible: full slip
    beta = np.linspace(0.0, 40.0 * b1, 200)
    M, _ = run(Gc, N, a, beta)
    assert M[-1] / cf.twist_full_slip_moment(MU, N, a) == pytest.approx(1.0, abs=1e-3)
    assert -run(Gc, N, a, -beta)[0][-1] == M[-1]        # odd in the twist


def test_lubkin_loading_and_deresiewicz_unloading():
    """Loading: Lubkin's curve; unloading from (beta*, M*): Masing's rule M = M* - 2 M_L((beta* - beta)/2)
    (Deresiewicz 1954); both within 1e-3 mu N a (two materials)."""
    Gc = d.twist_modulus(Sphere(R, STEEL), Sphere(R, GLASS))
    N, a = hertz(e_star(STEEL, GLASS), 2e-6)
    b1 = unit(Gc, N, a)
    up = np.linspace(0.0, 2.0 * b1, 201)
    down = np.linspace(2.0 * b1, -2.0 * b1, 401)[1:]
    M, _ = run(Gc, N, a, np.concatenate([up, down]))
    scale = MU * N * a
    load = np.array([cf.lubkin_moment(x, Gc, MU, N, a) for x in up[::20]])
    assert np.abs(M[:201:20] - load).max() < 1e-3 * scale
    Ms = load[-1]
    unload = np.array([Ms - 2.0 * cf.lubkin_moment((2.0 * b1 - x) / 2.0, Gc, MU, N, a) for x in down[19::40]])
    assert np.abs(M[201:][19::40] - unload).max() < 1e-3 * scale
    # the reversal point of the closed form is met: the far end of the cycle is the loading curve reversed
    assert M[-1] == pytest.approx(-M[200], abs=1e-3 * scale)


def test_convergence_with_cells():
    """Lubkin's curve is met ever more closely as the cells are refined (second order in the cell width)."""
    Gc = d.twist_modulus(Sphere(R, STEEL), Sphere(R, STEEL))
    N, a = hertz(e_star(STEEL, STEEL), 1e-6)
    b1 = unit(Gc, N, a)
    beta = np.linspace(0.0, 3.0 * b1, 301)
    exact = np.array([cf.lubkin_moment(x, Gc, MU, N, a) for x in beta[::15]])
    err = [np.abs(run(Gc, N, a, beta, n)[0][::15] - exact).max() / (MU * N * a) for n in (16, 64, 256)]
    assert err[2] < 2e-4 and err[1] < 1e-3
    assert err[2] < err[0] / 16


def test_closed_loops_dissipate_at_constant_force():
    """Random twist loops at constant N: each closed loop absorbs work (the area of a Masing loop) >= 0,
    and a loop's work equals the exact Masing area within the grid's accuracy."""
    rng = np.random.default_rng(5)
    Gc = d.twist_modulus(Sphere(R, STEEL), Sphere(R, STEEL))
    N, a = hertz(e_star(STEEL, STEEL), 1e-6)
    b1 = unit(Gc, N, a)
    for _ in range(3):
        amp = rng.uniform(0.2, 3.0) * b1
        beta = np.concatenate([np.linspace(0, amp, 50), np.linspace(amp, -amp, 100)[1:],
                               np.linspace(-amp, amp, 100)[1:]])
        M, W = run(Gc, N, a, beta)
        loop = W[-1] - W[49]            # from +amp round to +amp
        assert loop > 0.0
        # the area of a Masing loop between -amp and +amp: 4 (2 int_0^amp M_L - amp M_L(amp))
        xs = np.linspace(0.0, amp, 61)
        ML = np.array([cf.lubkin_moment(x, Gc, MU, N, a) for x in xs])
        area = 4.0 * (2.0 * np.trapezoid(ML, xs) - amp * ML[-1])
        assert loop == pytest.approx(area, rel=5e-3)


def test_varying_normal_force():
    """A normal force raised at a fixed twist leaves the moment (no displacement increment, a larger
    limit); the springs entering start unstrained, so a further twist is stiffer by the new radius; a
    contact grown from first touch and shrunk again (grid merged and split) keeps the closed forms; no
    work is created from rest."""
    Gc = d.twist_modulus(Sphere(R, STEEL), Sphere(R, STEEL))
    Es = e_star(STEEL, STEEL)
    N0, a0 = hertz(Es, 1e-6)
    N1, a1 = hertz(Es, 3e-6)
    b1 = unit(Gc, N0, a0)
    k = 60
    beta = np.concatenate([np.linspace(0.0, 0.5 * b1, k), np.full(k, 0.5 * b1)])
    Nn = np.concatenate([np.full(k, N0), np.linspace(N0, N1, k)])
    an = np.concatenate([np.full(k, a0), np.linspace(a0, a1, k)])
    beta = np.append(beta, beta[-1] + 1e-5 * b1)
    M, W = run(Gc, np.append(Nn, N1), np.append(an, a1), beta)
    assert M[-2] == pytest.approx(M[k - 1], rel=1e-12)
    assert (M[-1] - M[-2]) / cf.twist_no_slip_moment(Gc, a1, 1e-5 * b1) == pytest.approx(1.0, abs=1e-3)
    # from first touch up to 8 a0 at no twist, back to a0, then a small twist: the no-slip stiffness
    deltas = np.concatenate([np.geomspace(1e-12, 64e-6, 300), np.geomspace(64e-6, 1e-6, 300)])
    Ns, as_ = hertz(Es, deltas)
    beta = np.zeros(deltas.size + 1)
    beta[-1] = 1e-5 * b1
    Ns, as_ = np.append(Ns, Ns[-1]), np.append(as_, as_[-1])
    M, _ = run(Gc, Ns, as_, beta, 32)
    assert M[-1] / cf.twist_no_slip_moment(Gc, as_[-1], beta[-1]) == pytest.approx(1.0, abs=1e-3)
    # random histories of twist and overlap from rest: the work absorbed is never negative
    rng = np.random.default_rng(3)
    for _ in range(5):
        dl = 1e-6 * (1.0 + np.cumsum(rng.normal(0.0, 0.05, 400)).clip(-0.9, None))
        Nr, ar = hertz(Es, dl)
        br = b1 * np.cumsum(rng.normal(0.0, 0.1, 400))
        br[0] = 0.0
        _, W = run(Gc, Nr, ar, br)
        assert W.min() > -1e-12 * MU * N0 * a0 * b1


def test_the_springs_energy_never_rises_at_a_fixed_twist():
    """A small twist (0.01 beta_1, every spring stuck) held while the overlap cycles twice between 1 and 0.15
    times its value (the grid split and merged, cells cut by the receding edge): no work is done, so the
    springs' energy 8 G_c sum theta_i^2 w_i may fall (released, slid) but never rise, in any step."""
    Gc = d.twist_modulus(Sphere(R, STEEL), Sphere(R, STEEL))
    Es = e_star(STEEL, STEEL)
    n = d.TWIST_CELLS
    N0, a0 = hertz(Es, 1e-6)
    dl = 1e-6 * (0.575 + 0.425 * np.cos(np.linspace(0.0, 4.0 * np.pi, 81)))
    Nd, ad = hertz(Es, dl)

    def energy(h, a):
        x0 = np.arange(n) * h[d.Q_DS]
        x1 = np.minimum(x0 + h[d.Q_DS], a)
        return 8.0 * Gc * np.sum(h[d.Q_CELLS:] ** 2 * np.where(x1 > x0, x1**3 - x0**3, 0.0) / 3.0)

    H = np.zeros((1, d.Q_CELLS + n))
    d.advance(H, 0, 0, n, Gc, MU, R, N0, a0, 0.0, 0.01 * unit(Gc, N0, a0))
    U = [energy(H[0], a0)]
    for t in range(1, dl.size):
        d.advance(H, 0, 0, n, Gc, MU, R, Nd[t], ad[t], ad[t - 1], 0.0)
        U.append(energy(H[0], ad[t]))
    assert U[-1] > 0.1 * U[0]
    assert np.max(np.diff(U) / U[0]) <= 1e-12


def test_3d_kernel_twist_objective_and_batch():
    """In the 3D step (Scene(twist="deresiewicz")): the torque on body 1 is -M n with M on Lubkin's curve
    for any normal direction; swapping the bodies (n -> -n, w1 - w2 -> its negative) gives body 2 the
    opposite torque; the batch loop equals the single-contact step (to rounding: fused multiply-adds may
    differ between the two compiled loops)."""
    from dem_contact.dem.contact3d import contact_force_torque, contact_forces_serial, history_size, new_histories
    from dem_contact.dem.pairs import pair_table
    from dem_contact.laws.model import Scene
    from dem_contact.laws.slots import P_NSPRING

    sc = Scene(Sphere(R, STEEL), Sphere(R, GLASS), mu=MU, twist="deresiewicz")
    Gc = d.twist_modulus(sc.sphere, sc.body2)
    Rs = sc.pair.R_star
    delta = 1e-6
    N, a = 4 / 3 * sc.pair.E_star * math.sqrt(Rs) * delta**1.5, math.sqrt(Rs * delta)
    b1 = unit(Gc, N, a)
    P = sc.params[None, :]
    size = history_size(sc.normal_id, sc.tangential_id, int(sc.params[P_NSPRING]), sc.twist_id, sc.rolling_id)
    n = np.array([0.36, -0.48, 0.8])
    dt, steps = 1e-7, 60
    w = 2.0 * b1 / (steps * dt)
    H1, H2 = new_histories(1, size), new_histories(1, size)
    for k in range(steps + 1):
        wk = w * n if k else 0.0 * n
        q1 = contact_force_torque(sc.normal_id, sc.tangential_id, P, 0, H1, 0, *n, delta, 0.0, 0.0, 0.0, *wk, 0.0, dt)
        q2 = contact_force_torque(sc.normal_id, sc.tangential_id, P, 0, H2, 0, *(-n), delta, 0.0, 0.0, 0.0, *(-wk),
                                  0.0, dt)
        # the same twist (-w) . (-n): the torque -M (-n) on body 2, the reaction to -M n on body 1
        assert np.allclose(q2[6:], -np.array(q1[6:]), rtol=1e-12, atol=0.0)
    M = -float(np.dot(q1[6:], n))
    assert np.allclose(np.cross(q1[6:], n), 0.0, atol=1e-12 * abs(M))
    assert M == pytest.approx(cf.lubkin_moment(2.0 * b1, Gc, MU, N, a), abs=5e-3 * MU * N * a)
    # batch = single step
    tab = pair_table([Sphere(R, STEEL), Sphere(2 * R, GLASS)], [Wall(STEEL)], mu=MU, twist="deresiewicz")
    rng = np.random.default_rng(2)
    m = 6
    nrm = rng.normal(size=(m, 3))
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    pair = rng.integers(0, tab.params.shape[0], size=m)
    Hb, Hs = new_histories(m, tab.history_size), new_histories(m, tab.history_size)
    for k in range(20):
        vel = rng.normal(scale=0.01, size=(m, 3))
        spins = rng.normal(scale=50.0, size=(m, 3))
        dl = rng.uniform(5e-7, 2e-6, size=m)
        f, t, q = np.zeros((m, 3)), np.zeros((m, 3)), np.zeros((m, 3))
        contact_forces_serial(tab.normal_id, tab.tangential_id, tab.params, pair, Hb, nrm, dl, vel, np.zeros(m), dt,
                              f, t, spins=spins, torques=q)
        for c in range(m):
            out = contact_force_torque(tab.normal_id, tab.tangential_id, tab.params, pair[c], Hs, c, *nrm[c], dl[c],
                                       *vel[c], *spins[c], 0.0, dt)
            assert np.allclose(q[c], out[6:], rtol=1e-13, atol=0.0) and tuple(f[c]) == out[:3]
    assert np.allclose(Hb, Hs, rtol=1e-13, atol=0.0) and np.abs(q).max() > 0.0


def test_impact3d_resists_spin_about_the_normal():
    """Horak's case (a sphere spinning about the normal dropped on a plane): with no twist law the spin
    passes unchanged; with deresiewicz a fast spin slides throughout and loses the angular impulse of
    Lubkin's full-slip moment, (3 pi/16) mu int N a dt / I, and a slow spin (the contact sticking) loses a
    fraction independent of the spin; the energy budget closes."""
    from dem_contact.impacts.impact3d import impact3d
    from dem_contact.laws.model import Scene

    sc = Scene(Sphere(R, STEEL), Wall(STEEL), mu=MU, twist="deresiewicz")
    vn = 2.0
    s = impact3d(sc, vn, series=True).series
    a = np.sqrt(sc.pair.R_star * np.clip(s["overlap"], 0.0, None))
    I = 0.4 * sc.sphere.mass * R * R
    dw_slip = 3 * math.pi / 16 * MU * np.trapezoid(np.clip(s["normal_force"], 0, None) * a, s["t"]) / I
    w_fast = 3000.0 * dw_slip
    r = impact3d(sc, vn, spin=(0.0, 0.0, w_fast))
    assert w_fast - r.spin_r[2] == pytest.approx(dw_slip, rel=5e-3)
    assert impact3d(sc.replace(twist="none"), vn, spin=(0.0, 0.0, w_fast)).spin_r[2] == w_fast
    lost = [1.0 - impact3d(sc, vn, spin=(0.0, 0.0, w)).spin_r[2] / w for w in (1e-3 * dw_slip, 2e-3 * dw_slip)]
    assert lost[0] > 0.0 and lost[1] == pytest.approx(lost[0], rel=1e-3)
    assert abs(r.energy.error) < 1e-7 * r.energy.initial and not r.energy_created
