"""A thermal EHL solve is bounded by its time budget while it runs: the outer iteration checks
the budget of the accuracy-driven sequence between iterations (an outer iteration at a
stationary surface can run for many minutes, docs/thermal.md "Limits")."""

from __future__ import annotations

import ehl_multigrid as em
from ehl_multigrid.solution import Status


def test_a_thermal_solve_whose_budget_runs_out_in_its_outer_iteration_fails_naming_the_budget():
    sol = em.solve("appendix_c_line_4240N", physics="thermal", accuracy=0.005, options={"time_budget": 0.0})
    assert sol.status is Status.TIME_BUDGET and not sol.success
    first = sol.message.splitlines()[0]
    assert "time budget of 0 s" in first and "outer iteration 1" in first
    assert "time_budget" in sol.message  # what to try


def test_a_refinements_predicted_cost_counts_the_solves_on_its_grid_not_the_coarser_ones():
    # the controller scales what a refinement repeats: the round's solves on its grid (the solve,
    # its nz and box probes), not the estimate's coarser grid (the next round's coarse grid is
    # this one) nor solves of earlier rounds
    from ehl_multigrid.model.scene import load_scene
    from ehl_multigrid.multigrid.controller import Resolution
    from thermal.tehl.accuracy import _TEHLControl
    from thermal.tehl.line import TEHLOptions

    scene = load_scene("appendix_d_point")
    ctl = _TEHLControl(scene, scene.slip, TEHLOptions(points=257), True, 1025, 40, 4.0, 0.02)
    ctl.cache.walls = [((129, 20, 1.0), 5.0)]  # an earlier round
    ctl.round = (ctl.cache, 1)
    ctl.cache.walls += [((257, 20, 1.0), 18.0), ((129, 20, 1.0), 172.0), ((257, 10, 1.0), 19.0),
                        ((257, 20, 2.0), 32.0)]
    assert ctl.recurring_seconds(Resolution(257, 1.0, 1.0, 20)) == 18.0 + 19.0 + 32.0
    # the grid's own solve made in an earlier round (a probe then) counts once
    ctl.cache.walls = [((513, 20, 1.0), 40.0), ((257, 20, 1.0), 18.0)]
    ctl.round = (ctl.cache, 2)
    ctl.cache.walls += [((513, 10, 1.0), 25.0)]
    assert ctl.recurring_seconds(Resolution(513, 1.0, 1.0, 20)) == 25.0 + 40.0
    # nothing of the round on its grid or finer, and its own solve unknown: the whole round
    ctl.cache.walls = [((129, 20, 1.0), 5.0)]
    ctl.round = (ctl.cache, 0)
    assert ctl.recurring_seconds(Resolution(257, 1.0, 1.0, 20)) is None
