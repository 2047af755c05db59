"""Rebound models of oblique impact in the dimensionless groups of Wu, Thornton & Li (2009).

Pure numpy, usable on their own (Wu, Thornton & Li 2009, section 4). Theta is the dimensionless incidence
2 tan(theta_i) / ((1 + e_n) mu); every model returns f/mu, Omega_r, e_t and Psi_r through the momentum
identities (eqs 2.21-2.23) from its f/mu:

    Omega_r = Omega_i - f/mu,   e_t = 1 - 2 (f/mu) / Theta,   Psi_r = Theta + 5 Omega_i - 7 f/mu.

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


def theta_c_theory(kappa):
    """Critical Theta above which sliding persists, eq. 4.1 (Maw et al. 1976): (7 kappa - 1) / kappa."""
    kappa = np.asarray(kappa, dtype=float)
    if np.any(kappa <= 1.0 / 7.0):
        raise InputError("kappa must be > 1/7 for eq. 4.1")
    out = (7.0 * kappa - 1.0) / kappa
    return float(out) if out.ndim == 0 else out


def collapse_variable(Theta, kappa):
    """kappa Theta / (7 kappa - 1) = Theta / Theta_c(eq. 4.1): the RE curves of different nu collapse on it."""
    return np.asarray(Theta, dtype=float) / theta_c_theory(kappa)


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


def _identities(Theta, fm, Omega_i):
    """Omega_r, e_t, Psi_r from f/mu through eqs 2.21-2.23 (e_t NaN at Theta = 0)."""
    Theta = np.asarray(Theta, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        e_t = np.where(Theta != 0, 1.0 - 2.0 * fm / np.where(Theta != 0, Theta, 1.0), np.nan)
    return {"Theta": Theta, "f_over_mu": fm, "Omega_r": Omega_i - fm, "e_t": e_t,
            "Psi_r": Theta + 5.0 * Omega_i - 7.0 * fm}


def wu(Theta, c, Theta_c: float | None = None, Omega_i: float = 0.0) -> dict:
    """Wu et al. model, eqs 4.5-4.8: f/mu = c1 + c2 tanh(c3 + c4 Theta) for Theta < Theta_c, 1 above.

    c: (c1, c2, c3, c4); Theta_c: default the crossing of the curve with 1 (``wu_crossing``); give the
    paper's printed value to reproduce its piecewise curve. Returns dict of arrays Theta, f_over_mu,
    Omega_r, e_t, Psi_r."""
    Theta = np.asarray(Theta, dtype=float)
    tc = wu_crossing(c) if Theta_c is None else float(Theta_c)
    fm = np.where(Theta < tc, wu_curve(Theta, c), 1.0)
    return _identities(Theta, fm, Omega_i)


def wu_f_over_mu(Theta, c, Theta_c: float | None = None):
    """f/mu of eq. 4.5 (see ``wu``)."""
    return wu(Theta, c, Theta_c)["f_over_mu"]


def bilinear(Theta, kappa) -> dict:
    """Bilinear model (Walton; Foerster et al.), eqs 5.1-5.6: Psi_r = -beta Theta below
    Theta_c = (7 kappa - 1)/kappa, Theta - 7 above, beta = 1/(7 kappa - 1); f/mu = (1 + beta) Theta / 7
    below, 1 above."""
    Theta = np.asarray(Theta, dtype=float)
    tc = theta_c_theory(kappa)
    beta = 1.0 / (7.0 * kappa - 1.0)
    fm = np.where(Theta < tc, (1.0 + beta) * Theta / 7.0, 1.0)
    return _identities(Theta, fm, 0.0)


def rigid_body(Theta) -> dict:
    """Rigid-body dynamics (Brach), eqs 5.7-5.9: Theta_c = 7, f/mu = Theta/7 below (e_t = 5/7,
    Omega_r = -Theta/7, Psi_r = 0), 1 above."""
    Theta = np.asarray(Theta, dtype=float)
    fm = np.where(Theta < 7.0, Theta / 7.0, 1.0)
    return _identities(Theta, fm, 0.0)


def persistent_sliding(Theta, Omega_i: float = 0.0) -> dict:
    """Persistent sliding, f/mu = 1: Omega_r = Omega_i - 1, e_t = 1 - 2/Theta, Psi_r = Theta + 5 Omega_i - 7."""
    Theta = np.asarray(Theta, dtype=float)
    return _identities(Theta, np.ones_like(Theta), Omega_i)


def max_curve_difference(c_a, c_b, Theta_max: float, Theta_c_a=None, Theta_c_b=None, n: int = 2001) -> float:
    """max |f/mu_a - f/mu_b| of two eq. 4.5 models over 0 <= Theta <= Theta_max (each capped at its Theta_c)."""
    T = np.linspace(0.0, Theta_max, n)
    return float(np.max(np.abs(wu_f_over_mu(T, c_a, Theta_c_a) - wu_f_over_mu(T, c_b, Theta_c_b))))
