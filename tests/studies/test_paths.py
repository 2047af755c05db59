"""Prescribed paths: Cattaneo-Mindlin loops, planar reduction, rotation, Coulomb, the CSV reader and the
``dem-contact path`` command."""
import json
import math

import numpy as np
import pytest

import dem_contact as dc
from dem_contact.cli import main
from dem_contact.errors import InputError
from dem_contact.laws.contact import contact_step
from dem_contact.reference.paths import SHAPES, named_path, scene_path, slip_displacement
from dem_contact.studies.paths import path_scene, read_path_csv, reference_path, run_path, write_path_csv
from dem_contact.laws.model import reference_speed

DELTA = 1e-5
LAWS = ["mdr", "mdr_adaptive", "md", "mindlin_incremental", "mindlin_total"]


@pytest.fixture(scope="module")
def scenes(steel_sphere, steel_wall):
    return {t: dc.Scene(steel_sphere, steel_wall, mu=0.3, tangential=t, v_ref=reference_speed(5.0)) for t in LAWS}


def test_cattaneo_mindlin_loop(scenes):
    """Exact MDR along x at constant overlap: loading T = mu N [1 - (1 - u/u_s)^(3/2)] and the Masing
    unloading branch (Johnson 1985 section 7.2; Mindlin & Deresiewicz 1953), opposing the displacement."""
    sc = dc.Scene(scenes["mdr"].sphere, scenes["mdr"].body2, mu=0.3, tangential="mdr", mdr_springs=4000,
                  mdr_max_radius=1.01 * math.sqrt(0.01 * DELTA))
    us = slip_displacement(DELTA, sc.mu, sc.pair.kappa)
    delta, ux, uy = scene_path("load-unload", 0.8, 500, sc, DELTA)
    N, Tx, Ty = run_path(sc, delta, ux, uy)
    muN = 0.3 * N[0]
    assert N[0] == pytest.approx(4 / 3 * sc.pair.E_star * math.sqrt(0.01) * DELTA ** 1.5, rel=1e-12)
    x = ux / us
    i1, i2 = int(np.argmax(x)), int(np.argmin(x))
    load = slice(0, i1 + 1)
    cm = muN * (1 - (1 - x[load]) ** 1.5)
    assert np.max(np.abs(-Tx[load] - cm)) < 2e-3 * muN
    x_star, T_star = x[i1], -Tx[i1]
    unload = slice(i1, i2 + 1)
    masing = T_star - 2 * muN * (1 - (1 - (x_star - x[unload]) / 2) ** 1.5)
    assert np.max(np.abs(-Tx[unload] - masing)) < 2e-3 * muN
    assert np.all(Ty == 0.0)


@pytest.mark.parametrize("tangential", LAWS)
def test_straight_path_is_the_planar_law_turned(scenes, tangential):
    """A straight path along any direction: the planar law's force (laws.contact.contact_step) along it."""
    sc = scenes[tangential]
    delta, u, _ = scene_path("load-unload", 1.2, 120, sc, DELTA)
    delta = delta * (1 + 0.3 * np.sin(np.linspace(0, 3, delta.size)))      # varying N as well
    sc = path_scene(sc, delta.max())            # the mdr springs placed for the path, as run_path does
    h = sc.new_history()
    T = np.empty(delta.size)
    prev_d, prev_u = 0.0, 0.0
    for k in range(delta.size):
        T[k] = contact_step(sc.normal_id, sc.tangential_id, sc.params, h, delta[k], delta[k] - prev_d,
                            u[k] - prev_u)[2]
        prev_d, prev_u = delta[k], u[k]
    for phi in [0.0, 0.7, 2.5]:
        N, Tx, Ty = run_path(sc, delta, u * math.cos(phi), u * math.sin(phi))
        scale = 0.3 * N.max()
        assert np.max(np.abs(Tx + T * math.cos(phi))) < 1e-12 * scale
        assert np.max(np.abs(Ty + T * math.sin(phi))) < 1e-12 * scale


