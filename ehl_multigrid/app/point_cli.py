"""``ehl solve`` for point and elliptic contacts (``--contact point|elliptic`` or a point scene).

The output folder is locked while the command runs (a second command into it is refused); the
files are written into a staging folder and moved into place together, so a stop during
plotting keeps the result (not the figures of the interrupted plotting call) and nothing
partial reaches the folder.
Progress (each solve of the accuracy sequence, and the solver's cycles at most every few
seconds) goes to stderr. The film is solved by the front door :func:`ehl_multigrid.solve`."""

from __future__ import annotations

import argparse
import math
from dataclasses import fields
from pathlib import Path

from .. import front
from ..model.atomic import fault_point
from ..model.errors import InputError, require_solution
from ..model.output_folder import StagedOutputs, output_lock
from ..model.paths import safe_stem
from ..multigrid.options import PointOptions
from ..point.newton import NewtonOptions
from ..point.postprocess import summary_payload
from ..point.problem import problem_from_moes, problem_from_scene
from ..solution import MoesProblem
from .console import Progress, report_leftovers
from .solved import package_result, require_computed

DEFAULT_POINTS = 257


def options_from_args(args: argparse.Namespace, scene=None) -> dict:
    """FAS option keywords from the command line; the scene's ``[solver.ehl]`` table applies
    below them in :func:`~ehl_multigrid.point.solve.solve_point`; without ``points`` the
    solver chooses the grid from the accuracy target (``--accuracy``)."""
    kw: dict = {}
    cli = {
        "points": args.points, "levels": args.levels, "cycle": args.cycle, "cycles": args.cycles,
        "max_cycles": args.max_cycles, "deformation": args.deformation, "xmin": args.xmin,
        "xmax": args.xmax, "ymax": args.ymax, "threads": args.threads, "tol": args.tol,
        "tol_load": args.tol_load,
    }
    kw.update({k: v for k, v in cli.items() if v is not None})
    if args.half and getattr(args, "full_domain", False):
        raise InputError("--half and --full-domain exclude each other")
    if args.half:
        kw["half"] = True
    if getattr(args, "full_domain", False):
        kw["half"] = False
    return kw


def problem_from_args(args: argparse.Namespace, scene):
    if scene is None:
        if args.contact == "elliptic":
            if args.ellipticity is None:
                raise InputError("--contact elliptic needs --ellipticity theta = Rx/Ry (e.g. 0.25)")
            theta = args.ellipticity
        else:
            theta = 1.0 if args.ellipticity is None else args.ellipticity
            if not math.isclose(theta, 1.0):
                raise InputError(f"--ellipticity {theta:g} with --contact point: use --contact elliptic")
        if args.M is None or not args.M > 0:
            raise InputError(f"M = {args.M} must be > 0 (Moes load parameter)")
        if args.L is None or not args.L >= 0:
            raise InputError(f"L = {args.L} must be >= 0 (Moes lubricant parameter)")
        return problem_from_moes(args.M, args.L, theta, args.viscosity or "roelands",
                                 args.density or "dowson-higginson", args.alpha, args.eta0, args.p0)
    for flag in ("alpha", "eta0", "p0", "M", "L", "ellipticity"):
        if getattr(args, flag, None) is not None:
            raise InputError(f"--{flag} applies to Moes-only mode; set it in the scene file instead")
    table = scene.solver.get("ehl") or {}
    return problem_from_scene(scene, args.viscosity or table.get("viscosity", "roelands"),
                              args.density or table.get("density", "dowson-higginson"))


def newton_options_from_args(args: argparse.Namespace, scene=None) -> NewtonOptions:
    """Options of the Newton/pyamg path: defaults, the scene's ``[solver.ehl]`` keys that
    the path shares with FAS, then CLI flags; FAS-only flags are refused."""
    names = {f.name for f in fields(NewtonOptions)}
    kw: dict = {"points": DEFAULT_POINTS}
    if scene is not None:
        kw.update({k: v for k, v in (scene.solver.get("ehl") or {}).items() if k in names})
    for flag in ("levels", "cycle", "cycles", "max_cycles", "threads"):
        if getattr(args, flag, None) is not None:
            raise InputError(f"--{flag.replace('_', '-')} applies to --solver fas only")
    if args.half:
        raise InputError("--half applies to --solver fas only (the Newton path solves the full domain)")
    cli = {"points": args.points, "deformation": args.deformation, "xmin": args.xmin, "xmax": args.xmax,
           "ymax": args.ymax, "tol": args.tol, "tol_load": args.tol_load}
    kw.update({k: v for k, v in cli.items() if v is not None})
    return NewtonOptions(**kw)


