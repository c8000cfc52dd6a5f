"""A coarse Newton solve that failed on a grid is tried again on the later visits of the same
solve, but stopped after ``NEWTON_AFTER_FAILURE`` steps: on a grid whose discrete film is not
positive (isoviscous (3000, 0) probed from its solution on twice the box) each failing attempt
ran 80 steps, and the attempts that succeed in between take few."""

import ehl_multigrid.line.solver as ls
from ehl_multigrid.line.newton import NewtonFailure
from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.multigrid.options import LineOptions


def test_later_coarse_newton_attempts_on_a_grid_that_failed_stop_early(monkeypatch):
    solver = ls.line_solver(LineProblem.from_moes(20.0, 10.0), LineOptions(points=129))
    hz = solver.hierarchy
    hz.solver = solver
    calls = []

    def newton(lv, max_iter=80, **kw):
        calls.append((lv.n, max_iter))
        if len(calls) == 1:
            raise NewtonFailure("coarse Newton did not converge in 80 iterations")
        return 1

    monkeypatch.setattr(ls, "newton_solve", newton)
    hz._initial_guess(hz.levels[0])
    hz.coarse_solve(0, solver.settings)  # fails: relaxed instead
    hz.coarse_solve(0, solver.settings)
    hz.coarse_solve(0, solver.settings)
    n0 = hz.levels[0].n
    assert calls == [(n0, 80), (n0, ls.NEWTON_AFTER_FAILURE), (n0, ls.NEWTON_AFTER_FAILURE)]
    assert sum("coarse Newton failed" in a for a in solver.actions) == 1


def test_a_new_solve_starts_with_the_full_newton_again():
    a = ls.line_solver(LineProblem.from_moes(20.0, 10.0), LineOptions(points=129)).hierarchy
    a.newton_failed.add(0)
    b = ls.line_solver(LineProblem.from_moes(20.0, 10.0), LineOptions(points=129)).hierarchy
    assert not b.newton_failed
