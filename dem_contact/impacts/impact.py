"""One oblique impact: set-up, integration, and the rebound quantities of Wu, Thornton & Li (2009).

``impact(scene, vn, vt, spin)`` returns an ``ImpactResult`` with e_n, e_t, the impulse ratio f, the
dimensionless groups Theta, Psi_r, Omega_i, Omega_r (Wu, Thornton & Li 2009, eqs 2.1-2.20 and 7.1) and
the energy budget.
"""
from __future__ import annotations

import functools
import math
import warnings
import weakref
from dataclasses import MISSING, asdict, dataclass, field, fields

import numpy as np

from ..errors import InputError, NumericalError
from .integrator import (N_OUT, N_SERIES, O_COULOMB, O_DMAX, O_FMAX, O_MINWT, O_PN, O_PT, O_SLID,
                         O_STATUS, O_STEPS, O_TC, O_VN, O_VT, O_W1, O_W2, O_WN, O_WT, S_A, S_DELTA, S_N,
                         S_T, S_TANG, S_VN, S_VSLIP, SLIDE_IMPULSE_TOL, STATUS_MAX_STEPS, STATUS_NONFINITE, STATUS_OK,
                         B_INV_I1, B_INV_I2, B_INV_M, B_R1, B_R2, N_BODY, integrator_for)
from ..laws.slots import H_A
from ..laws import closed_forms as cf
from ..materials import Sphere, check_finite
from ..laws.model import Scene

#: Default time resolution: steps per elastic (Hertz) contact time at the impact's normal speed. With the
#: default law (adaptive MDR) f/mu is then within 3.5e-4 of its converged value and 7e-4 of converged MDR
#: (validation/chart); md needs about 1000 steps for 1e-3 of discretisation error.
DEFAULT_STEPS_PER_CONTACT = 50
#: Fewer steps per contact than this cannot resolve a contact: rejected.
MIN_STEPS_PER_CONTACT = 2.0
#: The contact must end within this many elastic contact times.
MAX_CONTACT_TIMES = 50.0
#: Relative tolerance (of the initial kinetic energy) above which energy counts as created.
ENERGY_CREATION_TOL = 1e-6
#: Final kinetic energy above the initial one by more than this fraction of it counts as energy gained
#: (rounding of the energies is about 1e-15 of them).
KE_ROUNDING_TOL = 1e-12
#: Energy-balance error (initial - final - work of the forces) above this fraction is warned about.
ENERGY_BALANCE_TOL = 1e-3
#: A passive normal law returns at most the normal speed it received, 0 <= e_n <= 1. An impact whose contact
#: ends while the sphere still approaches (e_n < 0: a time step too coarse for a dashpot, whose predicted force
#: turns tensile before the sphere stops) or whose e_n exceeds 1 by more than E_N_EXCESS_TOL is a numerical
#: failure (NumericalError). Up to it the impact is flagged ``energy_gained`` with a warning: the standard DEM
#: end of an elastic contact overshoots by 9e-4 at 10 steps per contact and by 3.5e-6 at 50.
E_N_EXCESS_TOL = 1e-3
#: The e_n of a calibrated law (the dashpot of hertz_damped and linear for their e_n, thornton's p_y for its
#: e_n at the calibration speed) is warned about when it misses the target by more than CALIBRATION_RTOL of
#: the target, and by more than CALIBRATION_ATOL (the hertz_damped dashpot of e_n = 0 is that of 1e-4): the
#: calibrations hold as dt -> 0 (hertz_damped: 0.01 gives 0.0104 at 50 steps per contact).
CALIBRATION_RTOL = 0.01
CALIBRATION_ATOL = 1e-4
#: Range of validity of the contact laws: Hertz and Mindlin-Deresiewicz theory assume a contact radius
#: small against the radius of curvature (Johnson 1985, section 4.2); beyond a = 0.2 R* (overlap 0.04 R*) the
#: result is flagged.
VALIDITY_A_OVER_R = 0.2
#: Work budget: at most this many steps per contact time (about 10 s per impact with the mdr reference).
MAX_STEPS_PER_CONTACT = 1e7
#: Memory budget of a returned time series [bytes].
MAX_SERIES_BYTES = 2**30
#: Every SI magnitude of an impact (peak overlap, force, contact time, energy) must lie in this range.
SCALE_RANGE = (1e-100, 1e100)

SCHEMES = ("located", "standard")

# build_result unpacks the integrator's output row in this order
assert (O_VN, O_VT, O_W1, O_W2, O_PN, O_PT, O_TC, O_DMAX, O_FMAX, O_SLID, O_STEPS, O_WN, O_WT, O_COULOMB, O_STATUS,
        O_MINWT) == tuple(range(N_OUT))


@dataclass(slots=True)
class EnergyBudget:
    """Energy of the impact [J]. friction and normal are the works absorbed by the tangential and normal
    forces along the path (trapezoid rule); error = initial - final - friction - normal."""

    initial: float
    final: float
    friction: float
    normal: float
    error: float