def run_solve(args: argparse.Namespace, scene) -> dict:
    """Solve, write ``<out>/<name>.h5`` and PNGs (unless ``--no-plots``), return the payload;
    the output folder ``args.out`` is locked meanwhile
    (:func:`~ehl_multigrid.model.output_folder.output_lock`)."""
    out = Path(getattr(args, "out", "ehl_out"))
    out.mkdir(parents=True, exist_ok=True)
    with output_lock(out, "ehl solve") as removed:
        report_leftovers("ehl solve", removed)
        with Progress("ehl solve") as prog:
            return _run_solve(args, scene, out, prog)


def _write_outputs(args: argparse.Namespace, res, out: Path, stem: str, payload: dict, key: str,
                   extra_plot=None) -> None:
    """Write the result ``res`` as ``<stem>.h5`` (its path under ``payload[key]``), the CSV
    profiles (``--csv``) and the figures (``extra_plot(folder, stem)`` adds one) through a
    staging folder: the finished files are moved into ``out`` together, also when a stop
    interrupts the plotting."""
    with StagedOutputs(out, stem) as staged:
        payload[key] = str(staged.done(res.save(staged.path(f"{stem}.h5"))))
        if getattr(args, "csv", False):
            from .profiles import write_profiles_csv

            payload["csv"] = [str(staged.done(p)) for p in write_profiles_csv(res, staged.dir, stem)]
        if not getattr(args, "no_plots", False):
            from .point_plots import plot_result

            fault_point("solve.plots")
            payload["plots"] = [str(staged.done(p)) for p in plot_result(res, staged.dir, stem)]
            if extra_plot is not None:
                payload["plots"].append(str(staged.done(extra_plot(staged.dir, stem))))


def _run_solve(args: argparse.Namespace, scene, out: Path, prog: Progress) -> dict:
    pb = problem_from_args(args, scene)
    solver = getattr(args, "solver", None) or "fas"
    rigid = bool(getattr(args, "rigid", False))
    if solver == "newton":
        if rigid:
            raise InputError("--rigid applies to --solver fas only")
        opt = newton_options_from_args(args, scene)
    else:
        fas_kw = options_from_args(args, scene)
        fas_kw["accuracy"] = getattr(args, "accuracy", None)
        if getattr(args, "max_points", None) is not None:
            fas_kw["max_points"] = args.max_points
        if getattr(args, "time_budget", None) is not None:
            fas_kw["time_budget"] = args.time_budget
        opt = PointOptions.build(**{k: v for k, v in fas_kw.items()
                                    if k not in ("accuracy", "max_points", "time_budget")})
    quiet = bool(getattr(args, "json", False))
    if scene is not None and math.isfinite(scene.supply.hoil):
        # a finite [supply] hoil: the mass-conserving (Elrod-Adams) solver finds the meniscus
        if solver == "newton":
            raise InputError(f"the scene supplies a finite oil layer (supply.hoil = {scene.supply.hoil:g} m): "
                             f"the starved point solver is FAS only, so --solver newton does not apply")
        return run_starved(args, scene, pb, fas_kw, rigid, quiet, out)
    if not quiet:
        if scene is None:
            print(f"# Moes-only point contact: M = {pb.M:g}, L = {pb.L:g}, theta = {pb.theta:g}; "
                  f"oil alpha = {pb.alpha:g} 1/Pa, eta0 = {pb.eta0:g} Pa s, p0 = {pb.p_r:g} Pa "
                  f"(pmax = alpha_bar/alpha = {pb.pmax:.4g} Pa"
                  f"{'; L = 0: isoviscous and incompressible' if pb.L == 0 else ''})")
        else:
            print(f"# scene {scene.name}: M = {pb.M:.5g}, L = {pb.L:.5g}, theta = {pb.theta:.4g}, "
                  f"pmax = {pb.pmax:.4g} Pa, a = {pb.a:.4g} m")
        how = (f"{opt.cycle or 'F (W where every grid alternates)'} cycles" if solver == "fas"
               else "Newton/pyamg")
        print(f"# {pb.viscosity} viscosity, {pb.density} density; {opt.points} points along X, "
              f"{how}, deformation {opt.deformation}{', half domain' if opt.half else ''}"
              f"{', rigid surfaces' if rigid else ''}")
    if scene is None:
        # a circular contact given as elliptic with theta = 1 is solved as the point contact it is
        problem = MoesProblem("point" if pb.theta == 1.0 else "elliptic", pb.M, pb.L, theta=pb.theta,
                              viscosity=pb.viscosity, density=pb.density, alpha=pb.alpha, eta0=pb.eta0,
                              p0=pb.p_r)
        model = {}
    else:
        problem, model = scene, {"viscosity": pb.viscosity, "density": pb.density}
    if solver == "newton":
        # the cross-check path has no accuracy control: judged on its iteration alone
        newton = {k: v for k, v in vars(opt).items() if k != "raise_on_failure"}
        sol = front.solve(problem, physics="steady", accuracy=None, options={"solver": "newton", **newton, **model})
    else:
        fas = {k: v for k, v in fas_kw.items() if k != "accuracy"}
        if rigid:
            fas["elastic"] = False
        sol = front.solve(problem, physics="steady", accuracy=fas_kw["accuracy"], options={**fas, **model},
                          callback=prog.solver_callback, progress=prog.say)
    raw = require_computed(sol)
    require_solution(raw, "point solver")
    res = package_result(sol)
    name = scene.name if scene is not None else f"point_M{pb.M:g}_L{pb.L:g}_th{pb.theta:g}"
    stem = safe_stem(name)  # a scene name is a label: never a path out of --out
    payload = summary_payload(res)
    payload["solver"] = solver
    prog.status("writing the result", force=True)
    _write_outputs(args, res, out, stem, payload, "file")
    if not quiet:
        from .console import print_table

        print_table({k: v for k, v in payload.items() if k not in ("actions", "plots")})
        for a in payload["actions"]:
            print(f"  action: {a}")
    return payload


