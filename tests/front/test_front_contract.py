"""The front door ``ehl_multigrid.solve`` over every physics: the result contract means the
same for each (types, frozen solution, read-only fields), and each front-door solve gives
exactly the films, errors and status of the entry point it wraps, called directly with the
same arguments (the adapter changes no number)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import ehl_multigrid as ehl
from ehl_multigrid.model.scene import Scene, load_scene
from ehl_multigrid.solution import (
    ErrorEstimate,
    Grid,
    Outcome,
    PartError,
    Solution,
    StarvedDetails,
    Status,
    ThermalDetails,
    TransientDetails,
)

ACC = 0.005

# the tests read the module's solves (one per physics, the starved one about 3 s): one worker
# builds each of them once
pytestmark = pytest.mark.xdist_group("front_contract_physics")


def same(a, b) -> bool:
    """Equal, or both NaN (an estimate that was not measured)."""
    return a == b or (math.isnan(a) and math.isnan(b))


def starved_line_scene() -> Scene:
    d = load_scene("page63_line_500N").to_dict()  # flooded hc about 25 nm
    d["supply"] = {"hoil": 1.5e-8}
    return Scene.from_dict(d)


def bump_line_scene() -> Scene:
    d = load_scene("page63_line_2000N").to_dict()
    d["feature"] = {"kind": "bump", "amplitude": 1e-8, "width": 1e-5, "x0": -3.0}
    return Scene.from_dict(d)


# one small case of each physics, shared by the contract and the equality tests
@pytest.fixture(scope="module")
def steady_line():
    return ehl.solve(ehl.MoesProblem("line", 20, 10), options={"points": 257})


@pytest.fixture(scope="module")
def steady_point():
    return ehl.solve(ehl.MoesProblem("point", 20, 10), options={"points": 65})


@pytest.fixture(scope="module")
def starved_line():
    # physics=None: the scene's finite [supply] hoil picks the starved solver
    return ehl.solve(starved_line_scene(), options={"points": 257})


@pytest.fixture(scope="module")
def thermal_line():
    return ehl.solve("appendix_c_line_4240N", physics="thermal",
                     options={"points": 129, "nz": 8, "slip": 0.5})


@pytest.fixture(scope="module")
def transient_line():
    return ehl.solve(bump_line_scene(), physics="transient", options={"points": 129, "steps": 5})


PHYSICS = ["steady_line", "steady_point", "starved_line", "thermal_line", "transient_line"]


@pytest.mark.parametrize("name", PHYSICS)
def test_the_contract_has_the_same_typed_attributes_for_every_physics(name, request):
    sol = request.getfixturevalue(name)
    assert isinstance(sol, Solution)
    assert sol.physics == name.split("_")[0] and sol.contact in ("line", "point")
    for v in (sol.Hc, sol.Hm, sol.hc, sol.hm):
        assert isinstance(v, float)
    assert sol.Hc > sol.Hm > 0.0
    assert math.isnan(sol.hc) or sol.hc > sol.hm > 0.0
    assert isinstance(sol.outcome, Outcome) and isinstance(sol.success, bool)
    assert isinstance(sol.status, Status) and sol.success == (sol.status == Status.CONVERGED)
    assert sol.message == sol.outcome.message and isinstance(sol.message, str) and sol.message
    assert isinstance(sol.outcome.actions, tuple) and isinstance(sol.outcome.iterations, int)
    assert sol.outcome.wall_s > 0.0
    assert isinstance(sol.error, ErrorEstimate)
    assert isinstance(sol.error.Hc, float) and isinstance(sol.error.Hm, float)
    assert all(isinstance(p, PartError) for p in sol.error.parts.values())
    assert sol.error.dominant is None or sol.error.dominant in sol.error.parts
    assert isinstance(sol.grid, Grid) and sol.grid.points == sol.fields["X"].size
    assert {"X", "P", "H"} <= set(sol.fields)
    assert sol.fields["P"].shape == sol.fields["H"].shape
    summary = sol.summary()
    assert summary["status"] == sol.status.label and summary["Hc"] == sol.Hc
    assert all(v is None or isinstance(v, (bool, int, float, str)) for v in summary.values())


@pytest.mark.parametrize("name", PHYSICS)
def test_the_solution_is_frozen_and_its_fields_read_only(name, request):
    sol = request.getfixturevalue(name)
    with pytest.raises(dataclasses.FrozenInstanceError):
        sol.Hc = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        sol.outcome.success = True
    with pytest.raises(dataclasses.FrozenInstanceError):
        sol.error.Hc = 0.0
    with pytest.raises(TypeError):
        sol.fields["P"] = np.zeros(3)
    for arr in sol.fields.values():
        with pytest.raises(ValueError, match="read-only"):
            arr.flat[0] = 1.0
    with pytest.raises(TypeError):
        sol.error.parts["grid"] = PartError(0.0, 0.0)


def test_the_solvers_own_arrays_stay_writable_beside_the_read_only_fields(steady_line):
    # the fields are copies: the raw result (for the transition) is not altered
    assert steady_line.raw.P.flags.writeable
    assert not np.shares_memory(steady_line.raw.P, steady_line.fields["P"])
    assert np.array_equal(steady_line.raw.P, steady_line.fields["P"])


def test_the_physics_extends_the_contract_by_composition(steady_line, starved_line, thermal_line,
                                                         transient_line):
    assert steady_line.details is None
    assert isinstance(starved_line.details, StarvedDetails) and "theta" in starved_line.fields
    assert isinstance(thermal_line.details, ThermalDetails) and {"T", "Z", "tau"} <= set(thermal_line.fields)
    assert isinstance(transient_line.details, TransientDetails)
    d = transient_line.details
    assert d.times.size == d.Hc_series.size == d.steps + 1 == 6
    assert d.Hc_series[-1] == transient_line.Hc and not d.hc_series.flags.writeable


def test_steady_line_equals_solve_line_called_directly(steady_line):
    from ehl_multigrid.line import solve_line

    direct = solve_line(20, 10, points=257, accuracy=ACC, raise_on_failure=False)
    assert steady_line.Hc == direct.Hc and steady_line.Hm == direct.Hm
    assert steady_line.status.label == direct.status_name and steady_line.message == direct.message
    assert same(steady_line.error.Hc, direct.error.Hc) and same(steady_line.error.Hm, direct.error.Hm)
    names = {"grid": "grid", "domain": "domain", "iteration": "algebraic"}
    for part, old in names.items():
        assert steady_line.error.parts[part] == PartError(direct.error.budget[old]["Hc"],
                                                          direct.error.budget[old]["Hm"])
    assert steady_line.error.target == ACC
    assert steady_line.error.meets_target == (max(direct.error.Hc, direct.error.Hm) <= ACC)


def test_steady_point_equals_solve_point_called_directly_on_the_half_domain(steady_point):
    from ehl_multigrid.point import solve_point

    direct = solve_point(20, 10, points=65, accuracy=ACC, raise_on_failure=False)
    assert direct.half and steady_point.grid.half
    assert steady_point.Hc == direct.Hc and steady_point.Hm == direct.Hm
    assert steady_point.status.label == direct.status_name
    assert same(steady_point.error.Hc, direct.error.Hc) and same(steady_point.error.Hm, direct.error.Hm)
    assert np.array_equal(steady_point.fields["P"], direct.P)


def test_starved_line_equals_solve_starved_scene_called_directly(starved_line):
    from ehl_multigrid.starved import solve_starved_scene

    direct = solve_starved_scene(starved_line_scene(), points=257, accuracy=ACC, raise_on_failure=False)
    assert starved_line.physics == "starved"
    assert starved_line.Hc == direct.Hc and starved_line.Hm == direct.Hm
    assert starved_line.hc == direct.scalars["hc"]
    assert starved_line.status.label == direct.status_name
    assert same(starved_line.error.Hc, direct.error.Hc) and same(starved_line.error.Hm, direct.error.Hm)
    d = starved_line.details
    assert d.meniscus_x == direct.scalars["meniscus_x"] and d.Hc_flooded == direct.scalars["Hc_flooded"]
    assert d.mass_balance_error == direct.scalars["mass_balance_error"] and d.hoil == 1.5e-8


def test_thermal_line_equals_solve_tehl_to_accuracy_called_directly(thermal_line):
    from thermal.tehl.accuracy import solve_tehl_to_accuracy
    from thermal.tehl.line import TEHLOptions

    scene = load_scene("appendix_c_line_4240N")
    direct = solve_tehl_to_accuracy(scene, 0.5, TEHLOptions(points=129, nz=8), ACC, refine=False)
    r, est = direct.result, direct.estimate
    assert thermal_line.Hc == r.Hc and thermal_line.Hm == r.Hm and thermal_line.hc == r.hc
    assert same(thermal_line.error.Hc, est.Hc) and same(thermal_line.error.Hm, est.Hm)
    for part, old in {"grid": "grid_x", "nz": "grid_z", "domain": "domain", "iteration": "iteration"}.items():
        assert thermal_line.error.parts[part] == PartError(est.budget["Hc"][old], est.budget["Hm"][old])
    assert thermal_line.details.friction_coefficient == r.friction_coefficient
    assert thermal_line.details.T_max == r.T_max and thermal_line.details.nz == 8
    assert thermal_line.success == direct.accurate


def test_transient_line_equals_solve_transient_line_called_directly(transient_line):
    from ehl_multigrid.line.problem import LineProblem
    from ehl_multigrid.transient.scene_feature import feature_from_scene_table
    from ehl_multigrid.transient.solve import solve_transient_line

    scene = bump_line_scene()
    pb = LineProblem.from_scene(scene, xmin=-4.5)  # the inlet of 'ehl transient'
    feature, body = feature_from_scene_table(scene.feature, pb)
    direct = solve_transient_line(pb, feature, body=body, slide_roll=scene.slip, points=129, steps=5)
    d = transient_line.details
    scale = pb.b**2 / pb.R  # metres per Venner film unit, as 'ehl transient' scales
    assert np.array_equal(d.times, direct.T)
    assert np.array_equal(d.Hc_series, [pb.moes_from_venner(h) for h in direct.Hc])
    assert np.array_equal(d.hc_series, direct.Hc * scale)
    assert np.array_equal(transient_line.fields["P"], direct.snapshots[5]["P"])
    assert transient_line.hm == direct.Hm[-1] * scale


def test_a_transient_run_is_inaccurate_under_a_target_whose_error_it_cannot_measure(transient_line):
    # on its given 129 points the grid pair (65 points) cannot start at M = 87, and the pair at
    # twice the step is beyond what the bump allows: the default target cannot be confirmed
    assert transient_line.status == Status.INACCURATE and not transient_line.success
    assert "grid part not measured" in transient_line.message and "0.005" in transient_line.message
    assert math.isnan(transient_line.error.Hc) and not transient_line.error.meets_target
    assert set(transient_line.error.parts) == {"grid", "time", "domain"}
    judged = ehl.solve(bump_line_scene(), physics="transient", accuracy=None,
                       options={"points": 129, "steps": 5})
    assert judged.success and judged.status == Status.CONVERGED
    assert judged.Hc == transient_line.Hc


def test_to_result_gives_the_package_result_of_every_physics(steady_line, thermal_line, transient_line):
    assert steady_line.to_result().kind == "ehl_line"
    assert thermal_line.to_result().kind == "tehl_line"
    assert transient_line.to_result().kind == "transient_line"


def test_transient_point_equals_solve_transient_point_called_directly():
    from ehl_multigrid.point.problem import problem_from_scene, resolve_domain
    from ehl_multigrid.transient.point_solve import solve_transient_point
    from ehl_multigrid.transient.scene_feature import point_feature_from_scene_table

    d = load_scene("default").to_dict()
    d["feature"] = {"kind": "dent", "amplitude": 5e-9, "width": 2e-5, "x0": -2.5}
    scene = Scene.from_dict(d)
    # one step (0.5 s of each run on 65 points): the start and a step, as many as the mapping needs
    sol = ehl.solve(scene, physics="transient", accuracy=None, options={"points": 65, "steps": 1})
    pb = problem_from_scene(scene)
    feature, body = point_feature_from_scene_table(scene.feature, pb, resolve_domain(pb, -4.5, None, None))
    direct = solve_transient_point(pb, feature, body=body, slide_roll=scene.slip, points=65, xmin=-4.5,
                                   steps=1)
    assert sol.success and sol.contact == "point" and not sol.grid.half  # features need the full domain
    assert len(sol.details.Hc_series) == 2  # the start and the step
    assert np.array_equal(sol.details.Hc_series, direct.Hc * pb.moes_factor)
    assert np.array_equal(sol.fields["H"], direct.snapshots[1]["H"])
    assert sol.fields["P"].shape == (sol.grid.points_y, sol.grid.points)
