"""The time budget of a line solve holds in every phase, the continuation in M included.

Isoviscous (M, L) = (5000, 0): its start grids hold no positive film, so the solve continues in
M from M = 2500 (line.solver.CONTINUATION_HALVINGS); the dense Newton starts, the cycles and
the continuation's steps each check the budget."""

import re
import time

import pytest

from ehl_multigrid.line import solve_line
from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.line.solver import continued_in_m, solve_line_problem
from ehl_multigrid.multigrid.controller import deadline
from ehl_multigrid.multigrid.options import LineOptions


@pytest.mark.solver
def test_continuation_in_m_stops_when_the_time_budget_runs_out_and_says_where():
    pb, opts = LineProblem.from_moes(5000.0, 0.0), LineOptions(points=4097, raise_on_failure=False)
    starts: dict = {}
    assert solve_line_problem(pb, opts, start_cache=starts).status_name == "start_failed"
    lines: list[str] = []
    with deadline(0.0):
        res = continued_in_m(pb, opts, start_cache=starts, progress=lines.append)
    assert res is not None and res.status_name == "time_budget" and not res.success
    # where the time went: the step of the continuation (its M) and the solve's phase
    assert "continuation in M to 5000" in res.message and "M = 2500" in res.message
    assert "ran out at" in res.message
    # the continuation reported its step before it was stopped
    assert any("continuation in M" in s and "M = 2500" in s for s in lines)


@pytest.mark.solver
def test_line_solve_with_a_tiny_time_budget_returns_soon_with_time_budget_status():
    # without the checks inside a solve, the first solve and its continuation in M ran to the
    # end (several seconds) before the budget was looked at
    budget = 0.3
    t0 = time.perf_counter()
    res = solve_line(5000, 0, accuracy=0.005, time_budget=budget)
    wall = time.perf_counter() - t0
    assert wall < budget + 1.5, wall
    assert res.status_name == "time_budget" and not res.success
    assert f"time budget of {budget:g} s ran out" in res.message


@pytest.fixture
def sub_nm_film(tmp_path):
    """A line contact at M = 9808, L = 1.07 with a sub-nanometre film: no positive film on the
    dense start grids, so its solves continue in M."""
    path = tmp_path / "subnm_film.toml"
    path.write_text(
        'name = "subnm_film"\n[contact]\nkind = "line"\nlength = 0.01\n[geometry]\nRx = 0.02\n'
        '[solids]\nE_reduced = 231000000000.0\n[lubricant]\npreset = "T9"\neta0 = 0.03\n'
        'alpha = 2.2e-8\n[operating]\nload = 20000\nus = 0.0003\nslip = 0.0\nT_oil = 40.0\n'
        'T_surface1 = 40.0\nT_surface2 = 40.0\n')
    return str(path)


@pytest.mark.solver
def test_failed_continuation_in_m_names_the_grid_and_step_that_failed(sub_nm_film):
    import ehl_multigrid as ehl

    # the continuation in M reaches M = 4904 and fails on its step back up, not on the
    # 2049-point start grid the first message named
    sol = ehl.solve(sub_nm_film, options={"points": 16385})
    assert not sol.outcome.success and sol.status.name == "START_FAILED"
    msg = sol.message
    assert "not positive on the 2049-point start grid" in msg
    # the failed step (M = 4904 -> 9808) and the grid it failed on (the finest: level 5 of 6)
    cont = msg.split("continuation in M", 1)[1]
    assert re.search(r"M = 9808 .* on the 16385-point grid \(diverged on grid 5\b", cont), cont
    # the start grid is capped at the dense Newton limit: finer grids are not what it needs
    assert "needs finer grids" not in msg


@pytest.mark.solver
def test_continuation_step_keeps_no_dense_floor_above_the_start_limit(sub_nm_film):
    import ehl_multigrid as ehl

    # the step to M = 4904 used to raise the cycles' floor to the 4097-point grid, solved by
    # dense Newton at every cycle (about a minute per cycle); the budget is a safety net
    budget = 15.0
    t0 = time.perf_counter()
    sol = ehl.solve(sub_nm_film, accuracy=0.01, options={"max_points": 65537, "time_budget": budget})
    wall = time.perf_counter() - t0
    assert sol.status.name != "TIME_BUDGET" and wall < 0.5 * budget, (sol.status, wall)
