"""An isoviscous line solve above ``CYCLE_FLOOR_M`` cycled from a given solution coarsens to
``CYCLE_FLOOR_POINTS`` only (a 513-point coarsest grid leaves a slow film mode there), and its
accuracy sequence resumes FMG from the solve before; with a pressure viscosity the grids stay."""

from __future__ import annotations

import numpy as np
import pytest

from ehl_multigrid.line import solve_line
from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.line.solver import CYCLE_FLOOR_POINTS, line_solver
from ehl_multigrid.multigrid.options import LineOptions


def _floor_points(M: float, L: float) -> int:
    solver = line_solver(LineProblem.from_moes(M, L), LineOptions(points=16385))
    hz = solver.hierarchy
    X = np.linspace(-1.0, 1.0, 101)
    hz.guess, hz.start_on_guess = (X, np.sqrt(1.0 - X**2), -0.5), True
    assert hz.start(solver) == len(hz.levels) - 1
    return hz.levels[hz.floor].n


@pytest.mark.parametrize(("M", "L", "want"), [(3000, 0, CYCLE_FLOOR_POINTS), (5000, 0, CYCLE_FLOOR_POINTS),
                                              (2000, 0, 513), (3000, 5, 513)])
def test_a_solve_from_a_given_solution_coarsens_to_1025_points_only_when_isoviscous_above_m_2000(M, L, want):
    assert _floor_points(M, L) == want


@pytest.mark.solver
def test_isoviscous_5000_at_half_a_percent_meets_on_131073_points_within_its_estimate():
    # limits of converged films (film tolerance 1e-8) on 32769-262145 points, x 1e-5: Hc 3.54334,
    # 3.55688, 3.56016, 3.56097 (ratios 4.1, 4.1) -> 3.5612; Hm 2.84725, 2.83718, 2.83610, 2.83543
    # (ratios 9.3, 1.6) -> 2.8344 +- 0.0007
    sol = solve_line(5000, 0, accuracy=0.005)
    assert sol.status_name == "converged" and sol.X.size <= 131073
    assert any("FMG resumed" in a for a in sol.actions)
    for film, limit in (("Hc", 3.5612e-5), ("Hm", 2.8344e-5)):
        true = abs(sol.scalars[f"{film}_venner"] / limit - 1.0)
        assert true <= sol.scalars[f"{film}_error"], (film, true, sol.scalars[f"{film}_error"])
