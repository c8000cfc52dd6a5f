"""Lazy package exports: a package's public names are imported from their submodules on first
use, so the command line (which registers every layer's subcommands at each start of ``ehl``)
does not import solvers, numba kernels or FFTs it will not run (PEP 562)."""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any


def lazy_exports(package: str, names: dict[str, str],
                 namespace: dict[str, Any]) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """``(__getattr__, __dir__)`` for ``package`` whose public ``names`` map to submodules
    (``{"solve_x": "solver"}`` loads ``package.solver.solve_x``); a loaded name is cached in the
    package's ``namespace`` (its ``globals()``)."""

    def __getattr__(name: str) -> Any:
        if name in names:
            value = getattr(importlib.import_module(f".{names[name]}", package), name)
            namespace[name] = value
            return value
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(names))

    return __getattr__, __dir__
