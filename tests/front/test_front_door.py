"""The front door's rules: which physics a problem gets, what input it refuses (naming the field,
the value and what is allowed), the one failure policy (a numerical failure is returned with
its status, never raised), the status table, and that ``import ehl_multigrid`` stays light."""

from __future__ import annotations

import ast
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import ehl_multigrid as ehl
from ehl_multigrid.front import decide_physics, status_of_error
from ehl_multigrid.model.errors import ConvergenceError, InputError
from ehl_multigrid.model.scene import Scene, load_scene
from ehl_multigrid.solution import ErrorEstimate, PartError, Status

ROOT = Path(__file__).resolve().parents[2]


def scene_with(name: str, **tables) -> Scene:
    d = load_scene(name).to_dict()
    d.update(tables)
    return Scene.from_dict(d)


# -- physics ---------------------------------------------------------------------------------------
def test_no_physics_picks_starved_for_a_finite_oil_supply_and_steady_otherwise():
    starved = scene_with("page63_line_500N", supply={"hoil": 1.5e-8})
    assert decide_physics(None, starved, None) == "starved"
    assert decide_physics(None, load_scene("page63_line_500N"), None) == "steady"
    assert decide_physics(None, None, ehl.MoesProblem("point", 20, 10)) == "steady"


def test_steady_physics_on_a_starved_scene_is_refused_naming_the_supply():
    starved = scene_with("page63_line_500N", supply={"hoil": 1.5e-8})
    with pytest.raises(InputError, match=r"\[supply\] hoil = 1\.5e-08 m.*physics = 'starved'"):
        ehl.solve(starved, physics="steady")


def test_starved_physics_on_a_flooded_scene_is_refused():
    with pytest.raises(InputError, match=r"\[supply\] hoil = inf m.*finite"):
        ehl.solve("page63_line_500N", physics="starved")


@pytest.mark.parametrize("physics", ["starved", "thermal", "transient"])
def test_physics_other_than_steady_need_a_scene(physics):
    with pytest.raises(InputError, match=f"physics = '{physics}' needs a scene"):
        ehl.solve(ehl.MoesProblem("line", 20, 10), physics=physics)


def test_a_transient_run_needs_a_feature_table():
    with pytest.raises(InputError, match=r"no \[feature\] table"):
        ehl.solve("page63_line_2000N", physics="transient")


def test_an_unknown_physics_is_refused_naming_the_allowed_ones():
    with pytest.raises(InputError, match=r"physics = 'magnetic'.*'steady', 'starved', 'thermal', 'transient'"):
        ehl.solve("default", physics="magnetic")


def test_the_thermal_physics_comes_from_the_layer_entry_point():
    from ehl_multigrid.front import registered_physics

    assert registered_physics()["thermal"].value == "thermal.front:solve_thermal"


# -- input -----------------------------------------------------------------------------------------
def test_an_unknown_option_is_refused_naming_it_and_the_accepted_ones():
    with pytest.raises(InputError, match=r"unknown option \['pointz'\].*accepted: \[.*'points'"):
        ehl.solve(ehl.MoesProblem("line", 20, 10), options={"pointz": 257})


def test_an_option_of_another_physics_is_refused():
    # half (the symmetric half domain) is a point contact's; a starved line has none
    starved = scene_with("page63_line_500N", supply={"hoil": 1.5e-8})
    with pytest.raises(InputError, match=r"\['half'\].*starved line"):
        ehl.solve(starved, options={"half": True})


def test_raise_on_failure_is_refused_as_the_front_door_never_raises_for_a_failure():
    with pytest.raises(InputError, match="raise_on_failure.*never raises"):
        ehl.solve(ehl.MoesProblem("line", 20, 10), options={"raise_on_failure": True})


def test_options_of_the_wrong_type_are_refused():
    from ehl_multigrid.multigrid.options import PointOptions

    with pytest.raises(InputError, match="PointOptions.*steady line"):
        ehl.solve(ehl.MoesProblem("line", 20, 10), options=PointOptions())
    with pytest.raises(InputError, match="must be a mapping"):
        ehl.solve(ehl.MoesProblem("line", 20, 10), options=[("points", 257)])


