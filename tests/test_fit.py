"""Fit of eq. 4.5: recovery of known curves from noisy data, exclusion of sliding points, Theta_c."""
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
