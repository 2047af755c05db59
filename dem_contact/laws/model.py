"""A contact model bound to a pair of bodies: the laws, their parameter row, and its calibration.

``Scene`` validates everything once and computes the effective properties and the parameter row that
the kernels read (see ``laws.slots``). A Scene is immutable: ``scene.replace(mu=0.1)`` builds the scene
with one setting changed, validated and calibrated again like a new one.
"""
from __future__ import annotations

import inspect
import math
from types import MappingProxyType

import numpy as np

from ..errors import InputError
from ..materials import Sphere, Wall, check_finite, pair_properties
from . import closed_forms as cf
from . import table
from .normal.hertz_damped import EN_FLOOR as HERTZ_DAMPED_EN_FLOOR
from .normal_impact import normal_impact
from .slots import (N_HIST_BASE, N_PARAMS, P_ESTAR, P_GSTAR, P_MSTAR, P_MU, P_NORMAL_LAW, P_ROLLING_LAW, P_RSTAR,
                    P_TANGENTIAL_LAW, P_TWIST_LAW)
from .tangential.mdr import MDR_PROFILES, MDR_RADIUS_MARGIN, MDR_SPRINGS, MDR_STEPS_PER_CONTACT  # noqa: F401

NORMAL_LAWS = table.ids("normal")
TANGENTIAL_LAWS = table.ids("tangential")
NORMAL_LAW_SOURCES = MappingProxyType({m.NAME: m.SOURCE for m in table.FAMILIES["normal"]})
TANGENTIAL_LAW_SOURCES = MappingProxyType({m.NAME: m.SOURCE for m in table.FAMILIES["tangential"]})
#: Cells of the default tangential law (even): its history row holds the cell width and these displacements.
MDR_ADAPTIVE_CELLS = table.law("tangential", table.DEFAULTS["tangential"]).CELLS_DEFAULT

#: Named models: laws and time-step practice of published DEM work.
#: thornton2001: Thornton, Ciomocos, Ning & Kafui (2001) and Thornton's DEM of that period: Thornton's
#: (1997) normal law (Hertz when nothing yields) with the Thornton-Yin incremental Mindlin-Deresiewicz
#: tangential law. Their time step is not given in terms we can reproduce; it is assumed fine enough for
#: converged results: 1000 steps per elastic contact time, where md is within 1e-3 of its converged f/mu.
MODELS = MappingProxyType({
    "thornton2001": MappingProxyType(dict(
        normal="thornton", normal_elastic="hertz", tangential="md", steps_per_contact=1000.0,
        source="Thornton et al. (2001), Contact mechanics and coefficients of restitution, "
               "in Granular Gases (Lecture Notes in Physics 564): thornton + md")),
})

#: Largest friction coefficient accepted (the failure map runs to 1e4).
MAX_MU = 1e10

def _law(name: str, family: str):
    laws = table.ids(family)
    if name not in laws:
        raise InputError(f"{family} law {name!r} is unknown; choose one of: {', '.join(laws)}")
    return table.law(family, name)


class _ReferenceSpeed(float):
    """A v_ref given by ``reference_speed``: used by the laws that take one, refused by none."""


def reference_speed(vn: float) -> float:
    """The speed ``vn`` [m/s] as the ``v_ref`` of a Scene whose laws may or may not take one, for code that
    builds scenes of any laws at the speed of its run (presets, studies, the command line): the laws that
    take a v_ref use it, ``replace`` keeps it (a later change to such a law finds it), and a Scene whose laws
    take none does not refuse it. A plain number given as v_ref to laws that take none is refused."""
    return _ReferenceSpeed(vn)


def law_of(family: str, name: str):
    """The module of the ``family`` law ``name`` (``laws.table``: its declarations and hooks), InputError
    naming the valid ones for an unknown name."""
    return _law(name, family)


#: the settings the laws take, by name (``declare.Option``; ``laws.table.options``)
OPTIONS = MappingProxyType({o.name: o for o in table.options()})


