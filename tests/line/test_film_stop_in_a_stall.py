"""Known defect, pinned (strict xfail): an accuracy-driven solve stops on its films' change per
cycle (``film_tol``) without a residual condition, and a V-cycle stall can hold the films still
far from the discrete solution. Line Roelands + Dowson-Higginson (M, L) = (500, 20) at 16385
points, ``accuracy=0.0025`` (the fit map's check solve): it stops after 4 finest cycles with the
residual at 2.6e-5 (tol 1e-5) falling ever more slowly (ratios 0.53, 0.66, 0.76, 0.87) and Hm
1 % above the discrete solution, while its algebraic estimate says 8e-5. The residual-stopped
solve stalls at the same place until its stall rule switches to W cycles, then converges to
that Hm (Hc agrees to 1e-4). When the film stop is fixed, this test passes and the xfail
goes."""

import pytest

from ehl_multigrid.line import solve_line


@pytest.mark.xfail(strict=True, reason="film stop in a V-cycle stall (see module docstring)")
def test_film_stopped_solve_has_hm_within_its_algebraic_estimate():
    acc = solve_line(500, 20, points=16385, accuracy=0.0025, raise_on_failure=False)
    deep = solve_line(500, 20, points=16385, estimate=False, tol=1e-6)
    stated = acc.extra["error_budget"]["algebraic"]["Hm"]
    true = abs(acc.scalars["Hm"] / deep.scalars["Hm"] - 1.0)
    assert true <= stated
