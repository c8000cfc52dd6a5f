"""A thermal EHL solve is bounded by its time budget while it runs: the outer iteration checks
the budget of the accuracy-driven sequence between iterations (an outer iteration at a
stationary surface can run for many minutes, docs/thermal.md "Limits")."""

from __future__ import annotations

import ehl_multigrid as em
from ehl_multigrid.solution import Status


def test_a_thermal_solve_whose_budget_runs_out_in_its_outer_iteration_fails_naming_the_budget():
    sol = em.solve("appendix_c_line_4240N", physics="thermal", accuracy=0.005, options={"time_budget": 0.0})
    assert sol.status is Status.TIME_BUDGET and not sol.success
    first = sol.message.splitlines()[0]
    assert "time budget of 0 s" in first and "outer iteration 1" in first
    assert "time_budget" in sol.message  # what to try
