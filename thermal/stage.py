"""Main-job stage: the traction curve of the scene (registered in ``ehl.stages``).

The stage chooses its own thermal model from the slips it sweeps (:func:`choose_model`): the
heating grows with the slip, so the thermal and the isothermal friction at the largest swept
slip are computed, and the thermal model is used when they differ by more than the plan's
tolerance. The planner's thermal decision is made at the scene's operating slip(s) for the
film and the Stribeck curve; when the two differ the stage says so in the plan's notes.

The friction at the scene's own operating slip is computed at that slip with the chosen
model, with an error estimate (:func:`operating_friction`). EHL pressure and film when a stage
solved them (the core film stage where the planner rejected the fit; the thermal film stage's
coupled film where the plan includes thermal EHL), Hertz with the fitted film otherwise; the
report says which.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ehl_multigrid.app.stages import RunContext, StageOutput
from ehl_multigrid.model.scene import Scene
from ehl_multigrid.multigrid.accuracy import GRID_SAFETY

from .film_error import FilmPart, film_friction_part
from .options import ThermalOptions
from .traction import default_slips, solve_traction, traction_curve, traction_result

#: order of the thermal friction model's grid error assumed by the operating-slip estimate: the
#: Hertz-input line contact converges at order 2, the point slices less regularly; 1.5 keeps the
#: Richardson estimate on the safe side of both (docs/thermal.md, "Traction grid per fidelity")
FRICTION_ORDER = 1.5
#: relative round-off of a computed friction coefficient (the force is a sum over 1e3-1e5
#: cells of the shear stress)
ROUNDOFF = 1e-12


@dataclass
class ModelChoice:
    """The traction stage's thermal model and why: ``thermal``; the largest swept ``slip``
    and, when measured there, the thermal and isothermal friction coefficients, their
    relative ``change`` and the thermal model's ``max_temperature_rise`` [K]; ``reason``."""

    thermal: bool
    slip: float
    reason: str
    f_thermal: float = math.nan
    f_isothermal: float = math.nan
    change: float = math.nan
    max_temperature_rise: float = math.nan

    def payload(self) -> dict[str, Any]:
        return {"thermal": self.thermal, "slip": self.slip, "friction_coefficient_thermal": self.f_thermal,
                "friction_coefficient_isothermal": self.f_isothermal, "relative_change": self.change,
                "max_temperature_rise": self.max_temperature_rise, "reason": self.reason}


def choose_model(scene: Scene, slips: Any, options: ThermalOptions, tolerance: float,
                 **inputs: Any) -> ModelChoice:
    """Thermal or isothermal friction for the slips ``slips``: decided at the largest |slip|,
    where the shear heating is largest, by the thermal and the isothermal friction there on
    the sweep's grid (``options``; ``inputs``: ``input``/``ehl`` of :func:`solve_traction`, the
    film stage's :class:`~ehl_multigrid.model.solved_film.SolvedFilm` in the main job).
    The thermal model is used when ``|f_thermal/f_isothermal - 1| > tolerance``; a scene whose
    ``[solver.thermal]`` sets ``thermal`` keeps its choice."""
    s = np.asarray(slips, dtype=float)
    s_max = float(s[np.argmax(np.abs(s))])
    table = scene.solver.get("thermal", {})
    if "thermal" in table:
        th = bool(table["thermal"])
        return ModelChoice(th, s_max, f"{'thermal' if th else 'isothermal'} as the scene's [solver.thermal] "
                                      f"thermal = {str(th).lower()} sets")
    if s_max == 0.0:
        return ModelChoice(False, 0.0, "every swept slip is 0: no shear heating")
    hot = solve_traction(scene, s_max, options=options.with_changes(thermal=True), **inputs)
    cold = solve_traction(scene, s_max, options=options.with_changes(thermal=False), **inputs)
    change = abs(hot.coefficient / cold.coefficient - 1.0) if cold.coefficient != 0.0 else math.inf
    need = bool(change > tolerance or not hot.converged)
    why = (f"at the largest slip {s_max:g} the thermal model heats the film by "
           f"{hot.max_temperature_rise:.3g} K and changes the friction coefficient from {cold.coefficient:.4g} "
           f"(isothermal) to {hot.coefficient:.4g}, by {change:.2g} "
           f"({'>' if change > tolerance else '<='} the tolerance {tolerance:g})")
    if not hot.converged:
        why += "; the thermal solve there did not converge, so the thermal model is kept and its points say so"
    return ModelChoice(need, s_max, why, hot.coefficient, cold.coefficient, change, hot.max_temperature_rise)


