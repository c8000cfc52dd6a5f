"""A transient run under the package's one accuracy controller
(:func:`~ehl_multigrid.multigrid.controller.control`): the time step and the grid are its
refinements.

A :class:`~ehl_multigrid.multigrid.controller.Resolution`'s ``dt`` scales the output step of
the first run; a run whose steps are sized by a local error tolerance (``time_tol``) takes
:data:`~.accuracy.TIGHTER_TOL` of the tolerance per halving (the pair of
:func:`~.accuracy.adaptive_time_error`). Its ``points`` is the grid along X; every run other
than the first takes the first run's time step (scaled), so runs on different grids share
their time levels.

Each answer's error has three parts. The time part comes from its pair, the run at twice the
step (fixed steps, :func:`~.accuracy.time_error`) or at half the step and
:data:`~.accuracy.TIGHTER_TOL` of the tolerance (:func:`~.accuracy.adaptive_time_error`). The
grid part comes from the same steps on the grids with half and a quarter of the intervals
(:func:`~.accuracy.grid_error`; the quarter only where it has :data:`MIN_PAIR_POINTS`). The
box part comes from the steady start of the run on that box (:func:`~.domain.box_part`); a line
run whose box the caller did not fix may double its inlet length at equal mesh
(``Resolution.box``, the step option ``box``). Runs are kept by resolution, so no run is made
twice: the run at ``dt`` that measured the time error of the answer at ``2 dt`` is the next time
refinement's answer, an answer's grid pairs are the grid refinement's, and the tighter run of
an adaptive pair the next answer.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

from ..model.errors import ConvergenceError, InputError
from ..multigrid.accuracy import DOMAIN_DECAY
from ..multigrid.controller import REQUIRED_GAIN, Candidate, ControlOutcome, Refinement, Resolution
from .accuracy import (
    GRID_MAX_ORDER,
    PREASYMPTOTIC_COURANT,
    TIGHTER_TOL,
    adaptive_time_error,
    courant,
    grid_error,
    time_error,
)
from .domain import box_part
from .result import TransientResult
from .stepping import MAX_STEPS

#: the smallest time step the sequence refines to, over the first run's: 64 times its steps
MIN_DT_SCALE = 1.0 / 64.0
#: the smallest time tolerance a run accepts (:func:`~.stepping.model_inputs`)
MIN_TIME_TOL = 1e-8
#: the coarsest grid (points along X) a grid pair is run on: a quarter of a 129-point point
#: grid (33) leaves a 50 um dent one mesh wide
MIN_PAIR_POINTS = 65


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
    points : the first run's grid (points along X).
    max_points : the finest grid a refinement may take (``points``: the grid is not refined,
        its part is still measured).
    on_answer : called with every completed run made as an answer (the first and each
        refinement), as it completes: a caller keeps the finished work of a sequence that is
        stopped.
    progress : called with one line of text before and after every run (its grid, step and
        purpose; the seconds it took).
    box_refinable : whether the inlet may be moved upstream (the step option ``box``: the inlet
        length scaled, at equal mesh); False where the caller fixed the box.
    accuracy : the target; where the box part alone reaches it and the box cannot be refined,
        no other refinement is made (none could meet it).
    box_measure : ``box_measure(run, line) -> (part or None, note)``, the box part of a
        completed run (:func:`~.domain.box_part`).
    """

    def __init__(self, run: Callable[..., TransientResult], *, dimensions: int, scheme: str = "bdf2",
                 time_tol: float | None = None, callback: Any = None, points: int = 0,
                 max_points: int | None = None,
                 on_answer: Callable[[TransientResult], None] | None = None,
                 progress: Callable[[str], None] | None = None, box_refinable: bool = False,
                 accuracy: float | None = None,
                 box_measure: Callable[[Any, bool], tuple[dict[str, float] | None, str]] = box_part) -> None:
        self.run, self.dimensions, self.scheme = run, dimensions, scheme
        self.box_measure = box_measure
        self.box_refinable, self.accuracy = box_refinable, accuracy
        self.time_tol, self.callback = time_tol, callback
        self.start = Resolution(points)
        self.max_points = points if max_points is None else max_points
        self.on_answer, self.progress = on_answer, progress
        self.order = 2 if scheme == "bdf2" else 1
        self.runs: dict[Resolution, TimeRun] = {}
        #: the time part of each estimated run ({"Hc", "Hm"}; None when not measured)
        self.parts: dict[Resolution, dict[str, float] | None] = {}
        #: the grid part of each estimated run ({"Hc", "Hm", "order_Hc", "order_Hm"}; None when
        #: not measured)
        self.grid_parts: dict[Resolution, dict[str, float] | None] = {}
        #: the box part of each box scale ({"Hc", "Hm"}; None when not measured) and how it was
        #: found
        self.box_parts: dict[float, dict[str, float] | None] = {}
        self.box_notes: dict[float, str] = {}
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
        """The first run, once it completed."""
        r = self.runs.get(self.start)
        return r.result if r is not None and r.error is None else None

    def _halvings(self, at: Resolution) -> int:
        return round(-math.log2(at.dt))

    def step_options(self, at: Resolution) -> dict[str, Any]:
        """The step options of the run at ``at`` over the first run's (none for the first):
        its time step scaled by ``at.dt`` and, on another grid, ``points``."""
        if at == self.start:
            return {}
        b = self.first
        if b is None:
            raise ValueError("a refined run needs the completed first run")
        opts: dict[str, Any] = {"dt": b.dt * at.dt, "steps": max(int(b.planned_steps / at.dt), 1),
                                "t_end": None, "checkpoint": None, "resume": None}
        if at.points != self.start.points:
            opts["points"] = at.points
        if at.box != self.start.box:
            opts["box"] = at.box
        if self.adaptive:
            opts["time_tol"] = self.time_tol * TIGHTER_TOL ** self._halvings(at)
        return opts

    @staticmethod
    def wider(at: Resolution) -> Resolution:
        """The inlet length doubled at equal mesh (line: twice the intervals)."""
        return replace(at, points=2 * (at.points - 1) + 1, box=2.0 * at.box)

    @staticmethod
    def coarser(at: Resolution) -> Resolution:
        """The same time step on the grid with half the intervals."""
        return replace(at, points=(at.points - 1) // 2 + 1)

    def limit(self, at: Resolution) -> str:
        """Why a run at ``at`` would be refused ("" when it would not)."""
        if at.points > self.max_points:
            return (f"the grid would have {at.points} points, more than the {self.max_points} allowed "
                    f"(max_points)")
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
        what = {"solve": "run", "pair": "pair run"}.get(purpose, purpose)
        if self.progress is not None:
            b = self.first
            step = f"dT = {b.dt * at.dt:.4g}" if b is not None else "the first step"
            self.progress(f"{what} on {at.points} points, {step}")
        try:
            result = self.run(self.callback if at == self.start else None, **self.step_options(at))
        except ConvergenceError as exc:
            result, error = getattr(exc, "partial", None), exc
        except InputError as exc:
            if at == self.start:
                raise  # the caller's input: refused as without a target
            error = exc
        r = self.runs[at] = TimeRun(at, result, error, time.perf_counter() - t0, purpose)
        if self.progress is not None:
            self.progress(f"{what} on {at.points} points {'done' if self.converged(r) else 'failed'} "
                          f"in {r.wall_s:.1f} s")
        return r

    # -- Controlled ----------------------------------------------------------------------------------
    def solve(self, at: Resolution) -> TimeRun:
        self.solved.append(at)
        r = self._run(at, "solve")
        if self.on_answer is not None and self.converged(r):
            self.on_answer(r.result)
        return r

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
        """The time part and the grid part of ``result``, each measured by its own runs
        (:meth:`time_part`, :meth:`grid_part`); their sum, NaN when either is unknown."""
        self.answers.append(at)
        t = self.time_part(result, at, record)
        g = self.grid_part(result, at, record)
        d = self.box_of(result, at)
        if t is None or g is None or d is None:
            return math.nan, math.nan
        return t["Hc"] + g["Hc"] + d["Hc"], t["Hm"] + g["Hm"] + d["Hm"]

    def box_of(self, result: TimeRun, at: Resolution) -> dict[str, float] | None:
        """The box part of the runs on ``at``'s box, measured once per box on the steady start
        of ``result`` (:func:`~.domain.box_part`); None (with a note) when its probes fail."""
        if at.box not in self.box_parts:
            part, note = self.box_measure(result.result, self.dimensions == 1)
            self.box_parts[at.box], self.box_notes[at.box] = part, note
        if self.box_parts[at.box] is None:
            self._note(at, self.box_notes[at.box])
        return self.box_parts[at.box]

    def time_part(self, result: TimeRun, at: Resolution,
                  record: Callable[[Refinement], None]) -> dict[str, float] | None:
        """The time part of ``result`` from its pair (:meth:`pair`); None (with a note) when
        the pair is refused or fails."""
        other = self.pair(at)
        second = (f"the run at {TIGHTER_TOL:g} of the time tolerance and half the step" if self.adaptive
                  else "the run at twice the time step")
        why = self.limit(other)
        if why:
            self.parts[at] = None
            self.notes[at] = f"time error not measured: {second} is refused ({why})"
            return None
        new = other not in self.runs
        p = self._run(other, "pair")
        if new:
            record(Refinement(other.points, 1.0, 1.0, math.nan, math.nan, p.wall_s, "time pair"))
        if isinstance(p.error, InputError):  # beyond what the feature or the tolerance allows
            self.parts[at] = None
            self.notes[at] = (f"time error not measured: {second} is refused ({p.error})"
                              + ("" if self.adaptive else "; a smaller dt allows it"))
            return None
        if not self.converged(p):
            self.parts[at] = None
            self.notes[at] = f"{second} for the time error failed: {self.failure(p)}"
            return None
        fine, coarse = result.result, p.result
        terr = adaptive_time_error(fine, coarse) if self.adaptive else time_error(fine, coarse)
        self.parts[at] = terr
        return terr

    def grid_part(self, result: TimeRun, at: Resolution,
                  record: Callable[[Refinement], None]) -> dict[str, float] | None:
        """The grid part of ``result`` from the same steps on the grids with half and a quarter
        of its intervals (the quarter where it has :data:`MIN_PAIR_POINTS`); None (with a note)
        when the grid with half the intervals is too coarse or its run fails."""
        grids = [self.coarser(at)]
        if self.coarser(grids[0]).points >= MIN_PAIR_POINTS:
            grids.append(self.coarser(grids[0]))
        if grids[0].points < MIN_PAIR_POINTS:
            self.grid_parts[at] = None
            self._note(at, f"grid error not measured: the grid with half the intervals has "
                           f"{grids[0].points} points, fewer than {MIN_PAIR_POINTS}")
            return None
        runs = []
        for g in grids:
            new = g not in self.runs
            r = self._run(g, "pair")
            if new:
                record(Refinement(g.points, 1.0, 1.0, math.nan, math.nan, r.wall_s, "grid pair"))
            if not self.converged(r):
                if g is grids[0]:
                    self.grid_parts[at] = None
                    self._note(at, f"grid error not measured: the run on {g.points} points failed: "
                                   f"{self.failure(r)}")
                    return None
                break  # two grids: first order
            runs.append(r.result)
        gerr = grid_error(result.result, runs)
        self.grid_parts[at] = gerr
        return gerr

    def _note(self, at: Resolution, text: str) -> None:
        self.notes[at] = f"{self.notes[at]}; {text}" if at in self.notes else text

    def _stalled(self, at: Resolution) -> tuple[float, float] | None:
        """``(now, before)``: the time error of ``at`` and of the answer one step coarser, when
        halving the step lowered it by less than :data:`REQUIRED_GAIN`."""
        now, before = self.parts.get(at), self.parts.get(replace(at, dt=2.0 * at.dt))
        if now is None or before is None:
            return None
        a, b = max(now[k] for k in ("Hc", "Hm")), max(before[k] for k in ("Hc", "Hm"))
        return (a, b) if not a < REQUIRED_GAIN * b else None

    def _time_order(self, at: Resolution) -> int:
        """The order the time part is predicted to fall at when the step is halved from ``at``:
        first where the run at ``at`` moves a mesh size per step or more (its pair then did, by
        more), the scheme's otherwise."""
        r = self.runs.get(at)
        if r is not None and r.result is not None and courant(r.result) >= PREASYMPTOTIC_COURANT:
            return 1
        return self.order

    def candidates(self, result: TimeRun, at: Resolution) -> list[Candidate]:
        """Halve the time step; double the grid (the same step); both. Each predicted from the
        parts measured at ``at`` (NaN where the part that would fall is unknown: the finer run
        measures it)."""
        t, g = self.parts.get(at), self.grid_parts.get(at)
        d = self.box_parts.get(at.box)

        def left(time_factor: float, grid_factor: float, box_factor: float = 1.0) -> float:
            if t is None or g is None or d is None:
                return math.nan
            return max(t[k] * time_factor + g[k] * grid_factor + d[k] * box_factor for k in ("Hc", "Hm"))

        def grid_factor() -> float:
            if g is None:
                return math.nan
            orders = [g[f"order_{k}"] for k in ("Hc", "Hm")]
            p = min(orders) if all(math.isfinite(o) for o in orders) else 1.0
            return 0.5 ** min(p, GRID_MAX_ORDER)

        wide = self.wider(at)
        box_ok = self.box_refinable and self.dimensions == 1 and not self.limit(wide)
        if d is None:
            # its probes failed: only a run on another box measures the box part again (tried
            # once)
            return [Candidate("box", wide, 0, math.nan)] if box_ok and at.box == self.start.box else []
        if not box_ok and self.accuracy is not None and max(d.values()) >= self.accuracy:
            return []  # the box part alone misses the target and stays (why_short says so)
        out = []
        dt_finer = replace(at, dt=0.5 * at.dt)
        time_ok = not (dt_finer.dt < MIN_DT_SCALE or self.limit(dt_finer) or self._stalled(at) is not None)
        tf = 0.5 ** self._time_order(at)
        if time_ok:
            out.append(Candidate("time_tol" if self.adaptive else "dt", dt_finer, 0, left(tf, 1.0)))
        grid_finer = at.finer()
        if not self.limit(grid_finer):
            # at the same step the finer grid moves more mesh sizes per step, and its time
            # pair may drop to first order: the time part is assumed unchanged
            out.append(Candidate("points", grid_finer, self.dimensions - 1, left(1.0, grid_factor())))
            both = replace(grid_finer, dt=0.5 * at.dt)
            if time_ok and not self.limit(both):
                out.append(Candidate("points+dt", both, self.dimensions, left(tf, grid_factor())))
        if box_ok and t is not None and g is not None:
            # the same mesh, steps and time step on the longer box: the grid and time parts are
            # assumed unchanged (measured again by its own pairs)
            out.append(Candidate("box", wide, 0, left(1.0, 1.0, 1.0 / DOMAIN_DECAY)))
        # a part not measured (its pair refused or failed): only a refinement of its own kind
        # measures it (the finer run's pair is this run)
        return [c for c in out if not (t is None and c.what == "points") and not (g is None and c.what == "dt")]

    def why_short(self, result: TimeRun, at: Resolution) -> str:
        finer = replace(at, dt=0.5 * at.dt)
        why = []
        stalled = self._stalled(at)
        if stalled is not None:
            why.append(f"halving the time step lowered the time error by less than "
                       f"{1.0 - REQUIRED_GAIN:.0%} ({stalled[1]:.2g} -> {stalled[0]:.2g}): what is left is "
                       f"not the step's (the step tolerance, or the film's own scale of time)")
        elif finer.dt < MIN_DT_SCALE:
            why.append(f"the time step is {at.dt:g} of the first run's, the smallest the sequence takes")
        elif self.limit(finer):
            why.append(self.limit(finer))
        if self.limit(at.finer()):
            why.append(self.limit(at.finer()))
        d, t, g = self.box_parts.get(at.box), self.parts.get(at), self.grid_parts.get(at)
        if at.box in self.box_parts and d is None:
            why.append(self.box_notes[at.box])
        if d is not None and t is not None and g is not None and \
                max(d.values()) >= max(t[k] + g[k] for k in d) / 2.0:
            run = self.runs[at].result
            fixed = ("the box is fixed (xmin given)" if self.dimensions == 1 else
                     "a point run's box is not refined")
            why.append(f"the box's truncation leaves Hc {d['Hc']:.2g}, Hm {d['Hm']:.2g} (inlet at X = "
                       f"{float(run.X[0]):g}) and {fixed}: a longer box (xmin further upstream) lowers it")
        return "; ".join(why) or "no refinement is predicted to help"

    # -- what the sequence did ---------------------------------------------------------------------------
    def actions(self, out: ControlOutcome, accuracy: float) -> tuple[str, ...]:
        """One line per refinement of the sequence and, when it stopped short, why."""
        lines = []
        runs = {at: r.result for at, r in self.runs.items() if r.result is not None}

        def where(at: Resolution) -> str:
            res = runs.get(at)
            box = f", inlet at X = {float(res.X[0]):g}" if res is not None and at.box != 1.0 else ""
            return (f"{at.points} points, dT = {res.dt:.4g}{box}" if res is not None
                    else f"{at.points} points, time step x{at.dt:g}")

        def parts(at: Resolution) -> str:
            t, g, d = self.parts.get(at), self.grid_parts.get(at), self.box_parts.get(at.box)
            tt = f"time Hc {t['Hc']:.2g}, Hm {t['Hm']:.2g}" if t is not None else "time not measured"
            gg = f"grid Hc {g['Hc']:.2g}, Hm {g['Hm']:.2g}" if g is not None else "grid not measured"
            dd = f"box Hc {d['Hc']:.2g}, Hm {d['Hm']:.2g}" if d is not None else "box not measured"
            return f"{tt}; {gg}; {dd}"

        for a, b in zip(self.answers, self.answers[1:], strict=False):
            what = []
            if b.box != a.box:
                what.append("inlet length doubled")
            elif b.points != a.points:
                what.append("grid doubled")
            if b.dt != a.dt:
                what.append(f"time tolerance x{TIGHTER_TOL:g} and output step halved" if self.adaptive
                            else "time step halved")
            lines.append(f"{' and '.join(what)}: {where(a)} -> {where(b)} ({parts(a)}; above the "
                         f"accuracy {accuracy:g})")
        for at in (at for at in self.solved if at not in self.answers):
            lines.append(f"the refinement to {where(at)} did not complete: {self.failure(self.runs[at])}")
        if out.why:
            lines.append(f"not refined further: {out.why}")
        return tuple(lines)
