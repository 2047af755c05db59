"""Fit of eq. 4.5: recovery of known curves from noisy data, exclusion of sliding points, Theta_c."""
import warnings

import numpy as np
import pytest

from dem_contact.rebound import models as rm
from dem_contact.errors import InputError
from dem_contact.rebound.fit import critical_theta, fit_wu


@pytest.mark.parametrize("key", ["EE", "RE nu=0", "PE 5 m/s"])
def test_fit_recovers_curve_from_noisy_data(key):
    c = rm.PUBLISHED_FITS[key]["c"]
    tc = rm.wu_crossing(c)
    rng = np.random.default_rng(7)
    T = np.linspace(0.0, tc, 60)[:-1]
    y = rm.wu_curve(T, c) + rng.normal(0.0, 0.003, T.size)
    f = fit_wu(T, y)
    # curves, not c's, are what the data determine
    assert rm.max_curve_difference(f.c, c, tc) < 0.004
    assert f.Theta_c == pytest.approx(tc, rel=0.02)
    assert abs(f.Theta_c - tc) < 4 * f.Theta_c_err
    assert f.rms == pytest.approx(0.003, rel=0.3)
    assert all(e > 0 for e in f.c_err)
    assert rm.wu_curve(f.Theta_c_099, f.c) == pytest.approx(0.99)


def test_fit_is_exact_without_noise():
    c = rm.PUBLISHED_FITS["EE"]["c"]
    T = np.linspace(0.0, 5.5, 40)
    f = fit_wu(T, rm.wu_curve(T, c))
    assert rm.max_curve_difference(f.c, c, 5.8) < 1e-6
    assert f.rms < 1e-8


def test_sliding_points_and_outliers_are_handled():
    c = rm.PUBLISHED_FITS["EE"]["c"]
    T = np.linspace(0.0, 5.5, 40)
    y = rm.wu_curve(T, c)
    y[10] += 0.2  # one outlier: the robust loss keeps the curve
    T2 = np.concatenate([T, np.linspace(6.0, 30.0, 20)])
    y2 = np.concatenate([y, np.ones(20)])
    sliding = T2 >= 6.0
    f = fit_wu(T2, y2, sliding)
    assert f.n_points == 40
    assert rm.max_curve_difference(f.c, c, 5.8) < 0.005


def test_fit_input_errors():
    with pytest.raises(InputError, match="at least 5 points"):
        fit_wu([0, 1, 2], [0, 0.1, 0.3])
    with pytest.raises(InputError, match="same length"):
        fit_wu([0, 1, 2], [0, 0.1])


def test_critical_theta_collects_three_estimates():
    c = rm.PUBLISHED_FITS["EE"]["c"]
    T = np.linspace(0.0, 5.5, 40)
    f = fit_wu(T, rm.wu_curve(T, c))
    ct = critical_theta(f, 0.8235294117647058, simulation=5.78)
    assert ct.theory == pytest.approx(5.7857, abs=1e-4)
    assert ct.fit == f.Theta_c and ct.simulation == 5.78
    assert set(ct.to_dict()) == {"fit", "fit_099", "simulation", "theory"}


def _tangential_curve(T, tc=5.786):
    """A curve that rises like f/mu and meets 1 tangentially at tc (as simulated curves do)."""
    x = np.clip(T / tc, 0.0, 1.0)
    return 1.0 - (1.0 - x) ** 2 * (1.0 - 0.05 * x)


def test_model_form_error_is_reported_apart_and_does_not_shrink():
    """Noise-free points that eq. 4.5 cannot follow: the statistical error shrinks with more points, the
    crossings of a coarse and a dense fit differ by many statistical errors, and the model-form error covers
    that difference and the true meeting point with 1."""
    tc = 5.786
    fits = []
    for n in (60, 6000):
        T = np.linspace(0.0, tc, n, endpoint=False)
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            fits.append(fit_wu(T, _tangential_curve(T, tc)))
    coarse, dense = fits
    assert dense.Theta_c_err < coarse.Theta_c_err / 5
    assert abs(coarse.Theta_c - dense.Theta_c) > 3 * dense.Theta_c_err
    assert abs(coarse.Theta_c - dense.Theta_c) < dense.Theta_c_model_err
    assert dense.Theta_c_model_err == pytest.approx(coarse.Theta_c_model_err, rel=0.3)
    assert abs(dense.Theta_c - tc) < 1.5 * dense.Theta_c_model_err      # a scale, not a bound
    assert not dense.extrapolated and dense.warnings == []


def test_extrapolated_theta_c_is_flagged():
    """A fit over 0-5 degrees of the EE scene (Theta < 0.6) says nothing reliable about Theta_c."""
    c = rm.PUBLISHED_FITS["EE"]["c"]
    T = np.linspace(0.0, 0.6, 6)
    with pytest.warns(RuntimeWarning, match="extrapolation"):
        f = fit_wu(T, rm.wu_curve(T, c) + np.array([0, 1, -1, 1, -1, 0]) * 1e-3)
    assert f.extrapolated and f.Theta_c > f.Theta_max
    assert f.Theta_c_model_err == float("inf")
    assert f.to_dict()["Theta_c_model_err"] is None


@pytest.mark.parametrize("loss", ["soft_l1", "linear"])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_fit_solver_reaches_scipy_minimum(loss, seed):
    """The Levenberg-Marquardt solver of fit_wu reaches the minimum scipy's least_squares finds for the same
    robust loss, bounds and data (eq. 4.5 with scatter and one outlier)."""
    from scipy.optimize import least_squares
    from dem_contact.rebound.fit import LOWER, SLIDING_LEVEL, UPPER, _jacobian, _start

    rng = np.random.default_rng(seed)
    T = np.sort(rng.uniform(0.0, 6.0, 60))
    c_true = (0.45 + 0.05 * seed, -0.6, 0.9, -0.4 - 0.05 * seed)
    y = rm.wu_curve(T, c_true) + 0.004 * rng.standard_normal(T.size)
    y[7] += 0.1
    f = fit_wu(T, y, loss=loss)
    T, y = T[y < SLIDING_LEVEL], y[y < SLIDING_LEVEL]      # the points fit_wu fits
    x0 = np.clip(_start(T, y), np.array(LOWER) + 1e-9, np.array(UPPER) - 1e-9)
    ref = least_squares(lambda c: rm.wu_curve(T, c) - y, x0, jac=lambda c: _jacobian(T, c), bounds=(LOWER, UPPER),
                        loss=loss, f_scale=0.01, x_scale="jac", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=20000)
    assert np.allclose(f.c, ref.x, rtol=1e-6, atol=1e-8)
    assert f.Theta_c == pytest.approx(rm.wu_crossing(tuple(ref.x)), rel=1e-7)
