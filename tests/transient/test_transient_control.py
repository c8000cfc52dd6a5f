"""A transient run under the accuracy controller (transient/control.py): with a target the
front door measures the run's time part and grid part and refines the time step (and, unless
the options fix it, the grid) until their sum meets the target; no run is made twice; a time
budget stops it; without a target nothing changes. The grid part and the grid refinement on
their own: test_transient_grid_part.py."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import ehl_multigrid as ehl
from ehl_multigrid import Scene, load_scene
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.multigrid.controller import Resolution, predicted_seconds
from ehl_multigrid.solution import Status

#: a dent 1.7 central films deep through page63_line_2000N: on 129 points the stated time part of
#: Hc is 1.5 % at this step, 0.51 % at half of it and about 0.15 % at a quarter (Hm: 6e-5)
DENT = {"kind": "dent", "amplitude": 1e-8, "width": 1e-4, "x0": -1.5}
DT = 0.01171875
RUN = {"points": 129, "dt": DT, "t_end": 1.0}


def dent_scene() -> Scene:
    d = load_scene("page63_line_2000N").to_dict()
    d["feature"] = DENT
    return Scene.from_dict(d)


def spy_runs(monkeypatch: pytest.MonkeyPatch) -> list[tuple[int, float | None, float | None]]:
    """The ``(points, dt, time_tol)`` of every line run the front door makes."""
    from ehl_multigrid.transient import solve as line_solve

    calls: list[tuple[int, float | None, float | None]] = []
    original = line_solve.solve_transient_line

    def spy(*args, **kw):
        calls.append((kw.get("points"), kw.get("dt"), kw.get("time_tol")))
        return original(*args, **kw)

    monkeypatch.setattr(line_solve, "solve_transient_line", spy)
    return calls


@pytest.fixture
def no_grid_part(monkeypatch: pytest.MonkeyPatch) -> None:
    """The time-step logic alone: every run's grid and box parts are zero (its grid pairs and
    box probes are not run)."""
    from ehl_multigrid.transient.control import TransientControl

    def zero(self, result, at, record):
        g = self.grid_parts[at] = {"Hc": 0.0, "Hm": 0.0, "order_Hc": math.nan, "order_Hm": math.nan}
        return g

    def no_box(self, result, at):
        d = self.box_parts[at.box] = {"Hc": 0.0, "Hm": 0.0}
        return d

    monkeypatch.setattr(TransientControl, "grid_part", zero)
    monkeypatch.setattr(TransientControl, "box_of", no_box)


@pytest.mark.solver
def test_a_run_whose_time_part_dominates_is_refined_in_dt_until_both_parts_meet_the_target(monkeypatch):
    """A 3 nm dent through page 63 at 500 N on 1025 points: at dT = 0.02 the pair at twice the
    step is beyond what the feature allows, so the step is halved (its pair is the first run);
    the grid pairs (513 and 257 points) are run at each answer's step."""
    calls = spy_runs(monkeypatch)
    d = load_scene("page63_line_500N").to_dict()
    d["feature"] = {"kind": "dent", "amplitude": 3e-9, "width": 1e-4, "x0": -1.5}
    sol = ehl.solve(Scene.from_dict(d), physics="transient", accuracy=0.02,
                    options={"points": 1025, "dt": 0.02, "t_end": 1.0})
    assert [(n, d) for n, d, _ in calls] == [(1025, 0.02), (1025, 0.04), (513, 0.02), (257, 0.02),
                                             (1025, 0.01), (513, 0.01), (257, 0.01)]
    t, g, d = sol.error.parts["time"], sol.error.parts["grid"], sol.error.parts["domain"]
    assert sol.status == Status.CONVERGED and sol.details.dt == 0.01 and sol.grid.points == 1025
    assert sol.error.Hc == pytest.approx(t.Hc + g.Hc + d.Hc) and sol.error.Hm == pytest.approx(t.Hm + g.Hm + d.Hm)
    assert max(sol.error.Hc, sol.error.Hm) <= 0.02
    (action,) = sol.outcome.actions
    assert re.match(r"time step halved: 1025 points, dT = 0\.02 -> 1025 points, dT = 0\.01 \(time Hc", action)
    assert "within the accuracy 0.02 after 1 refinement" in sol.message


def test_the_tighter_run_of_an_adaptive_pair_is_the_next_answer(monkeypatch, no_grid_part):
    calls = spy_runs(monkeypatch)
    d = load_scene("page63_line_2000N").to_dict()
    d["feature"] = {"kind": "dent", "amplitude": 5e-8, "width": 5e-5, "x0": -1.5e-4}
    sol = ehl.solve(Scene.from_dict(d), physics="transient", accuracy=3e-4,
                    options={"points": 129, "steps": 16, "time_tol": 1e-2, "time_error": True})
    # time part 4.3e-4 at 1e-2, then 2.4e-4 at an eighth of it (the first run's pair)
    assert [(c[0], c[2]) for c in calls] == [(129, 1e-2), (129, 1e-2 / 8), (129, 1e-2 / 64)]
    assert sol.details.steps == 32 and max(sol.error.parts["time"].Hc, sol.error.parts["time"].Hm) <= 3e-4
    assert re.search(r"time tolerance x0\.125\b.*output step", sol.outcome.actions[0])


