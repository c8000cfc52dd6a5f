"""Alternating X/Y line relaxation of the point-contact FAS solver for contacts long in the
rolling direction (Venner & Lubrecht 2000, "Multilevel methods in lubrication": line
relaxation along the direction of strong coupling)."""

from __future__ import annotations

import numpy as np
import pytest

from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.point import fas
from ehl_multigrid.point import numerics as nm
from ehl_multigrid.point.solve import problem_from_moes, solve_point


def _x_only_solution(M, L, theta, points, tol):
    problem = problem_from_moes(M, L, theta=theta)
    # the residual tolerance itself (grid_stop=None): the test needs the discrete solution
    options = PointOptions(points=points, half=True, tol=tol, tol_load=tol / 10.0, grid_stop=None,
                           max_cycles=40, alternating=False, threads=1)
    solver = fas.point_solver(problem, options)
    sol = solver.solve()
    assert sol.success
    return solver.hierarchy, solver.settings


@pytest.mark.parametrize(("theta", "tol"), [(1.0, 1e-7), (3.0, 1e-6)])
def test_y_sweep_keeps_a_converged_x_only_solution(theta, tol):
    """The X-only smoother's converged solution is a fixed point of the Y sweep: both relax
    the same discrete equations, so Y sweeps move P only at the level of the residual and do
    not raise it."""
    hz, s = _x_only_solution(20.0, 10.0, theta, 129, tol)
    lev = hz.levels[-1]
    r0 = hz.rel_residual(lev)
    P0 = lev.P.copy()
    H0 = hz.central_film(lev)
    for _ in range(3):
        nm.relax_sweep_y(lev.P, lev.H, lev.rho, lev.eps, lev.f, lev.D, lev.Ky, lev.hx, lev.hy,
                         True, s.switch, s.omega * fas.Y_OMEGA, s.omega_jd,
                         hz.options.wedge_order, fas.Y_JD_MODE)
        hz.update_film(lev)
        assert hz.rel_residual(lev) <= r0
    assert np.abs(lev.P - P0).max() / P0.max() < 100.0 * tol
    assert abs(hz.central_film(lev) - H0) / H0 < 10.0 * tol


def test_narrow_contact_relaxes_alternately_by_default():
    """b/a < 0.5 (theta = 4) switches alternation on; a circular contact keeps the X sweep."""
    opt = PointOptions(points=65, half=True)
    assert fas.PointHierarchy(problem_from_moes(100.0, 20.0, theta=4.0), opt).alternating
    assert not fas.PointHierarchy(problem_from_moes(100.0, 20.0, theta=1.0), opt).alternating


@pytest.mark.solver
def test_alternating_relaxation_converges_where_x_lines_stall():
    """(M, L) = (100, 20), theta = 4 at 257 points: X lines alone stall above the tolerance
    within max_cycles; alternating X and Y lines converge."""
    kw = dict(theta=4.0, points=257, half=True, estimate=False, raise_on_failure=False, threads=1)
    x_only = solve_point(100.0, 20.0, alternating=False, **kw)
    both = solve_point(100.0, 20.0, **kw)
    assert x_only.status_name == "max_cycles"
    assert both.status_name == "converged"


@pytest.mark.solver
def test_alternating_and_x_only_give_the_same_film():
    """Where both smoothers converge, (20, 10), theta = 4 at 129 points, to a residual of
    1e-6, their central films agree to that level: the Y sweep solves the same equations."""
    kw = dict(theta=4.0, points=129, half=True, estimate=False, tol=1e-6, tol_load=1e-7,
              max_cycles=40, threads=1, far_field=False)  # P = 0, as measured
    x_only = solve_point(20.0, 10.0, alternating=False, **kw)
    both = solve_point(20.0, 10.0, alternating=True, **kw)
    assert x_only.success and both.success
    Hx, Hb = x_only.scalars["Hc"], both.scalars["Hc"]
    assert abs(Hb - Hx) / Hx < 1e-5


@pytest.mark.parametrize(("alternating", "sweeps_of_work"), [(False, 1.0), (True, 2.0)])
def test_alternating_sweep_counts_two_sweeps_of_work(alternating, sweeps_of_work):
    """An alternating sweep (X lines then Y lines) is charged as two sweeps of work units."""
    problem = problem_from_moes(20.0, 10.0, theta=10.0)
    solver = fas.point_solver(problem, PointOptions(points=65, half=True, alternating=alternating))
    hz = solver.hierarchy
    hz._initial_guess()
    assert hz.relax(0, 3, solver.settings, True) == pytest.approx(3.0 * sweeps_of_work * hz.work(0))


@pytest.mark.solver
def test_y_pre_false_relaxes_y_lines_after_the_correction_only():
    """``y_pre=False``: the fine grids of a wider contact alternate in the post-relaxation only,
    so one F cycle per FMG level on 513^2 costs 2 + 2 instead of 4 + 2 sweeps of work per
    fine-grid visit (nu1 = 2, nu2 = 1); the default keeps both alternating
    (validation/bench/point_variants.py: fewer work units, no faster, less robust)."""
    kw = dict(points=513, half=True, cycles=1, max_cycles=0, adapt=False, threads=1, accuracy=None)
    both = solve_point(20.0, 10.0, **kw)
    post = solve_point(20.0, 10.0, y_pre=False, **kw)
    assert post.work_units < 0.72 * both.work_units
    # the same discrete problem: the films agree to the algebraic error of one FMG cycle
    assert abs(post.scalars["Hc_venner"] / both.scalars["Hc_venner"] - 1.0) < 5e-4
    coarse = dict(kw, points=257)
    assert solve_point(20.0, 10.0, y_pre=False, **coarse).work_units == solve_point(20.0, 10.0, **coarse).work_units
