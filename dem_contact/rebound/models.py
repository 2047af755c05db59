"""Rebound models of oblique impact in the dimensionless groups of Wu, Thornton & Li (2009).

Pure numpy, usable on their own (Wu, Thornton & Li 2009, section 4). Theta is the dimensionless incidence of
the contact patch, 2 v_ti / ((1 + e_n) mu V_ni) with v_ti = V_ti + R omega_i (eq. 7.1; without spin
2 tan(theta_i) / ((1 + e_n) mu), eq. 2.20), as ``ImpactResult.Theta`` gives it: with in-plane spin the f/mu
curves are unchanged when read at the patch Theta (section 7). Every model returns f/mu, Omega_r, e_t and
Psi_r through the momentum identities (eqs 2.21-2.23) from its f/mu, with the centre value
Theta - 5 Omega_i in e_t (e_t is a ratio of centre velocities, eq. 2.1b):

    Omega_r = Omega_i - (m*/m1) f/mu,   e_t = 1 - 2 (f/mu) / (Theta - 5 Omega_i),   Psi_r = Theta - 7 f/mu

(m*/m1 = 1 for a sphere on a wall, 1/2 for two identical spheres; the e_t and Psi_r forms hold for any two
solid spheres, with Omega_i from the radius and spin of body 1 and body 2 not spinning).

- ``wu``: the fit f/mu = c1 + c2 tanh(c3 + c4 Theta) below the crossing with 1, 1 above (eqs 4.5-4.8);
- ``bilinear``: Walton / Foerster et al., Psi_r = -beta Theta below Theta_c, beta = 1/(7 kappa - 1)
  (eqs 5.1-5.6);
- ``rigid_body``: Brach, f/mu = Theta/7 below Theta_c = 7 (eqs 5.7-5.9).

``PUBLISHED_FITS`` holds the paper's fits (for comparison only).
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError

#: Wu, Thornton & Li (2009) fits of eq. 4.5 (FEA, R = 10 mm, steel, mu = 0.3, no spin;
#: section 4). Theta_c_paper is the paper's printed critical value (where its curve reaches about 0.99);
#: Theta_c_eq41 is eq. 4.1 (None for the plastic cases). For comparison only.
PUBLISHED_FITS = {
    "RE nu=0": dict(case="RE", nu=0.0, vn=(5.0,), c=(0.4627, -0.6053, 1.0000, -0.3832), Theta_c_eq41=6.0,
                    Theta_c_paper=6.1277),
    "RE nu=0.3": dict(case="RE", nu=0.3, vn=(5.0,), c=(0.4459, -0.6112, 0.9288, -0.4050), Theta_c_eq41=5.786,
                      Theta_c_paper=5.8363),
    "RE nu=0.49": dict(case="RE", nu=0.49, vn=(5.0,), c=(0.4268, -0.6250, 0.8297, -0.4263), Theta_c_eq41=5.520,
                       Theta_c_paper=5.4440),
    "EE": dict(case="EE", nu=0.3, vn=(2.0, 5.0), c=(0.4458, -0.6024, 0.9522, -0.4341), Theta_c_eq41=5.786,
               Theta_c_paper=5.6582),
    "PE 2 m/s": dict(case="PE", nu=0.3, vn=(2.0,), c=(0.4768, -0.6030, 1.0658, -0.4245), Theta_c_eq41=None,
                     Theta_c_paper=5.5799),
    "PE 5 m/s": dict(case="PE", nu=0.3, vn=(5.0,), c=(0.4868, -0.6414, 0.9841, -0.3669), Theta_c_eq41=None,
                     Theta_c_paper=5.5005),
}


def kappa_from_nu(nu):
    """kappa = k_t/k_n = 2 (1 - nu) / (2 - nu) for identical materials or a rigid body on an elastic one
    (Johnson 1985, section 4.2; Wu, Thornton & Li 2009, section 2)."""
    nu = np.asarray(nu, dtype=float)
    return 2.0 * (1.0 - nu) / (2.0 - nu)


def _check_e_n(e_n):
    e_n = np.asarray(e_n, dtype=float)
    if not np.all((e_n >= 0.0) & (e_n <= 1.0)):
        raise InputError(f"e_n (normal coefficient of restitution) must be in [0, 1], got {e_n}")
    return e_n


def _check_kappa(kappa):
    kappa = np.asarray(kappa, dtype=float)
    if not np.all(np.isfinite(kappa) & (kappa > 0.0)):
        raise InputError(f"kappa (k_t/k_n) must be finite and > 0, got {kappa}")
    return kappa


def theta_c_theory(kappa, e_n=1.0):
    """Critical Theta above which sliding persists (no spin), ``regime_boundaries(...)["persistent_sliding"]``:
    Theta_c = max(7 - 2 e_n / (kappa (1 + e_n)), 2 / (kappa (1 + e_n))).

    Persistent sliding needs kappa v_t >= mu d(delta)/dt at every instant of an elastic unloading with
    k_t/k_n = kappa (Maw, Barber & Fawcett 1976; Johnson 1985, section 7.3). While the contact slides, v_t
    falls by 3.5 mu per unit of normal speed lost, so the margin kappa v_t - mu d(delta)/dt changes at the
    rate (3.5 kappa - 1) mu times the normal deceleration: for kappa > 2/7 it falls through the impact and
    the condition binds at separation, where d(delta)/dt = -e_n V_ni, giving 7 - 2 e_n / (kappa (1 + e_n))
    (at e_n = 1 eq. 4.1 of Wu, Thornton & Li 2009, (7 kappa - 1) / kappa); for kappa <= 2/7 it rises, the
    condition binds at first touch, and persistent sliding is sliding from first touch,
    Theta > 2 / (kappa (1 + e_n)). The larger of the two is the boundary for every kappa. For an impact
    whose e_n changes with the angle, give the e_n of the sliding impacts."""
    kappa = _check_kappa(kappa)
    e_n = _check_e_n(e_n)
    out = np.maximum(7.0 - 2.0 * e_n / (kappa * (1.0 + e_n)), 2.0 / (kappa * (1.0 + e_n)))
    return float(out) if out.ndim == 0 else out


def regime_boundaries(kappa, e_n=1.0) -> dict:
    """The values of Theta (no spin) that separate the regimes of an oblique impact, by the argument of
    ``theta_c_theory`` (kappa v_t against mu d(delta)/dt), in increasing order:

    - ``initial_sliding``: the contact slides from first touch iff Theta > 2 / (kappa (1 + e_n)), i.e.
      kappa tan(theta_i) > mu (1/kappa at e_n = 1);
    - ``compression_sliding``: it slides through the whole compression iff Theta >= 7 / (1 + e_n), i.e.
      tan(theta_i) >= 3.5 mu (3.5 at e_n = 1) for kappa >= 2/7;
    - ``persistent_sliding``: it slides until separation iff Theta >= ``theta_c_theory(kappa, e_n)``.

    For kappa < 2/7 the margin kappa v_t - mu d(delta)/dt rises while the contact slides: a contact that
    slides at first touch slides to the end, and one that does not cannot slide through the compression, so
    all three boundaries are the initial-sliding one.
    """
    kappa = float(_check_kappa(kappa))
    e_n = float(_check_e_n(e_n))
    initial = 2.0 / (kappa * (1.0 + e_n))
    return {"initial_sliding": initial, "compression_sliding": max(7.0 / (1.0 + e_n), initial),
            "persistent_sliding": theta_c_theory(kappa, e_n)}


def eq_4_1(kappa):
    """Eq. 4.1 of Wu, Thornton & Li (2009), Theta_c = (7 kappa - 1) / kappa: the critical Theta of an
    elastic impact (e_n = 1) for kappa > 2/7, and the critical value of the bilinear model (eq. 5.2) for any
    kappa > 1/7."""
    kappa = _check_kappa(kappa)
    if np.any(kappa <= 1.0 / 7.0):
        raise InputError(f"kappa must be > 1/7 for eq. 4.1 (Theta_c = (7 kappa - 1) / kappa > 0), got {kappa}")
    out = (7.0 * kappa - 1.0) / kappa
    return float(out) if out.ndim == 0 else out


def collapse_variable(Theta, kappa):
    """kappa Theta / (7 kappa - 1) = Theta / Theta_c(eq. 4.1): the RE curves of different nu collapse on it."""
    return np.asarray(Theta, dtype=float) / eq_4_1(kappa)


def wu_curve(Theta, c):
    """The bare tanh curve c1 + c2 tanh(c3 + c4 Theta) of eq. 4.5 (no cap at 1)."""
    c1, c2, c3, c4 = c
    return c1 + c2 * np.tanh(c3 + c4 * np.asarray(Theta, dtype=float))


def wu_crossing(c, level: float = 1.0) -> float:
    """Theta at which the curve of eq. 4.5 reaches ``level`` (Theta_c for level = 1); inf if it never does."""
    c1, c2, c3, c4 = c
    if c2 == 0 or c4 == 0:
        return math.inf
    y = (level - c1) / c2
    if not -1.0 < y < 1.0:
        return math.inf
    return (math.atanh(y) - c3) / c4


def _identities(Theta, fm, Omega_i, mass_ratio):
    """Omega_r, e_t, Psi_r from f/mu at the patch Theta through eqs 2.21-2.23 (see the module docstring;
    e_t NaN where the centre Theta - 5 Omega_i is 0)."""
    Theta = np.asarray(Theta, dtype=float)
    centre = Theta - 5.0 * Omega_i
    with np.errstate(divide="ignore", invalid="ignore"):
        e_t = np.where(centre != 0, 1.0 - 2.0 * fm / np.where(centre != 0, centre, 1.0), np.nan)
    return {"Theta": Theta, "f_over_mu": fm, "Omega_r": Omega_i - mass_ratio * fm, "e_t": e_t,
            "Psi_r": Theta - 7.0 * fm}


def _theta(Theta):
    """Theta as a float array; NaN or infinite values refused (a comparison with Theta_c would put them
    on either side silently)."""
    Theta = np.asarray(Theta, dtype=float)
    if not np.all(np.isfinite(Theta)):
        raise InputError(f"Theta (dimensionless incidence) must be finite, got {Theta}")
    return Theta


def _mass_ratio(mass_ratio):
    if not 0.0 < mass_ratio <= 1.0:
        raise InputError(f"mass_ratio (m*/m1: 1 for a wall, 1/2 for two identical spheres) must be in (0, 1], "
                         f"got {mass_ratio}")
    return float(mass_ratio)


def wu(Theta, c, Theta_c: float | None = None, Omega_i: float = 0.0, mass_ratio: float = 1.0) -> dict:
    """Wu et al. model, eqs 4.5-4.8 and 7.1: f/mu = c1 + c2 tanh(c3 + c4 Theta) for Theta < Theta_c, 1 above,
    at the patch Theta (module docstring) with initial spin Omega_i.

    c: (c1, c2, c3, c4); Theta_c: default the crossing of the curve with 1 (``wu_crossing``); give the
    paper's printed value to reproduce its piecewise curve; mass_ratio: m*/m1. Returns dict of arrays Theta,
    f_over_mu, Omega_r, e_t, Psi_r."""
    Theta = _theta(Theta)
    if len(c) != 4 or not np.all(np.isfinite(np.asarray(c, dtype=float))):
        raise InputError(f"c (the four c-parameters c1..c4 of eq. 4.5) must be four finite numbers, got {c}")
    tc = wu_crossing(c) if Theta_c is None else float(Theta_c)
    if math.isnan(tc):
        raise InputError("Theta_c must be a number (or None for the crossing of the curve with 1), got nan")
    fm = np.where(Theta < tc, wu_curve(Theta, c), 1.0)
    return _identities(Theta, fm, Omega_i, _mass_ratio(mass_ratio))


def wu_f_over_mu(Theta, c, Theta_c: float | None = None):
    """f/mu of eq. 4.5 (see ``wu``)."""
    return wu(Theta, c, Theta_c)["f_over_mu"]


def bilinear(Theta, kappa, Omega_i: float = 0.0, mass_ratio: float = 1.0) -> dict:
    """Bilinear model (Walton; Foerster et al.), eqs 5.1-5.6, at the patch Theta: Psi_r = -beta Theta below
    Theta_c = (7 kappa - 1)/kappa, Theta - 7 above, beta = 1/(7 kappa - 1); f/mu = (1 + beta) Theta / 7
    below, 1 above (the model holds e_n = 1 in its Theta_c)."""
    Theta = _theta(Theta)
    tc = eq_4_1(kappa)
    beta = 1.0 / (7.0 * kappa - 1.0)
    fm = np.where(Theta < tc, (1.0 + beta) * Theta / 7.0, 1.0)
    return _identities(Theta, fm, Omega_i, _mass_ratio(mass_ratio))


def rigid_body(Theta, Omega_i: float = 0.0, mass_ratio: float = 1.0) -> dict:
    """Rigid-body dynamics (Brach), eqs 5.7-5.9, at the patch Theta: Theta_c = 7, f/mu = Theta/7 below (the
    patch ends at rest, Psi_r = 0; without spin e_t = 5/7, Omega_r = -Theta/7), 1 above."""
    Theta = _theta(Theta)
    fm = np.where(Theta < 7.0, Theta / 7.0, 1.0)
    return _identities(Theta, fm, Omega_i, _mass_ratio(mass_ratio))


def persistent_sliding(Theta, Omega_i: float = 0.0, mass_ratio: float = 1.0) -> dict:
    """Persistent sliding, f/mu = 1, at the patch Theta: Omega_r = Omega_i - m*/m1,
    e_t = 1 - 2/(Theta - 5 Omega_i), Psi_r = Theta - 7."""
    Theta = _theta(Theta)
    return _identities(Theta, np.ones_like(Theta), Omega_i, _mass_ratio(mass_ratio))


def max_curve_difference(c_a, c_b, Theta_max: float, Theta_c_a=None, Theta_c_b=None, n: int = 2001) -> float:
    """max |f/mu_a - f/mu_b| of two eq. 4.5 models over 0 <= Theta <= Theta_max (each capped at its Theta_c)."""
    T = np.linspace(0.0, Theta_max, n)
    return float(np.max(np.abs(wu_f_over_mu(T, c_a, Theta_c_a) - wu_f_over_mu(T, c_b, Theta_c_b))))
