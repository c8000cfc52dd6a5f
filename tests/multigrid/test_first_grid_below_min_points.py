"""An accuracy-driven steady solve whose first grid fails below the smallest grid the solver
converges on for the load (``solve_to_accuracy(min_points=...)``, from
``point.problem.min_points`` uncapped) moves to the next grid: the planner caps its first grid
at 2049 points, and circular theta 10 at (5000, 10) ends ``max_cycles`` there while it needs
8193 (docs/robustness.md, "Point solver defaults")."""

from types import SimpleNamespace

import pytest

from ehl_multigrid.multigrid.accuracy import _SteadyControl
from ehl_multigrid.multigrid.controller import Resolution
from ehl_multigrid.point.problem import min_points


def _control(min_pts: int) -> _SteadyControl:
    return _SteadyControl(None, None, None, 0.02, True, 8193, 4.0, 2, min_points=min_pts)


@pytest.mark.parametrize("status", ["max_cycles", "diverged", "stalled"])
def test_a_failed_first_grid_below_the_smallest_for_the_load_moves_to_the_next(status):
    failed = SimpleNamespace(status_name=status)
    need = min_points(5000.0, 0.222, cap=None)
    assert need == 8193
    assert _control(need).remedy(failed, Resolution(2049), first=True) == Resolution(4097)
    # after a converged solve, or from the smallest grid on, a failure is not the grid's
    assert _control(need).remedy(failed, Resolution(2049), first=False) is None
    assert _control(need).remedy(failed, Resolution(8193), first=True) is None
    assert _control(0).remedy(failed, Resolution(2049), first=True) is None


def test_a_grid_without_a_positive_film_still_moves_to_the_next():
    assert _control(0).remedy(SimpleNamespace(status_name="film_not_positive"), Resolution(257),
                              first=False) == Resolution(513)
