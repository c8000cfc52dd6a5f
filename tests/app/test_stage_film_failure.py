"""Stages computed on the film stage's film: only a fallback estimate makes them failures; a
solved film short of its accuracy target is still a solved film."""

from __future__ import annotations

from pathlib import Path

from ehl_multigrid.app.stages import RunContext, StageOutput
from ehl_multigrid.model.scene import load_scene


def _ctx(film_summary: dict) -> RunContext:
    ctx = RunContext(load_scene("appendix_d_point"), plan=None, outdir=Path("."))
    ctx.outputs["film"] = StageOutput("film", None, film_summary)
    return ctx


def test_a_solved_film_short_of_its_target_does_not_mark_later_stages_as_estimates() -> None:
    ctx = _ctx({"converged": False, "status": "inaccurate", "message": "Hm error 0.19 > 0.02"})
    summary = ctx.mark_film_failure({"converged": True})
    assert ctx.film_failure() is None and summary == {"converged": True}


def test_a_fallback_film_marks_later_stages_with_the_reason() -> None:
    ctx = _ctx({"converged": False, "status": "diverged", "message": "the FMG start diverged",
                "solver_fallback": True})
    summary = ctx.mark_film_failure({"converged": True})
    assert summary["converged"] is False and summary["status"] == "film_estimate"
    assert "diverged" in summary["message"] and "FMG start" in summary["message"]
