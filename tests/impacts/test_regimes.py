"""The regime boundaries of an oblique impact (no spin), checked against the exact tangential reference
(``mdr``, the method of dimensionality reduction) on an elastic (EE) and a plastic (PE, e_n 0.70) impact:
sliding from first touch iff kappa tan(theta_i) > mu, through the whole compression iff
tan(theta_i) >= 3.5 mu, until separation iff Theta >= 7 - 2 e_n / (kappa (1 + e_n))."""
import numpy as np
import pytest

import dem_contact as dc
from dem_contact.impacts.presets import preset_scene
from dem_contact.impacts.sweep import critical_angle
from dem_contact.laws.model import MDR_STEPS_PER_CONTACT
from dem_contact.rebound import models as rm

STEPS = 2000


def _ratio(scene, vn, tan_theta):
    r = dc.impact(scene, vn=vn, vt=vn * tan_theta, series=True, steps_per_contact=STEPS)
    s = r.series
    return r, np.abs(s["tangential_force"]) / (scene.mu * np.maximum(s["normal_force"], 1e-300)), s


def _vt_at(sc, vn, boundary, fac):
    """Tangential speed whose Theta is ``fac`` times the regime boundary ``boundary`` of
    ``rm.regime_boundaries`` (with the e_n of the head-on impact: Theta = 2 vt / ((1 + e_n) mu vn))."""
    e_n = dc.impact(sc, vn=vn).e_n
    theta = fac * rm.regime_boundaries(sc.pair.kappa, e_n)[boundary]
    return theta * (1.0 + e_n) * sc.mu * vn / 2.0


@pytest.mark.parametrize("case", ["EE", "PE"])
def test_sliding_from_first_touch(case):
    """2% of the contact time in, the contact is at the Coulomb limit just above the boundary and
    below it just under it (the ratio there is kappa tan(theta_i) / mu, Mindlin's no-slip loading)."""
    sc = preset_scene(case, 5.0, tangential="mdr")
    early = STEPS // 50
    _, ra, _ = _ratio(sc, 5.0, _vt_at(sc, 5.0, "initial_sliding", 1.02) / 5.0)
    _, rb, _ = _ratio(sc, 5.0, _vt_at(sc, 5.0, "initial_sliding", 0.98) / 5.0)
    assert ra[early] == pytest.approx(1.0, abs=1e-6)
    assert rb[early] < 0.99


@pytest.mark.parametrize("case", ["EE", "PE"])
def test_sliding_through_the_compression(case):
    """The contact slides at every step of the compression from tan(theta_i) = 3.5 mu on, whatever kappa
    and e_n (not from (7 kappa - 3)/kappa), and sticks somewhere in it just below."""
    sc = preset_scene(case, 5.0, tangential="mdr")
    for fac, slides in ((1.02, True), (0.98, False)):
        _, ratio, s = _ratio(sc, 5.0, _vt_at(sc, 5.0, "compression_sliding", fac) / 5.0)
        peak = int(np.argmax(s["overlap"]))
        lowest = ratio[1:peak + 1].min()
        assert (lowest > 1.0 - 1e-3) == slides, (fac, lowest)


@pytest.mark.parametrize("vn", [2.0, 5.0])
def test_persistent_sliding_with_restitution(vn):
    """PE (e_n 0.86 and 0.70), exact reference with the Hertz-shaped plastic Coulomb limit, whose unloading
    is the elastic one that the criterion assumes: the direct Theta_c is 7 - 2 e_n / (kappa (1 + e_n)) (not
    eq. 4.1)."""
    sc = preset_scene("PE", vn, tangential="mdr", mdr_profile="scaled")
    crit = critical_angle(sc, vn, tol_deg=1e-4, steps_per_contact=MDR_STEPS_PER_CONTACT)
    theory = rm.regime_boundaries(sc.pair.kappa, crit.e_n)["persistent_sliding"]
    assert crit.Theta == pytest.approx(theory, rel=5e-4)
    assert abs(crit.Theta - rm.theta_c_theory(sc.pair.kappa)) > 0.05     # eq. 4.1 (e_n = 1) is off
