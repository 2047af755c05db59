"""The 3D chart against the BEM and the out-of-plane spin study (small sizes)."""
import numpy as np
import pytest

from dem_contact.impacts.presets import preset_scene
from dem_contact.studies import chart3d as c
from dem_contact.studies.spin import bem_spin_cases, spin_sweep


@pytest.fixture(scope="module")
def small_chart():
    paths = c.chart_paths(steps=60, paths=(("circle", 0.3), ("l-turn", 1.5)))
    forces = c.reference_forces(paths, n_across=16)
    return paths, forces


def test_vector_mdr_follows_the_bem_on_curved_paths(small_chart):
    """The vector MDR law within 0.03 mu N of the BEM on the circle through the origin of radius 0.3 and the
    L-turn after full slip (16 elements across: the BEM's own error is below 0.005 mu N there)."""
    paths, forces = small_chart
    rows = c.chart3d(paths, forces, laws=(("mdr_adaptive", "mdr_adaptive", {}),), repeats=1)
    assert [r.path for r in rows] == ["circle 0.3", "l-turn 1.5", "max"]
    assert all(r.error < 0.03 for r in rows)
    assert all(r.time_per_update_ns > 0 for r in rows)


def test_chart_error_is_zero_against_itself(small_chart, tmp_path):
    paths, _ = small_chart
    sc = c.chart_scene("md")
    own = {p: c.run_path(sc, *paths[p]) for p in paths}
    c.write_reference(tmp_path / "ref.csv", paths, own, 0)
    paths2, own2, n = c.read_reference(tmp_path / "ref.csv")
    assert n == 0 and list(paths2) == list(paths)
    for p in paths:
        assert all(np.array_equal(a, b) for a, b in zip(own[p], own2[p]))
        assert all(np.array_equal(a, b) for a, b in zip(paths[p], paths2[p]))
    rows = c.chart3d(paths2, own2, laws=(("md", "md", {}),), repeats=1)
    assert max(r.error for r in rows) == 0.0


def test_spin_study_against_the_bem():
    """A spin about the incident direction: the impulse-ratio vector of the default law within 0.01 of the
    BEM impact's (16 elements across, 60 steps), and exactly the planar impact along the slip."""
    sc = preset_scene("EE", 5.0)
    rows = spin_sweep(sc, 5.0, (30.0,), np.array([-2.0, 1.5]))
    assert max(r.planar_deviation for r in rows) < 1e-12
    b = bem_spin_cases(sc, [(30.0, 1.5)], 5.0, n_across=16, steps=60, laws=("mdr_adaptive",))[0]
    assert b.Theta_across == pytest.approx(1.5, rel=1e-3)
    assert b.error < 0.01
    assert b.out_of_plane_angle_deg == pytest.approx(b.bem_out_of_plane_angle_deg, abs=0.2)


def test_spin_reference_round_trip_and_chart(tmp_path):
    from dem_contact.studies.spin import bem_spin_reference, read_bem_spin_reference, write_rows

    sc = preset_scene("EE", 5.0)
    ref = bem_spin_reference(sc, [(30.0, 1.5)], 5.0, n_across=8, steps=30)
    write_rows(ref, tmp_path / "ref.csv")
    back = read_bem_spin_reference(tmp_path / "ref.csv")
    assert back == ref
    rows = c.spin_impact_chart(back, laws=(("mdr_adaptive", "mdr_adaptive", {}),), repeats=1)
    assert rows[0].law == "mdr_adaptive" and rows[0].error < 0.05 and rows[0].time_per_impact_us > 0


def test_law_scenes_keep_every_setting_but_the_law():
    """The spin study's law comparison changes the tangential law and the reference speed only (and the
    mdr-only settings where the law does not take them)."""
    from dem_contact.impacts.presets import preset_scene
    from dem_contact.studies.spin import law_scenes

    base = preset_scene("EE", 5.0, normal="hertz_damped", e_n=0.7, tangential="mdr",
                        mdr_profile="scaled").replace(mdr_springs=64)
    scenes = law_scenes(base, ("md", "mdr_adaptive", "mdr"), 3.0)
    assert scenes["mdr"].arguments == {**base.arguments, "v_ref": 3.0}
    assert scenes["mdr_adaptive"].arguments == {**base.arguments, "tangential": "mdr_adaptive", "v_ref": 3.0,
                                                "mdr_springs": None}
    assert scenes["md"].arguments == {**base.arguments, "tangential": "md", "v_ref": 3.0, "mdr_profile": "truncated",
                                      "mdr_springs": None}


ROOT = __import__("pathlib").Path(__file__).resolve().parents[2]


def test_twist_chart_meets_the_twist_cycle_target():
    """The exact twist law on the twist cycle to 2 beta_1 and back, against the committed BEM history at 128
    elements across (its own grid error below 3e-4 mu N a): moment within 0.01 mu N a, no tangential force;
    the reference's rows are the chart's path."""
    paths = c.twist_paths(paths=(("twist-cycle", 2.0),))
    rpath, ref = c.read_twist_reference(ROOT / "validation/bem/paths/twist-cycle_2_n128_s400.csv")
    for a, b in zip(rpath, paths["twist-cycle 2"]):
        assert np.allclose(a, b, rtol=1e-9, atol=0.0)
    rows = c.twist_chart(paths, {"twist-cycle 2": ref}, twist_laws=("deresiewicz",), repeats=1)
    (r,) = rows
    assert r.moment_error < 0.01 and r.force_error < 1e-6 and r.time_per_update_ns > 0


def test_sds_given_the_hertz_values_has_the_hertz_stiffness_and_full_slip_moment():
    """twist sds with ``sds_hertz_values``: the initial slope is the no-slip stiffness (16/3) G_c a^3 (Johnson
    1985, 7.4; steel on steel: G_c = G/2) and the moment at a large twist Lubkin's full slip (3 pi/16) mu N a,
    both from the closed forms of the scene's Hertz contact."""
    sc = c.twist_scene("sds")
    E, nu, R, d, mu = sc.sphere.material.E, sc.sphere.material.nu, sc.sphere.radius, c.DELTA, sc.mu
    a = np.sqrt(R * d)
    N = 4.0 / 3.0 * E / (2.0 * (1.0 - nu**2)) * np.sqrt(R) * d**1.5
    k = 16.0 / 3.0 * (E / (4.0 * (1.0 + nu))) * a**3
    full = 3.0 * np.pi / 16.0 * mu * N * a
    b = 1e-3 * full / k
    _, _, _, Mz = c.run_path(sc, [d, d, d], [0.0] * 3, [0.0] * 3, [0.0, b, 100.0 * full / k])
    assert Mz[1] == pytest.approx(-k * b, rel=1e-9)
    assert Mz[2] == pytest.approx(-full, rel=1e-9)
