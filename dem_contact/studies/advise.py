"""Recommend the cheapest model of the tangential response that meets a tolerance, from measured data.

Given a scene, ranges of normal speed and impact angle, an initial spin and a tolerance on f/mu (the
rebound kinematics follow exactly from it: Omega_r error = f/mu error, e_t error = 2 (f/mu error)/Theta,
Psi_r error = 7 (f/mu error); Wu, Thornton & Li 2009, eqs 2.21-2.23), ``advise`` integrates a sample of the ranges
with converged MDR (Popov & Hess 2015, chapter 6) and measures, on the same sample, the error and the cost of each
candidate:

1. rigid-body persistent sliding (f/mu = 1; exact where sliding persists through the whole impact);
2. the Wu et al. model f/mu = c1 + c2 tanh(c3 + c4 Theta) (eq. 4.5) with c's fitted to the sample
   (no initial spin only; ``rebound_models`` and ``fit``);
3. cheap tangential laws at coarse steps (mdr_adaptive, md);
4. the exact reference (mdr at its 4-digit settings).

Costs are measured times per impact (serial, warm JIT) or per evaluation of the closed form. The
recommendation is the cheapest candidate whose measured error is within the tolerance; ``verify`` runs
it against MDR on a fresh random sample of the ranges.
"""
from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

import numpy as np

from . import chart
from ..errors import InputError
from ..rebound.fit import fit_wu
from ..materials import Wall, check_finite
from ..laws.model import MDR_RADIUS_MARGIN, MDR_SPRINGS, MDR_STEPS_PER_CONTACT, Scene
from ..rebound.models import wu_curve

#: Laws at coarse steps tried as candidates: (tangential law, steps per contact).
LAW_CANDIDATES = (("mdr_adaptive", 10), ("mdr_adaptive", 20), ("mdr_adaptive", 50), ("mdr_adaptive", 100),
                  ("md", 100), ("md", 1000))


@dataclass
class Candidate:
    name: str
    description: str
    error: float          # max |f/mu error| against converged MDR on the sample
    time_us: float        # measured cost per impact [us]
    meets: bool = False
    params: dict = dataclasses.field(default_factory=dict)   # law and steps, or the fitted c's


@dataclass
class Advice:
    candidates: list
    recommended: Candidate | None
    tolerance: float
    sample_points: int
    verification: dict | None = None

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)


def _with_law(scene: Scene, tangential: str, vmax: float, **kw) -> Scene:
    """The scene with another tangential law (same normal law and calibration); mdr springs cover vmax."""
    if tangential == "mdr":
        kw["mdr_max_radius"] = MDR_RADIUS_MARGIN * scene.max_contact_radius(vmax)
    if tangential in ("mdr", "mdr_adaptive"):
        kw["mdr_profile"] = scene.mdr_profile
    kw["traction_yield"] = scene.traction_yield
    return Scene(scene.sphere, scene.body2, mu=scene.mu, normal=scene.normal, tangential=tangential,
                 e_n=scene.e_n, v_ref=scene.v_ref, **kw)


def _sample(vn_range, angle_range, n_speeds, n_angles, rng=None):
    vmin, vmax = vn_range
    if rng is None:
        speeds = np.unique(np.geomspace(vmin, vmax, n_speeds)) if vmax > vmin else np.array([vmin])
        angles = np.linspace(angle_range[0], angle_range[1], n_angles)
        return [(v, angles) for v in speeds]
    speeds = np.exp(rng.uniform(math.log(vmin), math.log(vmax), n_speeds))
    return [(v, rng.uniform(angle_range[0], angle_range[1], n_angles)) for v in speeds]


def _evaluate(scene, sample, spc, spin, repeats=1):
    """f/mu, Theta (patch, eq. 7.1), sliding flags and time per impact over the sample."""
    fm, Th, slid, t = [], [], [], []
    for vn, angles in sample:
        vt = vn * np.tan(np.radians(angles))
        r = chart.run(scene, vn, vt, spc, "located", repeats, spin=spin)
        v_ti = vt + scene.sphere.radius * spin
        fm.append(r.f_over_mu)
        Th.append(2.0 * v_ti / ((1.0 + r.e_n) * scene.mu * vn))
        slid.append(r.persistent_sliding)
        t.append(r.seconds_per_impact)
    return np.concatenate(fm), np.concatenate(Th), np.concatenate(slid), 1e6 * float(np.mean(t))


def _reference(scene, sample, spin, vmax):
    ref = _with_law(scene, "mdr", vmax, mdr_springs=2 * MDR_SPRINGS)
    return _evaluate(ref, sample, 4 * MDR_STEPS_PER_CONTACT, spin)


def _time_closed_form(fn, x, repeats=20):
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn(x)
        best = min(best, time.perf_counter() - t0)
    return 1e6 * best / x.size


