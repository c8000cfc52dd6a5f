"""``ehl solve`` of a line, point or elliptic contact, flooded or starved:
``run_contact_solve(args, scene, kind) -> dict`` (called by :mod:`ehl_multigrid.app.solve`).

Every geometry takes the same course. The output folder is locked while the command runs (a
second command into it is refused). The film is solved by the front door
:func:`ehl_multigrid.solve`: the mass-conserving (Elrod-Adams) solver for a scene with a finite
``[supply] hoil``, else the steady one. ``<out>/<name>.h5``, the CSV profiles (``--csv``) and
the figures are written into a staging folder and moved into place together, so a stop during
plotting keeps the result (not the figures of the interrupted plotting call) and nothing
partial reaches the folder. Progress (each solve of the accuracy sequence, and the solver's
cycles at most every few seconds) goes to stderr.

What the geometry decides -- the options its solvers read, the problem, the lines printed and
the figures -- is :func:`_solve_line` or :func:`_solve_point`. The payload names the result
``hdf5`` and the figures ``plots`` for every contact, as the other commands do.
"""

from __future__ import annotations

import argparse
import math
import warnings
from dataclasses import fields
from pathlib import Path
from typing import Any

from .. import front
from ..model.atomic import fault_point
from ..model.constants import MOES_ONLY_DEFAULTS
from ..model.errors import ConvergenceError, InputError, ModelRangeWarning, signal_cause
from ..model.output_folder import StagedOutputs, output_lock
from ..model.paths import safe_stem
from ..solution import MoesProblem
from .console import Progress, print_table, report_leftovers
from .solved import package_result, require_film

#: grid of the Newton/pyamg point path when neither the scene nor ``--points`` gives one
DEFAULT_POINTS = 257
#: multigrid options each solver reads, under their argparse names (in the order they are passed)
LINE_OPTIONS = ("points", "levels", "cycle", "cycles", "max_cycles", "deformation", "tol", "tol_load",
                "threads", "face")
POINT_OPTIONS = ("points", "levels", "cycle", "cycles", "max_cycles", "deformation", "xmin", "xmax", "ymax",
                 "threads", "tol", "tol_load")


#: payload keys the printed summary leaves out (the figure list; the actions follow it line by line)
HIDDEN = ("actions", "plots")


def run_contact_solve(args: argparse.Namespace, scene: Any, kind: str) -> dict[str, Any]:
    """Solve the ``kind`` contact (``"line"``, ``"point"``, ``"elliptic"``) of ``scene`` (or
    Moes ``--M``/``--L`` when ``scene`` is None), save and plot it; return the payload.

    Options come from the solver's defaults, then the scene's ``[solver.ehl]`` table, then the
    command-line flags. The output folder ``args.out`` is locked meanwhile
    (:func:`~ehl_multigrid.model.output_folder.output_lock`).
    """
    out = Path(getattr(args, "out", "ehl_out"))
    out.mkdir(parents=True, exist_ok=True)
    with output_lock(out, "ehl solve") as removed:
        report_leftovers("ehl solve", removed)
        with Progress("ehl solve") as prog:
            keeper = front.StopKeeper()
            args.writing = False
            try:
                payload = (_solve_line if kind == "line" else _solve_point)(args, scene, out, prog, keeper)
            except BaseException as exc:
                stop = signal_cause(exc)
                if stop is not None and not args.writing and not hasattr(stop, "kept"):
                    stop.kept = ("no solve had finished, so nothing was written (files of an earlier run in "  # type: ignore[attr-defined]
                                 f"{out} are as they were)")
                raise
            keeper.raise_stop(payload.get("hdf5", ""))
    if scene is not None:
        note = heat_note(scene, getattr(args, "accuracy", None))
        if note:
            payload["heat_note"] = note
            warnings.warn(note, ModelRangeWarning, stacklevel=2)
    return payload


