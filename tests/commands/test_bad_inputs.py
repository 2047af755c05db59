"""Options that cannot act, garbage magnitudes, work budgets, output paths: every one is a one-line error
(exit 2) naming the parameter, or a numerical failure (exit 3), never a traceback or a printed NaN."""
import json
import math
import os

import numpy as np
import pytest

import dem_contact as dc
from dem_contact.cli import main
from dem_contact.commands.common import explained_paths, null_paths
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
    (["impact3d", "--k-twist", "5"], "k_twist"),
    (["impact3d", "--twist", "sds"], "k_twist"),
    (["impact3d", "--rolling", "sds", "--k-roll", "-1", "--gamma-roll", "0", "--mu-roll", "0"], "k_roll"),
    (["path", "--shape", "twist-cycle", "--twist", "marshall", "--mu-twist", "1e-3"], "mu_twist"),
    (["path", "--shape", "twist-cycle", "--reference", "--k-twist", "1"], "--k-twist"),
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


# --- every output path of every command is checked before anything is computed ------------------------

OUTPUT_OPTIONS = {"csv", "plot", "out", "report"}
#: per (command, option): the arguments of a run that would otherwise compute, the bad path, the function
#: that computes (module, name), replaced so that the test sees whether it was called
OUTPUT_CASES = {
    ("sweep", "--csv"): (["--no-progress"], "missing/x.csv", ("dem_contact.commands.sweep", "sweep_angles")),
    ("sweep", "--plot"): (["--no-progress"], "x.pdf", ("dem_contact.commands.sweep", "sweep_angles")),
    ("impact3d", "--csv"): (["--angles", "0:10:10"], "missing/x.csv", ("dem_contact.commands.impact3d", "sweep3d")),
    ("path", "--csv"): (["--shape", "circle"], "missing/x.csv", ("dem_contact.studies.paths", "run_path")),
    ("path", "--plot"): (["--shape", "circle"], "x.pdf", ("dem_contact.studies.paths", "run_path")),
    ("chart", "--out"): ([], "blocker/sub", ("dem_contact.studies.chart", "chart")),
    ("validate", "--out"): ([], "blocker/sub", ("dem_contact.studies.wu2009", "run_validation")),
    ("benchmark", "--plot"): (["chung-ooi"], "blocker/sub", ("dem_contact.studies.chung_ooi", "run_suite")),
    ("benchmark", "--report"): (["chung-ooi"], "missing/r.md", ("dem_contact.studies.chung_ooi", "run_suite")),
    ("lammps-table", "--out"): (["--sphere", "0.001", "5e7", "0.25", "2500"], "missing/t.json",
                                ("dem_contact.dem.pairs", "pair_table")),
    ("lammps-mesh", "--out"): (["part.stl"], "missing/m.mesh", ("dem_contact.lammps.mesh_file", "from_stl")),
}


def _output_options():
    import argparse

    from dem_contact.cli import build_parser

    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    return {(cmd, opt) for cmd, p in sub.choices.items() for a in p._actions if a.dest in OUTPUT_OPTIONS
            for opt in a.option_strings}


def test_every_output_option_has_a_case():
    """The cases below cover every output option of every command (a new one must be added here)."""
    assert _output_options() == set(OUTPUT_CASES)


@pytest.mark.parametrize("cmd,opt", sorted(OUTPUT_CASES))
def test_output_paths_checked_before_computing(capsys, tmp_path, monkeypatch, cmd, opt):
    """A missing folder, a folder that cannot be made or a figure name that is not .png: one line, exit 2,
    before anything is computed or written."""
    import importlib

    args, bad, (module, name) = OUTPUT_CASES[(cmd, opt)]
    monkeypatch.chdir(tmp_path)
    (tmp_path / "blocker").write_text("")
    called = []
    mod = importlib.import_module(module)
    if hasattr(mod, name):
        monkeypatch.setattr(mod, name, lambda *a, **k: called.append(1))
    before = sorted(os.listdir(tmp_path))
    rc, out, err = run_cli(capsys, cmd, *args, opt, str(tmp_path / bad))
    assert rc == 2 and err.count("\n") == 1 and opt in err, err
    assert not called
    assert sorted(os.listdir(tmp_path)) == before


