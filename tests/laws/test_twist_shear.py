"""Twist with shear from one local state (laws.twist_shear): its two exact limits (the vector MDR law and the
deresiewicz twist law), the closed forms of Mindlin (1949), Johnson (1985, eq. 7.43) and Lubkin (1951),
closed loops at constant N, and the boundary-element reference with twist, also under a varying normal force."""
import math
import pathlib

import numpy as np
import pytest

from dem_contact.errors import InputError
from dem_contact.laws.twist import deresiewicz as d
from dem_contact.laws.twist_shear import twist_shear_path
from dem_contact.materials import STEEL
from dem_contact.reference.paths import named_path
from dem_contact.studies.chart3d import chart_scene, read_twist_reference
from dem_contact.studies.paths import run_path

BEM = pathlib.Path(__file__).resolve().parents[2] / "validation" / "bem" / "paths"
BEM_VARYING = pathlib.Path(__file__).resolve().parents[2] / "validation" / "twist" / "bem_extra"
MU, R, DELTA = 0.3, 0.01, 1e-5
G = STEEL.E / (2 * (1 + STEEL.nu))
G_STAR = G / (2 * (2 - STEEL.nu))       # steel on steel: 1/G* = (2 - nu1)/G1 + (2 - nu2)/G2
G_C = G / 2                             # 1/G_c = 1/G1 + 1/G2
E_STAR = STEEL.E / (2 * (1 - STEEL.nu**2))
A = math.sqrt(R * DELTA)
N = 4 / 3 * STEEL.E / (2 * (1 - STEEL.nu**2)) * math.sqrt(R) * DELTA**1.5
SLIP = 3 * MU * N / (16 * G_STAR * A)   # Mindlin's displacement at full slip
BETA1 = 3 * MU * N / (16 * G_C * A * A)  # the twist at which the no-slip moment equals mu N a


LEVERS = ("limits", "rings")


def law(ux, uy, beta, **kw):
    """The law's resistance along the path: minus the force and moment on body 1, and the work absorbed."""
    Tx, Ty, M, W = twist_shear_path(G_STAR, G_C, MU, R, N, A, ux, uy, beta, **kw)
    return -Tx, -Ty, -M, W


def test_the_path_law_has_the_signs_of_run_path():
    """twist_shear_path returns the force and the moment on body 1, as run_path (and dem-contact path): on one
    path of shear and twist at constant N below slip, 1e-3 slip lengths, where both are the no-slip
    closed forms, the same to rounding."""
    k = np.linspace(0.0, 1.0, 5)
    ux, uy, tw = 1e-3 * SLIP * k, -2e-3 * SLIP * k, 1e-3 * BETA1 * k
    _, Tx, Ty, Mz = run_path(chart_scene(twist="deresiewicz"), np.full(k.size, DELTA), ux, uy, tw)
    lx, ly, M, _ = twist_shear_path(G_STAR, G_C, MU, R, N, A, np.r_[0.0, ux], np.r_[0.0, uy], np.r_[0.0, tw])
    assert Tx[-1] < 0.0 and Ty[-1] > 0.0 and Mz[-1] < 0.0          # resisting the motion of body 1
    assert np.abs(lx[1:] - Tx).max() < 1e-9 * abs(Ty[-1]) and np.abs(ly[1:] - Ty).max() < 1e-9 * abs(Ty[-1])
    assert np.abs(M[1:] - Mz).max() < 1e-9 * abs(Mz[-1])


@pytest.mark.parametrize("lever", LEVERS)
def test_pure_shear_is_the_vector_mdr_law(lever):
    """No twist: every point of a ring alike, the cells of mdr_adaptive (16 cells, the same grid)."""
    sc = chart_scene()
    assert sc.pair.G_star == pytest.approx(G_STAR, rel=1e-12)
    k = np.linspace(0.0, 1.0, 61)
    ux = SLIP * np.concatenate([0.8 * k, 0.8 - 1.3 * k[1:], -0.5 + 0.3 * k[1:]])
    uy = SLIP * np.concatenate([0 * k, 0 * k[1:], 0.7 * k[1:]])
    Nr, Tx, Ty = run_path(sc, np.full(ux.size, DELTA), ux, uy)
    assert Nr[1:] == pytest.approx(N, rel=1e-12)
    lx, ly, M, _ = law(ux, uy, 0 * ux, cells=16, slip_lever=lever)
    assert np.abs(lx + Tx).max() < 1e-9 * MU * N and np.abs(ly + Ty).max() < 1e-9 * MU * N
    assert np.abs(M).max() < 1e-12 * MU * N * A          # rounding of the mean over the points


