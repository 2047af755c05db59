"""Stability map: which laws and integrator settings blow up, create energy, violate Coulomb or lose
accuracy at the edges of the parameter space.

Every case is one oblique impact of the EE steel scene (R = 10 mm) with one setting pushed to an
extreme: steps per contact down to 2, mu from 0 to 1e4, nu = 0, 0.49, 0.5, grazing angles up to 89.9
deg, normal speeds from 1e-4 to 100 m/s, plastic impacts up to V/V_y = 1e3. Each run is classified
from what the library itself reports (``impact`` raises NumericalError on a blow-up and flags energy
creation, Coulomb excess and coarse steps in ImpactResult.warnings), then compared with the converged
MDR reference (Popov & Hess 2015, chapter 6) for the accuracy class:

    ok          no failure, |f/mu - MDR| <= ACCURACY_TOL (and |e_n - MDR| <= ACCURACY_TOL)
    inaccurate  error above ACCURACY_TOL (reported by the library only as the coarse-steps warning)
    coulomb     |T| > mu N at some step (flagged: warning, ImpactResult.coulomb_violation > 0)
    energy      the tangential law did negative work (flagged: ImpactResult.energy_created, warning)
    blow-up     NaN / overflow / no separation / e_n outside [0, 1]: NumericalError
    rejected    the input is outside the valid range: InputError
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

from ..errors import InputError, NumericalError
from ..impacts.impact import impact
from ..materials import STEEL, Material, Sphere, Wall, pair_properties
from ..laws.model import TANGENTIAL_LAWS, Scene, reference_speed

ACCURACY_TOL = 0.02
OUTCOMES = ("ok", "inaccurate", "coulomb", "energy", "blow-up", "rejected")
#: Steps per contact of the MDR reference (default springs, model.MDR_SPRINGS).
REFERENCE_STEPS = 2000


@dataclass(frozen=True)
class Case:
    """One extreme setting: name, and the scene and impact it changes."""

    name: str
    nu: float = 0.3
    mu: float = 0.3
    vn: float = 5.0
    angle_deg: float = 20.0
    steps: float = 100.0
    plastic_ratio: float = 0.0     # V / V_y with the thornton law (0: elastic hertz)


CASES = (
    Case("2 steps/contact", steps=2.0),
    Case("3 steps/contact", steps=3.0),
    Case("5 steps/contact", steps=5.0),
    Case("mu = 0", mu=0.0),
    Case("mu = 1e4", mu=1e4),
    Case("mu = 1e4, 45 deg", mu=1e4, angle_deg=45.0),
    Case("nu = 0", nu=0.0, angle_deg=10.0),
    Case("nu = 0.49", nu=0.49),
    Case("nu = 0.5", nu=0.5),
    Case("80 deg", angle_deg=80.0),
    Case("89.9 deg", angle_deg=89.9),
    Case("1e-4 m/s", vn=1e-4),
    Case("100 m/s", vn=100.0),
    Case("V/V_y = 10", plastic_ratio=10.0),
    Case("V/V_y = 1e3", plastic_ratio=1e3),
    Case("V/V_y = 1e3, 10 steps", plastic_ratio=1e3, steps=10.0),
)


@dataclass
class StabilityRow:
    case: str
    tangential: str
    scheme: str
    outcome: str
    f_over_mu: float
    reference_f_over_mu: float
    e_n: float
    reference_e_n: float
    detail: str


def case_scene(case: Case, tangential: str) -> Scene:
    mat = Material(STEEL.E, case.nu, STEEL.rho)
    sphere_mat = mat
    normal = "hertz"
    if case.plastic_ratio > 0:
        # p_y such that V_y = vn / ratio (Thornton 1997, sphere on wall: V_y = 1.5605 sqrt(p_y^5 / (E*^4 rho)))
        E_star = pair_properties(Sphere(0.01, mat), Wall(mat)).E_star
        vy = case.vn / case.plastic_ratio
        p_y = (vy / 1.5605) ** 0.4 * (E_star**4 * STEEL.rho) ** 0.2
        sphere_mat = Material(STEEL.E, case.nu, STEEL.rho, yield_pressure=p_y)
        normal = "thornton"
    return Scene(Sphere(0.01, sphere_mat), Wall(mat), mu=case.mu, normal=normal, tangential=tangential,
                 v_ref=reference_speed(case.vn))


def _run(case: Case, tangential: str, scheme: str, steps: float):
    sc = case_scene(case, tangential)
    vt = case.vn * math.tan(math.radians(case.angle_deg))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return impact(sc, case.vn, vt, steps_per_contact=steps, scheme=scheme)


def classify(case: Case, tangential: str, scheme: str, ref) -> StabilityRow:
    """Run one case and classify it (``ref``: the reference ImpactResult, or None)."""
    nan = math.nan
    rf = ref.f_over_mu if ref is not None else nan
    re = ref.e_n if ref is not None else nan
    try:
        r = _run(case, tangential, scheme, case.steps)
    except NumericalError as e:
        return StabilityRow(case.name, tangential, scheme, "blow-up", nan, rf, nan, re, str(e))
    except InputError as e:
        return StabilityRow(case.name, tangential, scheme, "rejected", nan, rf, nan, re, str(e))
    detail = "; ".join(r.warnings)
    if r.energy_created:
        outcome = "energy"
    elif r.coulomb_violation > 0 and any("Coulomb" in w for w in r.warnings):
        outcome = "coulomb"
    else:
        err_f = abs(r.f_over_mu - rf) if case.mu > 0 else 0.0
        err_e = abs(r.e_n - re)
        bad = not (err_f <= ACCURACY_TOL and err_e <= ACCURACY_TOL)
        outcome = "inaccurate" if bad else "ok"
        if bad:
            detail = f"|f/mu error| = {err_f:.3g}, |e_n error| = {err_e:.3g}" + (f"; {detail}" if detail else "")
    return StabilityRow(case.name, tangential, scheme, outcome, r.f_over_mu, rf, r.e_n, re, detail)


def stability_map(laws=None, schemes=("located", "standard"), cases=CASES, progress=None) -> list:
    """Classify every (case, law, scheme). Returns a list of StabilityRow."""
    laws = list(TANGENTIAL_LAWS) if laws is None else list(laws)
    rows = []
    for case in cases:
        try:
            ref = _run(case, "mdr", "located", REFERENCE_STEPS)
        except (NumericalError, InputError):
            ref = None
        for law in laws:
            for scheme in schemes:
                if progress:
                    progress(f"{case.name} {law} {scheme}")
                rows.append(classify(case, law, scheme, ref))
    return rows


