"""The starved line contact for a given oil supply: the meniscus found by an outer root search.

In a steady line contact under Elrod-Adams cavitation the film ahead of the meniscus ``X_m``
is a film content ``theta = Hoil/H`` at zero pressure carrying the supplied flux ``Hoil``
(Venner units, ``hoil R/b^2``), and from the meniscus on the gap is full. The solution
downstream of ``X_m`` is therefore the flooded-inlet solution on the box ``[X_m, xmax]``,
and the meniscus is where that solution's mass flux equals the supply:

``F(X_m) = Hoil``,

with ``F`` the flux through the box (Couette plus pressure flow at the inlet face: the
pressure flow at the meniscus is the oil the full film pushes back into the partly filled
zone, the Elrod-Adams front condition). ``F`` grows from 0 (meniscus at the Hertzian edge)
to the flooded flux ``F_ff`` (meniscus far upstream); a supply ``Hoil >= F_ff`` floods the
contact (the excess flows back). Each ``F(X_m)`` is one multilevel solve of the
mass-conserving hierarchy (line.py, Elrod-Adams rupture behind the contact, so the layer left
on the track is computed, not assumed); the root is bracketed by a scan from the contact
outwards and refined by Brent's method, first on a coarse grid and then on the requested one.

The result lives on the box grid (``X`` from ``X_m``); ``extra['upstream']`` holds the
starved inlet ahead of it (``X``, ``H``, ``theta``) from the film equation.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable
from typing import Any

import numpy as np
import scipy.optimize

from ..line.problem import LineProblem
from ..line.solver import HINT, MAX_ACCURACY_POINTS, line_domain_change, solve_line_problem
from ..model.errors import ConvergenceError, InputError, require_range
from ..multigrid.accuracy import (
    LOAD_SENSITIVITY,
    ErrorEstimate,
    attach_estimate,
    estimate_error,
    line_hm_richardson,
    richardson,
)
from ..multigrid.controller import Resolution, control
from ..multigrid.options import LineOptions
from ..multigrid.result import EHLResult
from .gate import apply_mass_gate
from .line import solve_starved_problem, starved_options
from .refine import StarvedControl, compare_flooded, note_not_refined, supply_ratio
from .supply import check_hoil

#: meniscus positions tried (from the contact outwards) to bracket ``F(X_m) = Hoil``; the
#: flooded solver's start fails with the inlet at the Hertzian edge (measured at M = 20,
#: L = 10: X_m = -1.0 fails, -1.05 converges), so the scan starts just upstream of it
MENISCUS_SCAN = (-1.003, -1.006, -1.01, -1.02, -1.03, -1.05, -1.08, -1.12, -1.2, -1.35, -1.6, -2.0, -2.6, -3.5, -5.0,
                 -7.0, -10.0, -15.0, -25.0, -50.0)
#: tried only when the supply is below the flux at MENISCUS_SCAN[0]: box solves this close to the
#: Hertzian edge converge through the dense Newton last resort (513 points: (20, 10) 1.5 % of the
#: flooded flux at -1.002, (100, 10) 7.6 % at -1.003; -1.0 has no positive film on the start grid)
EDGE_SCAN = (-1.002, -1.0015, -1.001)
#: positions tried between the last one that carries too much and the edge
EDGE_TRIES = 4
#: grid of the coarse root search
COARSE_POINTS = 257


def upstream_film(res: EHLResult, X: np.ndarray) -> np.ndarray:
    """Film ``H = H0 + X^2/2 - (1/pi) int ln|X - x| P(x) dx`` at points ``X`` ahead of the box
    (zero pressure there), with the box pressure piecewise constant on its cells (the cell
    integrals of the line kernel, thesis (2.2))."""
    Xb, P, h = res.X, res.P, res.X[1] - res.X[0]

    def prim(u: np.ndarray) -> np.ndarray:  # antiderivative of ln|u|
        au = np.abs(u)
        return np.where(au > 0.0, u * np.log(np.where(au > 0.0, au, 1.0)) - u, 0.0)

    d_hi = (Xb[None, :] + 0.5 * h) - X[:, None]
    d_lo = (Xb[None, :] - 0.5 * h) - X[:, None]
    W = (prim(d_hi) - prim(d_lo)) @ P
    elastic = res.problem.elastic
    return res.H0 + 0.5 * X**2 - (W / math.pi if elastic else 0.0)


class _FluxMap:
    """``X_m -> F(X_m)`` by box solves on ``points`` points (cached)."""

    def __init__(self, problem: LineProblem, options: LineOptions, points: int) -> None:
        self.problem, self.points = problem, points
        self.options = dataclasses.replace(options, points=points, levels=None,
                                           fmg_start_points=None, raise_on_failure=False)
        self.cache: dict[float, EHLResult] = {}
        self.work = 0.0

    def solve(self, xm: float) -> EHLResult:
        if xm not in self.cache:
            pb = dataclasses.replace(self.problem, xmin=float(xm))
            res = self._counted(solve_starved_problem(pb, math.inf, self.options))
            if not res.success and res.message.startswith("the flooded start solve failed"):
                res = self._continued(pb, xm) or res
            self.cache[xm] = res
        return self.cache[xm]

    def _continued(self, pb: LineProblem, xm: float) -> EHLResult | None:
        """The box solve again, its flooded start begun from a converged box with a nearby
        meniscus (continuation in the meniscus position: near the Hertzian edge the flooded
        solve from the Hertzian guess diverges where the neighbour's solution converges); the
        nearest converged neighbour on each side is tried, nearest first."""
        done = sorted(((abs(x - xm), x, r) for x, r in self.cache.items()
                       if r.success and r.extra.get("flooded")), key=lambda d: d[0])
        sides = [d for d in done if d[1] < xm][:1] + [d for d in done if d[1] > xm][:1]
        for _, _, near_res in sorted(sides, key=lambda d: d[0]):
            near = near_res.extra["flooded"]
            # started on the finest grid itself: the FMG's coarse grids are what fail here
            opts = dataclasses.replace(self.options, raise_on_failure=False, film_tol=None,
                                       fmg_start_points=self.points)
            flooded = self._counted(solve_line_problem(pb, opts, guess=(near.X, near.P, near.H0)))
            if not flooded.success:
                continue
            res = self._counted(solve_starved_problem(pb, math.inf, self.options, flooded=flooded))
            if res.success:
                return res
        return None

    def _counted(self, res: EHLResult) -> EHLResult:
        """``res``, its work added to the searches' work."""
        self.work += res.work_units if math.isfinite(res.work_units) else 0.0
        return res

    def flux(self, xm: float) -> float:
        res = self.solve(xm)
        return float(res.scalars["flux_in"]) if res.success else math.nan


def _bracket(fm: _FluxMap, hoil: float, xmin: float, near: float | None = None) -> tuple[float, float]:
    """Adjacent meniscus positions with ``F`` below and above ``hoil`` (scan from the contact
    outwards; around ``near`` first when given)."""
    if near is not None:
        found = _bracket_near(fm, hoil, xmin, near)
        if found is not None:
            return found
        return _bracket(fm, hoil, xmin)
    cands = [x for x in MENISCUS_SCAN if x > xmin] + [xmin]
    prev = None
    for x in cands:
        F = fm.flux(x)
        if not math.isfinite(F):
            continue
        if F >= hoil:
            if prev is None:
                prev = _edge_bracket(fm, hoil, x, F)
            return x, prev
        prev = x
    raise ConvergenceError(f"no meniscus position in [{xmin:g}, {MENISCUS_SCAN[0]:g}] carries Hoil = "
                           f"{hoil:.4g} (largest flux found below it)", None, HINT)


def _bracket_near(fm: _FluxMap, hoil: float, xmin: float, near: float) -> tuple[float, float] | None:
    """The bracket of :func:`_bracket` around the previous grid's root ``near``: from ``near``
    towards the contact while the flux exceeds the supply, else outwards, by steps of 0.005,
    0.02, 0.08, then outwards over :data:`MENISCUS_SCAN`. Positions next to the Hertzian edge
    are solved only when the root lies there (their box solves end in the dense Newton last
    resort: 6.4 s at X_m = -1.003 on 1025 points for a roller bearing whose root lies at
    -1.015; docs/starvation.md). None when nothing brackets it (the full scan then runs)."""
    edge = EDGE_SCAN[-1] if near > MENISCUS_SCAN[0] else MENISCUS_SCAN[0]
    x0 = min(max(near, xmin), edge)
    F0 = fm.flux(x0)
    if not math.isfinite(F0):
        return None
    inward = F0 >= hoil  # the root lies closer to the contact
    last, F_last = x0, F0
    for d in (0.005, 0.02, 0.08):
        x = min(max(near + d if inward else near - d, xmin), edge)
        if x == last:
            continue
        F = fm.flux(x)
        if not math.isfinite(F):
            continue
        if inward and F < hoil:
            return last, x
        if not inward and F >= hoil:
            return x, last
        last, F_last = x, F
    if inward:
        return last, _edge_bracket(fm, hoil, last, F_last)
    for x in [x for x in MENISCUS_SCAN if xmin < x < last] + [xmin]:  # on outwards
        F = fm.flux(x)
        if math.isfinite(F) and F >= hoil:
            return x, last
        if math.isfinite(F):
            last = x
    return None


def _edge_bracket(fm: _FluxMap, hoil: float, x: float, F: float) -> float:
    """A meniscus closer to the Hertzian edge than ``x`` (whose flux ``F`` still exceeds the
    supply) that carries less than ``hoil``: positions that close the gap to the edge by 30 %
    at a time (box solves that fail are passed over), then :data:`EDGE_SCAN`; raises
    :class:`_Unreachable` with the closest position the box solver reached."""
    tries = [-1.0 - (-1.0 - x) * 0.7 ** i for i in range(1, EDGE_TRIES + 1)]
    for xe in sorted({t for t in tries + list(EDGE_SCAN) if t > x}):
        Fe = fm.flux(xe)
        if not math.isfinite(Fe):
            continue
        if Fe < hoil:
            return xe
        x, F = xe, Fe
    raise _Unreachable(x, F)


class _Unreachable(Exception):
    """The supply is below what the box solver reaches next to the Hertzian edge."""

    def __init__(self, x: float, F: float) -> None:
        super().__init__(f"X_m = {x:g}: F = {F:.4g}")
        self.x, self.F = x, F


def _root(fm: _FluxMap, hoil: float, lo: float, hi: float) -> float:
    """Brent's method on ``ln F(X_m) - ln Hoil`` between the bracket ends."""
    def g(x: float) -> float:
        F = fm.flux(x)
        if not math.isfinite(F):
            raise ConvergenceError(f"the flooded-inlet box solve at X_m = {x:.6g} did not converge "
                                   f"({fm.solve(x).message})", None, HINT)
        return math.log(F / hoil)

    return float(scipy.optimize.brentq(g, lo, hi, xtol=1e-12, rtol=1e-12, maxiter=60))


def supply_estimate(res: EHLResult, ladder: list[tuple[int, float, EHLResult]]) -> ErrorEstimate:
    """Error estimate at fixed supply: Richardson over the films of the nested root searches
    (grids refined by 2; first order with fewer than three, as the core estimate), no domain
    part (the box starts at the meniscus, ahead of which the starved inlet is exact), and the
    algebraic part from the supply mismatch and the load error."""
    Hc, Hm = float(res.scalars["Hc_venner"]), float(res.scalars["Hm_venner"])
    rc = richardson([r.scalars["Hc_venner"] for _, _, r in ladder])
    rm = line_hm_richardson([r.scalars["Hm_venner"] for _, _, r in ladder])
    grid = {"Hc": abs(rc.error / Hc), "Hm": abs(rm.error / Hm)}
    le = abs(float(res.load_error_history[-1])) if len(res.load_error_history) else math.inf
    alg = res.scalars.get("supply_mismatch", 0.0) + LOAD_SENSITIVITY * le
    budget = {"grid": grid, "domain": {"Hc": 0.0, "Hm": 0.0}, "algebraic": {"Hc": alg, "Hm": alg}}
    notes = ["grid part: Richardson over the root searches at fixed Hoil on "
             + ", ".join(str(n) for n, _, _ in ladder) + " points",
             "domain part 0: the box starts at the meniscus"]
    if not rc.regular:
        notes.append("Hc converges irregularly (or fewer than three grids): first-order estimate")
    return ErrorEstimate(grid["Hc"] + alg, grid["Hm"] + alg, budget, rc.order, rm.order,
                         rc.extrapolated, notes)


def solve_starved_line(problem: LineProblem, hoil: float, options: LineOptions | None = None,
                       accuracy: float | None = None, *, estimate: bool = True,
                       callback: Callable[[dict[str, Any]], None] | None = None,
                       scene: Any = None, max_points: int = MAX_ACCURACY_POINTS,
                       refine: bool | None = None, progress: Callable[[str], None] | None = None,
                       time_budget: float = math.inf, **kw: Any) -> EHLResult:
    """Solve the starved, mass-conserving isothermal EHL line contact for a supplied oil layer.

    Parameters
    ----------
    problem : the :class:`~ehl_multigrid.line.problem.LineProblem` (M, L, oil, box).
    hoil : supplied oil layer ahead of the contact in Venner units, ``Hoil = hoil R/b^2``
        (both surfaces together, at ambient density; Moes units: ``Hoil 8M/pi``;
        :func:`~ehl_multigrid.starved.supply.hoil_venner` converts metres). A layer at or
        above the flooded contact's flux floods it. Allowed: ``(0, inf]``.
    options : :class:`~ehl_multigrid.multigrid.options.LineOptions` (default: the line
        defaults with ``tol = tol_load = 1e-7``: the mass balance is the sum of the residuals);
        keywords override its fields (``points`` ...).
    accuracy : relative target for Hc and Hm: while the estimate exceeds it the grid is
        doubled by the package's accuracy controller
        (:func:`~ehl_multigrid.multigrid.controller.control`, up to ``max_points``); the
        result's status is ``"inaccurate"`` when it is still not met.
    refine : whether the grid may be refined; None: unless ``points`` or ``options`` are
        given (an explicit grid is only judged).
    progress : called with one line of text per solve of the refinement sequence.
    estimate : attach the error estimate (:func:`supply_estimate`: the core's Richardson
        rule over the films of nested root searches on 257, 513, ... points at fixed Hoil; the
        flooded solver's estimate when the inlet is flooded).

    Returns
    -------
    EHLResult
        On the box ``[meniscus_x, xmax]``: ``P``, ``H``, ``extra['theta']``, line scalars
        (``Hc``, ``Hm`` Moes, ``Hc_venner`` ...) and ``Hc_flooded``, ``Hm_flooded``,
        ``Hc_ratio``, ``Hm_ratio``, ``meniscus_x``, ``cavitation_x``, ``mass_balance_error``
        (the larger of the box's flux imbalance and the supply mismatch ``|F - Hoil|/Hoil``),
        ``outlet_layer`` (the layer left on the track, Moes; ``outlet_layer_venner``),
        ``rho_c_Hc_over_hoil``; ``extra['upstream']`` the starved inlet ahead of the box,
        ``extra['flooded']`` the flooded-inlet solution on the whole box, histories of the
        final solve, ``extra['meniscus_solves']`` the number of box solves and
        ``extra['meniscus_history']`` each of them (grid, meniscus, flux, status, cycles).

        By default a numerical failure is returned, not raised: ``success`` False, its status
        (``inaccurate`` when the estimate misses ``accuracy``) and the message naming why (a
        diverged solve, no meniscus carrying the supply).

    Raises
    ------
    InputError : bad ``hoil`` (negative, zero, NaN) or options.
    ConvergenceError : only with ``raise_on_failure=True``: the failure the result would have
        carried.
    """
    hoil = check_hoil(hoil)
    opts = starved_options(options, **kw)
    if estimate and opts.face != "arithmetic":
        # its estimate (the core's Richardson on the starved films) is validated with the
        # arithmetic face coefficient only (docs/accuracy.md)
        raise InputError(f"face = {opts.face!r}: the starved solver's error estimate is validated "
                         f"with the arithmetic face coefficient only; use estimate=False for a "
                         f"plain solve")
    if accuracy is not None:
        require_range("accuracy", accuracy, 1e-5, 0.5, "- (relative error)")
    if refine is None:
        refine = "points" not in kw and options is None
    line = _StarvedLineControl(problem, hoil, opts, accuracy, estimate, callback, scene, max_points)
    out = control(line, Resolution(opts.points), accuracy, refine=refine and estimate,
                  max_points=max_points, progress=progress, time_budget=time_budget)
    res = out.result
    if out.converged and out.why and res.status == 6:
        note_not_refined(res, out)
    if not res.success and opts.raise_on_failure:
        # the solves of the sequence return their failures (the controller judges them): the
        # caller's request to raise is honoured once, for the answer
        if res.status == 6:
            raise ConvergenceError(f"starved line solver: {res.message} ({res.X.size} points)",
                                   res.report, f"more points (up to max_points = {max_points})")
        raise ConvergenceError(f"starved line solver: {res.message}", res.report,
                               res.extra.get("hint", HINT))
    return res


class _StarvedLineControl(StarvedControl):
    """A starved line solve under the accuracy controller: the grid is the one refinement (the
    nested meniscus searches start again on the finer grid); each solve carries its own
    estimate (:func:`supply_estimate`)."""

    dimensions = 1

    def __init__(self, problem: LineProblem, hoil: float, opts: LineOptions, accuracy: float | None,
                 estimate: bool, callback: Any, scene: Any, max_points: int) -> None:
        super().__init__(accuracy, estimate, max_points)
        self.problem, self.hoil, self.opts, self.callback, self.scene = problem, hoil, opts, callback, scene

    def solve(self, at: Resolution) -> EHLResult:
        opts = dataclasses.replace(self.opts, points=at.points)
        return _solve_once(self.problem, self.hoil, opts, self.accuracy, self.with_estimate,
                           self.callback, self.scene)

    def converged(self, result: EHLResult) -> bool:
        return bool(result.success) or result.status == 6

    def estimate(self, res: EHLResult, at: Resolution, record: Any) -> tuple[float, float]:
        err = getattr(res, "error", None)
        return (err.Hc, err.Hm) if err is not None else (math.nan, math.nan)

    def predicted(self, res: EHLResult, b: dict[str, dict[str, float]]) -> float:
        # second order on the grid (the core's Richardson rule on the nested searches' films)
        return max(b["grid"][k] / 4.0 + sum(v[k] for n, v in b.items() if n != "grid")
                   for k in ("Hc", "Hm"))


def _solve_once(problem: LineProblem, hoil: float, opts: LineOptions, accuracy: float | None,
                estimate: bool, callback: Callable[[dict[str, Any]], None] | None,
                scene: Any) -> EHLResult:
    """One starved solve on ``opts.points`` (see :func:`solve_starved_line`); a numerical
    failure is returned (the accuracy controller's solves never raise), whatever
    ``opts.raise_on_failure``: :func:`solve_starved_line` raises for the final answer."""
    t0 = time.perf_counter()
    full = solve_starved_problem(problem, math.inf, dataclasses.replace(opts, raise_on_failure=False),
                                 callback=callback, scene=scene)
    if not full.success:
        return full
    F_ff = float(full.scalars["flux_in"])
    solves = 1
    if hoil >= F_ff:
        res = full
        res.scalars["meniscus_x"] = -math.inf
        res.extra["upstream"] = None
        fm_work = 0.0
    else:
        xmin = problem.xmin
        # nested root searches from COARSE_POINTS up to the requested grid: each starts near
        # the previous meniscus, and their films give the grid error at fixed supply
        grids = [min(COARSE_POINTS, opts.points)]
        while grids[-1] < opts.points:
            grids.append(2 * (grids[-1] - 1) + 1)
        maps, roots = [], []
        try:
            for n in grids:
                fm = _FluxMap(problem, opts, n)
                try:
                    lo, hi = _bracket(fm, hoil, xmin, near=roots[-1] if roots else None)
                    roots.append(_root(fm, hoil, lo, hi))
                except (_Unreachable, ConvergenceError):
                    # a meniscus this close to the Hertzian edge is shorter than the coarse
                    # search's mesh: start the nested searches one grid finer (two grids
                    # still give the error estimate)
                    if roots or len(grids) - grids.index(n) < 3:
                        raise
                    continue
                maps.append(fm)
            grids = [m.points for m in maps]
        except _Unreachable as exc:
            msg = (f"Hoil = {hoil:.4g} is below the flux the solver reaches with the meniscus next "
                   f"to the Hertzian edge ({exc.F:.4g} at X_m = {exc.x:g}, {exc.F / F_ff:.3g} of the "
                   f"flooded flux): severe starvation beyond this solver's range")
            out = EHLResult(status=5, message=msg)
            out.extra["hint"] = "a larger Hoil; the film then follows rho_c Hc = Hoil"
            out.scalars["Hc_flooded"] = full.scalars["Hc_flooded"]
            return out
        except ConvergenceError as exc:
            # a box solve of the search failed: a result with the reason, as for any failed solve
            out = EHLResult(status=3, message=f"meniscus search: {str(exc).splitlines()[0]}")
            out.scalars["Hc_flooded"] = full.scalars["Hc_flooded"]
            return out
        fine, xm = maps[-1], roots[-1]
        # the outer iteration: every box solve of the root searches (grid, meniscus, flux)
        history = [{"points": m.points, "meniscus_x": x, "flux": float(r.scalars.get("flux_in", math.nan)),
                    "status": r.status_name, "cycles": r.cycles}
                   for m in maps for x, r in m.cache.items()]
        solves += sum(len(m.cache) for m in maps)
        fm_work = sum(m.work for m in maps)
        ladder = [(n, x, m.solve(x)) for n, x, m in zip(grids, roots, maps, strict=True)]
        res = fine.solve(xm)
        F = float(res.scalars["flux_in"])
        res.scalars["meniscus_x"] = xm
        res.scalars["supply_mismatch"] = abs(F / hoil - 1.0)
        res.scalars["mass_balance_error"] = max(res.scalars["mass_balance_error"], abs(F / hoil - 1.0))
        Xu = np.linspace(xmin, xm, max(int(round((xm - xmin) / (res.X[1] - res.X[0]))), 2) + 1)[:-1]
        Hu = upstream_film(res, Xu)
        res.extra["upstream"] = {"X": Xu, "H": Hu, "theta": np.minimum(1.0, hoil / Hu)}
        res.extra["meniscus_history"] = history
    fl = full.extra["flooded"]
    compare_flooded(res.scalars, *(full.scalars[k] for k in ("Hc_flooded_venner", "Hm_flooded_venner",
                                                             "Hc_flooded", "Hm_flooded")))
    res.scalars["hoil_venner"] = hoil
    res.scalars["Hoil"] = problem.moes_from_venner(hoil) if math.isfinite(hoil) else math.inf
    res.scalars["flux_flooded"] = F_ff
    res.scalars["rho_c_Hc_over_hoil"] = supply_ratio(res.scalars["rho_c"], res.scalars["Hc_venner"], hoil)
    res.scalars["inlet_flooded"] = bool(hoil >= F_ff)
    # the Elrod-Adams outlet against the flooded (Reynolds-condition) solver on the same box
    res.scalars["outlet_change_Hc"] = full.scalars["Hc_venner"] / fl.scalars["Hc_venner"] - 1.0
    res.scalars["outlet_change_Hm"] = full.scalars["Hm_venner"] / fl.scalars["Hm_venner"] - 1.0
    res.extra["flooded"] = full
    res.extra["meniscus_solves"] = solves
    res.work_units = float(res.work_units) + fm_work + float(full.work_units)
    res.wall_s = time.perf_counter() - t0
    res.scalars.update(wall_s=res.wall_s, work_units=res.work_units, meniscus_solves=solves)
    res.scene = scene
    if math.isfinite(hoil):
        # a result that does not conserve mass is not a starved solution, whatever its iteration
        apply_mass_gate(res, res.scalars["mass_balance_error"], res.scalars["rho_c_Hc_over_hoil"])
    if estimate and res.success:
        if res.scalars["inlet_flooded"]:
            # the flooded solver's estimate of its own solution on this grid (domain part by
            # its doubled-box probe): the Elrod-Adams outlet changes the films by round-off
            est = estimate_error(fl, line_domain_change(fl.problem, fl.options, fl))
            est.notes.append("flooded inlet: the flooded solver's estimate on the same grid")
        else:
            est = supply_estimate(res, ladder)
            res.extra["meniscus_ladder"] = [{"points": n, "meniscus_x": x, "Hc_venner": r.scalars["Hc_venner"],
                                             "Hm_venner": r.scalars["Hm_venner"]} for n, x, r in ladder]
        attach_estimate(res, est, accuracy)
    return res


def solve_starved_scene(scene: Any, hoil: float | None = None, options: LineOptions | None = None,
                        accuracy: float | None = None, *, estimate: bool = True,
                        viscosity: str | None = None, density: str | None = None,
                        xmin: float | None = None, xmax: float | None = None, elastic: bool = True,
                        max_points: int = MAX_ACCURACY_POINTS, time_budget: float = math.inf,
                        progress: Callable[[str], None] | None = None, **kw: Any) -> EHLResult:
    """Starved line contact of a line-contact ``scene`` at its operating point, supplied with
    the scene's ``[supply] hoil`` [m] (or ``hoil`` [m]), converted with
    :func:`~ehl_multigrid.starved.supply.hoil_venner` (``Hoil = hoil R/b^2``). The scene's
    ``[solver.ehl]`` table applies (problem keys: viscosity, density, xmin, xmax; the rest are
    options below the keywords); explicit ``viscosity``, ``density``, ``xmin``, ``xmax``,
    ``elastic`` override it. Films in metres: ``hc = Hc_venner b^2/R`` (scalar ``hc``). A
    numerical failure is returned (or raised with ``raise_on_failure=True``), as by
    :func:`solve_starved_line`."""
    from ..multigrid.options import build_scene_options, scene_solver_table
    from .supply import hoil_venner

    model, table = scene_solver_table(scene, "line")
    given = {"viscosity": viscosity, "density": density, "xmin": xmin, "xmax": xmax}
    prob = {**{"viscosity": "roelands", "density": "dowson-higginson", "xmax": 1.5}, **model,
            **{k: v for k, v in given.items() if v is not None}}
    pb = LineProblem.from_scene(scene, elastic=elastic, **prob)
    h_m = scene.supply.hoil if hoil is None else hoil
    opts = build_scene_options(LineOptions, starved_options(options), table, kw)
    # the grid is refined towards the accuracy unless the caller or the scene fixed it
    refine = options is None and "points" not in kw and "points" not in table
    res = solve_starved_line(pb, hoil_venner(h_m, pb.b, pb.R), opts, accuracy, estimate=estimate,
                             scene=scene, max_points=max_points, refine=refine, progress=progress,
                             time_budget=time_budget)
    scale = pb.b**2 / pb.R
    res.scalars["hoil"] = h_m
    if "Hc_venner" in res.scalars:  # (not when the supply is out of reach)
        res.scalars["hc"] = res.scalars["Hc_venner"] * scale
        res.scalars["hm"] = res.scalars["Hm_venner"] * scale
        res.scalars["outlet_layer_m"] = res.scalars["outlet_layer_venner"] * scale
    return res
