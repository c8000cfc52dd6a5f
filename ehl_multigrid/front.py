"""The front door of every film solve, in the manner of ``scipy.optimize.minimize(method=...)``::

    import ehl_multigrid as ehl
    sol = ehl.solve("page63_line_2000N")                     # a scene: name, TOML path or Scene
    sol = ehl.solve(ehl.MoesProblem("line", M=20, L=10))     # Moes groups alone
    sol = ehl.solve(scene, physics="thermal", accuracy=0.01, options={"points": 257})
    sol.Hc, sol.Hm, sol.success, sol.status, sol.error.Hc, sol.error.dominant

:func:`solve` resolves the problem (a :class:`~ehl_multigrid.model.scene.Scene`, a built-in
scene name, a TOML path, or a :class:`~ehl_multigrid.solution.MoesProblem`), decides the
physics and the contact (line, point or elliptic, from the problem), checks the options and
hands the solve to the existing solver of that physics and contact, whose answer it returns as
a :class:`~ehl_multigrid.solution.Solution` (the same contract for every physics). The solvers
and their numbers are unchanged: this is an adapter over
:func:`~ehl_multigrid.line.solve_line`, :func:`~ehl_multigrid.point.solve_point`,
:func:`~ehl_multigrid.starved.solve_starved_scene`,
:func:`~ehl_multigrid.starved.solve_starved_point_scene`, the transient solvers
(:func:`~ehl_multigrid.transient.solve_transient_line`,
:func:`~ehl_multigrid.transient.solve_transient_point`), and the physics the layers above the
core register in the entry-point group ``ehl.physics`` (``thermal``:
:func:`thermal.front.solve_thermal`; the core never imports a layer).

One failure policy: a numerical failure never raises; the solution says it failed
(``success`` False, a :class:`~ehl_multigrid.solution.Status` other than ``CONVERGED``, the
message) and keeps what was computed in ``raw``. Bad input raises
:class:`~ehl_multigrid.model.errors.InputError` naming the field, the value and what is allowed.
"""

from __future__ import annotations

import math
import os
import time
import warnings
from collections.abc import Callable, Collection, Mapping
from dataclasses import fields, is_dataclass, replace
from typing import Any

from .model.errors import (
    ConvergenceError,
    InputError,
    require_choice,
    require_range,
    require_slip,
    signal_cause,
)
from .model.plausibility import warn_model_range
from .model.results import RENAMED_PARTS
from .model.scene import Scene, load_scene
from .solution import (
    ErrorEstimate,
    Grid,
    MoesProblem,
    Outcome,
    PartError,
    Solution,
    StarvedDetails,
    Status,
    TransientDetails,
    as_float,
    frozen_fields,
)

__all__ = ["solve", "resolve_problem", "decide_physics", "solver_keywords", "status_of_error",
           "failed_solution", "ehl_solution", "ehl_error"]

#: the physics the core solves itself; others come from the entry-point group ``ehl.physics``
BUILTIN = ("steady", "starved", "transient")
#: the entry-point group of the physics of the layers above the core:
#: ``solve_physics(scene, *, accuracy, options, callback, progress) -> Solution``
PHYSICS_GROUP = "ehl.physics"
#: options of a transient run besides the multigrid options of its time steps
TRANSIENT_RUN_KEYS = ("dt", "steps", "t_end", "scheme", "snapshot_every", "accept_stall", "xmin",
                      "xmax", "time_error", "checkpoint", "resume", "cavitation", "time_tol",
                      "mass_tol", "time_budget", "max_points", "on_answer")
#: seconds a transient run with an accuracy target may spend refining when no ``time_budget``
#: is given: its refinements multiply the run's steps and grid points (a point run of 129^2
#: points takes about 10 s, at 257^2 and half the step about 80 s)
TRANSIENT_TIME_BUDGET = 600.0
#: the finest grid a transient run's grid refinement takes when no ``max_points`` is given
TRANSIENT_MAX_POINTS = {"line": 4097, "point": 257}
#: options of a scene's steady or starved solve that choose the model rather than the numerics
#: (the scene's ``[solver.ehl]`` table applies below them; a MoesProblem carries its own)
MODEL_KEYS = ("viscosity", "density")
#: the point solvers of the steady physics: FAS/FMG multigrid, and the Newton/pyamg cross-check
POINT_SOLVERS = ("fas", "newton")
#: option names the front door refuses, and why
REFUSED = {"raise_on_failure": "the front door never raises for a numerical failure: the "
                               "solution says it failed (check solution.success and solution.status)"}


# -- problem and physics ---------------------------------------------------------------------------
def resolve_problem(problem: Any) -> tuple[Scene | None, MoesProblem | None]:
    """``(scene, None)`` for a :class:`Scene`, a built-in scene name or a TOML path (loaded with
    :func:`~ehl_multigrid.model.scene.load_scene`); ``(None, problem)`` for a
    :class:`MoesProblem`; InputError otherwise."""
    if isinstance(problem, Scene):
        return problem, None
    if isinstance(problem, MoesProblem):
        return None, problem
    if isinstance(problem, (str, os.PathLike)):
        return load_scene(problem), None
    raise InputError(f"problem = {problem!r} ({type(problem).__name__}) is not a scene (Scene, built-in "
                     f"scene name or TOML path) or a MoesProblem")


def _starved_supply(scene: Scene) -> bool:
    return math.isfinite(scene.supply.hoil) or bool(scene.supply.hoil_profile)


def registered_physics() -> dict[str, Any]:
    """The physics the installed layers register (entry-point group ``ehl.physics``):
    name -> entry point."""
    from importlib.metadata import entry_points

    return {e.name: e for e in entry_points(group=PHYSICS_GROUP) if e.name not in BUILTIN}