@pytest.mark.parametrize("lever", LEVERS)
def test_pure_twist_is_deresiewicz(lever):
    """No shear: every point at the same |theta|, the twist cells of deresiewicz (32 cells), also with a
    reversal across the whole elastic range in one step."""
    beta = BETA1 * np.concatenate([np.linspace(0, 2, 41), np.linspace(2, -2, 81)[1:], np.linspace(-2, 1, 61)[1:],
                                   [-3.0, 2.0]])
    M_ref, W_ref = d.twist_path(G_C, MU, R, np.full(beta.size, N), np.full(beta.size, A), beta, 32)
    Tx, Ty, M, W = law(0 * beta, 0 * beta, beta, slip_lever=lever)
    assert np.abs(M - M_ref).max() < 1e-9 * MU * N * A
    assert np.abs(W - W_ref).max() < 1e-9 * MU * N * A * BETA1
    assert np.abs(Tx).max() < 1e-12 * MU * N and np.abs(Ty).max() < 1e-12 * MU * N


@pytest.mark.parametrize("lever", LEVERS)
def test_closed_forms(lever):
    # no slip, shear and twist together: Mindlin's 8 G* a u and Johnson's (16/3) G_c a^3 beta, exact
    Tx, Ty, M, _ = law(np.array([0.0, 1e-6 * SLIP]), np.array([0.0, -2e-6 * SLIP]), np.array([0.0, 1e-6 * BETA1]),
                       slip_lever=lever)
    assert Tx[-1] == pytest.approx(8 * G_STAR * A * 1e-6 * SLIP, rel=1e-12)
    assert Ty[-1] == pytest.approx(-8 * G_STAR * A * 2e-6 * SLIP, rel=1e-12)
    assert M[-1] == pytest.approx(16 / 3 * G_C * A**3 * 1e-6 * BETA1, rel=1e-12)
    # full slip: mu N in shear (every cell at its limit), Lubkin's (3 pi/16) mu N a in twist (the centre
    # never slips: within 1e-3 at 40 beta_1)
    k = np.linspace(0.0, 1.0, 101)
    assert law(3 * SLIP * k, 0 * k, 0 * k, slip_lever=lever)[0][-1] == pytest.approx(MU * N, rel=1e-12)
    assert law(0 * k, 0 * k, 40 * BETA1 * k, slip_lever=lever)[2][-1] == pytest.approx(
        3 * math.pi / 16 * MU * N * A, rel=1e-3)


@pytest.mark.parametrize("lever", LEVERS)
def test_shear_and_twist_share_the_limit(lever):
    """A contact near full slip in shear carries less twist, and twisting it takes force that untwisting
    does not give back."""
    k = np.linspace(0.0, 1.0, 101)
    twist_only = law(0 * k, 0 * k, BETA1 * k, slip_lever=lever)[2][-1]
    ux = SLIP * np.concatenate([0.9 * k, np.full(200, 0.9)])
    beta = BETA1 * np.concatenate([0 * k, k[1:], 1 - k[1:]])
    Tx, _, M, _ = law(ux, 0 * ux, beta, slip_lever=lever)
    assert M[200] < 0.9 * twist_only
    assert Tx[-1] < 0.9 * Tx[100]


def hertz_disc_full_slip(t, nr=100, nt=180):
    """(T / (mu N), M / (mu N a)) of the Hertz disc sliding with (v, w a) = (cos t, sin t): mu p along the
    sliding direction of the rigid motion at every point (midpoint quadrature in r, theta)."""
    r = (np.arange(nr) + 0.5) / nr
    th = (np.arange(nt) + 0.5) / nt * 2 * np.pi
    rr, tt = np.meshgrid(r, th, indexing="ij")
    x, y = rr * np.cos(tt), rr * np.sin(tt)
    w = 3 / (2 * np.pi) * np.sqrt(1 - rr**2) * rr / nr * 2 * np.pi / nt      # p dA / N (a = 1)
    vx, vy = math.cos(t) - math.sin(t) * y, math.sin(t) * x
    m = np.hypot(vx, vy)
    return (w * vx / m).sum(), (w * (x * vy - y * vx) / m).sum()


