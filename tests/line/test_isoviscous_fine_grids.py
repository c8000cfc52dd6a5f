"""Isoviscous line contact (M, L) = (20, 0) on 4097-16385 points (line.solver.default_switch_eps).

Before the film-scale switch these solves stalled or diverged (residual ~1e-2, Hc 5-40 % off):
``eps/h`` grows with refinement, so the h-scaled switch left the flat film's centre
Gauss-Seidel, whose elastic coupling the collective line system holds only within its band,
and the contact's smooth modes grew. The reference is independent of the multigrid path: dense
Newton on 1025 and 2049 points (the 1025-point solve from the Hertzian guess, the 2049-point
one from it) and their Richardson limit."""

import math

import pytest

from ehl_multigrid.line import solve_line
from ehl_multigrid.line.newton import newton_solve
from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.line.solver import LineHierarchy
from ehl_multigrid.multigrid.options import LineOptions

BARUS = {"viscosity": "barus", "density": "incompressible"}


@pytest.fixture(scope="module")
def dense_newton():
    """Discrete films (Hc, Hm in Moes units) of the dense Newton solves on 1025 and 2049 points."""
    pb = LineProblem.from_moes(20.0, 0.0)
    films, guess = {}, None
    for n in (1025, 2049):
        hz = LineHierarchy(pb, LineOptions(points=n, levels=1))
        hz.guess = guess
        lv = hz.levels[0]
        hz._initial_guess(lv)
        newton_solve(lv, max_iter=120)
        guess = (lv.X, lv.P.copy(), lv.H0)
        m = hz.measure(0)
        assert m.residual < 1e-10 and abs(m.load_error) < 1e-12
        films[n] = (pb.moes_from_venner(m.Hc), pb.moes_from_venner(m.Hm))
    return films


@pytest.mark.solver
@pytest.mark.parametrize("model", [{}, BARUS], ids=["roelands", "barus"])
@pytest.mark.parametrize("points", [4097, 8193, 16385])
@pytest.mark.xdist_group("line_isoviscous_dense_newton")
def test_isoviscous_line_converges_on_fine_grids(dense_newton, points, model):
    r = solve_line(20.0, 0.0, points=points, estimate=False, raise_on_failure=False,
                   grid_stop=None, **model)
    assert r.status_name == "converged", r.message
    assert r.residual_history[-1] < 1e-5 and abs(r.load_error_history[-1]) < 1e-6
    # plain multigrid: no rejected cycle, no stall step, no dense Newton finish
    assert not r.actions, r.actions
    coarse, fine = dense_newton[1025], dense_newton[2049]
    # second-order Richardson limit of the dense Newton films; the scale is the larger relative
    # 1025 -> 2049 change of the two films (Hm, a grid-point minimum, converges irregularly)
    limit = [f + (f - c) / 3.0 for c, f in zip(coarse, fine, strict=True)]
    scale = max(abs(f / c - 1.0) for c, f in zip(coarse, fine, strict=True))
    for got, ref in zip((r.Hc, r.Hm), limit, strict=True):
        assert abs(got / ref - 1.0) < scale
    # and Hc nearer the limit than the 2049-point discrete solution
    assert abs(r.Hc - limit[0]) < abs(fine[0] - limit[0])
    assert math.isfinite(r.Hm) and r.Hm < r.Hc
