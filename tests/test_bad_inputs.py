"""Options that cannot act, garbage magnitudes, work budgets, output paths: every one is a one-line error
(exit 2) naming the parameter, or a numerical failure (exit 3), never a traceback or a printed NaN."""
import math
import os

import numpy as np
import pytest

import dem_contact as dc
from dem_contact.cli import main
from dem_contact.impacts.impact import MAX_STEPS_PER_CONTACT, build_result
from dem_contact.impacts.integrator import N_OUT, O_PN, O_STATUS, O_TC, O_VN, integrator_for
from dem_contact.impacts.presets import preset_scene
from dem_contact.impacts.sweep import sweep

STEEL = dc.STEEL
QUICK = ["--steps-per-contact", "20"]


def run_cli(capsys, *args):
    rc = main(list(args))
    out, err = capsys.readouterr()
    return rc, out, err


@pytest.mark.parametrize("args,word", [
    # options that cannot act
    (["impact", "--e-n", "0.5"], "e_n"),
    (["impact", "--case", "RE", "--E", "1e5"], "E"),
    (["impact", "--rigid-sphere", "--nu", "0.2"], "nu"),
    (["impact", "--rigid-wall", "--wall-E", "1e9"], "wall_E"),
    (["impact", "--yield-stress", "1e9"], "thornton"),
    (["impact", "--normal", "thornton", "--yield-stress", "1e9", "--e-n", "0.9"], "e_n"),
    (["impact", "--series"], "--series"),
    (["sweep", "--mu", "0", "--no-progress"], "--mu"),
    (["sweep", "--plot", "a.png", "--no-plot"], "--no-plot"),
    # magnitudes outside what double precision computes
    (["impact", "--vn", "1e-300"], "vn"),
    (["impact", "--vn", "1e300"], "vn"),
    (["impact", "--vt", "1e300"], "vt"),
    (["impact", "--spin", "1e300"], "spin"),
    (["impact", "--radius", "1e300"], "radius"),
    (["impact", "--radius", "1e-300"], "radius"),
    (["impact", "--E", "1e-300"], "E"),
    (["impact", "--density", "1e300"], "rho"),
    (["impact", "--mu", "1e300"], "mu"),
    (["impact", "--case", "PE", "--yield-stress", "1e300"], "yield_stress"),
    (["impact", "--normal", "thornton", "--e-n", "1e-6"], "e_n"),
    # work budgets, refused up front
    (["impact", "--steps-per-contact", "1e12"], "steps_per_contact"),
    (["impact", "--dt", "1e-30"], "dt"),
    (["impact", "--steps-per-contact", "1e7", "--series", "--json"], "GiB"),
    (["sweep", "--steps-per-contact", "1e6", "--angles", "0:85:0.001", "--no-progress"], "limit"),
    (["sweep", "--steps-per-contact", "5e6", "--angles", "0:85:0.01", "--no-progress"], "limit"),
])
def test_cli_bad_input_is_one_line_exit_2(capsys, args, word):
    rc, out, err = run_cli(capsys, *args)
    assert rc == 2, (out, err)
    assert err.count("\n") == 1 and word in err, err
    assert out == ""


@pytest.mark.parametrize("opt,path,word", [
    ("--csv", "/proc/x.csv", "cannot be written"),
    ("--plot", "/nonexistent/dir/x.png", "does not exist"),
    ("--plot", "x.txt", ".png"),
    ("--csv", ".", "directory"),
])
def test_sweep_output_paths_checked_before_computing(capsys, tmp_path, monkeypatch, opt, path, word):
    monkeypatch.chdir(tmp_path)
    called = []
    import dem_contact.commands.sweep as cmd
    monkeypatch.setattr(cmd, "sweep_angles", lambda *a, **k: called.append(1))
    rc, out, err = run_cli(capsys, "sweep", opt, path, "--no-progress")
    assert rc == 2 and word in err and err.count("\n") == 1, err
    assert not called                       # refused before any impact was computed
    assert os.listdir(tmp_path) == []       # and nothing was written


