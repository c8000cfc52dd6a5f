"""Main-job stage: the traction curve of the scene (registered in ``ehl.stages``).

Thermal or isothermal as the plan decides; EHL pressure and film when the core film stage
solved them, Hertz with the fitted film otherwise.
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
    figures: list[Path] = []
    if ctx.plots:
        from .plots import plot_all

        figures = [Path(p) for p in plot_all(res, ctx.outdir, f"traction_{scene.name}").values()]
    fmax = max(points, key=lambda p: abs(p.coefficient))
    summary = {
        "thermal": thermal, "input": "ehl" if use_ehl else "hertz",
        "slip": [p.slip for p in points], "friction_coefficient": [p.coefficient for p in points],
        "max_temperature_rise": [p.max_temperature_rise for p in points],
        "converged": all(p.converged for p in points),
    }
    text = (f"{'Thermal' if thermal else 'Isothermal'} Eyring traction over {len(points)} slips "
            f"({'EHL' if use_ehl else 'Hertz + fitted'} film): largest |f| = {abs(fmax.coefficient):.4g} at slip "
            f"{fmax.slip:g}, largest temperature rise {max(p.max_temperature_rise for p in points):.3g} K; "
            f"converged: {summary['converged']}.")
    return StageOutput("traction", res, summary, figures, text)


traction_stage.order = 20
