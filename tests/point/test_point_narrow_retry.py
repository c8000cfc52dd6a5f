"""A contact narrower than long whose FMG start diverges on the automatic coarse grid is
solved again from four times as many coarse intervals (``RETRY_FINER_START``), and a narrow
contact at high M that the grid cannot resolve says how many points it needs
(``min_points(..., cap=None)``, thesis-independent measurements in point/problem.py)."""

import pytest

import ehl_multigrid.point.solve as solve_mod
from ehl_multigrid.point.problem import NARROW_BELOW, min_points, problem_from_moes
from ehl_multigrid.point.solve import solve_fas


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


def test_diverged_narrow_contact_is_solved_again_from_a_finer_coarse_grid(narrow, monkeypatch):
    monkeypatch.setattr(solve_mod, "RETRY_COARSER_START", False)
    monkeypatch.setattr(solve_mod, "RETRY_FINER_START", False)
    before = solve_fas(narrow, points=1025, half=True, raise_on_failure=False)
    assert before.status_name == "diverged"
    monkeypatch.setattr(solve_mod, "RETRY_FINER_START", True)
    sol = solve_fas(narrow, points=1025, half=True, raise_on_failure=False)
    assert any("256 coarse intervals instead of 64 (RETRY_FINER_START)" in a for a in sol.actions)
    # the iteration now converges, to a film the grid cannot make positive: said, with the grid
    assert sol.status_name == "film_not_positive"
    assert "use points >= 4097" in sol.message
    assert "b/a = 0.222" in sol.message
