"""No Scene option is lost on the way: from the CLI's option table to ``preset_scene``, and on the paths that
build one Scene from another (``impacts.sweep.scene_with``, ``studies.advise``, ``studies.chart3d``)."""
import inspect
from types import SimpleNamespace

import numpy as np
import pytest

from dem_contact.cli import build_parser
from dem_contact.commands import common
from dem_contact.impacts import presets
from dem_contact.impacts.presets import preset_scene
from dem_contact.impacts.sweep import scene_with
import dem_contact as dc
from dem_contact.laws import table
from dem_contact.laws.model import Scene
from dem_contact.studies import advise as advise_mod
from dem_contact.studies import chart3d, spin

#: settings that the paths below must carry over (those not named as changed)
KEPT = ("sphere", "body2", "mu", "normal", "e_n", "mdr_profile", "traction_yield", "model")


def _changed_value(kwargs):
    """A value of the option of table row ``kwargs`` other than its default, as command-line text."""
    if kwargs.get("action") == "store_true":
        return None
    if "choices" in kwargs:
        return next(c for c in kwargs["choices"] if c != kwargs.get("default"))
    return "0.123"


def test_scene_table_is_preset_scene_keywords():
    """The CLI's scene options are the keyword arguments of preset_scene (but the twist and rolling laws, of the
    torque options) and the settings the normal and tangential laws declare for the command line, no other."""
    params = inspect.signature(presets.preset_scene).parameters
    keywords = [n for n, p in params.items() if p.kind is p.KEYWORD_ONLY and n not in ("twist", "rolling")]
    declared = [o.name for o in table.options() if o.cli is not None
                and any(o in m.OPTIONS for f in ("normal", "tangential") for m in table.FAMILIES[f])]
    assert declared and sorted(common.SCENE_KEYWORDS) == sorted(keywords + declared)


@pytest.mark.parametrize("command", ["impact", "impact3d", "sweep", "advise"])
@pytest.mark.parametrize("flag,kwargs", [row for row in common.SCENE_OPTIONS if row[0] not in ("--case", "--vn")],
                         ids=lambda x: x if isinstance(x, str) else "")
def test_each_scene_option_reaches_preset_scene(monkeypatch, command, flag, kwargs):
    """Every scene option given on the command line arrives at preset_scene (checked with a stub: the value
    need not make a valid scene)."""
    seen = {}
    monkeypatch.setattr(common, "preset_scene", lambda case, vn, **kw: seen.update(kw, case=case, vn=vn))
    value = _changed_value(kwargs)
    args = build_parser().parse_args([command, flag] + ([] if value is None else [value]))
    if args.vn is None:         # (sweep and advise set it in run)
        args.vn = 5.0
    common.scene_from_args(args)
    name = common.dest(flag)
    expected = True if value is None else (kwargs["type"](value) if "type" in kwargs else value)
    assert seen[name] == expected
    assert all(seen[common.dest(f)] == common.default(k) for f, k in common.SCENE_OPTIONS
               if f not in (flag, "--case", "--vn"))


def test_cli_scene_keeps_the_options():
    args = build_parser().parse_args(["impact", "--case", "PE", "--e-n", "0.8", "--mdr-profile", "scaled",
                                      "--traction-yield", "--mu", "0.25"])
    sc = common.scene_from_args(args)
    assert (sc.normal, sc.e_n, sc.mdr_profile, sc.traction_yield, sc.mu) == ("thornton", 0.8, "scaled", "proportional", 0.25)


@pytest.fixture(scope="module")
def rich():
    """A scene with settings off their defaults: thornton calibrated from e_n, scaled mdr profile, traction
    yield, another friction."""
    return preset_scene("PE", 5.0, e_n=0.8, mdr_profile="scaled", traction_yield=True, mu=0.25)


def _assert_kept(before, after, *changed):
    for name in KEPT:
        if name not in changed:
            assert after.arguments[name] == before.arguments[name], name


def test_scene_with_keeps_every_setting(rich):
    _assert_kept(rich, scene_with(rich, mu=0.1), "mu")
    _assert_kept(rich, scene_with(rich, nu=0.25), "sphere", "body2")
    adaptive = scene_with(rich, tangential="mdr_adaptive", mdr_springs=64)
    assert scene_with(adaptive, mu=0.2).mdr_springs == 64       # a setting of the law kept
    md = scene_with(adaptive, tangential="md")
    _assert_kept(rich, md, "mdr_profile")
    assert md.tangential == "md" and md.mdr_profile == "truncated"     # (md takes no profile: its default)
    mdr = scene_with(rich, tangential="mdr", v_ref=7.0)
    _assert_kept(rich, mdr)
    assert (mdr.tangential, mdr.v_ref) == ("mdr", 7.0)


