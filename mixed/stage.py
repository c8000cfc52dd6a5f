"""Main-job stage: the Stribeck curve of a rough scene (registered in ``ehl.stages``).

Skipped for smooth scenes. Thermal film friction and starved curves as the plan decides; the
thermal grid is the fidelity's (:data:`~ehl_multigrid.model.fidelity.FIDELITIES`). When the film
stage solved the film (the planner rejected the fit; ``ctx.film()``), the fitted film of the load
sharing is calibrated on it: ``hc_solved/hc_fit`` at the operating point, applied over the
speed range; the report says which film was used.
"""

from __future__ import annotations

import math
from pathlib import Path

from ehl_multigrid.app.stages import RunContext, StageOutput
from ehl_multigrid.model.fidelity import FIDELITIES


def film_calibration(ctx: RunContext) -> tuple[float, str]:
    """``(film_factor, description)``: the solved central film over the fitted one at the
    operating point when the film stage ran the EHL solver, else ``(1, why the fit)``."""
    scene = ctx.scene
    film = ctx.film()
    hc_fit = scene.central_film_fit()[1]
    if film is not None:
        hc = film.hc
        ratio = film.Hc_ratio
        if ratio is not None and math.isfinite(ratio) and ratio > 0.0:
            # a starved solve: the curves apply the starvation of each supply themselves (6.4),
            # so the calibration takes the flooded film of the same discretisation
            hc_ff = hc / ratio
            k = hc_ff / hc_fit
            return k, (f"fitted film calibrated on the solved flooded film (the starved solve's "
                       f"flooded companion, hc = {hc * 1e9:.4g} nm starved): hc_flooded/hc_fit = "
                       f"{hc_ff * 1e9:.4g}/{hc_fit * 1e9:.4g} nm = {k:.4g} at the operating point, applied "
                       f"over the speed range; the starvation of each supply from (6.4)")
        k = hc / hc_fit
        what = "solved film"
        if film.thermal:
            # its thermal reduction is the operating speed's; the heating grows with the speed squared
            what = "coupled thermal film (its thermal reduction at the operating speed)"
        return k, (f"fitted film calibrated on the {what}: hc_solved/hc_fit = {hc * 1e9:.4g}/{hc_fit * 1e9:.4g} nm "
                   f"= {k:.4g} at the operating point, applied over the speed range")
    setting = ctx.setting("film") if ctx.plan is not None else "fit"
    return 1.0, f"fitted film ({setting}; hc_fit = {hc_fit * 1e9:.4g} nm at the operating point)"


#: regime codes of :func:`~mixed.stribeck.classify_regime` in the words of a summary
REGIME_WORDS = {"BL": "boundary lubrication", "ML": "mixed lubrication", "EHL": "full-film EHL"}


def stribeck_stage(ctx: RunContext) -> StageOutput | None:
    from .stribeck import default_us, stribeck_cases, stribeck_options, stribeck_result
    from .tasks import stribeck_point_task

    scene, plan = ctx.scene, ctx.plan
    if scene.roughness is None:
        return None
    thermal = plan.includes("thermal")
    hoil = list(scene.supply.hoil_over_sigma) if plan.includes("starvation") else []
    us = default_us(scene)
    topts = None
    level = FIDELITIES.get(plan.fidelity)
    if thermal and level is not None and not {"nx", "nz"} & set(scene.solver.get("thermal", {})):
        # the fidelity's grid unless the scene sets one
        topts = level.stribeck.as_options()
    factor, film_source = film_calibration(ctx)
    curves = stribeck_cases(scene, us, hoil_over_sigma=hoil, thermal=thermal, thermal_options=topts,
                            options=stribeck_options(scene), film_factor=factor)
    res = stribeck_result(scene, curves, thermal=thermal)
    res.meta["film_source"] = film_source
    figures: list[Path] = []
    if ctx.plots:
        from .plots import stribeck_figures

        figures = [Path(f) for f in stribeck_figures(curves, ctx.outdir, f"stribeck_{scene.name}")]
    c = curves[0]
    f = c.friction.coefficient
    op = stribeck_point_task(scene, thermal=thermal, thermal_options=topts, film_factor=factor)
    i_min = int(f.argmin())
    summary = {
        "thermal": thermal, "us": c.us, "friction_coefficient": f,
        "Pa": c.sharing.Pa, "Ph": c.sharing.Ph, "gamma1": c.sharing.gamma1, "hfr": c.sharing.hfr, "hss": c.sharing.hss,
        "converged": c.converged and op["converged"], "film_factor": factor, "film_source": film_source,
        "operating_point": op,
    }
    text = (f"{'Thermal' if thermal else 'Isothermal'} Stribeck curve over us = {us.min():.3g}-{us.max():.3g} m/s "
            f"at slip {c.friction.slip:g}: f = {f[0]:.3g} at the slowest speed, minimum {f[i_min]:.3g} at "
            f"{c.us[i_min]:.3g} m/s, {f[-1]:.3g} at the fastest"
            + (f"; starved curves for hoil/sigma = {hoil}" if hoil else "")
            + f". At the operating us = {op['us']:.3g} m/s: f = {op['friction_coefficient']:.4g}, the asperities "
            f"carry {100 * op['asperity_fraction']:.3g} % of the load (load-sharing film hfr/Rq = {op['Lambda']:.3g}): "
            f"{REGIME_WORDS[op['regime']]}; converged: {summary['converged']}. Film: {film_source}.")
    if ctx.mark_film_failure(summary).get("status") == "film_estimate":
        text += f" NOT A SOLVED-FILM RESULT: {summary['message']}."
    return StageOutput("stribeck", res, summary, figures, text)


stribeck_stage.order = 30
