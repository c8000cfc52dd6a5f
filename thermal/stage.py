"""Main-job stage: the traction curve of the scene (registered in ``ehl.stages``).

Thermal or isothermal as the plan decides; EHL pressure and film when the core film stage
solved them (the planner rejected the fit), Hertz with the fitted film otherwise; the report
says which.
"""

from __future__ import annotations

from pathlib import Path

from ehl_multigrid.app.stages import RunContext, StageOutput

from .options import ThermalOptions
from .traction import default_slips, traction_curve, traction_result


def traction_stage(ctx: RunContext) -> StageOutput | None:
    scene, plan = ctx.scene, ctx.plan
    thermal = plan.includes("thermal")
    film = ctx.result("film")
    use_ehl = film is not None and film.kind in ("ehl_line", "ehl_point")
    options = ThermalOptions.for_fidelity(scene, plan.fidelity, thermal=thermal)
    slips = [float(s) for s in default_slips(scene)]
    points = traction_curve(scene, slips, options=options, input="ehl" if use_ehl else "hertz",
                            ehl=film if use_ehl else None)
    res = traction_result(scene, points, options)
    hc_fit = scene.central_film_fit()[1]
    if use_ehl:
        film_source = (f"solved EHL pressure and film of the film stage (hc = {film.scalars['hc'] * 1e9:.4g} nm; "
                       f"the fit gives {hc_fit * 1e9:.4g} nm)")
    else:
        film_source = f"Hertz pressure and the fitted film hc = {hc_fit * 1e9:.4g} nm ({plan.get('film').setting})"
    res.meta["film_source"] = film_source
    figures: list[Path] = []
    if ctx.plots:
        from .plots import plot_all

        figures = [Path(p) for p in plot_all(res, ctx.outdir, f"traction_{scene.name}").values()]
    fmax = max(points, key=lambda p: abs(p.coefficient))
    summary = {
        "thermal": thermal, "input": "ehl" if use_ehl else "hertz",
        "slip": [p.slip for p in points], "friction_coefficient": [p.coefficient for p in points],
        "max_temperature_rise": [p.max_temperature_rise for p in points],
        "converged": all(p.converged for p in points), "film_source": film_source,
    }
    text = (f"{'Thermal' if thermal else 'Isothermal'} Eyring traction over {len(points)} slips: largest |f| = "
            f"{abs(fmax.coefficient):.4g} at slip {fmax.slip:g}, largest temperature rise "
            f"{max(p.max_temperature_rise for p in points):.3g} K; converged: {summary['converged']}. "
            f"Film: {film_source}.")
    return StageOutput("traction", res, summary, figures, text)


traction_stage.order = 20