@pytest.mark.parametrize("accuracy", [0.0, 0.7, math.nan, "tight"])
def test_an_accuracy_outside_its_range_is_refused(accuracy):
    with pytest.raises(InputError, match=r"accuracy = .*\[1e-05, 0\.5\]"):
        ehl.solve(ehl.MoesProblem("line", 20, 10), accuracy=accuracy)


def test_a_problem_that_is_neither_a_scene_nor_moes_is_refused():
    with pytest.raises(InputError, match=r"problem = 42 \(int\)"):
        ehl.solve(42)
    with pytest.raises(InputError, match="scene 'no_such_scene'"):
        ehl.solve("no_such_scene")


@pytest.mark.parametrize("kw, field", [
    ({"contact": "roller", "M": 20, "L": 10}, "contact"),
    ({"contact": "line", "M": -1.0, "L": 10}, "M"),
    ({"contact": "line", "M": 20, "L": 50.0}, "L"),
    ({"contact": "point", "M": 20, "L": 10, "alpha": 1.0}, "alpha"),
    ({"contact": "line", "M": 20, "L": 10, "theta": 0.5}, "theta"),
    ({"contact": "elliptic", "M": 20, "L": 10, "theta": 1.0}, "theta"),
    ({"contact": "point", "M": 20, "L": 10, "viscosity": "eyring"}, "viscosity"),
])
def test_a_moes_problem_is_validated_at_construction_naming_the_field(kw, field):
    with pytest.raises(InputError, match=rf"^{field} = "):
        ehl.MoesProblem(**kw)


def test_a_moes_problem_fills_the_package_oil_defaults():
    from ehl_multigrid.model.constants import MOES_ONLY_DEFAULTS

    p = ehl.MoesProblem("elliptic", 20, 10, theta=0.25)
    assert p.oil == MOES_ONLY_DEFAULTS and p.solver_problem().theta == 0.25


# -- one failure policy --------------------------------------------------------------------------
def test_a_cycle_budget_of_zero_returns_a_failed_solution_instead_of_raising():
    sol = ehl.solve(ehl.MoesProblem("line", 20, 10), options={"points": 257, "max_cycles": 0})
    assert not sol.success and sol.status == Status.MAX_CYCLES
    assert "0 extra cycles" in sol.message
    assert math.isnan(sol.error.Hc) and not sol.error.meets_target
    assert sol.raw is not None and sol.raw.status_name == "max_cycles"


def test_a_grid_far_too_coarse_is_a_failed_solution_without_a_film():
    # M = 1000 on 33 points: the iteration diverges; its iterate is no film
    sol = ehl.solve(ehl.MoesProblem("point", 1000, 10), options={"points": 33})
    assert not sol.success and sol.status == Status.DIVERGED
    assert "too coarse" in sol.message and "513" in sol.message
    assert math.isnan(sol.Hc) and math.isnan(sol.Hm) and not sol.fields and sol.grid is None
    assert sol.raw.status_name == "diverged"  # what was computed is kept


def test_a_callback_that_stops_the_solve_gives_status_stopped():
    seen = []

    def stop(info):
        seen.append(info)
        raise StopIteration

    sol = ehl.solve(ehl.MoesProblem("line", 20, 10), options={"points": 257}, callback=stop)
    assert sol.status == Status.STOPPED and not sol.success and len(seen) == 1
    assert isinstance(seen[0], dict)


def test_a_raised_thermal_failure_is_returned_with_its_status():
    with pytest.warns(UserWarning, match="callback is not called"):
        sol = ehl.solve("appendix_c_line_4240N", physics="thermal", callback=print,
                        options={"points": 129, "nz": 8, "max_outer": 1})
    assert not sol.success and sol.status == Status.MAX_CYCLES
    assert "outer" in sol.message and "1 iterations" in sol.message
    assert math.isnan(sol.Hc) and not sol.fields