def test_scene_with_named_model():
    model = preset_scene("PE", 5.0, model="thornton2001")
    kept = scene_with(model, mu=0.2, tangential=model.tangential)
    assert (kept.model, kept.normal, kept.tangential, kept.steps_per_contact) == (
        "thornton2001", model.normal, model.tangential, model.steps_per_contact)
    other = scene_with(model, tangential="mdr_adaptive")        # another law leaves the model, its normal law stays
    assert (other.model, other.normal, other.tangential) == (None, model.normal, "mdr_adaptive")


def test_advise_keeps_the_scene_settings(monkeypatch, rich):
    """Every scene that advise measures (the reference, the candidates, the verification) is the given scene
    with another tangential law: e_n, mdr_profile, traction_yield, mu and the normal law kept."""
    scenes = []

    def fake_evaluate(scene, sample, spc, spin_, repeats=1, scheme="located"):
        scenes.append(scene)
        n = sum(len(a) for _, a in sample)
        return np.full(n, 0.5), np.linspace(0.0, 8.0, n), np.zeros(n, bool), 1.0

    monkeypatch.setattr(advise_mod, "_evaluate", fake_evaluate)
    a = advise_mod.advise(rich, (1.0, 5.0), (0.0, 60.0), tol=1.0, n_speeds=2, n_angles=3, verify=True,
                          candidates=[("mdr_adaptive", 30)])
    assert a.recommended is not None
    laws = {sc.tangential for sc in scenes}
    assert {"mdr", "mdr_adaptive", "md"} <= laws
    for sc in scenes:
        _assert_kept(rich, sc, *(() if sc.tangential in ("mdr", "mdr_adaptive") else ("mdr_profile",)))
    assert max(sc.mdr_springs for sc in scenes if sc.tangential == "mdr") > min(
        sc.mdr_springs for sc in scenes if sc.tangential == "mdr")      # the reference: twice the springs


def test_spin_chart_keeps_the_scene_settings(monkeypatch):
    """The 3D spin chart builds each law's scene from the given scene, every setting kept."""
    base = preset_scene("EE", 5.0, normal="hertz_damped", e_n=0.7, mu=0.2)
    scenes = []
    monkeypatch.setattr(spin, "compare_spin_cases",
                        lambda sc, ref, vn: scenes.extend(sc.values()) or [SimpleNamespace(error=0.0)])
    monkeypatch.setattr(spin, "time_per_impact", lambda *a, **k: 1e-6)
    ref = [SimpleNamespace(vt=1.0, spin_x=10.0, steps=100)]
    rows = chart3d.spin_impact_chart(ref, vn=4.0, repeats=1, scene=base)
    assert len(rows) == len(chart3d.LAWS) == len(scenes)
    for (label, law, options), sc in zip(chart3d.LAWS, scenes):
        assert isinstance(sc, Scene) and sc.tangential == law and sc.v_ref == 4.0
        _assert_kept(base, sc)
        assert all(getattr(sc, k) == v for k, v in options.items())


def test_v_ref_refused_where_no_law_takes_it():
    """v_ref acts on the linear laws, the thornton calibration and the mdr grid only: given to other laws it
    is refused, naming the laws that take it; reference_speed(vn) is the run's speed for any laws (used where
    taken, kept through replace for a later law that takes it)."""
    from dem_contact.laws.model import reference_speed
    sphere, wall = dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL)
    with pytest.raises(dc.InputError, match="v_ref applies to the laws .*linear"):
        dc.Scene(sphere, wall, v_ref=5.0)
    with pytest.raises(dc.InputError, match="v_ref"):
        dc.Scene(sphere, wall, tangential="md").replace(v_ref=5.0)
    s = dc.Scene(sphere, wall, v_ref=reference_speed(5.0))
    assert s.v_ref == 5.0
    mdr = s.replace(tangential="mdr")
    assert mdr.mdr_max_radius > 0 and mdr.v_ref == 5.0
    assert dc.Scene(sphere, wall, tangential="mdr", v_ref=5.0).with_tangential("md").v_ref is None