@pytest.mark.parametrize("tangential", LAWS)
@pytest.mark.parametrize("shape", SHAPES)
def test_coulomb_and_elastic_start(scenes, tangential, shape):
    sc = scenes[tangential]
    delta, ux, uy = scene_path(shape, 0.6, 200, sc, DELTA)
    N, Tx, Ty = run_path(sc, delta, ux, uy)
    assert np.all(np.hypot(Tx, Ty) <= 0.3 * N * (1 + 1e-12))
    # first tangential step: elastic, T = -8 G* a du opposing the displacement (Mindlin 1949)
    a = math.sqrt(sc.pair.R_star * DELTA)
    k = 8 * sc.pair.G_star * a
    du = np.array([ux[1] - ux[0], uy[1] - uy[0]])
    if tangential != "mindlin_total":
        assert np.allclose([Tx[1], Ty[1]], -k * du, rtol=2e-2, atol=0)


def test_separation_releases_the_history(scenes):
    sc = scenes["mdr_adaptive"]
    d = np.array([DELTA, DELTA, 0.0, DELTA, DELTA])
    ux = np.array([0.0, 2e-7, 2e-7, 2e-7, 3e-7])
    N, Tx, Ty = run_path(sc, d, ux, np.zeros(5))
    assert N[2] == 0.0 and Tx[2] == 0.0
    N2, Tx2, _ = run_path(sc, d[3:], ux[3:] - 2e-7, np.zeros(2))
    assert Tx[3:] == pytest.approx(Tx2, rel=1e-14)


def test_csv_round_trip_and_errors(tmp_path):
    p = tmp_path / "p.csv"
    p.write_text("# a comment\nux,delta,uy,extra\n1e-7,1e-5,0,x\n2e-7,1e-5,1e-7,y\n")
    d, ux, uy = read_path_csv(p)
    assert list(d) == [1e-5, 1e-5] and list(ux) == [1e-7, 2e-7] and list(uy) == [0.0, 1e-7]
    out = tmp_path / "o.csv"
    write_path_csv(out, d, ux, uy, d, ux, uy)
    assert out.read_text().splitlines()[0] == "delta,ux,uy,N,Tx,Ty"
    (tmp_path / "bad1.csv").write_text("delta,ux\n1e-5,0\n")
    with pytest.raises(InputError, match="uy"):
        read_path_csv(tmp_path / "bad1.csv")
    (tmp_path / "bad2.csv").write_text("delta,ux,uy\n1e-5,zero,0\n")
    with pytest.raises(InputError, match="row 1: column ux"):
        read_path_csv(tmp_path / "bad2.csv")
    (tmp_path / "bad3.csv").write_text("delta,ux,uy\n1e-5,nan,0\n")
    with pytest.raises(InputError, match="ux"):
        read_path_csv(tmp_path / "bad3.csv")
    with pytest.raises(InputError, match="same length"):
        run_path(dc.Scene(dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL)), [1e-5, 1e-5], [0.0], [0.0, 0.0])
    with pytest.raises(InputError, match="shape"):
        named_path("square", 1.0, 100, delta=1e-5, mu=0.3, kappa=0.8)