def heat_note(scene: Any, accuracy: float | None) -> str | None:
    """Why the isothermal film of ``scene`` is short of ``accuracy`` because of the contact's
    heat (the plan's estimate, :func:`~ehl_multigrid.app.plan.thermal_film_change`, above the
    standard fidelity's tolerance too), or None. Its estimated error does not include that
    change."""
    from ..model.fidelity import FIDELITIES
    from .plan import thermal_film_change

    # below the main job's standard tolerance the heat's change is common (most built-in scenes
    # are at 0.4-1.8 %) and the plan's estimate of it too rough to single a contact out
    floor = FIDELITIES["standard"].tolerance
    change = thermal_film_change(scene)
    if accuracy is None or change.expected <= max(accuracy, floor):
        return None
    return (f"the plan estimates that the contact's heat changes the film by up to {change.expected:.2g}, "
            f"more than the accuracy {accuracy:g} and {floor:g} (the larger of a third of Gupta et al.'s "
            f"1992 inlet-heating reduction {change.gupta:.2g}, the share the coupled solver measured on "
            f"the built-in scenes, and the contact-heat estimate {change.heating:.2g}; a rough upper "
            f"estimate): this isothermal film's estimated error leaves that out; `ehl solve SCENE "
            f"--thermal` solves it")


# -- shared ----------------------------------------------------------------------------------------
def given(args: argparse.Namespace, names: tuple[str, ...]) -> dict[str, Any]:
    """The options of ``names`` (argparse names, which are the solver's keys) that are set."""
    return {k: v for k in names if (v := getattr(args, k, None)) is not None}


def solver_options(args: argparse.Namespace, names: tuple[str, ...], **fixed: Any) -> dict[str, Any]:
    """The multigrid options given on the command line: those of ``names``, then ``fixed``,
    then ``--max-points``, ``--time-budget`` and ``--rigid`` (``elastic`` false)."""
    opts = {**given(args, names), **fixed, **given(args, ("max_points", "time_budget"))}
    if getattr(args, "rigid", False):
        opts["elastic"] = False
    return opts


def write_and_print(args: argparse.Namespace, out: Path, kind: str, raw: Any, res: Any, name: str,
                    payload: dict[str, Any], starved: bool, hidden: tuple[str, ...] = HIDDEN) -> dict[str, Any]:
    """Write the result ``res`` as ``<stem>.h5``, the CSV profiles (``--csv``) and the figures
    (of the solver's result ``raw``; with the film content of a ``starved`` one) through a
    staging folder, name them in ``payload`` and print its summary (unless ``--json``)."""
    if "error_budget" in payload and "error_budget" in res.meta:
        # the JSON states the budget as the file does: by the contract's part names
        payload["error_budget"] = res.meta["error_budget"]
    args.writing = True  # a stop from here on may keep the result (StagedOutputs)
    stem = safe_stem(name)  # a scene name is a label: never a path out of --out
    # the finished files are moved into --out together when the block ends (a stop while
    # plotting keeps the result and the CSV, not the figures of the interrupted call)
    with StagedOutputs(out, stem) as staged:
        payload["hdf5"] = str(staged.done(res.save(staged.path(f"{stem}.h5"))))
        if getattr(args, "csv", False):
            from .profiles import write_profiles_csv

            payload["csv"] = [str(staged.done(p)) for p in write_profiles_csv(res, staged.dir, stem)]
        if not getattr(args, "no_plots", False):
            from .film_plots import film_figures, starved_figure

            fault_point("solve.plots")
            figures = film_figures(kind, raw, res, staged.dir, stem, name)
            payload["plots"] = [str(staged.done(p)) for p in figures]
            if starved:
                payload["plots"].append(str(staged.done(starved_figure(kind, raw, staged.dir, stem, name))))
    if not args.json:
        print_table({k: v for k, v in payload.items() if k not in hidden})
        for a in payload["actions"]:
            print(f"  action: {a}")
    return payload


