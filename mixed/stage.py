"""Main-job stage: the Stribeck curve of a rough scene (registered in ``ehl.stages``).

Skipped for smooth scenes. Thermal film friction and starved curves as the plan decides.
"""

from __future__ import annotations

from pathlib import Path

from ehl_multigrid.app.stages import RunContext, StageOutput

#: Thermal film-friction grid of the Stribeck stage per fidelity, from the accuracy-cost study
#: (validation/pareto/REPORT.md): largest friction error over three speeds against 160 x 40 was
#: 0.82 % (20 x 5), 0.09 % (40 x 10) for the page-63 line and 0.51 %, 0.08 % for series D.
THERMAL_GRID = {"fast": {"nx": 20, "nz": 5}, "standard": {"nx": 20, "nz": 5}, "reference": {"nx": 40, "nz": 10}}


def stribeck_stage(ctx: RunContext) -> StageOutput | None:
    from .stribeck import default_us, stribeck_cases, stribeck_options, stribeck_result

    scene, plan = ctx.scene, ctx.plan
    if scene.roughness is None:
        return None
    thermal = plan.includes("thermal")
    hoil = list(scene.supply.hoil_over_sigma) if plan.includes("starvation") else []
    us = default_us(scene)
    topts = None
    if thermal and not {"nx", "nz"} & set(scene.solver.get("thermal", {})):
        topts = THERMAL_GRID.get(plan.fidelity)
    curves = stribeck_cases(scene, us, hoil_over_sigma=hoil, thermal=thermal, thermal_options=topts,
                            options=stribeck_options(scene))
    res = stribeck_result(scene, curves, thermal=thermal)
    figures: list[Path] = []
    if ctx.plots:
        from .plots import stribeck_figures

        figures = [Path(f) for f in stribeck_figures(curves, ctx.outdir, f"stribeck_{scene.name}")]
    c = curves[0]
    f = c.friction.coefficient
    i_min = int(f.argmin())
    summary = {
        "thermal": thermal, "us": c.us, "friction_coefficient": f,
        "Pa": c.sharing.Pa, "Ph": c.sharing.Ph, "gamma1": c.sharing.gamma1, "hfr": c.sharing.hfr, "hss": c.sharing.hss,
        "converged": c.converged,
    }
    text = (f"{'Thermal' if thermal else 'Isothermal'} Stribeck curve over us = {us.min():.3g}-{us.max():.3g} m/s "
            f"at slip {c.friction.slip:g}: f = {f[0]:.3g} at the slowest speed, minimum {f[i_min]:.3g} at "
            f"{c.us[i_min]:.3g} m/s, {f[-1]:.3g} at the fastest"
            + (f"; starved curves for hoil/sigma = {hoil}" if hoil else "") + f"; converged: {c.converged}.")
    return StageOutput("stribeck", res, summary, figures, text)


stribeck_stage.order = 30