def test_a_time_budget_that_forbids_the_refinement_returns_the_first_run_marked_inaccurate(monkeypatch,
                                                                                            no_grid_part):
    from ehl_multigrid.multigrid import controller

    calls = spy_runs(monkeypatch)
    monkeypatch.setattr(controller, "predicted_seconds", lambda *a, **k: 1e6)
    sol = ehl.solve(dent_scene(), physics="transient", accuracy=0.005,
                    options={**RUN, "time_budget": 100.0})
    assert [c[1] for c in calls] == [DT, 2 * DT]
    assert sol.status == Status.INACCURATE and sol.details.dt == DT
    assert sol.error.parts["time"].Hc > 0.005
    why = ("the refinement to 129 points (box x1, tolerance x1, time step x0.5) is predicted to take "
           "about 1000000 s, more than the")
    assert f"not refined further: {why}" in sol.message and "time budget of 100 s" in sol.message
    (action,) = sol.outcome.actions
    assert action.startswith(f"not refined further: {why}") and action.endswith("time budget of 100 s")


def test_without_a_target_the_run_and_its_time_part_are_those_of_today(no_grid_part):
    from ehl_multigrid.line.problem import LineProblem
    from ehl_multigrid.transient.accuracy import time_error
    from ehl_multigrid.transient.scene_feature import feature_from_scene_table
    from ehl_multigrid.transient.solve import solve_transient_line

    opts = {"points": 129, "dt": DT, "steps": 20, "time_error": True}
    plain = ehl.solve(dent_scene(), physics="transient", accuracy=None, options=opts)
    budget = ehl.solve(dent_scene(), physics="transient", accuracy=None, options={**opts, "time_budget": 1.0})
    # a target the first run meets: the controller returns that run and its pair's estimate
    met = ehl.solve(dent_scene(), physics="transient", accuracy=0.5, options=opts)
    scene = dent_scene()
    pb = LineProblem.from_scene(scene, xmin=-4.5)
    feature, body = feature_from_scene_table(scene.feature, pb)
    # the run, and its time part from the run at twice the step (half the steps)
    run = {"body": body, "slide_roll": scene.slip, "points": 129}
    direct = solve_transient_line(pb, feature, dt=DT, steps=20, **run)
    terr = time_error(direct, solve_transient_line(pb, feature, dt=2 * DT, steps=10, **run))
    for sol in (plain, budget, met):
        assert np.array_equal(sol.details.Hc_series, plain.details.Hc_series)
        assert np.array_equal(sol.fields["H"], direct.snapshots[20]["H"])
        assert np.array_equal(sol.raw.Hm, direct.Hm)
        assert (sol.error.parts["time"].Hc, sol.error.parts["time"].Hm) == (terr["Hc"], terr["Hm"])
    assert plain.status == budget.status == Status.CONVERGED and plain.message == budget.message
    assert met.status == Status.CONVERGED and "within the accuracy 0.5" in met.message


def test_a_checkpoint_with_a_refinement_target_is_refused(tmp_path):
    from ehl_multigrid.transient.checkpoint import Checkpoint

    with pytest.raises(InputError, match=r"\['checkpoint'\] with an accuracy target"):
        ehl.solve(dent_scene(), physics="transient", accuracy=0.01,
                  options={**RUN, "time_error": True, "checkpoint": Checkpoint(tmp_path / "c.h5")})
    with pytest.raises(InputError, match=r"time_budget = -1 s .*\[0, inf\] s"):
        ehl.solve(dent_scene(), physics="transient", accuracy=0.01, options={**RUN, "time_budget": -1})


def test_the_predicted_time_of_a_refinement_grows_with_its_steps():
    # half the step: twice the steps, on the same grid
    assert predicted_seconds(3.0, 129, Resolution(129, dt=0.5), 1, 1.0) == 6.0
    assert predicted_seconds(3.0, 129, Resolution(257), 1) == 6.0  # unchanged without a time step
    assert Resolution(129, dt=0.25).describe() == "129 points, time step x0.25 (box x1)"
    assert Resolution(129).describe() == "129 points (box x1)"


def test_a_coarse_run_at_a_mesh_per_step_makes_the_time_part_first_order():
    # the default step (Courant 1) can miss a dent: a 0.5 um dent through the tribometer left
    # the minimum film at its smooth value there, and the second-order term stated 0.090 for a
    # true 0.15; from a coarse run at Courant 0.5 the second-order term stays
    from types import SimpleNamespace

    from ehl_multigrid.transient.accuracy import TIME_SAFETY, courant, time_error

    X = np.linspace(-4.5, 1.5, 129)

    def run(dt, hm):
        return SimpleNamespace(dt=dt, X=X, speed=2.0, scheme="bdf2", Hc=np.ones(len(hm)), Hm=np.asarray(hm),
                               steady_film=lambda name: 1.0)

    h = X[1] - X[0]
    for c_coarse, p in ((1.0, 1), (0.5, 2)):
        dt = c_coarse * h / 2.0 / 2.0  # the fine run's step: half the coarse one's
        fine, coarse = run(dt, [1.0, 0.9, 0.8, 0.9, 1.0]), run(2 * dt, [1.0, 0.95, 1.0])
        assert courant(coarse) == pytest.approx(c_coarse)
        assert time_error(fine, coarse)["Hm"] == pytest.approx(TIME_SAFETY * 0.15 / (2**p - 1))