@dataclass(slots=True)     # (35 fields: an instance dict would cost more than the rest of the result)
class ImpactResult:
    """Outcome of one impact. Velocities in m/s, spins in rad/s, times in s, lengths in m, forces in N.

    Sign conventions (Wu, Thornton & Li 2009, section 2): vn > 0 towards the wall; v_t = V_t + R omega; e_t
    is the ratio of the centre velocities, V_tr / V_ti (eq. 2.1b); Theta and Psi_r use the contact-patch
    velocity (eq. 7.1: Theta = 2 v_ti / ((1 + e_n) mu V_ni), where the rebound models read f/mu).
    rebound_angle_deg is the angle of the rebound velocity of the centre from the normal, positive in the direction of the
    incident tangential velocity; patch_rebound_angle_deg the same for the contact-patch velocity.

    persistent_sliding: |T| >= (1 - SLIDE_TOL) mu N at every step until the last SLIDE_IMPULSE_TOL of the
    normal impulse (``integrator.SLIDE_TOL`` = 1e-3, ``SLIDE_IMPULSE_TOL`` = 1e-4), the criterion of the
    direct critical angle; sliding_fraction: the fraction of the normal impulse delivered before the first
    step below (1 - SLIDE_TOL) mu N (1 when there is none).

    energy_created: the tangential law did negative work at some time (a passive law cannot);
    energy_gained: the final kinetic energy exceeds the initial one beyond rounding (KE_ROUNDING_TOL),
    whatever the cause (the works of the normal and tangential forces are in ``energy``). Both are also
    in ``warnings``, with an impulse ratio |f| > mu, an energy-balance error above ENERGY_BALANCE_TOL, a
    contact beyond the laws' range of validity (a > VALIDITY_A_OVER_R R*) and an e_n that misses the target
    of its calibration (CALIBRATION_RTOL). An e_n outside [0, 1 + E_N_EXCESS_TOL] is never returned: the
    impact raises NumericalError. NaN marks what is undefined: e_t at vt = 0 (|vt| < 1e-100 vn); f/mu,
    Theta, Psi_r, Omega_i, Omega_r at mu = 0 (``to_dict`` gives None and the reason).
    """

    vn_i: float
    vt_i: float
    omega_i: float
    vn_r: float
    vt_r: float
    omega_r: float
    theta_i_deg: float
    e_n: float
    e_t: float
    f: float
    f_over_mu: float
    Theta: float
    Psi_r: float
    Omega_i: float
    Omega_r: float
    rebound_angle_deg: float
    patch_rebound_angle_deg: float
    normal_impulse: float
    tangential_impulse: float
    contact_time: float
    max_overlap: float
    max_force: float
    persistent_sliding: bool
    sliding_fraction: float
    steps: int
    dt: float
    energy: EnergyBudget
    energy_created: bool
    coulomb_violation: float
    warnings: list          # (built whole by ``build_result``: no defaults but for the fields added last)
    model: dict
    settings: dict
    omega2_r: float = 0.0
    series: dict | None = None
    energy_gained: bool = False

    def to_dict(self, series: bool = False) -> dict:
        """JSON-ready dict: NaN and inf become None, and ``null_values`` gives the reason for each (only
        when there is one)."""
        d = asdict(self)
        if not series:
            d.pop("series")
        elif self.series is not None:
            d["series"] = {k: v.tolist() for k, v in self.series.items()}
        why = {k: _undefined_reason(k, self) for k, v in d.items()
               if isinstance(v, (float, np.floating)) and not math.isfinite(v)}
        d = _json_safe(d)
        if why:
            d["null_values"] = why
        return d


#: The dimensionless quantities that divide by mu (undefined at mu = 0).
_PER_MU = ("f_over_mu", "f_across_over_mu", "Theta", "Theta_across", "Psi_r", "Psi_r_across", "Omega_i",
           "Omega_r", "Omega_across_i", "Omega_across_r")


#: The fields of ImpactResult that every impact result reports after its own (``with_outcome``): the step
#: count, time step, energy budget and its checks, warnings, model, settings, time series.
OUTCOME_FIELDS = ("steps", "dt", "energy", "energy_created", "coulomb_violation", "warnings", "model", "settings",
                  "series", "energy_gained")


def with_outcome(cls):
    """Class decorator: the dataclass of ``cls`` (its own fields annotated) with the OUTCOME_FIELDS of
    ImpactResult after its own, declared once there (type and default)."""
    own = dict(cls.__dict__.get("__annotations__", {}))
    for f in fields(ImpactResult):
        if f.name in OUTCOME_FIELDS:
            own[f.name] = f.type
            if f.default_factory is not MISSING:
                setattr(cls, f.name, field(default_factory=f.default_factory))
            elif f.default is not MISSING:
                setattr(cls, f.name, f.default)
    cls.__annotations__ = own
    return dataclass(cls)


def _undefined_reason(key: str, r) -> str:
    """Why quantity ``key`` of result ``r`` is undefined (NaN)."""
    if key in _PER_MU and r.model.get("mu", 1.0) == 0.0:
        return "undefined at mu = 0 (the quantity is divided by mu)"
    if key == "e_t":
        return "undefined: no incident tangential velocity of the centre (e_t = vt_r / vt)"
    return "not a finite number"