def test_full_slip_under_sliding_and_spin():
    """Sliding with spin far into full slip (default lever rings): force and moment within 0.07 mu N and
    0.04 mu N a of the exact Hertz disc's at the same ratio of spin to sliding (validation: 0.060 and 0.029
    at most over the ratios); the separate limits bound them."""
    k = np.linspace(0.0, 1.0, 401)
    L = 40 * max(SLIP, BETA1 * A)
    for t in (0.4, 0.8, 1.2):
        Tx, Ty, M, _ = law(L * math.cos(t) * k, 0 * k, L * math.sin(t) * k / A)
        Te, Me = hertz_disc_full_slip(t)
        assert abs(Tx[-1] / (MU * N) - Te) < 0.07 and abs(M[-1] / (MU * N * A) - Me) < 0.04
        assert abs(Ty[-1]) < 1e-9 * MU * N
        assert Tx[-1] < MU * N and M[-1] < 3 * math.pi / 16 * MU * N * A


@pytest.mark.parametrize("lever", LEVERS)
def test_objective_under_the_points_symmetries(lever):
    """A turn of the path by 2 pi / K turns the force (the K points map onto each other) and keeps the
    moment; the mirror y -> -y with the twist reversed mirrors the force and reverses the moment."""
    rng = np.random.default_rng(3)
    p = np.cumsum(rng.normal(0, 0.3, (80, 3)), axis=0)
    p[0] = 0.0
    ux, uy, beta = SLIP * p[:, 0], SLIP * p[:, 1], BETA1 * p[:, 2]
    Tx, Ty, M, W = law(ux, uy, beta, slip_lever=lever)
    Rx, Ry, RM, _ = law(-uy, ux, beta, slip_lever=lever)      # turned by pi/2 (K = 8)
    assert np.abs(Rx + Ty).max() < 1e-9 * MU * N and np.abs(Ry - Tx).max() < 1e-9 * MU * N
    assert np.abs(RM - M).max() < 1e-9 * MU * N * A
    Fx, Fy, FM, _ = law(ux, -uy, -beta, slip_lever=lever)
    assert np.abs(Fx - Tx).max() < 1e-9 * MU * N and np.abs(Fy + Ty).max() < 1e-9 * MU * N
    assert np.abs(FM + M).max() < 1e-9 * MU * N * A


@pytest.mark.parametrize("lever", LEVERS)
def test_closed_loops_absorb_work(lever):
    """Random histories, then closed loops in (ux, uy, beta) of every size, at constant N: the loop work is
    positive (the law creates no energy; checked, not proven: see the module docstring)."""
    rng = np.random.default_rng(7)
    t = np.linspace(0, 2 * np.pi, 61)
    for _ in range(40):
        pre = np.cumsum(rng.normal(0, 0.4, (30, 3)), axis=0)
        pre[0] = 0.0
        amp = 10 ** rng.uniform(-2.5, 0.3)
        c = rng.normal(0, 0.8, (4, 3)) * amp
        loop = np.outer(np.sin(t), c[0]) + np.outer(1 - np.cos(t), c[1]) + np.outer(np.sin(2 * t), c[2] / 2) \
            + np.outer(1 - np.cos(2 * t), c[3] / 2)
        path = np.vstack([pre, pre[-1] + loop[1:]])
        W = law(SLIP * path[:, 0], SLIP * path[:, 1], BETA1 * path[:, 2], cells=16, slip_lever=lever)[3]
        assert W[-1] - W[29] > 0.0


@pytest.mark.parametrize("shape", ["shear-twist_0.6", "circle-twist_0.4"])
def test_boundary_element_reference_with_twist(shape):
    """The stored BEM histories (128 elements across, 400 steps; validation/bem/twist.py), default law:
    force within 0.03 mu N and moment within 0.03 mu N a (the separate laws miss by 0.22 / 0.09 and
    0.10 / 0.14)."""
    (dl, ux, uy, tw), (Nr, Txr, Tyr, Mzr) = read_twist_reference(BEM / f"{shape}_n128_s400.csv")
    name, size = shape.split("_")
    path = named_path(name, float(size), 400, delta=DELTA, mu=MU, kappa=4 * G_STAR * 2 * (1 - STEEL.nu**2) / STEEL.E,
                      twist_unit=BETA1)
    assert all(np.allclose(p, q, rtol=1e-9, atol=1e-20) for p, q in zip(path, (dl, ux, uy, tw)))
    Tx, Ty, M, _ = law(ux, uy, tw)
    assert np.max(np.hypot(Tx + Txr, Ty + Tyr)) < 0.03 * MU * N
    assert np.max(np.abs(M + Mzr)) < 0.03 * MU * N * A


