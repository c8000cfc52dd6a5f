"""One accuracy controller for every physics: solve at a resolution, estimate the error, refine
the cheapest way until the target or a budget is met.

A physics plugs in through :class:`Controlled`: how to solve at a :class:`Resolution` (points
along X, box scale, tolerance scale, z-layers of a thermal film), how to estimate the error of a
converged solve (parts such as grid, domain, iteration, each with its own refinement), which
refinements it can make and what each is predicted to leave of the error
(:class:`Candidate`). The controller owns what every physics shares: the choice among the
candidates (:func:`choose`), the time budget (a refinement predicted to overrun it is not
started), the most accurate solve kept when a finer one fails or the budget runs out, the
fallback to one grid finer than the last converged solve when a larger step diverges, and the
record of every solve (:class:`Refinement`).

Used by the steady line and point solvers (:func:`~ehl_multigrid.multigrid.accuracy.solve_to_accuracy`),
the starved line and point solvers, the thermal (TEHL) solver and the transient runs
(:mod:`ehl_multigrid.transient.control`: the time step is their refinement).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, replace
from typing import Any, Protocol

from ..model.errors import ConvergenceError, signal_cause

#: the ``time.perf_counter()`` value at which the innermost :func:`control` sequence's time
#: budget runs out (inf outside one); long solves read it through :func:`check_deadline`
_DEADLINE: ContextVar[tuple[float, float]] = ContextVar("ehl_deadline", default=(math.inf, math.inf))


class StopScope:
    """Where a stop (Ctrl-C, the command line's SIGTERM) of an accuracy sequence is kept: the
    outermost :func:`control` inside :func:`keep_on_stop` returns its most accurate finished
    solve instead of raising, and records the stop in ``stop`` for the caller to raise after
    the answer is built."""

    def __init__(self) -> None:
        self.stop: BaseException | None = None
        self.depth = 0


_STOP_SCOPE: ContextVar[StopScope | None] = ContextVar("ehl_stop_scope", default=None)


@contextmanager
def keep_on_stop() -> Iterator[StopScope | None]:
    """Within the block, a stop during an accuracy sequence that has a finished (converged and
    estimated) solve ends the sequence with that solve, its ``why`` naming the stop; the stop
    is in the yielded scope's ``stop``, and the caller raises it once the answer is kept. A
    block inside another one yields None: the outermost caller raises."""
    if _STOP_SCOPE.get() is not None:
        yield None
        return
    scope = StopScope()
    token = _STOP_SCOPE.set(scope)
    try:
        yield scope
    finally:
        _STOP_SCOPE.reset(token)


def stop_name(stop: BaseException) -> str:
    """``"interrupted (Ctrl-C)"`` or ``"terminated (SIGTERM)"``."""
    return "interrupted (Ctrl-C)" if isinstance(stop, KeyboardInterrupt) else "terminated (SIGTERM)"


class TimeBudgetSpent(ConvergenceError):
    """A solve stopped because the time budget of the sequence it belongs to ran out."""


@contextmanager
def deadline(budget: float, started: float | None = None) -> Iterator[None]:
    """Within the block, :func:`check_deadline` raises once ``budget`` seconds have passed
    since ``started`` (default now); a deadline already set by an enclosing block is kept
    when it is earlier."""
    t0 = time.perf_counter() if started is None else started
    at = t0 + budget
    outer = _DEADLINE.get()
    token = _DEADLINE.set((at, budget) if at < outer[0] else outer)
    try:
        yield
    finally:
        _DEADLINE.reset(token)


def check_deadline(where: str) -> None:
    """Raise :class:`TimeBudgetSpent` when the time budget of the running sequence (set by
    :func:`deadline`, as :func:`control` does) has run out; ``where`` names the step that
    stops (a solve's iteration), for the message. Called between the iterations of the
    solves that can run for minutes (the outer iteration of a thermal EHL solve)."""
    at, budget = _DEADLINE.get()
    if time.perf_counter() >= at:
        raise TimeBudgetSpent(f"the time budget of {budget:g} s ran out at {where}", None,
                              "a larger time_budget, a looser accuracy or a coarser start grid")


@dataclass(frozen=True)
class Resolution:
    """What a solve is resolved with: ``points`` along X (``2^k m + 1``), the default box scaled
    by ``box``, the iteration tolerances scaled by ``tol``, ``nz`` layers across a thermal film
    (0 without), and ``dt``, the time step of a transient run scaled from its first run's (1
    for the steady physics)."""

    points: int
    box: float = 1.0
    tol: float = 1.0
    nz: int = 0
    dt: float = 1.0

    def finer(self) -> Resolution:
        """One grid finer, all else equal."""
        return replace(self, points=2 * (self.points - 1) + 1)

    def describe(self) -> str:
        nz = f", nz = {self.nz}" if self.nz else ""
        dt = f", time step x{self.dt:g}" if self.dt != 1.0 else ""
        tol = f", tolerances x{self.tol:g}" if self.tol != 1.0 else ""
        return f"{self.points} points{nz}{dt}{tol} (box x{self.box:g})"


@dataclass(frozen=True)
class Candidate:
    """A refinement the physics can make: its name (``points``, ``box``, ``points+box``,
    ``tolerance``, ``nz``), the resolution it leads to, a cost rank (0 cheapest) and the
    largest relative film error it is predicted to leave."""

    what: str
    at: Resolution
    rank: int
    predicted: float
    #: the prediction if what the finer solve may add works (an extrapolation, a box
    #: correction): only the hopeful choice reads it (NaN: ``predicted``)
    hoped: float = math.nan


@dataclass(frozen=True)
class Refinement:
    """One solve of a controlled sequence: its resolution, estimated film errors (NaN when the
    iteration did not converge), wall time, purpose (``solve``: a candidate answer;
    ``levels``: a coarser grid solved for the estimate of a finer one) and the refinement
    chosen after it (``""`` for none)."""

    points: int
    box: float
    tol: float
    Hc_error: float
    Hm_error: float
    wall_s: float
    purpose: str = "solve"
    nz: int = 0
    next: str = ""


class Controlled(Protocol):
    """What a physics provides to :func:`control`."""

    #: 1 (line) or 2 (point): the work of a solve grows as ``points^dimensions``
    dimensions: int

    def solve(self, at: Resolution) -> Any:
        """One solve at ``at``; never raises for a numerical failure."""

    def converged(self, result: Any) -> bool:
        """Whether the iteration of ``result`` converged (its accuracy not yet judged)."""

    def failure(self, result: Any) -> str:
        """One line on why ``result`` did not converge."""

    def estimate(self, result: Any, at: Resolution,
                 record: Callable[[Refinement], None]) -> tuple[float, float]:
        """Estimate the error of a converged ``result``, store it in the result and judge it;
        return the relative errors of Hc and Hm (NaN when unknown). Extra solves made for the
        estimate are passed to ``record``."""

    def candidates(self, result: Any, at: Resolution) -> list[Candidate]:
        """The refinements possible from ``at`` within the physics' limits, with predictions."""

    def remedy(self, result: Any, at: Resolution, first: bool) -> Resolution | None:
        """A refinement that may cure a failed solve (a grid too coarse for the load), or None;
        ``first`` when no solve has converged yet."""

    def why_short(self, result: Any, at: Resolution) -> str:
        """What the estimate says is missing when no candidate helps, in the user's terms."""

    # Optional: ``recurring_seconds(at) -> float | None``, the seconds of the last round (the
    # solve on ``at`` and its estimate) spent on work a refinement repeats at its finer
    # resolution (the solves on ``at``'s grid), without the coarser grids and one-time
    # references the next round reuses; None or absent: the whole round (predicted_seconds).


#: a candidate predicted within this factor of the lowest prediction counts as equal to it:
#: the predictions are not sharper, and the cheaper one is taken
PREDICTION_SHARPNESS = 1.1
#: a refinement that misses the target must at least lower the error by this factor
REQUIRED_GAIN = 0.9
#: a cheaper finer grid predicted within this factor of the target is tried before the
#: refinement predicted to meet it, once per sequence in two dimensions (docs/accuracy.md,
#: "The accuracy controller")
HOPE = 1.5


def choose(candidates: list[Candidate], accuracy: float, now: float, hope: float = 1.0) -> Candidate | None:
    """The cheapest candidate predicted to meet ``accuracy``; else the cheapest of those predicted
    within :data:`PREDICTION_SHARPNESS` of the lowest that lower ``now`` (the current error)
    by :data:`REQUIRED_GAIN`; else None. A candidate whose prediction is NaN is a refinement
    the estimate itself needs (a part could not be measured at this resolution) and is taken
    first. With ``hope`` > 1, a finer grid (a candidate whose name has ``points``: one more FMG
    grid, whose extrapolation the prediction leaves out) of a lower cost rank than that choice
    and predicted (or ``hoped``) within ``hope`` times ``accuracy`` is taken instead (the lowest
    of those)."""
    unknown = [c for c in candidates if math.isnan(c.predicted)]
    if unknown:
        return min(unknown, key=lambda c: c.rank)
    ok = [c for c in candidates if math.isfinite(c.predicted)]
    if not ok:
        return None
    meeting = [c for c in ok if c.predicted <= accuracy]
    if meeting:
        best = min(meeting, key=lambda c: (c.rank, c.predicted))
    else:
        lowest = min(c.predicted for c in ok)
        # an unknown current error (NaN) is improved by any finite prediction; a cheaper
        # candidate that gains too little does not hide a dearer one that gains enough
        # (docs/accuracy.md, the controller's rules)
        gaining = [c for c in ok if c.predicted <= PREDICTION_SHARPNESS * lowest
                   and not c.predicted >= REQUIRED_GAIN * now]
        if not gaining:
            return None
        best = min(gaining, key=lambda c: (c.rank, c.predicted))

    def hoped(c: Candidate) -> float:
        return c.predicted if math.isnan(c.hoped) else min(c.hoped, c.predicted)

    near = [c for c in ok if c.rank < best.rank and "points" in c.what and hoped(c) <= hope * accuracy]
    return min(near, key=lambda c: (hoped(c), c.rank)) if near else best


def fallback_gains(physics: Controlled, last: tuple[Any, float], at: Resolution, safe: Resolution) -> bool:
    """Whether ``safe``, one grid finer than the last converged solve ``at`` (``last``: its
    result and estimated error), is worth solving after a larger refinement failed: unless the
    physics offers it as a candidate predicted to lower the error by less than
    :data:`REQUIRED_GAIN` (a transient run whose time part dominates gains nothing from a finer
    grid at the same step)."""
    res, worst = last
    if res is None or math.isnan(worst):
        return True
    same = [c for c in physics.candidates(res, at) if c.at == safe and math.isfinite(c.predicted)]
    return not same or min(c.predicted for c in same) < REQUIRED_GAIN * worst


def predicted_seconds(last_round: float, points: int, to: Resolution, dimensions: int,
                      dt: float = 1.0) -> float:
    """Wall time of a refinement to ``to`` from ``last_round``, the seconds the last solve and
    its estimate took on ``points`` at the time step scale ``dt``: the multilevel work grows as
    the number of unknowns, ``((n' - 1)/(n - 1))^dimensions``, and a transient run's as its
    number of steps, ``dt/dt'``; a tolerance or nz step costs about as much again."""
    return (last_round * max(1.0, (to.points - 1) / max(points - 1, 1)) ** dimensions
            * max(1.0, dt / to.dt))


@dataclass
class ControlOutcome:
    """Outcome of :func:`control`."""

    #: the returned solve: the one that met the target, else the most accurate converged one,
    #: else (nothing converged) the last failed one
    result: Any
    #: its estimated larger film error (NaN when unknown or nothing converged)
    worst: float
    #: whether a converged solve met the target (True without a target)
    met: bool
    #: whether any solve converged
    converged: bool
    steps: list[Refinement]
    #: why the refinement stopped short of the target ("" when it did not)
    why: str
    wall_s: float
    #: the last solve made (the returned one unless a finer solve failed or missed more)
    last: Any = None
    #: whether the time budget ended the sequence (a solve stopped by it, or a refinement
    #: not started for it)
    budget_spent: bool = False


def control(physics: Controlled, start: Resolution, accuracy: float | None, *, refine: bool = True,
            time_budget: float = math.inf, max_points: int | None = None,
            progress: Callable[[str], None] | None = None, started: float | None = None,
            fallback: Resolution | None = None) -> ControlOutcome:
    """Solve at ``start``, estimate, and refine until the estimated film errors meet
    ``accuracy`` (relative; None: judge the iteration only) or a budget is spent.

    ``refine=False`` judges the first solve only (an explicit grid or box). ``time_budget``
    (seconds) bounds the sequence: a refinement whose predicted time
    (:func:`predicted_seconds`) exceeds what is left is not started; a solve already running
    is not interrupted. ``max_points`` bounds the fallback of a failed large step (one grid
    finer than the last converged solve). ``progress(text)`` receives one line per solve and,
    before each refinement, its predicted time. ``started`` (a ``time.perf_counter()``
    value) is when the sequence began, if before this call (its budget and wall count from it).
    ``fallback``: where to go on when ``start`` (a chosen start, such as a wider box) fails
    before any solve converged (the plain start the choice replaced).

    A solve that checks the budget between its iterations (:func:`check_deadline`) is stopped
    when it runs out; the sequence then ends with the most accurate converged solve so far
    (or, with none, as failed), its ``why`` naming the budget.
    """
    t0 = time.perf_counter() if started is None else started
    scope = _STOP_SCOPE.get()
    # only the outermost sequence keeps its answer on a stop: an inner one (a probe's, a
    # thermal solve's isothermal start) lets the stop reach it
    keeps = scope is not None and scope.depth == 0 and scope.stop is None
    if scope is not None:
        scope.depth += 1
    try:
        with deadline(time_budget, t0):
            return _control(physics, start, accuracy, refine, time_budget, max_points, progress, t0,
                            fallback, scope if keeps else None)
    finally:
        if scope is not None:
            scope.depth -= 1


def _control(physics: Controlled, start: Resolution, accuracy: float | None, refine: bool,
             time_budget: float, max_points: int | None, progress: Callable[[str], None] | None,
             t0: float, fallback: Resolution | None, scope: StopScope | None = None) -> ControlOutcome:
    if scope is None:
        return _sequence(physics, start, accuracy, refine, time_budget, max_points, progress, t0, fallback)
    kept: dict[str, Any] = {}
    try:
        return _sequence(physics, start, accuracy, refine, time_budget, max_points, progress, t0,
                         fallback, kept)
    except BaseException as exc:
        stop = signal_cause(exc)
        if stop is None or "best" not in kept:
            raise
        scope.stop = stop
        why = f"{stop_name(stop)} during {kept['doing']}"
        if progress is not None:
            progress(f"{why}: keeping the most accurate finished solve ({time.perf_counter() - t0:.1f} s)")
        res, worst = kept["best"]
        return ControlOutcome(res, worst, False, True, kept["steps"], why, time.perf_counter() - t0,
                              kept.get("last"), False)


def _sequence(physics: Controlled, start: Resolution, accuracy: float | None, refine: bool,
              time_budget: float, max_points: int | None, progress: Callable[[str], None] | None,
              t0: float, fallback: Resolution | None, kept: dict[str, Any] | None = None) -> ControlOutcome:
    """The loop of :func:`control`; ``kept`` (when given) follows the most accurate finished
    solve, the resolution being solved and the record, for a stop to return."""
    if kept is None:
        kept = {}
    round_t0 = t0
    steps: list[Refinement] = []
    kept["steps"] = steps
    limit = max_points if max_points is not None else 1 << 30

    def say(what: str, at: Resolution) -> None:
        if progress is not None:
            progress(f"{at.points} points, box x{at.box:g}: {what} ({time.perf_counter() - t0:.1f} s)")

    def done(result: Any, worst: float, met: bool, ok: bool, why: str = "") -> ControlOutcome:
        return ControlOutcome(result, worst, met, ok, steps, why, time.perf_counter() - t0, last, spent)

    best: tuple[Any, float] | None = None
    failed: set[Resolution] = set()
    last_ok: Resolution | None = None
    last_ok_out: tuple[Any, float] = (None, math.nan)
    at = start
    why = ""
    last: Any = None
    hoped = False
    spent = False
    while True:
        ts = time.perf_counter()
        kept["doing"] = f"the solve on {at.describe()}"
        res = last = physics.solve(at)
        kept["last"] = last
        if not physics.converged(res):
            reason = physics.failure(res)
            say(reason.split(":")[0], at)
            steps.append(Refinement(at.points, at.box, at.tol, math.nan, math.nan,
                                    time.perf_counter() - ts, nz=at.nz))
            if time.perf_counter() - t0 >= time_budget:
                # no remedy or fallback can run: the budget is spent
                spent = True
                why = f"the time budget of {time_budget:g} s ran out during the solve on {at.describe()}"
                stop = " ran out at "  # the step a solve stopped at (TimeBudgetSpent), else its failure
                why += f", at {reason.split(stop, 1)[1]}" if stop in reason else f": {reason}"
                if best is None:
                    return done(res, math.nan, False, False, why)
                break
            if best is None and fallback is not None and fallback != at and fallback not in failed:
                failed.add(at)
                at, fallback = fallback, None
                continue
            fix = physics.remedy(res, at, best is None) if refine and accuracy is not None else None
            if fix is not None and fix.points <= limit and fix not in failed:
                failed.add(at)
                at = fix
                continue
            if best is None:
                return done(res, math.nan, False, False, reason)
            failed.add(at)
            safe = last_ok.finer() if last_ok is not None else None
            if (safe is not None and safe not in failed and safe.points <= limit and safe != at
                    and fallback_gains(physics, last_ok_out, last_ok, safe)):
                # a larger step failed: the smallest one, from the last converged solve
                at = safe
                continue
            why = f"the refinement to {at.describe()} did not converge ({reason})"
            break
        last_ok = at
        kept["doing"] = f"the error estimate of the solve on {at.describe()}"
        ec, em = physics.estimate(res, at, steps.append)
        worst = max(ec, em) if not (math.isnan(ec) or math.isnan(em)) else math.nan
        last_ok_out = (res, worst)
        # NaN counts as worst; of two solves whose error is not bounded (inf) the finer one
        if best is None or not best[1] <= worst or (math.isinf(worst) and math.isinf(best[1])):
            best = kept["best"] = (res, worst)
        met = accuracy is None or worst <= accuracy
        say(f"estimated error Hc {ec:.2%}, Hm {em:.2%}", at)
        if met or not refine:
            steps.append(Refinement(at.points, at.box, at.tol, ec, em, time.perf_counter() - ts, nz=at.nz))
            return done(res, worst, met, True)
        # one hopeful step per sequence (after it missed, the candidate predicted to meet), and
        # only where a cost rank is 4x the work: in one dimension a missed hope costs half
        # the step it was to save
        hope = HOPE if physics.dimensions >= 2 and not hoped else 1.0
        step = choose(physics.candidates(res, at), accuracy, worst, hope)
        hoped = hoped or (step is not None and step.predicted > accuracy)
        steps.append(Refinement(at.points, at.box, at.tol, ec, em, time.perf_counter() - ts,
                                nz=at.nz, next=step.what if step else ""))
        if step is not None and step.at in failed:
            why = f"the refinement to {step.at.describe()} did not converge before"
            break
        if step is None:
            why = physics.why_short(res, at)
            if best[0] is not res:
                # the answer is an earlier solve: say why this one is not it, not only why the
                # refinement stopped
                why = (f"the solve on {at.describe()} estimated {worst:.2g}, no better than the "
                       f"{best[1]:.2g} of the solve returned; from it, {why}")
            break
        now = time.perf_counter()
        recurring = getattr(physics, "recurring_seconds", None)
        base = recurring(at) if recurring is not None else None
        base = now - round_t0 if base is None else min(base, now - round_t0)
        cost = predicted_seconds(base, at.points, step.at, physics.dimensions, at.dt)
        left = time_budget - (now - t0)
        if left <= 0.0:
            why, spent = f"the time budget of {time_budget:g} s is spent", True
            break
        if cost > left:
            spent = True
            dt = f", time step x{step.at.dt:g}" if step.at.dt != 1.0 else ""
            why = (f"the refinement to {step.at.points} points (box x{step.at.box:g}, tolerance "
                   f"x{step.at.tol:g}{dt}) is predicted to take about {cost:.0f} s, more than the "
                   f"{left:.0f} s left of the time budget of {time_budget:g} s")
            break
        kept["doing"] = f"the refinement to {step.at.describe()}"
        say(f"refining, predicted about {cost:.0f} s", step.at)
        at = step.at
        round_t0 = time.perf_counter()
    return done(best[0], best[1], False, True, why)

