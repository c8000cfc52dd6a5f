"""Point solves that cannot reach their tolerance say why: a residual asked below the
relaxation's floor ends ``residual_floor`` with settled films, not ``diverged``
(``POINT_POLICY.quiet_below``); a steep Barus solve that diverges names the cause."""

import re

import pytest

from ehl_multigrid.point import solve_point


@pytest.mark.solver
def test_a_tolerance_below_the_floor_ends_at_the_floor_with_settled_films():
    common = dict(points=513, half=True, far_field=False, estimate=False, raise_on_failure=False, threads=1)
    deep = solve_point(20, 10, tol=1e-9, tol_load=1e-6, max_cycles=60, grid_stop=None, **common)
    # before: a cycle at 4.9e-9 after 1.5e-9 was rejected as growth, the stall steps stirred
    # the iterate and the solve ended "diverged"
    assert deep.status_name == "residual_floor", deep.message
    # the message names the residual it stopped at and the tolerance asked
    assert re.search(r"\b\d\.?\d*e-0[6-9]\b.*\(tol 1e-09\)", deep.message), deep.message
    assert deep.residual_history[-1] < 1e-5
    assert not any("rejected" in a for a in deep.actions)
    ref = solve_point(20, 10, tol=1e-7, tol_load=1e-6, grid_stop=None, **common)
    assert ref.success
    for h in ("Hc", "Hm"):
        assert abs(deep.scalars[h] / ref.scalars[h] - 1.0) < 1e-6


@pytest.mark.solver
def test_a_diverged_steep_barus_solve_says_why_and_names_roelands():
    # circular-ish theta 4, alpha_bar 49.6: diverges on 257 points, also from the finer start
    # (the fit-check map's (20, 20), alpha_bar 33, diverges only from 1025 points, at 2-4 times the cost)
    sol = solve_point(20, 30, theta=4, viscosity="barus", density="incompressible", points=257,
                      estimate=False, raise_on_failure=False, far_field=False)  # as measured
    assert sol.status_name == "diverged"
    assert "alpha_bar = 49.6" in sol.message and "Roelands" in sol.message


def test_a_failed_solve_with_a_piezoviscous_peak_far_above_hertz_says_why():
    # Roelands (1, 25, theta 10): the iterate stalls and diverges with P = 13-14 at its peak
    # (14 GPa) on 257 and 513 points; the converged (1, 10, theta 10) peaks at 6.4. (1, 30,
    # theta 10) diverges on 129 points with P = 10.9 (13.3 GPa), in a seventh of the time
    sol = solve_point(1, 30, theta=10, points=129, estimate=False, raise_on_failure=False,
                      far_field=False)  # P = 0, as measured (the far field's iterate peaks at 5.9)
    assert not sol.success
    # the reason names the peak pressure (dimensionless and in GPa) and the Roelands law
    assert re.search(r"P = 1[0-4](\.\d+)? \(1[0-5](\.\d+)? GPa\)", sol.message), sol.message
    assert "Roelands" in sol.message
    assert sol.P.max() > 10.0


def test_the_piezoviscous_peak_reason_needs_a_peak_above_its_threshold():
    import numpy as np

    from ehl_multigrid.point.problem import problem_from_moes
    from ehl_multigrid.point.solve import PIEZOVISCOUS_PEAK, piezoviscous_peak_reason

    pb = problem_from_moes(1, 25, 10.0)
    assert piezoviscous_peak_reason(pb, np.array([0.0, 0.9 * PIEZOVISCOUS_PEAK])) == ""
    assert piezoviscous_peak_reason(pb, np.array([0.0, np.nan, 20.0])) == ""  # a NaN field says nothing
    why = piezoviscous_peak_reason(pb, np.array([0.0, 14.0]))
    assert "P = 14 (14.2 GPa)" in why and "10^47 times" in why
    # at high M such a peak in a failed iterate is the divergence, not the regime
    assert piezoviscous_peak_reason(problem_from_moes(5000, 25, 10.0), np.array([0.0, 14.0])) == ""