def test_bad_input_is_refused():
    z = np.zeros(3)
    for kw in ({"cells": 15}, {"cells": 0}, {"sectors": 1}, {"sectors": 2.5}, {"cells": True},
               {"slip_lever": "radius"}, {"residual": "halved"}):
        with pytest.raises(InputError):
            law(z, z, z, **kw)
    with pytest.raises(InputError):
        law(z, z, np.zeros(4))
    with pytest.raises(InputError):
        law(z, z, np.array([0.0, np.nan, 0.0]))
    with pytest.raises(InputError):
        twist_shear_path(G_STAR, G_C, 0.0, R, N, A, z, z, z)
    for n_, a_ in ((np.full(4, N), A), (N, np.array([A, -A, A])), (np.array([N, np.inf, N]), A)):
        with pytest.raises(InputError, match="N \\(normal force|a \\(contact radius"):
            twist_shear_path(G_STAR, G_C, MU, R, n_, a_, z, z, z)


def test_the_path_command_runs_the_coupled_law():
    """``dem-contact path --shape shear-twist --coupled``: the command's forces and moment on body 1 (its
    Hertz N and a, the scene's moduli) against the stored BEM history of the same path, within the law's
    0.03 mu N and 0.03 mu N a; --coupled with another law, with the reference or with a normal law other than
    Hertz is refused (exit 2)."""
    import json
    import subprocess
    import sys

    run = lambda *a: subprocess.run([sys.executable, "-m", "dem_contact", "path", *a], capture_output=True,  # noqa: E731
                                    text=True, timeout=600)
    r = run("--shape", "shear-twist", "--coupled", "--json")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    _, (Nr, Txr, Tyr, Mzr) = read_twist_reference(BEM / "shear-twist_0.6_n128_s400.csv")
    assert np.allclose(out["N"], N, rtol=1e-12)
    assert np.max(np.hypot(np.array(out["Tx"]) - Txr, np.array(out["Ty"]) - Tyr)) < 0.03 * MU * N
    assert np.max(np.abs(np.array(out["Mz"]) - Mzr)) < 0.03 * MU * N * A
    for args, word in ((("--shape", "shear-twist", "--coupled", "--reference"), "--coupled"),
                       (("--shape", "twist-cycle", "--coupled", "--twist", "sds"), "--coupled"),
                       (("--shape", "shear-twist", "--coupled", "--normal", "thornton", "--yield-stress", "1e9"),
                        "Hertz")):
        r = run(*args)
        assert r.returncode == 2 and word in r.stderr and "Traceback" not in r.stderr, r.stderr


def hertz(delta):
    """(N, a) of a Hertz contact at the overlaps delta (Johnson 1985, eq. 4.23), steel on steel, R* = R."""
    return 4 / 3 * E_STAR * math.sqrt(R) * delta**1.5, np.sqrt(R * delta)


def varying_path():
    """(delta, ux, uy) of a path that shears while the overlap is loaded to 1.9, unloaded to 0.6 (once by 0.6 to
    0.75 in one row) and oscillated, in units of DELTA and SLIP; the contact's first radius and its largest lie
    in one octave [n ds / 2, n ds) of the grid and it never shrinks below n ds / 4, so that the grids of
    mdr_adaptive and deresiewicz (set at first contact, then doubled or halved) are the law's (set by the
    largest radius)."""
    k = np.linspace(0.0, 1.0, 31)[1:]
    d = np.concatenate([[1.0], 1 + 0 * k, 1 + 0.9 * k, 1.9 - 1.3 * k, [0.75], 0.6 + 0.6 * np.sin(3 * k) ** 2])
    x = np.concatenate([[0.0], 0.7 * k, 0.7 + 0 * k, 0.7 - 1.2 * k, [-0.45], -0.5 + 0.4 * np.sin(5 * k)])
    y = np.concatenate([[0.0], 0 * k, 0.3 * k, 0.3 + 0 * k, [0.25], 0.3 - 0.8 * k])
    return DELTA * d, SLIP * x, SLIP * y


