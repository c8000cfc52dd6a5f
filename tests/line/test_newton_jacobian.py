"""The coarse-grid Newton Jacobian (line/newton.py) against finite differences of the
discrete Reynolds residual: every column, elastic and rigid, both wedge orders."""

import numpy as np
import pytest

from ehl_multigrid.line.newton import _system
from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.line.solver import LineHierarchy
from ehl_multigrid.multigrid.options import LineOptions


@pytest.mark.parametrize("order", [1, 2])
@pytest.mark.parametrize(("M", "L", "elastic"), [(20.0, 10.0, True), (5.0, 0.0, False)])
def test_newton_jacobian_matches_finite_differences(M, L, elastic, order):
    pb = LineProblem.from_moes(M, L, elastic=elastic)
    lv = LineHierarchy(pb, LineOptions(points=65, wedge_order=order)).levels[-1]
    x = lv.X
    rng = np.random.default_rng(1)
    # positive inside: the rheology is clamped at P = 0, where differences are one-sided
    P = 0.05 + np.where(np.abs(x) < 1.0, np.sqrt(np.clip(1.0 - x**2, 0.0, None)), 0.0)
    P *= 1.0 + 0.2 * rng.random(lv.n)
    P[0] = P[-1] = 0.0
    H0 = 0.3  # a film positive everywhere: eps differentiable
    r, J = _system(lv, P, H0, True)
    n = lv.n
    assert J.shape == (n - 2, n - 1)
    fd = np.empty_like(J)
    for col in range(n - 1):
        step = 1e-6 * max(1.0, abs(P[col + 1]) if col < n - 2 else H0)
        Pp, Pm, Hp, Hm = P.copy(), P.copy(), H0, H0
        if col < n - 2:
            Pp[col + 1] += step
            Pm[col + 1] -= step
        else:
            Hp, Hm = H0 + step, H0 - step
        rp, _ = _system(lv, Pp, Hp, False)
        rm, _ = _system(lv, Pm, Hm, False)
        # r = f - L: dL/dx = -dr/dx
        fd[:, col] = -(rp - rm)[1:-1] / (2.0 * step)
    scale = np.abs(fd).max()
    assert np.abs(J - fd).max() < 1e-6 * scale


def test_a_start_from_another_box_solution_gives_the_same_film_in_fewer_newton_steps():
    import dataclasses

    from ehl_multigrid.line.solver import solve_line_problem

    # (100, 10): the dense Newton start on 257 points (129 hold no film), as (1000, 10) on 2049
    pb = LineProblem.from_moes(100.0, 10.0)
    opts = LineOptions(points=513)
    sol = solve_line_problem(pb, opts)
    wide = dataclasses.replace(pb, xmin=pb.xmin - (pb.xmax - pb.xmin))
    cold = solve_line_problem(wide, opts, points=1025)
    warm = solve_line_problem(wide, opts, points=1025, guess=(sol.X, sol.P, sol.H0))
    assert cold.success and warm.success
    assert warm.scalars["Hc_venner"] == pytest.approx(cold.scalars["Hc_venner"], rel=1e-6)
    assert warm.scalars["Hm_venner"] == pytest.approx(cold.scalars["Hm_venner"], rel=1e-6)
    assert warm.extra["newton_iterations"] < cold.extra["newton_iterations"]


def test_serial_blas_restores_the_callers_thread_count():
    from threadpoolctl import threadpool_info

    from ehl_multigrid.multigrid.threads import serial_blas

    def blas_threads():
        return [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]

    before = blas_threads()
    with serial_blas():
        assert all(n == 1 for n in blas_threads())
    assert blas_threads() == before


def test_a_guess_replaces_a_start_grid_too_coarse_for_the_dense_newton(monkeypatch):
    # M = 500 needs a 513-point start grid; with the dense start capped at 257 points the
    # given solution starts the cycles on the finest grid and they reach the same films
    from ehl_multigrid.line import solver as ls

    pb = LineProblem.from_moes(500.0, 10.0)
    tight = dict(points=2049, film_tol=1e-7, tol_load=1e-9, max_cycles=60, raise_on_failure=False)
    ref = ls.solve_line_problem(pb, LineOptions(), **tight)
    coarse = ls.solve_line_problem(pb, LineOptions(points=1025))
    monkeypatch.setattr(ls, "MAX_START_POINTS", 257)
    with pytest.raises(Exception, match="not positive"):
        ls.solve_line_problem(pb, LineOptions(), **{**tight, "raise_on_failure": True})
    warm = ls.solve_line_problem(pb, LineOptions(), guess=(coarse.X, coarse.P, coarse.H0), **tight)
    assert ref.success and warm.success
    assert any("from the given solution" in a for a in warm.actions)
    assert warm.scalars["Hc_venner"] == pytest.approx(ref.scalars["Hc_venner"], rel=1e-5)
    assert warm.scalars["Hm_venner"] == pytest.approx(ref.scalars["Hm_venner"], rel=1e-5)
