"""Local Newton at the outlet pressure drop of high-``alpha_bar`` Barus line contacts
(line/newton.py ``local_newton``, line/solver.py ``LineHierarchy.relax``).

The collective line relaxation freezes ``eps``; where the viscosity changes by orders of
magnitude between two points (Barus + incompressible, (M, L) = (100, 20): ``eps/h^2`` from 1e-8
to 1e4 across one cell at X = 0.97 on 4097 points) the residual concentrates there and the
cycles stall. A windowed Newton solve with the exact Jacobian block settles it."""

import numpy as np
import pytest

from ehl_multigrid.line import solve_line
from ehl_multigrid.line.discrete import projected
from ehl_multigrid.line.newton import (
    _fluid,
    local_newton,
    newton_solve,
    reynolds_jacobian,
    reynolds_jacobian_block,
)
from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.line.solver import LineHierarchy
from ehl_multigrid.multigrid.options import LineOptions

BARUS = {"viscosity": "barus", "density": "incompressible"}


def _level(M, L, points, **model):
    pb = LineProblem.from_moes(M, L, **model)
    hz = LineHierarchy(pb, LineOptions(points=points))
    return hz, hz.levels[-1]


@pytest.mark.parametrize(("lo", "hi"), [(1, 64), (20, 41), (60, 128)])
def test_jacobian_block_is_the_block_of_the_full_jacobian(lo, hi):
    hz, lv = _level(100.0, 20.0, 129, **BARUS)
    hz._initial_guess(lv)
    r, st = _fluid(lv, lv.P, lv.H0)
    full = reynolds_jacobian(lv.P, *st, lv.kernel, lv.h, lv.order, lv.elastic)
    block = reynolds_jacobian_block(lv.P, *st, lv.kernel, lv.h, lv.order, lv.elastic, lo, hi, False)
    np.testing.assert_array_equal(block, full[lo - 1:hi - 1, lo - 1:hi - 1])


def test_local_newton_settles_a_disturbed_window_and_leaves_the_rest():
    # the discrete solution on 257 points (dense Newton), disturbed at the outlet drop
    hz, lv = _level(100.0, 10.0, 257, **BARUS)
    hz._initial_guess(lv)
    newton_solve(lv, max_iter=120)
    exact = lv.P.copy()
    c = int(np.argmax(np.where(lv.X > 0.5, -np.diff(lv.P, append=0.0), 0.0)))  # steepest drop
    rng = np.random.default_rng(3)
    lv.P[c - 5:c + 6] *= 1.0 + 0.05 * rng.standard_normal(11)
    before = np.abs(projected(_fluid(lv, lv.P, lv.H0)[0], lv.P))[c - 10:c + 11].max()
    disturbed = lv.P.copy()
    local_newton(lv, c, half=16)
    after = np.abs(projected(_fluid(lv, lv.P, lv.H0)[0], lv.P))[c - 10:c + 11].max()
    assert after < 1e-3 * before
    outside = np.r_[0:c - 16, c + 17:lv.n]
    np.testing.assert_array_equal(lv.P[outside], disturbed[outside])
    # driven further, the window's solution with the rest fixed is the exact one (the rest
    # is exact): Newton converges to it, not to another root
    local_newton(lv, c, half=16, max_iter=50, reduce=1e-12)
    assert np.abs(lv.P - exact).max() < 1e-9 * exact.max()


@pytest.mark.solver
def test_barus_line_at_4097_points_converges_with_local_newton_and_stalls_without():
    # 20 cycles, not the default 60: with local Newton it converges in 11; without, the residual
    # stays near 0.1 (the solve ends "stalled" after 43 cycles at 2.5 times the cost)
    kw = {"points": 4097, "estimate": False, "raise_on_failure": False, "max_cycles": 20, **BARUS}
    off = solve_line(100.0, 20.0, local_newton=None, **kw)
    on = solve_line(100.0, 20.0, **kw)
    assert not off.success and off.residual_history[-1] > 1e-3
    assert on.success, on.message
    assert on.residual_history[-1] < 1e-5


def test_local_newton_result_is_the_dense_newton_discrete_solution():
    # 2049 points: small enough for the dense Newton of the whole grid (the other solver
    # path), started from the multigrid result and driven to 1e-10
    kw = {"points": 2049, "estimate": False, "tol": 1e-8, "tol_load": 1e-10, **BARUS}
    mg = solve_line(100.0, 20.0, **kw)
    assert mg.success
    _, lv = _level(100.0, 20.0, 2049, **BARUS)
    lv.P, lv.H0 = mg.P.copy(), float(mg.H0)
    newton_solve(lv, max_iter=60)
    st = lv.state()
    Hc = float(np.interp(0.0, lv.X, st.H))
    Hm = float(np.min(st.H[(np.abs(lv.X) <= 1.5) | (lv.P > 0)]))
    assert mg.scalars["Hc_venner"] == pytest.approx(Hc, rel=1e-6)
    assert mg.scalars["Hm_venner"] == pytest.approx(Hm, rel=1e-6)