def decide_physics(physics: str | None, scene: Scene | None, moes: MoesProblem | None) -> str:
    """The physics to solve: ``physics`` checked against the problem, or (None) ``"starved"``
    for a scene with a finite ``[supply] hoil`` and ``"steady"`` otherwise.

    A flooded ("steady") film is never solved for a starved scene, the starved, thermal and
    transient physics need a scene, and a transient run needs a ``[feature]`` table."""
    known = list(BUILTIN[:2]) + sorted(registered_physics()) + [BUILTIN[2]]
    if physics is None:
        return "starved" if scene is not None and _starved_supply(scene) else "steady"
    if physics not in known:
        raise InputError(f"physics = {physics!r} is not one of the allowed values {known}"
                         + (" (the thermal physics comes with the thermal layer's entry point "
                            f"{PHYSICS_GROUP}:thermal; reinstall the package: pip install -e .)"
                            if physics == "thermal" else ""))
    if moes is not None and physics != "steady":
        raise InputError(f"physics = {physics!r} needs a scene (oil supply, temperatures, solids, "
                         f"feature); a MoesProblem is solved with physics = 'steady'")
    if scene is None:
        return physics
    hoil = scene.supply.hoil
    if physics == "steady" and _starved_supply(scene):
        raise InputError(f"[supply] hoil = {hoil:.4g} m: the scene supplies a finite oil layer, and "
                         f"physics = 'steady' would give the flooded film; use physics = 'starved' "
                         f"(or None, which chooses it), or remove hoil (inf) for a flooded contact")
    if physics == "starved" and not _starved_supply(scene):
        raise InputError(f"[supply] hoil = {hoil:g} m: physics = 'starved' needs a finite oil layer "
                         f"(allowed: (0, inf) m); the scene's inlet is flooded: use physics = 'steady'")
    if physics == "transient" and not scene.feature:
        raise InputError(f"scene {scene.name!r} has no [feature] table: physics = 'transient' runs a "
                         f"surface feature (waviness, bump, dent, map) through the contact")
    return physics


# -- options ---------------------------------------------------------------------------------------
def solver_keywords(options: Any, accepted: Collection[str], cls: type | None,
                    what: str) -> tuple[Any, dict[str, Any]]:
    """``(options_object, keywords)`` of a solve from ``options``: the solver's own options
    dataclass ``cls`` (returned as is), a mapping of keywords (every key in ``accepted``), or
    None. InputError for an unknown key (naming it and the accepted ones), a key of
    :data:`REFUSED`, another dataclass, or anything else."""
    if options is None:
        return None, {}
    if cls is not None and isinstance(options, cls):
        return options, {}
    if is_dataclass(options) and not isinstance(options, type):
        want = f"{cls.__name__} or " if cls is not None else ""
        raise InputError(f"options = {type(options).__name__}(...) are not the options of {what}: give "
                         f"{want}a mapping of {sorted(accepted)}")
    if not isinstance(options, Mapping):
        raise InputError(f"options = {options!r} must be a mapping of solver options (or None)")
    for key in options:
        if key in REFUSED:
            raise InputError(f"option {key!r} is not accepted: {REFUSED[key]}")
    unknown = sorted(str(k) for k in options if k not in accepted)
    if unknown:
        raise InputError(f"unknown option{'s' if len(unknown) > 1 else ''} {unknown} for {what}; "
                         f"accepted: {sorted(accepted)}")
    return None, dict(options)


def _field_names(cls: type) -> set[str]:
    return {f.name for f in fields(cls)} - set(REFUSED)


def warn_unused_callback(callback: Any, what: str) -> None:
    """Say (UserWarning) that ``what`` calls no callback, when one was given."""
    if callback is not None:
        warnings.warn(f"callback is not called: {what} takes no per-cycle callback", UserWarning,
                      stacklevel=4)


# -- failures --------------------------------------------------------------------------------------
def status_of_error(exc: ConvergenceError) -> Status:
    """The status of a :class:`ConvergenceError`: its report's status when it carries one (a
    multilevel solve's), else from its message: a film that closed -> ``FILM_NOT_POSITIVE``,
    a failed start -> ``START_FAILED``, an iteration limit -> ``MAX_CYCLES``, a solve stopped
    by its time budget (:class:`~ehl_multigrid.multigrid.controller.TimeBudgetSpent`) ->
    ``TIME_BUDGET``, otherwise ``DIVERGED`` (as the solvers' own results say for a search or
    solve that failed)."""
    from .multigrid.controller import TimeBudgetSpent

    if isinstance(exc, TimeBudgetSpent):
        return Status.TIME_BUDGET
    rep = getattr(exc, "report", None)
    label = (getattr(rep, "extra", None) or {}).get("status")
    # (a report that says converged belongs to a solve whose result was refused afterwards,
    # e.g. a time step that converged to a non-finite pressure: never a success here)
    if isinstance(label, str) and label.upper() in Status.__members__ and label != "converged":
        return Status[label.upper()]
    text = str(exc).splitlines()[0].lower()
    if "film collapsed" in text or "film closed" in text:
        return Status.FILM_NOT_POSITIVE
    if "start" in text and ("fail" in text or "not converge" in text):
        return Status.START_FAILED
    if "not converge in" in text or "not converged in" in text or "not converged after" in text:
        return Status.MAX_CYCLES
    return Status.DIVERGED


#: statuses whose iterate is no film (an initial guess, or a diverged iterate that may hold
#: NaN/inf): their films and fields are left out of the solution (``raw`` keeps them)
NO_FILM = (Status.START_FAILED, Status.DIVERGED)


def failed_solution(physics: str, contact: str, exc: ConvergenceError, accuracy: float | None,
                    t0: float, scene: Any = None, raw: Any = None) -> Solution:
    """The solution of a solve that raised ``exc``: no films or fields, the status of
    :func:`status_of_error`, the error's message (with its hint), ``raw`` what was kept."""
    status = status_of_error(exc)
    return Solution(physics=physics, contact=contact,
                    outcome=Outcome(False, status, str(exc), time.perf_counter() - t0),
                    error=ErrorEstimate(target=accuracy, notes=("the solve failed: no error estimate",)),
                    raw=raw, scene=scene)