@dataclass
class OperatingFriction:
    """Friction coefficient at the scene's operating slip, its estimated absolute ``error``
    (a coefficient; the friction vanishes at pure rolling, so a relative error would say
    nothing there) and the parts of the estimate."""

    slip: float
    coefficient: float
    error: float
    parts: dict[str, float] = field(default_factory=dict)
    max_temperature_rise: float = 0.0
    converged: bool = True
    grid: str = ""
    #: how the film part of the error was measured ("" without one)
    film_part: str = ""

    def payload(self) -> dict[str, Any]:
        return {"slip": self.slip, "friction_coefficient": self.coefficient,
                "friction_coefficient_error": self.error, "error_parts": dict(self.parts),
                "max_temperature_rise": self.max_temperature_rise, "converged": self.converged,
                "grid": self.grid, "film_part": self.film_part}


def with_coupled_friction(op: OperatingFriction, coupled: float | None) -> OperatingFriction:
    """``op`` with the part ``coupled`` = ``|f - f_coupled|`` where the thermal film stage's
    coupled thermal EHL solve gave its own friction coefficient ``coupled`` at the same slip.

    Both compute the friction on the same coupled film; the chapter-3 model of this stage and
    the coupled solve's thermal layer treat the pressure term of the shear stress differently
    (momentum ``auto`` against the solve's flow factors), and the difference is as large as
    the grid part or larger: a spur gear at slip 0.6 (1025 points, nx 1024, nz 20 on the same
    box) gives 0.04448 here (0.04436 with ``momentum="on"``) against the solve's 0.04426."""
    if coupled is None or not math.isfinite(coupled):
        return op
    parts = {**op.parts, "coupled": abs(op.coefficient - float(coupled))}
    return OperatingFriction(op.slip, op.coefficient, float(sum(parts.values())), parts, op.max_temperature_rise,
                             op.converged, op.grid, op.film_part)


def with_film_part(op: OperatingFriction, part: FilmPart) -> OperatingFriction:
    """``op`` with the part ``film``: the friction's change with the grid of the film it is
    computed on (:func:`~thermal.film_error.film_friction_part`). Not measured (NaN): the error
    is unknown and ``op`` no longer counts as converged."""
    parts = {**op.parts, "film": part.error}
    ok = op.converged and math.isfinite(part.error)
    return OperatingFriction(op.slip, op.coefficient, float(sum(parts.values())), parts, op.max_temperature_rise,
                             ok, op.grid, part.how)


def finer(options: ThermalOptions) -> ThermalOptions:
    """The grid twice as fine in every direction (nx, nz, slices)."""
    return options.with_changes(nx=2 * options.nx, nz=2 * options.nz, slices=2 * options.slices)


def operating_friction(scene: Scene, options: ThermalOptions, choice: ModelChoice, **inputs: Any) -> OperatingFriction:
    """The friction coefficient at ``scene.slip`` with the chosen model (``options``), computed
    at that slip on the grid twice as fine as the sweep's in nx, nz and slices, with its error:

    * ``grid`` -- Richardson from the sweep's grid, ``GRID_SAFETY |f_h - f_2h| / (2^p - 1)``
      with ``p`` = :data:`FRICTION_ORDER`;
    * ``iteration`` -- the thermal march's stress tolerance times ``|f|``;
    * ``model`` -- with the isothermal model at a non-zero slip, the thermal change measured
      at the largest of the swept and operating slips (where it is largest) times ``|f|``;
    * ``roundoff`` -- :data:`ROUNDOFF` times the friction at that slip (at pure
      rolling the friction vanishes and what is computed is round-off).
    """
    fine_opts = finer(options)
    fine = solve_traction(scene, scene.slip, options=fine_opts, **inputs)
    coarse = solve_traction(scene, scene.slip, options=options, **inputs)
    f = fine.coefficient
    grid = GRID_SAFETY * abs(f - coarse.coefficient) / (2.0**FRICTION_ORDER - 1.0)
    iteration = options.tol_tau * abs(f)
    model = 0.0
    if not options.thermal and scene.slip != 0.0 and math.isfinite(choice.change):
        model = choice.change * abs(f)
    scale = max([abs(f)] + [abs(v) for v in (choice.f_thermal, choice.f_isothermal) if math.isfinite(v)])
    parts = {"grid": grid, "iteration": iteration, "model": model, "roundoff": ROUNDOFF * scale}
    point = scene.kind != "line"
    desc = f"nx {fine_opts.nx}, nz {fine_opts.nz}" + (f", {fine_opts.slices} slices" if point else "")
    return OperatingFriction(float(scene.slip), float(f), float(sum(parts.values())), parts,
                             float(fine.max_temperature_rise), bool(fine.converged and coarse.converged), desc)


