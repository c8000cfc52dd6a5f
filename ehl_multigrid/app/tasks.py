"""Tasks: units of work that the sweep runner and the main job can run on a scene.

A task is a callable ``task(scene, **options) -> dict`` returning scalars (numbers, strings,
bools, or 1-D lists) and optionally, under the key ``"result"``, a
:class:`~ehl_multigrid.model.results.Result` that the caller saves. Tasks are found through the
``ehl.tasks`` entry-point group, so layers above the core add theirs without the core
importing them.
"""

from __future__ import annotations

from collections.abc import Callable
from importlib.metadata import entry_points
from typing import Any

from ..model.errors import InputError
from ..model.scene import Scene


def fit_task(scene: Scene, **options: Any) -> dict[str, Any]:
    """Hertz, Moes groups and fitted central film of the scene (no solver)."""
    if options:
        raise InputError(f"task 'fit' takes no options, got {sorted(options)}")
    return {k: v for k, v in scene.summary().items() if not isinstance(v, str)}


#: physics a film task solves (a transient run is a time series, not one film)
FILM_PHYSICS = ("steady", "starved", "thermal")


def film_task(scene: Scene, *, physics: str | None = None, accuracy: float | None = 0.005,
              **options: Any) -> dict[str, Any]:
    """The solved film of the scene through the front door :func:`ehl_multigrid.solve`: films
    (Moes-scaled and in metres), their stated errors and status, the grid, the cost, and the
    fitted central film for the scene's supply (:meth:`Scene.supplied_film_fit`: a starved
    scene's is reduced by Chevalier's (6.1)) with the solve's deviation from it (the check a
    design tool's fit needs).

    ``physics``: ``"steady"``, ``"starved"`` or ``"thermal"`` (None: starved for a finite
    ``[supply] hoil``, else steady); ``accuracy`` as for ``ehl_multigrid.solve`` (``null``:
    judged on the iteration); other options are the solver's (``points``, ``max_points``,
    ``time_budget``, ...). The case keeps its :class:`~ehl_multigrid.model.results.Result`
    (fields and scene) under ``"result"``; a failed solve is a row with its status, not an
    error, so a map shows where the solver fails.
    """
    from .. import front

    if physics is not None and physics not in FILM_PHYSICS:
        raise InputError(f"task 'film': physics = {physics!r} is not one of {list(FILM_PHYSICS)}")
    sol = front.solve(scene, physics=physics, accuracy=accuracy, options=options or None)
    Hc_fit, hc_fit = scene.supplied_film_fit()
    row: dict[str, Any] = {
        # (the sweep's own "status" column says whether the case ran: the solve's is its own)
        "physics": sol.physics, "solve_status": sol.status.label, "converged": bool(sol.success),
        "Hc": sol.Hc, "Hm": sol.Hm, "hc": sol.hc, "hm": sol.hm,
        "Hc_error": sol.error.Hc, "Hm_error": sol.error.Hm, "error_dominant": sol.error.dominant or "",
        "points": sol.grid.points if sol.grid is not None else 0,
        "solve_wall_s": sol.outcome.wall_s, "work_units": sol.outcome.work_units,
        "hc_fit": hc_fit, "Hc_fit": Hc_fit, "hc_over_fit": sol.hc / hc_fit if hc_fit > 0 else float("nan"),
    }
    if sol.raw is not None and sol.fields:
        row["result"] = sol.to_result()
    return row


_REGISTERED: dict[str, Callable[..., dict[str, Any]]] = {}


def register_task(name: str, func: Callable[..., dict[str, Any]]) -> None:
    """Register a task in this process (for scripts and tests; entry points are the normal way).

    Process executors started with ``spawn`` do not see it; threads and in-process dask do.
    """
    _REGISTERED[name] = func


def available_tasks() -> list[str]:
    return sorted(set(_REGISTERED) | {ep.name for ep in entry_points(group="ehl.tasks")})


def get_task(name: str) -> Callable[..., dict[str, Any]]:
    if name in _REGISTERED:
        return _REGISTERED[name]
    eps = {ep.name: ep for ep in entry_points(group="ehl.tasks")}
    if name not in eps:
        raise InputError(f"task {name!r} is not available; installed tasks: {available_tasks()}")
    return eps[name].load()
