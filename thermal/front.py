"""The thermal physics of the front door :func:`ehl_multigrid.solve` (``physics="thermal"``),
registered in the entry-point group ``ehl.physics`` so the core never imports this layer.

:func:`solve_thermal` wraps :func:`thermal.tehl.accuracy.solve_tehl_to_accuracy` (line and
point contacts; a line scene with a finite ``[supply] hoil`` is solved starved, a point scene
with one is refused), or with ``estimate=False`` the TEHL solve alone (:func:`film_alone`),
and returns its answer as a :class:`~ehl_multigrid.solution.Solution`: the TEHL films, the
budget of :func:`thermal.tehl.accuracy.estimate_error` as error parts (``grid`` along X,
``nz`` across the film, ``domain``, ``iteration``; point films anchored on the core's
isothermal films also ``isothermal``) and the thermal quantities in
:class:`~ehl_multigrid.solution.ThermalDetails`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import fields, replace
from typing import Any

from ehl_multigrid.front import failed_solution, solver_keywords, warn_unused_callback
from ehl_multigrid.model.errors import ConvergenceError, InputError, require_range
from ehl_multigrid.model.scene import Scene
from ehl_multigrid.solution import (
    ErrorEstimate,
    Grid,
    Outcome,
    PartError,
    Solution,
    StarvedDetails,
    Status,
    ThermalDetails,
    as_float,
    frozen_fields,
)

#: keywords of :func:`~thermal.tehl.accuracy.solve_tehl_to_accuracy` accepted as options beside
#: the :class:`~thermal.tehl.line.TEHLOptions` fields
RUN_KEYS = ("slip", "max_points", "max_nz", "box_limit", "time_budget", "threads", "estimate", "start")
#: the budgets of the refinement towards a target, which needs the error estimate
REFINE_KEYS = ("max_points", "max_nz", "box_limit", "time_budget")


def solve_thermal(scene: Scene, *, accuracy: float | None, options: Any = None,
                  callback: Any = None, progress: Any = None) -> Solution:
    """Thermal EHL (TEHL) solve of a line or point ``scene`` to ``accuracy``.

    Parameters
    ----------
    scene : the scene (its slip unless ``options["slip"]``).
    accuracy : relative target of the estimated errors of Hc and Hm, or None (judged on the
        outer iteration alone).
    options : a mapping of :class:`~thermal.tehl.line.TEHLOptions` fields (``points``, ``nz``,
        ``compressive_heating`` ...) and of ``slip``, ``max_points``, ``max_nz``, ``box_limit``,
        ``time_budget`` [s] (the refinement's budgets), ``threads`` (numba threads of the
        solve, in [1, 1024]; the caller's setting is restored afterwards); or a
        ``TEHLOptions``. As ``ehl solve --thermal``: the grid starts at 513 points (line) or
        257 (point), nz 20, and is refined towards the target unless ``points`` or ``nz`` is
        given (or a ``TEHLOptions``), which are only judged. ``estimate`` (default True):
        False solves the film alone on its grid, without the error estimate (the error is
        then unknown: with a target the solve is ``INACCURATE``, with ``accuracy=None``
        judged on its outer iteration alone). ``start``: the :class:`Solution` of a thermal
        solve of the same line scene at another slip on the same grid along X and box (a
        traction curve's previous slip): the solve continues from it (its isothermal start
        and solution, or a starved solve's meniscus; :func:`thermal.tehl.line.continuation`).
    progress : called with one line of text per solve of the refinement sequence.
    callback : not called (the TEHL solve takes none; a UserWarning says so). The TEHL solve
        reports no progress lines either (the front door's ``progress`` is not passed here).

    Returns a :class:`~ehl_multigrid.solution.Solution` (``physics="thermal"``); a solve that
    fails returns ``success`` False with its status, never raises. InputError for bad input
    (options, slip, a starved point scene, a start of another contact or grid).
    """
    from .tehl.accuracy import solve_tehl_to_accuracy
    from .tehl.line import TEHLOptions

    t0 = time.perf_counter()
    accepted = {f.name for f in fields(TEHLOptions)} | set(RUN_KEYS)
    dc, kw = solver_keywords(options, accepted, TEHLOptions, "the thermal (TEHL) solve")
    run = {k: kw.pop(k) for k in RUN_KEYS if k in kw}
    warn_unused_callback(callback, "the thermal (TEHL) solve")
    point = scene.kind != "line"
    if dc is None:
        refine = not ({"points", "nz"} & set(kw))
        dc = TEHLOptions(**{"points": 257 if point else 513, **kw})
    else:
        refine = False
    slip = run.pop("slip", None)
    threads = run.pop("threads", None)
    if threads is not None:
        require_range("threads", threads, 1, 1024, "threads")
    estimate = run.pop("estimate", True)
    if not isinstance(estimate, bool):
        raise InputError(f"option estimate = {estimate!r} must be true or false")
    previous = start_result(run.pop("start", None), scene, dc)
    refused = sorted(k for k in REFINE_KEYS if k in run)
    if not estimate and refused:
        raise InputError(f"option{'s' if len(refused) > 1 else ''} {refused} with estimate = False: "
                         f"the refinement towards the accuracy needs the error estimate")
    try:
        with _threads(threads):
            if not estimate:
                done = film_alone(scene, slip, dc, accuracy, previous)
            else:
                done = solve_tehl_to_accuracy(scene, slip, dc, accuracy, refine=refine, progress=progress,
                                              start=previous, **run)
    except ConvergenceError as exc:
        return failed_solution("thermal", scene.kind, exc, accuracy, t0, scene)
    return thermal_solution(done, scene, accuracy, t0)


def start_result(start: Any, scene: Scene, options: Any) -> Any:
    """The TEHL line result a solve continues from (option ``start``; None: none): the
    :class:`Solution` of a thermal solve with a film, of ``scene`` at another slip, on the grid
    along X and the box of ``options``. InputError naming what differs otherwise."""
    if start is None:
        return None
    if scene.kind != "line":
        raise InputError(f"option start with a {scene.kind} contact: a TEHL point solve starts from its own "
                         f"isothermal solve (start applies to line contacts)")
    if not isinstance(start, Solution) or start.physics != "thermal" or start.raw is None:
        what = (f"a {start.physics} Solution" if isinstance(start, Solution) and start.raw is not None else
                "a Solution without a film" if isinstance(start, Solution) else type(start).__name__)
        raise InputError(f"option start = {what}: it must be the Solution of a thermal solve that produced a "
                         f"film (ehl_multigrid.solve(..., physics='thermal'))")
    r = start.raw.result
    if replace(r.scene, slip=scene.slip) != scene:
        raise InputError(f"option start is a solve of scene {r.scene.name!r}, which differs from scene "
                         f"{scene.name!r} in more than its slip: a solve continues one of the same contact")
    o = options
    theirs = (r.options.points, r.options.xmin, r.options.xmax, r.options.box)
    if theirs != (o.points, o.xmin, o.xmax, o.box):
        raise InputError(f"option start was solved on points = {theirs[0]}, xmin = {theirs[1]}, xmax = "
                         f"{theirs[2]}, box = {theirs[3]:g}; this solve asks for points = {o.points}, xmin = "
                         f"{o.xmin}, xmax = {o.xmax}, box = {o.box:g}: a solve continues one on its own "
                         f"grid and box")
    return r


def film_alone(scene: Scene, slip: float | None, options: Any, accuracy: float | None,
               previous: Any = None) -> Any:
    """The TEHL film of ``scene`` on the grid of ``options`` without its error estimate
    (option ``estimate=False``), continuing from ``previous`` (:func:`start_result`), as an
    :class:`~thermal.tehl.accuracy.AccurateTEHL` whose ``estimate`` is None: accurate only
    without a target (the error is not known). Raises the solver's ConvergenceError."""
    from .tehl.accuracy import AccurateTEHL
    from .tehl.line import continuation, solve_tehl_line
    from .tehl.point import solve_tehl_point

    t0 = time.perf_counter()
    if scene.kind == "line":
        r = solve_tehl_line(scene, slip, options, **continuation(previous, scene))
    else:
        r = solve_tehl_point(scene, slip, options)
    if accuracy is None:
        msg = "converged (the outer iteration; the error is not estimated: estimate = False)"
    else:
        msg = (f"the error is not estimated (estimate = False), so the accuracy {accuracy:g} cannot be "
               f"confirmed (accuracy = None judges the solve on its outer iteration alone)")
    return AccurateTEHL(r, None, accuracy, accuracy is None, [], msg, time.perf_counter() - t0)


@contextmanager
def _threads(threads: int | None) -> Iterator[None]:
    """numba's thread count for the solve (None: the caller's), restored afterwards: it is
    process state, and the TEHL options carry none."""
    if threads is None:
        yield
        return
    import numba

    from ehl_multigrid.multigrid.threads import preserved_threads, resolve_threads

    with preserved_threads():
        numba.set_num_threads(resolve_threads(threads))
        yield


def thermal_solution(done: Any, scene: Scene, accuracy: float | None, t0: float) -> Solution:
    """The :class:`Solution` of an :class:`~thermal.tehl.accuracy.AccurateTEHL`."""
    from .tehl.accuracy import CONTRACT_PARTS
    from .tehl.results import tehl_line_result, tehl_point_result

    r, est = done.result, done.estimate
    point = scene.kind != "line"
    if float(r.scene.slip) != float(r.slip):
        # the result's scene is the contact solved: at the slip asked for (options["slip"]), so
        # that a saved result solved again from its scene gives the same answer
        r.scene = r.scene.with_operating(slip=float(r.slip))
        scene = r.scene
    if done.accurate:
        status, message = Status.CONVERGED, done.message
    else:  # as 'ehl solve --thermal': converged means the estimate meets the target too
        status, message = Status.INACCURATE, "iteration converged but " + done.message
    actions = tuple((getattr(r.report, "extra", None) or {}).get("actions", ()))
    outcome = Outcome(status == Status.CONVERGED, status, message, time.perf_counter() - t0,
                      math.nan, len(r.outer), actions)
    if est is None:  # (estimate = False)
        error = ErrorEstimate(target=accuracy, notes=("not estimated: the film was solved alone (estimate = False)",))
        budget: dict[str, Any] = {}
    else:
        parts = {CONTRACT_PARTS[p]: PartError(as_float(est.budget["Hc"][p]), as_float(est.budget["Hm"][p]))
                 for p in CONTRACT_PARTS if p in est.budget["Hc"]}
        error = ErrorEstimate(as_float(est.Hc), as_float(est.Hm), parts, accuracy, tuple(est.notes))
        budget = est.budget
    o = r.options
    starved = None
    if getattr(r, "starved", None):
        s = r.starved
        flooded = s.get("inlet_flooded")
        starved = StarvedDetails(
            meniscus_x=as_float(s.get("meniscus_x")), Hc_flooded=as_float(s.get("Hc_flooded")),
            Hm_flooded=as_float(s.get("Hm_flooded")), Hc_ratio=as_float(s.get("Hc_ratio")),
            Hm_ratio=as_float(s.get("Hm_ratio")), mass_balance_error=as_float(s.get("mass_balance_error")),
            hoil=as_float(s.get("hoil")), inlet_flooded=None if flooded is None else bool(flooded))
    details = ThermalDetails(
        Hc_isothermal=float(r.Hc_isothermal), Hm_isothermal=float(r.Hm_isothermal),
        friction=float(r.friction), friction_coefficient=float(r.friction_coefficient),
        friction_decoupled=float(r.friction_decoupled), T_max=float(r.T_max),
        heat_balance_error=float(r.heat_balance_error),
        heat_partition=tuple(float(x) for x in r.heat_partition), slip=float(r.slip), nz=int(o.nz),
        outer_iterations=len(r.outer),
        friction_coefficient_error=as_float(budget.get("friction_coefficient", {}).get("total")),
        T_max_error_K=as_float(budget.get("T_max", {}).get("total")), starved=starved)
    scale = r.problem.film_scale
    if point:
        arrays = {"X": r.X, "Y": r.Y, "P": r.P, "H": r.H, "T_mid": r.T_mid,
                  "T_surface1": r.T_surface1, "T_surface2": r.T_surface2}
        box = (float(r.X[0]), float(r.X[-1]), -float(r.Y[-1]), float(r.Y[-1]))
        grid = Grid(int(r.X.size), int(r.Y.size), None, box, True)

        def builder() -> Any:
            return tehl_point_result(r)
    else:
        arrays = {"X": r.X, "P": r.P, "H": r.H, "Z": r.Z, "T": r.T, "tau": r.tau}
        grid = Grid(int(r.X.size), None, None, (float(r.X[0]), float(r.X[-1])), False)

        def builder() -> Any:
            return tehl_line_result(r)
    return Solution(physics="thermal", contact=scene.kind, outcome=outcome, Hc=float(r.Hc), Hm=float(r.Hm),
                    hc=float(r.Hc) * scale, hm=float(r.Hm) * scale, error=error, fields=frozen_fields(arrays),
                    grid=grid, details=details, raw=done, scene=scene, _result_builder=builder)