# -- line ------------------------------------------------------------------------------------------
def _solve_line(args: argparse.Namespace, scene: Any, out: Path, prog: Progress,
                keeper: front.StopKeeper) -> dict[str, Any]:
    for opt in ("ymax", "ellipticity"):
        if getattr(args, opt, None) is not None:
            raise InputError(f"--{opt} applies to point contacts, not to a line contact")
    if getattr(args, "half", False) or getattr(args, "full_domain", False):
        raise InputError("--half and --full-domain apply to point contacts, not to a line contact")
    if getattr(args, "solver", None) == "newton":
        raise InputError("--solver newton is the point-contact cross-check path; line contacts use "
                         "the FAS solver (whose coarsest grid is already solved by Newton)")
    opts = solver_options(args, LINE_OPTIONS)
    accuracy = getattr(args, "accuracy", None)
    model = given(args, ("viscosity", "density", "xmin", "xmax"))
    # an unconverged or inaccurate result comes back (the front door never raises for it): it
    # is written and says so
    if scene is None:
        oil = {k: getattr(args, k, None) for k in ("alpha", "eta0", "p0")}
        laws = {k: model.pop(k) for k in ("viscosity", "density") if k in model}
        problem = MoesProblem("line", args.M, args.L, **laws, **oil)
        sol = keeper.solve(problem, physics="steady", accuracy=accuracy, options={**opts, **model},
                           callback=prog.solver_callback, progress=prog.say)
        raw = require_film(sol, "line solver")
        used = {k: (v if v is not None else MOES_ONLY_DEFAULTS[k]) for k, v in oil.items()}
        name = f"line_M{args.M:g}_L{args.L:g}"
        if not args.json:
            pb = raw.problem
            print(f"Moes-only line contact M = {args.M:g}, L = {args.L:g}; oil data used: "
                  f"p0 = {used['p0']:.4g} Pa, alpha = {used['alpha']:.4g} 1/Pa, "
                  f"eta0 = {used['eta0']:.4g} Pa s ({pb.viscosity}, {pb.density}); pmax = {pb.pmax:.4g} Pa"
                  f"{' (L = 0: isoviscous and incompressible)' if args.L == 0 else ''}")
    else:
        for k in ("alpha", "eta0", "p0"):
            if getattr(args, k, None) is not None:
                raise InputError(f"--{k} applies to Moes-only mode (--M/--L); with a scene the "
                                 f"oil comes from the scene's [lubricant] table")
        if math.isfinite(scene.supply.hoil):
            sol = keeper.solve(scene, physics="starved", accuracy=accuracy, options={**opts, **model})
            raw = require_film(sol, "starved line solver")
            if raw.X is None:  # nothing to write: e.g. a supply below the solver's reach
                raise ConvergenceError(f"starved line solver: {sol.message}")
        else:
            sol = keeper.solve(scene, physics="steady", accuracy=accuracy, options={**opts, **model},
                               callback=prog.solver_callback, progress=prog.say)
            raw = require_film(sol, "line solver")
        name = scene.name
    res = package_result(sol)
    starved = "meniscus_x" in raw.scalars
    if starved:
        from ..starved.line import starved_payload

        payload = starved_payload(raw)  # adds Hc_flooded, meniscus_x, mass_balance_error ...
    else:
        payload = raw.payload()
    prog.status("writing the result", force=True)
    return write_and_print(args, out, "line", raw, res, name, payload, starved)


# -- point and elliptic ----------------------------------------------------------------------------
def point_problem(args: argparse.Namespace, scene: Any) -> Any:
    """The :class:`~ehl_multigrid.point.problem.PointProblem` of ``scene`` or of Moes
    ``--M``/``--L`` (``--contact point`` or ``elliptic`` with ``--ellipticity``)."""
    from ..point.problem import problem_from_moes, problem_from_scene

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


def newton_options(args: argparse.Namespace, scene: Any = None) -> Any:
    """:class:`~ehl_multigrid.point.newton.NewtonOptions` of the Newton/pyamg path: defaults,
    the scene's ``[solver.ehl]`` keys that the path shares with FAS, then CLI flags; FAS-only
    flags are refused."""
    from ..point.newton import NewtonOptions

    names = {f.name for f in fields(NewtonOptions)}
    kw: dict = {"points": DEFAULT_POINTS}
    if scene is not None:
        kw.update({k: v for k, v in (scene.solver.get("ehl") or {}).items() if k in names})
    for flag in ("levels", "cycle", "cycles", "max_cycles", "threads"):
        if getattr(args, flag, None) is not None:
            raise InputError(f"--{flag.replace('_', '-')} applies to --solver fas only")
    if args.half:
        raise InputError("--half applies to --solver fas only (the Newton path solves the full domain)")
    kw.update(given(args, ("points", "deformation", "xmin", "xmax", "ymax", "tol", "tol_load")))
    return NewtonOptions(**kw)


