"""Chevalier's exponent from the flooded inlet (``delta = "inlet"``), checked against the
package's mass-conserving starved solvers (thesis (6.1)-(6.4); Chevalier et al. 1998)."""

import math

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import Scene, load_scene
from ehl_multigrid.model.starvation import INLET_HC_RANGE_ELLIPTIC, INLET_THETA_RANGE
from ehl_multigrid.multigrid.rheology import density
from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.point.solve import solve_fas
from ehl_multigrid.starved.point import STARVED_TOL, solve_starved_point
from mixed.sharing import fitted_film, load_sharing
from mixed.starvation import INLET_HC_RANGE, LINE_INLET_DELTA, chevalier_reduction, inlet_delta
from mixed.stribeck import stribeck_curve


def _supplied_with_the_flooded_film(pb):
    """``(Hc_ff, Hc/Hc_ff, r)`` of the starved point solver (129^2, half domain) supplied with
    the flooded central film, ``r = Hoil/(Hc_ff rho_c)`` with rho at the flooded centre."""
    ff = solve_fas(pb, points=129, half=True, wedge_order=1, tol=STARVED_TOL, max_cycles=40)
    Hff = ff.scalars["Hc_venner"]
    i0 = int(np.argmin(np.abs(ff.X)))
    rho_c = float(density(float(ff.P[0, i0]), ff.problem.rheology())[0])
    s = solve_starved_point(pb, Hff, points=129, half=True)
    assert s.status_name == "converged"
    return Hff, s.scalars["Hc_venner"] / Hff, 1.0 / rho_c


@pytest.mark.solver
def test_inlet_exponent_matches_the_starved_point_solver_where_3p5_does_not():
    """(20, 10), supply = the flooded central film: the solver's Hc/Hc_ff against (6.1) with
    r = Hoil/(Hc_ff rho_c) (rho at the flooded centre), as in validation/starved."""
    Hff, ratio, r = _supplied_with_the_flooded_film(problem_from_moes(20.0, 10.0))
    d = inlet_delta("point", Hff)
    assert 2.6 < d < 2.9
    assert chevalier_reduction(r, d) / ratio - 1 == pytest.approx(0.0, abs=0.015)
    assert chevalier_reduction(r, 3.5) / ratio - 1 > 0.04  # the constant exponent is 4-6 % high here


def test_line_inlet_exponent_is_the_mass_balance_limit():
    """The starved line solver gives Hc/Hc_ff = min(r, 1) (no side flow); (6.1) at delta 20
    stays within 0.5 % of it away from the knee and within 3.5 % (2^(-1/20)) at r = 1."""
    assert inlet_delta("line", 0.3) == LINE_INLET_DELTA
    r = np.array([0.2, 0.5, 0.8, 1.25, 2.0, 5.0])
    assert np.allclose(chevalier_reduction(r, LINE_INLET_DELTA), np.minimum(r, 1.0), rtol=5e-3)
    assert chevalier_reduction(1.0, LINE_INLET_DELTA) == pytest.approx(2 ** (-1 / 20))


def test_inlet_exponent_is_held_outside_the_measured_films():
    lo, hi = INLET_HC_RANGE
    assert inlet_delta("point", lo / 10) == pytest.approx(inlet_delta("point", lo))
    assert inlet_delta("point", hi * 10) == pytest.approx(inlet_delta("point", hi))
    assert inlet_delta("point", 0.2) > inlet_delta("point", 0.4)  # thicker inlet film, softer knee
    with pytest.raises(InputError, match="hc_venner"):
        inlet_delta("point", -1.0)


def test_inlet_exponent_in_the_stribeck_curve_keeps_the_film_monotone_and_bounded():
    sc = load_scene("chapter6_starved_0.5GPa").with_supply(delta="inlet")
    us = np.geomspace(0.01, 100.0, 40)
    hoil = 1.5 * sc.roughness.Rq
    c = stribeck_curve(sc, us, hoil=hoil, transitions=False)
    fixed = stribeck_curve(sc.with_supply(delta=3.5), us, hoil=hoil, transitions=False)
    ok = ~c.sharing.boundary
    assert np.all(np.diff(c.sharing.hfr[ok]) > 0)
    assert np.all(c.sharing.hfr[ok] < c.sharing.hc_fit[ok])
    d = c.sharing.delta_used[ok]
    assert np.all((d > 2.0) & (d < 4.0)) and np.ptp(d) > 0.05
    # a smaller exponent bends the knee earlier: a thinner starved film than delta = 3.5
    assert np.all(c.sharing.hfr[ok] <= fixed.sharing.hfr[ok] * (1 + 1e-12))
    # the transition speeds use the same exponent as the curve
    f = fitted_film(sc, 50.0, 1.0, hoil=hoil)
    f35 = fitted_film(sc, 50.0, 1.0, hoil=hoil, delta=3.5)
    assert f < f35


