"""One entry point for point and elliptic contacts, shaped like :func:`~ehl_multigrid.line.solve_line`.

>>> sol = solve_point(20, 10, points=129)                     # doctest: +SKIP
>>> round(sol.Hc, 2), sol.success, sol.status_name            # doctest: +SKIP
>>> res = sol.to_result()                                     # kind "ehl_point"
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..model.errors import ConvergenceError, InputError, require_choice, require_range
from ..multigrid.accuracy import (
    CORRECTION_MIN_DECAY,
    DECAY_SAFETY,
    DOMAIN_SAFETY,
    FAR_DOMAIN_SAFETY,
    MESH_SAFETY,
    PROBE_FILM_TOL,
    BoxSeries,
    domain_correction,
    film_change,
    film_tol,
    iteration_error,
    solve_to_accuracy,
)
from ..multigrid.gridchoice import solver_grid
from ..multigrid.options import PointOptions, build_scene_options, scene_solver_table
from ..multigrid.result import EHLResult, ended_relaxation, tightened, tightening
from ..multigrid.rheology import log_viscosity
from ..multigrid.threads import preserved_threads
from .farfield import far_field_on
from .fas import ALTERNATE_BELOW, ALTERNATING_CYCLE, HINT, grid_layout, point_solver, y_ratio
from .postprocess import build_result
from .problem import (
    NARROW_BELOW,
    WIDE_CONTACT,
    PointProblem,
    coarse_intervals,
    default_domain,
    domain_scale,
    min_points,
    problem_from_moes,
    problem_from_scene,
    resolve_domain,
    rigid_length,
)

SOLVERS = ("fas", "newton")
#: A solve of a wider contact (b/a >= ALTERNATE_BELOW) that ends so with the default
#: relaxation is solved again with X and Y lines alternating on every grid (docs/robustness.md,
#: "Point solver defaults").
RETRY_ALTERNATING = ("max_cycles", "stalled", "diverged")
#: Largest grid an accuracy target may refine to: the tribometer scenes at 1-1.93 GPa need 4097
#: points for 0.5 % (docs/robustness.md, "Point solver defaults").
MAX_ACCURACY_POINTS = 4097

#: Barus solves that diverge at alpha_bar >= this get the reason in their message: there the
#: X-line relaxation oscillates row to row at the outlet (docs/robustness.md).
BARUS_STEEP = 30.0

#: A failed solve whose iterate's pressure peaks above this many times the Hertzian maximum
#: says why: a piezoviscous rise that the elastic deformation hardly limits (docs/robustness.md).
PIEZOVISCOUS_PEAK = 3.0
#: ... and only at loads this light (Moes M), where the deformation is small against the film:
#: at high M a peak of that size in a failed iterate is the divergence itself (EHL pressure
#: spikes stay near the Hertzian maximum), not the regime
PIEZOVISCOUS_RIGID_M = 10.0


def piezoviscous_peak_reason(problem: PointProblem, P: np.ndarray | None) -> str:
    """Why a point solve at M <= :data:`PIEZOVISCOUS_RIGID_M` whose pressure peaks above
    :data:`PIEZOVISCOUS_PEAK` times the Hertzian maximum has no meaningful answer (empty when it
    does not): the peak, in Pa, and the viscosity the law gives there."""
    if P is None or problem.M > PIEZOVISCOUS_RIGID_M or not np.isfinite(P).all():
        return ""
    peak = float(P.max())
    if not peak > PIEZOVISCOUS_PEAK:
        return ""
    decades = log_viscosity(peak, problem.rheology())[0] / math.log(10.0)
    law = "Roelands (2.6)" if problem.viscosity == "roelands" else "Barus (2.4)"
    return (f"the iterate's pressure peaks at P = {peak:.3g} ({peak * problem.pmax / 1e9:.3g} GPa), "
            f"{peak:.2g} times the Hertzian maximum, where {law} gives a viscosity 10^{decades:.0f} times "
            f"the inlet's: at M = {problem.M:.3g} and alpha_bar = {problem.alpha_bar:.3g} the load is "
            f"carried by a piezoviscous pressure rise that the elastic deformation hardly limits (the "
            f"piezoviscous-rigid regime), at pressures far beyond those any viscosity law is fitted "
            f"to; this isothermal Newtonian model has no meaningful answer there")


#: Widest box (times the default) an accuracy target may ask for in the thick-film regime
THICK_FILM_BOX_LIMIT = 8.0

#: The answer of a point-contact solve is the package's one EHL result type.
PointSolution = EHLResult


def _finish(sol: EHLResult, scene: Any) -> EHLResult:
    sol.scene = scene
    sol.builder = build_result
    sol.scalars = dict(build_result(sol, scene, fields=False).scalars)
    return sol


#: finest-grid cycles over which a solve that ran out of cycles must have contracted steadily, and
#: the fall over them (twice the policy's stall test), for the relaxation retries to be skipped
#: (:func:`steadily_contracting`)
STEADY_WINDOW = 8
STEADY_FALL = 0.8


def steadily_contracting(sol: EHLResult) -> bool:
    """True when ``sol`` ran out of cycles (``max_cycles``) with its residual and load error
    each falling on every one of its last :data:`STEADY_WINDOW` cycles, to at most
    :data:`STEADY_FALL` of their first value, and no cycle rejected: slow, not unstable. The
    whole-refresh retry answers an iteration that oscillates or diverges (``retry_full_refresh``,
    docs/robustness.md); on a slow one it runs out of cycles again (circular (5, 0), 1025 points
    on eight times the box: the three attempts contract by 0.88-0.91 a cycle, 17 s each)."""
    r = np.asarray(sol.residual_history, dtype=float)[-STEADY_WINDOW:]
    g = np.abs(np.asarray(sol.load_error_history, dtype=float))[-STEADY_WINDOW:]
    if sol.status_name != "max_cycles" or r.size < STEADY_WINDOW or g.size < STEADY_WINDOW:
        return False
    if any("rejected" in a for a in sol.actions):
        return False
    falling = bool(np.all(np.diff(r) < 0.0) and np.all(np.diff(g) < 0.0))
    return falling and r[-1] <= STEADY_FALL * r[0] and g[-1] <= STEADY_FALL * g[0]


def slow_note(sol: EHLResult, retries: list[str]) -> str:
    """The action of the relaxation ``retries`` skipped because ``sol`` was slow, not unstable."""
    r = np.asarray(sol.residual_history, dtype=float)[-STEADY_WINDOW:]
    q = (r[-1] / r[0]) ** (1.0 / (r.size - 1))
    what = f"{retries[0]} was" if len(retries) == 1 else f"neither {' nor '.join(retries)} was"
    return (f"ended max_cycles still contracting steadily (residual x{q:.2f} a cycle over the last "
            f"{r.size}): slow, not unstable, so {what} tried")


def _again(problem: PointProblem, opt: PointOptions, solver: Any, sol: EHLResult,
           callback: Callable[[dict[str, Any]], None] | None, how: str,
           guess: Any = None) -> tuple[Any, EHLResult]:
    """Solve again with ``opt`` (from ``guess``, when given); keep the better of the two
    attempts (converged, else the lower final residual); both attempts count in the work and
    wall time."""
    again = point_solver(problem, opt, guess)
    sol2 = again.solve(callback=callback)
    note = f"ended {sol.status_name} ({sol.message}); solved again with {how}: {sol2.status_name}"
    work, wall = sol.work_units + sol2.work_units, sol.wall_s + sol2.wall_s
    if sol2.success or sol2.residual_history[-1:].min(initial=np.inf) \
            < sol.residual_history[-1:].min(initial=np.inf):
        solver.hierarchy.solver = None
        solver, sol = again, sol2
    else:
        again.hierarchy.solver = None
    sol.work_units, sol.wall_s = work, wall  # every attempt is the cost of the answer
    sol.actions.append(note)
    return solver, sol


def solve_fas(problem: PointProblem, options: PointOptions | None = None,
              callback: Callable[[dict[str, Any]], None] | None = None, scene: Any = None,
              guess: tuple[np.ndarray, np.ndarray, np.ndarray, float] | None = None,
              **kw: Any) -> EHLResult:
    """FAS/FMG solve of one :class:`PointProblem`; keyword arguments override ``options``.

    ``guess = (X, Y, P, H00)``, a converged solution of the same contact on another grid, box
    or cell aspect (``Y`` from 0 up for a half domain), starts the cycles on the finest grid
    from it instead of the FMG (so the result has no FMG films below its finest grid)."""
    opt = PointOptions.build(options, **kw)
    # adapt=False asks for the iteration exactly as configured: no retry either
    retry = opt.alternating is None and opt.adapt and problem.b_over_a >= ALTERNATE_BELOW
    auto_coarse = opt.adapt and opt.n_coarse is None and opt.levels is None
    # the robustness retries (PointOptions.retry_*; docs/robustness.md)
    coarser = opt.retry_coarser_start and auto_coarse
    finer = opt.retry_finer_start and auto_coarse and problem.b_over_a < ALTERNATE_BELOW
    square = opt.retry_square_cells and opt.adapt and opt.y_ratio is None and problem.b_over_a < 1.0
    # a wide contact's coarse grid capped below the rule's (problem.WIDE_COARSE_MAX)
    uncapped = 0
    if opt.retry_uncapped_start and auto_coarse and problem.b_over_a >= WIDE_CONTACT:
        xmin, xmax, _ = resolve_domain(problem, opt.xmin, opt.xmax, opt.ymax, opt.elastic)
        uncapped = uncapped_coarse(problem, xmax - xmin, opt.points)
    first = replace(opt, raise_on_failure=False) if (retry or coarser or finer or square or uncapped) else opt
    with preserved_threads():
        solver = point_solver(problem, first, guess)
        hz0 = solver.hierarchy
        n_coarse = hz0.levels[0].nx - 1
        sol = solver.solve(callback=callback)
        square_ratio = y_ratio(hz0.xmax - hz0.xmin, 2.0 * hz0.ymax, n_coarse, 1.0)
        base = opt  # the options of the later retries: on the cells of the attempt kept
        if square and sol.status_name == "diverged" and square_ratio < hz0.y_ratio:
            solver, sol = _again(problem, replace(opt, y_ratio=square_ratio, raise_on_failure=False),
                                 solver, sol, callback, f"square cells (y_ratio {square_ratio:g} "
                                 f"instead of {hz0.y_ratio:g}; retry_square_cells)", guess)
            base = replace(opt, y_ratio=solver.hierarchy.y_ratio)
        hz1 = solver.hierarchy
        # every grid alternated already (the fine-grid rule, not the policy's switch) and the
        # iteration was merely slow: the retry would add nothing but another slow solve
        alternated = not hz1.alternating and all(lev.alternate for lev in hz1.levels)
        skipped = []
        if retry and sol.status_name in RETRY_ALTERNATING and alternated and steadily_contracting(sol):
            skipped.append("the retry alternating on every grid (every grid alternated already)")
        elif retry and sol.status_name in RETRY_ALTERNATING:
            # X lines alone failed: solve again alternating X and Y lines on every grid from
            # the start (the policy's mid-solve switch comes too late on some grids)
            # (with W cycles unless the options name one: point_cycle)
            solver, sol = _again(problem, replace(base, alternating=True, raise_on_failure=False), solver,
                                 sol, callback, "X and Y lines alternating on every grid", guess)
        full_refresh = (retry and opt.retry_full_refresh and sol.status_name in RETRY_ALTERNATING
                        and opt.local_film_update)
        if full_refresh and steadily_contracting(sol):
            skipped.append("the whole-refresh retry (retry_full_refresh)")
        elif full_refresh:
            # W cycles unless the options name one: with the steady default's F cycles circular
            # Barus (500, 20, theta 0.25) at 1025 points diverges in this retry too
            solver, sol = _again(problem, replace(base, local_film_update=False, raise_on_failure=False,
                                                  cycle=base.cycle or ALTERNATING_CYCLE),
                                 solver, sol, callback, "the film refreshed by whole deformations "
                                 "between the X and Y halves (retry_full_refresh)", guess)
        if skipped:
            sol.actions.append(slow_note(sol, skipped))
        if finer and sol.status_name == "diverged" and 4 * n_coarse <= (opt.points - 1) // 4:
            solver, sol = _again(problem, replace(base, n_coarse=4 * n_coarse, raise_on_failure=False), solver,
                                 sol, callback, f"{4 * n_coarse} coarse intervals instead of {n_coarse} "
                                 "(retry_finer_start)", guess)
        if coarser and sol.status_name == "diverged" and n_coarse >= 32:
            solver, sol = _again(problem, replace(base, n_coarse=n_coarse // 2, raise_on_failure=False), solver,
                                 sol, callback, f"{n_coarse // 2} coarse intervals instead of {n_coarse} "
                                 "(retry_coarser_start)", guess)
        if sol.status_name in UNCAPPED_RETRY_STATUSES and uncapped > n_coarse:
            solver, sol = _again(problem, replace(base, n_coarse=uncapped, raise_on_failure=False), solver,
                                 sol, callback, f"{uncapped} coarse intervals instead of {n_coarse} "
                                 "(retry_uncapped_start)", guess)
        if (retry or coarser or finer or square or uncapped) and not sol.success and opt.raise_on_failure:
            raise ConvergenceError(f"point solver: {sol.message}", sol.report, solver.hint)
    hz = solver.hierarchy
    hz.solver = None  # break the solver <-> hierarchy cycle: the grids are freed with the solver
    fine = hz.levels[-1]
    sol.contact, sol.solver, sol.problem, sol.options = "point", "fas", problem, opt
    # the hierarchy dies with this call: its finest arrays become the result's, not copies
    # (two fine-grid arrays off the peak, 67 MB at 2049^2 full domain)
    sol.X, sol.Y, sol.P, sol.H = fine.X, fine.Y, fine.P, fine.H
    sol.H0, sol.half, sol.levels = hz.H00, opt.half, len(hz.levels)
    sol.extra.update(domain=(hz.xmin, hz.xmax, hz.ymax), y_ratio=hz.y_ratio,
                     square_cells_fallback=bool(square and hz.y_ratio < hz0.y_ratio))
    sol.extra.update(final_omega=sol.settings.omega, final_omega_jd=sol.settings.omega_jd,
                     final_h00_gain=sol.settings.h00_gain, final_cycle=sol.settings.cycle,
                     final_switch=sol.settings.switch)
    if not sol.success and not opt.elastic:
        sol.message += ("; rigid surfaces (elastic = False): the box, the coarsest mesh and the start "
                        "follow the rigid film's inlet length sqrt(2 H) (point.problem.rigid_film); a "
                        "given box or coarse grid that does not resolve it can diverge")
    elif not sol.success:
        need = min_points(problem.M, problem.b_over_a, cap=None)
        if opt.points < need:
            sol.message += (f"; at M = {problem.M:.4g} a grid of {opt.points} points is too coarse "
                            f"for this solver: use points >= {need}")
            if problem.b_over_a < NARROW_BELOW and problem.M >= 1000:
                sol.message += (f" (a contact this narrow, b/a = {problem.b_over_a:.3g}, thins its film "
                                "at the sides |Y| = b into a constriction that needs many cells across b)")
        if sol.status_name == "diverged" and problem.viscosity == "barus" and problem.alpha_bar >= BARUS_STEEP:
            sol.message += (f"; Barus viscosity exp(alpha_bar P) at alpha_bar = {problem.alpha_bar:.3g} varies "
                            f"by e^{problem.alpha_bar:.0f} per unit of P: at the outlet neighbouring rows of "
                            "the grid end up at viscosities many decades apart and the line relaxation "
                            "oscillates from row to row until it blows up. Roelands (2.6), far less steep "
                            "at high pressure, converged on every fit-map case where Barus diverged")
        why = piezoviscous_peak_reason(problem, sol.P)
        if why and sol.status_name in ("diverged", "max_cycles", "stalled"):
            sol.message += "; " + why
        if sol.load_error_history.size and sol.load_error_history[-1] > 1e-2:
            sol.message += ("; the load cannot be balanced: at low M the inlet of this domain is too "
                            "short (extend xmin/ymax), at high M the grid is too coarse (more points)")
    return _finish(sol, scene)


#: why an elliptic rigid point film misses a tight target (docs/robustness.md, "Rigid surfaces")
RIGID_BOX_NOTE = ("rigid surfaces: far upstream the film grows as r^2 and the pressure falls only as "
                  "r^-3, so the load outside the box, and the box error, fall about as 1/box (circular "
                  "(20, 0) without its far-field boundary: Hc +7.5 % from twice the box, +2.6 % more from "
                  "four times); wider boxes are not tried: leave the far-field boundary on "
                  "(far_field, point.farfield) to bound it")


#: statuses of a failed start that the retry from a converged neighbour answers
#: (``PointOptions.retry_from_neighbour``)
NEIGHBOUR_RETRY = ("diverged", "max_cycles", "stalled")


def solve_from_neighbour(problem: PointProblem, options: PointOptions, failed: EHLResult,
                         neighbour: EHLResult, callback: Callable[[dict[str, Any]], None] | None = None,
                         scene: Any = None) -> EHLResult:
    """Solve again with ``options`` from the converged solution ``neighbour`` (same contact,
    another grid or box), on its cell aspect; the better of the two attempts is returned (the
    new one when it converges), carrying the work and wall time of both and a note."""
    o = replace(options, y_ratio=neighbour.extra.get("y_ratio", options.y_ratio))
    again = solve_fas(problem, o, callback=callback, scene=scene,
                      guess=(neighbour.X, neighbour.Y, neighbour.P, float(neighbour.H0)))
    n_nb = neighbour.X.shape[0]
    note = (f"ended {failed.status_name} ({failed.message.split(';')[0]}); solved again from the "
            f"converged {n_nb}-point solution of the sequence (retry_from_neighbour): "
            f"{again.status_name}")
    keep = again if again.success else failed
    keep.work_units = failed.work_units + again.work_units
    keep.wall_s = failed.wall_s + again.wall_s
    keep.actions.append(note)
    return keep


#: film and load tolerance of the domain probes of a far-field contact, as a share of the
#: solve's film stop (docs/accuracy.md, "Far-field boundary")
FAR_PROBE_FRACTION = 0.2

#: the probes' residual tolerance, whatever the solve's: they stop on their films, so a
#: tolerance step of the solve reuses them (docs/accuracy.md, "Domain error")
PROBE_RESIDUAL_TOL = 1e-4


def learned_coarse(problem: PointProblem, cache: dict[PointOptions, EHLResult] | None, points: int,
                   length: float) -> int | None:
    """Coarse intervals of a probe on a box of X ``length``: the rule's
    (:func:`~.problem.coarse_intervals`) scaled by the smallest share of it an earlier probe of
    the sequence converged with after its coarse start was halved (``retry_coarser_start``);
    None (the rule) when none was. A probe that needed the coarser start on one box needs it on
    the wider boxes too, and its failed first attempt costs 7-8 times the solve (the 6205 inner
    race at 0.5 %: 402 WU against 50 for the 1025-point probe on twice the box)."""
    share = 1.0
    for o, r in (cache or {}).items():
        if r.success and any("retry_coarser_start" in a for a in r.actions) and o.n_coarse is None:
            rule = coarse_intervals(problem.M, o.xmax - o.xmin, o.points, domain_scale(problem),
                                    rigid_length(problem), problem.b_over_a)
            used = (int(o.points) - 1) // 2 ** (r.levels - 1)
            share = min(share, used / rule)
    if share >= 1.0:
        return None
    rule = coarse_intervals(problem.M, length, points, domain_scale(problem), rigid_length(problem),
                            problem.b_over_a)
    return max(16, int(rule * share))


def looser_probe(cache: dict[PointOptions, EHLResult], options: PointOptions) -> EHLResult | None:
    """A converged probe of ``cache`` on the same grid and box as ``options`` stopped at a
    looser film or load tolerance (a domain probe before the box series needs it tighter):
    the tighter probe continues its cycles from it instead of solving again from the coarsest
    grid. None when there is none."""
    return _looser(cache, options, True, ("n_coarse",))


def _looser(cache: dict[PointOptions, EHLResult], options: PointOptions, success: bool,
            free: tuple[str, ...] = ()) -> EHLResult | None:
    """A probe of ``cache`` with ``success`` equal to the given one whose options equal
    ``options`` but for the film and load tolerances (looser or equal) and the fields ``free``."""
    def same(o: PointOptions) -> dict[str, Any]:
        return {k: v for k, v in vars(o).items() if k not in ("film_tol", "tol_load", *free)}

    key = same(options)
    for o, r in cache.items():
        if (bool(r.success) == success and same(o) == key
                and (o.film_tol or 0.0) >= (options.film_tol or 0.0) and o.tol_load >= options.tol_load):
            return r
    return None


def failed_looser(cache: dict[PointOptions, EHLResult], options: PointOptions) -> EHLResult | None:
    """A probe of ``cache`` that did not converge on the same grid, box and coarse start as
    ``options`` at a looser (or equal) film and load tolerance: the tighter probe would run the
    same cycles from the same start and fail too (circular (5, 0) at 1 %: a 1025-point probe
    on eight times the box ran out of cycles twice, 53 s each, before and after the solve's
    tolerance step). None when there is none."""
    return _looser(cache, options, False)


#: the ends of a wide contact's solve from its capped coarse grid that
#: :func:`uncapped_coarse` retries (retry_uncapped_start, docs/robustness.md)
UNCAPPED_RETRY_STATUSES = ("residual_floor", "max_cycles")


def uncapped_coarse(problem: PointProblem, length: float, points: int) -> int:
    """Coarse intervals the rule (:func:`~.problem.coarse_intervals`) gives a box of X ``length``
    without the wide-contact cap: (1000, 0, theta 0.1) on twice the default box
    (1025 points, film-stopped at 2e-4) ends at its residual floor from the capped 64 intervals
    with Hc 2 % off, its films wandering 1.8 % over the last cycles, and converges from 128
    in 7 cycles."""
    return coarse_intervals(problem.M, length, points, domain_scale(problem), rigid_length(problem))


#: a probe that runs out of cycles with at least this many coarse intervals (the rule's) is
#: solved again from half as many (:func:`coarser_probe`; from 64 to 32 the (5, 0) probe failed)
PROBE_COARSER_FROM = 128


def coarser_probe(problem: PointProblem, options: PointOptions, res: EHLResult) -> EHLResult:
    """``res``, or the probe solved again from half its coarse intervals when it ran out of
    cycles on the rule's coarse grid: on a wide box the film drifts in a mode the coarsest grid
    only relaxes (circular (5, 0), 1025 points on eight times the box: 1136 work units without
    converging from 128 intervals, 146 from 64). Both attempts count in the work."""
    if res.success or res.status_name != "max_cycles" or options.n_coarse is not None:
        return res
    n_coarse = (int(options.points) - 1) // 2 ** (res.levels - 1)
    if n_coarse < PROBE_COARSER_FROM:
        return res
    if any("(retry_uncapped_start)" in a for a in res.actions):
        x0, x1, _ = resolve_domain(problem, options.xmin, options.xmax, options.ymax, options.elastic)
        capped = coarse_intervals(problem.M, x1 - x0, options.points, domain_scale(problem),
                                  rigid_length(problem), problem.b_over_a)
        if n_coarse // 2 == capped:
            return res  # half of the uncapped start is the capped one, which this solve tried first
    again = solve_fas(problem, replace(options, n_coarse=n_coarse // 2))
    kept, other = (again, res) if again.success else (res, again)
    kept.work_units += other.work_units
    kept.wall_s += other.wall_s
    kept.actions.append(f"probe ended max_cycles on {n_coarse} coarse intervals; solved again "
                        f"from {n_coarse // 2}: {again.status_name}")
    return kept


def point_domain_change(problem: PointProblem, options: PointOptions, sol: EHLResult,
                        cache: dict[PointOptions, EHLResult] | None = None,
                        boxes: tuple[float, ...] = (1.0, 2.0), tight: float | None = None, coarser: int = 0,
                        used: list[EHLResult] | None = None, hm_sub: bool = False,
                        look: float | None = None, looks: dict[Any, tuple[float, float]] | None = None
                        ) -> tuple[float, float] | list[tuple[float, float]] | None:
    """Relative change of (Hc, Hm) when the box is doubled in X and Y at equal mesh size,
    measured by two converged solves on a coarse grid of the solve (two grids below the
    finest, at least the solver's minimum grid; finer grids up to the solve's own when that does
    not converge); None when no pair converges.

    ``boxes`` (scales of the solve's box, each twice the one before) with more than two entries
    returns the list of the successive changes, each relative to the smaller box; ``tight``
    (a film and load tolerance) replaces the probes' own film tolerance; a series whose widest
    probe has more intervals than the solve is not run. ``coarser`` halves the
    probe mesh that many times (no finer mesh is then tried when it fails); ``used`` receives
    the probe solves; ``hm_sub`` measures Hm by its sub-grid minimum (:func:`film_change`).

    ``cache`` (options -> result) keeps the probe solves of one refinement sequence: the wide
    solve of a box is the narrow solve of the next box's probe, on the same mesh.

    ``look`` (the target accuracy) lets a pair on a probe mesh of at least :data:`LOOK_FROM`
    points per default box first look on the mesh twice as coarse (for a contact narrower than
    long, b/a < 0.75, only where that mesh holds the solver's minimum grid: (100, 10, theta 10)
    on 1025 points, b/a 0.22, its 257-point look failed to converge, 2.4 s for nothing; wider
    contacts' looks converged on half it, the 6205's on 257 points): where that change, times
    :data:`LOOK_MARGIN`, leaves a domain part of at most :data:`LOOK_FRACTION` of the target,
    it is returned times the margin and the probe mesh is not solved. ``looks`` keeps the
    looks taken in one refinement sequence, so that the probe after a solve answers as the
    first box decision did on the same mesh and box."""
    top = sol.levels - 1
    n_f = sol.X.shape[0]
    xmin, xmax, ymax = sol.extra["domain"]
    # the probe's mesh is no coarser than the solver's minimum grid on the default box; for the
    # plain probes (the fixed factor's change) that of a circular contact: a narrow contact's
    # extra cells across a do not make its first box change more accurate ((50, 10, theta 3):
    # d2 of Hc 0.265, 0.251, 0.247 % and of Hm 0.377, 0.326, 0.408 % on 129, 257, 513 points per
    # default box; validation/accuracy/probe_mesh.py) and cost 3-4 times as much. The tight
    # series of a box correction keeps the contact's own: its coarse-mesh pair, one mesh lower,
    # would fall where Hm's second change is off ((20, 10, theta 4): 0.027 % on 65 points per
    # default box against 0.17 % on 129-257)
    d0 = default_domain(problem, options.elastic)
    far = far_field_on(options.far_field)
    scale = 2 ** max(0, round(math.log2((xmax - xmin) / (d0[1] - d0[0]))))
    n_min = (min_points(problem.M, 1.0 if tight is None else problem.b_over_a) - 1) * scale + 1
    if domain_scale(problem) > 1.0:
        # thick film: the film varies over the inlet length s, not a; a quarter of s per cell
        s = rigid_length(problem)
        n_min = min_points(problem.M, problem.b_over_a)
        while (xmax - xmin) / (n_min - 1) > 0.25 * s:
            n_min = 2 * (n_min - 1) + 1
    n_p = min(max((n_f - 1) // 4 + 1, n_min), n_f) if top >= 2 else n_f
    for _ in range(coarser):
        n_p = (n_p - 1) // 2 + 1
    key = (n_p, xmin, xmax, ymax, sol.extra.get("y_ratio"), hm_sub)
    if looks is not None and key in looks:
        seen = looks[key]
    elif (look is not None and len(boxes) == 2 and not coarser and tight is None
            and domain_scale(problem) <= 1.0 and (n_p - 1) // scale + 1 >= LOOK_FROM
            and (problem.b_over_a >= 0.75 or (n_p - 1) // 2 // scale + 1 >= min_points(problem.M, problem.b_over_a))
            and resolved_on(sol, (n_p - 1) // 2 + 1)):
        seen = point_domain_change(problem, options, sol, cache, boxes, coarser=1, used=used, hm_sub=hm_sub)
        if seen is not None and not (domain_safety(options) * LOOK_MARGIN * max(abs(seen[0]), abs(seen[1]))
                                     <= LOOK_FRACTION * look):
            seen = None
        if looks is not None and seen is not None:
            looks[key] = seen
    else:
        seen = None
    if seen is not None:
        sol.extra["domain_note"] = (f"box change measured on {(n_p - 1) // 2 + 1} points per box "
                                    f"(the probe mesh halved), times {LOOK_MARGIN:g}")
        return LOOK_MARGIN * seen[0], LOOK_MARGIN * seen[1]
    while True:
        if len(boxes) > 2 and (n_p - 1) * boxes[-1] > n_f - 1:
            # the widest box would need more points than the solve itself: such a probe costs more
            # than the refinement it could save (circular (20, 10) at 5 %: a 513-point probe, 16 s,
            # for a 0.3 s solve on 129 points)
            return None

        def solve(n: int, f: float) -> EHLResult:
            # the probes need the film to well below the domain change, not the load to 1e-5:
            # they stop on the film (PROBE_FILM_TOL), as the line's. Stopped on the residual
            # (1e-4) instead, the series-C disc contact (M 6114, L 4.95; 513/1025 points) read
            # its probes' iteration errors as a box effect of Hc -2.6 %, Hm +14.7 % (film-stopped:
            # +1.6e-5, -8.6e-4; at tol 1e-6: +8e-6, -7.6e-4), circular (1000, 10) Hc +0.29 %,
            # Hm -1.2 % (film-stopped: +1.3e-4, +7.5e-5). No tighter than the solve's own film
            # stop (a twentieth of its target): thick films converge slowly on the wide boxes,
            # (1, 0) at 2 %: 1025 points on a 400 a box reached max_cycles at 1e-4 (93 s)
            if tight is not None:
                ftol = ltol = tight
            elif far and options.film_tol:
                # the far field leaves box changes of a few 1e-4: the probes' iteration errors
                # (about 2.5x their film stop) would read as one
                ftol = ltol = FAR_PROBE_FRACTION * options.film_tol
            else:
                ftol, ltol = max(PROBE_FILM_TOL, options.film_tol or 0.0), max(options.tol_load, 1e-4)
            # the films stop the probes; one residual tolerance for every step of the sequence
            # lets a tolerance step of the solve reuse the probes of the step before
            points = int(round((n - 1) * f)) + 1
            o = replace(options, points=points, levels=None,
                        n_coarse=learned_coarse(problem, cache, points, f * (xmax - xmin)),
                        xmin=f * xmin, xmax=f * xmax, ymax=f * ymax, y_ratio=sol.extra["y_ratio"],
                        raise_on_failure=False, tol=PROBE_RESIDUAL_TOL,
                        tol_load=ltol, film_tol=ftol)
            if cache is None:
                r = coarser_probe(problem, o, solve_fas(problem, o))
            else:
                if o not in cache:
                    start = looser_probe(cache, o)
                    failed = None if start is not None else failed_looser(cache, o)
                    if failed is not None:
                        cache[o] = failed
                    else:
                        cache[o] = solve_fas(problem, o, guess=None if start is None else
                                             (start.X, start.Y, start.P, float(start.H0)))
                        if start is not None and not cache[o].success:
                            cache[o] = solve_fas(problem, o)
                        cache[o] = coarser_probe(problem, o, cache[o])
                r = cache[o]
            if used is not None:
                used.append(r)
            return r

        changes = []
        for f in boxes[:-1]:  # a pair that fails ends the series: no wider box is solved for it
            # a probe at its residual floor counts, its jitter added to the change (not the
            # box-series probes: a jitter there would read as a box change that does not decay)
            change = film_change(lambda n=n_p, f=f: solve(n, f), lambda n=n_p, f=f: solve(n, 2.0 * f),
                                 floor_ok=tight is None, hm_sub=hm_sub)
            if change is None:
                break
            changes.append(change)
        if len(changes) == len(boxes) - 1:
            return changes[0] if len(boxes) == 2 else changes
        if n_p >= n_f or coarser:
            return None
        n_p = 2 * (n_p - 1) + 1  # one grid finer when the coarse probe does not converge


#: probe meshes (points per default box) from which a domain probe first looks on the mesh twice
#: as coarse (:func:`point_domain_change`); below, the look would save under half a second
LOOK_FROM = 257
#: the look's change counts where its domain part (times :data:`LOOK_MARGIN`) is at most this
#: fraction of the target: the coarse mesh's error then matters little beside the other parts
LOOK_FRACTION = 0.25
#: factor on the look's change: the mesh twice as coarse read the box change 0.68-1.0 times the
#: probe mesh's where it read less (docs/accuracy.md, "What the estimator costs")
LOOK_MARGIN = 2.0


#: a look's mesh must hold the solve's FMG film within this fraction of its finest film
#: (:func:`resolved_on`; looks on coarser-resolved meshes stopped at residual floors:
#: docs/accuracy.md, "What the estimator costs")
LOOK_RESOLVED = 0.05


def resolved_on(sol: Any, points: int) -> bool:
    """Does the solve's FMG film on its grid of ``points`` lie within :data:`LOOK_RESOLVED` of
    its finest film (Hc)? True where that is not known: a solve not made yet, no FMG film on
    that grid."""
    films = {int(d["points"]): d["Hc"] for d in getattr(sol, "fmg", None) or ()}
    top = getattr(sol, "scalars", {}).get("Hc_venner")
    hc = films.get(points)
    if hc is None or top is None or not top:
        return True
    return abs(hc / top - 1.0) <= LOOK_RESOLVED


#: the default box is skipped when its domain part is predicted above this many times the
#: target; below, a box correction on the default box often meets ((100, 20) at 1 %: 1.56 times,
#: met on 513 points x1 in 7.9 s, against 16.4 s from 1025 points on x2)
START_WIDE = 2.0


@dataclass(frozen=True)
class PlannedSolve:
    """A solve not made yet, as :func:`point_domain_change` reads one: its grid levels, X
    nodes (their count), box and cell aspect (``extra``)."""

    levels: int
    X: np.ndarray
    extra: dict[str, Any] = field(default_factory=dict)


def planned_solve(problem: PointProblem, options: PointOptions) -> PlannedSolve:
    """The grid layout a :func:`solve_fas` with ``options`` will have (:func:`~.fas.grid_layout`)."""
    domain = resolve_domain(problem, options.xmin, options.xmax, options.ymax, options.elastic)
    levels, ratio = grid_layout(problem, options, domain)
    return PlannedSolve(levels, np.empty(int(options.points)), {"domain": domain, "y_ratio": ratio})


def domain_safety(options: PointOptions) -> float:
    """Factor on a box probe's film change that gives the domain part of the estimate:
    :data:`~ehl_multigrid.multigrid.accuracy.FAR_DOMAIN_SAFETY` with the far-field boundary,
    :data:`~ehl_multigrid.multigrid.accuracy.DOMAIN_SAFETY` with ``P = 0``."""
    return FAR_DOMAIN_SAFETY if far_field_on(options.far_field) else DOMAIN_SAFETY


def same_problem_probe(problem: PointProblem, options: PointOptions,
                       probes: dict[PointOptions, EHLResult]) -> EHLResult | None:
    """A converged domain probe of the discrete problem ``options`` ask for (same grid, box and
    cells; looser tolerances): a solve of the sequence continues it by a tolerance step instead
    of a new FMG solve (the 6205 inner race: its 513-point probe of the default box is the
    repair's 513-point grid; docs/accuracy.md, "What the estimator costs")."""
    want = resolve_domain(problem, options.xmin, options.xmax, options.ymax, options.elastic)
    layout = ("tol", "tol_load", "film_tol", "n_coarse", "levels", "xmin", "xmax", "ymax", "y_ratio",
              "raise_on_failure")
    for po, pr in probes.items():
        if not (pr.success and tuple(pr.extra.get("domain", ())) == want and options.film_tol is not None
                and po.film_tol is not None and options.film_tol < po.film_tol):
            continue
        # every option but the tolerances and the grid layout equal: the same discrete problem
        if replace(po, **{k: getattr(options, k) for k in layout}) == options:
            return pr
    return None


def start_box(problem: PointProblem, options: PointOptions, accuracy: float,
              cache: dict[PointOptions, EHLResult],
              looks: dict[Any, tuple[float, float]] | None = None) -> tuple[float, float] | None:
    """The box change (Hc, Hm) the domain probes of the planned first solve (``options``, on
    the default box) measure, when it says that box cannot meet ``accuracy``: its domain part
    (:func:`domain_safety` times the larger change) exceeds
    :data:`START_WIDE` times the target, so the controller would refine to twice the box at
    the same mesh after that solve. None otherwise: also when the probes fail, and for a
    contact whose box change does not decay fast (:func:`fast_box_decay`), which meets its
    target sooner from the default box's own estimate ((20, 0) at 0.5 %: 14 s from 257 points
    on the default box, 31 s from 513 on twice it). The probes go to ``cache`` and serve the
    later estimates."""
    if not fast_box_decay(problem):
        return None
    change = point_domain_change(problem, options, planned_solve(problem, options), cache, look=accuracy,
                                 looks=looks)
    safety = domain_safety(options)
    if change is None or not safety * max(abs(change[0]), abs(change[1])) > START_WIDE * accuracy:
        return None
    return change


#: film and load tolerance of the box-series probes (:func:`point_box_series`)
SERIES_FILM_TOL = 1e-4


def decays_below(problem: PointProblem, options: PointOptions, sol: EHLResult,
                 cache: dict[PointOptions, EHLResult] | None = None) -> bool:
    """Whether the box change decays fast enough below the solve's box for a correction
    (:data:`~ehl_multigrid.multigrid.accuracy.CORRECTION_MIN_DECAY`, same sign), judged on the
    domain probes at their own tolerance: the pair around the solve's box is its domain probe,
    the pair below it usually the probe of the solve before (both cached), so that a series
    that cannot correct is not solved ((20, 0): about 2 per doubling)."""
    pre = point_domain_change(problem, options, sol, cache, boxes=(0.5, 1.0, 2.0))
    if pre is None:
        return False
    (bc, bm), (dc, dm) = pre
    return all(d != 0.0 and b / d >= CORRECTION_MIN_DECAY for b, d in ((bc, dc), (bm, dm)))


#: solves of at least this many points along X measure the box series' second change on the
#: coarse mesh where its first change agrees with the probe mesh's (:data:`COARSE_D4_AGREEMENT`;
#: docs/accuracy.md, "Box correction")
COARSE_D4_FROM = 2049
COARSE_D4_AGREEMENT = 0.25


def point_box_series(problem: PointProblem, options: PointOptions, sol: EHLResult,
                     cache: dict[PointOptions, EHLResult] | None = None,
                     left: tuple[float, float] | None = None) -> BoxSeries | None:
    """The box series of a box correction (:func:`~ehl_multigrid.multigrid.accuracy.domain_correction`)
    on the probe mesh of :func:`point_domain_change` (film-stopped probes): the change of (Hc,
    Hm) from the solve's box to twice it and, where the solve's box is at least twice the
    default and the change decays fast enough below it (:func:`decays_below`), the change one
    box lower (half the solve's box to it); else the change from twice to four times the box
    (a box below the default would cut the Hertz contact). Also the first change again on a
    mesh twice as coarse, and the probes' iteration errors. None when the series on the probe
    mesh fails. One box lower costs an eighth of one box further: circular (20, 10) at 0.5 % on
    1025 points and twice the box, 0.1 s against 5.2 s. On solves of :data:`COARSE_D4_FROM`
    points and more the change beyond twice the box is measured on the coarse mesh and scaled
    by the ratio of the first change on the two meshes (the 6205 inner race on 2049 points:
    corrected films within 0.012 % of the probe mesh's series), where that first change agrees
    within :data:`COARSE_D4_AGREEMENT` on both meshes.

    ``left`` (per film, Hc and Hm: the part of the target the grid and iteration parts leave)
    skips the series, returning None, where the mesh dependence of the first change alone
    (the part of the correction's error that two cheap pairs measure, a lower bound of what it
    leaves) exceeds it for either film: the wider probes would be solved for a correction that
    cannot meet the target (circular (100, 10) at 0.5 % on 513 points: a 513-point probe on
    four times the box, 1.6 s). ``sol.extra["box_series_skipped"]`` then says so."""
    xmin, xmax, _ = sol.extra["domain"]
    d0 = default_domain(problem, options.elastic)
    coarse: list[tuple[float, float] | None] = []
    # Hm's box change measured by the nodal or the sub-grid minimum film, whichever moves less
    # from the coarse mesh to the probe mesh: either jumps on coarse meshes where the other does
    # not (first change on 65 and 129 points per default box, nodal / sub-grid: circular
    # (100, 10) 0.326 / 0.326 % and 0.186 / 0.331 %, converged 0.34 %; (20, 0) 0.43 / 0.03 %
    # and 0.47 / 0.74 %, converged 0.56 %); both tend to the same change
    pairs = {sub: (point_domain_change(problem, options, sol, cache, tight=SERIES_FILM_TOL, hm_sub=sub),
                   point_domain_change(problem, options, sol, cache, coarser=1, tight=SERIES_FILM_TOL,
                                       hm_sub=sub)) for sub in (False, True)}
    known = None not in pairs[True] + pairs[False]
    hm_sub = known and abs(pairs[True][0][1] - pairs[True][1][1]) < abs(pairs[False][0][1] - pairs[False][1][1])
    sol.extra["box_series_hm"] = "sub-grid" if hm_sub else "nodal"
    if left is not None:
        fine, rough = pairs[hm_sub]
        if fine is not None and rough is not None:
            least = [DECAY_SAFETY * MESH_SAFETY * abs(f - r) for f, r in zip(fine, rough, strict=True)]
            if any(a > b for a, b in zip(least, left, strict=True)):
                sol.extra["box_series_skipped"] = (
                    f"box correction not measured: the mesh dependence of the box change alone "
                    f"(Hc {least[0]:.2%}, Hm {least[1]:.2%}) leaves more than the target allows "
                    f"after the grid and iteration parts (Hc {left[0]:.2%}, Hm {left[1]:.2%})")
                return None

    def series(boxes: tuple[float, float, float]) -> BoxSeries | None:
        used: list[EHLResult] = []
        fine, rough = pairs[hm_sub]
        changes = None
        if (boxes[0] >= 1.0 and sol.X.shape[0] >= COARSE_D4_FROM and fine is not None and rough is not None
                and all(d != 0.0 and abs(c - d) <= COARSE_D4_AGREEMENT * abs(d) for c, d in zip(rough, fine, strict=True))):
            # beyond the box: the second change on the coarse mesh, scaled by the first change's
            # ratio of the two meshes (its widest probe has half the points of the probe mesh's,
            # which is as large as the solve: the 6205 inner race on 2049 points, 15.5 s)
            low = point_domain_change(problem, options, sol, cache, boxes=boxes, coarser=1, used=used,
                                      tight=SERIES_FILM_TOL, hm_sub=hm_sub)
            point_domain_change(problem, options, sol, cache, used=used, tight=SERIES_FILM_TOL, hm_sub=hm_sub)
            if low is not None:
                changes = [fine, tuple(d4 * d2 / c2 for d4, d2, c2 in zip(low[1], fine, low[0], strict=True))]
        if changes is None:  # on the probe mesh, also where the coarse mesh's series failed
            changes = point_domain_change(problem, options, sol, cache, boxes=boxes, used=used,
                                          tight=SERIES_FILM_TOL, hm_sub=hm_sub)
        if changes is None:
            return None
        if not coarse:  # the mesh dependence, once a series exists to correct with
            coarse.append(pairs[hm_sub][1])
        noise = [0.0, 0.0]
        # the solves of the last (converged) series: its pairs, a middle box shared
        for r in {id(r): r for r in used[-6:]}.values():
            fin = [h for h in r.history if h.level == r.levels - 1]
            for i, k in enumerate(("Hc", "Hm")):
                films = [getattr(h, k) for h in fin]
                e = iteration_error(films) / abs(films[-1]) if len(films) >= 2 and films[-1] else math.inf
                noise[i] += e  # each film enters the correction about once
        if boxes[0] < 1.0:
            return BoxSeries(changes[1], None, coarse[0], (noise[0], noise[1]), below=changes[0])
        return BoxSeries(changes[0], changes[1], coarse[0], (noise[0], noise[1]))

    if (xmax - xmin) >= 2.0 * (d0[1] - d0[0]) * (1.0 - 1e-9) and decays_below(problem, options, sol, cache):
        low = series((0.5, 1.0, 2.0))
        if low is None or low.d2_coarse is None or all(
                domain_correction(low.d2[i], None, low.d2_coarse[i], low.noise[i], low.below[i]) is not None
                for i in (0, 1)):
            return low
        # the decay below the box is too slow for a correction (thick films, L = 0: about 2
        # per doubling): measured beyond the box, where it is faster
    return series((1.0, 2.0, 4.0))


def fast_box_decay(problem: PointProblem) -> bool:
    """Whether the box change of this contact is expected to fall by at least 3 per doubling,
    enough for a box correction (:func:`point_box_series`): piezoviscous (L >= 5), M >= 10 and
    no thick-film box. Measured on the probe mesh (129 points per default box, boxes 1x, 2x,
    4x; Hc and Hm): (10, 5) 13 and 5.3, (20, 5) 5.8 and 3.4, (50, 5) 6.2 and 3.2, (20, 10) 7.3
    and 5.8; below: (20, 0) 2.5 and 1.7, (20, 2) 3.9 and 2.0, (5, 5) 3.1 and 1.4."""
    return problem.L >= 5.0 and problem.M >= 10.0 and domain_scale(problem) <= 1.0


def thick_film_reason(problem: PointProblem, res: EHLResult, accuracy: float) -> str:
    """Why a thick-film (low M) point contact misses its target when the box error dominates:
    the physics, the inlet predicted to meet the target and what to do instead."""
    b = res.error.budget
    dom = max(b["domain"].values())
    s = rigid_length(problem)
    if math.isnan(dom):
        # the box probes did not converge: the physics without the inlet it would take
        return (f"at M = {problem.M:.3g} the film is thick against the elastic deformation (rigid-"
                f"isoviscous side): the pressure spreads over the inlet length s = (2H)^0.5 = {s:.3g} a "
                f"and the fully flooded film still grows with the inlet, so the box error matters "
                f"here, and the solves on boxes twice and four times as wide that measure it did not "
                f"converge. A contact this lightly loaded is usually limited by its oil supply: give "
                f"the meniscus position as xmin and read the result as the film for that supply")
    if not dom > 0.5 * accuracy:
        return ""
    inlet = -res.extra["domain"][0]
    # half of the target left to the box, the rest to the grid
    need = f"about {inlet * dom / (0.5 * accuracy):.0f} a"
    return (f"at M = {problem.M:.3g} the film is thick against the elastic deformation (rigid-"
            f"isoviscous side): the pressure spreads over the inlet length s = (2H)^0.5 = {s:.3g} a and "
            f"the fully flooded film still grows with the inlet, the box error falling only about as "
            f"1/inlet length; meeting {accuracy:g} needs an inlet of {need} (this box: {inlet:.3g} a). "
            f"A contact this lightly loaded is usually limited by its oil supply: give the meniscus "
            f"position as xmin and read the result as the film for that supply")


def solve_point(
    M: float | None = None, L: float | None = None, *, theta: float = 1.0, scene: Any = None,
    viscosity: str | None = None, density: str | None = None,
    alpha: float | None = None, eta0: float | None = None, p0: float | None = None,
    solver: str = "fas", rigid: bool = False,
    callback: Callable[[dict[str, Any]], None] | None = None,
    options: PointOptions | None = None, accuracy: float | None = None, estimate: bool = True,
    max_points: int = MAX_ACCURACY_POINTS, progress: Callable[[str], None] | None = None,
    time_budget: float | None = None, **kw: Any,
) -> EHLResult:
    """Solve the steady isothermal EHL point or elliptic contact (Venner's dimensionless
    Reynolds, film and load equations; Roelands (2.6) and Dowson-Higginson (2.7) by default).

    Give either Moes ``M, L`` and ``theta = Rx/Ry`` (oil data ``alpha``, ``eta0``, ``p0``
    default to :data:`~ehl_multigrid.model.constants.MOES_ONLY_DEFAULTS`) or a point/elliptic
    ``scene``, whose ``[solver.ehl]`` table (viscosity, density and any option) applies below
    the explicit arguments (defaults: Roelands, Dowson-Higginson). ``solver`` is ``"fas"`` (FAS/FMG multigrid,
    :class:`~ehl_multigrid.multigrid.options.PointOptions`) or ``"newton"`` (the Newton
    semi-system path with pyamg, :class:`~ehl_multigrid.point.newton.NewtonOptions`);
    ``rigid=True`` switches the elastic deformation off (FAS only). Remaining keyword
    arguments are options of the chosen solver. The FAS solver uses the symmetric half
    domain (Y >= 0) unless ``half`` is given (by keyword, the scene's table or ``options``):
    smooth contacts are symmetric in Y, and the films equal the full domain's to 1e-8.

    ``accuracy`` (relative, e.g. 0.005) asks for Hc and Hm within that error: the grid is
    chosen from the measured grid-error constants (at least :func:`min_points`) and refined
    (one more FMG grid, a box twice as wide, tighter tolerances) until the estimated error
    meets it or ``max_points`` is reached; an explicit ``points`` or box is kept and only
    judged. Every FAS result carries its estimated errors (``Hc_error``, ``Hm_error``,
    ``error.budget``: grid, domain, algebraic) unless ``estimate=False``; with an accuracy,
    ``success`` also requires the estimate to meet it (status ``"inaccurate"`` otherwise).
    ``progress(text)`` receives one line per solve of that sequence. ``time_budget`` (seconds)
    bounds it: no refinement is started that is predicted to overrun it (the cost grows with
    the number of unknowns: 4x per finer grid), and the most accurate answer so far comes back
    (``"inaccurate"`` when it misses the target). Measured: circular (5000, 0) at 2 % runs
    1025 -> 2049 -> 4097 points, a tolerance step and the box-decay probes, about 10 minutes on
    one thread.

    Returns an :class:`~ehl_multigrid.multigrid.result.EHLResult`.
    """
    require_choice("solver", solver, SOLVERS)
    model, table = scene_solver_table(scene, "point") if scene is not None else ({}, {})
    viscosity = viscosity or model.get("viscosity", "roelands")
    density = density or model.get("density", "dowson-higginson")
    if scene is not None:
        if M is not None or L is not None:
            raise InputError("give either a scene or M and L, not both")
        pb = problem_from_scene(scene, viscosity, density)
    else:
        if M is None or L is None:
            raise InputError("solve_point needs M and L (Moes groups) or a scene")
        pb = problem_from_moes(M, L, theta, viscosity, density, alpha, eta0, p0)
    if solver == "fas":
        if rigid:
            kw["elastic"] = False
        opts = build_scene_options(PointOptions, options, table, kw)
        if "half" not in kw and "half" not in table and options is None:
            # smooth contacts are symmetric in Y: the half domain gives the same films (to 1e-8)
            # in about half the time (half=False asks for the full domain)
            opts = replace(opts, half=True)
        if not estimate:
            return solve_fas(pb, opts, callback=callback, scene=scene)
        if accuracy is not None:
            require_range("accuracy", accuracy, 1e-5, 0.5, "- (relative error)")
        require_range("max_points", max_points, 65, 65537, "points")
        if time_budget is not None:
            require_range("time_budget", time_budget, 0.0, math.inf, "s")
        explicit = "points" in kw or "points" in table or (options is not None and accuracy is None)
        fixed_box = any(getattr(opts, k) is not None for k in ("xmin", "xmax", "ymax"))
        points = opts.points
        if accuracy is not None and not explicit:
            # within the budget, but never below the smallest grid the solver converges on
            floor = min_points(pb.M, pb.b_over_a)
            points = min(solver_grid("point", pb.M, accuracy, floor=floor).points, max(max_points, floor))
        base = resolve_domain(pb, opts.xmin, opts.xmax, opts.ymax, opts.elastic)
        # the last converged solve of the sequence (and of each grid and box: a tolerance step
        # continues it), and the cell aspect every later solve keeps
        # once one fell back to square cells (the same discrete problem on each grid for the
        # Richardson estimate, and no stretched attempt that fails first)
        seq: dict[str, Any] = {"ok": None, "y_ratio": None, "grids": {}}

        def solve(n: int, box: float, tol_factor: float) -> EHLResult:
            dom = {} if box == 1.0 else dict(xmin=box * base[0], xmax=box * base[1], ymax=box * base[2])
            o = replace(opts, points=n, tol=opts.tol * tol_factor, tol_load=opts.tol_load * tol_factor,
                        raise_on_failure=False, film_tol=film_tol(opts, accuracy, tol_factor), **dom)
            if seq["y_ratio"] is not None:
                o = replace(o, y_ratio=seq["y_ratio"])
            prev = seq["grids"].get((n, box))
            probe_start = prev is None and (prev := same_problem_probe(pb, o, probes)) is not None
            r = None
            # a solve on other cells than the sequence's (before its fall-back to square cells)
            # is another discrete problem: no step continues it
            if prev is not None and o.y_ratio in (None, prev.extra["y_ratio"]) and (
                    tightening(prev, o) or probe_start):
                # a tolerance step: the cycles go on from the converged solve of this grid
                # on the cells and coarse grid of that solve (a retry may have changed them)
                # with the relaxation it ended with (the policy may have damped it)
                # (a domain probe's relaxation stays the solve's own: its retries may have moved
                # h00_gain outside the options' range, a thick film's box of a hundred a)
                same = replace(o, y_ratio=prev.extra["y_ratio"],
                               n_coarse=(int(o.points) - 1) // 2 ** (prev.levels - 1),
                               **({} if probe_start else ended_relaxation(prev)))
                t = solve_fas(pb, same, callback=callback, scene=scene,
                              guess=(prev.X, prev.Y, prev.P, float(prev.H0)))
                r = tightened(prev, t, o) if t.success and t.levels == prev.levels else None
            if r is None:
                r = solve_fas(pb, o, callback=callback, scene=scene)
            if (opts.retry_from_neighbour and not r.success and seq["ok"] is not None
                    and r.status_name in NEIGHBOUR_RETRY):
                r = solve_from_neighbour(pb, o, r, seq["ok"], callback, scene)
            if r.success:
                seq["ok"] = seq["grids"][(n, box)] = r
                if opts.y_ratio is None and r.extra.get("square_cells_fallback"):
                    seq["y_ratio"] = r.extra["y_ratio"]
            return r

        probes: dict[PointOptions, EHLResult] = {}

        looks: dict[Any, tuple[float, float]] = {}  # the coarse looks taken (point_domain_change)

        def probe(res: EHLResult, box: float) -> tuple[float, float] | None:
            return point_domain_change(pb, res.options, res, probes, look=accuracy, looks=looks)

        def decay_probe(res: EHLResult, box: float, left: tuple[float, float] | None = None) -> BoxSeries | None:
            return point_box_series(pb, res.options, res, probes, left)

        # thick films (low M) spread over many inlet lengths: their box may grow further, on a
        # mesh that coarsens with it (the coarse grid follows the inlet length)
        box_limit = THICK_FILM_BOX_LIMIT if domain_scale(pb) > 1.0 else 4.0
        far = far_field_on(opts.far_field)
        if not opts.elastic:
            # rigid surfaces keep their box: with the far-field boundary its error is small
            # (circular: 0.2 % from half the box to the whole), without it (far_field=False) it
            # falls only about as 1/box (RIGID_BOX_NOTE); a wider box on the coarsest mesh the
            # rigid inlet length needs costs more than it gains (1025 points on twice the box: 125 s)
            box_limit = 1.0

        def first(n: int) -> tuple[int, float]:
            # (called only for a refined sequence) a box too small for the target is found by the
            # domain probes alone, before its solve
            wide = 2 * (n - 1) + 1
            change = None if wide > max_points or box_limit == 1.0 else start_box(
                pb, replace(opts, points=n, raise_on_failure=False, film_tol=film_tol(opts, accuracy)),
                accuracy, probes, looks)
            if change is None:
                return n, 1.0
            if progress is not None:
                progress(f"{n} points, box x1: the domain probes change Hc by {change[0]:+.2%} and Hm "
                         f"by {change[1]:+.2%} on twice the box: starting on box x2")
            return wide, 2.0

        # thick films: the box change falls 1.3-2.2x per doubling (validation/accuracy), where a
        # measured decay bounds the error no better than the fixed factor, and their probes on
        # 4-32x boxes cost minutes (fit map, Roelands (5, 20): 715 s against 31 s)
        res = solve_to_accuracy(solve, probe, accuracy, points, max_points, box_limit=box_limit,
                                min_points=min_points(pb.M, pb.b_over_a, cap=None),
                                start=first,
                                refine=accuracy is not None and not (explicit or fixed_box),
                                decay_probe=decay_probe if domain_scale(pb) <= 1.0 and not far else None,
                                progress=progress, correct_box=True, extrapolate=True,
                                hope_correction=fast_box_decay(pb) and not far,
                                domain_safety=domain_safety(opts),
                                time_budget=math.inf if time_budget is None else time_budget)
        why = thick_film_reason(pb, res, accuracy) if res.status_name == "inaccurate" \
            and domain_scale(pb) > 1.0 and opts.elastic else ""
        if res.status_name == "inaccurate" and not opts.elastic and not far:
            why = RIGID_BOX_NOTE
        if why:
            res.message += "; " + why
        need = min_points(pb.M, pb.b_over_a, cap=None)
        if res.status_name == "inaccurate" and need > max(max_points, int(res.options.points)):
            res.message += (f"; at M = {pb.M:.4g} and b/a = {pb.b_over_a:.3g} this solver needs at least "
                            f"{need} points (max_points {max_points})")
            if pb.b_over_a < NARROW_BELOW and pb.M >= 1000:
                res.message += ": the film's side constriction at |Y| = b is not resolved below that"
        if not res.success and opts.raise_on_failure:
            raise ConvergenceError(f"point solver: {res.message}", res.report, HINT)
        return res
    if rigid:
        raise InputError("rigid = True is available with solver = 'fas' only")
    from .newton import solve_newton_amg

    sol = solve_newton_amg(pb, options, **kw)
    if scene is not None:
        sol = _finish(sol, scene)
    return sol
