"""Stores the timings that the Performance page states: runs benchmark files of ``tests/benchmarks`` with
pytest-benchmark and keeps, per benchmark, its min, median and mean [s] (and its extra_info), plus a record
``name=machine`` (CPU model, logical cores, numba threads, Python, when it ran).

    python validation/performance/run_benchmarks.py impacts      # test_bench_sweep.py, test_bench_impact.py
    python validation/performance/run_benchmarks.py contact3d    # test_bench_contact3d.py: the C comparison
                                                                  # and the pressed-packing workload
    python validation/performance/run_benchmarks.py twist        # test_bench_twist.py: with and without deresiewicz
    python validation/performance/run_benchmarks.py plugin       # test_bench_plugin.py: pair_style dem/contact
                                                                  # against LAMMPS's pair granular

Each writes ``validation/performance/results/<set>.json``: a list of records, one per benchmark, ``name`` its
pytest name (``test_bench_sweep_10k[2]``), and for each law timed both in C and in numba a record
``name=c_over_numba[LAW]`` whose ``ratio`` is the C loop's min over numba's (above 1: numba faster). Timings depend on the machine and on what else runs on it.
"""
from __future__ import annotations

import datetime
import json
import os
import pathlib
import platform
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
OUT = ROOT / "validation" / "performance" / "results"
SETS = {
    "impacts": (["tests/benchmarks/test_bench_sweep.py", "tests/benchmarks/test_bench_impact.py"], None),
    "contact3d": (["tests/benchmarks/test_bench_contact3d.py"], "test_c or test_numba or test_bench_pressed_like"),
    "twist": (["tests/benchmarks/test_bench_twist.py"], None),
    "plugin": (["tests/benchmarks/test_bench_plugin.py"], None),
}


def cpu_model() -> str:
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def run(name: str) -> pathlib.Path:
    files, select = SETS[name]
    with tempfile.TemporaryDirectory() as tmp:
        raw = pathlib.Path(tmp) / "bench.json"
        cmd = [sys.executable, "-m", "pytest", *files, "--benchmark-only", f"--benchmark-json={raw}", "-q",
               "-p", "no:cacheprovider"]
        if select:
            cmd += ["-k", select]
        subprocess.run(cmd, cwd=ROOT, check=True)
        data = json.loads(raw.read_text())
    rows = [{"name": "machine", "cpu": cpu_model(), "cores": os.cpu_count(),
             "python": platform.python_version(), "date": datetime.date.today().isoformat(),
             "command": f"python validation/performance/run_benchmarks.py {name}"}]
    for b in data["benchmarks"]:
        s = b["stats"]
        extra = b.get("extra_info") or {}
        rows.append({"name": b["name"], "group": b.get("group"), "min": s["min"], "median": s["median"],
                     "mean": s["mean"], "rounds": s["rounds"], **extra})
    mins = {r["name"]: r["min"] for r in rows if "min" in r}
    for n in list(mins):
        if n.startswith("test_c[") and "test_numba[" + n[len("test_c["):] in mins:
            law = n[len("test_c["):-1]
            rows.append({"name": f"c_over_numba[{law}]", "ratio": mins[n] / mins[f"test_numba[{law}]"]})
    OUT.mkdir(parents=True, exist_ok=True)
    path = OUT / f"{name}.json"
    path.write_text(json.dumps(rows, indent=1) + "\n")
    return path


if __name__ == "__main__":
    names = sys.argv[1:] or list(SETS)
    for n in names:
        if n not in SETS:
            sys.exit(f"unknown set {n!r}: {', '.join(SETS)}")
    for n in names:
        print(run(n))
