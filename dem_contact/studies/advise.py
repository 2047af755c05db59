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
import warnings
from dataclasses import dataclass

import numpy as np

from . import chart
from ..errors import InputError, NumericalError
from ..rebound.fit import fit_wu
from ..impacts.impact import check_steps_per_contact
from ..impacts.sweep import scene_with
from ..materials import Wall, check_finite
from ..laws.model import MDR_RADIUS_MARGIN, MDR_SPRINGS, MDR_STEPS_PER_CONTACT, Scene, law_of
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
    scheme: str = "located"                       # integrator end of the law candidates
    warnings: list = dataclasses.field(default_factory=list)

    def to_dict(self) -> dict:
        """JSON-ready dict: a quantity that is not a number is None, with its reason in ``null_values``."""
        d = dataclasses.asdict(self)
        why = {}
        for key, cands in (("candidates", d["candidates"]), ("recommended", [d["recommended"]])):
            for i, c in enumerate(cands):
                if c is None:
                    continue
                at = f"{key}[{i}]" if key == "candidates" else key
                if not math.isfinite(c["error"]):
                    why[f"{at}.error"] = ("the candidate failed numerically on the sample (a blow-up, or an e_n "
                                          "outside [0, 1] at its time step): no error measured")
                    c["error"] = None
                if "Theta_c" in c["params"] and not math.isfinite(c["params"]["Theta_c"]):
                    why[f"{at}.params.Theta_c"] = "the fitted curve does not reach f/mu = 1: no Theta_c"
                    c["params"]["Theta_c"] = None
        if d["recommended"] is None:
            why["recommended"] = "no candidate meets the tolerance"
        if d["verification"] is None:
            why["verification"] = "not run (verify=False, or nothing recommended)"
        if why:
            d["null_values"] = why
        return d


def _with_law(scene: Scene, tangential: str, vmax: float, **kw) -> Scene:
    """The scene with another tangential law, every other setting kept (``impacts.sweep.scene_with``: the
    normal law and its calibration, e_n, mdr_profile, traction_yield, ...); mdr springs cover vmax."""
    if "mdr_max_radius" in law_of("tangential", tangential).OPTIONS:
        kw["mdr_max_radius"] = MDR_RADIUS_MARGIN * scene.max_contact_radius(vmax)
    return scene_with(scene, tangential=tangential, **kw)


def _sample(vn_range, angle_range, n_speeds, n_angles, rng=None):
    vmin, vmax = vn_range
    if rng is None:
        speeds = np.unique(np.geomspace(vmin, vmax, n_speeds)) if vmax > vmin else np.array([vmin])
        angles = np.linspace(angle_range[0], angle_range[1], n_angles)
        return [(v, angles) for v in speeds]
    speeds = np.exp(rng.uniform(math.log(vmin), math.log(vmax), n_speeds))
    return [(v, rng.uniform(angle_range[0], angle_range[1], n_angles)) for v in speeds]


def _evaluate(scene, sample, spc, spin, repeats=1, scheme="located"):
    """f/mu, Theta (patch, eq. 7.1), sliding flags and time per impact over the sample (NaN where the
    impacts failed)."""
    fm, Th, slid, t = [], [], [], []
    for vn, angles in sample:
        vt = vn * np.tan(np.radians(angles))
        r = chart.run(scene, vn, vt, spc, scheme, repeats, spin=spin)
        v_ti = vt + scene.sphere.radius * spin
        fm.append(r.f_over_mu)
        Th.append(2.0 * v_ti / ((1.0 + r.e_n) * scene.mu * vn))
        slid.append(r.persistent_sliding if r.persistent_sliding is not None else np.zeros(vt.size, bool))
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
           n_angles: int = 12, verify: bool = False, seed: int = 1, scheme: str = "located",
           candidates=()) -> Advice:
    """Measure the candidates on a sample of the ranges and recommend the cheapest within ``tol``.

    scheme: integrator end of the law candidates ("located" or "standard"; the reference is always
    located and converged); candidates: further (tangential law, steps per contact) to measure besides
    LAW_CANDIDATES (with the scene's normal law)."""
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
    if scheme not in chart.SCHEMES:
        raise InputError(f"scheme {scheme!r} is unknown; choose one of: {', '.join(chart.SCHEMES)}")
    laws = list(LAW_CANDIDATES)
    for law, spc in candidates:
        spc = check_steps_per_contact(spc)
        if (law, spc) not in laws:
            laws.append((law, spc))
    sample = _sample((vmin, vmax), (a0, a1), n_speeds, n_angles)
    f_ref, Th, _, _ = _reference(scene, sample, spin, vmax)
    cands = []
    x = np.linspace(0.0, 10.0, 1000)
    err = float(np.max(np.abs(1.0 - f_ref)))
    cands.append(Candidate("sliding", "rigid-body persistent sliding, f/mu = 1 (Omega_r = Omega_i - 1, "
                           "e_t = 1 - 2/(Theta - 5 Omega_i))", err, _time_closed_form(np.ones_like, x)))
    notes = []
    if spin == 0.0:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")     # the fit's warnings are in fit.warnings
                fit = fit_wu(Th, f_ref)
            notes += [f"Wu et al. fit: {w}" for w in fit.warnings]
            err = float(np.max(np.abs(fit(Th) - f_ref)))
            c = ", ".join(f"{v:.4f}" for v in fit.c)
            tc = f"{fit.Theta_c:.4g}" if math.isfinite(fit.Theta_c) else "none (the curve does not reach 1)"
            cands.append(Candidate("wu", f"Wu et al. eq. 4.5 fitted to MDR: c = ({c}), Theta_c = {tc}",
                                   err, _time_closed_form(lambda t: wu_curve(t, fit.c), x),
                                   params={"c": list(fit.c), "Theta_c": fit.Theta_c}))
        except (InputError, NumericalError, ValueError, RuntimeError) as e:
            notes.append(f"no Wu et al. candidate: its fit to the sample failed ({e})")
    end = "" if scheme == "located" else f", {scheme} scheme"
    for law, spc in laws:
        sc = _with_law(scene, law, vmax)
        f, _, _, t = _evaluate(sc, sample, spc, spin, repeats=3, scheme=scheme)
        cands.append(Candidate(f"{law}@{spc:g}", f"tangential law {law}, {spc:g} steps per contact{end}",
                               float(np.max(np.abs(f - f_ref))), t,
                               params={"law": law, "steps": spc, "scheme": scheme}))
    sc = _with_law(scene, "mdr", vmax, mdr_springs=MDR_SPRINGS)
    f, _, _, t = _evaluate(sc, sample, MDR_STEPS_PER_CONTACT, spin, repeats=1)
    cands.append(Candidate(f"mdr@{MDR_STEPS_PER_CONTACT}", f"exact reference mdr, {MDR_SPRINGS} springs, "
                           f"{MDR_STEPS_PER_CONTACT} steps per contact", float(np.max(np.abs(f - f_ref))), t,
                           params={"law": "mdr", "steps": MDR_STEPS_PER_CONTACT}))
    for c in cands:
        c.meets = bool(np.isfinite(c.error) and c.error <= tol)
    ok = sorted((c for c in cands if c.meets), key=lambda c: c.time_us)
    advice = Advice(cands, ok[0] if ok else None, tol, sum(len(a) for _, a in sample), scheme=scheme,
                    warnings=notes)
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
        f = _evaluate(sc, sample, cand.params["steps"], spin, scheme=cand.params.get("scheme", "located"))[0]
    err = float(np.max(np.abs(f - f_ref)))
    return {"points": int(f.size), "max_error": err, "passed": bool(err <= tol), "seed": seed}
