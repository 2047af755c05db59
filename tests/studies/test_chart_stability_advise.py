"""Speed-accuracy chart, stability map and advise: small runs that check what they report."""
import math

import numpy as np
import pytest

import dem_contact as dc
from dem_contact.studies import advise as adv
from dem_contact.studies import chart, stability
from dem_contact.impacts.impact import build_result
from dem_contact.impacts.integrator import N_OUT, O_COULOMB, O_FMAX, O_TC, O_PN, O_PT, O_STATUS, O_VN


def test_chart_errors_and_pareto():
    """mdr against its own converged reference has tiny model error; md's model error is the known
    ~0.02-0.03 deficit near Theta = 1; discretisation error falls with steps; the Pareto front is
    non-dominated."""
    rows = chart.chart(laws=["md", "mdr_adaptive"], normals=["hertz"], schemes=["located"], steps=[20, 200],
                       n_theta=11, repeats=1)
    by = {(r.tangential, r.steps_per_contact): r for r in rows}
    assert by[("mdr_adaptive", 200)].model_err_f_over_mu < 2e-3
    assert 0.01 < by[("md", 200)].model_err_f_over_mu < 0.05
    for law in ("md", "mdr_adaptive"):
        assert by[(law, 200)].discretisation_err_f_over_mu < by[(law, 20)].discretisation_err_f_over_mu
    front = [r for r in rows if r.pareto]
    for r in front:
        assert not any(o.time_per_impact_us < r.time_per_impact_us and o.err_f_over_mu < r.err_f_over_mu
                       for o in rows)


@pytest.mark.parametrize("case,law,outcome", [
    (stability.Case("2 steps", steps=2.0), "md", "blow-up"),             # e_n = 1.6 > 1: a numerical failure
    (stability.Case("mu = 1e4", mu=1e4), "md", "energy"),                 # ill-conditioned md at huge mu
    (stability.Case("nu = 0", nu=0.0, angle_deg=10.0), "mindlin_total", "energy"),
    (stability.Case("2 steps", steps=2.0), "mdr", "blow-up"),            # contact outgrows the springs
    (stability.Case("5 steps", steps=5.0), "md", "inaccurate"),          # coarse: flagged by a warning
    (stability.Case("89.9 deg", angle_deg=89.9), "mdr_adaptive", "ok"),
    (stability.Case("V/V_y = 1e3", plastic_ratio=1e3), "mdr_adaptive", "ok"),
])
def test_stability_classes(case, law, outcome):
    ref = stability._run(case, "mdr", "located", 400)
    row = stability.classify(case, law, "located", ref)
    assert row.outcome == outcome
    if outcome in ("energy", "inaccurate"):
        assert row.detail     # the library's own warning is reported


def test_coulomb_excess_is_flagged(steel_sphere, steel_wall):
    """The Coulomb check of build_result: an output row with |T| > mu N is reported as a warning."""
    sc = dc.Scene(steel_sphere, steel_wall, mu=0.3)
    out = np.zeros(N_OUT)
    out[O_VN], out[O_PN], out[O_PT], out[O_FMAX], out[O_COULOMB], out[O_STATUS] = -5.0, 1.0, 0.1, 1e4, 1.0, 0
    out[O_TC] = 5e-5
    with pytest.warns(RuntimeWarning, match="Coulomb"):
        r = build_result(sc, out, 5.0, 1.0, 0.0, 0.0, 1e-7, 100.0, "located")
    assert r.coulomb_violation == 1.0


def test_advise_recommends_sliding_above_critical_angle(steel_sphere, steel_wall):
    """Above the critical angle (Theta > Theta_c, Wu, Thornton & Li 2009, section 4) the rigid-body sliding formulas are
    exact: advise measures ~0 error for them and recommends them; below it sliding is wrong by f/mu."""
    sc = dc.Scene(steel_sphere, steel_wall, mu=0.1)
    # Theta = 2 tan(angle) / (2 mu) > 10 for angles above 45 deg at mu = 0.1
    a = adv.advise(sc, (2.0, 5.0), (50.0, 80.0), tol=1e-3, n_speeds=2, n_angles=4, verify=True)
    assert a.recommended.name == "sliding"
    assert a.recommended.error < 1e-5
    assert a.verification["passed"]
    b = adv.advise(sc, (2.0, 5.0), (0.0, 10.0), tol=1e-3, n_speeds=1, n_angles=4)
    sliding = next(c for c in b.candidates if c.name == "sliding")
    assert not sliding.meets and sliding.error > 0.5
    assert b.recommended is not None and b.recommended.error <= 1e-3
    assert all(math.isfinite(c.time_us) and c.time_us > 0 for c in b.candidates)
