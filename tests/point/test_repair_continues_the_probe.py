"""A point sequence's repair (coarser grids solved to convergence for the estimate) continues a
converged domain probe of the same discrete problem (same grid, box and cells, looser
tolerances: ``point.solve.same_problem_probe``) by a tolerance step instead of a new FMG solve
(the 6205 inner race at 0.5 %: its 513-point repair 1.0 -> 0.36 s). The answer is the one the
FMG repair gives, to its tolerance."""

import pytest

import ehl_multigrid as ehl
import ehl_multigrid.point.solve as ps

pytestmark = pytest.mark.solver
PROBLEM = ehl.MoesProblem("elliptic", M=50, L=10, theta=3)


def _run(monkeypatch, reuse: bool):
    calls, real = [], ps.solve_fas

    def spy(problem, options=None, *a, **kw):
        calls.append((options.points, options.xmin, kw.get("guess") is not None))
        return real(problem, options, *a, **kw)

    monkeypatch.setattr(ps, "solve_fas", spy)
    if not reuse:
        monkeypatch.setattr(ps, "same_problem_probe", lambda *a, **k: None)
    return ehl.solve(PROBLEM, accuracy=0.01), calls


def test_the_repair_continues_the_probe_of_its_grid_and_gives_the_same_answer(monkeypatch):
    fresh, fresh_calls = _run(monkeypatch, reuse=False)
    monkeypatch.undo()
    reused, calls = _run(monkeypatch, reuse=True)
    assert fresh.success and reused.success and reused.grid.points == fresh.grid.points
    # the 129-point probe of the default box (xmin given) and the repair's 129-point solve of it
    probe = [c for c in calls if c[0] == 129 and c[1] is not None]
    repair = [c for c in calls if c[0] == 129 and c[1] is None]
    assert probe and repair and all(guess for _, _, guess in repair)
    assert not any(guess for n, xmin, guess in fresh_calls if n == 129 and xmin is None)
    assert reused.Hc == pytest.approx(fresh.Hc, rel=1e-5)
    assert reused.Hm == pytest.approx(fresh.Hm, rel=1e-5)
    assert reused.error.Hc == pytest.approx(fresh.error.Hc, rel=0.05)
    assert reused.error.Hm == pytest.approx(fresh.error.Hm, rel=0.05)
