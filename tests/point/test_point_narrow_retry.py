"""A contact narrower than long whose FMG start diverges on the automatic coarse grid is
solved again from four times as many coarse intervals (``retry_finer_start``), and a narrow
contact at high M that the grid cannot resolve says how many points it needs
(``min_points(..., cap=None)``, thesis-independent measurements in point/problem.py). Both
on square cells (``y_ratio`` given); the default cells, stretched with the ellipse, converge
the same contact on the same X points."""

import re

import pytest

from ehl_multigrid.point.problem import NARROW_BELOW, min_points, problem_from_moes
from ehl_multigrid.point.solve import solve_fas

pytestmark = pytest.mark.solver


@pytest.fixture(scope="module")
def narrow():
    # theta = 10: b/a = 0.22; M = 1000, L = 0 (isoviscous, stiff): 1025 points
    return problem_from_moes(1000.0, 0.0, 10.0)


def test_narrow_contact_rule_asks_for_more_points_than_the_cap(narrow):
    assert narrow.b_over_a < NARROW_BELOW
    assert min_points(narrow.M, narrow.b_over_a) == 2049
    assert min_points(narrow.M, narrow.b_over_a, cap=None) == 4097
    assert min_points(5000.0, narrow.b_over_a, cap=None) == 8193
    # wider contacts and lighter loads keep the rule they had
    assert min_points(1000.0, 0.41, cap=None) == 1025
    assert min_points(500.0, narrow.b_over_a, cap=None) == 1025


#: square cells for b/a = 0.22 on the default box: (ny - 1)/(nx - 1) = 2^round(log2(0.22))
SQUARE = 0.25


@pytest.mark.slow  # the retry decision: test_point_retry_chain.py (no solves)
def test_diverged_narrow_contact_is_solved_again_from_a_finer_coarse_grid(narrow):
    kw = dict(points=1025, half=True, y_ratio=SQUARE, raise_on_failure=False, retry_coarser_start=False)
    before = solve_fas(narrow, retry_finer_start=False, **kw)
    assert before.status_name == "diverged"
    sol = solve_fas(narrow, **kw)
    assert any(re.search(r"\b256 coarse intervals\b.*\b64\b.*retry_finer_start", a) for a in sol.actions)
    # the iteration now converges, to a film the grid cannot make positive: said, with the grid
    assert sol.status_name == "film_not_positive"
    assert "use points >= 4097" in sol.message
    assert "b/a = 0.222" in sol.message


def test_narrow_contact_converges_on_cells_stretched_with_the_ellipse(narrow):
    # the default grid: as many points across b as along a (y_ratio 1 here), where square
    # cells leave b ~56 cells at 1025 points and the film cannot be made positive
    sol = solve_fas(narrow, points=1025, half=True, raise_on_failure=False)
    assert sol.extra["y_ratio"] == 1.0
    assert sol.status_name == "converged"
    assert sol.scalars["Hm"] > 0.0


@pytest.mark.slow  # the retry decision: test_point_retry_chain.py (no solves)
def test_diverged_solve_on_stretched_cells_is_solved_again_on_square_cells():
    # Barus (20, 20, theta 4): NaN from the first coarse cycles on stretched cells (P = 0 on
    # the boundary, as measured: with the far field the stretched cells converge)
    pb = problem_from_moes(20.0, 20.0, 4.0, viscosity="barus", density="incompressible")
    no_start_retry = dict(retry_finer_start=False, retry_coarser_start=False, far_field=False)
    before = solve_fas(pb, points=257, raise_on_failure=False, retry_square_cells=False, **no_start_retry)
    assert before.status_name == "diverged"
    sol = solve_fas(pb, points=257, raise_on_failure=False, **no_start_retry)
    assert any("retry_square_cells" in a for a in sol.actions)
    assert sol.status_name == "converged"
    assert sol.extra["y_ratio"] == 0.5  # square cells for b/a = 0.40
    assert sol.extra["square_cells_fallback"] and not before.extra["square_cells_fallback"]
    # the same discrete problem as asked for square cells directly
    direct = solve_fas(pb, points=257, y_ratio=0.5, raise_on_failure=False, far_field=False)
    assert sol.scalars["Hc"] == pytest.approx(direct.scalars["Hc"], rel=1e-12)
    assert not direct.extra["square_cells_fallback"]  # asked for, not fallen back to
