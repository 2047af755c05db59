"""Every class of bad input gets a clear error naming the parameter, from Python and from the CLI."""
import math
import subprocess
import sys

import pytest

import dem_contact as dc

STEEL = dc.STEEL


@pytest.mark.parametrize("kwargs,name", [
    (dict(E=208e9, nu=0.6, rho=7850), "nu"),
    (dict(E=208e9, nu=-1.0, rho=7850), "nu"),
    (dict(E=-1.0, nu=0.3, rho=7850), "E"),
    (dict(E=208e9, nu=0.3, rho=-7850), "rho"),
    (dict(E=math.nan, nu=0.3, rho=7850), "E"),
    (dict(E=208e9, nu=math.nan, rho=7850), "nu"),
    (dict(E=208e9, nu=0.3, rho=7850, yield_stress=-1.0), "yield_stress"),
])
def test_material_errors(kwargs, name):
    with pytest.raises(ValueError, match=name) as e:
        dc.Material(**kwargs)
    assert isinstance(e.value, dc.InputError)


def test_nu_half_is_valid():
    assert dc.Material(208e9, 0.5, 7850).nu == 0.5


def test_body_and_scene_errors():
    with pytest.raises(dc.InputError, match="radius"):
        dc.Sphere(-0.01, STEEL)
    with pytest.raises(dc.InputError, match="radius"):
        dc.Sphere(0.0, STEEL)
    s, w = dc.Sphere(0.01, STEEL), dc.Wall(STEEL)
    with pytest.raises(dc.InputError, match="mu"):
        dc.Scene(s, w, mu=-0.1)
    with pytest.raises(dc.InputError, match="mu"):
        dc.Scene(s, w, mu=math.nan)
    with pytest.raises(dc.InputError, match="tangential law"):
        dc.Scene(s, w, tangential="nope")
    with pytest.raises(dc.InputError, match="thornton"):
        dc.Scene(s, w, normal="thornton")
    with pytest.raises(dc.InputError, match="v_ref"):
        dc.Scene(s, w, normal="linear", e_n=0.5)
    with pytest.raises(dc.InputError, match="rigid"):
        dc.Scene(dc.Sphere(0.01, dc.Material.rigid()), dc.Wall.rigid())


def test_impact_errors():
    sc = dc.Scene(dc.Sphere(0.01, STEEL), dc.Wall(STEEL))
    with pytest.raises(dc.InputError, match="vn"):
        dc.impact(sc, -1.0)          # moving away from the wall
    with pytest.raises(dc.InputError, match="vn"):
        dc.impact(sc, 0.0)
    with pytest.raises(dc.InputError, match="vt"):
        dc.impact(sc, 1.0, math.nan)
    with pytest.raises(dc.InputError, match="spin"):
        dc.impact(sc, 1.0, 0.0, math.inf)
    with pytest.raises(dc.InputError, match="dt"):
        dc.impact(sc, 5.0, dt=1e-4)  # longer than the contact
    with pytest.raises(dc.InputError, match="steps_per_contact"):
        dc.impact(sc, 5.0, steps_per_contact=1.5)
    with pytest.raises(dc.InputError, match="scheme"):
        dc.impact(sc, 5.0, scheme="rk4")


def cli(*args):
    return subprocess.run([sys.executable, "-m", "dem_contact", *args], capture_output=True, text=True)


@pytest.mark.parametrize("args,word", [
    (["--nu", "0.7"], "nu"),
    (["--E", "-5"], "E"),
    (["--density", "-1"], "rho"),
    (["--radius", "-0.01"], "radius"),
    (["--mu", "-0.2"], "mu"),
    (["--vn", "-1"], "vn"),
    (["--vt", "nan"], "vt"),
    (["--dt", "1e-3"], "dt"),
    (["--normal", "thornton", "--case", "EE"], "thornton"),
    (["--steps-per-contact", "1"], "steps_per_contact"),
    (["--mu", "abc"], "mu"),
])
def test_cli_errors(args, word):
    p = cli("impact", *args)
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and word in lines[0], p.stderr
    assert "Traceback" not in p.stderr


def test_cli_json():
    import json
    p = cli("impact", "--json", "--angle", "30", "--steps-per-contact", "200")
    assert p.returncode == 0, p.stderr
    d = json.loads(p.stdout)
    assert d["e_n"] == pytest.approx(1.0, abs=1e-4)
    assert {"initial", "final", "friction", "normal", "error"} <= set(d["energy"])
    assert d["model"]["normal_law"] == "hertz"