def test_a_failed_transient_step_keeps_the_completed_steps(monkeypatch):
    from ehl_multigrid.transient import solve as line_solve

    original = line_solve._LineStepper.solve_step
    calls = {"n": 0}

    def step(self):  # the start, then two good steps, then a NaN pressure
        calls["n"] += 1
        res = original(self)
        if calls["n"] > 3:
            self.hz.fine.P[3] = np.nan
        return res

    monkeypatch.setattr(line_solve._LineStepper, "solve_step", step)
    scene = scene_with("page63_line_2000N", feature={"kind": "bump", "amplitude": 1e-8, "width": 1e-5,
                                                     "x0": -3.0})
    sol = ehl.solve(scene, physics="transient", accuracy=None, options={"points": 129, "steps": 5})
    # the step converged but left a non-finite pressure: never a success
    assert not sol.success and sol.status == Status.DIVERGED
    assert "time step 3" in sol.message and "not finite" in sol.message
    assert not sol.details.complete and sol.details.steps == 2 and sol.raw.complete is False
    assert sol.Hc == sol.details.Hc_series[-1] > 0.0


def test_status_of_a_convergence_error_is_never_a_success():
    class Report:
        extra = {"status": "converged"}

    assert status_of_error(ConvergenceError("step failed", Report())) == Status.DIVERGED
    Report.extra = {"status": "stalled"}
    assert status_of_error(ConvergenceError("x", Report())) == Status.STALLED
    assert status_of_error(ConvergenceError("the film collapsed (min H = -1)")) == Status.FILM_NOT_POSITIVE
    assert status_of_error(ConvergenceError("TEHL: the isothermal start did not converge")) == \
        Status.START_FAILED


# -- the contract's types ------------------------------------------------------------------------------
def test_status_has_the_numbers_and_names_of_the_solvers_table():
    from ehl_multigrid.multigrid.result import STATUS

    assert {s.value: s.label for s in Status} == STATUS
    assert Status.CONVERGED == 0 and Status.from_label("mass_not_conserved") == Status.MASS_NOT_CONSERVED
    with pytest.raises(InputError, match="status = 'fine'"):
        Status.from_label("fine")


def test_the_dominant_part_is_the_largest_measured_one_and_the_target_is_judged():
    est = ErrorEstimate(0.004, 0.009, {"grid": PartError(0.003, 0.008), "domain": PartError(math.nan, math.nan),
                                       "iteration": PartError(0.001, 0.001)}, target=0.01)
    assert est.dominant == "grid" and est.meets_target
    assert not ErrorEstimate(0.004, 0.02, {}, target=0.01).meets_target
    assert not ErrorEstimate(0.004, math.nan, {}, target=0.01).meets_target  # unknown: not met
    assert not ErrorEstimate(0.004, 0.004, {}, target=None).meets_target  # nothing judged
    assert ErrorEstimate().dominant is None


# -- imports -------------------------------------------------------------------------------------
def test_importing_the_package_loads_no_solver():
    heavy = ("numba", "scipy.fft", "ehl_multigrid.line.solver", "ehl_multigrid.point.fas",
             "ehl_multigrid.multigrid.driver", "thermal")
    code = ("import sys, ehl_multigrid\n"
            f"print('loaded:' + ','.join(m for m in {heavy!r} if m in sys.modules))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip().splitlines()[-1] == "loaded:"


@pytest.mark.parametrize("module", ["ehl_multigrid/front.py", "ehl_multigrid/solution.py"])
def test_the_front_door_imports_neither_the_application_nor_the_layers_above(module):
    tree = ast.parse((ROOT / module).read_text())
    names = [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    names += [("." * n.level) + (n.module or "") for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    bad = [m for m in names if m.lstrip(".").split(".")[0] in ("app", "thermal", "mixed")
           or m.startswith(("ehl_multigrid.app", "thermal", "mixed"))]
    assert names and bad == []
