"""The contract of every normal law that takes a target restitution (``TAKES_E_N``, ``laws.table``): built with
its declared ``EXAMPLE`` settings, an impact at the default time step gives the e_n that its
``calibration_target`` promises, within the tolerance the impacts warn at (``CALIBRATION_RTOL``, ``_ATOL``),
at the speed where the calibration holds, or at speeds a decade apart where it holds at every speed."""
import pytest

import dem_contact as dc
from dem_contact.impacts.impact import CALIBRATION_ATOL, CALIBRATION_RTOL
from dem_contact.laws import table

CALIBRATED = [m.NAME for m in table.FAMILIES["normal"] if m.TAKES_E_N]


@pytest.mark.parametrize("normal", CALIBRATED)
def test_a_calibrated_law_meets_its_target(normal):
    law = table.law("normal", normal)
    sc = dc.Scene(dc.Sphere(0.01, dc.STEEL), dc.Wall(dc.STEEL), mu=0.3, normal=normal, v_ref=dc.reference_speed(2.0),
                  **law.EXAMPLE)
    target = law.calibration_target(sc)
    assert target is not None, f"{normal} takes e_n but states no calibration target"
    e, speed, what = target
    for vn in ((speed,) if speed is not None else (0.5, 5.0)):
        r = dc.impact(sc, vn, 0.0)
        assert abs(r.e_n - e) <= max(CALIBRATION_RTOL * e, CALIBRATION_ATOL), (normal, vn, r.e_n, e, what)
        assert not any("misses the target" in w for w in r.warnings)
