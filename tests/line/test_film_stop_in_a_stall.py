"""An accuracy-driven solve stops on its films' change per cycle (``film_tol``); a V-cycle
stall can hold the films still far from the discrete solution. Line Roelands +
Dowson-Higginson (M, L) = (500, 20) at 16385 points, ``accuracy=0.0025`` (the fit map's check
solve): V cycles alone stop after 4 cycles, residual 2.6e-5 (tol 1e-5), with Hm 1 % above the
discrete solution and a stated algebraic error of 8e-5. An early stop (residual above its
tolerance) of a V- or F-cycle solve is therefore confirmed by one W cycle
(``confirm_early_stop``, an option of every multilevel solve).

The stall came from the outlet pressure drop, where the line relaxation's frozen ``eps`` cannot
settle; the local Newton solve there (``LineOptions.local_newton``, the default since) removes
it, so the stall is reproduced here with ``local_newton=None``, and the default solve is
tested against the same discrete solution.

The discrete solution (``deep``) is solved with F cycles to ``tol = 1e-8``: they do not stall
on this case (V cycles do, and get there only after the switch to W cycles, with 1.5x the work)."""

import pytest

from ehl_multigrid.line import solve_line
from ehl_multigrid.multigrid.accuracy import correction_factors

CASE = dict(M=500.0, L=20.0, points=16385, local_newton=None)


# every test reads the module's discrete solution: one worker builds it once
pytestmark = [pytest.mark.solver, pytest.mark.xdist_group("film_stop_in_a_stall_deep")]


@pytest.fixture(scope="module")
def deep():
    sol = solve_line(**CASE, estimate=False, tol=1e-8, tol_load=1e-9, max_cycles=200, cycle="F")
    assert sol.success and sol.residual_history[-1] < 1e-8, sol.message
    return sol


def _film_stopped(**kw):
    return solve_line(**CASE, accuracy=0.0025, raise_on_failure=False, **kw)


def _own(r, k: str) -> float:
    """The film of ``r``'s own grid (an accuracy-driven result reports films extrapolated over
    the grids: the discrete solution is compared with what the iteration reached)."""
    fc, fm = correction_factors(r.extra.get("film_correction"))
    return r.scalars[k] / (fc if k == "Hc" else fm)


@pytest.fixture(scope="module")
def confirmed():
    """The default film stop (confirmed by a W cycle), read by two tests."""
    return _film_stopped()


def test_v_cycle_film_stop_without_confirmation_is_one_percent_off(deep):
    r = _film_stopped(confirm_early_stop=False)
    assert abs(_own(r, "Hm") / deep.scalars["Hm"] - 1.0) > 5e-3


def test_confirmed_film_stop_is_close_to_the_discrete_solution(deep, confirmed):
    r = confirmed
    assert abs(_own(r, "Hm") / deep.scalars["Hm"] - 1.0) < 5e-4
    assert abs(_own(r, "Hm") / deep.scalars["Hm"] - 1.0) < r.scalars["Hm_error"]


@pytest.mark.xfail(strict=True, reason="Hm still drifts by 2e-4 after the confirmed stop: 2.6x "
                   "its stated algebraic part (the total estimate, 0.45 %, covers it)")
def test_confirmed_film_stop_hm_within_its_algebraic_estimate(deep, confirmed):
    r = confirmed
    true = abs(_own(r, "Hm") / deep.scalars["Hm"] - 1.0)
    assert true <= r.extra["error_budget"]["algebraic"]["Hm"]


def test_with_local_newton_the_film_stop_is_within_its_algebraic_estimate(deep):
    case = {**CASE, "local_newton": 1025}
    r = solve_line(**case, accuracy=0.0025, raise_on_failure=False)
    true = abs(_own(r, "Hm") / deep.scalars["Hm"] - 1.0)
    # measured: 1.3e-6 against a stated algebraic part of 4.8e-4 (without: 2.3e-4 against 9e-5)
    assert true <= r.extra["error_budget"]["algebraic"]["Hm"]
    assert abs(_own(r, "Hc") / deep.scalars["Hc"] - 1.0) <= r.extra["error_budget"]["algebraic"]["Hc"]
