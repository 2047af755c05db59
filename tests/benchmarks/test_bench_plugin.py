"""Cost of a contact update of pair_style dem/contact (the LAMMPS plugin) against LAMMPS's own pair granular
hertz/material + mindlin, side by side in one process: the CPU time of LAMMPS's Pair section per contact update
(tests/lammps/plugin_bench.py; the fastest of REPEAT runs of each engine, taking turns), in extra_info; on a pressed 2,000-sphere pack and a 20,000-sphere pour, for
mindlin_total (the arithmetic of LAMMPS's model) and the library's default law, the pack on two ranks, and the
cost of the energy accounting (pair_style ... energy yes).

    pytest tests/benchmarks/test_bench_plugin.py --benchmark-only --benchmark-json plugin.json
"""
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import _have_lammps

pytestmark = pytest.mark.skipif(not _have_lammps() or shutil.which("g++") is None,
                                reason="needs the lammps extra and a C++ compiler")

ROOT = Path(__file__).resolve().parents[2]
MPIRUN = shutil.which("mpirun", path=os.path.join(sys.prefix, "bin")) or shutil.which("mpirun")


#: runs of each engine in a timed case, taking turns; the fastest counts (the ratio of two engines then depends
#: less on what else the machine did meanwhile)
REPEAT = 3


def _bench(scene, n, steps, tangential, ranks=1, engines="native,plugin", energy=False, repeat=REPEAT):
    from dem_contact.lammps import plugin_build
    plugin_build.build()
    cmd = [sys.executable, "tests/lammps/plugin_bench.py", scene, str(n), str(steps), "--tangential", tangential,
           "--engines", engines, "--repeat", str(repeat)] + (["--energy"] if energy else [])
    lib = os.path.join(sys.prefix, "lib")
    r = subprocess.run(cmd if ranks == 1 else [MPIRUN, "-np", str(ranks), *cmd], capture_output=True, text=True,
                       cwd=ROOT, env=dict(os.environ, LD_LIBRARY_PATH=lib, PYTHONPATH=str(ROOT)))
    assert r.returncode == 0, r.stderr[-3000:]
    return json.loads(r.stdout)


@pytest.mark.parametrize("scene,n,steps", [("pack", 2000, 300), ("pour", 20000, 200)])
@pytest.mark.parametrize("tangential", ["mindlin_total", "mdr_adaptive"])
def test_bench_plugin_against_pair_granular(benchmark, scene, n, steps, tangential):
    _bench(scene, 216, 20, tangential, repeat=1)            # the kernels compiled, off the clock
    out = benchmark.pedantic(_bench, args=(scene, n, steps, tangential), rounds=1, iterations=1)
    ours, native = out["plugin"], out["native"]
    benchmark.extra_info.update(
        contacts=ours["contacts"], plugin_ns_per_update=ours["ns_per_update"],
        native_ns_per_update=native["ns_per_update"], ratio=ours["ns_per_update"] / native["ns_per_update"])


def test_bench_plugin_two_ranks(benchmark):
    _bench("pack", 216, 20, "mindlin_total", engines="plugin", repeat=1)
    one = _bench("pack", 2000, 300, "mindlin_total", engines="plugin")["plugin"]
    two = benchmark.pedantic(_bench, args=("pack", 2000, 300, "mindlin_total", 2, "plugin"), rounds=1,
                             iterations=1)["plugin"]
    benchmark.extra_info.update(one_rank_pair_s=one["pair_s"], two_ranks_pair_s=two["pair_s"],
                                speedup=one["pair_s"] / two["pair_s"])


def test_bench_plugin_energy_accounting(benchmark):
    """pair_style dem/contact ... energy yes (the work of each contact's forces accounted) against no, on the
    pressed pack with mindlin_total."""
    _bench("pack", 216, 20, "mindlin_total", engines="plugin", repeat=1)
    without = _bench("pack", 2000, 300, "mindlin_total", engines="plugin")["plugin"]
    out = benchmark.pedantic(_bench, args=("pack", 2000, 300, "mindlin_total"),
                             kwargs=dict(engines="plugin", energy=True), rounds=1, iterations=1)["plugin"]
    benchmark.extra_info.update(ns_per_update=out["ns_per_update"], without_ns_per_update=without["ns_per_update"],
                                ratio=out["ns_per_update"] / without["ns_per_update"])


@pytest.mark.parametrize("tangential", ["mindlin_total", "mdr_adaptive"])
def test_bench_plugin_in_lmp(benchmark, tangential):
    """The pressed pack in ``lmp -in`` (tests/lammps/plugin_bench_lmp.py): pair granular, the plugin reaching the
    step through Python, and the plugin with the step compiled ahead of time (no Python)."""
    def run(n, steps, repeat):
        from dem_contact.lammps import plugin_build
        plugin_build.build()
        r = subprocess.run([sys.executable, "tests/lammps/plugin_bench_lmp.py", str(n), str(steps), "--tangential",
                            tangential, "--repeat", str(repeat)], capture_output=True, text=True, cwd=ROOT,
                           env=dict(os.environ, LD_LIBRARY_PATH=os.path.join(sys.prefix, "lib"), PYTHONPATH=str(ROOT)))
        assert r.returncode == 0, r.stderr[-3000:]
        return json.loads(r.stdout)

    run(216, 20, 1)          # (built and compiled, off the clock)
    out = benchmark.pedantic(run, args=(2197, 1000, REPEAT), rounds=1, iterations=1)
    native = out["native"]["ns_per_update"]
    benchmark.extra_info.update(native_ns_per_update=native, python_ns_per_update=out["python"]["ns_per_update"],
                                aot_ns_per_update=out["aot"]["ns_per_update"],
                                python_ratio=out["python"]["ns_per_update"] / native,
                                aot_ratio=out["aot"]["ns_per_update"] / native)
