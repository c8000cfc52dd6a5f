"""Main-job stage: the coupled thermal EHL film (registered in ``ehl.stages``).

The planner's ``tehl`` decision weighs the thermal film reduction (Gupta et al. 1992) against
the fidelity's tolerance. Where the plan stages it, this stage solves the
film again with the temperature across it (thermal.tehl: Reynolds with Eyring flow factors,
the energy equation (3.5) and the surface temperatures, coupled by an outer iteration) through
the front door :func:`ehl_multigrid.solve` (``physics="thermal"``) at the plan's tolerance and
the scene's operating slip. Its film is the one the later stages (traction, Stribeck) compute
on (:meth:`~ehl_multigrid.app.stages.RunContext.film` takes the last solved film). A point
contact's coupled solve costs 10-150 s (docs/thermal.md): it runs where the plan stages it (the
contact's heat, ``plan.CONTACT_HEATING_FILM_POINT``, or a third of Gupta's reduction above the
tolerance, ``plan.TEHL_POINT_FRACTION``); elsewhere the plan advises it (``ehl solve SCENE
--thermal``) and this stage does not run.

A solve that fails leaves the film stage's isothermal film to the later stages and says so:
its summary's ``converged`` is false (exit 3), since the plan found the isothermal film off by
more than the tolerance.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from ehl_multigrid.app.stages import TEHL_STAGED, RunContext, StageOutput
from ehl_multigrid.model.solved_film import SolvedFilm

#: thermal loading ``beta eta0 um^2/k`` above which the stage does not try the coupled solve,
#: which ends erratically beyond about 3 (docs/thermal.md, "Limits: thermal loading above about 3")
COUPLED_LOADING_LIMIT = 3.0

#: the result keys of the coupled solve that the stage's summary carries
SUMMARY_KEYS = ("Hc", "Hm", "hc", "hm", "Hc_isothermal", "Hm_isothermal", "film_reduction", "T_max",
                "friction_coefficient", "outer_iterations", "slip")


def thermal_film_stage(ctx: RunContext) -> StageOutput | None:
    """The coupled thermal EHL film of a scene whose plan stages ``tehl`` (None for other
    scenes and plans)."""
    from ehl_multigrid.solution import Status

    scene, plan = ctx.scene, ctx.plan
    if not plan.includes("tehl") or plan.get("tehl").setting != TEHL_STAGED:
        return None
    loading = scene.thermal_properties()["thermal_loading"]
    if loading > COUPLED_LOADING_LIMIT:
        note = (f"the coupled thermal EHL solve was not tried: the thermal loading {loading:.3g} lies beyond "
                f"the coupled solver's range (about {COUPLED_LOADING_LIMIT:g}, docs/thermal.md; `ehl solve "
                f"SCENE --thermal` tries it); the later stages compute on the film stage's isothermal film, "
                f"which the plan finds off by more than the tolerance {plan.tolerance:g} "
                f"(Gupta's reduction {plan.get('tehl').estimate:.2g})")
        summary = {"converged": False, "status": "not_tried", "message": note}
        return StageOutput("thermal_film", None, summary, [], f"NO THERMAL FILM: {note}.", notes=[note])
    options: dict[str, Any] = ctx.solve_limits()
    sol = ctx.solve(scene, physics="thermal", accuracy=plan.tolerance, options=options or None)
    usable = sol.status in (Status.CONVERGED, Status.INACCURATE) and sol.fields
    res = sol.to_result() if usable else None
    if res is None or not (res.scalars.get("hm") or 0.0) > 0.0:
        why = (sol.message or "no message").splitlines()[0]
        note = (f"the coupled thermal EHL solve did not give a film ({sol.status.label}: {why}); the later "
                f"stages compute on the film stage's isothermal film, which the plan finds off by more "
                f"than the tolerance {plan.tolerance:g}")
        summary = {"converged": False, "status": sol.status.label, "message": note}
        return StageOutput("thermal_film", None, summary, [], f"NO THERMAL FILM: {note}.", notes=[note])
    err = sol.error
    summary = {k: res.scalars.get(k) for k in SUMMARY_KEYS}
    summary.update(points=sol.grid.points if sol.grid is not None else None, nz=sol.details.nz,
                   Hc_error=err.Hc, Hm_error=err.Hm, converged=True, status=sol.status.label,
                   message=sol.message)
    notes = []
    if sol.status is Status.INACCURATE:
        notes.append(f"thermal film solve did not reach the {plan.tolerance:g} target: estimated errors "
                     f"Hc {err.Hc:.2g}, Hm {err.Hm:.2g}")
    s = res.scalars
    why = next((n for n in err.notes if n.startswith(("T_max is", "T_max's"))), "not measured")
    t_error = (f"+- {sol.details.T_max_error_K:.2g} K" if math.isfinite(sol.details.T_max_error_K) else
               f"error unknown: {why}")
    friction = f", friction coefficient {s['friction_coefficient']:.4g}" if s["slip"] != 0.0 else ""
    text = (f"Coupled thermal EHL film at the operating slip {s['slip']:g} on {summary['points']} points "
            f"along X, nz {summary['nz']}: hc = {s['hc'] * 1e9:.4g} nm, hm = {s['hm'] * 1e9:.4g} nm "
            f"(Hc/Hc_isothermal {s['Hc'] / s['Hc_isothermal']:.4g}, Hm/Hm_isothermal "
            f"{s['Hm'] / s['Hm_isothermal']:.4g} on the same grid); largest oil temperature "
            f"{s['T_max']:.4g} degC ({t_error}){friction}; estimated errors Hc {err.Hc:.2g}, Hm {err.Hm:.2g} (target "
            f"{plan.tolerance:g}); status: {sol.status.label}. The later stages compute on this film.")
    figures: list[Path] = []
    if ctx.plots:
        from .tehl.plots import plot_tehl

        figures.append(Path(plot_tehl(res, ctx.outdir / f"{scene.name}_thermal_film.png")))
    return StageOutput("thermal_film", res, summary, figures, text, notes=notes, film=SolvedFilm.from_result(res, sol.grid))


# after the core film stage, before the traction curve (order 20) that computes on its film
thermal_film_stage.order = 10
