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
