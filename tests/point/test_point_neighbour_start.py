"""A point solve started on its finest grid from a converged solution of the same contact
(another grid, or a box twice as wide) reaches the FMG solve's discrete answer, and the
accuracy sequence answers a refinement whose own start fails by solving it again from the
sequence's last converged solution (``retry_from_neighbour``)."""

from types import SimpleNamespace

import pytest

import ehl_multigrid.point.solve as solve_mod
from ehl_multigrid.point.problem import problem_from_moes, resolve_domain
from ehl_multigrid.point.solve import solve_fas, solve_point

TIGHT = dict(half=True, tol=1e-7, tol_load=1e-7, raise_on_failure=False)


@pytest.fixture(scope="module")
def circular():
    return problem_from_moes(20.0, 10.0, 1.0)


@pytest.fixture(scope="module")
def coarse(circular):
    sol = solve_fas(circular, points=129, **TIGHT)
    assert sol.success
    return sol


def _guess(sol):
    return (sol.X, sol.Y, sol.P, float(sol.H0))


def _rel(a: float, b: float) -> float:
    return abs(a - b) / abs(b)


@pytest.mark.xdist_group("point_neighbour_start_coarse")
def test_finer_grid_started_from_a_coarser_solution_reaches_the_fmg_answer(circular, coarse):
    fmg = solve_fas(circular, points=257, **TIGHT)
    warm = solve_fas(circular, points=257, guess=_guess(coarse), **TIGHT)
    assert fmg.success and warm.success
    assert any("no FMG" in a for a in warm.actions)
    # no FMG grid below the finest: the Richardson films are missing (the sequence repairs them)
    assert all(d["level"] == warm.levels - 1 for d in warm.fmg)
    for key in ("Hc_venner", "Hm_venner"):
        assert _rel(warm.scalars[key], fmg.scalars[key]) < 1e-5
    # the start is near the answer: the coarse grid's films differ from it by more than that
    assert _rel(coarse.scalars["Hc_venner"], fmg.scalars["Hc_venner"]) > 1e-4


@pytest.mark.xdist_group("point_neighbour_start_coarse")
def test_wider_box_started_from_the_default_box_reaches_the_fmg_answer(circular, coarse):
    x0, x1, y1 = resolve_domain(circular, None, None, None)
    wide = dict(xmin=2 * x0, xmax=2 * x1, ymax=2 * y1)
    fmg = solve_fas(circular, points=257, **wide, **TIGHT)
    warm = solve_fas(circular, points=257, guess=_guess(coarse), **wide, **TIGHT)
    assert fmg.success and warm.success
    for key in ("Hc_venner", "Hm_venner"):
        assert _rel(warm.scalars[key], fmg.scalars[key]) < 1e-5


@pytest.mark.xdist_group("point_neighbour_start_coarse")
def test_full_domain_started_from_a_half_domain_solution(circular, coarse):
    opts = dict(TIGHT, half=False)
    fmg = solve_fas(circular, points=129, **opts)
    warm = solve_fas(circular, points=129, guess=_guess(coarse), **opts)
    assert warm.success
    assert _rel(warm.scalars["Hc_venner"], fmg.scalars["Hc_venner"]) < 1e-5


def _start_on_129(*args, **kw):
    # the sequence starts on 129 points, where 0.3 % is not met: it refines to 257 points on a
    # box twice as wide (the domain part dominates there)
    return SimpleNamespace(points=129)


def _fail_first_257(monkeypatch, probing):
    """Make the sequence's first 257-point solve (not a domain probe's) fail as diverged;
    returns the list of calls (points, xmin, from a guess, inside a probe)."""
    real = solve_mod.solve_fas
    calls = []

    def solve_fas(problem, options=None, callback=None, scene=None, guess=None, **kw):
        res = real(problem, options, callback=callback, scene=scene, guess=guess, **kw)
        calls.append((options.points, options.xmin, guess is not None, probing[0]))
        if calls[-1] == (257, -9.0, False, False) and calls.count(calls[-1]) == 1:
            res.set_status(3, "diverged on grid 5 (made to fail by the test)")
        return res

    monkeypatch.setattr(solve_mod, "solve_fas", solve_fas)
    monkeypatch.setattr(solve_mod, "solver_grid", _start_on_129)
    # the sequence starts on the default box (no start-box choice): the refinement follows a
    # converged solve, the neighbour of the retry
    monkeypatch.setattr(solve_mod, "start_box", lambda *a, **k: None)
    return calls


def test_failed_refinement_is_solved_again_from_the_converged_neighbour(monkeypatch, probing):
    """The refinement of the sequence is made to fail from its FMG start: the sequence solves
    it again from the 129-point solution and goes on, instead of stopping there."""
    calls = _fail_first_257(monkeypatch, probing)
    res = solve_point(20.0, 10.0, accuracy=0.003, max_points=257, half=True, raise_on_failure=False,
                      far_field=False)
    i = calls.index((257, -9.0, False, False))
    assert calls[i + 1] == (257, -9.0, True, False)  # the same grid and box, from the neighbour
    assert any("retry_from_neighbour" in a for a in res.actions)
    assert res.X.shape[0] == 257
    solves = [r["points"] for r in res.extra["refinements"] if r["purpose"] == "solve"]
    assert solves == [129, 257]
    # the answer from the neighbour states its error like any other (grid part by the repair
    # solves of the coarser grids, which the FMG did not leave)
    assert all(v == v for v in res.error.budget["grid"].values())
    # and it is the FMG's answer on that grid and box, within the stated algebraic error
    x0, x1, y1 = resolve_domain(res.problem, None, None, None)
    fmg = solve_fas(res.problem, points=257, xmin=2 * x0, xmax=2 * x1, ymax=2 * y1, far_field=False, **TIGHT)
    for key, part in (("Hc_venner", "Hc"), ("Hm_venner", "Hm")):
        assert _rel(res.scalars[key], fmg.scalars[key]) <= max(res.error.budget["algebraic"][part], 1e-6)


def test_without_the_neighbour_retry_the_sequence_falls_back_to_the_smaller_step(monkeypatch, probing):
    calls = _fail_first_257(monkeypatch, probing)
    res = solve_point(20.0, 10.0, accuracy=0.003, max_points=257, half=True, raise_on_failure=False, far_field=False,
                      retry_from_neighbour=False)
    assert (257, -9.0, True, False) not in calls
    assert not any("retry_from_neighbour" in a for a in res.actions)
    steps = [(r["points"], r["box"]) for r in res.extra["refinements"] if r["purpose"] == "solve"]
    # the failed box step, then one grid finer on the default box (the sequence's safe step)
    assert steps == [(129, 1.0), (257, 2.0), (257, 1.0)]
