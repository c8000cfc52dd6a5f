"""A tolerance step of the accuracy loop continues the cycles of the converged solve of the same
grid and box (``multigrid.result.tightened``) instead of solving again from the coarsest grid."""

import dataclasses
import math
from types import SimpleNamespace

import numpy as np
import pytest

from ehl_multigrid.line import solve_line
from ehl_multigrid.line.solver import solve_line_problem
from ehl_multigrid.multigrid.options import LineOptions
from ehl_multigrid.multigrid.result import EHLResult, tightened, tightening
from ehl_multigrid.point import solve_point
from ehl_multigrid.point.solve import solve_fas


def test_tightening_needs_the_same_grid_and_a_tighter_tolerance():
    prev = SimpleNamespace(options=LineOptions(points=1025, tol=1e-4, tol_load=1e-5, film_tol=5e-4))
    assert tightening(prev, LineOptions(points=1025, tol=1e-5, tol_load=1e-6, film_tol=5e-5))
    assert tightening(prev, LineOptions(points=1025, tol=1e-4, tol_load=1e-5, film_tol=5e-5))
    assert not tightening(prev, LineOptions(points=2049, tol=1e-5, tol_load=1e-6, film_tol=5e-5))
    assert not tightening(prev, LineOptions(points=1025, tol=1e-4, tol_load=1e-5, film_tol=5e-4))


def test_a_continued_solve_carries_the_fmg_films_histories_and_work_of_the_one_before():
    prev = EHLResult(0, "converged", cycles=7, residual_history=np.array([1e-2, 1e-4]),
                     load_error_history=np.array([1e-3, 1e-6]), work_units=30.0, actions=["a"],
                     history=["c1", "c2"], fmg=[{"points": 129, "Hc": 0.1, "Hm": 0.05, "level": 0}])
    tight = EHLResult(0, "converged", cycles=3, residual_history=np.array([1e-5]),
                      load_error_history=np.array([1e-7]), work_units=6.0, history=["c3"])
    tight.scalars["cycles"] = 3
    out = tightened(prev, tight)
    assert out.fmg == prev.fmg and out.history == ["c1", "c2", "c3"]
    assert list(out.residual_history) == [1e-2, 1e-4, 1e-5] and out.load_error_history[-1] == 1e-7
    assert out.cycles == 10 and out.scalars["cycles"] == 10 and out.work_units == 36.0
    assert out.actions[0] == "a" and "7 cycles before, 1 after" in out.actions[-1]


def _raw(r, k):
    return r.scalars.get(k + "_field", r.scalars[k])


@pytest.mark.solver
def test_a_line_tolerance_step_continues_and_agrees_with_a_fresh_solve_of_its_grid():
    """Line (100, 25) at 0.5 %: 4097 -> 8193 points, then a tolerance step on 8193 points
    (0.32 s continued, against 0.47 s for the FMG solve of that grid). The continued films equal a fresh FMG solve of the same options within the stated
    algebraic parts (measured: 2e-6 against 3.7e-5, 4.2e-5)."""
    r = solve_line(100.0, 25.0, accuracy=0.005)
    assert r.success and any("tolerance step" in a for a in r.actions)
    assert r.fmg and math.isfinite(r.error.budget["grid"]["Hc"])  # the FMG films were carried
    fresh = solve_line_problem(r.problem, dataclasses.replace(r.options, raise_on_failure=False))
    assert fresh.success
    for k in ("Hc", "Hm"):
        assert abs(_raw(r, k) / fresh.scalars[k] - 1.0) < r.error.budget["algebraic"][k]


@pytest.mark.solver
def test_a_point_tolerance_step_continues_and_agrees_with_a_fresh_solve_of_its_grid():
    """Roelands (20, 25, theta 0.1) at 2 %: a tolerance step on 129 points, continued (9 cycles,
    0.15 s against 0.60 s for the FMG solve); the films equal a fresh FMG solve of the same
    options within the stated algebraic parts (measured: 1.1e-6, 1.2e-7 against 1.4e-5, 3e-6)."""
    r = solve_point(20.0, 25.0, theta=0.1, accuracy=0.02)
    assert r.success and any("tolerance step" in a for a in r.actions)
    fresh = solve_fas(r.problem, dataclasses.replace(r.options, raise_on_failure=False,
                                                     y_ratio=r.extra["y_ratio"]))
    assert fresh.success
    for k in ("Hc", "Hm"):
        assert abs(_raw(r, k) / fresh.scalars[k] - 1.0) < r.error.budget["algebraic"][k]


@pytest.mark.solver
def test_no_tolerance_step_continues_a_solve_on_other_cells_than_the_sequence_keeps(monkeypatch):
    """Once a solve of the sequence falls back to square cells, every later solve keeps them; a
    tolerance step must not continue a converged solve on the earlier cells (another discrete
    problem: for Barus (20, 20, theta 4) at 1 % a 257-point film on y_ratio 1 in a sequence on
    0.5 states Hm 5.1 % on 513 points, against 0.85 % with the whole sequence on one set of
    cells; docs/accuracy.md). Stand-in fall-back: the (20, 25, theta 0.1) case's 65-point
    repair level is solved on other cells and reported as a fall-back; its 129-point tolerance
    step then follows."""
    import ehl_multigrid.point.solve as ps

    real, calls = ps.solve_fas, []

    def spy(problem, options, **kw):
        fake = options.points == 65 and options.y_ratio is None
        r = real(problem, dataclasses.replace(options, y_ratio=0.5) if fake else options, **kw)
        if fake:
            r.extra["square_cells_fallback"] = True
        calls.append((options.points, r.extra["y_ratio"], "guess" in kw))
        return r

    monkeypatch.setattr(ps, "solve_fas", spy)
    r = solve_point(20.0, 25.0, theta=0.1, accuracy=0.02)
    assert r.success
    after = calls[[c[0] for c in calls].index(65):]
    assert any(n == 129 for n, _, _ in after)  # the stand-in reached the tolerance step
    assert all(ratio == 0.5 for _, ratio, _ in after), after