def run_starved(args: argparse.Namespace, scene, pb, fas_kw: dict, rigid: bool, quiet: bool,
                out: Path | None = None) -> dict:
    """``ehl solve`` on a point scene with a finite ``[supply] hoil``: the starved
    (mass-conserving) point solver, its error estimate, the flooded film of the same
    discretisation; writes ``<out>/<name>.h5`` (with ``theta``) and PNGs."""
    from ..starved.point import starved_point_payload

    if fas_kw.get("time_budget") is not None:
        raise InputError("--time-budget applies to flooded contacts: the starved point solver "
                         "refines its grid only (use --max-points to bound it)")
    kw = {k: v for k, v in fas_kw.items() if k not in ("accuracy", "max_points")}
    if rigid:
        kw["elastic"] = False
    if getattr(args, "max_points", None) is not None:
        kw["max_points"] = args.max_points
    if not quiet:
        print(f"# scene {scene.name}: M = {pb.M:.5g}, L = {pb.L:.5g}, theta = {pb.theta:.4g}, "
              f"pmax = {pb.pmax:.4g} Pa, a = {pb.a:.4g} m; starved inlet: oil layer "
              f"{scene.supply.hoil:.4g} m (mass-conserving Elrod-Adams solver)")
    fsol = front.solve(scene, physics="starved", accuracy=fas_kw.get("accuracy"),
                       options={**kw, "viscosity": pb.viscosity, "density": pb.density})
    sol = require_computed(fsol)
    res = package_result(fsol)
    out = Path(getattr(args, "out", "ehl_out")) if out is None else out
    stem = safe_stem(scene.name)  # a scene name is a label: never a path out of --out
    payload = starved_point_payload(sol, res)
    payload["solver"] = "starved-fas"

    def starved_plot(folder: Path, stem: str) -> Path:
        from ..starved.plots import plot_starved_point

        return plot_starved_point(sol, folder / stem, scene.name)

    _write_outputs(args, res, out, stem, payload, "file", starved_plot)
    if not quiet:
        from .console import print_table

        print_table({k: v for k, v in payload.items() if k not in ("actions", "plots", "error_budget")})
        for a in payload["actions"]:
            print(f"  action: {a}")
    return payload
