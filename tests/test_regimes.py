"""The regime boundaries of an oblique impact (no spin), checked against the exact tangential reference
(``mdr``, the method of dimensionality reduction) on an elastic (EE) and a plastic (PE, e_n 0.70) impact:
sliding from first touch iff kappa tan(theta_i) > mu, through the whole compression iff
tan(theta_i) >= 3.5 mu, until separation iff Theta >= 7 - 2 e_n / (kappa (1 + e_n))."""
import math

import numpy as np
import pytest

import dem_contact as dc
from dem_contact.impacts.presets import preset_scene
from dem_contact.impacts.sweep import critical_angle
from dem_contact.rebound import models as rm

STEPS = 2000


def _ratio(scene, vn, tan_theta):
    r = dc.impact(scene, vn=vn, vt=vn * tan_theta, series=True, steps_per_contact=STEPS)
    s = r.series
    return r, np.abs(s["tangential_force"]) / (scene.mu * np.maximum(s["normal_force"], 1e-300)), s


@pytest.mark.parametrize("case", ["EE", "PE"])
def test_sliding_from_first_touch(case):
    """2% of the contact time in, the contact is at the Coulomb limit just above the boundary and
    below it just under it (the ratio there is kappa tan(theta_i) / mu, Mindlin's no-slip loading)."""
    sc = preset_scene(case, 5.0, tangential="mdr")
    k = sc.pair.kappa
    early = STEPS // 50
    above, ra, _ = _ratio(sc, 5.0, 1.02 * sc.mu / k)
    below, rb, _ = _ratio(sc, 5.0, 0.98 * sc.mu / k)
    assert ra[early] == pytest.approx(1.0, abs=1e-6)
    assert rb[early] < 0.99
    assert above.Theta > rm.regime_boundaries(k, above.e_n)["initial_sliding"] > below.Theta


@pytest.mark.parametrize("case", ["EE", "PE"])
def test_sliding_through_the_compression(case):
    """The contact slides at every step of the compression from tan(theta_i) = 3.5 mu on, whatever kappa
    and e_n (not from (7 kappa - 3)/kappa), and sticks somewhere in it just below."""
    sc = preset_scene(case, 5.0, tangential="mdr")
    for fac, slides in ((1.02, True), (0.98, False)):
        r, ratio, s = _ratio(sc, 5.0, fac * 3.5 * sc.mu)
        peak = int(np.argmax(s["overlap"]))
        lowest = ratio[1:peak + 1].min()
        assert (lowest > 1.0 - 1e-3) == slides, (fac, lowest)
        assert (r.Theta >= rm.regime_boundaries(sc.pair.kappa, r.e_n)["compression_sliding"]) == slides


@pytest.mark.parametrize("vn", [2.0, 5.0])
def test_persistent_sliding_with_restitution(vn):
    """PE (e_n 0.86 and 0.70) with the Hertz-shaped plastic Coulomb limit, whose unloading is the elastic
    one that the criterion assumes: the direct Theta_c is 7 - 2 e_n / (kappa (1 + e_n)) (not eq. 4.1)."""
    sc = preset_scene("PE", vn, mdr_profile="scaled")
    crit = critical_angle(sc, vn, tol_deg=1e-4)
    theory = rm.theta_c_theory(sc.pair.kappa, crit.e_n)
    assert crit.Theta == pytest.approx(theory, rel=5e-4)
    assert abs(crit.Theta - rm.theta_c_theory(sc.pair.kappa)) > 0.05     # eq. 4.1 (e_n = 1) is off
    assert math.isclose(rm.regime_boundaries(sc.pair.kappa, crit.e_n)["persistent_sliding"], theory)