# --- strict JSON: no NaN or Infinity; every null says why ---------------------------------------------

def _strict(text):
    def refuse(const):
        raise AssertionError(f"not strict JSON: {const}")
    return json.loads(text, parse_constant=refuse)


JSON_RUNS = {
    "impact": ["impact", "--mu", "0", "--vt", "0"],
    "impact3d": ["impact3d", "--mu", "0", "--vt", "0", "0"],
    "impact3d-sweep": ["impact3d", "--angles", "0:10:10", *QUICK],
    "sweep": ["sweep", "--speed", "5", "--angles", "0:60:30", "--no-progress", *QUICK],
    "advise": ["advise", "--vn-range", "1", "3", "--angle-range", "0", "40"],     # a fit that never reaches 1
    "path": ["path", "--shape", "circle", "--steps", "10"],
    "benchmark": ["benchmark", "chung-ooi", "--test", "1"],
}


def test_every_json_option_is_run_below():
    import argparse

    from dem_contact.cli import build_parser

    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    with_json = {cmd for cmd, p in sub.choices.items() for a in p._actions if "--json" in a.option_strings}
    assert with_json == {args[0] for args in JSON_RUNS.values()}


@pytest.mark.parametrize("args", list(JSON_RUNS.values()), ids=list(JSON_RUNS))
def test_json_is_strict_and_every_null_has_a_reason(capsys, args):
    rc, out, err = run_cli(capsys, *args, "--json")
    assert rc == 0, err
    data = _strict(out)
    nulls = set(null_paths(data))
    assert nulls <= explained_paths(data), nulls - explained_paths(data)


def test_json_of_a_non_finite_number_is_null_with_a_reason():
    """dump_json, under every command's --json: never a ValueError on inf or NaN."""
    from dem_contact.commands.common import dump_json

    d = _strict(dump_json({"a": math.inf, "b": [1.0, np.float64("nan")], "c": {"d": -math.inf}}))
    assert d["a"] is None and d["b"] == [1.0, None] and d["c"]["d"] is None
    assert set(d["null_values"]) == {"a", "b[1]", "c.d"}


# --- options that cannot act are refused; those that can, act ----------------------------------------

@pytest.mark.parametrize("args,word", [
    (["advise", "--vn", "3"], "--vn-range"),
    (["advise", "--dt", "1e-6"], "--steps-per-contact"),
    (["path", "--shape", "circle", "--rigid-sphere", "--E", "1e9"], "--E"),
    (["path", "--shape", "circle", "--rigid-wall", "--wall-nu", "0.2"], "--wall-nu"),
    (["sweep", "--speed", "5", "--vn", "3", "--no-progress"], "--speed"),
    (["chart", "--stability", "--steps", "5", "--repeats", "1"], "--steps, --repeats"),
])
def test_options_that_cannot_act_are_refused(capsys, args, word):
    rc, out, err = run_cli(capsys, *args)
    assert rc == 2 and err.count("\n") == 1 and word in err, err


def test_a_path_too_large_to_sample_is_refused(capsys):
    """A named path of 1e300 slip displacements: the parameter's range, not an overflow in the sampling."""
    rc, out, err = run_cli(capsys, "path", "--shape", "circle", "--size", "1e300")
    assert rc == 2 and err.count("\n") == 1 and "size" in err and "1e+06" in err, err


def test_advise_law_step_and_scheme_options_act(capsys, monkeypatch):
    """--tangential, --steps-per-contact and --scheme reach advise as a candidate and the integrator end."""
    import dem_contact.studies.advise as adv

    seen = {}

    def fake(scene, *a, **k):
        seen.update(k, tangential=scene.tangential)
        raise dc.InputError("stop")

    monkeypatch.setattr(adv, "advise", fake)
    rc, out, err = run_cli(capsys, "advise", "--tangential", "md", "--steps-per-contact", "300", "--scheme",
                           "standard")
    assert rc == 2 and seen["scheme"] == "standard" and list(seen["candidates"]) == [("md", 300.0)]


