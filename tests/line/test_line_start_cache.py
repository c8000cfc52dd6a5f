"""The solves of one accuracy sequence share their converged FMG start grids
(``solve_line_problem(start_cache=...)``): a later solve starts its dense Newton on the start
grid an earlier one converged on, from that solution. An accuracy sequence solves the same start
grid again for every finer grid, and at M = 3000 that is a dense Newton solve of 2049 points
(3-4 s) each time. The cached solution is only a start: FAS cycles (on a grid with coarser grids
below it) or Newton check it, and the answer is the one a fresh solve gives. Solves outside a sequence keep nothing, so they repeat bit for bit."""

from __future__ import annotations

import pytest

from ehl_multigrid.line import solve_line
from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.line.solver import solve_line_problem

PB = LineProblem.from_moes(1000, 10)


def test_a_later_solve_of_a_sequence_starts_from_the_start_grid_an_earlier_one_converged_on():
    starts: dict = {}
    first = solve_line_problem(PB, points=2049, start_cache=starts)
    # M = 1000: 257 and 513 points hold no positive film; the start is 1025
    assert any("moved to 1025 points" in a for a in first.actions)
    assert sum(v is not None for v in starts.values()) == 1  # the grids without a start: None
    again = solve_line_problem(PB, points=4097, start_cache=starts)
    # straight to the 1025-point start, no failed coarser attempts, no Newton iteration there
    assert not any("non-positive film" in a for a in again.actions)
    assert any("FMG started" in a and "1025-point" in a for a in again.actions)
    fresh = solve_line_problem(PB, points=4097)
    assert again.work_units < fresh.work_units
    for key in ("Hc_venner", "Hm_venner"):
        assert again.scalars[key] == pytest.approx(fresh.scalars[key], rel=1e-9)


def test_solves_outside_a_sequence_repeat_bit_for_bit():
    a, b = (solve_line(1000, 10, points=2049, estimate=False) for _ in range(2))
    assert a.scalars["Hc_venner"] == b.scalars["Hc_venner"] and a.work_units == b.work_units
