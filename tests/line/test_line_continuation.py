"""Continuation in M for line contacts whose start grids hold no positive film.

Isoviscous (M, L) = (5000, 0): the dense Newton start (up to 2049 points) gives a non-positive
discrete film on every start grid, so the solve ends ``start_failed``; started from the
solution at M = 2500 it converges (line.solver.CONTINUATION_HALVINGS)."""

import pytest

from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.line.solver import continued_in_m, neighbour_problem, solve_line_problem
from ehl_multigrid.multigrid.accuracy import estimate_error
from ehl_multigrid.multigrid.options import LineOptions


@pytest.fixture(scope="module")
def heavy():
    return LineProblem.from_moes(5000.0, 0.0), LineOptions(points=4097, raise_on_failure=False)


def test_neighbour_keeps_alpha_pmax_equal_to_alpha_bar():
    pb = LineProblem.from_moes(2000.0, 10.0)
    q = neighbour_problem(pb, 0.5)
    assert q.M == 1000.0 and q.L == pb.L
    assert q.alpha * q.pmax == pytest.approx(LineProblem.from_moes(1000.0, 10.0).alpha_bar, rel=1e-12)


@pytest.mark.solver
def test_start_that_holds_no_film_is_continued_from_half_the_load(heavy):
    pb, opts = heavy
    starts: dict = {}
    assert solve_line_problem(pb, opts, start_cache=starts).status_name == "start_failed"
    sol = continued_in_m(pb, opts, start_cache=starts)
    assert sol is not None and sol.success
    assert "continued in M from 2500 -> 5000" in sol.actions[-1]
    # the start grids the failed solve found without a positive film are not solved again
    assert not any("non-positive film" in a and "M = 5000" in a for a in sol.actions)
    assert sol.H.min() > 0.0 and sol.problem.M == 5000.0
    # the residual stop leaves this grid's films far from its discrete solution (the films
    # move by 10 % after the residual is met): the iteration part of the estimate must say so
    est = estimate_error(sol, (0.0, 0.0))
    # the discrete solution: cycles on the finest grid from the continued one (its start grids
    # fail again, as above, and the solve would end up there anyway)
    tight = solve_line_problem(pb, opts, guess=(sol.X, sol.P, sol.H0), from_guess=True, tol=1e-7,
                               tol_load=1e-8, max_cycles=100)
    assert tight.success
    for k in ("Hc", "Hm"):
        assert abs(sol.scalars[k] / tight.scalars[k] - 1.0) <= est.budget["algebraic"][k]