@pytest.mark.parametrize("lever", LEVERS)
def test_pure_shear_under_a_varying_force_is_the_vector_mdr_law(lever):
    """No twist, the overlap varying: the cells of mdr_adaptive (16 cells) through the 3D kernel, to rounding."""
    dl, ux, uy = varying_path()
    Nr, Tx, Ty = run_path(chart_scene(), dl, ux, uy)
    Nh, ah = hertz(dl)
    assert np.allclose(Nr, Nh, rtol=1e-12)
    z = np.zeros(1)
    for rule in ("scaled", "dropped"):
        lx, ly, M, _ = twist_shear_path(G_STAR, G_C, MU, R, np.r_[z, Nh], np.r_[z, ah], np.r_[z, ux], np.r_[z, uy],
                                        np.zeros(ux.size + 1), cells=16, slip_lever=lever, residual=rule)
        assert np.abs(lx[1:] - Tx).max() < 1e-9 * MU * N and np.abs(ly[1:] - Ty).max() < 1e-9 * MU * N
        assert np.abs(M).max() < 1e-12 * MU * N * A
    assert np.abs(Tx).max() > 0.5 * MU * N             # (the path slides)


@pytest.mark.parametrize("lever", LEVERS)
def test_pure_twist_under_a_varying_force_is_deresiewicz(lever):
    """No shear, the overlap varying (once unloaded by 0.6 to 0.75 in one row while the twist turns back): the
    twist cells of deresiewicz (32 cells, ``twist_path``), to rounding."""
    dl = varying_path()[0]
    Nh, ah = hertz(dl)
    k = np.linspace(0.0, 1.0, 31)[1:]
    b = BETA1 * np.concatenate([[0.0, 0.0], 1.5 * k, 1.5 - 3.5 * k, -2 + 0 * k, [-1.9], -2 + 4 * k])
    M_ref, W_ref = d.twist_path(G_C, MU, R, np.r_[0.0, Nh], np.r_[0.0, ah], b, 32)
    for rule in ("scaled", "kept"):
        Tx, Ty, M, W = twist_shear_path(G_STAR, G_C, MU, R, np.r_[0.0, Nh], np.r_[0.0, ah], 0 * b, 0 * b, b,
                                        slip_lever=lever, residual=rule)
        assert np.abs(M + M_ref).max() < 1e-9 * MU * N * A         # (twist_path: the resisting moment)
        assert np.abs(W - W_ref).max() < 1e-9 * MU * N * A * BETA1
        assert np.abs(Tx).max() < 1e-12 * MU * N and np.abs(Ty).max() < 1e-12 * MU * N
    assert np.abs(M_ref).max() > MU * N * A           # (the path slips)


def test_boundary_element_reference_under_a_varying_force():
    """Shear, twist and a varying overlap: the stored BEM histories (64 elements across, 400 steps;
    validation/twist/run_twist_shear_varying.py) against coupled_path, force within 0.03 and 0.09 mu N and
    moment within 0.015 and 0.05 mu N a (N and a of each row) on a path that shears, twists, loads to 2 delta,
    twists back and unloads while shearing back, and on a circle with twist while the overlap oscillates by
    40% (the separate laws miss by 0.21 / 0.09 and 0.07 / 0.22; the BEM's own grid error, 64 against 96
    across, is 5e-4 / 6e-4)."""
    from dem_contact.studies.paths import coupled_path

    for name, tol_f, tol_m in (("shear_twist_load_unload", 0.03, 0.015), ("circle_twist_overlap_40pct", 0.09, 0.05)):
        (dl, ux, uy, tw), (Nr, Txr, Tyr, Mzr) = read_twist_reference(BEM_VARYING / f"{name}_n64_s400.csv")
        Nh, ah = hertz(dl)
        assert np.ptp(dl) > 0.7 * DELTA and np.allclose(Nr, Nh, rtol=1e-9)
        Nc, Tx, Ty, Mz = coupled_path(chart_scene(), dl, ux, uy, tw)
        assert np.allclose(Nc, Nh, rtol=1e-12)
        assert np.max(np.hypot(Tx - Txr, Ty - Tyr) / (MU * Nh)) < tol_f
        assert np.max(np.abs(Mz - Mzr) / (MU * Nh * ah)) < tol_m


