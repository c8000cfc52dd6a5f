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


def test_a_coupled_thermal_film_solved_after_a_failed_film_stage_is_no_estimate() -> None:
    # page 63 at 16000 N with a 5 nm layer: the isothermal starved solver refuses the supply, the
    # thermal layer's starved TEHL solve converges, and the traction stage computes on that film
    import numpy as np

    from ehl_multigrid.model.results import Result
    from ehl_multigrid.model.solved_film import SolvedFilm

    ctx = _ctx({"converged": False, "status": "start_failed", "message": "severe starvation",
                "solver_fallback": True})
    assert ctx.film_failure() is not None
    res = Result("tehl_line", scene=load_scene("page63_line_16000N"))
    res.add_coord("x", np.linspace(-1e-4, 1e-4, 5), "m")
    res.add_field("p", np.ones(5), "Pa", ("x",))
    res.add_field("h", np.full(5, 4e-9), "m", ("x",))
    res.set_scalar("hc", 4e-9, "m")
    res.set_scalar("status", "converged")
    film = SolvedFilm.from_result(res)
    ctx.outputs["thermal_film"] = StageOutput("thermal_film", None, {"converged": True}, film=film)
    summary = ctx.mark_film_failure({"converged": True})
    assert ctx.film_failure() is None and summary == {"converged": True}
