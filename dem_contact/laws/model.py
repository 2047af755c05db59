"""A contact model bound to a pair of bodies: the laws, their parameter row, and its calibration.

``Scene`` validates everything once and computes the effective properties and the parameter row that
the kernels read (see ``laws.slots``). A Scene is immutable: ``scene.replace(mu=0.1)`` builds the scene
with one setting changed, validated and calibrated again like a new one.
"""
from __future__ import annotations

import functools
import inspect
import math
from types import MappingProxyType

import numpy as np

from ..errors import InputError
from ..materials import Sphere, Wall, check_finite, pair_properties
from . import closed_forms as cf
from . import contact as C
from .normal_impact import normal_impact
from .slots import (N_HIST_BASE, N_PARAMS, P_DELTA_Y, P_DX, P_ESTAR, P_F_Y, P_GAMMA, P_GSTAR, P_KN, P_KT,
                    P_MDR_PROFILE, P_MSTAR, P_MU, P_NORMAL_LAW, P_NSPRING, P_PY, P_RSTAR, P_TANGENTIAL_LAW,
                    P_TY_DMU, P_TY_NODES, P_TY_TABLE)

NORMAL_LAWS = MappingProxyType({
    "hertz": C.HERTZ,
    "thornton": C.THORNTON,
    "hertz_damped": C.HERTZ_DAMPED,
    "linear": C.LINEAR_NORMAL,
})
TANGENTIAL_LAWS = MappingProxyType({
    "md": C.MD,
    "md_rescale": C.MD_RESCALE,
    "mindlin_total": C.MINDLIN_TOTAL,
    "mindlin_incremental": C.MINDLIN_INCREMENTAL,
    "mindlin_rescale": C.MINDLIN_RESCALE,
    "linear": C.LINEAR_TANGENTIAL,
    "ddm": C.DDM,
    "mdr": C.MDR,
    "mdr_adaptive": C.MDR_ADAPTIVE,
})

NORMAL_LAW_SOURCES = MappingProxyType({
    "hertz": "Hertz (Johnson 1985), elastic",
    "thornton": "Thornton (1997) elastic-perfectly plastic, limiting contact pressure p_y",
    "hertz_damped": "Hertz + dashpot 2 gamma sqrt(m* k_n) d(delta)/dt, force clamped at 0, gamma calibrated for e_n",
    "linear": "linear spring-dashpot, stiffness matched to the Hertz contact time at v_ref, closed-form e_n",
})
TANGENTIAL_LAW_SOURCES = MappingProxyType({
    "md": "Thornton & Yin (1991) incremental Mindlin-Deresiewicz",
    "md_rescale": "md with a_new/a_old scaling when the contact shrinks (Thornton, Cummins & Cleary 2013)",
    "mindlin_total": "total-displacement no-slip Hertz-Mindlin (LIGGGHTS tangential history, EDEM, LAMMPS mindlin)",
    "mindlin_incremental": "incremental Hertz-Mindlin force (Yade, LAMMPS mindlin/force)",
    "mindlin_rescale": "incremental Hertz-Mindlin with a/a_old rescaling (LAMMPS mindlin_rescale/force)",
    "linear": "Cundall-Strack linear spring, k_t = kappa k_n(linear, matched at v_ref)",
    "ddm": "Di Renzo & Di Maio (2005): total displacement, k_t = (2/3) 8 G* a",
    "mdr": "exact reference: method of dimensionality reduction (Popov & Hess), springs on a half-line",
    "mdr_adaptive": "method of dimensionality reduction with few cells on a grid that follows the contact",
})

#: Default number of MDR springs (cells on the half-line x >= 0): with MDR_STEPS_PER_CONTACT steps per
#: contact, f/mu of an oblique impact is within 1e-5 of the converged MDR value (4 significant digits).
MDR_SPRINGS = 200
#: Steps per contact for 4-digit MDR results (see MDR_SPRINGS).
MDR_STEPS_PER_CONTACT = 1000
#: Cells of the mdr_adaptive law (even): its history row holds the cell width and these displacements.
MDR_ADAPTIVE_CELLS = 16
#: The MDR grid covers this multiple of the largest contact radius expected at v_ref.
MDR_RADIUS_MARGIN = 1.05

#: Coulomb-limit profiles of the MDR laws during plastic loading (``Scene(mdr_profile=...)``, laws.mdr).
MDR_PROFILES = MappingProxyType({"truncated": 0.0, "scaled": 1.0})

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

