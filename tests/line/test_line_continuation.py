"""Continuation in M for line contacts whose start grids hold no positive film.

Isoviscous (M, L) = (5000, 0): the dense Newton start (up to 2049 points) gives a non-positive
discrete film on every start grid, so the solve ends ``start_failed``; started from the
solution at M = 2500 it converges (line.solver.CONTINUATION_HALVINGS)."""

import pytest

from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.line.solver import (
    MAX_START_POINTS,
    continued_in_m,
    from_start_grid,
    neighbour_problem,
    solve_line_problem,
)
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


def assert_within_algebraic_part(pb: LineProblem, opts: LineOptions, sol) -> None:
    """The films of ``sol`` lie within its stated algebraic part of the discrete solution:
    cycles on the finest grid from ``sol`` to a tight residual (its start grids fail again, and
    the solve would end up there anyway)."""
    est = estimate_error(sol, (0.0, 0.0))
    tight = solve_line_problem(pb, opts, guess=(sol.X, sol.P, sol.H0), from_guess=True, tol=1e-7,
                               tol_load=1e-8, max_cycles=100)
    assert tight.success
    for k in ("Hc", "Hm"):
        assert abs(sol.scalars[k] / tight.scalars[k] - 1.0) <= est.budget["algebraic"][k]


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
    assert_within_algebraic_part(pb, opts, sol)


@pytest.mark.solver
def test_start_that_holds_no_film_is_solved_from_the_start_grids_discrete_solution(heavy):
    """Before the continuation in M: cycles on the finest grid from the largest start grid's
    discrete solution (film not positive there), which the failed solve leaves behind (on 8193
    points: on 4097 the cycles from it diverge, and the continuation is left to do it)."""
    pb = heavy[0]
    opts = LineOptions(points=8193, film_tol=2.5e-4, raise_on_failure=False)
    starts: dict = {}
    filmless: dict = {}
    first = solve_line_problem(pb, opts, start_cache=starts, filmless_starts=filmless)
    assert first.status_name == "start_failed"
    (X, P, H0), = filmless.values()
    assert X.size == MAX_START_POINTS and P.max() > 0.5
    sol = from_start_grid(pb, opts, filmless, start_cache=starts)
    assert sol is not None and sol.success and sol.H.min() > 0.0
    assert "from the 2049-point start grid's solution" in sol.actions[-1]
    # the same discrete solution as the continuation's, within the stated algebraic error
    assert_within_algebraic_part(pb, opts, sol)


def test_without_a_filmless_start_grid_solution_nothing_is_tried():
    pb = LineProblem.from_moes(5000.0, 0.0)
    assert from_start_grid(pb, LineOptions(points=4097), {}) is None
