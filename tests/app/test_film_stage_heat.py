"""A starved point contact whose heat the planner expects to move the film by more than the
tolerance has no coupled thermal solver (the point TEHL solver is a flooded one): its
isothermal film is reported short of its accuracy (status ``inaccurate``, exit 3), never as a
success."""

from __future__ import annotations

import pytest

import ehl_multigrid.front as front
from ehl_multigrid.app.cli import not_converged
from ehl_multigrid.app.mainjob import film_stage
from ehl_multigrid.app.plan import make_plan
from ehl_multigrid.app.stages import TEHL_UNAVAILABLE, RunContext
from ehl_multigrid.model.scene import load_scene


def _slow_sliding_ball(**supply):
    # the default ball at 0.2 m/s in pure rolling-sliding (slip 1): the contact's heat thins the
    # flooded coupled film by 5 % (tests/app/test_plan.py)
    return load_scene("default").with_operating(us=0.2, slip=1.0).with_supply(**supply)


def test_a_starved_sliding_point_contact_is_planned_without_a_coupled_film():
    starved = make_plan(_slow_sliding_ball(hoil=5e-8), tolerance=0.02).get("tehl")
    assert starved.include and starved.setting == TEHL_UNAVAILABLE and starved.estimate > 0.02
    flooded = make_plan(_slow_sliding_ball(hoil=float("inf")), tolerance=0.02).get("tehl")
    assert flooded.setting != TEHL_UNAVAILABLE and "thermal film stage" in flooded.setting
    # at a tolerance above the expected change the isothermal starved film is all it needs
    loose = make_plan(_slow_sliding_ball(hoil=5e-8), tolerance=0.1).get("tehl")
    assert not loose.include and loose.setting != TEHL_UNAVAILABLE


@pytest.mark.solver
def test_the_film_stage_reports_such_a_film_short_of_its_accuracy(tmp_path, monkeypatch):
    sc = _slow_sliding_ball(hoil=5e-8)
    plan = make_plan(sc, tolerance=0.02)
    # a film that met its own (isothermal) target stands in for the starved solve
    met = front.solve(load_scene("appendix_d_point"), physics="steady", accuracy=0.5)
    assert met.success
    monkeypatch.setattr(front, "solve", lambda *args, **kwargs: met)
    out = film_stage(RunContext(sc, plan, tmp_path, plots=False, progress=False))
    assert out.summary["converged"] is False and out.summary["status"] == "inaccurate"
    assert "starved point inlet" in out.summary["message"] and "status: inaccurate" in out.text
    assert "starved point inlet" in (not_converged({"film": out.summary}) or "")


@pytest.mark.solver
def test_a_film_already_short_of_its_target_keeps_its_own_reason_beside_the_heat(tmp_path, monkeypatch):
    sc = _slow_sliding_ball(hoil=5e-8)
    short = front.solve(load_scene("appendix_d_point"), physics="steady", accuracy=1e-4,
                        options={"max_points": 65})
    assert short.status.label == "inaccurate"
    monkeypatch.setattr(front, "solve", lambda *args, **kwargs: short)
    out = film_stage(RunContext(sc, make_plan(sc, tolerance=0.02), tmp_path, plots=False, progress=False))
    assert out.summary["status"] == "inaccurate" and out.summary["converged"] is False
    assert out.summary["message"].startswith(short.message) and "starved point inlet" in out.summary["message"]