#: Steps per Hertz contact time used to calibrate the damped-Hertz dashpot.
CALIBRATION_STEPS = 4000
#: Hertz contact time of the unit problem E* = R* = m* = V = 1.
UNIT_HERTZ_TC = cf.hertz_contact_time(1.0, 1.0, 1.0, 1.0)
#: ``hertz_damped`` with e_n = 0 (and any e_n below this) uses the dashpot calibrated for this e_n: a dashpot
#: reaches e_n = 0 only in the limit gamma -> inf, so the rebound speed is at most 1e-4 of the impact speed.
HERTZ_DAMPED_EN_FLOOR = 1e-4


def _law(name: str, table: dict, what: str) -> int:
    if name not in table:
        raise InputError(f"{what} law {name!r} is unknown; choose one of: {', '.join(table)}")
    return table[name]


def _unit_damped_impact(gamma: float):
    """(final normal velocity, contact time, max overlap, status) of a normal damped-Hertz impact of the
    unit problem (E* = R* = m* = V = 1) at CALIBRATION_STEPS steps per Hertz contact time: e_n and
    t_c / t_c,Hertz depend on gamma alone."""
    p = np.zeros(N_PARAMS)
    p[P_ESTAR] = p[P_RSTAR] = p[P_MSTAR] = 1.0
    p[P_GAMMA] = gamma
    return normal_impact(C.HERTZ_DAMPED, p, np.zeros(N_HIST_BASE), 1.0, 1.0, UNIT_HERTZ_TC / CALIBRATION_STEPS,
                         100 * CALIBRATION_STEPS)


@functools.lru_cache(maxsize=256)
def hertz_damping_for_restitution(e_n: float) -> float:
    """Dashpot ratio gamma of ``hertz_damped`` that gives restitution ``e_n`` (0 < e_n <= 1), found once
    by root finding on simulated normal impacts of the unit problem."""
    from scipy.optimize import brentq

    if e_n >= 1.0:
        return 0.0

    def restitution(gamma):
        vn, _, _, status = _unit_damped_impact(gamma)
        if status != 0:
            raise InputError(f"e_n = {e_n:g} is too low to be reached by the hertz_damped law")
        return -vn

    if restitution(0.0) <= e_n:
        return 0.0      # the undamped law already gives e_n within the calibration's resolution
    hi = 1.0
    while restitution(hi) > e_n:
        hi *= 2.0
        if hi > 1e3:
            raise InputError(f"e_n = {e_n:g} is too low to be reached by the hertz_damped law")
    return brentq(lambda g: restitution(g) - e_n, 0.0, hi, xtol=1e-13, rtol=1e-12)


