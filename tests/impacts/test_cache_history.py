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

#: law pairs of the commands: the default, the plastic preset, the classic md, a damped normal law (scene case,
#: normal law, tangential law, e_n or None)
PAIRS = [
    ("EE", "hertz", "mdr_adaptive", None),
    ("PE", "thornton", "mdr_adaptive", None),
    ("EE", "hertz", "md", None),
    ("EE", "hertz_damped", "mdr", 0.7),
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


USER_MODULE = r"""
import dem_contact
from dem_contact.kernel_cache import follow_kernels
follow_kernels(__file__)

import numpy as np
from numba import njit

from dem_contact.impacts.presets import preset_scene
from dem_contact.laws.normal.hertz import hertz


@njit(cache=True)
def users_own_loop(p, deltas):
    total = 0.0
    for d in deltas:
        total += hertz(p, d)[0]
    return total


scene = preset_scene("EE", 5.0, tangential="linear")
from dem_contact.dem.contact3d import contact_forces_serial, history_size, new_histories
# (the 3D batch loop of one law: it inlines Hertz's force as every 3D entry does, and compiles in seconds)
H = new_histories(1, history_size(scene.normal_id, scene.tangential_id))
f, ft = np.zeros((1, 3)), np.zeros((1, 3))
contact_forces_serial(scene.normal_id, scene.tangential_id, scene.params[None, :], np.zeros(1, np.int64), H,
                      np.array([[0.0, 0.0, 1.0]]), np.array([1e-6]), np.zeros((1, 3)), np.zeros(1), 1e-7, f, ft)
print(scene.max_contact_radius(5.0), users_own_loop(scene.params, np.array([1e-6, 2e-6])), -f[0, 2])
"""


@pytest.mark.slow
def test_compiled_code_follows_the_law_sources_it_inlines(tmp_path):
    """A law edited after its kernels were cached (a new version installed over an old one) is what runs next:
    in the package's own kernels and in a user's cached loop that follows the package's kernels."""
    import shutil

    import dem_contact

    pkg = tmp_path / "site"
    shutil.copytree(os.path.dirname(dem_contact.__file__), pkg / "dem_contact",
                    ignore=shutil.ignore_patterns("__pycache__"))
    (tmp_path / "user.py").write_text(USER_MODULE)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba"), PYTHONPATH=str(pkg))

    def run():
        done = subprocess.run([sys.executable, str(tmp_path / "user.py")], env=env, capture_output=True, text=True,
                              timeout=600)
        assert done.returncode == 0, done.stderr[-3000:]
        return [float(x) for x in done.stdout.split()]

    before = run()
    assert run() == before                               # loaded from the cache: the same numbers
    law = pkg / "dem_contact" / "laws" / "normal" / "hertz.py"
    text = law.read_text()
    # Hertz's force is written once (hertz_vector): the edit reaches the planar impact and the 3D loop alike
    assert text.count("return 4.0 / 3.0 * E * a * delta, a") == 1
    law.write_text(text.replace("return 4.0 / 3.0 * E * a * delta, a", "return 8.0 / 3.0 * E * a * delta, a"))
    after = run()
    assert after[1] == pytest.approx(2.0 * before[1], rel=1e-14)    # the user's loop: Hertz's force doubled
    assert after[2] == pytest.approx(2.0 * before[2], rel=1e-14)    # the 3D kernel's too
    # the head-on impact of the planar kernel (laws.normal_impact): twice the stiffness, so the largest overlap
    # is 2^(-2/5) and the largest contact radius sqrt(R* delta_max) 2^(-1/5) times the same
    assert after[0] == pytest.approx(2.0 ** -0.2 * before[0], rel=2e-3)
