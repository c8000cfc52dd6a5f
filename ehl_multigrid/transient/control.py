"""A transient run under the package's one accuracy controller
(:func:`~ehl_multigrid.multigrid.controller.control`): the time step is the refinement.

A :class:`~ehl_multigrid.multigrid.controller.Resolution`'s ``dt`` scales the output step of
the first run; a run whose steps are sized by a local error tolerance (``time_tol``) takes
:data:`~.accuracy.TIGHTER_TOL` of the tolerance per halving (the pair of
:func:`~.accuracy.adaptive_time_error`). The grid is the first run's: no grid (space) error is
estimated, so no finer grid can be predicted and none is offered (docs/transient.md, "A time
step refined to a target").

Each run's time part comes from its pair, the run at twice the step (fixed steps,
:func:`~.accuracy.time_error`) or at half the step and :data:`~.accuracy.TIGHTER_TOL` of the
tolerance (:func:`~.accuracy.adaptive_time_error`). Runs are kept by resolution: the run at
``dt`` that estimated the error of the answer at ``2 dt`` is the next refinement's answer
(fixed steps), and the tighter run of an adaptive pair the next answer (adaptive), so no run is
made twice.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

from ..model.errors import ConvergenceError, InputError
from ..multigrid.controller import REQUIRED_GAIN, Candidate, ControlOutcome, Refinement, Resolution
from .accuracy import TIGHTER_TOL, adaptive_time_error, time_error
from .result import TransientResult
from .stepping import MAX_STEPS

#: the smallest time step the sequence refines to, over the first run's: 64 times its steps
MIN_DT_SCALE = 1.0 / 64.0
#: the smallest time tolerance a run accepts (:func:`~.stepping.model_inputs`)
MIN_TIME_TOL = 1e-8


@dataclass
class TimeRun:
    """One run of the sequence at ``at``: its ``result`` (None when refused, or when it failed
    before a step completed; a failed run's completed steps otherwise), the ``error`` that
    ended it (None for a run that completed), wall seconds and ``purpose`` (``solve``: a
    candidate answer; ``pair``: made for the time error of another run)."""

    at: Resolution
    result: TransientResult | None
    error: Exception | None
    wall_s: float
    purpose: str


class TransientControl:
    """A transient run as a :class:`~ehl_multigrid.multigrid.controller.Controlled` physics.

    Parameters
    ----------
    run : ``run(callback, **step_options) -> TransientResult``: the run of the front door with
        the given step options (``dt``, ``steps``, ``t_end``, ``time_tol``, ``checkpoint``,
        ``resume``) over its own; raises :class:`ConvergenceError` (with ``partial``) or
        :class:`InputError`.
    dimensions : 1 (line) or 2 (point).
    scheme : ``"bdf2"`` (second order in the step) or ``"euler"`` (first order).
    time_tol : the first run's local time tolerance (adaptive steps), or None (fixed steps).
    callback : called with the steps of the first run (the refined runs and the pairs are
        made without it).
    """

    def __init__(self, run: Callable[..., TransientResult], *, dimensions: int, scheme: str = "bdf2",
                 time_tol: float | None = None, callback: Any = None) -> None:
        self.run, self.dimensions, self.scheme = run, dimensions, scheme
        self.time_tol, self.callback = time_tol, callback
        self.order = 2 if scheme == "bdf2" else 1
        self.runs: dict[Resolution, TimeRun] = {}
        #: the time part of each estimated run ({"Hc", "Hm"}; None when not measured)
        self.parts: dict[Resolution, dict[str, float] | None] = {}
        #: why a run's time part was not measured
        self.notes: dict[Resolution, str] = {}
        #: the runs asked for as answers, and those estimated, in order
        self.solved: list[Resolution] = []
        self.answers: list[Resolution] = []

    # -- the runs ----------------------------------------------------------------------------------
    @property
    def adaptive(self) -> bool:
        return self.time_tol is not None

    @property
    def first(self) -> TransientResult | None:
        """The first run (time step scale 1), once it completed."""
        r = next((r for at, r in self.runs.items() if at.dt == 1.0), None)
        return r.result if r is not None and r.error is None else None

    def _halvings(self, at: Resolution) -> int:
        return round(-math.log2(at.dt))

    def step_options(self, at: Resolution) -> dict[str, Any]:
        """The step options of the run at ``at`` over the first run's (none at scale 1)."""
        if at.dt == 1.0:
            return {}
        b = self.first
        if b is None:
            raise ValueError("a refined run needs the completed first run")
        opts: dict[str, Any] = {"dt": b.dt * at.dt, "steps": max(int(b.planned_steps / at.dt), 1),
                                "t_end": None, "checkpoint": None, "resume": None}
        if self.adaptive:
            opts["time_tol"] = self.time_tol * TIGHTER_TOL ** self._halvings(at)
        return opts

    def limit(self, at: Resolution) -> str:
        """Why a run at ``at`` would be refused ("" when it would not)."""
        b = self.first
        if b is not None and int(b.planned_steps / at.dt) > MAX_STEPS:
            return (f"the time step x{at.dt:g} would take {int(b.planned_steps / at.dt)} steps, more than "
                    f"the {MAX_STEPS} a run allows")
        if self.adaptive and self.time_tol * TIGHTER_TOL ** self._halvings(at) < MIN_TIME_TOL:
            return (f"the time tolerance would be {self.time_tol * TIGHTER_TOL ** self._halvings(at):.2g}, "
                    f"below the {MIN_TIME_TOL:g} a run allows")
        return ""

    def _run(self, at: Resolution, purpose: str) -> TimeRun:
        if at in self.runs:
            return self.runs[at]
        t0 = time.perf_counter()
        result: TransientResult | None = None
        error: Exception | None = None
        try:
            result = self.run(self.callback if at.dt == 1.0 else None, **self.step_options(at))
        except ConvergenceError as exc:
            result, error = getattr(exc, "partial", None), exc
        except InputError as exc:
            if at.dt == 1.0:
                raise  # the caller's input: refused as without a target
            error = exc
        r = self.runs[at] = TimeRun(at, result, error, time.perf_counter() - t0, purpose)
        return r

    # -- Controlled ----------------------------------------------------------------------------------
    def solve(self, at: Resolution) -> TimeRun:
        self.solved.append(at)
        return self._run(at, "solve")

    def converged(self, result: TimeRun) -> bool:
        return result.error is None and result.result is not None and bool(result.result.complete)

    def failure(self, result: TimeRun) -> str:
        if result.error is not None:
            return str(result.error).splitlines()[0]
        return result.result.stop_reason if result.result is not None else "no step completed"

    def remedy(self, result: TimeRun, at: Resolution, first: bool) -> Resolution | None:
        return None

    def pair(self, at: Resolution) -> Resolution:
        """The run whose difference from ``at`` measures its time part."""
        return replace(at, dt=at.dt * (0.5 if self.adaptive else 2.0))

    def estimate(self, result: TimeRun, at: Resolution,
                 record: Callable[[Refinement], None]) -> tuple[float, float]:
        self.answers.append(at)
        other = self.pair(at)
        second = (f"the run at {TIGHTER_TOL:g} of the time tolerance and half the step" if self.adaptive
                  else "the run at twice the time step")
        why = self.limit(other)
        if why:
            self.parts[at] = None
            self.notes[at] = f"time error not measured: {second} is refused ({why})"
            return math.nan, math.nan
        new = other not in self.runs
        p = self._run(other, "pair")
        if new:
            record(Refinement(at.points, 1.0, 1.0, math.nan, math.nan, p.wall_s, "time pair"))
        if isinstance(p.error, InputError):  # beyond what the feature or the tolerance allows
            self.parts[at] = None
            self.notes[at] = (f"time error not measured: {second} is refused ({p.error})"
                              + ("" if self.adaptive else "; a smaller dt allows it"))
            return math.nan, math.nan
        if not self.converged(p):
            self.parts[at] = None
            self.notes[at] = f"{second} for the time error failed: {self.failure(p)}"
            return math.nan, math.nan
        fine, coarse = result.result, p.result
        terr = adaptive_time_error(fine, coarse) if self.adaptive else time_error(fine, coarse)
        self.parts[at] = terr
        return terr["Hc"], terr["Hm"]

    def _stalled(self, at: Resolution) -> tuple[float, float] | None:
        """``(now, before)``: the time error of ``at`` and of the answer one step coarser, when
        halving the step lowered it by less than :data:`REQUIRED_GAIN`."""
        now, before = self.parts.get(at), self.parts.get(replace(at, dt=2.0 * at.dt))
        if now is None or before is None:
            return None
        a, b = max(now.values()), max(before.values())
        return (a, b) if not a < REQUIRED_GAIN * b else None

    def candidates(self, result: TimeRun, at: Resolution) -> list[Candidate]:
        finer = replace(at, dt=0.5 * at.dt)
        if finer.dt < MIN_DT_SCALE or self.limit(finer) or self._stalled(at) is not None:
            return []
        terr = self.parts.get(at)
        # unmeasured (the pair refused or failed): the finer run's pair is this run, so halving
        # the step is the refinement the estimate needs
        predicted = math.nan if terr is None else max(terr.values()) / 2.0**self.order
        return [Candidate("time_tol" if self.adaptive else "dt", finer, 0, predicted)]

    def why_short(self, result: TimeRun, at: Resolution) -> str:
        finer = replace(at, dt=0.5 * at.dt)
        stalled = self._stalled(at)
        if stalled is not None:
            return (f"halving the time step lowered the time error by less than "
                    f"{1.0 - REQUIRED_GAIN:.0%} ({stalled[1]:.2g} -> {stalled[0]:.2g}): what is left is "
                    f"not the step's (the step tolerance, or the film's own scale of time)")
        if finer.dt < MIN_DT_SCALE:
            return f"the time step is {at.dt:g} of the first run's, the smallest the sequence takes"
        return self.limit(finer) or "no refinement is predicted to help"

    # -- what the sequence did ---------------------------------------------------------------------------
    def actions(self, out: ControlOutcome, accuracy: float) -> tuple[str, ...]:
        """One line per refinement of the sequence and, when it stopped short, why."""
        lines = []
        runs = {at: r.result for at, r in self.runs.items() if r.result is not None}

        def dt_of(at: Resolution) -> str:
            res = runs.get(at)
            return f"dT = {res.dt:.4g}" if res is not None else f"time step x{at.dt:g}"

        for a, b in zip(self.answers, self.answers[1:], strict=False):
            terr = self.parts.get(a)
            err = (f"time error Hc {terr['Hc']:.2g}, Hm {terr['Hm']:.2g} above the accuracy {accuracy:g}"
                   if terr is not None else "time error not measured: halving the step measures it")
            what = (f"time tolerance x{TIGHTER_TOL:g} and output step halved" if self.adaptive
                    else "time step halved")
            lines.append(f"{what}: {dt_of(a)} -> {dt_of(b)} ({err})")
        tried = [at for at in self.solved if at not in self.answers]
        for at in tried:
            lines.append(f"the refinement to {dt_of(at)} did not complete: {self.failure(self.runs[at])}")
        if out.why:
            lines.append(f"not refined further: {out.why}")
        return tuple(lines)
