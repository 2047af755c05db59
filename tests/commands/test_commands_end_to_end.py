"""Every command, end to end, each in its own process, on a numba cache that other processes filled first
(the kernels of other law pairs compiled and stored before): exit code 0, no traceback, strict JSON, and the
physics each prints (an elastic impact rebounds with e_n = 1, a plastic one with less, a sliding contact
has f/mu = 1, the Coulomb limit holds)."""
import json
import math
import subprocess
import sys

import pytest


def _strict(text):
    def refuse(name):
        raise AssertionError(f"non-standard JSON constant {name}")
    return json.loads(text, parse_constant=refuse)


@pytest.fixture(scope="module")
def cli():
    """Runs a command in its own process, on the test run's numba cache (filled by the processes before it)."""
    def run(*args):
        p = subprocess.run([sys.executable, "-m", "dem_contact", *args], capture_output=True, text=True,
                           timeout=600)
        assert "Traceback" not in p.stderr, p.stderr[-3000:]
        assert p.returncode == 0, (args, p.stderr[-3000:])
        return p.stdout

    # other processes fill the cache first, with other law pairs
    run("sweep", "--tangential", "md", "--angles", "0:80:40", "--no-plot", "--no-progress")
    run("sweep", "--case", "PE", "--vn", "2", "--angles", "0:80:40", "--no-plot", "--no-progress")
    run("impact", "--normal", "hertz_damped", "--e-n", "0.5", "--tangential", "mindlin_total", "--angle", "20")
    return run


@pytest.mark.slow
def test_impact_and_impact3d(cli):
    r = _strict(cli("impact", "--angle", "30", "--json"))
    assert abs(r["e_n"] - 1.0) < 1e-4 and abs(r["f_over_mu"]) <= 1.0 + 1e-9
    r3 = _strict(cli("impact3d", "--angle", "30", "--json"))
    assert abs(r3["e_n"] - r["e_n"]) < 1e-4           # the planar impact seen in 3D
    p = _strict(cli("impact", "--case", "PE", "--vn", "2", "--json"))
    assert 0.5 < p["e_n"] < 0.95                       # Thornton's plastic contact dissipates
    # spin about the normal: kept without a twist law, braked by the exact one (a twist dissipates)
    free = _strict(cli("impact3d", "--angle", "30", "--spin-vector", "0", "0", "300", "--json"))
    twisted = _strict(cli("impact3d", "--angle", "30", "--spin-vector", "0", "0", "300", "--twist", "deresiewicz",
                          "--json"))
    assert free["spin_r"][2] == 300.0 and 0.0 < twisted["spin_r"][2] < 299.0
    assert twisted["model"]["twist_law"] == "deresiewicz"


@pytest.mark.slow
def test_sweeps(cli, tmp_path):
    s = _strict(cli("sweep", "--angles", "0:85:5", "--json", "--no-progress", "--csv", str(tmp_path / "s.csv"),
                    "--plot", str(tmp_path / "s.png")))
    pts = s["points"]
    assert all(abs(p["e_n"] - 1.0) < 1e-4 for p in pts)
    assert abs(pts[-1]["f_over_mu"] - 1.0) < 1e-6      # 85 deg: sliding throughout
    assert (tmp_path / "s.csv").stat().st_size > 0 and (tmp_path / "s.png").stat().st_size > 0
    pe = _strict(cli("sweep", "--case", "PE", "--vn", "2", "--angles", "0:80:40", "--json", "--no-plot",
                     "--no-progress"))
    assert all(0.5 < p["e_n"] < 0.95 for p in pe["points"])


@pytest.mark.slow
def test_advise_path_benchmark_chart_warmup(cli, tmp_path):
    a = _strict(cli("advise", "--vn-range", "1", "3", "--angle-range", "0", "40", "--json"))
    assert a
    path = _strict(cli("path", "--shape", "circle", "--json"))
    ratio = [math.hypot(x, y) / n for n, x, y in zip(path["N"], path["Tx"], path["Ty"]) if n > 0]
    assert ratio and max(ratio) <= 0.3 * (1 + 1e-9)   # Coulomb: |T| <= mu N
    b = _strict(cli("benchmark", "chung-ooi", "--test", "1", "--json"))
    assert b
    out = cli("chart", "--out", str(tmp_path / "chart"), "--laws", "md", "--normals", "hertz", "--steps", "50",
              "--n-theta", "3", "--repeats", "1")
    assert out and any((tmp_path / "chart").iterdir())
    assert "ready" in cli("warmup")


@pytest.mark.slow
def test_validate_quick_writes_its_report(cli, tmp_path):
    cli("validate", "--quick", "--out", str(tmp_path / "val"))
    report = (tmp_path / "val" / "report.md").read_text()
    assert "coarser grids" in report and "steps of 5 deg" in report
    assert len(list((tmp_path / "val" / "figures").glob("*.png"))) >= 5


@pytest.mark.parametrize("angles, n", [("55:70:0.5", 31), ("70:85:5", 4)])
def test_sweep_keeps_its_rows_when_eq_4_5_cannot_be_fitted(angles, n, capsys):
    """Zoomed on the critical angle (the tanh does not converge on those points) or all in persistent
    sliding (nothing to fit): the rows and the simulated Theta_c come back, the fit is null with its reason."""
    from dem_contact.cli import main

    assert main(["sweep", "--angles", angles, "--json", "--no-progress"]) == 0
    out = _strict(capsys.readouterr().out)
    assert out["fit"] is None and out["fit_error"] and "fit" in out["null_values"]
    assert len(out["points"]) == n
    assert out["Theta_c_sim"] == pytest.approx(out["Theta_c_theory"], rel=2e-3)