def advise(scene: Scene, vn_range, angle_range, spin: float = 0.0, tol: float = 0.01, *, n_speeds: int = 3,
           n_angles: int = 12, verify: bool = False, seed: int = 1) -> Advice:
    """Measure the candidates on a sample of the ranges and recommend the cheapest within ``tol``."""
    if not isinstance(scene.body2, Wall):
        raise InputError("advise handles sphere-wall impacts only")
    if scene.mu <= 0:
        raise InputError("mu must be > 0 for advise (with mu = 0 there is no tangential force)")
    vmin = check_finite("vn_min (m/s)", vn_range[0], lo=0.0)
    vmax = check_finite("vn_max (m/s)", vn_range[1], lo=0.0)
    a0 = check_finite("angle_min (deg)", angle_range[0], lo=0.0, lo_open=False, hi=90.0, hi_open=True)
    a1 = check_finite("angle_max (deg)", angle_range[1], lo=0.0, lo_open=False, hi=90.0, hi_open=True)
    if vmax < vmin or a1 < a0:
        raise InputError("ranges must be given as (min, max) with min <= max")
    tol = check_finite("tol (tolerance on f/mu)", tol, lo=0.0)
    spin = check_finite("spin (rad/s)", spin)
    sample = _sample((vmin, vmax), (a0, a1), n_speeds, n_angles)
    f_ref, Th, _, _ = _reference(scene, sample, spin, vmax)
    cands = []
    x = np.linspace(0.0, 10.0, 1000)
    err = float(np.max(np.abs(1.0 - f_ref)))
    cands.append(Candidate("sliding", "rigid-body persistent sliding, f/mu = 1 (Omega_r = Omega_i - 1, "
                           "e_t = 1 - 2/Theta)", err, _time_closed_form(np.ones_like, x)))
    if spin == 0.0:
        try:
            fit = fit_wu(Th, f_ref)
            err = float(np.max(np.abs(fit(Th) - f_ref)))
            c = ", ".join(f"{v:.4f}" for v in fit.c)
            cands.append(Candidate("wu", f"Wu et al. eq. 4.5 fitted to MDR: c = ({c}), Theta_c = {fit.Theta_c:.4g}",
                                   err, _time_closed_form(lambda t: wu_curve(t, fit.c), x),
                                   params={"c": list(fit.c), "Theta_c": fit.Theta_c}))
        except (InputError, ValueError, RuntimeError):
            pass   # too few points below Theta_c to fit
    for law, spc in LAW_CANDIDATES:
        sc = _with_law(scene, law, vmax)
        f, _, _, t = _evaluate(sc, sample, spc, spin, repeats=3)
        cands.append(Candidate(f"{law}@{spc}", f"tangential law {law}, {spc} steps per contact",
                               float(np.max(np.abs(f - f_ref))), t, params={"law": law, "steps": spc}))
    sc = _with_law(scene, "mdr", vmax)
    f, _, _, t = _evaluate(sc, sample, MDR_STEPS_PER_CONTACT, spin, repeats=1)
    cands.append(Candidate(f"mdr@{MDR_STEPS_PER_CONTACT}", f"exact reference mdr, {MDR_SPRINGS} springs, "
                           f"{MDR_STEPS_PER_CONTACT} steps per contact", float(np.max(np.abs(f - f_ref))), t,
                           params={"law": "mdr", "steps": MDR_STEPS_PER_CONTACT}))
    for c in cands:
        c.meets = bool(np.isfinite(c.error) and c.error <= tol)
    ok = sorted((c for c in cands if c.meets), key=lambda c: c.time_us)
    advice = Advice(cands, ok[0] if ok else None, tol, sum(len(a) for _, a in sample))
    if verify and advice.recommended is not None:
        advice.verification = verify_candidate(scene, advice.recommended, (vmin, vmax), (a0, a1), spin, tol,
                                               seed=seed)
    return advice


def verify_candidate(scene, cand, vn_range, angle_range, spin, tol, *, seed=1, n_speeds=3, n_angles=8):
    """Run ``cand`` against converged MDR on a random sample of the ranges: max |f/mu error|, pass/fail."""
    rng = np.random.default_rng(seed)
    sample = _sample(vn_range, angle_range, n_speeds, n_angles, rng)
    f_ref, Th, _, _ = _reference(scene, sample, spin, vn_range[1])
    if cand.name == "sliding":
        f = np.ones_like(f_ref)
    elif cand.name == "wu":
        f = np.where(Th < cand.params["Theta_c"], wu_curve(Th, cand.params["c"]), 1.0)
    else:
        sc = _with_law(scene, cand.params["law"], vn_range[1])
        f = _evaluate(sc, sample, cand.params["steps"], spin)[0]
    err = float(np.max(np.abs(f - f_ref)))
    return {"points": int(f.size), "max_error": err, "passed": bool(err <= tol), "seed": seed}
