"""The objects a user configures cannot change under the computations that use them: Scene (replace builds a
changed copy), PairTable, Material, Sphere, Wall, PairProperties and the law and model tables."""
import dataclasses

import numpy as np
import pytest

from dem_contact.dem.pairs import pair_table
from dem_contact.errors import InputError
from dem_contact.impacts.impact import impact
from dem_contact.laws import model as M
from dem_contact.laws.model import Scene
from dem_contact.laws.slots import P_MU
from dem_contact.materials import STEEL, Material, Sphere, Wall, pair_properties

YIELDING = Material(E=70e9, nu=0.25, rho=2700.0, yield_pressure=1.2e9)


def _scene(**kw):
    return Scene(**{"sphere": Sphere(0.01, STEEL), "body2": Wall(STEEL), "mu": 0.3, "tangential": "md", **kw})


def test_a_scene_cannot_be_changed_after_use():
    """Every attribute assignment is refused with a one-line InputError that names replace; the parameter
    row handed out is a copy; impacts of the scene before and after the attempt are the same."""
    s = _scene()
    r0 = impact(s, 1.0, 0.2)
    for name, value in (("mu", 0.1), ("normal", "thornton"), ("tangential", "mdr"), ("e_n", 0.5), ("v_ref", 2.0),
                        ("params", np.zeros(3)), ("sphere", Sphere(0.02, STEEL)), ("pair", None), ("new", 1)):
        with pytest.raises(InputError, match=rf"^a Scene is immutable: scene\.{name} cannot be assigned; use "
                                             rf"scene\.replace\({name}=\.\.\.\)"):
            setattr(s, name, value)
    with pytest.raises(InputError, match="immutable"):
        del s.mu
    p = s.params
    p[P_MU] = 5.0
    assert s.mu == 0.3 and s.params[P_MU] == 0.3
    r1 = impact(s, 1.0, 0.2)
    assert r1.f == r0.f and r1.e_t == r0.e_t


def test_replace_gives_the_scene_built_with_the_changed_arguments():
    """replace(**changes) equals a Scene built from scratch with those arguments, on every path: the
    parameter row, the description, and impacts (the impact functions cache constants per scene, so a
    scene used before the change must not lend them to the changed one)."""
    s = _scene()
    impact(s, 1.0, 0.2)                                # the per-scene constants of s are cached now
    for changes in (dict(mu=0.1), dict(mu=0.0), dict(normal="hertz_damped", e_n=0.5),
                    dict(normal="linear", e_n=0.7, v_ref=1.0), dict(tangential="mdr_adaptive", mdr_springs=8),
                    dict(tangential="mdr", v_ref=1.0), dict(sphere=Sphere(0.005, YIELDING), normal="thornton"),
                    dict(body2=Sphere(0.02, STEEL))):
        r = s.replace(**changes)
        fresh = _scene(**changes)
        assert np.array_equal(r.params, fresh.params) and r.describe() == fresh.describe(), changes
        a, b = impact(r, 1.0, 0.2), impact(fresh, 1.0, 0.2)
        assert (a.e_n, a.e_t, a.f, a.Psi_r) == (b.e_n, b.e_t, b.f, b.Psi_r), changes
    assert s.mu == 0.3 and s.tangential == "md" and s.normal == "hertz"


def test_a_replaced_friction_coefficient_acts_on_the_impact():
    """Far above the critical impact angle the contact slides throughout, and the impulse ratio is the
    friction coefficient (Coulomb: |T| = mu N at every step; Maw et al. 1976): f = mu for the replaced mu."""
    s = _scene(tangential="mdr_adaptive")
    vn = 1.0
    for mu in (0.3, 0.1, 0.05):
        r = impact(s.replace(mu=mu), vn, 20.0 * mu * vn)           # Theta = 2 vt / ((1 + e_n) mu vn) = 20
        assert r.persistent_sliding and abs(r.f / mu - 1.0) < 1e-9


def test_replace_validates_like_a_new_scene():
    s = _scene()
    with pytest.raises(InputError, match=r"^replace: 'friction' is not an argument of Scene; valid: sphere, body2"):
        s.replace(friction=0.1)
    with pytest.raises(InputError, match=r"^mu \(friction coefficient\) = -1 is outside the valid range"):
        s.replace(mu=-1.0)
    with pytest.raises(InputError, match=r"^e_n applies to the laws thornton \(normal\), hertz_damped \(normal\), linear \(normal\) only \(here: hertz"):
        s.replace(e_n=0.5)
    m = Scene(Sphere(0.005, YIELDING), Wall(STEEL), model="thornton2001")
    r = m.replace(mu=0.2)
    assert (r.model, r.normal, r.tangential, r.steps_per_contact, r.mu) == ("thornton2001", "thornton", "md",
                                                                            m.steps_per_contact, 0.2)
    assert r.arguments == {**m.arguments, "mu": 0.2}


def test_the_other_configured_objects_are_immutable():
    """PairTable, Material, Sphere, Wall and PairProperties are frozen (dataclasses.replace validates
    again); the law and model tables cannot be edited."""
    tab = pair_table([Sphere(1e-3, STEEL)], [Wall(STEEL)], tangential="md")
    for obj, name in ((tab, "normal_id"), (tab, "params"), (STEEL, "E"), (Sphere(1e-3, STEEL), "radius"),
                      (Wall(STEEL), "material"), (pair_properties(Sphere(1e-3, STEEL), Wall(STEEL)), "E_star")):
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(obj, name, 1)
    assert isinstance(tab.scenes, tuple)
    with pytest.raises(InputError, match="immutable"):
        tab.scenes[0].mu = 0.1
    with pytest.raises(InputError, match=r"^radius \(m\) = -1 is outside"):
        dataclasses.replace(Sphere(1e-3, STEEL), radius=-1.0)
    with pytest.raises(InputError, match=r"^nu \(Poisson ratio\) = 0.7 is outside"):
        dataclasses.replace(STEEL, nu=0.7)
    for table in (M.NORMAL_LAWS, M.TANGENTIAL_LAWS, M.MODELS, M.MODELS["thornton2001"], M.MDR_PROFILES,
                  M.NORMAL_LAW_SOURCES, M.TANGENTIAL_LAW_SOURCES):
        with pytest.raises(TypeError):
            table["hertz"] = 9


def test_a_path_scene_keeps_every_setting_of_the_scene():
    """The mdr scene of a path (springs placed for the path's largest overlap) is the scene with that one
    change: the limiting-pressure coupling and the MDR profile are kept."""
    from dem_contact.studies.paths import path_scene

    s = Scene(Sphere(0.005, YIELDING), Wall(STEEL), mu=0.3, normal="thornton", tangential="mdr", v_ref=1.0,
              mdr_profile="scaled", traction_yield=True)
    d = 1e-6
    r = path_scene(s, d)
    a = (s.pair.R_star * d) ** 0.5
    assert r.arguments == {**s.arguments, "mdr_springs": s.mdr_springs, "mdr_max_radius": 1.05 * a}
    assert (r.mdr_profile, r.traction_yield) == ("scaled", "proportional")