def traction_stage(ctx: RunContext) -> StageOutput | None:
    scene, plan = ctx.scene, ctx.plan
    film = ctx.film()
    use_ehl = film is not None
    inputs = {"input": "ehl" if use_ehl else "hertz", "ehl": film}
    slips = [float(s) for s in default_slips(scene)]
    base = ThermalOptions.for_fidelity(scene, plan.fidelity)
    # the operating slip too: a range given in the scene may stop short of it, and the operating
    # friction's model part is the change measured here
    choice = choose_model(scene, [*slips, float(scene.slip)], base, plan.tolerance, **inputs)
    thermal = choice.thermal
    options = base.with_changes(thermal=thermal)
    notes = []
    if thermal != plan.includes("thermal"):
        notes.append(
            f"traction curve: {'thermal' if thermal else 'isothermal'} model over its slips up to {choice.slip:g} "
            f"(the plan's thermal decision, made at the operating slip {scene.slip:g} for the film and the "
            f"Stribeck curve, is {'thermal' if plan.includes('thermal') else 'isothermal'}): {choice.reason}")
    points = traction_curve(scene, slips, options=options, **inputs)
    res = traction_result(scene, points, options)
    op = operating_friction(scene, options, choice, **inputs)
    if film is not None:
        op = with_film_part(op, film_friction_part(scene, film, finer(options), op.coefficient, **inputs))
    coupled = ctx.outputs.get("thermal_film")
    f_coupled = None
    if film is not None and film.thermal and coupled is not None and coupled.summary.get("slip") == op.slip:
        f_coupled = coupled.summary.get("friction_coefficient")
        op = with_coupled_friction(op, f_coupled)
    hc_fit = scene.supplied_film_fit()[1]
    fitted = ("fitted film" if math.isinf(scene.supply.hoil) else
              f"fitted film starved by Chevalier's (6.1) for hoil = {scene.supply.hoil * 1e9:.4g} nm")
    if film is not None:
        solved = ("coupled thermal EHL pressure and film of the thermal film stage" if film.thermal else
                  "solved EHL pressure and film of the film stage")
        film_source = f"{solved} (hc = {film.hc * 1e9:.4g} nm; the {fitted} gives {hc_fit * 1e9:.4g} nm)"
    else:
        film_source = f"Hertz pressure and the {fitted} hc = {hc_fit * 1e9:.4g} nm ({ctx.setting('film')})"
    res.meta["film_source"] = film_source
    res.meta["thermal_model"] = choice.reason
    res.set_scalar("operating_slip", op.slip)
    res.set_scalar("friction_coefficient_at_operating_slip", op.coefficient)
    res.set_scalar("friction_coefficient_at_operating_slip_error", op.error)
    figures: list[Path] = []
    if ctx.plots:
        from .plots import plot_all

        figures = [Path(p) for p in plot_all(res, ctx.outdir, f"traction_{scene.name}").values()]
    fmax = max(points, key=lambda p: abs(p.coefficient))
    summary = {
        "thermal": thermal, "thermal_model": choice.payload(), "input": inputs["input"],
        "slip": [p.slip for p in points], "friction_coefficient": [p.coefficient for p in points],
        "max_temperature_rise": [p.max_temperature_rise for p in points],
        "operating_slip": op.slip, "friction_coefficient_at_operating_slip": op.coefficient,
        "friction_coefficient_at_operating_slip_error": op.error, "operating_point": op.payload(),
        "converged": all(p.converged for p in points) and op.converged, "film_source": film_source,
    }
    text = (f"{'Thermal' if thermal else 'Isothermal'} Eyring traction over {len(points)} slips "
            f"({'thermal' if thermal else 'isothermal'} model because {choice.reason}): largest |f| = "
            f"{abs(fmax.coefficient):.4g} at slip {fmax.slip:g}, largest temperature rise "
            f"{max(p.max_temperature_rise for p in points):.3g} K. At the operating slip {op.slip:g}: "
            f"f = {op.coefficient:.4g} +- {op.error:.2g} (estimated; computed at that slip on {op.grid}, "
            f"temperature rise {op.max_temperature_rise:.3g} K"
            + ("" if "film" not in op.parts else f"; the film's grid {op.parts['film']:.2g} of it"
               if math.isfinite(op.parts["film"]) else f"; the film's grid part unknown ({op.film_part})")
            + (f"; the coupled thermal EHL solve's own friction, {f_coupled:.4g}, counted in the error"
               if "coupled" in op.parts else "")
            + f"); converged: {summary['converged']}. "
            f"Film: {film_source}.")
    if plan.includes("asperities"):
        # a rough scene: this is the friction of the film alone; the Stribeck stage shares the
        # load with the asperities
        lam = plan.get("asperities").estimate
        summary["full_film_only"] = True
        text += (f" This is the full film's friction (smooth surfaces): the surfaces are rough "
                 f"(the smooth film's Lambda = hc/Rq down to {lam:.3g} over the planned speeds), so the asperities carry part of the load; the "
                 f"Stribeck stage gives the mixed friction at the operating point.")
    if ctx.mark_film_failure(summary).get("status") == "film_estimate":
        text += f" NOT A SOLVED-FILM RESULT: {summary['message']}."
    return StageOutput("traction", res, summary, figures, text, notes=notes)


traction_stage.order = 20
