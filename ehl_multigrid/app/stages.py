"""What a stage of the main job (``ehl run``) receives and returns.

A stage is a callable ``stage(ctx: RunContext) -> StageOutput | None`` registered in the
``ehl.stages`` entry-point group; the layers above the core (thermal, mixed) provide theirs and
import only this module from the application. A leaf module: it imports nothing from the rest
of the application (the plan is seen through the small :class:`PlanView` protocol).

The plan is read-only to the stages: what a stage learns while it runs (a note, a setting that
departs from its decision, such as a film fit after a failed solve) goes into its
:class:`StageOutput`, and later stages read it there (:meth:`RunContext.setting`).

The later stages read the last solved film (the film stage's, or the thermal layer's coupled
thermal film that follows it) as a typed
:class:`~ehl_multigrid.model.solved_film.SolvedFilm` (:meth:`RunContext.film`; none when the film
is the fit or an estimate after a failed solve); a stage's
:class:`~ehl_multigrid.model.results.Result` is what goes to the HDF5 file.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol

from ..model.results import Result
from ..model.scene import Scene
from ..model.solved_film import SolvedFilm

#: the planner's ``tehl`` setting under which the thermal layer's film stage solves the coupled
#: film (:mod:`ehl_multigrid.app.plan` writes it, the stage reads it)
TEHL_STAGED = "coupled thermal EHL film (thermal film stage)"
#: the ``tehl`` setting of a starved point contact whose heat is expected to change the film by
#: more than the tolerance: no coupled solver covers it, so the film stage's isothermal film is
#: short of the target (status ``inaccurate``), never a success
TEHL_UNAVAILABLE = "isothermal film, short of the tolerance: no coupled thermal EHL for starved point contacts"


class PlanView(Protocol):
    """The planner's decisions as a stage reads them (``ehl_multigrid.app.plan.Plan``)."""

    fidelity: str
    tolerance: float

    def includes(self, model: str) -> bool:
        """Whether the plan includes ``model`` (``"thermal"``, ``"starvation"``, ...)."""
        ...

    def get(self, model: str) -> Any:
        """The decision on ``model`` (estimate, threshold, setting, reason)."""
        ...

    def to_dict(self) -> dict[str, Any]:
        """The plan as plain data (stored in every result's ``meta['plan']``)."""
        ...


@dataclass
class StageOutput:
    """What one stage of the main job produced."""

    name: str
    result: Result | None = None
    summary: dict[str, Any] = field(default_factory=dict)
    figures: list[Path] = field(default_factory=list)
    text: str = ""
    wall_s: float = float("nan")
    #: what the stage noted while it ran (in its section of the report and its result's meta)
    notes: list[str] = field(default_factory=list)
    #: the setting the stage used where it departs from its plan decision (e.g. "fit (solver
    #: fallback)" after a failed film solve); None: the decision's
    setting: str | None = None
    #: the stage's solved film, what later stages compute on (None: a fit or an estimate, and for
    #: stages that solve no film)
    film: SolvedFilm | None = None


@dataclass
class RunContext:
    """Everything a stage may read: scene, plan, output folder, earlier stages' results."""

    scene: Scene
    plan: PlanView
    outdir: Path
    plots: bool = True
    progress: bool = True
    outputs: dict[str, StageOutput] = field(default_factory=dict)
    #: seconds for the film stage's accuracy sequence (``ehl run --time-budget``); None: no bound
    time_budget: float | None = None
    #: largest grid the film stages may refine to (``ehl run --max-points``); None: the solver's
    max_points: int | None = None
    #: the film solves' keeper of a stop (:meth:`solve`)
    keeper: Any = field(default=None, repr=False)

    def solve(self, problem: Any, **kw: Any) -> Any:
        """A film stage's solve through the front door :func:`ehl_multigrid.solve`: a stop
        (Ctrl-C, SIGTERM) during its accuracy sequence returns the most accurate finished solve,
        and the main job raises the stop once the stage's output is kept."""
        from ..front import StopKeeper

        if self.keeper is None:
            self.keeper = StopKeeper()
        return self.keeper.solve(problem, **kw)

    def solve_limits(self) -> dict[str, Any]:
        """The options of a film stage's solve that ``ehl run`` sets: ``time_budget`` and
        ``max_points`` where given."""
        return {k: v for k, v in (("time_budget", self.time_budget), ("max_points", self.max_points))
                if v is not None}

    def result(self, name: str) -> Result | None:
        """The result of the earlier stage ``name``, or ``None`` if it did not run."""
        out = self.outputs.get(name)
        return out.result if out is not None else None

    def film(self) -> SolvedFilm | None:
        """The solved film the later stages compute on: the last one a stage produced (the
        thermal layer's coupled thermal film when that stage ran and succeeded, else the film
        stage's), or ``None`` when no stage solved one (the film is the fit or an estimate:
        Hertz pressure with a fitted film)."""
        films = [out.film for out in self.outputs.values() if out.film is not None]
        return films[-1] if films else None

    def setting(self, model: str) -> str:
        """The setting ``model`` ran with: its stage's own where it departed from the plan,
        else the plan's decision."""
        out = self.outputs.get(model)
        return out.setting if out is not None and out.setting else self.plan.get(model).setting

    def film_failure(self) -> str | None:
        """Why the film stage's film is an estimate (its solve failed), or ``None``: a stage
        computed on that film is not a success either and says so (converged false, exit 3)."""
        out = self.outputs.get("film")
        if out is None or not out.summary.get("solver_fallback") or self.film() is not None:
            # (a later stage's solved film, the coupled thermal one, replaces the estimate)
            return None
        return (f"computed on an estimated film, not a solved one: the film stage's solve failed "
                f"({out.summary.get('status')}: {out.summary.get('message')})")

    def mark_film_failure(self, summary: dict) -> dict:
        """``summary`` with ``converged`` false, ``status`` ``film_estimate`` and the reason
        when the film is an estimate (:meth:`film_failure`); unchanged otherwise."""
        why = self.film_failure()
        if why is not None:
            summary.update(converged=False, status="film_estimate", message=why)
        return summary
