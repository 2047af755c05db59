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

#: Values of Scene(traction_yield=) that switch it on (True is "proportional").
TRACTION_YIELD = ("proportional", "partial_slip")


def _traction_yield(value):
    """False, or the name of the traction distribution of the first-yield table (True: "proportional")."""
    if value is False or value is None:
        return False
    if value is True:
        return "proportional"
    if isinstance(value, str) and value in TRACTION_YIELD:
        return value
    raise InputError(f"traction_yield = {value!r} is unknown; choose False, True or one of: "
                     f"{', '.join(TRACTION_YIELD)}")


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


class Scene:
    """A sphere against a wall or a second sphere, with a normal and a tangential law.

    Parameters
    ----------
    sphere : Sphere (body 1)
    body2 : Wall or Sphere
    mu : friction coefficient, >= 0
    normal : one of ``NORMAL_LAWS``; tangential : one of ``TANGENTIAL_LAWS``
    e_n : target normal restitution: sets the dashpot of ``hertz_damped`` and ``linear``; for
        ``thornton`` calibrates p_y at speed ``v_ref`` when the materials give no yield pressure.
        ``hertz_damped`` accepts e_n = 0 (perfectly inelastic): it is the limit of infinite damping, and
        any e_n below HERTZ_DAMPED_EN_FLOOR uses the dashpot of e_n = HERTZ_DAMPED_EN_FLOOR
    v_ref : reference normal speed [m/s], needed by ``linear`` laws (stiffness matched to the Hertz
        contact time at v_ref) and by the thornton calibration from e_n; for ``mdr`` the largest normal
        speed expected (sets the extent of the springs). Refused by a scene none of whose laws takes it,
        unless given as ``reference_speed(vn)`` (the run's speed, for laws that may or may not use one)
    mdr_springs : number of MDR springs (cells on the half-line), ``mdr`` only (default MDR_SPRINGS)
    mdr_max_radius : largest contact radius the MDR springs must cover [m] (``mdr`` only; default: the
        maximum contact radius of a normal impact at v_ref, times MDR_RADIUS_MARGIN)
    mdr_profile : Coulomb limit of the MDR laws (the laws that take it, ``laws.table``) during Thornton's plastic
        loading: "truncated" (default), mu times the line load of the Hertz pressure truncated at p_y,
        the distribution Thornton's force law is built on; "scaled", a Hertz-shaped limit scaled to mu N
        (see ``laws.tangential.mdr``). Both are the same for elastic laws and for Thornton unloading.
    traction_yield : ``thornton`` only: the limiting pressure falls with the traction the contact carries,
        p_y g(|T|/N), g = first-yield pressure of a Hertz contact carrying that traction over that without
        (Hamilton 1983 stresses, von Mises; ``laws.traction_yield``), tabulated for the Poisson ratio of
        the yielding body. False (default): off; "proportional" (or True): the traction (|T|/N) p;
        "partial_slip": the Cattaneo-Mindlin traction of the stick radius c/a = (1 - |T|/(mu N))^(1/3).
    twist, rolling : the twist law (torque about the normal from the relative spin about it) and the rolling
        law (torque across the normal from the relative rolling), for the 3D kernels (which take the relative
        spin and return the torque, ``dem.contact3d.contact_force_torque``): ``"none"`` (default), or LAMMPS's
        engine models, which are not contact mechanics of smooth spheres: twist ``"marshall"`` (coefficients
        from the tangential law and the contact radius) or ``"sds"``, rolling ``"sds"`` (``laws.twist``,
        ``laws.rolling``)
    k_twist, gamma_twist, mu_twist : twist="sds" only (then required): spring [N m/rad], dashpot
        [N m s/rad] and slider [m] (the limit is mu_twist N), LAMMPS's ``twisting sds`` coefficients
    k_roll, gamma_roll, mu_roll : rolling="sds" only (then required): spring [N/m], dashpot [N s/m] and
        slider [-] (the limit of the pseudo-force is mu_roll N, of the torque mu_roll R* N), LAMMPS's
        ``rolling sds`` coefficients
    model : a named model that sets the laws and the time step: ``MODELS`` (``"thornton2001"``: Thornton
        et al. 2001, thornton + md). Its laws are not to be given as well.

    A Scene is immutable (its attributes cannot be assigned: the parameter row, the calibrations and the
    constants cached by the impact functions are derived from them once): ``scene.replace(mu=0.1)`` returns
    a new Scene with the same arguments but the ones given, built and checked like a new one. ``params`` is
    a copy of the parameter row (float64[N_PARAMS], ``laws.slots``), for the kernels; writing to it changes
    no Scene.
    """

    #: the head-on impact under a normal law alone (``laws.normal_impact``), for the laws' calibrations
    integrate_normal = staticmethod(normal_impact)

    #: the constructor's arguments, which ``replace`` accepts
    ARGUMENTS = ("sphere", "body2", "mu", "normal", "tangential", "e_n", "v_ref", "mdr_springs", "mdr_max_radius",
                 "mdr_profile", "traction_yield", "model", "twist", "rolling", "k_twist", "gamma_twist", "mu_twist",
                 "k_roll", "gamma_roll", "mu_roll")

    def __init__(self, sphere: Sphere, body2: Sphere | Wall, mu: float = 0.3, normal: str = table.DEFAULTS["normal"],
                 tangential: str = table.DEFAULTS["tangential"], e_n: float | None = None, v_ref: float | None = None,
                 mdr_springs: int | None = None, mdr_max_radius: float | None = None,
                 mdr_profile: str = "truncated", traction_yield: bool | str = False, model: str | None = None,
                 twist: str = table.DEFAULTS["twist"], rolling: str = table.DEFAULTS["rolling"],
                 k_twist: float | None = None, gamma_twist: float | None = None, mu_twist: float | None = None,
                 k_roll: float | None = None, gamma_roll: float | None = None, mu_roll: float | None = None):
        self._args = dict(sphere=sphere, body2=body2, mu=mu, normal=normal, tangential=tangential, e_n=e_n,
                          v_ref=v_ref, mdr_springs=mdr_springs, mdr_max_radius=mdr_max_radius,
                          mdr_profile=mdr_profile, traction_yield=traction_yield, model=model, twist=twist,
                          rolling=rolling, k_twist=k_twist, gamma_twist=gamma_twist, mu_twist=mu_twist,
                          k_roll=k_roll, gamma_roll=gamma_roll, mu_roll=mu_roll)
        if not isinstance(sphere, Sphere):
            raise InputError("sphere must be a Sphere")
        if not isinstance(body2, (Sphere, Wall)):
            raise InputError("body2 must be a Wall or a Sphere")
        self.sphere = sphere
        self.body2 = body2
        self.mu = check_finite("mu (friction coefficient)", mu, lo=0.0, hi=MAX_MU, lo_open=False)
        self.model = model
        self.steps_per_contact = None       # the model's time-step practice (None: the integrator default)
        if model is not None:
            if model not in MODELS:
                raise InputError(f"model {model!r} is unknown; choose one of: {', '.join(MODELS)}")
            spec = MODELS[model]
            yields = any(b.material.p_y is not None for b in (sphere, body2))
            model_normal = spec["normal"] if yields or e_n is not None else spec["normal_elastic"]
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
        self.e_n = None if e_n is None else check_finite("e_n (normal restitution)", e_n, lo=0.0, hi=1.0,
                                                                    lo_open=False)
        self.v_ref = None if v_ref is None else check_finite("v_ref (reference normal speed, m/s)", v_ref, lo=0.0)
        self.traction_yield = _traction_yield(traction_yield)
        self.mdr_profile = mdr_profile
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
        self.mdr_springs = 0
        self._params = p
        for law in self.laws:
            law.configure(self, p)
        # history slots after N_HIST_BASE (the laws with cells)
        self.tangential_extra_slots = table.planar_extra(self.tangential_id, self.mdr_springs)
        self._frozen = True

    def _refuse_options(self):
        """A law option given to laws that do not take it cannot act: refused."""
        defaults = inspect.signature(Scene).parameters
        taken = sum((law.OPTIONS for law in self.laws), ())
        for option in table.options():
            if option == "v_ref" and isinstance(self._args["v_ref"], _ReferenceSpeed):
                continue
            if option not in taken and self._args[option] != defaults[option].default:
                takers = [f"{m.NAME} ({m.FAMILY})" for laws in table.FAMILIES.values() for m in laws
                          if option in m.OPTIONS]
                raise InputError(f"{option} applies to the laws {', '.join(takers)} only "
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
        """``replace(tangential=..., **changes)`` for another tangential law: the settings that only the mdr
        laws take (mdr_springs, mdr_max_radius, mdr_profile) go back to their defaults where the new law does
        not take them (a cell count of one law is not one of another); every other setting is kept."""
        defaults = inspect.signature(Scene).parameters
        new = _law(tangential, "tangential")
        others = sum((law.OPTIONS for law in self.laws if law is not self.tangential_law), new.OPTIONS)
        drop = [] if tangential == self.tangential else [
            k for k in self.tangential_law.OPTIONS if k not in others or k in ("mdr_springs", "mdr_max_radius")
            if not (k == "v_ref" and isinstance(self._args["v_ref"], _ReferenceSpeed))]
        reset = {k: defaults[k].default for k in drop if k not in changes}
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


def _material_dict(m) -> dict:
    if m.is_rigid:
        return {"rigid": True, "rho": m.rho}
    d = {"E": m.E, "nu": m.nu, "rho": m.rho}
    if m.p_y is not None:
        d["p_y"] = m.p_y
    return d