def _fas_half(args: argparse.Namespace) -> dict[str, bool]:
    """``half`` of the FAS point solver from ``--half`` / ``--full-domain`` (its own default
    when neither is given)."""
    full = getattr(args, "full_domain", False)
    if args.half and full:
        raise InputError("--half and --full-domain exclude each other")
    return {"half": True} if args.half else {"half": False} if full else {}


def _solve_point(args: argparse.Namespace, scene: Any, out: Path, prog: Progress,
                 keeper: front.StopKeeper) -> dict[str, Any]:
    from ..multigrid.options import PointOptions

    pb = point_problem(args, scene)
    solver = getattr(args, "solver", None) or "fas"
    rigid = bool(getattr(args, "rigid", False))
    accuracy = getattr(args, "accuracy", None)
    if solver == "newton":
        if rigid:
            raise InputError("--rigid applies to --solver fas only")
        opt = newton_options(args, scene)
    else:
        fas = solver_options(args, POINT_OPTIONS, **_fas_half(args))
        opt = PointOptions.build(**{k: v for k, v in fas.items() if k not in ("max_points", "time_budget", "elastic")})
    if scene is not None and math.isfinite(scene.supply.hoil):
        # a finite [supply] hoil: the mass-conserving (Elrod-Adams) solver finds the meniscus
        if solver == "newton":
            raise InputError(f"the scene supplies a finite oil layer (supply.hoil = {scene.supply.hoil:g} m): "
                             f"the starved point solver is FAS only, so --solver newton does not apply")
        return _solve_starved_point(args, scene, pb, fas, accuracy, out, keeper)
    if not args.json:
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
        sol = keeper.solve(problem, physics="steady", accuracy=None, options={"solver": "newton", **newton, **model})
    else:
        sol = keeper.solve(problem, physics="steady", accuracy=accuracy, options={**fas, **model},
                           callback=prog.solver_callback, progress=prog.say)
    raw = require_film(sol, "point solver")
    res = package_result(sol)
    from ..point.postprocess import summary_payload

    payload = summary_payload(res)
    payload["solver"] = solver
    prog.status("writing the result", force=True)
    name = scene.name if scene is not None else f"point_M{pb.M:g}_L{pb.L:g}_th{pb.theta:g}"
    return write_and_print(args, out, "point", raw, res, name, payload, False)


def _solve_starved_point(args: argparse.Namespace, scene: Any, pb: Any, fas: dict[str, Any],
                         accuracy: float | None, out: Path, keeper: front.StopKeeper) -> dict[str, Any]:
    """A point scene with a finite ``[supply] hoil``: the starved (mass-conserving) point
    solver, its error estimate, the flooded film of the same discretisation; the result is
    written with ``theta``."""
    from ..starved.point import starved_point_payload

    if not args.json:
        print(f"# scene {scene.name}: M = {pb.M:.5g}, L = {pb.L:.5g}, theta = {pb.theta:.4g}, "
              f"pmax = {pb.pmax:.4g} Pa, a = {pb.a:.4g} m; starved inlet: oil layer "
              f"{scene.supply.hoil:.4g} m (mass-conserving Elrod-Adams solver)")
    fsol = keeper.solve(scene, physics="starved", accuracy=accuracy,
                        options={**fas, "viscosity": pb.viscosity, "density": pb.density})
    sol = require_film(fsol, "starved point solver")
    res = package_result(fsol)
    payload = starved_point_payload(sol, res)
    payload["solver"] = "starved-fas"
    return write_and_print(args, out, "point", sol, res, scene.name, payload, True, (*HIDDEN, "error_budget"))
