"""Old import paths of modules that moved, kept working for one release.

``ehl_multigrid.scene`` is now ``ehl_multigrid.model.scene``, ``ehl_multigrid.cli`` is now
``ehl_multigrid.app.cli`` and so on (:data:`MOVED`). A finder on ``sys.meta_path`` answers the
old names: importing one warns with a :class:`DeprecationWarning` that names the new path and
returns the new module itself, so ``import ehl_multigrid.scene``,
``from ehl_multigrid.scene import load_scene`` and ``from ehl_multigrid import scene`` all give
the object that ``ehl_multigrid.model.scene`` is.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import sys
import warnings
from types import ModuleType

#: old dotted name -> new dotted name
MOVED: dict[str, str] = {
    **{f"ehl_multigrid.{m}": f"ehl_multigrid.model.{m}" for m in (
        "convergence", "errors", "fits", "groups", "hertz", "lubricant", "results", "scene",
        "solids")},
    **{f"ehl_multigrid.{m}": f"ehl_multigrid.app.{m}" for m in (
        "cli", "mainjob", "plan", "sweep", "tasks")},
    "ehl_multigrid.gridchoice": "ehl_multigrid.multigrid.gridchoice",
    "ehl_multigrid.app.gridchoice": "ehl_multigrid.multigrid.gridchoice",
    "ehl_multigrid.solve_cli": "ehl_multigrid.app.solve",
    "ehl_multigrid.line.cli": "ehl_multigrid.app.line_cli",
    "ehl_multigrid.line.plots": "ehl_multigrid.app.line_plots",
    "ehl_multigrid.point.cli": "ehl_multigrid.app.point_cli",
    "ehl_multigrid.point.plots": "ehl_multigrid.app.point_plots",
}

REMOVAL = "will be removed in the next release"


class _MovedModuleFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds and "loads" an old name by importing the new module and handing it back."""

    def __init__(self) -> None:
        self._own_specs: dict[str, importlib.machinery.ModuleSpec | None] = {}

    def find_spec(self, fullname: str, path=None, target=None):
        if fullname not in MOVED:
            return None
        return importlib.machinery.ModuleSpec(fullname, self)

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType:
        new = MOVED[spec.name]
        # stacklevel 2 skips the import machinery's frames and names the importing line
        warnings.warn(f"{spec.name} moved to {new}; import it from there ({spec.name} {REMOVAL})",
                      DeprecationWarning, stacklevel=2)
        module = importlib.import_module(new)
        self._own_specs[spec.name] = getattr(module, "__spec__", None)
        return module

    def exec_module(self, module: ModuleType) -> None:
        # the import system set the module's __spec__ to the old name's spec; the module is the
        # new one and must keep its own (importlib.reload and pickling read it)
        module.__spec__ = self._own_specs.pop(module.__spec__.name)


_FINDER = _MovedModuleFinder()


def install() -> None:
    """Put the finder first on ``sys.meta_path`` (once)."""
    if not any(isinstance(f, _MovedModuleFinder) for f in sys.meta_path):
        sys.meta_path.insert(0, _FINDER)