def test_the_path_command_runs_the_coupled_law_under_a_varying_overlap(tmp_path):
    """``dem-contact path PATH.csv --coupled`` on a path whose overlap varies (and leaves the contact for a row):
    the command's output is coupled_path's, and its N the Hertz force of each row."""
    import json
    import subprocess
    import sys

    from dem_contact.studies.paths import coupled_path

    dl, ux, uy = varying_path()
    dl[40] = -1e-7
    tw = BETA1 * np.sin(np.linspace(0.0, 6.0, dl.size))
    f = tmp_path / "p.csv"
    np.savetxt(f, np.column_stack([dl, ux, uy, tw]), delimiter=",", header="delta,ux,uy,twist", comments="",
               fmt="%.17g")
    r = subprocess.run([sys.executable, "-m", "dem_contact", "path", str(f), "--coupled", "--json"],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    N, Tx, Ty, Mz = coupled_path(chart_scene(), dl, ux, uy, tw)
    assert np.allclose(out["N"], hertz(np.maximum(dl, 0.0))[0], rtol=1e-12)
    for key, v in (("N", N), ("Tx", Tx), ("Ty", Ty), ("Mz", Mz)):
        assert np.array_equal(np.array(out[key]), v), key
    assert out["Tx"][40] == out["Mz"][40] == 0.0 and out["Tx"][41] != 0.0


@pytest.mark.parametrize("lever", LEVERS)
def test_pure_twist_under_a_varying_force_in_coarse_steps_is_deresiewicz(lever):
    """No shear, coarse rows: the contact twisted into full slip, then unloaded to half its overlap while the
    twist turns back by 1.5 beta_1 in one row (points beyond their lowered circles reversed past the far side),
    and random coarse rows (twist steps ~2 beta_1, the overlap 0.6 to 1.9): deresiewicz's twist cells, to
    rounding."""
    rng = np.random.default_rng(2)
    rows = [(np.array([0, 1, 1, 1, 0.5, 0.5]), np.array([0, 0, 1.0, 3.0, 1.5, 1.4]))]
    for _ in range(20):
        dl = rng.uniform(0.6, 1.9, 12)
        dl[:3] = 0.0, 1.0, 1.9
        rows.append((dl, np.r_[0.0, np.cumsum(rng.normal(0.0, 2.0, 11))]))
    for dl, b in rows:
        Nh, ah = hertz(DELTA * dl)
        M_ref, _ = d.twist_path(G_C, MU, R, Nh, ah, BETA1 * b, 32)
        _, _, M, _ = twist_shear_path(G_STAR, G_C, MU, R, Nh, ah, 0 * b, 0 * b, BETA1 * b, slip_lever=lever)
        assert np.abs(M + M_ref).max() < 1e-9 * MU * N * A


def test_sliding_with_spin_while_unloading_against_the_boundary_element_reference():
    """A slide with spin into full slip, unloaded to 0.6 of its overlap and reloaded to 1.2 while it goes on
    (the stored BEM history, 64 across, 300 steps): the points beyond their lowered circles slide (lever
    min(lambda, rho)), and the moment follows the BEM's within 0.05 mu N a (taking their step elastically
    instead, the moment keeps that of the larger radius: 0.142 against the BEM's 0.078 mu N a unloaded)."""
    from dem_contact.studies.paths import coupled_path

    (dl, ux, uy, tw), (Nr, Txr, Tyr, Mzr) = read_twist_reference(
        BEM_VARYING / "slide_and_spin_unload_reload_n64_s300.csv")
    Nh, ah = hertz(dl)
    assert np.ptp(dl) > 0.5 * DELTA and np.allclose(Nr, Nh, rtol=1e-9)
    _, Tx, Ty, Mz = coupled_path(chart_scene(), dl, ux, uy, tw)
    assert np.max(np.hypot(Tx - Txr, Ty - Tyr) / (MU * Nh)) < 0.05
    assert np.max(np.abs(Mz - Mzr) / (MU * Nh * ah)) < 0.05
