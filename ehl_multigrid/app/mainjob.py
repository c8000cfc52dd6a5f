"""``ehl run``: the main job on a scene, planned and end to end.

1. :func:`~ehl_multigrid.app.plan.make_plan` decides what the scene needs (with the numbers why).
2. The core *film* stage computes the pressure and film field: the multigrid solver through the
   front door :func:`ehl_multigrid.solve` when the plan asks for it (accuracy from the
   fidelity), otherwise Hertz pressure with the fitted film.
3. Stages that the layers above register in the ``ehl.stages`` entry-point group run next, in
   the order of their ``order`` attribute (thermal traction curve, Stribeck curve, ...). A stage
   is a callable ``stage(ctx: RunContext) -> StageOutput | None`` (:mod:`ehl_multigrid.app.stages`);
   the core never imports them.
4. All results go into one HDF5 file (rewritten atomically after every stage, so an interrupted
   run keeps the finished stages) and a Markdown report with the figures says what was modelled
   and why.

Outputs are one set per scene: ``<stem>.h5``, ``<stem>_report.md`` and the figures, where
``<stem>`` is the scene name made safe as a file name (:func:`~ehl_multigrid.model.paths.safe_stem`;
nothing is ever written outside the output folder). The run holds the lock of the output folder
(:func:`~ehl_multigrid.model.output_folder.output_lock`: a second command into it is refused, exit code
2), removes the leftovers of dead runs there, writes into a hidden staging folder inside it and
then moves the files of the finished stages into place, removing the files of the scene's
previous run that the new set does not replace (listed in ``.ehl-run-<stem>.json``), so a reused
folder never shows old figures beside a new film, and runs of different scenes into one folder
keep each other's outputs. The HDF5 file's root attribute ``complete`` is false until every stage
has run; an interrupted run (Ctrl-C, SIGTERM) still moves its finished stages into place, marked
incomplete in the file and in the report, while the files of the stage it stopped in never
reach the folder. Progress goes to stderr (:class:`~ehl_multigrid.app.console.Progress`).
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import shutil
import time
from dataclasses import dataclass
from importlib.metadata import entry_points
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from ..model.atomic import atomic_savefig, deferred_signals, fault_point, write_text_atomic
from ..model.errors import signal_cause
from ..model.hertz import hertz_pressure_line, hertz_pressure_point
from ..model.output_folder import output_lock, staging_dir
from ..model.paths import safe_stem, writable_dir
from ..model.results import Result, save_results
from ..model.scene import Scene
from ..model.solved_film import FILM_KINDS, SolvedFilm
from ..solution import Status
from . import warmup
from .console import Progress, print_table, report_leftovers
from .plan import make_plan, print_plan
from .solved import package_result, require_computed
from .stages import TEHL_UNAVAILABLE, RunContext, StageOutput

__all__ = ["MainJobOptions", "RunContext", "StageOutput", "film_stage", "hertz_result",
           "registered_stages", "run_main_job", "write_report"]


@dataclass(frozen=True)
class MainJobOptions:
    """How ``ehl run`` runs a scene.

    Parameters
    ----------
    out_dir : Path
        Folder for the HDF5 file, the report and the figures (created if missing).
    fidelity : str or None
        ``"fast"``, ``"standard"`` or ``"reference"`` (planner default when ``None``).
    tolerance : float or None
        Target relative accuracy; overrides ``fidelity`` when given.
    plots : bool
        Write PNG figures.
    quiet : bool
        No printed summary on stdout (``ehl run --json``); progress still goes to stderr
        (``EHL_PROGRESS=off`` silences it).
    time_budget : float or None
        Seconds for the film stage's multigrid accuracy sequence (flooded contacts): no
        refinement is started that is predicted to overrun it, and the most accurate film so
        far is used, its estimated error stated. ``None``: no bound. The starved solvers refine
        their grid only and do not take it (the report says so).
    max_points : int or None
        Largest grid (points along X) the film stages' accuracy targets may refine to
        (``ehl run --max-points``); ``None``: each solver's own (4097 point, 262145 line, 513
        starved point; the coupled thermal film 1025 point, 16385 line).
    """

    out_dir: Path = Path("ehl_out")
    fidelity: str | None = None
    tolerance: float | None = None
    plots: bool = True
    quiet: bool = False
    time_budget: float | None = None
    max_points: int | None = None


# -- the core film stage -------------------------------------------------------------------------


def hertz_result(scene: Scene, n: int = 201) -> Result:
    """Hertz pressure and fitted uniform film on the scene's contact, as a :class:`Result`."""
    hz = scene.hertz
    res = Result("hertz_fit", scene=scene)
    x = np.linspace(-1.5 * hz.a, 1.5 * hz.a, n)
    res.add_coord("x", x, "m", "rolling direction")
    if scene.kind == "line":
        res.add_field("p", hertz_pressure_line(x, hz.b, hz.pmax), "Pa", ("x",), "Hertz pressure")
    else:
        y = np.linspace(-1.5 * hz.b, 1.5 * hz.b, n)
        res.add_coord("y", y, "m", "transverse direction")
        X, Y = np.meshgrid(x, y, indexing="ij")
        res.add_field("p", hertz_pressure_point(X, Y, hz.a, hz.b, hz.pmax), "Pa", ("x", "y"), "Hertz pressure")
    for k, v in scene.summary().items():
        if isinstance(v, (int, float)):
            res.set_scalar(k, v, _UNITS.get(k, "-"))
    res.meta["stage"] = "hertz + fitted film"
    return res