@functools.lru_cache(maxsize=256)
def hertz_damped_time_ratio(gamma: float) -> float:
    """Contact time of the damped-Hertz law over the elastic Hertz contact time (gamma alone)."""
    if gamma == 0.0:
        return 1.0
    return min(1.0, _unit_damped_impact(gamma)[1] / UNIT_HERTZ_TC)


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
        speed expected (sets the extent of the springs)
    mdr_springs : number of MDR springs (cells on the half-line), ``mdr`` only (default MDR_SPRINGS)
    mdr_max_radius : largest contact radius the MDR springs must cover [m] (``mdr`` only; default: the
        maximum contact radius of a normal impact at v_ref, times MDR_RADIUS_MARGIN)
    mdr_profile : Coulomb limit of the MDR laws (``mdr``, ``mdr_adaptive``) during Thornton's plastic
        loading: "truncated" (default), mu times the line load of the Hertz pressure truncated at p_y,
        the distribution Thornton's force law is built on; "scaled", a Hertz-shaped limit scaled to mu N
        (see ``laws.mdr``). Both are the same for elastic laws and for Thornton unloading.
    traction_yield : ``thornton`` only: the limiting pressure falls with the traction the contact carries,
        p_y g(|T|/N), g = first-yield pressure of a Hertz contact with sliding traction over that without
        (Hamilton 1983 stresses, von Mises; ``laws.traction_yield``), tabulated for the Poisson ratio of
        the yielding body. Off by default.
    model : a named model that sets the laws and the time step: ``MODELS`` (``"thornton2001"``: Thornton
        et al. 2001, thornton + md). Its laws are not to be given as well.

    A Scene is immutable (its attributes cannot be assigned: the parameter row, the calibrations and the
    constants cached by the impact functions are derived from them once): ``scene.replace(mu=0.1)`` returns
    a new Scene with the same arguments but the ones given, built and checked like a new one. ``params`` is
    a copy of the parameter row (float64[N_PARAMS], ``laws.slots``), for the kernels; writing to it changes
    no Scene.
    """

    #: the constructor's arguments, which ``replace`` accepts
    ARGUMENTS = ("sphere", "body2", "mu", "normal", "tangential", "e_n", "v_ref", "mdr_springs", "mdr_max_radius",
                 "mdr_profile", "traction_yield", "model")

    def __init__(self, sphere: Sphere, body2: Sphere | Wall, mu: float = 0.3, normal: str = "hertz",
                 tangential: str = "mdr_adaptive", e_n: float | None = None, v_ref: float | None = None,
                 mdr_springs: int | None = None, mdr_max_radius: float | None = None,
                 mdr_profile: str = "truncated", traction_yield: bool = False, model: str | None = None):
        self._args = dict(sphere=sphere, body2=body2, mu=mu, normal=normal, tangential=tangential, e_n=e_n,
                          v_ref=v_ref, mdr_springs=mdr_springs, mdr_max_radius=mdr_max_radius,
                          mdr_profile=mdr_profile, traction_yield=traction_yield, model=model)
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
            if normal not in ("hertz", model_normal) or tangential not in ("mdr_adaptive", spec["tangential"]):
                raise InputError(f"model={model!r} sets the laws ({model_normal} + {spec['tangential']} here): "
                                 f"give no other normal or tangential law with it")
            normal, tangential = model_normal, spec["tangential"]
            self.steps_per_contact = spec["steps_per_contact"]
        self.normal = normal
        self.tangential = tangential
        self.normal_id = _law(normal, NORMAL_LAWS, "normal")
        self.tangential_id = _law(tangential, TANGENTIAL_LAWS, "tangential")
        self.e_n = None if e_n is None else check_finite("e_n (normal restitution)", e_n, lo=0.0, hi=1.0,
                                                                    lo_open=False)
        self.v_ref = None if v_ref is None else check_finite("v_ref (reference normal speed, m/s)", v_ref, lo=0.0)
        self.pair = pr = pair_properties(sphere, body2)
        p = np.zeros(N_PARAMS)
        p[P_ESTAR] = pr.E_star
        p[P_GSTAR] = pr.G_star
        p[P_RSTAR] = pr.R_star
        p[P_MSTAR] = pr.m_star
        p[P_MU] = self.mu
        p[P_NORMAL_LAW] = self.normal_id + 1           # the laws the row is built for (checked entries)
        p[P_TANGENTIAL_LAW] = self.tangential_id + 1
        self.p_y = None
        if self.e_n is not None and normal == "hertz":
            raise InputError("e_n cannot act on the hertz law (elastic, e_n = 1): use hertz_damped or linear for a "
                             "restitution, or thornton to calibrate its yield pressure from e_n")
        if normal == "thornton":
            if pr.p_y is not None:
                if self.e_n is not None:
                    raise InputError("the thornton law takes p_y from the material's yield, so e_n cannot act: give "
                                     "either a yield of a material or e_n (with v_ref) to calibrate p_y, not both")
                self.p_y = pr.p_y
                self.p_y_source = "material"
            elif self.e_n is not None:
                e_min = cf.thornton_restitution_ratio(cf.THORNTON_MIN_VELOCITY_RATIO)
                if not e_min <= self.e_n < 1.0:
                    raise InputError(f"e_n = {self.e_n:g} cannot be calibrated with the thornton law: valid range "
                                     f"[{e_min:.3g}, 1)")
                v = self._need_v_ref("the thornton calibration from e_n")
                self.p_y = cf.thornton_yield_pressure_for_restitution(pr.E_star, pr.R_star, pr.m_star, self.e_n, v)
                self.p_y_source = f"calibrated for e_n = {self.e_n:g} at {v:g} m/s"
            else:
                raise InputError("the thornton law needs a yield: give yield_pressure or yield_stress of a "
                                 "material, or e_n (with v_ref) to calibrate p_y")
            # F_y ~ p_y^3 R*^2 / E*^2 must stay an ordinary number
            py_max = (1e100 * 6.0 * pr.E_star**2 / (math.pi**3 * pr.R_star**2)) ** (1.0 / 3.0)
            py_min = (1e-100 * 6.0 * pr.E_star**2 / (math.pi**3 * pr.R_star**2)) ** (1.0 / 3.0)
            if not py_min <= self.p_y <= py_max:
                raise InputError(f"p_y = {self.p_y:g} Pa (limiting contact pressure of the thornton law) is outside "
                                 f"[{py_min:.3g}, {py_max:.3g}] Pa for this pair, where its yield force is an "
                                 f"ordinary number (a p_y that is never reached is the hertz law)")
            p[P_PY] = self.p_y
            p[P_DELTA_Y] = cf.thornton_yield_overlap(pr.E_star, pr.R_star, self.p_y)
            p[P_F_Y] = cf.thornton_yield_force(pr.E_star, pr.R_star, self.p_y)
        if normal == "hertz_damped":
            # e_n = 0 is the gamma -> inf limit of the dashpot (rebound speed ~ gamma^-2, contact time -> 0),
            # reached at no finite gamma: the dashpot of e_n = HERTZ_DAMPED_EN_FLOOR stands for it.
            e_used = 1.0 if self.e_n is None else max(self.e_n, HERTZ_DAMPED_EN_FLOOR)
            p[P_GAMMA] = hertz_damping_for_restitution(e_used)
        if normal == "linear":
            p[P_GAMMA] = cf.linear_damping_ratio(1.0 if self.e_n is None else self.e_n)
            if p[P_GAMMA] >= 1.0:
                raise InputError("e_n = 0 cannot be reached by the linear law: valid range (0, 1]")
        if normal == "linear" or tangential == "linear":
            v = self._need_v_ref(f"the linear {'normal' if normal == 'linear' else 'tangential'} law")
            p[P_KN] = pr.m_star * (math.pi / cf.hertz_contact_time(pr.E_star, pr.R_star, pr.m_star, v)) ** 2
            p[P_KT] = pr.kappa * p[P_KN]
        if mdr_profile not in MDR_PROFILES:
            raise InputError(f"mdr_profile = {mdr_profile!r} is unknown; choose one of: {', '.join(MDR_PROFILES)}")
        if mdr_profile != "truncated" and tangential not in ("mdr", "mdr_adaptive"):
            raise InputError("mdr_profile applies to the mdr and mdr_adaptive tangential laws only")
        self.mdr_profile = mdr_profile
        p[P_MDR_PROFILE] = MDR_PROFILES[mdr_profile]
        self.traction_yield = bool(traction_yield)
        if self.traction_yield:
            if normal != "thornton":
                raise InputError("traction_yield applies to the thornton normal law only")
            self._set_traction_yield(p)
        self._params = p
        self.mdr_springs = 0
        self.tangential_extra_slots = 0     # history slots after N_HIST_BASE (mdr laws)
        if tangential == "mdr":
            self._set_mdr_grid(mdr_springs, mdr_max_radius)
        elif tangential == "mdr_adaptive":
            n = MDR_ADAPTIVE_CELLS if mdr_springs is None else mdr_springs
            if isinstance(n, bool) or int(n) != n or n % 2 or not 2 <= n <= 1024:
                raise InputError(f"mdr_springs = {n!r} must be an even integer in [2, 1024] for mdr_adaptive")
            self.mdr_springs = int(n)
            self.tangential_extra_slots = int(n) + 1        # the cell width, then the cells
            self._params[P_NSPRING] = int(n)
            if mdr_max_radius is not None:
                raise InputError("mdr_max_radius applies to the mdr tangential law only")
        elif mdr_springs is not None or mdr_max_radius is not None:
            raise InputError("mdr_springs and mdr_max_radius apply to the mdr and mdr_adaptive laws only")
        self._frozen = True

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
        not take them (a cell count of mdr is not one of mdr_adaptive); every other setting is kept."""
        defaults = inspect.signature(Scene).parameters
        drop = [] if tangential == self.tangential else (
            ["mdr_springs", "mdr_max_radius"] + ([] if tangential in ("mdr", "mdr_adaptive") else ["mdr_profile"]))
        reset = {k: defaults[k].default for k in drop if k not in changes}
        return self.replace(tangential=tangential, **{**reset, **changes})

    @property
    def arguments(self) -> dict:
        """The constructor's arguments of this Scene (a copy)."""
        return dict(self._args)

    @property
    def params(self) -> np.ndarray:
        """The parameter row the kernels read, float64[N_PARAMS] (``laws.slots``): a copy (the Scene does
        not change)."""
        return self._params.copy()

    def _set_traction_yield(self, p):
        """Table of p0_first(mu_eff) / p0_first(0) on [0, mu] in the parameter row (none for mu = 0: the
        contact then carries no traction and the law is Thornton's)."""
        from .traction_yield import TABLE_NODES, first_yield_ratio_table

        pr = self.pair
        mats = [b.material for b in (self.sphere, self.body2) if not b.material.is_rigid]
        yielding = [m for m in mats if m.p_y is not None and m.p_y == pr.p_y]
        self.traction_yield_nu = (yielding or mats)[0].nu
        if self.mu == 0.0:
            return
        nu = min(max(self.traction_yield_nu, 0.0), 0.5)
        table = first_yield_ratio_table(nu, self.mu)
        p[P_TY_NODES] = TABLE_NODES
        p[P_TY_DMU] = self.mu / (TABLE_NODES - 1)
        p[P_TY_TABLE:P_TY_TABLE + TABLE_NODES] = table

    def _set_mdr_grid(self, springs, max_radius):
        n = MDR_SPRINGS if springs is None else springs
        if isinstance(n, bool) or int(n) != n or not 2 <= n <= 10**6:
            raise InputError(f"mdr_springs = {n!r} must be an integer in [2, 1e6]")
        n = int(n)
        if max_radius is not None:
            r = check_finite("mdr_max_radius (largest contact radius, m)", max_radius, lo=0.0)
        elif self.v_ref is not None:
            r = MDR_RADIUS_MARGIN * self.max_contact_radius(self.v_ref)
        else:
            raise InputError("the mdr tangential law needs v_ref (largest normal speed expected, m/s, > 0) or "
                             "mdr_max_radius (largest contact radius, m) to place its springs")
        self.mdr_springs = n
        self.tangential_extra_slots = n
        self.mdr_max_radius = r
        self._params[P_NSPRING] = n
        self._params[P_DX] = r / n

    def max_contact_radius(self, vn: float) -> float:
        """Largest contact radius sqrt(R* delta_max) [m] of a head-on impact at normal speed vn [m/s],
        from a simulated normal impact with this scene's normal law."""
        p = self.params
        p[P_MU] = 0.0
        pr = self.pair
        dt = cf.hertz_contact_time(pr.E_star, pr.R_star, pr.m_star, vn) / 2000.0
        dmax = normal_impact(self.normal_id, p, np.zeros(N_HIST_BASE), vn, 1.0 / pr.m_star, dt, 200000)[2]
        return math.sqrt(pr.R_star * dmax)

    def _need_v_ref(self, what: str) -> float:
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
        """Contact duration at normal speed vn [s] that sets the time step: Hertz; the damped-Hertz contact
        (shorter, by a factor that depends on gamma only); or the linear spring's closed form."""
        pr = self.pair
        if self.normal == "linear":
            return cf.linear_contact_time(self._params[P_KN], pr.m_star, self._params[P_GAMMA])
        tc = cf.hertz_contact_time(pr.E_star, pr.R_star, pr.m_star, vn)
        if self.normal == "hertz_damped":
            tc *= hertz_damped_time_ratio(float(self._params[P_GAMMA]))
        return tc

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
        if self.normal == "thornton":
            d.update(p_y=self.p_y, p_y_source=self.p_y_source, delta_y=p[P_DELTA_Y], F_y=p[P_F_Y])
        if self.normal in ("hertz_damped", "linear"):
            d.update(e_n_target=1.0 if self.e_n is None else self.e_n, gamma=p[P_GAMMA])
            if self.normal == "hertz_damped" and self.e_n is not None and self.e_n < HERTZ_DAMPED_EN_FLOOR:
                d.update(e_n_dashpot=HERTZ_DAMPED_EN_FLOOR)
        if p[P_KN] > 0:
            d.update(k_n_linear=p[P_KN], k_t_linear=p[P_KT], v_ref=self.v_ref)
        if self.model is not None:
            d.update(model_source=MODELS[self.model]["source"], steps_per_contact_model=self.steps_per_contact)
        if self.traction_yield:
            d.update(traction_yield=True, traction_yield_nu=self.traction_yield_nu)
        if self.tangential in ("mdr", "mdr_adaptive"):
            d.update(mdr_profile=self.mdr_profile)
        if self.tangential == "mdr":
            d.update(mdr_springs=self.mdr_springs, mdr_max_radius=self.mdr_max_radius, mdr_dx=p[P_DX])
        return d


def _material_dict(m) -> dict:
    if m.is_rigid:
        return {"rigid": True, "rho": m.rho}
    d = {"E": m.E, "nu": m.nu, "rho": m.rho}
    if m.p_y is not None:
        d["p_y"] = m.p_y
    return d