def _json_safe(x):
    if isinstance(x, dict):
        return {k: _json_safe(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_json_safe(v) for v in x]
    if isinstance(x, (float, np.floating)):
        x = float(x)
        return x if math.isfinite(x) else None
    if isinstance(x, np.integer):
        return int(x)
    if isinstance(x, np.bool_):
        return bool(x)
    return x


def time_step(scene: Scene, vn: float, steps_per_contact: float | None = None, dt: float | None = None):
    """Validated time step [s] and the steps per contact it gives (default: the scene's model practice,
    ``Scene.steps_per_contact``, else DEFAULT_STEPS_PER_CONTACT; at most MAX_STEPS_PER_CONTACT)."""
    tc = scene.contact_time(vn)
    if dt is not None and steps_per_contact is not None:
        raise InputError("give either dt or steps_per_contact, not both")
    if dt is not None:
        dt = check_finite("dt (time step, s)", dt, lo=0.0)
        spc = tc / dt
        if spc < MIN_STEPS_PER_CONTACT:
            raise InputError(f"dt = {dt:g} s cannot resolve the contact: it must be <= t_c / "
                             f"{MIN_STEPS_PER_CONTACT:g} = {tc / MIN_STEPS_PER_CONTACT:g} s (t_c = {tc:g} s)")
        if not spc <= MAX_STEPS_PER_CONTACT:
            raise InputError(f"dt = {dt:g} s asks for {spc:.3g} steps per contact time (t_c = {tc:g} s); the limit "
                             f"is {MAX_STEPS_PER_CONTACT:g}: dt must be >= {tc / MAX_STEPS_PER_CONTACT:.3g} s")
        return dt, spc
    spc = default_steps_per_contact(scene) if steps_per_contact is None else check_steps_per_contact(steps_per_contact)
    return tc / spc, spc


def max_steps(spc: float) -> int:
    """Step limit of an impact at ``spc`` steps per contact time (MAX_CONTACT_TIMES contact times)."""
    return int(math.ceil(MAX_CONTACT_TIMES * spc)) + 10


def check_steps_per_contact(steps_per_contact) -> float:
    return check_finite("steps_per_contact", steps_per_contact, lo=MIN_STEPS_PER_CONTACT, hi=MAX_STEPS_PER_CONTACT,
                        lo_open=False)


def default_steps_per_contact(scene: Scene) -> float:
    """The scene's model practice, ``Scene.steps_per_contact``, else DEFAULT_STEPS_PER_CONTACT."""
    return check_steps_per_contact(getattr(scene, "steps_per_contact", None) or DEFAULT_STEPS_PER_CONTACT)


def check_incident(vn, vt, spin):
    vn = check_finite("vn (normal impact speed towards the wall, m/s)", vn, lo=0.0)
    vt = check_finite("vt (tangential velocity, m/s)", vt)
    spin = check_finite("spin (initial angular velocity, rad/s)", spin)
    return vn, vt, spin


def speed_range(scene: Scene) -> tuple:
    """Normal speeds [m/s] for which the scene's elastic Hertz scales (peak overlap ~ vn^0.8, peak force
    ~ vn^1.2, contact time ~ vn^-0.2, kinetic energy ~ vn^2) all lie inside SCALE_RANGE."""
    pr = scene.pair
    return _speed_range(pr.E_star, pr.R_star, pr.m_star)


@functools.lru_cache(maxsize=64)
def _speed_range(E_star, R_star, m_star):
    lo, hi = math.log(SCALE_RANGE[0]), math.log(SCALE_RANGE[1])
    d1 = cf.hertz_max_overlap(E_star, R_star, m_star, 1.0)
    scales = [(d1, 0.8), (cf.hertz_force(E_star, R_star, d1), 1.2),
              (cf.HERTZ_TC_FACTOR * d1, -0.2), (0.5 * m_star, 2.0)]
    v_lo, v_hi = -math.inf, math.inf
    for q1, k in scales:
        a, b = (lo - math.log(q1)) / k, (hi - math.log(q1)) / k
        a, b = min(a, b), max(a, b)
        v_lo, v_hi = max(v_lo, a), min(v_hi, b)
    return math.exp(v_lo), math.exp(v_hi)


def check_scales(scene: Scene, vn: float, vt: float, spin: float, spin2: float = 0.0):
    """Raise InputError when the impact's magnitudes leave the range that double precision computes
    faithfully (a force that underflows to 0, an energy that overflows): every SI magnitude of the
    impact (peak overlap, force, contact time, kinetic energy) must lie inside SCALE_RANGE."""
    v_lo, v_hi = speed_range(scene)
    if not v_lo <= vn <= v_hi:
        raise InputError(f"vn = {vn:g} m/s is outside the range this scene can be computed in, [{v_lo:.3g}, "
                         f"{v_hi:.3g}] m/s (peak overlap, force, contact time and kinetic energy must stay within "
                         f"[{SCALE_RANGE[0]:g}, {SCALE_RANGE[1]:g}] SI)")
    m = scene.pair.m_star
    v_max = math.sqrt(2.0 * SCALE_RANGE[1] / m)
    if not abs(vt) <= v_max:
        raise InputError(f"vt = {vt:g} m/s: its kinetic energy exceeds {SCALE_RANGE[1]:g} J; |vt| must be <= "
                         f"{v_max:.3g} m/s for this sphere")
    for name, w, body in (("spin", spin, scene.sphere), ("spin2", spin2, scene.body2)):
        if isinstance(body, Sphere):
            w_max = math.sqrt(2.0 * SCALE_RANGE[1] / body.inertia)
            if not abs(w) <= w_max:
                raise InputError(f"{name} = {w:g} rad/s: its kinetic energy exceeds {SCALE_RANGE[1]:g} J; "
                                 f"|{name}| must be <= {w_max:.3g} rad/s for this sphere")


def check_series_budget(max_steps: int):
    """Refuse a time series that would need more than MAX_SERIES_BYTES of memory."""
    need = max_steps * N_SERIES * 8
    if need > MAX_SERIES_BYTES:
        raise InputError(f"series: up to {max_steps} steps x {N_SERIES} columns need {need / 2**30:.3g} GiB; the "
                         f"limit is {MAX_SERIES_BYTES / 2**30:g} GiB: lower steps_per_contact (or raise dt)")


def check_law_reach(scene: Scene, vn_max: float):
    """InputError when the tangential law's state cannot cover the contact at normal speed vn_max (its
    ``max_radius``: the extent of the mdr springs)."""
    reach = scene.tangential_law.max_radius(scene)
    if reach is None:
        return
    a = scene.max_contact_radius(vn_max)
    if a > reach:
        raise InputError(f"vn = {vn_max:g} m/s: the contact radius ({a:.4g} m) would exceed the extent of the "
                         f"{scene.tangential} springs ({reach:.4g} m, placed for v_ref = {scene.v_ref} m/s): build "
                         f"the scene with v_ref >= {vn_max:g} m/s or a larger mdr_max_radius")


def body_inertia(scene: Scene):
    """(1/m*, R1, R2, 1/I1, 1/I2) of the scene; a wall has R2 = 0 and 1/I2 = 0."""
    s1 = scene.sphere
    if isinstance(scene.body2, Sphere):
        return 1.0 / scene.pair.m_star, s1.radius, scene.body2.radius, 1.0 / s1.inertia, 1.0 / scene.body2.inertia
    return 1.0 / scene.pair.m_star, s1.radius, 0.0, 1.0 / s1.inertia, 0.0


def body_row(scene: Scene) -> np.ndarray:
    """The scene's body row of ``integrator.integrator_for``: ``body_inertia`` (slots B_*)."""
    row = np.zeros(N_BODY)
    row[B_INV_M], row[B_R1], row[B_R2], row[B_INV_I1], row[B_INV_I2] = body_inertia(scene)
    return row


def impact(scene: Scene, vn: float, vt: float = 0.0, spin: float = 0.0, *, spin2: float = 0.0,
           steps_per_contact: float | None = None, dt: float | None = None, scheme: str = "located",
           series: bool = False) -> ImpactResult:
    """Simulate one impact of the scene's sphere.

    vn: normal speed towards the wall or the other sphere, > 0 [m/s]; vt: tangential velocity of the
    centre [m/s]; spin: initial angular velocity omega [rad/s] (v_t = vt + R omega); spin2: of body 2
    (sphere-sphere only). Time step: ``steps_per_contact`` per elastic contact time (default
    DEFAULT_STEPS_PER_CONTACT) or an explicit ``dt`` [s]. scheme: "located" (separation located inside
    the last step) or "standard" (the contact ends at the first step without overlap, as in LIGGGHTS and
    LAMMPS). series: also return the time histories.

    Raises InputError for invalid input and NumericalError when the integration fails: no separation, a
    non-finite state, or an e_n that no passive normal law gives (a contact that ends while the bodies
    still approach, or e_n above 1 by more than E_N_EXCESS_TOL: a time step too coarse for the laws).
    """
    if not isinstance(scene, Scene):
        raise InputError(f"scene must be a Scene, got {type(scene).__name__}")
    if not (type(vn) is float and type(vt) is float and type(spin) is float and type(spin2) is float
            and vn > 0.0 and math.isfinite(vn + vt + spin + spin2)):
        vn, vt, spin = check_incident(vn, vt, spin)
        spin2 = check_finite("spin2 (initial angular velocity of body 2, rad/s)", spin2)
    c = scene_constants(scene)
    if spin2 != 0.0 and not c.sphere2:
        raise InputError("spin2 applies to a second sphere only: a wall does not turn")
    if scheme not in SCHEMES:
        raise InputError(f"scheme {scheme!r} is unknown; choose one of: {', '.join(SCHEMES)}")
    if not (c.v_lo <= vn <= c.v_hi and abs(vt) <= c.vt_max and abs(spin) <= c.spin_max
            and abs(spin2) <= c.spin2_max):
        check_scales(scene, vn, vt, spin, spin2)       # raises, naming the magnitude out of range
    if steps_per_contact is None and dt is None and c.spc is not None:
        spc = c.spc
        n_max = c.max_steps
        dt = scene.contact_time(vn) / spc
    else:
        dt, spc = time_step(scene, vn, steps_per_contact, dt)
        n_max = max_steps(spc)
    if c.reach is not None:
        check_law_reach(scene, vn)
    if series:
        check_series_budget(n_max)
        ser = np.zeros((n_max, N_SERIES))
    else:
        ser = _NO_SERIES
    out = np.empty(N_OUT)
    h = np.empty(c.history_size)
    try:
        c.integrate(c.params, h, c.bodies, vn, vt, spin, spin2, dt, n_max, scheme == "located", out, ser)
    except Exception as e:     # a failure inside the compiled code (a division by zero in a law, ...): no result
        raise NumericalError(f"the {scene.normal}/{scene.tangential} kernels failed ({type(e).__name__}: "
                             f"{e}) at vn = {vn:g} m/s, dt = {dt:g} s") from None
    if c.reach is not None:
        check_law_grid(scene, h, vn)
    return _build_result(c, scene, out, vn, vt, spin, spin2, dt, spc, scheme, ser, None)


def check_law_grid(scene: Scene, h, vn: float):
    """Raise NumericalError if the contact outgrew the tangential law's ``max_radius`` (the mdr springs: the
    kernel then stops the integration with a NaN force)."""
    reach = scene.tangential_law.max_radius(scene)
    if reach is not None and h[H_A] > reach:
        raise NumericalError(f"the contact radius {h[H_A]:.4g} m at vn = {vn:g} m/s exceeds the extent of the "
                             f"{scene.tangential} springs ({reach:.4g} m): raise the scene's v_ref or "
                             f"mdr_max_radius")


def derived_arrays(scene, out, vn, vt, spin, spin2, spc) -> dict:
    """Rebound quantities and check flags of many impacts at once (numpy arrays, one entry per row of
    ``out``), by the very operations ``build_result`` applies to one impact, so the numbers are identical.

    Keys: e_n, e_t, f, f_over_mu, Theta, Psi_r, Omega_i, Omega_r, theta_deg, persistent_sliding, failed
    (the impact raises NumericalError in ``build_result``), warned (it has at least one warning), and the
    flags energy_created, energy_gained."""
    inv_m, R1, R2, inv_I1, inv_I2 = body_inertia(scene)
    m = 1.0 / inv_m
    mu = scene.mu
    vn_r, vt_r, w_r, w2_r = out[:, O_VN], out[:, O_VT], out[:, O_W1], out[:, O_W2]
    PN, PT, tc, dmax, fmax = out[:, O_PN], out[:, O_PT], out[:, O_TC], out[:, O_DMAX], out[:, O_FMAX]
    WN, WT = out[:, O_WN], out[:, O_WT]
    with np.errstate(all="ignore"):
        e_n = -vn_r / vn
        v_ti = vt + R1 * spin + R2 * spin2
        v_tr = vt_r + R1 * w_r + R2 * w2_r
        f = PT / PN
        tiny_vt = np.abs(vt) < 1e-100 * vn
        e_t = np.where(tiny_vt, np.nan, vt_r / np.where(tiny_vt, 1.0, vt))
        denom = (1.0 + e_n) * mu * vn
        if mu > 0:
            fm = f / mu
            ok = denom > 0
            Theta = np.where(ok, 2.0 * v_ti / denom, np.nan)
            Psi_r = np.where(ok, 2.0 * v_tr / denom, np.nan)
            Omega_i = np.where(ok, 2.0 * R1 * spin / (5.0 * denom), np.nan)
            Omega_r = np.where(ok, 2.0 * R1 * w_r / (5.0 * denom), np.nan)
            defined = (np.isfinite(fm) & np.isfinite(Theta) & np.isfinite(Psi_r) & np.isfinite(Omega_r))
        else:
            fm = Theta = Psi_r = Omega_i = Omega_r = np.full(vn.shape, np.nan)
            defined = np.ones(vn.shape, dtype=bool)
        defined &= np.isfinite(e_n) & np.isfinite(f) & (tiny_vt | np.isfinite(e_t))
        state_ok = np.all(np.isfinite(out[:, [O_VN, O_VT, O_W1, O_W2, O_PN, O_PT, O_TC, O_DMAX, O_FMAX, O_WN,
                                               O_WT]]), axis=1)
        failed = ((out[:, O_STATUS] != STATUS_OK) | ~state_ok | ~(PN > 0.0) | ~(tc > 0.0) | ~defined
                  | ~((e_n >= 0.0) & (e_n <= 1.0 + E_N_EXCESS_TOL)))
        I1 = 0.0 if inv_I1 == 0 else 1.0 / inv_I1
        I2 = 0.0 if inv_I2 == 0 else 1.0 / inv_I2
        E0 = 0.5 * m * (vn * vn + vt * vt) + 0.5 * I1 * spin**2 + 0.5 * I2 * spin2**2
        E1 = 0.5 * m * (vn_r**2 + vt_r**2) + 0.5 * I1 * w_r**2 + 0.5 * I2 * w2_r**2
        error = E0 - E1 - WT - WN
        created = out[:, O_MINWT] < -ENERGY_CREATION_TOL * E0
        gained = (E1 - E0 > KE_ROUNDING_TOL * E0) | (e_n * e_n - 1.0 > KE_ROUNDING_TOL)
        warned = (created | gained | (out[:, O_COULOMB] > 1e-9 * np.maximum(mu * fmax, 1e-300))
                  | (np.abs(error) > ENERGY_BALANCE_TOL * E0)
                  | (np.sqrt(dmax / scene.pair.R_star) > VALIDITY_A_OVER_R) | (spc < 10))
        c = scene_constants(scene)
        if c.e_target is not None:
            warned |= c.calibration_missed(e_n, vn)
        if mu > 0:
            warned |= np.abs(f) > mu * (1.0 + 1e-9)
        theta_deg = np.degrees(np.arctan2(vt, vn))
    return dict(e_n=e_n, e_t=e_t, f=f, f_over_mu=fm, Theta=Theta, Psi_r=Psi_r, Omega_i=Omega_i, Omega_r=Omega_r,
                theta_deg=theta_deg, persistent_sliding=out[:, O_SLID] >= 1.0 - SLIDE_IMPULSE_TOL, failed=failed,
                warned=warned, energy_created=created, energy_gained=gained)


#: math.degrees(x) is x * _DEGREES (CPython multiplies by 180 / pi)
_DEGREES = 180.0 / math.pi
#: A time series of no steps (the integrator records none): shared, it cannot be written.
_NO_SERIES = np.zeros((0, N_SERIES))


class SceneConstants:
    """What every impact of one scene shares, computed once per scene (``scene_constants``): the inertia,
    the bounds of ``check_scales``, the default steps per contact, the kernel of its laws, the scene's
    ``describe()`` (shared by its results: read only)."""

    def __init__(self, scene: Scene):
        self.inertia = inv_m, _, _, inv_I1, inv_I2 = body_inertia(scene)
        self.m = 1.0 / inv_m
        self.I1 = 0.0 if inv_I1 == 0 else 1.0 / inv_I1
        self.I2 = 0.0 if inv_I2 == 0 else 1.0 / inv_I2
        self.mu = scene.mu
        self.R_star = scene.pair.R_star
        self.params = scene.params
        self.bodies = body_row(scene)
        self.integrate = integrator_for(scene.normal_id, scene.tangential_id)
        self.history_size = scene.history_size
        self.sphere2 = isinstance(scene.body2, Sphere)
        self.reach = scene.tangential_law.max_radius(scene)      # None: the tangential law covers any radius
        # the bounds of check_scales (inf: no bound)
        self.v_lo, self.v_hi = speed_range(scene)
        self.vt_max = math.sqrt(2.0 * SCALE_RANGE[1] / scene.pair.m_star)
        self.spin_max, self.spin2_max = (math.sqrt(2.0 * SCALE_RANGE[1] / b.inertia) if isinstance(b, Sphere)
                                         else math.inf for b in (scene.sphere, scene.body2))
        try:
            self.spc = default_steps_per_contact(scene)
            self.max_steps = max_steps(self.spc)
        except InputError:
            self.spc = None                         # time_step raises it at every impact
        self.model = scene.describe()
        # the e_n its calibration aims at (None: not calibrated), at speed e_target_vn (None: any speed)
        self.e_target, self.e_target_vn, self.e_target_what = calibration_target(scene)
        self.e_target_or_0 = 0.0 if self.e_target is None else self.e_target
        self.e_tol = (math.inf if self.e_target is None else
                      max(CALIBRATION_RTOL * self.e_target, CALIBRATION_ATOL))

    def calibration_missed(self, e_n, vn):
        """e_n misses the calibration's target (see CALIBRATION_RTOL) at an impact of normal speed vn (numbers
        or arrays); a calibration that holds at one speed only is judged at that speed only."""
        miss = np.abs(e_n - self.e_target) > self.e_tol
        if self.e_target_vn is not None:
            miss = miss & (np.abs(vn - self.e_target_vn) <= 1e-9 * vn)
        return miss


def calibration_target(scene: Scene) -> tuple:
    """(e_n, speed, what): the restitution that the scene's normal law was calibrated for, the normal speed
    [m/s] at which it holds (None: every speed) and a description of the calibration; (None, None, None)
    for a law that is not calibrated to an e_n."""
    target = scene.normal_law.calibration_target(scene)
    return (None, None, None) if target is None else target


_CONSTANTS = weakref.WeakKeyDictionary()


def scene_constants(scene: Scene) -> SceneConstants:
    """The scene's ``SceneConstants``, computed on first use (a Scene is not modified after construction)."""
    c = _CONSTANTS.get(scene)
    if c is None:
        c = _CONSTANTS[scene] = SceneConstants(scene)
    return c


def describe(scene: Scene) -> dict:
    """``scene.describe()``, computed once per scene (the results of its impacts share it: read only)."""
    return scene_constants(scene).model


def impact_warnings(c, scene, *, e_n, f_abs, energy, minwt, coul, fmax, dmax, spc, vn, created, gained_total,
                    gained_normal) -> list:
    """The warnings of one impact (planar or 3D) from its checks: ``c`` the scene's ``SceneConstants``; e_n, the
    impulse ratio |f|, the EnergyBudget, the least running tangential work minwt [J], the largest Coulomb
    excess coul [N], the peak force fmax [N] and overlap dmax [m], the steps per contact, the normal speed;
    the flags energy_created, and kinetic energy gained in total and in the normal motion."""
    mu = scene.mu
    E0 = energy.initial
    WN, WT = energy.normal, energy.friction
    msgs = []
    if created:
        msgs.append(f"energy created: the {scene.tangential} tangential law did negative work "
                    f"(running work reached {minwt:.3e} J)")
    works = f"work absorbed by the normal force {WN:.4g} J, by the tangential force {WT:.4g} J"
    if gained_total:
        msgs.append(f"kinetic energy gained: the final kinetic energy exceeds the initial one by "
                    f"{(energy.final - E0) / E0:.3g} of it ({works})")
    if gained_normal:
        msgs.append(f"kinetic energy gained in the normal motion: e_n exceeds 1 by {e_n - 1.0:.3g} "
                    f"(e_n = {e_n:.12g}; {works})")
    if coul > 1e-9 * max(mu * fmax, 1e-300):
        msgs.append(f"Coulomb limit exceeded by {coul:.3e} N")
    if mu > 0 and f_abs > mu * (1.0 + 1e-9):
        why = scene.normal_law.hint(scene, "impulse_excess")
        msgs.append(f"impulse ratio |f| exceeds mu by {f_abs / mu - 1.0:.3g} of mu{why}")
    if abs(energy.error) > ENERGY_BALANCE_TOL * E0:
        msgs.append(f"energy balance error {energy.error / E0:.3g} of the initial kinetic energy (more than "
                    f"{ENERGY_BALANCE_TOL:g}): refine the time step")
    a_over_R = math.sqrt(dmax / c.R_star)
    if a_over_R > VALIDITY_A_OVER_R:
        msgs.append(f"contact beyond the range of the contact laws: the contact radius reached "
                    f"{a_over_R:.3g} R* (overlap {dmax / c.R_star:.3g} R*); Hertz-Mindlin "
                    f"theory assumes a small contact, a <= {VALIDITY_A_OVER_R:g} R*")
    if c.e_target is not None and c.calibration_missed(e_n, vn):
        msgs.append(f"e_n = {e_n:.6g} misses the target {c.e_target:g} of {c.e_target_what} by "
                    f"{abs(e_n - c.e_target) / c.e_target:.3g} of it (tolerance {CALIBRATION_RTOL:g} of it and "
                    f"{CALIBRATION_ATOL:g}): the "
                    f"calibration holds as dt -> 0; refine the time step")
    if spc < 10:
        msgs.append(f"only {spc:.3g} steps per contact: results are coarse")
    return msgs


def _coarse_step_hint(scene) -> str:
    return scene.normal_law.hint(scene, "coarse_step")


def raise_if_no_impulse(scene, PN, tc, vn, dt, spc):
    """NumericalError for a contact that produced no normal impulse or took no time."""
    if PN > 0.0 and tc > 0.0:
        return
    if tc == 0.0:
        raise NumericalError(f"the contact ended at first touch, before any time passed: at {spc:.4g} steps per "
                             f"contact (dt = {dt:g} s) the time step is too coarse for the {scene.normal} law"
                             f"{_coarse_step_hint(scene)}; use more steps per contact")
    raise NumericalError(f"the contact produced no normal impulse (normal impulse {PN:g} N s, contact time "
                         f"{tc:g} s): its forces underflow double precision")


def raise_if_restitution_impossible(scene, e_n, vn, dt, spc):
    """NumericalError for an e_n that no passive normal law gives (see E_N_EXCESS_TOL)."""
    if 0.0 <= e_n <= 1.0 + E_N_EXCESS_TOL:
        return
    coarse = (f" at {spc:.4g} steps per contact (dt = {dt:g} s): the time step is too coarse for the "
              f"{scene.normal} law{_coarse_step_hint(scene)}; use more steps per contact")
    if e_n < 0.0:
        raise NumericalError(f"the contact ended while the bodies still approached (e_n = {e_n:.4g} < 0, final "
                             f"normal velocity {-e_n * vn:.4g} m/s towards the contact){coarse}")
    raise NumericalError(f"e_n = {e_n:.8g} exceeds 1 by {e_n - 1.0:.3g}, more than the {E_N_EXCESS_TOL:g} that "
                         f"a passive normal law may show from discretisation{coarse}")


def _raise_failed(scene, status, steps, vn, dt):
    """NumericalError for an integration that ended with ``status`` (STATUS_MAX_STEPS, STATUS_NONFINITE)."""
    if status == STATUS_MAX_STEPS:
        hint = scene.normal_law.hint(scene, "long_contact")
        raise NumericalError(f"the contact did not end within {int(steps)} steps "
                             f"({MAX_CONTACT_TIMES:g} elastic Hertz contact times at vn = {vn:g} m/s){hint}")
    if status == STATUS_NONFINITE:
        raise NumericalError(f"non-finite state (NaN or overflow) after {int(steps)} steps: the "
                             f"{scene.normal}/{scene.tangential} laws blew up at dt = {dt:g} s")


def build_result(scene, out, vn, vt, spin, spin2, dt, spc, scheme, ser=None, model=None) -> ImpactResult:
    """Turn the integrator's output row into an ImpactResult (raises NumericalError on failure); ``model``:
    the dict for ``ImpactResult.model`` (default: the scene's ``describe()``)."""
    return _build_result(scene_constants(scene), scene, out, vn, vt, spin, spin2, dt, spc, scheme, ser, model)


def _build_result(c, scene, out, vn, vt, spin, spin2, dt, spc, scheme, ser, model) -> ImpactResult:
    """``build_result`` with the scene's constants ``c``."""
    # the output row, slot by slot (O_VN ... O_MINWT)
    vn_r, vt_r, w_r, w2_r, PN, PT, tc, dmax, fmax, slid, steps, WN, WT, coul, status, minwt = out.tolist()
    if status != STATUS_OK:
        _raise_failed(scene, status, steps, vn, dt)
    inv_m, R1, R2, inv_I1, inv_I2 = c.inertia
    m = c.m
    mu = c.mu
    e_n = -vn_r / vn
    v_ti = vt + R1 * spin + R2 * spin2
    v_tr = vt_r + R1 * w_r + R2 * w2_r
    if not math.isfinite(vn_r + vt_r + w_r + w2_r + PN + PT + tc + dmax + fmax + WN + WT):
        state = {"final normal velocity": vn_r, "final tangential velocity": vt_r, "final spin": w_r,
                 "final spin of body 2": w2_r, "normal impulse": PN, "tangential impulse": PT,
                 "contact time": tc, "max overlap": dmax, "max force": fmax,
                 "normal work": WN, "tangential work": WT}
        bad = [k for k, v in state.items() if not math.isfinite(v)] or ["sum of the state"]
        raise NumericalError(f"non-finite result ({', '.join(bad)}) with the {scene.normal}/{scene.tangential} "
                             f"laws at dt = {dt:g} s")
    if not PN > 0.0 or not tc > 0.0:
        raise_if_no_impulse(scene, PN, tc, vn, dt, spc)
    if not 0.0 <= e_n <= 1.0 + E_N_EXCESS_TOL:
        raise_if_restitution_impossible(scene, e_n, vn, dt, spc)
    f = PT / PN
    # undefined (NaN, None in JSON): f/mu and the dimensionless groups at mu = 0, e_t at vt = 0
    fm = f / mu if mu > 0 else math.nan
    denom = (1.0 + e_n) * mu * vn
    if mu > 0 and denom > 0:
        Theta = 2.0 * v_ti / denom
        Psi_r = 2.0 * v_tr / denom
        Omega_i = 2.0 * R1 * spin / (5.0 * denom)
        Omega_r = 2.0 * R1 * w_r / (5.0 * denom)
    else:
        Theta = Psi_r = Omega_i = Omega_r = math.nan
    # e_t = vt_r / vt is undefined at vt = 0 and overflows for |vt| below 1e-100 of vn: NaN there
    tiny_vt = abs(vt) < 1e-100 * vn
    e_t = vt_r / vt if not tiny_vt else math.nan
    # (a finite sum: all its terms are finite)
    if not math.isfinite(e_n + f + (0.0 if tiny_vt else e_t) + (fm + Theta + Psi_r + Omega_r if mu > 0 else 0.0)) and not (
            math.isfinite(e_n) and math.isfinite(f) and (tiny_vt or math.isfinite(e_t))
            and (mu <= 0 or (math.isfinite(fm) and math.isfinite(Theta) and math.isfinite(Psi_r)
                             and math.isfinite(Omega_r)))):
        defined = {"e_n": e_n, "f": f, "f_over_mu": fm if mu > 0 else 0.0, "Theta": Theta if mu > 0 else 0.0,
                   "Psi_r": Psi_r if mu > 0 else 0.0, "Omega_r": Omega_r if mu > 0 else 0.0,
                   "e_t": e_t if not tiny_vt else 0.0}
        bad = [k for k, v in defined.items() if not math.isfinite(v)]
        raise NumericalError(f"non-finite result ({', '.join(bad)}) with the {scene.normal}/{scene.tangential} "
                             f"laws at dt = {dt:g} s")
    I1 = c.I1
    E0 = 0.5 * m * (vn * vn + vt * vt) + 0.5 * I1 * spin**2
    E1 = 0.5 * m * (vn_r**2 + vt_r**2) + 0.5 * I1 * w_r**2
    if c.sphere2:       # (a wall's terms are 0: I2 = 0, spin2 = w2_r = 0)
        I2 = c.I2
        E0 += 0.5 * I2 * spin2**2
        E1 += 0.5 * I2 * w2_r**2
    energy = EnergyBudget(E0, E1, WT, WN, E0 - E1 - WT - WN)
    # A passive tangential law stores or dissipates: its running work can never be negative.
    created = minwt < -ENERGY_CREATION_TOL * E0
    gained_total = E1 - E0 > KE_ROUNDING_TOL * E0
    # the normal motion alone: a passive normal law cannot return more than it received (e_n <= 1)
    gained_normal = e_n * e_n - 1.0 > KE_ROUNDING_TOL
    gained = gained_total or gained_normal
    msgs = []
    if (created or gained or coul > 1e-9 * max(mu * fmax, 1e-300) or (mu > 0 and abs(f) > mu * (1.0 + 1e-9))
            or abs(energy.error) > ENERGY_BALANCE_TOL * E0 or math.sqrt(dmax / c.R_star) > VALIDITY_A_OVER_R
            or spc < 10 or abs(e_n - c.e_target_or_0) > c.e_tol):     # (no calibration: e_tol = inf)
        msgs = impact_warnings(c, scene, e_n=e_n, f_abs=abs(f), energy=energy, minwt=minwt, coul=coul, fmax=fmax,
                               dmax=dmax, spc=spc, vn=vn, created=created, gained_total=gained_total,
                               gained_normal=gained_normal)
        for msg in msgs:
            warnings.warn(msg, RuntimeWarning, stacklevel=3)
    series_dict = None
    if ser is not None and ser.shape[0] > 0:
        n = int(steps)
        names = {S_T: "t", S_DELTA: "overlap", S_N: "normal_force", S_TANG: "tangential_force",
                 S_A: "contact_radius", S_VN: "vn", S_VSLIP: "v_slip"}
        first = {S_VN: vn, S_VSLIP: v_ti}     # the state at first touch heads every column
        series_dict = {name: np.concatenate([[first.get(col, 0.0)], ser[:n, col]])
                       for col, name in names.items()}
    # positional, in the order of the fields (much faster than keywords for this many fields)
    return ImpactResult(
        vn, vt, spin, vn_r, vt_r, w_r,                                 # vn_i, vt_i, omega_i, vn_r, vt_r, omega_r
        math.atan2(vt, vn) * _DEGREES,                                 # theta_i_deg
        e_n, e_t, f, fm, Theta, Psi_r, Omega_i, Omega_r,
        math.atan2(vt_r, -vn_r) * _DEGREES,                            # rebound_angle_deg
        math.atan2(v_tr, -vn_r) * _DEGREES,                            # patch_rebound_angle_deg
        PN, PT, tc, dmax, fmax,                  # normal_impulse, tangential_impulse, contact_time, max_overlap, max_force
        slid >= 1.0 - SLIDE_IMPULSE_TOL, slid,   # persistent_sliding (integrator.is_sliding), sliding_fraction
        int(steps), dt, energy, created,
        0.0 if coul < 0.0 else coul,             # coulomb_violation, max(coul, 0.0)
        msgs,                                    # warnings
        c.model if model is None else model,
        {"scheme": scheme, "dt": dt, "steps_per_contact": spc, "vn": vn, "vt": vt, "spin": spin},  # settings
        w2_r, series_dict, gained)               # omega2_r, series, energy_gained
