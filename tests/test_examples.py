"""Every example runs (small sizes, in a subprocess) and exits with 0."""
import os
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import _have_lammps

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"

CASES = {
    "dem_pour.py": ["--small"],
    "single_impact.py": ["--steps", "200"],
    "sweep.py": ["--n", "4", "--steps", "100"],
    "custom_composition.py": ["--normal", "hertz", "--tangential", "md", "mindlin_total", "--mu", "0.2",
                              "--steps", "100"],
    "lammps_impact.py": ["--angle", "30", "--json"],
    "lammps_pour.py": ["--small", "--json"],
    "make_hopper_stl.py": ["--out", "hopper_copy.stl", "--binary"],
}
NEEDS_LAMMPS = {"lammps_impact.py", "lammps_pour.py"}
#: examples run by other tests: test_lammps_scene.py runs them --small, against LAMMPS's own models
ELSEWHERE = {"lammps_drum.py", "lammps_hopper.py"}


def test_every_example_is_listed():
    assert {p.name for p in EXAMPLES.glob("*.py")} == set(CASES) | ELSEWHERE


@pytest.mark.parametrize("name", sorted(CASES))
def test_example_runs(name, tmp_path):
    if name in NEEDS_LAMMPS and not _have_lammps():
        pytest.skip("needs the lammps extra")
    args = list(CASES[name])
    if name == "dem_pour.py":
        args += ["--out", str(tmp_path / "out")]
    r = subprocess.run([sys.executable, str(EXAMPLES / name), *args], capture_output=True, text=True,
                       cwd=tmp_path, timeout=600, env=dict(os.environ, MPLBACKEND="Agg"))
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
    if name == "dem_pour.py":
        out = tmp_path / "out"
        vtk = sorted(out.glob("pour_*.vtk"))
        assert vtk and (out / "pour.png").stat().st_size > 0 and (out / "energy.csv").exists()
        head = vtk[-1].read_text().splitlines()[:5]
        assert head[0].startswith("# vtk DataFile") and head[3] == "DATASET POLYDATA"
