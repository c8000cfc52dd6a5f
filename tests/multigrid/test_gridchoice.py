"""Grid choice from the measured grid-error constants (ehl_multigrid/multigrid/gridchoice.py)."""

import pytest

from ehl_multigrid.line import solve_line
from ehl_multigrid.multigrid.gridchoice import grid_error_constant, solver_grid


@pytest.mark.parametrize("tol", [0.1, 0.02, 0.002])
@pytest.mark.parametrize(("contact", "M"), [("line", 20.0), ("line", 500.0), ("point", 20.0), ("point", 150.0)])
def test_chosen_grid_meets_half_the_tolerance_or_is_the_largest(contact, M, tol):
    g = solver_grid(contact, M, tol)
    assert g.predicted_error <= 0.5 * tol or g.points == (16385 if contact == "line" else 1025)
    smaller = (g.points - 1) // 2 + 1
    if smaller >= (1025 if contact == "line" else 129):
        assert g.C / (smaller - 1) ** 2 > 0.5 * tol  # the next coarser grid would not do


def test_grid_error_constant_grows_with_load():
    cs = [grid_error_constant("line", M)[0] for M in (10.0, 20.0, 100.0, 500.0, 2000.0)]
    assert all(b > a for a, b in zip(cs, cs[1:], strict=False))


@pytest.mark.solver
def test_predicted_grid_error_holds_between_tabulated_loads():
    """M = 50 lies between the study's M = 20 and 100: the interpolated C predicts the error of
    Hc on 1025 points against a 16x finer solve within a factor 1.5."""
    # the films of the two solves (no error estimate: its extra solves do not change them)
    coarse = solve_line(50.0, 10.0, points=1025, estimate=False)
    fine = solve_line(50.0, 10.0, points=16385, estimate=False)
    assert coarse.converged and fine.converged
    measured = abs(coarse.Hc - fine.Hc) / fine.Hc / (1.0 - (1024 / 16384) ** 2)
    predicted = grid_error_constant("line", 50.0)[0] / 1024**2
    assert predicted / 1.5 < measured < 1.5 * predicted


def test_a_first_grid_short_of_half_the_tolerance_says_it_is_the_largest_and_refined_from():
    capped = solver_grid("point", 1000.0, 0.002)
    assert capped.points == 1025 and capped.predicted_error > 0.001
    assert "refines" in capped.first_grid_reason(0.002)
    fine = solver_grid("line", 100.0, 0.02)
    assert fine.predicted_error <= 0.01 and "refines" not in fine.first_grid_reason(0.02)
