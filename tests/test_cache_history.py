"""The same inputs give the same numbers whatever numba's cache holds and whatever ran before in the process.

A fresh ``NUMBA_CACHE_DIR`` is filled by separate processes, each of which compiles a different law pair first
(the history that once gave two law pairs one compiled name); then one process loads them all from that cache
and runs A, B, A for every ordered pair of law pairs (a sweep and a single impact each): every result equals,
bit for bit, the one of the fresh process that compiled that pair.
"""
import json
import os
import subprocess
import sys

import pytest

#: law pairs of the commands: the default, the plastic preset, the classic md, a spring law, the damped and linear
#: normal laws (scene case, normal law, tangential law, e_n or None)
PAIRS = [
    ("EE", "hertz", "mdr_adaptive", None),
    ("PE", "thornton", "mdr_adaptive", None),
    ("EE", "hertz", "md", None),
    ("EE", "hertz", "mindlin_total", None),
    ("EE", "hertz_damped", "mdr", 0.7),
    ("EE", "linear", "linear", 0.8),
]

WORKER = r"""
import json, sys
import numpy as np
from dem_contact import impact
from dem_contact.impacts.presets import preset_scene
from dem_contact.impacts.sweep import sweep_angles

PAIRS = json.loads(sys.argv[2])

def run(k):
    case, normal, tangential, e_n = PAIRS[k]
    vn = 2.0 if case == "PE" else 5.0
    scene = preset_scene(case, vn, normal=normal, tangential=tangential, e_n=e_n)
    s = sweep_angles(scene, [0.0, 20.0, 40.0, 70.0], vn)
    r = impact(scene, vn=vn, vt=1.5)
    return [float(x).hex() for x in (*s.e_n, *s.f_over_mu, r.e_n, r.e_t, r.omega_r)]

if sys.argv[1] == "first":
    print(json.dumps(run(int(sys.argv[3]))))
else:
    out = {}
    for a in range(len(PAIRS)):
        for b in range(len(PAIRS)):
            if a != b:
                out[f"{a} {b}"] = [run(a), run(b), run(a)]
    print(json.dumps(out))
"""


def _worker(env, *args):
    done = subprocess.run([sys.executable, "-c", WORKER, *args], env=env, capture_output=True, text=True,
                          timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


@pytest.mark.slow
def test_law_pairs_from_a_shared_cache_give_the_fresh_results(tmp_path):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba"))
    pairs = json.dumps(PAIRS)
    fresh = [_worker(env, "first", pairs, str(k)) for k in range(len(PAIRS))]
    seq = _worker(env, "sequence", pairs)
    wrong = []
    for key, runs in seq.items():
        a, b = map(int, key.split())
        for got, want, name in zip(runs, (fresh[a], fresh[b], fresh[a]), ("A", "B", "A again")):
            if got != want:
                wrong.append(f"{PAIRS[a][1:3]} then {PAIRS[b][1:3]}: {name} differs from a fresh process")
    assert not wrong, "\n".join(wrong[:10])


def test_every_jitted_function_of_the_package_has_a_name_of_its_own():
    """numba names compiled code by the function's module and qualified name: two jitted functions of the
    package under one name could run each other's code once loaded from the cache."""
    import importlib
    import pkgutil

    from numba.core.registry import CPUDispatcher

    import dem_contact

    seen = {}
    for mod in pkgutil.walk_packages(dem_contact.__path__, "dem_contact."):
        if mod.name.endswith("__main__"):
            continue
        module = importlib.import_module(mod.name)
        for obj in vars(module).values():
            if isinstance(obj, CPUDispatcher):
                key = (obj.py_func.__module__, obj.py_func.__qualname__)
                assert seen.setdefault(key, obj) is obj, f"two jitted functions named {key}"
    assert len(seen) > 50
