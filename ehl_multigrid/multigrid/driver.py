"""One FAS/FMG driver for every multilevel EHL solve.

The driver owns what does not depend on the discretisation: the recursive V, W and F cycles,
Full Multigrid (solve on a start grid, interpolate to each finer grid, ``cycles`` cycles
there), extra finest-grid cycles until the tolerances are met, the robustness policy
(:mod:`.policy`), the per-cycle callback, the histories and the result. A contact supplies a
*hierarchy* (its grids and unknowns) with these methods (``k`` indexes the grids, coarsest
first):

``levels``                      sequence of grids; each has ``shape`` (points per axis),
                                ``spacing`` (mesh sizes) and ``npts``
``name``                        ``"line"``, ``"point"`` ... (for messages)
``start(solver) -> k0``         initial guess and solution on the FMG start grid ``k0``
``relax(k, sweeps, settings, coarse, post=False)``   relaxation sweeps (``coarse``: ``k`` is
                                below the current FMG grid, where the film constant may move;
                                ``post``: after the coarse-grid correction)
``restrict(k, settings) -> token``       FAS coarse problem on ``k - 1`` from grid ``k``
``correct(k, token, settings)`` add the interpolated coarse-grid correction to grid ``k``
``coarse_solve(k, settings)``   solve on the coarsest grid
``fmg_interpolate(k, settings)`` start grid ``k`` from the solution on ``k - 1``
``snapshot(k) / restore(k, s)`` save and restore the iterate on grids ``0 .. k``
``measure(k) -> Measurement``   residual, load error and central film of grid ``k``
``raise_switch(settings) -> str``        widen the Jacobi-distributive zone ("" if it cannot)
``last_resort(k, solver) -> bool``       optional: finish a stalled solve another way
``work(k)``                     cost of one sweep on grid ``k`` in finest-grid sweeps

Every method may return a cost in work units (finest-grid sweeps) or None. The hierarchy logs
what it does with ``solver.note(message)``.

Modelled on pyamg's ``MultilevelSolver``: the solver exposes its levels, cycle type, residual
history and a callback, and ``repr`` lists the grids.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..model.errors import ConvergenceError
from .accuracy import LOAD_SENSITIVITY, hm_max_order, iteration_error, last_film_change, richardson
from .controller import TimeBudgetSpent, check_deadline
from .options import MultigridOptions
from .policy import NOTHING_CHANGED, RobustnessPolicy, Settings
from .result import EHLResult


@dataclass
class Measurement:
    """Finest-grid (or current-grid) observables after a cycle."""

    residual: float
    load_error: float
    Hc: float
    ok: bool
    Hm: float = math.nan
    #: minimum film between the nodes (point contacts; NaN where not measured)
    Hm_sub: float = math.nan


@dataclass
class CycleRecord:
    """One accepted cycle: grid, index, residual, load error, central film (Venner units)."""

    level: int
    cycle: int
    residual: float
    load_error: float
    Hc: float
    work_units: float
    level_residuals: list[float] = field(default_factory=list)
    Hm: float = math.nan
    Hm_sub: float = math.nan


#: the grid rule stops only while the residual is within this factor of the tolerance: films
#: still while the residual sits far above it would mean an iteration stuck somewhere the films
#: do not see
GRID_STOP_RESIDUAL = 10.0
#: the grid rule never leaves more than this (relative) iteration error in the films: a quarter of
#: a coarse grid's percent-level grid error would let paths that should agree (thermal in its
#: isothermal limit, half and full domain) differ; the rule is meant for fine grids
GRID_STOP_CAP = 1e-4


class _Stop(Exception):
    """Internal: the solve ends early with a status code."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status
        self.message = message


