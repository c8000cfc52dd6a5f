"""The point hierarchy's work arrays: one sweep scratch and one residual array shared by every
grid, no deformation array above the coarsest grid, scalars without mirrored copies. The
films must be those of a hierarchy that keeps its own arrays per grid (bit for bit)."""

import math

import numpy as np

import ehl_multigrid.point.fas as fas
from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.point import build_result, problem_from_moes, solve_fas
from ehl_multigrid.point.fas import PointHierarchy, point_solver
from ehl_multigrid.point.postprocess import film_metrics, full_fields, solution_metrics


def test_grids_share_one_scratch_and_one_residual_array():
    hz = PointHierarchy(problem_from_moes(20.0, 10.0), PointOptions(points=129, half=True))
    fine = hz.levels[-1]
    for lev in hz.levels:
        assert np.shares_memory(lev.D, fine.D) and np.shares_memory(lev.r, fine.r)
        assert lev.D.flags.c_contiguous and lev.D.shape == lev.P.shape
    assert hz.levels[0].W is not None  # the coarse solve moves H00 on a fixed W
    assert all(lev.W is None for lev in hz.levels[1:])


class _OwnArrays(PointHierarchy):
    """The hierarchy before the arrays were shared: each grid its own D, r and W."""

    def share_work_arrays(self) -> None:
        for lev in self.levels:
            lev.D, lev.r, lev.W = np.zeros(lev.shape), np.zeros(lev.shape), np.zeros(lev.shape)


def test_shared_arrays_give_the_films_of_separate_arrays(monkeypatch):
    pb = problem_from_moes(20.0, 10.0)
    opts = PointOptions(points=129, half=False, raise_on_failure=False)
    shared = point_solver(pb, opts)
    a = shared.solve()
    monkeypatch.setattr(fas, "PointHierarchy", _OwnArrays)
    own = fas.point_solver(pb, opts)
    assert isinstance(own.hierarchy, _OwnArrays)
    b = own.solve()
    assert a.work_units == b.work_units and a.iterations == b.iterations
    fa, fb = shared.hierarchy.levels[-1], own.hierarchy.levels[-1]
    assert np.array_equal(fa.P, fb.P) and np.array_equal(fa.H, fb.H)


def _same(a: dict, b: dict) -> bool:
    return a.keys() == b.keys() and all(
        a[k] == b[k] or (isinstance(a[k], float) and math.isnan(a[k]) and math.isnan(b[k])) for k in a)


def test_half_domain_scalars_equal_those_of_the_mirrored_domain():
    sol = solve_fas(problem_from_moes(20.0, 10.0), points=65, half=True)
    Y, P, H = full_fields(sol.X, sol.Y, sol.P, sol.H, True)
    assert _same(solution_metrics(sol.X, sol.Y, sol.P, sol.H, True), film_metrics(sol.X, Y, P, H))
    with_fields = build_result(sol).scalars
    assert _same(build_result(sol, fields=False).scalars, with_fields)
    assert with_fields["Y_Hm"] < 0.0  # the mirrored domain's first minimum: the lower lobe


def test_the_starved_residual_stays_in_the_shared_buffer():
    # the starved hierarchy's residual used to rebind lev.r to a fresh array per grid
    from ehl_multigrid.starved.point import StarvedPointHierarchy

    hz = StarvedPointHierarchy(problem_from_moes(20.0, 10.0), PointOptions(points=129, half=True), 0.3)
    fine = hz.levels[-1]
    for lev in hz.levels:
        lev.theta = np.ones(lev.shape)
        r = hz.residual(lev)
        assert r is lev.r and np.shares_memory(lev.r, fine.r)
