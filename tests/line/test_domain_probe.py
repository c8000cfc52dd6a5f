"""The line domain probe (``line_domain_change``): its two solves start on their finest grid from
the solution (``from_guess``) at a film tolerance tight enough that the measured box change is
the change between the two discrete solutions, not a remnant of their common start."""

import dataclasses

import pytest

from ehl_multigrid.line import solve_line
from ehl_multigrid.line.solver import line_domain_change, solve_line_problem


@pytest.fixture(scope="module")
def sol():
    return solve_line(20.0, 10.0, points=2049, estimate=False)


def test_a_solve_from_the_solution_starts_on_the_finest_grid_and_keeps_the_discrete_film(sol):
    o = dataclasses.replace(sol.options, points=1025, levels=None, tol=1e-9, tol_load=1e-10,
                            max_cycles=200)
    fmg = solve_line_problem(sol.problem, o)
    start = solve_line_problem(sol.problem, o, guess=(sol.X, sol.P, sol.H0), from_guess=True)
    assert fmg.success and start.success
    assert any("from the given solution (no FMG)" in a for a in start.actions)
    assert start.cycles < fmg.cycles
    assert start.Hc == pytest.approx(fmg.Hc, rel=1e-7)
    assert start.Hm == pytest.approx(fmg.Hm, rel=1e-7)


def test_domain_probe_from_the_solution_measures_the_deep_box_change(sol):
    change = line_domain_change(sol.problem, sol.options, sol)
    assert change is not None
    # the same two discrete problems solved deep by FMG (the probe's pair: a quarter of the
    # points on the default box, half on the box twice as long)
    wide = dataclasses.replace(sol.problem, xmin=sol.problem.xmin - (sol.problem.xmax - sol.problem.xmin))
    o = dataclasses.replace(sol.options, levels=None, tol=1e-9, tol_load=1e-10, max_cycles=200)
    a = solve_line_problem(sol.problem, o, points=513)
    b = solve_line_problem(wide, o, points=1025)
    deep = (b.Hc / a.Hc - 1.0, b.Hm / a.Hm - 1.0)
    assert abs(deep[0]) > 1e-5  # a change the probe must resolve
    for got, want in zip(change, deep, strict=True):
        assert got == pytest.approx(want, rel=0.05)