def test_delta_input_is_checked():
    sc = load_scene("chapter6_starved_0.5GPa")
    with pytest.raises(InputError, match="supply.delta"):
        sc.with_supply(delta="solver")
    with pytest.raises(InputError, match="supply.delta"):
        sc.with_supply(delta=40.0)
    with pytest.raises(InputError, match="delta"):
        load_sharing(sc, [1.0], hoil=sc.roughness.Rq, delta="auto")
    assert sc.with_supply(delta="inlet").supply.delta == "inlet"
    assert math.isinf(sc.with_supply(delta="inlet").supply.hoil)


def test_inlet_exponent_is_refused_for_elliptic_contacts_outside_the_measured_ellipticity():
    # the 6205 inner race: b/a 9.4, theta = Rx/Ry far below 0.25
    sc = load_scene("bearing_6205_inner_race").to_dict()
    sc["roughness"] = load_scene("series_C_disc3_1.93GPa").to_dict()["roughness"]
    ell = Scene.from_dict(sc).with_supply(delta="inlet")
    assert ell.theta < INLET_THETA_RANGE[0]
    with pytest.raises(InputError, match=r"elliptic contacts with theta .* \[0.25, 4\]"):
        load_sharing(ell, [1.0], hoil=ell.roughness.Rq)
    with pytest.raises(InputError, match="theta"):
        inlet_delta("elliptic", 0.1, 5.0)


@pytest.mark.solver
@pytest.mark.parametrize(("M", "L", "theta"), [(300.0, 5.0, 0.25), (50.0, 10.0, 4.0)])
def test_elliptic_inlet_exponent_matches_the_starved_point_solver_where_the_circular_rule_does_not(M, L, theta):
    """Supply = the flooded central film, as the circular test above: the wide contact (theta
    0.25, little side flow) has a sharper knee than the circular rule says, the narrow one a
    softer one (validation/starved/study_collapse_elliptic.py)."""
    Hff, ratio, r = _supplied_with_the_flooded_film(problem_from_moes(M, L, theta))
    rule = abs(chevalier_reduction(r, inlet_delta("elliptic", Hff, theta)) / ratio - 1)
    circular = abs(chevalier_reduction(r, inlet_delta("point", Hff)) / ratio - 1)
    assert rule < 0.02
    assert circular > 2.0 * rule


def test_elliptic_inlet_exponent_joins_the_circular_rule_at_theta_one():
    h = np.geomspace(INLET_HC_RANGE[0], INLET_HC_RANGE_ELLIPTIC[1], 7)
    assert np.allclose(inlet_delta("elliptic", h, 1.0), inlet_delta("point", h), atol=1e-12)
    # wider contacts (smaller theta) lose less oil sideways: a larger exponent
    assert inlet_delta("elliptic", 0.1, 0.25) > inlet_delta("elliptic", 0.1, 1.0) > inlet_delta("elliptic", 0.1, 4.0)


def test_an_elliptic_scene_takes_the_elliptic_inlet_exponent_in_the_mixed_layer():
    d = load_scene("chapter6_starved_0.5GPa").to_dict()
    d["geometry"]["Ry"] = 2.0 * d["geometry"]["Rx"]  # theta = Rx/Ry = 0.5
    d["contact"]["kind"] = "elliptic"
    ell = Scene.from_dict(d).with_supply(delta="inlet")
    assert ell.theta == pytest.approx(0.5)
    ls = load_sharing(ell, [0.1, 1.0, 10.0], hoil=1.5 * ell.roughness.Rq)
    d_used = ls.delta_used[np.isfinite(ls.delta_used)]
    assert d_used.size and np.all((d_used > 3.0) & (d_used < 5.0))


def test_flooded_elliptic_contact_needs_no_exponent():
    d = load_scene("bearing_6205_inner_race").to_dict()
    d["roughness"] = load_scene("series_C_disc3_1.93GPa").to_dict()["roughness"]
    ell = Scene.from_dict(d).with_supply(delta="inlet")
    ls = load_sharing(ell, [1.0, 10.0])  # flooded: the exponent is never used
    assert np.all(np.isnan(ls.delta_used))
