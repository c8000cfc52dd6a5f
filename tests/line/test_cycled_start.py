"""The FMG start grid above a grid that holds no positive film is solved by FAS cycles from that
grid's solution (``LineHierarchy._cycled_start``) before the dense Newton solve: the cycles give
the same discrete solution, a grid whose cycles settle on a non-positive film is not solved
again by Newton, and a probe on a longer box keeps the default box's coarsest mesh size
(``coarse_points(M, box)``)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import ehl_multigrid.line.solver as ls
from ehl_multigrid.line.problem import LineProblem, box_ratio
from ehl_multigrid.line.solver import LineHierarchy, coarse_points, solve_line_problem
from ehl_multigrid.multigrid.options import LineOptions


def _newton_grids(monkeypatch) -> list[int]:
    seen, real = [], ls.newton_solve

    def spy(level, *a, **kw):
        if kw.get("single"):  # the start's dense solves (the cycles' coarsest grid: not single)
            seen.append(level.n)
        return real(level, *a, **kw)

    monkeypatch.setattr(ls, "newton_solve", spy)
    return seen


def test_a_start_grid_solved_by_cycles_gives_the_dense_newton_solution(monkeypatch):
    pb = LineProblem.from_moes(2000, 5)
    opts = LineOptions(points=4097, tol=1e-9, tol_load=1e-10, max_cycles=100)
    dense_grids = _newton_grids(monkeypatch)
    cycled = solve_line_problem(pb, opts)
    assert cycled.success
    # 513 and 1025 points carry no positive film at M = 2000; 2049 is reached by cycles alone
    assert any("2049 points" in a and "FAS cycles" in a for a in cycled.actions)
    assert 2049 not in dense_grids
    monkeypatch.setattr(LineHierarchy, "_cycled_start", lambda self, k, solver: False)
    dense = solve_line_problem(pb, opts)
    assert dense.success and 2049 in dense_grids
    for key in ("Hc_venner", "Hm_venner"):
        assert cycled.scalars[key] == pytest.approx(dense.scalars[key], rel=1e-7)


def test_a_start_grid_whose_cycles_settle_on_a_non_positive_film_is_not_solved_by_newton(monkeypatch):
    # isoviscous M = 3000: 2049 points, the dense start's largest grid, hold no positive film
    dense_grids = _newton_grids(monkeypatch)
    r = solve_line_problem(LineProblem.from_moes(3000, 0), LineOptions(points=4097, raise_on_failure=False))
    assert r.status_name == "start_failed"
    assert 2049 not in dense_grids


@pytest.mark.parametrize(("M", "box", "want"), [(20, 1.0, 65), (2000, 1.0, 513), (2000, 2.0, 1025),
                                                (2000, 4.0, 2049), (2000, 1.3, 513), (2000, 0.5, 513)])
def test_the_coarsest_grid_keeps_its_mesh_size_on_a_longer_box(M, box, want):
    assert coarse_points(M, box) == want


def test_a_probe_of_twice_the_box_coarsens_to_the_default_box_mesh_size():
    pb = LineProblem.from_moes(2000, 0)
    wide = dataclasses.replace(pb, xmin=pb.xmin - (pb.xmax - pb.xmin))
    assert box_ratio(pb) == pytest.approx(1.0) and box_ratio(wide) == pytest.approx(2.0)
    short = LineHierarchy(pb, LineOptions(points=4097)).levels[0]
    long = LineHierarchy(wide, LineOptions(points=8193)).levels[0]
    assert np.diff(long.X)[0] == pytest.approx(np.diff(short.X)[0])


def test_a_later_solve_starts_fmg_above_the_filmless_start_grids_from_the_given_solution():
    pb = LineProblem.from_moes(5000, 5)
    tight = LineOptions(points=8193, tol=1e-9, tol_load=1e-10, max_cycles=100, raise_on_failure=False)
    starts: dict = {}
    first = solve_line_problem(pb, dataclasses.replace(tight, points=4097), start_cache=starts)
    assert first.status_name == "start_failed"  # 513-2049 points hold no positive film at M = 5000
    assert starts and all(v is None for v in starts.values())
    src = ls.continued_in_m(pb, dataclasses.replace(tight, points=4097), start_cache=starts)
    guess = (src.X, src.P, src.H0)
    fmg = solve_line_problem(pb, tight, guess=guess, start_cache=starts)
    assert any("4097 points" in a and "FAS cycles" in a and "given solution" in a for a in fmg.actions)
    assert [d["points"] for d in fmg.fmg] == [4097, 8193]  # an FMG sequence for the estimate
    finest = solve_line_problem(pb, tight, guess=guess, from_guess=True)
    assert fmg.success and finest.success
    for key in ("Hc_venner", "Hm_venner"):
        assert fmg.scalars[key] == pytest.approx(finest.scalars[key], rel=1e-6)


def test_an_isoviscous_later_solve_keeps_its_start_on_the_finest_grid():
    # FMG through the fine grids of an isoviscous contact rejects cycle after cycle: the later
    # solves of its sequence cycle on their finest grid from the given solution
    pb = LineProblem.from_moes(3000, 0)
    opts = LineOptions(points=16385, raise_on_failure=False)
    starts: dict = {}
    solve_line_problem(pb, opts, start_cache=starts)
    src = ls.continued_in_m(pb, opts, start_cache=starts)  # (its M = 1500 step fails on 8193)
    r = solve_line_problem(pb, opts, guess=(src.X, src.P, src.H0), start_cache=starts)
    assert r.success
    assert any("16385-point grid" in a and "given solution" in a for a in r.actions)