# -- the multilevel results (steady, starved) ---------------------------------------------------------
def ehl_error(est: Any, accuracy: float | None) -> ErrorEstimate:
    """The contract's estimate of an :class:`~ehl_multigrid.multigrid.accuracy.ErrorEstimate`
    (budget ``grid``, ``domain``, ``algebraic`` -> parts ``grid``, ``domain``, ``iteration``)."""
    if est is None:
        return ErrorEstimate(target=accuracy, notes=("not estimated: the iteration did not converge",))
    parts = {RENAMED_PARTS.get(k, k): PartError(as_float(v.get("Hc")), as_float(v.get("Hm")))
             for k, v in est.budget.items()}
    return ErrorEstimate(as_float(est.Hc), as_float(est.Hm), parts, accuracy, tuple(est.notes))


def _grid_of(res: Any, line: bool) -> Grid | None:
    X = getattr(res, "X", None)
    if X is None:
        return None
    levels = int(res.levels) if getattr(res, "levels", 0) else None
    if line:
        return Grid(int(X.shape[0]), None, levels, (float(X[0]), float(X[-1])), False)
    Y = res.Y
    half = bool(getattr(res, "half", False))
    ylo = -float(Y[-1]) if half else float(Y[0])
    return Grid(int(X.shape[0]), int(Y.shape[0]), levels, (float(X[0]), float(X[-1]), ylo, float(Y[-1])), half)


def ehl_solution(res: Any, physics: str, contact: str, accuracy: float | None, t0: float,
                 scene: Any = None, details: Any = None, extra_fields: Mapping[str, Any] | None = None
                 ) -> Solution:
    """The :class:`Solution` of a multilevel solver's
    :class:`~ehl_multigrid.multigrid.result.EHLResult`. A result whose start failed holds the
    initial guess and a diverged one an iterate that is no film (:data:`NO_FILM`): their films
    and fields are left out (they stay in ``raw``); any other failed result keeps its last
    iterate, flagged by its status."""
    status = Status(int(res.status))
    scal = res.scalars
    line = contact == "line"
    film = status not in NO_FILM and getattr(res, "X", None) is not None
    if film and status in (Status.TIME_BUDGET, Status.STOPPED) and not (
            as_float(scal.get("Hc")) > 0.0 and as_float(scal.get("Hm")) > 0.0):
        # a solve stopped (time budget, callback) before a cycle touched its start guess
        # (Hc = Hm = 0): that iterate is no film
        film = False
    arrays: dict[str, Any] = {}
    if film:
        arrays = {"X": res.X, "P": res.P, "H": res.H}
        if not line:
            arrays["Y"] = res.Y
        arrays.update(extra_fields or {})
    builder = None
    if film and getattr(res, "builder", None) is not None:
        def builder() -> Any:
            return res.to_result(scene)
    outcome = Outcome(bool(res.success), status, str(res.message), time.perf_counter() - t0,
                      as_float(res.work_units), int(res.cycles), tuple(res.actions))
    films = {k: as_float(scal.get(k)) if film else math.nan for k in ("Hc", "Hm", "hc", "hm")}
    return Solution(physics=physics, contact=contact, outcome=outcome, **films,
                    error=ehl_error(getattr(res, "error", None), accuracy), fields=frozen_fields(arrays),
                    grid=_grid_of(res, line) if film else None, details=details, raw=res, scene=scene,
                    _result_builder=builder)


def _starved_details(scal: Mapping[str, Any]) -> StarvedDetails:
    flooded = scal.get("inlet_flooded")
    return StarvedDetails(
        meniscus_x=as_float(scal.get("meniscus_x")), Hc_flooded=as_float(scal.get("Hc_flooded")),
        Hm_flooded=as_float(scal.get("Hm_flooded")), Hc_ratio=as_float(scal.get("Hc_ratio")),
        Hm_ratio=as_float(scal.get("Hm_ratio")), mass_balance_error=as_float(scal.get("mass_balance_error")),
        hoil=as_float(scal.get("hoil")), rho_c_Hc_over_hoil=as_float(scal.get("rho_c_Hc_over_hoil")),
        inlet_flooded=None if flooded is None else bool(flooded))


# -- the physics -------------------------------------------------------------------------------------
def _model_keys(options: Any, moes: MoesProblem | None) -> set[str]:
    """The model options a solve accepts: :data:`MODEL_KEYS` for a scene; none for a
    MoesProblem, whose laws are its own fields (InputError naming them when given)."""
    if moes is None:
        return set(MODEL_KEYS)
    given = sorted(k for k in MODEL_KEYS if isinstance(options, Mapping) and k in options)
    if given:
        raise InputError(f"option{'s' if len(given) > 1 else ''} {given} with a MoesProblem: its laws are "
                         f"its own fields (MoesProblem(..., viscosity='barus', density='incompressible'))")
    return set()


def _steady(scene: Scene | None, moes: MoesProblem | None, contact: str, accuracy: float | None,
            options: Any, callback: Any, progress: Any, t0: float) -> Solution:
    from .multigrid.options import LineOptions, PointOptions

    problem: dict[str, Any] = {"scene": scene}
    if moes is not None:
        problem = {"M": moes.M, "L": moes.L, "viscosity": moes.viscosity, "density": moes.density,
                   "alpha": moes.alpha, "eta0": moes.eta0, "p0": moes.p0}
    model = _model_keys(options, moes)
    if contact == "line":
        from .line import solve_line as run

        accepted = _field_names(LineOptions) | {"max_points", "time_budget", "xmin", "xmax", "elastic"} | model
        dc, kw = solver_keywords(options, accepted, LineOptions, "the steady line solver")
    else:
        from .point import solve_point as run

        if moes is not None:
            problem["theta"] = moes.theta
        solver = options.get("solver", "fas") if isinstance(options, Mapping) else "fas"
        require_choice("solver", solver, POINT_SOLVERS)
        if solver == "newton":
            if progress is not None:
                warnings.warn("progress is not called: the Newton/pyamg point solver has no "
                              "accuracy sequence", UserWarning, stacklevel=3)
            return _newton(run, problem, scene, contact, accuracy, options, callback, model, t0)
        accepted = _field_names(PointOptions) | {"max_points", "time_budget", "solver"} | model
        dc, kw = solver_keywords(options, accepted, PointOptions, "the steady point solver")
        kw.pop("solver", None)
    try:
        # (point: the symmetric half domain unless the options, keywords or the scene's
        # [solver.ehl] table say otherwise -- solve_point's default, as 'ehl run' solves)
        res = run(**problem, options=dc, accuracy=accuracy, callback=callback, progress=progress,
                  raise_on_failure=False, **kw)
    except ConvergenceError as exc:
        return failed_solution("steady", contact, exc, accuracy, t0, scene)
    return ehl_solution(res, "steady", contact, accuracy, t0, scene)