_UNITS = {
    "load": "N", "us": "m/s", "T_oil": "degC", "E_reduced": "Pa", "Rx": "m", "Ry": "m",
    "eta0": "Pa s", "alpha": "1/Pa", "pmax": "Pa", "mean_pressure": "Pa", "area": "m^2",
    "hc_fit": "m", "hc_fit_supplied": "m", "a": "m", "b": "m", "length": "m",
}


def plot_hertz(res: Result, path: Path) -> Path:
    sc = res.scene
    fig = Figure(figsize=(6, 3.5))
    ax = fig.subplots()
    x = res["x"]
    p = res["p"] if res["p"].ndim == 1 else res["p"][:, res["p"].shape[1] // 2]
    ax.plot(x * 1e3, p / 1e9, label="Hertz pressure")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("p [GPa]")
    ax2 = ax.twinx()
    inside = p > 0
    ax2.plot(x[inside] * 1e3, np.full(inside.sum(), res.scalars["hc_fit"] * 1e9), "C1--", label="fitted central film")
    ax2.set_ylabel("h [nm]")
    ax2.set_ylim(0, 2 * res.scalars["hc_fit"] * 1e9)
    ax.set_title(f"{sc.name}: pmax = {res.scalars['pmax'] / 1e9:.3g} GPa, hc(fit) = {res.scalars['hc_fit'] * 1e9:.3g} nm")
    fig.legend(loc="upper right", fontsize=8)
    fig.subplots_adjust(left=0.11, right=0.89, bottom=0.14, top=0.9)
    atomic_savefig(fig, path, dpi=110)
    return path


def film_stage(ctx: RunContext) -> StageOutput:
    """Pressure and film: multigrid solver or Hertz + fit, as the plan says."""
    scene, plan = ctx.scene, ctx.plan
    dec = plan.get("film")
    contact = "line" if scene.kind == "line" else "point"
    figures: list[Path] = []
    if dec.setting == "multigrid solver":
        # the fidelity's tolerance is the solver's accuracy target: it picks and refines grid and
        # box until its error estimate meets it (a [solver.ehl] grid in the scene is kept and judged)
        budget = ctx.solve_limits()
        if math.isfinite(scene.supply.hoil):
            # a finite inlet oil layer: the mass-conserving starved solver finds the meniscus
            fsol = ctx.solve(scene, physics="starved", accuracy=plan.tolerance, options=budget or None)
        else:
            # smooth point and elliptic contacts are symmetric in Y: the half domain gives the same
            # films (tested to 1e-5, measured 4e-8) in about half the time
            fsol = ctx.solve(scene, physics="steady", accuracy=plan.tolerance,
                               options={**budget, **({"half": True} if contact == "point" else {})} or None)
        sol = require_computed(fsol)  # the solver's result: what the payload and the figures read
        # a solve that ended without fields (a starved line supply below the meniscus search's
        # reach, a failed search) has nothing to build: a failed film like any other
        res = package_result(fsol) if sol.builder is not None else None
        scalars = res.scalars if res is not None else sol.scalars
        points = scalars.get("points")
        label = fsol.status.label
        usable = fsol.status in (Status.CONVERGED, Status.INACCURATE)
        if res is None or not usable or not (scalars.get("hm") or 0.0) > 0.0:
            # an unconverged or non-positive film must not feed the later stages, and it is not a
            # success: the stage says it failed (converged false: exit 3) and its film is an
            # estimate labelled as such (for a starved scene never the flooded fit)
            status = "film_not_positive" if usable else label
            why = (fsol.message or "no message").splitlines()[0]
            hm = scalars.get("hm")
            note = (f"multigrid solve{f' on {points} points' if points else ''} did not give a converged "
                    f"positive film ({label}: {why}{'' if hm is None else f'; hm = {hm:.3g} m'})")
            out = _fit_film_output(ctx, failure=note)
            out.notes.append(note + "; the film is an estimate, not a solved film")
            out.summary.update(converged=False, status=status, message=note, solver_fallback=True)
            return out
        notes = []
        if fsol.status is Status.INACCURATE:
            # still far closer than the fit (whose deviation made the planner call the solver):
            # used, with its estimated error stated
            notes.append(f"film solve did not reach the {plan.tolerance:g} target: estimated "
                         f"errors Hc {sol.Hc_error:.2g}, Hm {sol.Hm_error:.2g}")
        summary = {k: res.scalars.get(k) for k in ("Hc", "Hm", "hc", "hm", "p_spike", "load_error", "points",
                                                     "converged", "Hc_error", "Hm_error")}
        summary["status"], summary["message"] = label, fsol.message
        if plan.includes("tehl") and plan.get("tehl").setting == TEHL_UNAVAILABLE:
            # whatever the isothermal solve's own verdict, the contact's heat is expected to move
            # the film by more than the target, and nothing here solves it
            heat = (f"the contact's heat is expected to change the film by up to {plan.get('tehl').estimate:.2g} "
                    f"(> the tolerance {plan.tolerance:g}; plan: tehl), and the coupled thermal EHL "
                    f"solvers do not cover a starved point inlet: the isothermal film is short of its accuracy")
            notes.append(heat)
            # a solve already short of its target keeps its own reason beside this one
            message = heat if fsol.status is Status.CONVERGED else f"{fsol.message}; {heat}"
            summary.update(converged=False, status=Status.INACCURATE.label, message=message)
            label = Status.INACCURATE.label
        summary["Hc_fit"], summary["hc_fit"] = scene.central_film_fit()
        starved = "meniscus_x" in sol.scalars
        fit = f"fit: hc = {summary['hc_fit'] * 1e9:.4g} nm"
        if starved:
            summary.update({k: sol.scalars.get(k) for k in (
                "Hc_flooded", "Hm_flooded", "Hc_ratio", "meniscus_x", "mass_balance_error", "hoil")})
            # the flooded fit alone, beside a starved film, reads as the film the oil would give
            summary["Hc_fit_supplied"], summary["hc_fit_supplied"] = scene.supplied_film_fit()
            fit = (f"fit: hc = {summary['hc_fit'] * 1e9:.4g} nm flooded, "
                   f"{summary['hc_fit_supplied'] * 1e9:.4g} nm for the supply by Chevalier's (6.1)")
        along = "along X" if scene.kind == "line" else "per direction"
        text = (f"Film from the multigrid solver on {points} points {along}: hc = {res.scalars['hc'] * 1e9:.4g} nm, "
                f"hm = {res.scalars['hm'] * 1e9:.4g} nm ({fit}); "
                f"estimated errors Hc {sol.Hc_error:.2g}, Hm {sol.Hm_error:.2g} (target {plan.tolerance:g}); "
                f"load error {res.scalars['load_error']:.2g}, status: {label}.")
        why = sol.extra.get("not_refined_because") if fsol.status is Status.INACCURATE else None
        if why:
            text += f" Not refined further: {why}."
            summary["not_refined_because"] = why
        if starved:
            text += (f" Starved inlet (oil layer {scene.supply.hoil * 1e9:.4g} nm, mass-conserving "
                     f"Elrod-Adams solver): meniscus at X = {sol.scalars['meniscus_x']:.5g}, "
                     f"Hc/Hc_flooded = {sol.scalars['Hc_ratio']:.3g}.")
        if ctx.plots:
            from .film_plots import film_figures, starved_figure

            figures += film_figures(contact, sol, res, ctx.outdir, f"{scene.name}_film", scene.name)
            if starved:
                figures.append(starved_figure(contact, sol, ctx.outdir, f"{scene.name}_film", scene.name))
    else:
        return _fit_film_output(ctx)
    # the later stages compute on this typed film; the Result goes to the HDF5 file
    film = SolvedFilm.from_result(res, fsol.grid) if res.kind in FILM_KINDS else None
    return StageOutput("film", res, summary, figures, text, notes=notes, film=film)


def _fit_film_output(ctx: RunContext, failure: str | None = None) -> StageOutput:
    """Hertz pressure with the fitted film: the flooded fit, or for a finite ``[supply] hoil``
    the fit reduced by Chevalier's (6.1)-(6.4) (:meth:`Scene.supplied_film_fit`), never the
    flooded fit. With ``failure`` (why the film solve failed) the film is reported as an
    estimate, not a solved film."""
    scene = ctx.scene
    res = hertz_result(scene)
    Hc, hc = scene.central_film_fit()
    fit = "Moes" if scene.kind == "line" else "Nijenbanning"
    summary = {"Hc_fit": Hc, "hc_fit": hc, "pmax": scene.hertz.pmax}
    starved = math.isfinite(scene.supply.hoil)
    under = f"under Hertz pressure pmax = {scene.hertz.pmax / 1e9:.4g} GPa."
    if starved:
        hcs = scene.supplied_film_fit()[1]
        summary.update(hc_estimate=hcs, starvation_factor=hcs / hc, film_source="starved estimate")
        res.set_scalar("hc_estimate", hcs, "m")
        res.set_scalar("starvation_factor", hcs / hc, "-")
        text = (f"Starved inlet (oil layer {scene.supply.hoil * 1e9:.4g} nm): Chevalier's reduction (6.1) gives "
                f"hc = {hcs / hc:.3g} x the {fit} fit of the flooded film = {hcs * 1e9:.4g} nm (the flooded fit, "
                f"{hc * 1e9:.4g} nm, does not apply), {under}")
    else:
        text = f"Film from the {fit} fit: hc = {hc * 1e9:.4g} nm {under}"
    # (the Hertz figure draws the flooded fit as the film: not for a starved scene)
    figures = [plot_hertz(res, ctx.outdir / f"{scene.name}_film.png")] if ctx.plots and not starved else []
    if failure is not None:
        res.meta["film_source"] = "estimate: the film solve failed"
        summary.setdefault("film_source", "fit estimate")
        text = f"{failure}. NO SOLVED FILM: the film is an ESTIMATE. {text}"
        return StageOutput("film", res, summary, figures, text,
                           setting=f"{'starved estimate' if starved else 'fit'} (solver fallback)")
    return StageOutput("film", res, summary, figures, text)


# -- driver --------------------------------------------------------------------------------------
def registered_stages() -> list[tuple[str, Any]]:
    stages = []
    for ep in entry_points(group="ehl.stages"):
        fn = ep.load()
        stages.append((getattr(fn, "order", 100), ep.name, fn))
    return [(name, fn) for _, name, fn in sorted(stages, key=lambda t: (t[0], t[1]))]


def write_report(ctx: RunContext, path: Path, missing: list[str] | None = None) -> Path:
    """The Markdown report of the run; ``missing`` names stages that did not run (interrupted)."""
    sc, plan = ctx.scene, ctx.plan
    lines = [f"# {sc.name}", "", sc.description, ""]
    if missing:
        lines += [f"**Incomplete run**: interrupted before the stage(s) {', '.join(missing)}; the results "
                  "below are those that finished (the HDF5 file says complete = false).", ""]
    if sc.source:
        lines += [f"Source: {sc.source}", ""]
    s = sc.summary()
    lines += ["## Contact", "",
              f"{sc.kind} contact, load {sc.load:.4g} N, pmax {s['pmax'] / 1e9:.4g} GPa, us {sc.us:.4g} m/s, "
              f"slip {sc.slip:g}, oil {sc.lubricant.name} at {sc.T_oil:g} degC (eta0 {s['eta0']:.4g} Pa s); "
              f"Moes M = {s['M']:.4g}, L = {s['L']:.4g}.", "",
              f"## What was modelled and why (fidelity {plan.fidelity}, tolerance {plan.tolerance:g})", "",
              "| model | included | setting | estimate | threshold | why |", "|---|---|---|---|---|---|"]
    for d in plan.decisions:
        lines.append(f"| {d.model} | {'yes' if d.include else 'no'} | {d.setting} | {d.estimate:.3g} | {d.threshold:.3g} | {d.reason} |")
    for name, out in ctx.outputs.items():
        lines += ["", f"## {name} ({out.wall_s:.2f} s)", "", out.text, ""]
        lines += [f"Note: {n}" for n in out.notes] + ([""] if out.notes else [])
        for fig in out.figures:
            lines.append(f"![{fig.stem}]({Path(fig).name})")
    return write_text_atomic(path, "\n".join(lines) + "\n")


def _publish(staging: Path, out: Path, stem: str, scene_name: str, names: list[str] | None = None) -> list[str]:
    """Move the complete files ``names`` of ``staging`` (default: every plain file in it) into
    ``out``, record the new set in ``.ehl-run-<stem>.json``, then delete the files of the
    scene's previous run that it does not replace, and remove ``staging``; return the names
    moved. The index is written before the deletions and names what is being removed, so a
    crash between the two leaves no file that no index knows about; it never lists a file that
    does not exist."""
    manifest = out / f".ehl-run-{stem}.json"
    try:
        data = json.loads(manifest.read_text())
        old = set(data.get("files", [])) | set(data.get("removing", []))
    except (OSError, ValueError, AttributeError, TypeError):
        old = set()
    legacy = out / "report.md"  # the single report of earlier versions: remove it if it was this scene's
    try:
        if legacy.is_file() and legacy.read_text().splitlines()[:1] == [f"# {scene_name}"]:
            old.add(legacy.name)
    except (OSError, UnicodeDecodeError):
        pass
    if names is None:
        names = [p.name for p in staging.iterdir() if p.is_file() and not p.name.startswith(".")]
    new = []
    for name in dict.fromkeys(names):
        if Path(name).name == name and not name.startswith(".") and (staging / name).is_file():
            os.replace(staging / name, out / name)
            new.append(name)
            fault_point("publish")
    new.sort()
    stale = sorted(n for n in old - set(new) if Path(n).name == n)
    write_text_atomic(manifest, json.dumps({"scene": scene_name, "files": new, "removing": stale}))
    for name in stale:
        target = out / name
        if target.is_file():  # only plain names inside the folder
            try:
                target.unlink()
            except OSError:
                pass
    shutil.rmtree(staging, ignore_errors=True)
    return new


def run_main_job(scene: Scene, options: MainJobOptions | None = None) -> dict[str, Any]:
    """Plan ``scene``, run the film stage and every registered stage, write the HDF5 results,
    ``<stem>_report.md`` and the figures into ``options.out_dir`` as one set (see the module
    docstring); return the payload ``ehl run --json`` prints.

    Raises
    ------
    InputError : the output folder is not writable, or another process writes into it
        (:class:`~ehl_multigrid.model.paths.OutputLocked`, naming its PID).
    """
    options = options if options is not None else MainJobOptions()
    out = writable_dir(options.out_dir)  # before any work: a read-only folder costs nothing
    with output_lock(out, "ehl run") as removed:
        report_leftovers("ehl run", removed)
        return _run_locked(scene, options, out)


def _run_locked(scene: Scene, options: MainJobOptions, out: Path) -> dict[str, Any]:
    """:func:`run_main_job` once the output folder ``out`` is locked."""
    stem = safe_stem(scene.name)
    plan = make_plan(scene, fidelity=options.fidelity, tolerance=options.tolerance)
    if stem != scene.name:
        # stages name their figures after the scene: give them a name that is a safe file name
        plan.notes.append(f"scene name {scene.name!r} is not a safe file name; outputs use {stem!r}")
        scene = dataclasses.replace(scene, name=stem)
    stages: list[tuple[str, Any]] = [("film", film_stage)] + registered_stages()
    staging = staging_dir(out, stem)
    ctx = RunContext(scene, plan, staging, plots=options.plots, progress=not options.quiet,
                     time_budget=options.time_budget, max_points=options.max_points)
    h5_name, report_name = f"{stem}.h5", f"{stem}_report.md"
    h5, report = out / h5_name, out / report_name
    planned = [name for name, _ in stages]
    ran: list[str] = []

    def save(complete: bool) -> None:
        save_results(staging / h5_name, {k: o.result for k, o in ctx.outputs.items() if o.result is not None},
                     meta={"plan": plan.to_dict(), "scene": scene.name, "stages_planned": planned,
                           "stages_run": list(ran)}, complete=complete, planned=planned,
                     compress=complete)  # a partial file is replaced by the next stage's

    prog = Progress(f"ehl run {scene.name}", total=len(stages), unit="stages")
    helpers = warmup.start(scene.kind)
    try:
        for i, (name, stage) in enumerate(stages, 1):
            prog.status(f"stage {i}/{len(stages)} {name}", force=True)
            fault_point(f"run.stage.{name}")
            t0 = time.perf_counter()
            output = stage(ctx)
            ran.append(name)
            if output is not None:
                output.wall_s = time.perf_counter() - t0
                if output.result is not None:
                    output.result.meta["plan"] = plan.to_dict()
                    if output.notes:
                        output.result.meta["notes"] = list(output.notes)
                    if output.setting:
                        output.result.meta["setting"] = output.setting
                ctx.outputs[name] = output
            save(complete=len(ran) == len(planned))
            prog.advance(text=f"{name} took {time.perf_counter() - t0:.1f} s")
            if ctx.keeper is not None:  # a stop kept this stage's film: the later stages do not run
                ctx.keeper.raise_stop(str(h5), f" as the {name} stage's film; the stages after it did not run")
    except BaseException as exc:
        stop = signal_cause(exc)
        if stop is not None and not hasattr(stop, "kept"):
            stop.kept = (f"the finished stages ({', '.join(ctx.outputs)}) were written to {h5}, marked incomplete"  # type: ignore[attr-defined]
                         if ctx.outputs else f"no stage had finished, so nothing was written (files of an "
                         f"earlier run of {scene.name} in {out} are as they were)")
            if ctx.outputs:
                stop.written = str(h5)  # type: ignore[attr-defined]
        raise
    finally:
        warmup.stop(helpers)
        prog.close()
        # only the finished stages' files are moved (a figure of the stage a stop interrupted
        # stays in the staging folder, which is removed); a stop request waits for the move
        with deferred_signals():
            fault_point("run.publish")
            if ctx.outputs:
                if len(ran) != len(planned):
                    save(complete=False)
                write_report(ctx, staging / report_name, missing=[n for n in planned if n not in ran])
                finished = [h5_name, report_name] + [Path(f).name for o in ctx.outputs.values() for f in o.figures]
                _publish(staging, out, stem, scene.name, finished)
            shutil.rmtree(staging, ignore_errors=True)
        for o in ctx.outputs.values():
            o.figures = [out / Path(f).name for f in o.figures]
    payload: dict[str, Any] = {"scene": scene.name, "hdf5": str(h5), "report": str(report),
                               "plan": {d.model: ctx.setting(d.model) if d.include else "off"
                                        for d in plan.decisions}}
    for name, o in ctx.outputs.items():
        payload[name] = o.summary
    if not options.quiet:
        print_plan(plan)
        for name, o in ctx.outputs.items():
            print(f"{name}: {o.text}")
        print_table({"hdf5": str(h5), "report": str(report)})
    return payload