def test_advise_measures_the_extra_candidate_with_the_scheme(steel_sphere, steel_wall):
    from dem_contact.studies.advise import advise

    sc = dc.Scene(steel_sphere, steel_wall, mu=0.3)
    a = advise(sc, (2.0, 5.0), (0.0, 40.0), n_speeds=1, n_angles=3, scheme="standard", candidates=[("md", 30)])
    laws = [c for c in a.candidates if "law" in c.params and c.name != "mdr@1000"]
    assert any(c.name == "md@30" for c in laws)
    assert all(c.params["scheme"] == "standard" and "standard scheme" in c.description for c in laws)
    assert math.isfinite(next(c for c in laws if c.name == "md@30").error)


def test_every_tangential_law_offered_by_path_works(capsys):
    """An offered choice works: every --tangential of path (mdr places its springs for the path)."""
    import argparse

    from dem_contact.cli import build_parser

    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    laws = next(a for a in sub.choices["path"]._actions if a.dest == "tangential").choices
    for law in laws:
        rc, out, err = run_cli(capsys, "path", "--shape", "circle", "--steps", "10", "--tangential", law)
        assert rc == 0, (law, err)


# --- messages ---------------------------------------------------------------------------------------

def test_path_csv_with_byte_order_mark(capsys, tmp_path):
    """A CSV saved by a spreadsheet (UTF-8 with a byte-order mark) reads as the same path."""
    text = "delta,ux,uy\n1e-5,0,0\n1e-5,1e-7,0\n"
    (tmp_path / "plain.csv").write_text(text, encoding="utf-8")
    (tmp_path / "bom.csv").write_text(text, encoding="utf-8-sig")
    rc1, plain, err1 = run_cli(capsys, "path", str(tmp_path / "plain.csv"))
    rc2, bom, err2 = run_cli(capsys, "path", str(tmp_path / "bom.csv"))
    assert rc1 == rc2 == 0, err2
    assert bom.splitlines()[1:] == plain.splitlines()[1:]


def test_shape_error_names_the_shape():
    from dem_contact.dem.contact3d import _array

    with pytest.raises(dc.InputError, match=r"^H must have shape \(3, any\) .*got \(2, 5\)$") as e:
        _array("H", np.zeros((2, 5)), 2, np.float64, (3, None))
    assert "'n'" not in str(e.value)


def test_readme_benchmark_usage_parses():
    """The README's usage line of the benchmark, with its placeholders filled in, is a valid command."""
    import pathlib
    import re

    from dem_contact.cli import build_parser

    readme = (pathlib.Path(__file__).resolve().parents[2] / "README.md").read_text()
    usage = next(line.strip() for line in readme.splitlines() if line.strip().startswith("dem-contact benchmark"))
    test_part = re.search(r"\[--test N.*?\]+", usage).group(0)
    filled = test_part.replace("[", " ").replace("]", " ").replace("...", "").replace("N", "1").split()
    assert filled.count("--test") == 2            # the README shows how to ask for several tests
    args = build_parser().parse_args(["benchmark", "chung-ooi", *filled])
    assert args.test == [1, 1]


def test_chart_csv_with_byte_order_mark(tmp_path):
    """The package's own CSVs read back after a spreadsheet saved them with a byte-order mark."""
    from dem_contact.studies import chart

    rows = [chart.ChartRow("hertz", "md", "located", 20.0, 0.1, 0.2, 0.3, 1e-4, 0.05, 0.05, 1.5)]
    chart.write_csv(rows, tmp_path / "c.csv")
    text = (tmp_path / "c.csv").read_text()
    (tmp_path / "bom.csv").write_text(text, encoding="utf-8-sig")
    back = chart.read_csv(tmp_path / "bom.csv")
    assert [r.tangential for r in back] == ["md"] and back[0].err_f_over_mu == 0.1


def test_csv_outputs_hold_no_nan(capsys, tmp_path):
    """Undefined quantities are empty cells in every CSV a command writes (sweep, impact3d --angles)."""
    for args in (["sweep", "--no-progress", "--no-plot", "--angles", "0:20:20", *QUICK],
                 ["impact3d", "--mu", "0", "--angles", "0:20:20", *QUICK]):
        csv_path = tmp_path / f"{args[0]}.csv"
        rc, out, err = run_cli(capsys, *args, "--csv", str(csv_path))
        assert rc == 0, err
        text = csv_path.read_text().lower()
        assert "nan" not in text and "inf" not in text and ",," in text     # (e_t at 0 deg is undefined)