def _newton(run: Callable[..., Any], problem: dict[str, Any], scene: Scene | None, contact: str,
            accuracy: float | None, options: Mapping[str, Any], callback: Any, model: set[str],
            t0: float) -> Solution:
    """The steady point contact on the Newton/pyamg cross-check path of
    :func:`~ehl_multigrid.point.solve_point` (``options["solver"] == "newton"``): a fixed grid,
    the full domain, no error estimate."""
    from .point.newton import NewtonOptions

    if accuracy is not None:
        raise InputError(f"accuracy = {accuracy:g} with solver = 'newton': the Newton/pyamg cross-check "
                         f"path estimates no error and refines nothing; give accuracy = None (judged on "
                         f"its iteration alone) or the FAS solver (solver = 'fas', the default)")
    accepted = _field_names(NewtonOptions) | {"solver"} | model
    _, kw = solver_keywords(options, accepted, None, "the Newton/pyamg point solver")
    kw.pop("solver")
    warn_unused_callback(callback, "the Newton/pyamg point solver")
    try:
        res = run(**problem, solver="newton", raise_on_failure=False, **kw)
    except ConvergenceError as exc:
        return failed_solution("steady", contact, exc, accuracy, t0, scene)
    return ehl_solution(res, "steady", contact, accuracy, t0, scene)


def _starved(scene: Scene, contact: str, accuracy: float | None, options: Any, callback: Any,
             progress: Any, t0: float) -> Solution:
    from .multigrid.options import LineOptions, PointOptions

    if contact == "line":
        from .starved import solve_starved_scene as run

        accepted = _field_names(LineOptions) | {"max_points", "time_budget", "xmin", "xmax", "elastic"} | set(MODEL_KEYS)
        dc, kw = solver_keywords(options, accepted, LineOptions, "the starved line solver")
        warn_unused_callback(callback, "the starved line solver (meniscus search)")
    else:
        from .starved import solve_starved_point_scene as run

        accepted = _field_names(PointOptions) | {"max_points", "time_budget", "flooded"} | set(MODEL_KEYS)
        dc, kw = solver_keywords(options, accepted, PointOptions, "the starved point solver")
        warn_unused_callback(callback, "the starved point solver")
    try:
        res = run(scene, options=dc, accuracy=accuracy, raise_on_failure=False, progress=progress, **kw)
    except ConvergenceError as exc:
        return failed_solution("starved", contact, exc, accuracy, t0, scene)
    theta = res.extra.get("theta")
    return ehl_solution(res, "starved", contact, accuracy, t0, scene, _starved_details(res.scalars),
                        {"theta": theta} if theta is not None else None)