def test_command(tmp_path, capsys):
    p = tmp_path / "p.csv"
    p.write_text("delta,ux,uy\n1e-5,0,0\n1e-5,1e-7,0\n1e-5,1e-7,1e-7\n")
    assert main(["path", str(p), "--json", "--csv", str(tmp_path / "o.csv")]) == 0
    d = json.loads(capsys.readouterr().out)
    sc = dc.Scene(dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL))
    N, Tx, Ty = run_path(sc, *read_path_csv(p))
    assert d["N"] == list(N) and d["Tx"] == list(Tx) and d["Ty"] == list(Ty)
    assert len((tmp_path / "o.csv").read_text().splitlines()) == 4
    assert main(["path", "--shape", "l-turn", "--tangential", "md", "--rigid-wall", "--plot",
                 str(tmp_path / "l.png")]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[1] == "N,Tx,Ty,Mz" and len(out) == 2 + 401
    assert (tmp_path / "l.png").stat().st_size > 0
    assert main(["path", "--shape", "load-unload", "--size", "0.5", "--steps", "12", "--reference", "--n-across",
                 "8", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert len(d["N"]) == 13 and d["law"].startswith("boundary-element")
    Nb, Txb, _ = run_path(sc, *scene_path("load-unload", 0.5, 12, sc, 1e-5))
    assert np.allclose(d["Tx"], Txb, rtol=0, atol=0.05 * 0.3 * Nb[0])   # MDR vs a coarse BEM on a straight path
    for argv in (["path"], ["path", str(p), "--shape", "circle"], ["path", str(p), "--size", "2"],
                 ["path", "--shape", "circle", "--overlap", "-1"], ["path", "--shape", "circle", "--mu", "-1"],
                 ["path", str(tmp_path / "none.csv")],
                 ["path", "--shape", "circle", "--reference", "--normal", "thornton", "--yield-stress", "1e9"]):
        assert main(argv) == 2, argv
        assert capsys.readouterr().err.count("\n") == 1


def test_a_path_deeper_than_the_laws_is_refused(capsys):
    """An overlap not below R* (1e300 m) is an InputError naming the row, from Python and as one line with
    exit code 2 from the CLI, instead of a non-finite force."""
    from dem_contact.impacts.presets import preset_scene

    with pytest.raises(InputError, match=r"^delta\[1\] = 1e\+300 m is not below"):
        run_path(preset_scene("EE", 5.0), [1e-6, 1e300], [0.0, 0.0], [0.0, 0.0])
    assert main(["path", "--shape", "circle", "--overlap", "1e300"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "not below the pair's effective radius" in err


def test_twist_paths_through_the_law_and_the_reference(tmp_path, capsys):
    """A path with a twist column: every twist law of the table gets the relative spin d twist/dt about
    the normal through contact_force_torque (Mz opposes the twist in the first step; 0 for 'none', which
    leaves the force as without twist); the CLI refuses a twisting path with the default law 'none' unless
    --twist is named, and with --reference returns the BEM's Mz; the CSV output has twist and Mz."""
    from dem_contact.laws import table
    from dem_contact.reference.paths import TWIST_SHAPES

    base = dc.Scene(dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL), mu=0.3)
    d, ux, uy, tw = scene_path("circle-twist", 0.4, 40, base, DELTA)
    N0, Tx0, Ty0 = run_path(base, d, ux, uy)
    needs = dict(sds=dict(k_twist=1e-2, gamma_twist=0.0, mu_twist=1e-4))   # (an engine model's coefficients)
    for law in table.ids("twist"):
        sc = base.replace(twist=law, **needs.get(law, {}))
        N, Tx, Ty, Mz = run_path(sc, d, ux, uy, tw)
        assert np.all(np.isfinite(Mz)) and Mz[1] * tw[1] <= 0.0
        if law == "none":
            assert np.all(Mz == 0.0) and np.array_equal(Tx, Tx0) and np.array_equal(Ty, Ty0)
    for shape in TWIST_SHAPES:                        # the named twist paths close where they say
        d2, x2, y2, t2 = scene_path(shape, 0.5, 30, base, DELTA)
        assert t2[0] == 0.0 and np.max(np.abs(t2)) > 0 and np.all(d2 == DELTA)
    p = tmp_path / "t.csv"
    p.write_text("delta,ux,uy,twist\n1e-5,0,0,0\n1e-5,1e-7,0,2e-3\n1e-5,1e-7,0,0\n")
    assert len(read_path_csv(p)) == 4
    assert main(["path", str(p)]) == 2
    err = capsys.readouterr().err
    assert "--twist" in err and err.count("\n") == 1
    assert main(["path", str(p), "--twist", "none", "--reference"]) == 2
    capsys.readouterr()
    assert main(["path", str(p), "--twist", "none", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["Mz"] == [0.0, 0.0, 0.0]
    out = tmp_path / "o.csv"
    assert main(["path", str(p), "--reference", "--n-across", "12", "--json", "--csv", str(out)]) == 0
    j = json.loads(capsys.readouterr().out)
    Nr, Txr, Tyr, Mzr = reference_path(base, *read_path_csv(p), n_across=12)
    assert j["Mz"] == list(Mzr) and j["Tx"] == list(Txr) and Mzr[1] < 0 < Mzr[2]
    rows = out.read_text().splitlines()
    assert rows[0] == "delta,ux,uy,twist,N,Tx,Ty,Mz" and float(rows[2].split(",")[-1]) == Mzr[1]
    assert main(["path", "--shape", "twist-cycle", "--steps", "8", "--reference", "--n-across", "8",
                 "--plot", str(tmp_path / "t.png")]) == 0
    assert (tmp_path / "t.png").stat().st_size > 0