def test_output_dir_checks(capsys, tmp_path):
    blocker = tmp_path / "f"
    blocker.write_text("")
    for args in (["chart", "--out", str(blocker / "sub")], ["validate", "--out", str(blocker / "sub")],
                 ["benchmark", "chung-ooi", "--report", str(tmp_path / "no" / "r.md")]):
        rc, out, err = run_cli(capsys, *args)
        assert rc == 2 and err.count("\n") == 1, (args, err)


def test_mdr_grid_sized_for_the_sweep_speed(capsys):
    """With --speed, the mdr springs are placed for the total speed (the largest normal speed), so the
    sweep runs instead of failing with a misleading message."""
    rc, out, err = run_cli(capsys, "sweep", "--tangential", "mdr", "--speed", "10", "--angles", "0:80:40",
                           "--no-progress", "--no-plot", "--json", *QUICK)
    assert rc == 0, err


def test_mdr_grid_too_small_is_named():
    sc = preset_scene("EE", 2.0, tangential="mdr")
    with pytest.raises(dc.InputError, match="v_ref >= 10"):
        dc.impact(sc, 10.0, 1.0)
    with pytest.raises(dc.InputError, match="v_ref"):
        sweep(sc, [1.0, 10.0], [0.1, 0.1])


def test_thornton_contact_that_does_not_end_says_why(capsys):
    rc, out, err = run_cli(capsys, "impact", "--normal", "thornton", "--yield-pressure", "1e3")
    assert rc == 3 and "p_y" in err and err.count("\n") == 1


@pytest.mark.parametrize("make,word", [
    (lambda: dc.Sphere(1e300, STEEL).mass, "radius"),
    (lambda: dc.Sphere(1e-300, STEEL), "radius"),
    (lambda: dc.Sphere(0.01, "steel"), "Material"),
    (lambda: dc.Wall(None), "Material"),
    (lambda: dc.Material(E=1e300, nu=0.3, rho=1.0), "E"),
    (lambda: dc.impact(None, 5.0), "Scene"),
    (lambda: dc.impact(dc.Scene(dc.Sphere(0.01, STEEL), dc.Wall(STEEL)), 5.0, spin2=3.0), "spin2"),
    (lambda: dc.Scene(dc.Sphere(0.01, STEEL), dc.Wall(STEEL), e_n=0.5), "e_n"),
    (lambda: dc.Scene(dc.Sphere(0.01, dc.Material(208e9, 0.3, 7850, yield_stress=1e9)), dc.Wall(STEEL),
                      normal="thornton", e_n=0.9, v_ref=5.0), "e_n"),
    (lambda: dc.Scene(dc.Sphere(0.01, STEEL), dc.Wall(STEEL), normal="thornton", e_n=1e-6, v_ref=5.0), "e_n"),
    (lambda: dc.impact(preset_scene("EE", 5.0), 5.0, steps_per_contact=10 * MAX_STEPS_PER_CONTACT),
     "steps_per_contact"),
])
def test_python_bad_input_is_input_error(make, word):
    with pytest.raises(dc.InputError, match=word):
        make()


def test_nonfinite_output_row_is_a_numerical_error():
    """Whatever the cause, a result with a NaN, an inf or no impulse is never returned."""
    sc = preset_scene("EE", 5.0)
    for slot, value in ((O_VN, math.nan), (O_PN, math.inf), (O_PN, 0.0)):
        out = np.zeros(N_OUT)
        out[O_VN], out[O_PN], out[O_TC], out[O_STATUS] = -5.0, 1.0, 5e-5, 0
        out[slot] = value
        with pytest.raises(dc.NumericalError):
            build_result(sc, out, 5.0, 1.0, 0.0, 0.0, 1e-6, 50.0, "located")


def test_undefined_quantities_are_said_so(capsys):
    rc, out, err = run_cli(capsys, "impact", "--angle", "0", "--mu", "0", *QUICK)
    assert rc == 0
    assert "nan" not in out.lower() and "inf" not in out.lower()
    assert "undefined (vt = 0)" in out and "undefined (mu = 0)" in out


@pytest.mark.parametrize("ids", [(0, 99), (9, 8), (-1, 8), (True, 8), (0.5, 8)])
def test_integrator_of_unknown_laws_is_refused(ids):
    """The per-law-pair integrator is built for known law ids only (no kernel compiled for anything else)."""
    with pytest.raises(dc.InputError, match="not law ids"):
        integrator_for(*ids)