def _transient(scene: Scene, contact: str, accuracy: float | None, options: Any, callback: Any,
               t0: float, progress: Callable[[str], None] | None = None) -> Solution:
    from .multigrid.options import LineOptions, PointOptions
    from .transient.defaults import DEFAULT_POINTS, DEFAULT_XMIN
    from .transient.supply import supply_notes

    line = contact == "line"
    cls = LineOptions if line else PointOptions
    accepted = _field_names(cls) | set(TRANSIENT_RUN_KEYS)
    dc, kw = solver_keywords(options, accepted, cls, f"the transient {'line' if line else 'point'} solver")
    runkw = {k: kw.pop(k) for k in TRANSIENT_RUN_KEYS if k in kw}
    want_time_error = bool(runkw.pop("time_error", False))
    budget = runkw.pop("time_budget", None)
    if budget is not None:
        budget = require_range("time_budget", budget, 0.0, math.inf, "s")
    on_answer = runkw.pop("on_answer", None)
    if on_answer is not None and not callable(on_answer):
        raise InputError(f"option on_answer = {on_answer!r} is not callable")
    # a target is judged on a measured error: the time part and the grid part, each from its
    # own runs, refined in the time step and (unless the options fix the grid) the grid
    controlled = accuracy is not None
    held = sorted(k for k in ("checkpoint", "resume") if runkw.get(k) is not None)
    if controlled and held:
        raise InputError(f"option{'s' if len(held) > 1 else ''} {held} with an accuracy target: a "
                         f"checkpoint holds one run, and the error estimate makes several; give "
                         f"accuracy = None (the run judged on its steps, time_error still measured) "
                         f"or leave out {' and '.join(held)} (on_answer keeps each finished answer)")
    fixed_grid = (dc is not None) or ("points" in kw)
    max_points = runkw.pop("max_points", None)
    if max_points is not None and fixed_grid:
        raise InputError(f"option max_points = {max_points} with a fixed grid (points or an options "
                         f"object): leave out points to let the grid be refined up to max_points")
    require_slip("operating.slip", scene.slip)
    if dc is None:
        kw.setdefault("points", DEFAULT_POINTS["line" if line else "point"])
    box_keys = {k: runkw.pop(k) for k in ("xmin", "xmax") if k in runkw}
    warn: list[str] = []
    if line:
        from .line.problem import LineProblem
        from .transient.scene_feature import feature_from_scene_table
        from .transient.solve import solve_transient_line as solver

        # the box is the problem's (xmin, xmax), as 'ehl transient' builds it
        pb = LineProblem.from_scene(scene, **{"xmin": DEFAULT_XMIN, **box_keys})
        feature, body = feature_from_scene_table(scene.feature, pb)
        scale = pb.b**2 / pb.R
        starved_ok = runkw.get("cavitation") == "mass-conserving"
        if starved_ok and not scene.supply.hoil_profile and math.isfinite(scene.supply.hoil):
            from .starved.supply import hoil_venner

            runkw["hoil"] = hoil_venner(scene.supply.hoil, pb.b, pb.R)
    else:
        from .point.problem import problem_from_scene, resolve_domain
        from .transient.point_solve import solve_transient_point as solver
        from .transient.scene_feature import point_feature_from_scene_table

        pb = problem_from_scene(scene)
        starved_ok = runkw.get("cavitation") == "mass-conserving"
        if starved_ok and (scene.supply.hoil_profile or math.isfinite(scene.supply.hoil)):
            from .starved.supply import hoil_venner, layer_across_track

            # Venner units of the point contact: hoil Rx/a^2 (as solve_starved_point_scene)
            if scene.supply.hoil_profile:
                runkw["hoil_y"] = layer_across_track(scene.supply, pb.a, pb.Rx)
            else:
                runkw["hoil"] = hoil_venner(scene.supply.hoil, pb.a, pb.Rx)
        if dc is not None and box_keys:
            raise InputError(f"options {sorted(box_keys)} with a PointOptions object: give the box "
                             f"(xmin, xmax, ymax) in the PointOptions")
        if dc is None:
            kw.update({"xmin": DEFAULT_XMIN, **box_keys})
        src = kw if dc is None else {k: getattr(dc, k) for k in ("xmin", "xmax", "ymax")}
        box = resolve_domain(pb, src.get("xmin"), src.get("xmax"), src.get("ymax"))
        feature, body = point_feature_from_scene_table(scene.feature, pb, box, warn)
        scale = pb.a**2 / pb.Rx
    # the projection models a flooded inlet: a starving supply is refused (as 'ehl transient')
    notes = warn + supply_notes(scene, feature, scale, starved_ok)

    def run(call: Any = callback, **step: Any) -> Any:
        opts = dc
        if "points" in step and dc is not None:
            opts = replace(dc, points=step.pop("points"))
        box = step.pop("box", 1.0)
        # the controller's longer box (line): the inlet moved upstream, the outlet kept
        problem = pb if box == 1.0 else replace(pb, xmin=pb.xmax - box * (pb.xmax - pb.xmin))
        return solver(problem, feature, body=body, slide_roll=scene.slip, options=opts, callback=call,
                      **{**kw, **runkw, **step})

    if controlled:
        points = int(kw["points"] if dc is None else dc.points)
        if fixed_grid:
            most = points
        else:
            most = TRANSIENT_MAX_POINTS["line" if line else "point"] if max_points is None else int(
                require_range("max_points", max_points, points, 2**20 + 1, "points"))
        return _transient_to_accuracy(run, points, most, line, runkw, pb, scale, accuracy,
                                      TRANSIENT_TIME_BUDGET if budget is None else budget, callback,
                                      on_answer, t0, scene, notes, progress, line and not box_keys)
    try:
        res = run()
    except ConvergenceError as exc:
        part = getattr(exc, "partial", None)
        if part is None or not part.series["T"]:
            return failed_solution("transient", contact, exc, accuracy, t0, scene, part)
        return _transient_solution(part, pb, line, scale, accuracy, t0, scene, notes, None,
                                   (status_of_error(exc), str(exc)))
    if on_answer is not None and res.complete:
        on_answer(res)
    terr = None
    if want_time_error:
        from .transient.accuracy import (
            TIGHTER_TOL,
            adaptive_time_error,
            tighter_run_options,
            time_error,
        )

        adaptive = runkw.get("time_tol") is not None
        second = (f"the run at {TIGHTER_TOL:g} of the time tolerance and half the step" if adaptive
                  else "the run at twice the time step")
        try:
            # (a run of its own: it neither writes the run's checkpoint nor continues it)
            if adaptive:
                terr = adaptive_time_error(res, run(None, **tighter_run_options(res, runkw["time_tol"]),
                                                    checkpoint=None, resume=None))
            else:
                terr = time_error(res, run(None, dt=2.0 * res.dt, steps=max(res.planned_steps // 2, 1),
                                           t_end=None, checkpoint=None, resume=None))
        except ConvergenceError as exc:
            notes.append(f"{second} for the time error failed: {str(exc).splitlines()[0]}")
        except InputError as exc:  # beyond what the feature or the tolerance's range allows
            notes.append(f"time error not measured: {second} is refused ({exc})"
                         + ("" if adaptive else "; a smaller dt allows it"))
    return _transient_solution(res, pb, line, scale, accuracy, t0, scene, notes, terr, None)


def _transient_to_accuracy(run: Callable[..., Any], points: int, max_points: int, line: bool,
                           runkw: dict[str, Any], pb: Any, scale: float, accuracy: float, budget: float,
                           callback: Any, on_answer: Any, t0: float, scene: Scene,
                           notes: list[str], progress: Callable[[str], None] | None = None,
                           box_refinable: bool = False) -> Solution:
    """A transient run whose time, grid and box parts are measured
    (:class:`~ehl_multigrid.transient.control.TransientControl`) and refined by the accuracy
    controller, in the time step, up to ``max_points`` in the grid and (``box_refinable``) in
    the inlet length, until their sum meets ``accuracy`` or ``budget`` seconds are spent."""
    from .multigrid.controller import Resolution, control
    from .transient.control import TransientControl

    ctl = TransientControl(run, dimensions=1 if line else 2, scheme=runkw.get("scheme", "bdf2"),
                           time_tol=runkw.get("time_tol"), callback=callback, points=points,
                           max_points=max_points, on_answer=on_answer, progress=progress,
                           box_refinable=box_refinable, accuracy=accuracy)
    out = control(ctl, Resolution(points), accuracy, time_budget=budget, max_points=max_points, started=t0,
                  progress=progress)
    r = out.result
    if not out.converged:  # the first run failed: as without a target
        exc = r.error
        if isinstance(exc, ConvergenceError):
            if r.result is None or not r.result.series["T"]:
                return failed_solution("transient", scene.kind, exc, accuracy, t0, scene, r.result)
            return _transient_solution(r.result, pb, line, scale, accuracy, t0, scene, notes, None,
                                       (status_of_error(exc), str(exc)))
        return _transient_solution(r.result, pb, line, scale, accuracy, t0, scene, notes, None, None)
    notes = notes + ([ctl.notes[r.at]] if r.at in ctl.notes else [])
    return _transient_solution(r.result, pb, line, scale, accuracy, t0, scene, notes, ctl.parts.get(r.at),
                               None, (out, ctl))


def _transient_solution(res: Any, pb: Any, line: bool, scale: float, accuracy: float | None, t0: float,
                        scene: Any, notes: list[str], terr: dict[str, float] | None,
                        failure: tuple[Status, str] | None, controlled: tuple[Any, Any] | None = None
                        ) -> Solution:
    """The :class:`Solution` of a transient run ``res``; ``controlled``: the
    :class:`~ehl_multigrid.multigrid.controller.ControlOutcome` and the
    :class:`~ehl_multigrid.transient.control.TransientControl` of a run refined to a target."""
    import numpy as np

    def moes(H: Any) -> Any:
        if line:
            return np.array([pb.moes_from_venner(float(h)) for h in np.atleast_1d(H)])
        return np.atleast_1d(np.asarray(H, dtype=float)) * pb.moes_factor

    Hc_v, Hm_v = res.Hc, res.Hm
    Hc_s, Hm_s = moes(Hc_v), moes(Hm_v)
    last = max(res.snapshots)
    snap = res.snapshots[last]
    arrays = {"X": res.X, "P": snap["P"], "H": snap["H"]}
    Y = getattr(res, "Y", None)
    if not line:
        arrays["Y"] = Y
    s = res.summary()
    cyc = np.asarray(res.series["cycles"][1:], dtype=float)
    wu = np.asarray(res.series["work_units"][1:], dtype=float)
    details = TransientDetails(
        times=res.T, Hc_series=Hc_s, Hm_series=Hm_s, hc_series=Hc_v * scale, hm_series=Hm_v * scale,
        complete=bool(res.complete), stop_reason=res.stop_reason, steps=int(res.steps),
        planned_steps=int(res.planned_steps), dt=float(res.dt), scheme=res.scheme,
        feature=res.feature.describe(), Hc_steady=float(moes(res.steady_film("Hc"))[0]),
        Hm_steady=float(moes(res.steady_film("Hm"))[0]), Hc_min=float(Hc_s.min()), Hc_max=float(Hc_s.max()),
        Hm_min=float(Hm_s.min()), stalled_steps=int(s["stalled_steps"]), notes=tuple(notes))
    measured = terr is not None
    gerr = derr = None
    if controlled is not None:
        at = controlled[0].result.at
        gerr, derr = controlled[1].grid_parts.get(at), controlled[1].box_parts.get(at.box)
    nan = PartError(math.nan, math.nan)
    parts = {"grid": PartError(gerr["Hc"], gerr["Hm"]) if gerr is not None else nan,
             "time": PartError(terr["Hc"], terr["Hm"]) if measured else nan,
             "domain": PartError(derr["Hc"], derr["Hm"]) if derr is not None else nan}
    local = s.get("time_error_max", math.nan)
    adaptive = math.isfinite(local)
    if controlled is None:
        enotes = ("no accuracy target: the grid (space) error is not estimated, and each time step is "
                  "converged to its residual tolerance",)
    else:
        enotes = ("grid part: Richardson in the mesh size on the largest film differences over the run "
                  "from the same steps on the grids with half and a quarter of the intervals (max over "
                  "the run, relative to the smooth steady film); each time step is converged to its "
                  "residual tolerance",
                  controlled[1].box_notes.get(controlled[0].result.at.box, "box part not measured"))
    if measured:
        enotes += ("time part: twice the largest film difference from a run at an eighth of the time "
                   "tolerance and half the output step (max over the run, relative to the smooth "
                   "steady film)" if adaptive else
                   "time part: twice the Richardson term in the time step from a run at twice the "
                   "step (max over the run, relative to the smooth steady film)",)
    elif controlled is not None:
        why = next((n for n in notes if "time error" in n), "")
        enotes += (why if why.startswith("time error not measured") else f"time part not measured: {why}",)
    else:
        enotes += ("time part not measured (options time_error=True measures it: a second run at "
                   + ("an eighth of the time tolerance and half the output step, about three times the "
                      "cost)" if adaptive else
                      "twice the time step, about 1.5 times the cost)"),)
    if adaptive:
        # the local error bounds one step, not the film's error over the run (docs/transient.md)
        enotes += (f"time steps sized by time_tol: largest local film error per step {local:.2g} "
                   f"({s['rejected_steps']} steps solved again smaller)",)
    both = measured and gerr is not None and derr is not None
    error = ErrorEstimate(terr["Hc"] + gerr["Hc"] + derr["Hc"] if both else math.nan,
                          terr["Hm"] + gerr["Hm"] + derr["Hm"] if both else math.nan, parts, accuracy, enotes)
    if failure is not None:
        status, message = failure
    elif not res.complete:
        status, message = Status.FILM_NOT_POSITIVE, res.stop_reason
    else:
        done = f"completed {res.steps} time steps of dT = {res.dt:.4g} on {res.X.size} points"
        if accuracy is None:
            status, message = Status.CONVERGED, done
        else:
            met = controlled[0].met and both
            status = Status.CONVERGED if met else Status.INACCURATE
            message = _transient_judgement(done, controlled, error, accuracy)
    actions = tuple(getattr(res.steady, "actions", ()))
    if controlled is not None:
        actions += controlled[1].actions(controlled[0], accuracy)
    outcome = Outcome(status == Status.CONVERGED, status, message, time.perf_counter() - t0,
                      float(wu.sum()) if wu.size else math.nan, int(cyc.sum()), actions)
    grid = Grid(int(res.X.size), None if line else int(Y.size), None,
                (float(res.X[0]), float(res.X[-1])) if line else
                (float(res.X[0]), float(res.X[-1]), float(Y[0]), float(Y[-1])), False)
    films = {"Hc": float(Hc_s[-1]), "Hm": float(Hm_s[-1]), "hc": float(Hc_v[-1]) * scale,
             "hm": float(Hm_v[-1]) * scale}

    def builder() -> Any:
        from .transient.package_result import transient_result

        return transient_result(scene.kind, scene, arrays, details, films)
    return Solution(physics="transient", contact=scene.kind, outcome=outcome, **films, error=error,
                    fields=frozen_fields(arrays), grid=grid, details=details, raw=res, scene=scene,
                    _result_builder=builder)


def _transient_judgement(done: str, controlled: tuple[Any, Any], error: ErrorEstimate,
                         accuracy: float) -> str:
    """The message of a completed run judged against ``accuracy``: its parts, the refinements,
    and why it stopped short."""
    out, ctl = controlled
    answers = ctl.answers
    refined = len(answers) - 1
    how = f" after {refined} refinement{'s' if refined > 1 else ''} from {answers[0].describe()}" if refined > 0 else ""
    if out.result is not out.last:
        how += "; the most accurate run of the sequence"
    t, g, d = error.parts["time"], error.parts["grid"], error.parts["domain"]
    tm = (f"time part Hc {t.Hc:.2g}, Hm {t.Hm:.2g}" if math.isfinite(t.worst) else "time part not measured")
    gm = (f"grid part Hc {g.Hc:.2g}, Hm {g.Hm:.2g}" if math.isfinite(g.worst) else "grid part not measured")
    dm = (f"box part Hc {d.Hc:.2g}, Hm {d.Hm:.2g}" if math.isfinite(d.worst) else "box part not measured")
    if out.met and math.isfinite(error.Hc):
        return (f"{done}: error Hc {error.Hc:.2g}, Hm {error.Hm:.2g} ({tm}; {gm}; {dm}) within the accuracy "
                f"{accuracy:g}{how}")
    total = (f"error Hc {error.Hc:.2g}, Hm {error.Hm:.2g}" if math.isfinite(error.Hc) else "error not known")
    return f"{done}: {total} ({tm}; {gm}; {dm}) above the accuracy {accuracy:g}{how}; not refined further: {out.why}"


# -- the front door ----------------------------------------------------------------------------------
def solve(problem: Scene | MoesProblem | str | os.PathLike, *, physics: str | None = None,
          accuracy: float | None = 0.005, options: Mapping[str, Any] | Any = None,
          callback: Callable[[dict[str, Any]], Any] | None = None,
          progress: Callable[[str], None] | None = None) -> Solution:
    """Solve the film of a lubricated contact.

    Parameters
    ----------
    problem : a :class:`~ehl_multigrid.model.scene.Scene`, a built-in scene name or a TOML
        path (:func:`~ehl_multigrid.model.scene.load_scene`), or a
        :class:`~ehl_multigrid.solution.MoesProblem`. The contact (line, point, elliptic)
        follows from it.
    physics : ``"steady"`` (isothermal, flooded), ``"starved"`` (mass-conserving, Elrod-Adams,
        the scene's finite ``[supply] hoil``), ``"thermal"`` (TEHL; from the thermal layer)
        or ``"transient"`` (the scene's ``[feature]`` passing through the contact). None:
        ``"starved"`` for a scene with a finite ``[supply] hoil``, else ``"steady"``. A
        flooded film is never solved for a starved scene (``"steady"`` with a finite hoil is
        refused).
    accuracy : relative target of the estimated errors of Hc and Hm, in [1e-5, 0.5]; the
        solvers refine their grid (box, tolerances) towards it unless the options fix the grid,
        and a result that misses it has status ``INACCURATE``. None: judged on the iteration
        alone. A transient run with a target measures its time part (a run at twice the step)
        and grid part (the same steps on the grids with half and a quarter of the intervals),
        relative to the smooth steady film over the run, and refines the time step and,
        unless the options fix the grid, the grid (up to ``max_points``) until their sum meets
        it, within ``time_budget`` (default 600 s) (docs/transient.md). None: one run judged
        on its steps.
    options : a mapping of the solver's options (e.g. ``{"points": 257, "max_points": 513,
        "time_budget": 30, "half": True}``), or the solver's own options object
        (:class:`~ehl_multigrid.multigrid.options.LineOptions`,
        :class:`~ehl_multigrid.multigrid.options.PointOptions`, thermal:
        ``thermal.tehl.line.TEHLOptions``). Besides the numerical options a scene's steady or
        starved solve takes the model, ``viscosity`` and ``density`` (above the scene's
        ``[solver.ehl]`` table; a MoesProblem carries its own), a steady point solve
        ``solver="newton"`` (the Newton/pyamg cross-check path: a fixed grid, the
        :class:`~ehl_multigrid.point.newton.NewtonOptions` fields, ``accuracy=None``), and a
        transient run ``time_error``, ``time_budget`` (seconds of the refinement to a target),
        ``max_points`` (the finest grid of that refinement; default 4097 line, 257 point),
        ``on_answer`` (called with each completed answer of the refinement, as it completes),
        ``checkpoint`` and ``resume`` (:mod:`ehl_multigrid.transient.checkpoint`; refused
        together with a target: a checkpoint holds one run).
        An unknown key is refused, naming it and the accepted ones (see docs/api.md for each
        physics).
    callback : called with a small dict after every multilevel cycle (steady) or time step
        (transient; the first run's steps when the time step is refined to a target); raising StopIteration in it stops a steady solve (status ``STOPPED``).
        The starved and thermal solvers and the Newton path take none (a UserWarning says so).
    progress : called with one line of text per solve of the accuracy sequence (grid, box,
        estimate, seconds), as ``ehl solve`` prints on stderr: steady FAS, starved, thermal and
        transient (each run of the refinement to a target) solves. A transient run without a
        target and the Newton path have no such sequence: a UserWarning says ``progress`` is
        not called.

    Returns
    -------
    Solution
        ``Hc``, ``Hm`` (Moes), ``hc``, ``hm`` [m], ``success``, ``status``, ``message``,
        ``error`` (``Hc``, ``Hm``, ``parts``, ``dominant``), ``fields``, ``grid``,
        ``details`` -- the same meaning for every physics.

    Raises
    ------
    InputError
        Bad input only (problem, physics, accuracy, options, scene values), naming the field,
        the value and what is allowed. A numerical failure is returned, never raised.
    KeyboardInterrupt
        Ctrl-C (or the command line's SIGTERM, ``Terminated``) stops the solve. When it stops a
        steady, starved or thermal accuracy sequence that has finished (converged and
        estimated) a solve, the exception's ``solution`` is the most accurate of them, status
        ``INACCURATE``, its message naming the stop: ``except KeyboardInterrupt as e:
        getattr(e, "solution", None)``.

    Notes
    -----
    The first call defaults ``OMP_WAIT_POLICY`` to ``PASSIVE`` in the process's environment
    (a value already set wins), as the ``ehl`` command does
    (:func:`~ehl_multigrid.multigrid.threads.passive_openmp_wait`): OpenMP threads that spin
    between parallel regions take the working thread's core when the machine is busy (a
    129-point thermal point solve, other core busy: 31-141 s spinning, 11 s passive, 9 s on
    one thread). It has no effect once numba's threads run (set it before then to choose).
    """
    from .multigrid.controller import keep_on_stop
    from .multigrid.threads import passive_openmp_wait  # (the solvers load on first use)

    t0 = time.perf_counter()
    passive_openmp_wait()
    scene, moes = resolve_problem(problem)
    contact = scene.kind if scene is not None else moes.contact
    physics = decide_physics(physics, scene, moes)
    if accuracy is not None:
        require_range("accuracy", accuracy, 1e-5, 0.5, "- (relative error)")
    for name, fn in (("callback", callback), ("progress", progress)):
        if fn is not None and not callable(fn):
            raise InputError(f"{name} = {fn!r} is not callable")
    if physics == "transient" and progress is not None and accuracy is None:
        warnings.warn("progress is not called: a transient run without a target is one run, reported "
                      "per time step through callback", UserWarning, stacklevel=2)
    if physics == "transient":  # a stopped run keeps its steps through its checkpoint instead
        sol = _dispatch(physics, scene, moes, contact, accuracy, options, callback, progress, t0)
    else:
        with keep_on_stop() as scope:
            sol = _dispatch(physics, scene, moes, contact, accuracy, options, callback, progress, t0)
        if scope is not None and scope.stop is not None:
            scope.stop.solution = sol  # type: ignore[attr-defined]
            raise scope.stop
    if scene is not None and sol.fields:
        warn_model_range("film", sol.hm, f"the minimum film hm of {scene.name}")
    return sol


class StopKeeper:
    """Solves through :func:`solve` for a command that writes its answer: a stop (Ctrl-C,
    SIGTERM) that kept the most accurate finished solve of an accuracy sequence returns that
    solution from :meth:`solve`, so the command writes it, and :meth:`raise_stop` raises the
    stop afterwards with ``kept`` saying what was written (the command line prints it)."""

    def __init__(self) -> None:
        self.stop: BaseException | None = None

    def solve(self, problem: Any, **kw: Any) -> Solution:
        try:
            return solve(problem, **kw)
        except BaseException as exc:
            stop = signal_cause(exc)
            sol = getattr(stop, "solution", None)
            if sol is None:
                raise
            self.stop = stop
            return sol

    def raise_stop(self, written: str, note: str = "") -> None:
        """Raise the kept stop, if any; ``written`` names the file the kept answer went to
        (the stop's ``written``; "": none), ``note`` what else the command says about it."""
        if self.stop is None:
            return
        sol = self.stop.solution  # type: ignore[attr-defined]
        grid = f"{sol.grid.points} points, " if sol.grid is not None else ""
        err = (f"stated error Hc {sol.error.Hc:.2g}, Hm {sol.error.Hm:.2g}"
               if math.isfinite(sol.error.Hc) and math.isfinite(sol.error.Hm) else "error not known")
        self.stop.kept = (f"the most accurate finished solve ({grid}{err}, status {sol.status.label}) "  # type: ignore[attr-defined]
                          + (f"was written to {written}{note}" if written else f"was not written (no output folder){note}"))
        self.stop.written = written or None  # type: ignore[attr-defined]
        raise self.stop


def _dispatch(physics: str, scene: Scene | None, moes: MoesProblem | None, contact: str,
              accuracy: float | None, options: Any, callback: Any, progress: Any, t0: float) -> Solution:
    """The solve of ``physics``: the core's own, or the layer registered for it."""
    if physics == "steady":
        return _steady(scene, moes, contact, accuracy, options, callback, progress, t0)
    if physics == "starved":
        return _starved(scene, contact, accuracy, options, callback, progress, t0)
    if physics == "transient":
        return _transient(scene, contact, accuracy, options, callback, t0, progress)
    run = registered_physics()[physics].load()
    try:
        sol = run(scene, accuracy=accuracy, options=options, callback=callback, progress=progress)
    except ConvergenceError as exc:  # the layer's adapter should return it; the policy holds anyway
        return failed_solution(physics, contact, exc, accuracy, t0, scene)
    if not isinstance(sol, Solution):
        raise TypeError(f"the {PHYSICS_GROUP}:{physics} entry point returned {type(sol).__name__}, "
                        f"not a Solution")
    return sol