class Scene:
    """A sphere against a wall or a second sphere, with a normal and a tangential law.

    Parameters
    ----------
    sphere : Sphere (body 1)
    body2 : Wall or Sphere
    mu : friction coefficient, >= 0
    normal : one of ``NORMAL_LAWS``; tangential : one of ``TANGENTIAL_LAWS``
    model : a named model that sets the laws and the time step: ``MODELS`` (``"thornton2001"``: Thornton
        et al. 2001, thornton + md). Its laws are not to be given as well.
    twist, rolling : the twist law (torque about the normal from the relative spin about it) and the rolling
        law (torque across the normal from the relative rolling), for the 3D kernels (which take the relative
        spin and return the torque, ``dem.contact3d.contact_force_torque``): ``"none"`` (default), the exact
        twist ``"deresiewicz"``, or LAMMPS's engine models, which are not contact mechanics of smooth spheres:
        twist ``"marshall"`` (coefficients from the tangential law and the contact radius) or ``"sds"``,
        rolling ``"sds"`` (``laws.twist``, ``laws.rolling``)
    **options : the settings the laws take (``OPTIONS`` of the law files, ``laws.declare.Option``), listed
        below with the laws that take them. A setting given to a scene none of whose laws takes it cannot act
        and is refused; ``v_ref`` given as ``reference_speed(vn)`` (the run's speed, for code that builds
        scenes of any laws) is the exception. ``e_n`` for ``hertz_damped`` accepts 0 (perfectly inelastic):
        the limit of infinite damping, for which the dashpot of e_n = HERTZ_DAMPED_EN_FLOOR stands.

    A Scene is immutable (its attributes cannot be assigned: the parameter row, the calibrations and the
    constants cached by the impact functions are derived from them once): ``scene.replace(mu=0.1)`` returns
    a new Scene with the same arguments but the ones given, built and checked like a new one. ``params`` is
    a copy of the parameter row (float64[N_PARAMS], ``laws.slots``), for the kernels; writing to it changes
    no Scene.
    """

    #: the head-on impact under a normal law alone (``laws.normal_impact``), for the laws' calibrations
    integrate_normal = staticmethod(normal_impact)

    #: the constructor's arguments besides the laws' options
    BASE_ARGUMENTS = ("sphere", "body2", "mu", "normal", "tangential", "model", "twist", "rolling")

    def __init__(self, sphere: Sphere, body2: Sphere | Wall, mu: float = 0.3, normal: str = table.DEFAULTS["normal"],
                 tangential: str = table.DEFAULTS["tangential"], model: str | None = None,
                 twist: str = table.DEFAULTS["twist"], rolling: str = table.DEFAULTS["rolling"], **options):
        unknown = [k for k in options if k not in OPTIONS]
        if unknown:
            raise InputError(f"{', '.join(map(repr, unknown))} is not a setting of Scene; valid: "
                             f"{', '.join(self.ARGUMENTS)}")
        self._args = dict(sphere=sphere, body2=body2, mu=mu, normal=normal, tangential=tangential, model=model,
                          twist=twist, rolling=rolling, **{o.name: options.get(o.name, o.default) for o in OPTIONS.values()})
        if not isinstance(sphere, Sphere):
            raise InputError("sphere must be a Sphere")
        if not isinstance(body2, (Sphere, Wall)):
            raise InputError("body2 must be a Wall or a Sphere")
        self.sphere = sphere
        self.body2 = body2
        self.mu = check_finite("mu (friction coefficient)", mu, lo=0.0, hi=MAX_MU, lo_open=False)
        for o in OPTIONS.values():
            object.__setattr__(self, o.name, o.check(self._args[o.name]))
        self.model = model
        self.steps_per_contact = None       # the model's time-step practice (None: the integrator default)
        if model is not None:
            if model not in MODELS:
                raise InputError(f"model {model!r} is unknown; choose one of: {', '.join(MODELS)}")
            spec = MODELS[model]
            yields = any(b.material.p_y is not None for b in (sphere, body2))
            model_normal = spec["normal"] if yields or self.e_n is not None else spec["normal_elastic"]
            if (normal not in (table.DEFAULTS["normal"], model_normal)
                    or tangential not in (table.DEFAULTS["tangential"], spec["tangential"])):
                raise InputError(f"model={model!r} sets the laws ({model_normal} + {spec['tangential']} here): "
                                 f"give no other normal or tangential law with it")
            normal, tangential = model_normal, spec["tangential"]
            self.steps_per_contact = spec["steps_per_contact"]
        self.normal = normal
        self.tangential = tangential
        _law(normal, "normal")
        _law(tangential, "tangential")
        self.normal_id = table.law_id("normal", normal)
        self.tangential_id = table.law_id("tangential", tangential)
        self.twist, self.rolling = twist, rolling
        _law(twist, "twist")
        _law(rolling, "rolling")
        self.twist_id = table.law_id("twist", twist)
        self.rolling_id = table.law_id("rolling", rolling)
        self._refuse_options()
        self.pair = pr = pair_properties(sphere, body2)
        p = np.zeros(N_PARAMS)
        p[P_ESTAR] = pr.E_star
        p[P_GSTAR] = pr.G_star
        p[P_RSTAR] = pr.R_star
        p[P_MSTAR] = pr.m_star
        p[P_MU] = self.mu
        p[P_NORMAL_LAW] = self.normal_id + 1           # the laws the row is built for (checked entries)
        p[P_TANGENTIAL_LAW] = self.tangential_id + 1
        p[P_TWIST_LAW] = self.twist_id + 1
        p[P_ROLLING_LAW] = self.rolling_id + 1
        self.p_y = None
        self._params = p
        for law in self.laws:
            law.configure(self, p)
        # history slots after N_HIST_BASE (the laws with cells)
        self.tangential_extra_slots = table.planar_extra(self.tangential_id, self.mdr_springs or 0)
        self._frozen = True

    def _refuse_options(self):
        """A law option given to laws that do not take it cannot act: refused."""
        taken = sum((law.OPTIONS for law in self.laws), ())
        for option in OPTIONS.values():
            if isinstance(self._args[option], _ReferenceSpeed):
                continue
            if option not in taken and self._args[option] != option.default:
                raise InputError(f"{option} applies to the laws {', '.join(table.takers(option))} only "
                                 f"(here: {' + '.join(law.NAME for law in self.laws)})")

    def __setattr__(self, name, value):
        if self.__dict__.get("_frozen"):
            raise InputError(f"a Scene is immutable: scene.{name} cannot be assigned; use "
                             f"scene.replace({name}=...) for a scene with it changed")
        object.__setattr__(self, name, value)

    def __delattr__(self, name):
        raise InputError(f"a Scene is immutable: scene.{name} cannot be deleted")

    def replace(self, **changes) -> "Scene":
        """A new Scene with the constructor arguments of this one, but ``changes`` (any of ``ARGUMENTS``),
        validated and calibrated like a new Scene."""
        unknown = [k for k in changes if k not in self.ARGUMENTS]
        if unknown:
            raise InputError(f"replace: {', '.join(map(repr, unknown))} is not an argument of Scene; valid: "
                             f"{', '.join(self.ARGUMENTS)}")
        return Scene(**{**self._args, **changes})

    __replace__ = replace           # copy.replace (Python 3.13)

    def with_tangential(self, tangential: str, **changes) -> "Scene":
        """``replace(tangential=..., **changes)`` for another tangential law: the settings of the old law that
        no law of the new scene takes, and those that hold for one law only (``per_law``: a cell count of
        one law is not one of another), go back to their defaults; every other setting is kept."""
        new = _law(tangential, "tangential")
        others = sum((law.OPTIONS for law in self.laws if law is not self.tangential_law), new.OPTIONS)
        drop = [] if tangential == self.tangential else [
            o for o in self.tangential_law.OPTIONS if (o not in others or o.per_law)
            and not isinstance(self._args[o], _ReferenceSpeed)]
        reset = {o.name: o.default for o in drop if o not in changes}
        return self.replace(tangential=tangential, **{**reset, **changes})

    @property
    def normal_law(self):
        """The normal law's module (``laws.table``)."""
        return table.law("normal", self.normal_id)

    @property
    def tangential_law(self):
        """The tangential law's module (``laws.table``)."""
        return table.law("tangential", self.tangential_id)

    @property
    def laws(self) -> tuple:
        """The law modules of the four families (normal, tangential, twist, rolling)."""
        return (self.normal_law, self.tangential_law, table.law("twist", self.twist_id),
                table.law("rolling", self.rolling_id))

    @property
    def arguments(self) -> dict:
        """The constructor's arguments of this Scene (a copy)."""
        return dict(self._args)

    @property
    def params(self) -> np.ndarray:
        """The parameter row the kernels read, float64[N_PARAMS] (``laws.slots``): a copy (the Scene does
        not change)."""
        return self._params.copy()

    def max_contact_radius(self, vn: float) -> float:
        """Largest contact radius sqrt(R* delta_max) [m] of a head-on impact at normal speed vn [m/s],
        from a simulated normal impact with this scene's normal law."""
        p = self.params
        p[P_MU] = 0.0
        pr = self.pair
        dt = cf.hertz_contact_time(pr.E_star, pr.R_star, pr.m_star, vn) / 2000.0
        dmax = normal_impact(self.normal_id, p, np.zeros(N_HIST_BASE), vn, 1.0 / pr.m_star, dt, 200000)[2]
        return math.sqrt(pr.R_star * dmax)

    def need_v_ref(self, what: str) -> float:
        """v_ref, for a law that ``what`` needs it (``InputError`` if it was not given)."""
        if self.v_ref is None:
            raise InputError(f"v_ref (reference normal speed, m/s, > 0) is required by {what}")
        return self.v_ref

    @property
    def history_size(self) -> int:
        return N_HIST_BASE + self.tangential_extra_slots

    def new_history(self) -> np.ndarray:
        """A zeroed history row for one contact."""
        return np.zeros(self.history_size)

    def contact_time(self, vn: float) -> float:
        """Contact duration at normal speed vn [s] that sets the time step: the normal law's (Hertz's; the
        damped-Hertz contact is shorter, by a factor that depends on gamma only; the linear spring's closed
        form)."""
        return self.normal_law.contact_time(self, vn)

    def describe(self) -> dict:
        """The model and its derived parameters, for reports."""
        pr = self.pair
        p = self._params
        d = {
            "normal_law": self.normal,
            "normal_law_source": NORMAL_LAW_SOURCES[self.normal],
            "tangential_law": self.tangential,
            "tangential_law_source": TANGENTIAL_LAW_SOURCES[self.tangential],
            "model": self.model,
            "mu": self.mu,
            "E_star": pr.E_star, "G_star": pr.G_star, "R_star": pr.R_star, "m_star": pr.m_star,
            "kappa": pr.kappa,
            "sphere": {"radius": self.sphere.radius, **_material_dict(self.sphere.material)},
        }
        if isinstance(self.body2, Wall):
            d["wall"] = _material_dict(self.body2.material)
        else:
            d["sphere2"] = {"radius": self.body2.radius, **_material_dict(self.body2.material)}
        if self.model is not None:
            d.update(model_source=MODELS[self.model]["source"], steps_per_contact_model=self.steps_per_contact)
        d.update(twist_law=self.twist, rolling_law=self.rolling)
        for law in self.laws:
            d.update(law.describe(self, p))
        return d



def _signature():
    """Scene's signature: the base arguments, then the laws' settings (keyword only, with their defaults)."""
    P = inspect.Parameter
    base = [q for q in inspect.signature(Scene.__init__).parameters.values() if q.kind != P.VAR_KEYWORD][1:]
    return inspect.Signature(base + [P(o.name, P.KEYWORD_ONLY, default=o.default) for o in OPTIONS.values()])


Scene.ARGUMENTS = Scene.BASE_ARGUMENTS + tuple(OPTIONS)
Scene.__signature__ = _signature()
Scene.__doc__ += "\n    Settings of the laws (``**options``):\n\n" + "\n".join(
    f"    {o.name} : {o.describe()}; taken by {', '.join(table.takers(o))}" for o in OPTIONS.values()) + "\n"

def _material_dict(m) -> dict:
    if m.is_rigid:
        return {"rigid": True, "rho": m.rho}
    d = {"E": m.E, "nu": m.nu, "rho": m.rho}
    if m.p_y is not None:
        d["p_y"] = m.p_y
    return d
