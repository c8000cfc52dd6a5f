"""A line solve whose dense Newton start cannot hold a film returns no film."""

import math

from ehl_multigrid.line import solve_line


def test_a_failed_start_reports_nan_films_not_zero():
    # (5000, 0) on 129 points: no positive film on the start grid, nor at M = 2500, 1250 and 625
    # (the continuation in M); the same path as on the default grid, where the start grids fail
    # up to the 2049-point cap
    res = solve_line(5000, 0, points=129, raise_on_failure=False)
    assert res.status_name == "start_failed" and not res.success
    assert "not positive" in res.message
    assert all(math.isnan(res.scalars[k]) for k in ("Hc", "Hm", "Hc_venner", "Hm_venner", "X_Hm"))
