"""One front door (issue 42): a film is solved through ``ehl_multigrid.solve`` and no package
exports another film-solve entry point. The solvers behind the front door stay importable by
module path for the package itself, its tests and validation scripts, but no ``__all__``
lists them."""

from __future__ import annotations

import importlib
import pkgutil
import re

import pytest

#: the rule: a public name that reads as a solve ("solve", "solver"), a curve of solves or a
#: solve's start is a film-solve entry point unless it is listed here with why it is not one
FILM_SOLVE_NAME = re.compile(r"solve|_curve$|_start$", re.I)
NOT_FILM_SOLVES = {
    ("ehl_multigrid", "solve"): "the front door itself",
    ("ehl_multigrid.multigrid", "MultilevelSolver"): "the FAS driver over a contact's grid hierarchy: "
                                                      "no problem of its own",
    ("thermal", "solve_traction"): "friction of the thermal model on a given film (Hertz or solved)",
    ("thermal", "traction_curve"): "the same over slips: no film is solved",
    ("thermal", "solve_thermal_line"): "temperature and shear across a given film profile",
    ("thermal", "solve_thermal_lines"): "a batch of those",
    ("mixed", "stribeck_curve"): "load sharing and friction on the fitted film: no film is solved",
}
#: the solvers behind the front door: internal, still importable by module path
INTERNAL_SOLVERS = {
    "ehl_multigrid.line": ("solve_line", "solve_line_problem", "line_solver"),
    "ehl_multigrid.point": ("solve_point", "solve_fas", "solve_newton_amg", "point_solver"),
    "ehl_multigrid.starved": ("solve_starved_line", "solve_starved_scene", "solve_starved_problem",
                              "solve_starved_point", "solve_starved_point_scene"),
    "ehl_multigrid.transient": ("solve_transient_line", "solve_transient_point"),
    "thermal.tehl": ("solve_tehl_line", "solve_tehl_line_starved", "tehl_traction_curve", "isothermal_start",
                     "solve_tehl_point", "solve_tehl_to_accuracy"),
}


def _packages() -> list[str]:
    names = []
    for top in ("ehl_multigrid", "thermal", "mixed"):
        mod = importlib.import_module(top)
        names.append(top)
        names += [m.name for m in pkgutil.walk_packages(mod.__path__, f"{top}.") if m.ispkg]
    return names


PACKAGES = _packages()


def test_the_packages_are_found():
    assert {"ehl_multigrid", "ehl_multigrid.line", "ehl_multigrid.point", "ehl_multigrid.starved",
            "ehl_multigrid.transient", "thermal", "thermal.tehl", "mixed"} <= set(PACKAGES)


@pytest.mark.parametrize("package", PACKAGES)
def test_no_package_exports_a_film_solve_other_than_the_front_door(package):
    mod = importlib.import_module(package)
    public = getattr(mod, "__all__", [])
    solves = [n for n in public if FILM_SOLVE_NAME.search(n) and (package, n) not in NOT_FILM_SOLVES]
    assert solves == [], f"{package}.__all__ exports film-solve entry points {solves}: solve through " \
                         f"ehl_multigrid.solve"
    for name in INTERNAL_SOLVERS.get(package, ()):
        assert name not in public


def test_the_front_door_is_the_top_level_solve():
    import ehl_multigrid
    from ehl_multigrid.front import solve

    assert "solve" in ehl_multigrid.__all__ and ehl_multigrid.solve is solve


@pytest.mark.parametrize("package, name", [(p, n) for p, names in INTERNAL_SOLVERS.items() for n in names])
def test_the_solvers_behind_the_front_door_stay_importable_from_their_package(package, name):
    assert callable(getattr(importlib.import_module(package), name))