class MultilevelSolver:
    """FAS/FMG solve of one EHL problem on a contact's grid hierarchy.

    Parameters
    ----------
    hierarchy : the contact's grids and discretisation (see module docstring).
    options : immutable :class:`MultigridOptions` of the solve.
    settings : the adaptive per-solve settings (start values).
    policy : :class:`RobustnessPolicy` of the contact.
    hint : what to try when the solve fails (appended to error messages).

    Attributes
    ----------
    levels, cycle, residuals, load_errors, history, actions, work_units
    """

    def __init__(self, hierarchy: Any, options: MultigridOptions, settings: Settings,
                 policy: RobustnessPolicy, hint: str = "") -> None:
        self.hierarchy = hierarchy
        self.options = options
        self.settings = settings
        self.policy = policy
        self.hint = hint
        self.residuals: list[float] = []
        self.load_errors: list[float] = []
        self.history: list[CycleRecord] = []
        self.fmg: list[dict[str, float]] = []
        self.actions: list[str] = []
        self.work_units = 0.0
        self.start_level = 0
        self._level_res: list[float] = []
        self._callback: Callable | None = None
        self._finest_phase = False
        self._confirmed_at = -1
        #: check the time budget of the running sequence before each cycle (ends the solve
        #: with status ``time_budget``; the steady line solver sets it)
        self.deadline_checks = False

    # -- introspection --------------------------------------------------------------------
    @property
    def levels(self) -> list:
        return list(self.hierarchy.levels)

    @property
    def cycle(self) -> str:
        return self.settings.cycle

    def __repr__(self) -> str:
        lines = [f"MultilevelSolver({type(self.hierarchy).__name__}, cycle {self.settings.cycle}, "
                 f"{len(self.hierarchy.levels)} levels, deformation {self.options.deformation})"]
        for k, lv in enumerate(self.hierarchy.levels):
            shape = " x ".join(str(s) for s in lv.shape)
            h = ", ".join(f"{v:.4g}" for v in lv.spacing)
            lines.append(f"  level {k}: {shape} points, h = {h}")
        return "\n".join(lines)

    def note(self, message: str) -> None:
        """Record a robustness action (also listed in the result)."""
        self.actions.append(message)

    def _add(self, cost: float | None) -> None:
        if cost:
            self.work_units += float(cost)

    # -- cycles ---------------------------------------------------------------------------
    def _cycle(self, k: int, top: int, kind: str) -> None:
        """One FAS cycle with grid ``k`` as the current fine grid (``top``: the FMG grid)."""
        hz, s, o = self.hierarchy, self.settings, self.options
        if k == 0:
            self._add(hz.coarse_solve(0, s))
            return
        self._add(hz.relax(k, o.nu1, s, k != top))
        token, lres = hz.restrict(k, s)
        if lres is not None:
            self._level_res.append(lres)
        if kind == "V" or k == 1:
            self._cycle(k - 1, top, kind)
        elif kind == "W":
            self._cycle(k - 1, top, "W")
            self._cycle(k - 1, top, "W")
        else:  # F: an F cycle then a V cycle below
            self._cycle(k - 1, top, "F")
            self._cycle(k - 1, top, "V")
        hz.correct(k, token, s)
        self._add(hz.relax(k, o.nu2, s, k != top, post=True))

    def trial_cycle(self, k: int) -> Measurement:
        """One FAS cycle on grid ``k`` outside the histories and the robustness policy: for a
        hierarchy's start that falls back to another method when the cycles fail (the caller
        restores the iterate). Its work units count; numerical errors propagate."""
        self._level_res = []
        self._cycle(k, k, self.settings.cycle)
        return self.hierarchy.measure(k)

    def run_cycle(self, k: int, c: int) -> Measurement:
        """One accepted cycle on grid ``k``: rejected attempts are undone and repeated with
        the policy's next step; raises ``_Stop`` when the retries run out."""
        hz, pol, s = self.hierarchy, self.policy, self.settings
        if self.deadline_checks:
            check_deadline(f"cycle {c} on the {hz.levels[k].shape[-1]}-point grid")
        saved = hz.snapshot(k)
        recent = [h.residual for h in self.history if h.level == k]
        last = self.history[-1] if self.history else None
        prev_le = last.load_error if last is not None and last.level == k else None
        last_change = None
        for attempt in range(pol.params.max_retries):
            self._level_res = []
            try:
                if k > 0:
                    self._cycle(k, k, s.cycle)
                else:
                    self._add(hz.coarse_solve(0, s))
                m = hz.measure(k)
            except (np.linalg.LinAlgError, FloatingPointError, ValueError) as exc:
                m = Measurement(math.inf, math.inf, math.nan, False)
                self.note(f"cycle {c} on grid {k} failed: {exc}")
            if pol.accept(m.ok, m.residual, m.load_error, recent, prev_le, self._accept_tol()):
                pol.recover(s)
                break
            hz.restore(k, saved)
            before = dataclasses.astuple(s)
            what = pol.on_reject(s, hz)
            self.note(f"cycle {c} on grid {k} rejected (residual {m.residual:.3g}, load error "
                      f"{m.load_error:.3g}, attempt {attempt + 1}): {what}")
            change = (what, dataclasses.astuple(s))
            if change[1] == before and (change == last_change or what in ("fail", NOTHING_CHANGED)):
                # the attempt is deterministic: from the restored state with the same settings
                # the next one would fail the same way (point Barus (1000, 20) at 2049 points
                # repeated its NaN six times, same load error to the digit)
                raise _Stop(3, f"diverged on grid {k}: cycle {c} rejected {attempt + 1} times and the "
                               f"remedies are exhausted (last residual {m.residual:.3g})")
            last_change = change
        else:
            raise _Stop(3, f"diverged on grid {k}: {pol.params.max_retries} attempts of cycle {c} "
                           f"rejected (last residual {m.residual:.3g})")
        self.record(k, c, m)
        return m

    def record(self, k: int, c: int, m: Measurement) -> None:
        """Append an accepted cycle (or a last-resort solve, ``c = -1``) to the histories and
        call the callback."""
        rec = CycleRecord(k, c, m.residual, m.load_error, m.Hc, self.work_units, list(self._level_res), m.Hm,
                          m.Hm_sub)
        self.history.append(rec)
        if k == len(self.hierarchy.levels) - 1:
            self.residuals.append(m.residual)
            self.load_errors.append(m.load_error)
        if self._callback is not None:
            info = {"level": k, "points": self.hierarchy.levels[k].shape[-1], "cycle": c,
                    "residual": m.residual, "load_error": m.load_error, "Hc_venner": m.Hc,
                    "work_units": self.work_units, "cycle_type": self.settings.cycle}
            try:
                self._callback(info)
            except StopIteration:
                raise _Stop(4, f"stopped by the callback after cycle {c} on grid {k}") from None

    def converged(self) -> bool:
        o = self.options
        if not self.residuals:
            return False
        if o.film_tol is not None and not (self.history and self.history[-1].cycle == -1):
            # (after a direct last-resort solve, c = -1, the film's jump to the discrete
            # solution is no iteration error: its residual decides)
            top = len(self.hierarchy.levels) - 1
            need = getattr(self.hierarchy, "film_stop_films", 2)
            fin = [h for h in self.history[-need:] if h.level == top]
            if len(fin) < need or abs(self.load_errors[-1]) >= o.film_tol:
                return False
            a, b = fin[-2:]
            return (abs(b.Hc - a.Hc) < o.film_tol * abs(b.Hc)
                    and abs(b.Hm - a.Hm) < o.film_tol * abs(b.Hm))
        if self.residuals[-1] < o.tol and abs(self.load_errors[-1]) < o.tol_load:
            return True
        return self.grid_stop()

    def needs_confirmation(self) -> bool:
        """True when :meth:`converged` holds only by an early rule (residual above ``tol``), the
        cycles are not W already, the last cycle was not the confirming W cycle and the options
        ask for the confirmation (``confirm_early_stop``: a V-cycle stall can hold the films
        still far from the discrete solution; docs/robustness.md)."""
        o = self.options
        if not o.confirm_early_stop or self.settings.cycle == "W" or not self.residuals:
            return False
        if self.residuals[-1] < o.tol and abs(self.load_errors[-1]) < o.tol_load:
            return False
        return self._confirmed_at != len(self.history)

    def wants_cycles(self) -> bool:
        """The hierarchy's own criterion once the tolerances hold (its ``wants_cycles(solver)``,
        e.g. the oil balance of a mass-conserving time step): True asks for another finest-grid
        cycle within ``max_cycles``; the solve stays converged when the limit ends them."""
        wants = getattr(self.hierarchy, "wants_cycles", None)
        return bool(wants is not None and wants(self))

    def confirm(self, k: int, c: int) -> None:
        """One W cycle on grid ``k`` (then back to the solve's cycle type unless the policy
        changed it meanwhile)."""
        s = self.settings
        kind, n_actions = s.cycle, len(self.actions)
        s.cycle = "W"
        try:
            self.run_cycle(k, c)
        finally:
            if len(self.actions) == n_actions:
                s.cycle = kind
        self._confirmed_at = len(self.history)

    def _accept_tol(self) -> float:
        """Residual below which a cycle is accepted whatever its growth: the tolerance, or the
        policy's ``quiet_below`` under the residual rule (a film-stopped solve keeps the growth
        test: its films, not its residual, end it)."""
        o = self.options
        return max(o.tol, self.policy.params.quiet_below) if o.film_tol is None else o.tol

    def _floor_message(self, tol: float) -> str:
        """Why a solve stalled below the policy's ``quiet_below``, with the films' last
        changes."""
        d = last_film_change(self.history)
        moved = "" if d is None else \
            f"; the last cycle changed Hc by {d['Hc']:.2g} and Hm by {d['Hm']:.2g} (relative)"
        return (f"the residual stopped falling at {self.residuals[-1]:.3g} (tol {tol:.3g}) over "
                f"{self.policy.params.stall_window} cycles, below {self.policy.params.quiet_below:g}: "
                f"the floor of this grid's relaxation, not a divergence; ask for a tolerance above "
                f"it or stop on the films (film_tol){moved}")

    def films_at_floor(self) -> bool:
        """True when a film-stopped solve sits at its relaxation's residual floor: the residual
        is below the policy's ``quiet_below`` and has not fallen by ``stall_factor`` over
        ``stall_window`` finest-grid cycles, and the films' changes over the second half of that
        window are no smaller than over the first (jitter, not a contraction): the (5000, 0)
        decay probe on 2049 points (box x2, film_tol 1e-5) holds its residual at 7e-7 to 1e-6
        while Hc jumps by 4e-6 to 5.6e-5 per cycle, and without this test runs out its 60 cycles
        (5 min) without meeting the film rule."""
        p = self.policy.params
        w = p.stall_window
        top = len(self.hierarchy.levels) - 1
        r = self.residuals[-w:]
        fin = [h for h in self.history[-(w + 1):] if h.level == top]
        if len(r) < w or len(fin) < w + 1 or not (p.stall_factor * r[0] < r[-1] < p.quiet_below):
            return False
        def rel(new: float, old: float) -> float:
            return abs(new / old - 1.0) if old != 0.0 else math.inf

        d = [max(rel(b.Hc, a.Hc), rel(b.Hm, a.Hm)) for a, b in zip(fin[:-1], fin[1:], strict=True)]
        half = w // 2
        return max(d[half:]) >= max(d[:half])

    def _film_floor_message(self) -> str:
        d = last_film_change(self.history)
        moved = "" if d is None else f" (last cycle: Hc {d['Hc']:.2g}, Hm {d['Hm']:.2g}, relative)"
        return (f"the films still jump by more than film_tol = {self.options.film_tol:g} per cycle"
                f"{moved} while the residual stays at {self.residuals[-1]:.3g}, the floor of this "
                f"grid's relaxation, over {self.policy.params.stall_window} cycles: the films are "
                f"not resolved below that jitter; ask for a film tolerance above it")

    def grid_stop(self) -> bool:
        """True when further cycles would move both films by less than ``options.grid_stop``
        of the larger of their grid errors (see :class:`MultigridOptions`); the estimates are those of
        :func:`~ehl_multigrid.multigrid.accuracy.estimate_error`, so a result stopped here
        reports an algebraic error below that fraction of its grid error."""
        o, hz = self.options, self.hierarchy
        if o.grid_stop is None or not getattr(hz, "grid_stop", False):
            return False
        if not (self.residuals[-1] < GRID_STOP_RESIDUAL * o.tol
                and abs(self.load_errors[-1]) < o.tol_load):
            # the load balance is kept to its tolerance: users check it (the extremes matrix
            # counts a larger load error as wrong)
            return False
        top = len(hz.levels) - 1
        fin = [h for h in self.history if h.level == top and h.cycle >= 0]
        coarse = [d for d in self.fmg if d["level"] < top]
        if len(fin) < 3 or not coarse:
            return False
        load = LOAD_SENSITIVITY * abs(self.load_errors[-1])
        grid, algebraic = [], []
        for key, cap in (("Hc", 2.0), ("Hm", hm_max_order(hz.name))):
            films = [getattr(h, key) for h in fin]
            last = films[-1]
            if not (math.isfinite(last) and last > 0.0):
                return False
            grid.append(richardson([d[key] for d in coarse] + [last], max_order=cap).error / last)
            algebraic.append(iteration_error(films) / last + load)
        # the scale is the larger grid error: Hm's can be tiny by a lucky sequence (circular
        # (20, 10) at 2049 points: 2.8e-5 against Hc's 4.4e-5) while the discrete minimum
        # jitters by 1e-5 from cycle to cycle
        return max(algebraic) <= min(o.grid_stop * max(grid), GRID_STOP_CAP)

    # -- driver ---------------------------------------------------------------------------
    def solve(self, callback: Callable[[dict[str, Any]], None] | None = None) -> EHLResult:
        """FMG, then extra finest-grid cycles until the tolerances are met.

        ``callback(info)`` is called after every accepted cycle with a dict (level, points,
        cycle, residual, load_error, Hc_venner, work_units, cycle_type); raising
        ``StopIteration`` in it ends the solve with status ``"stopped"``.
        """
        self._callback = callback
        hint = self.hint
        t0 = time.perf_counter()
        status, message = 0, ""
        hz, o = self.hierarchy, self.options
        top = len(hz.levels) - 1
        with np.errstate(all="ignore"):
            try:
                k0 = hz.start(self)
                self.start_level = k0
                # a start from a converged coarser solve of the same problem keeps its FMG films
                self.fmg.extend(getattr(hz, "resumed_fmg", ()))
                m0 = hz.measure(k0)
                Hc_prev = m0.Hc
                self.fmg.append({"level": k0, "points": hz.levels[k0].shape[-1], "Hc": m0.Hc,
                                 "Hm": m0.Hm, "Hm_sub": m0.Hm_sub, "dHc": math.nan})
                for k in range(k0 + 1, top + 1):
                    self._add(hz.fmg_interpolate(k, self.settings))
                    for c in range(o.cycles):
                        m = self.run_cycle(k, c)
                    self.fmg.append({"level": k, "points": hz.levels[k].shape[-1], "Hc": m.Hc,
                                     "Hm": m.Hm, "Hm_sub": m.Hm_sub, "dHc": m.Hc - Hc_prev})
                    Hc_prev = m.Hc
                if top == k0 and top > 0:
                    # started on the finest grid: a failure of this first cycle may also be
                    # finished by the hierarchy's last resort
                    self._finest_phase = True
                    self.run_cycle(top, 0)
                extra = 0
                self._finest_phase = True
                while extra < o.max_cycles:
                    if self.converged():
                        if self.needs_confirmation():
                            self.confirm(top, o.cycles + extra)
                            extra += 1
                            continue
                        if not self.wants_cycles():
                            break
                    self.run_cycle(top, o.cycles + extra)
                    extra += 1
                    if o.film_tol is not None and not self.converged() and self.films_at_floor():
                        raise _Stop(8, self._film_floor_message())
                    if not self.converged() and self.policy.stalled(self.residuals, o.tol):
                        r = self.residuals
                        if o.film_tol is None and r[-1] < self.policy.params.quiet_below:
                            # at the relaxation's residual floor a stall step only stirs the iterate
                            raise _Stop(8, self._floor_message(o.tol))
                        what = self.policy.on_stall(self.settings, hz, len(self.residuals))
                        if what is None:
                            raise _Stop(2, f"stalled: the residual fell only from "
                                           f"{r[-self.policy.params.stall_window]:.3g} to {r[-1]:.3g} "
                                           f"over {self.policy.params.stall_window - 1} cycles")
                        self.note(f"residual stalled at {r[-1]:.3g}: {what}")
                if self.converged() and not self.needs_confirmation():
                    status = 0
                    if o.film_tol is None and not (self.residuals[-1] < o.tol
                                                   and abs(self.load_errors[-1]) < o.tol_load):
                        self.note(f"stopped on the grid rule: the films' iteration error is below "
                                  f"{o.grid_stop:g} of their grid error (residual "
                                  f"{self.residuals[-1]:.3g}, tol {o.tol:.3g})")
                else:
                    status = 1
                    message = (f"not converged after {extra} extra cycles: residual "
                               f"{self.residuals[-1]:.3g} (tol {o.tol:.3g}), load error "
                               f"{self.load_errors[-1]:.3g} (tol {o.tol_load:.3g})")
            except _Stop as stop:
                status, message = stop.status, stop.message
            except TimeBudgetSpent as exc:
                status, message = 10, str(exc).split("\n  what to try:")[0]
                hint = exc.hint or self.hint
            except ConvergenceError as exc:
                status, message = 5, str(exc).split("\n  what to try:")[0]
                hint = exc.hint or self.hint
            if status in (2, 3) and self._finest_phase and hasattr(hz, "last_resort"):
                if hz.last_resort(top, self):
                    status = 0 if self.converged() else status
        wall = time.perf_counter() - t0
        finite = hz.finite() if hasattr(hz, "finite") else True
        if status == 0 and not finite:
            status, message = 3, "the solution holds NaN or inf"
        last = self.history[-1] if self.history else None
        if status == 0 and last is not None and last.level == top and last.Hm <= 0.0:
            # a converged discrete solution with touching surfaces: the grid cannot carry the
            # film at this load (measured: circular (1000, 10, theta 10) at 257 points, Hm < 0)
            status = 7
            message = (f"the iteration converged to a film that is not positive (minimum film "
                       f"{last.Hm:.3g}, Venner units) on the {hz.levels[top].shape[-1]}-point "
                       f"grid: too coarse for this load, use more points")
        if status == 0:
            message = "converged"
        record = EHLResult(
            status=status, message=message, cycles=len(self.history), residual_history=np.asarray(self.residuals, dtype=float),
            load_error_history=np.asarray(self.load_errors, dtype=float), work_units=self.work_units,
            wall_s=wall, actions=list(self.actions), history=list(self.history), fmg=list(self.fmg),
            tolerances={"residual": o.tol, "load": o.tol_load}, settings=self.settings,
            start_level=self.start_level)
        if not record.success and o.raise_on_failure:
            raise ConvergenceError(f"{hz.name} solver: {message}", record.report, hint)
        return record
