"""A later solve of a line accuracy sequence goes on from the previous converged solve of the
same discrete problem (line.solver.resumable, LineHierarchy._resumed_start)."""

import dataclasses

import pytest

from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.line.solver import resumable, solve_line_problem
from ehl_multigrid.multigrid.options import LineOptions

# the tests read the module's three solves: one worker builds them once
pytestmark = pytest.mark.xdist_group("fmg_resume_coarse_and_fine")


@pytest.fixture(scope="module")
def coarse_and_fine():
    pb = LineProblem.from_moes(1000.0, 10.0)
    opts = LineOptions(points=4097, film_tol=1e-5)
    coarse = solve_line_problem(pb, opts)
    fine_opts = dataclasses.replace(opts, points=16385)
    fresh = solve_line_problem(pb, fine_opts)
    resumed = solve_line_problem(pb, fine_opts, resume=coarse)
    return coarse, fresh, resumed


def test_the_resumed_solve_gives_the_fresh_solves_films_for_less_work(coarse_and_fine):
    coarse, fresh, resumed = coarse_and_fine
    assert coarse.success and fresh.success and resumed.success
    assert any("resumed" in a and "4097-point" in a for a in resumed.actions)
    for f in ("Hc", "Hm"):
        # both stop on the films at a relative change of 1e-5 per cycle
        assert resumed.scalars[f] == pytest.approx(fresh.scalars[f], rel=1e-4)
    assert resumed.work_units < fresh.work_units


def test_the_grids_below_keep_the_previous_solves_fmg_films(coarse_and_fine):
    coarse, _, resumed = coarse_and_fine
    top = coarse.levels - 1
    below = [d for d in coarse.fmg if d["level"] < top]
    assert resumed.fmg[: len(below)] == below
    start = resumed.fmg[len(below)]
    assert start["points"] == 4097
    assert start["Hc"] == pytest.approx(coarse.scalars["Hc_venner"], rel=1e-12)


def test_resumable_takes_the_finest_coarser_grid_of_the_same_discretisation(coarse_and_fine):
    coarse, fresh, _ = coarse_and_fine
    opts = dataclasses.replace(coarse.options, points=65537, tol=1e-6)  # tolerances may differ
    grids = {(4097, 1.0): coarse, (16385, 1.0): fresh}
    assert resumable(grids, 65537, 1.0, opts) is fresh
    assert resumable(grids, 65537, 2.0, opts) is None  # another box
    assert resumable(grids, 16385, 1.0, opts) is coarse  # only coarser grids
    assert resumable(grids, 65537, 1.0, dataclasses.replace(opts, face="logarithmic")) is None


def test_a_solve_whose_cycles_were_rejected_is_not_resumed(coarse_and_fine):
    # its contact's cycles are fragile: page-63 500 N at 0.1 %, resumed on 8193 points from such
    # a 4097-point solve, rejected cycles for 1.4 s where the whole FMG converged in 0.14 s
    coarse, _, _ = coarse_and_fine
    fragile = dataclasses.replace(coarse, actions=["cycle 1 on grid 6 rejected (residual 0.000356, ...)"])
    opts = dataclasses.replace(coarse.options, points=16385)
    assert resumable({(4097, 1.0): coarse}, 16385, 1.0, opts) is coarse
    assert resumable({(4097, 1.0): fragile}, 16385, 1.0, opts) is None
