"""The front door's thermal options a TEHL traction curve needs (issue 42): ``estimate=False``
(the film alone, its error honestly unknown) and ``start`` (a slip continuing from the previous
slip's solve). Through them ``ehl tehl --slip a,b,c`` gives exactly the films of the TEHL
solver's own curve."""

from __future__ import annotations

import math

import numpy as np
import pytest

import ehl_multigrid as ehl
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import Scene, load_scene
from ehl_multigrid.solution import Status

SCENE = "appendix_c_line_4240N"
GRID = {"points": 129, "nz": 8}

pytestmark = pytest.mark.xdist_group("front_thermal_curve")


@pytest.fixture(scope="module")
def scene():
    return load_scene(SCENE)


@pytest.fixture(scope="module")
def curve(scene):
    """Three slips through the front door, each continuing from the one before."""
    sols = []
    for s in (0.0, 0.5, 1.0):
        sols.append(ehl.solve(scene, physics="thermal", accuracy=None,
                              options={**GRID, "slip": s, "estimate": False,
                                       "start": sols[-1] if sols else None}))
    return sols


def test_a_film_solved_alone_states_that_its_error_is_not_estimated(curve):
    sol = curve[1]
    assert sol.success and sol.status == Status.CONVERGED  # judged on its outer iteration
    assert math.isnan(sol.error.Hc) and math.isnan(sol.error.Hm) and dict(sol.error.parts) == {}
    assert "estimate = False" in sol.error.notes[0] and "not estimated" in sol.message
    assert math.isnan(sol.details.friction_coefficient_error) and math.isnan(sol.details.T_max_error_K)
    assert sol.raw.estimate is None and not sol.error.meets_target


def test_a_film_solved_alone_under_a_target_is_inaccurate(scene, curve):
    sol = ehl.solve(scene, physics="thermal", accuracy=0.01, options={**GRID, "slip": 0.0, "estimate": False})
    # the error is not known, so the target cannot be confirmed: not a success
    assert sol.status == Status.INACCURATE and not sol.success
    assert "0.01" in sol.message and "not estimated" in sol.message
    assert sol.Hc == curve[0].Hc and sol.Hm == curve[0].Hm  # the same film (no start at slip 0)


def test_a_curve_through_the_front_door_equals_the_tehl_solvers_own_curve(scene, curve):
    from thermal.tehl.line import TEHLOptions, tehl_traction_curve

    direct = tehl_traction_curve(scene, [0.0, 0.5, 1.0], TEHLOptions(**GRID))
    for sol, r in zip(curve, direct, strict=True):
        assert sol.details.slip == r.slip and sol.Hc == r.Hc and sol.Hm == r.Hm
        assert np.array_equal(sol.fields["P"], r.P) and np.array_equal(sol.fields["T"], r.T)
        assert sol.details.friction_coefficient == r.friction_coefficient
        assert len(sol.raw.result.outer) == len(r.outer)


def test_a_slip_continued_from_the_previous_one_needs_fewer_outer_iterations(scene, curve):
    cold = ehl.solve(scene, physics="thermal", accuracy=None, options={**GRID, "slip": 1.0, "estimate": False})
    assert cold.success and curve[2].details.outer_iterations < cold.details.outer_iterations
    # the same fixed point within the outer tolerances (tol_H 1e-4)
    assert abs(curve[2].Hc / cold.Hc - 1.0) < 1e-3


def test_a_continued_solve_with_its_estimate_continues_the_solve_it_judges(scene, curve):
    from thermal.tehl.accuracy import estimate_error
    from thermal.tehl.line import TEHLOptions, continuation, solve_tehl_line

    sol = ehl.solve(scene, physics="thermal", accuracy=None, options={**GRID, "slip": 0.5, "start": curve[0]})
    r = solve_tehl_line(scene, 0.5, TEHLOptions(**GRID), **continuation(curve[0].raw.result, scene))
    assert sol.Hc == r.Hc == curve[1].Hc and sol.details.outer_iterations == len(r.outer)
    # the estimate is that of the continued solve, its coarser grids solved on their own
    est = estimate_error(r, extrapolate=False)
    assert sol.error.Hc == est.Hc and sol.error.Hm == est.Hm


def test_the_options_of_a_film_solved_alone_are_checked(scene):
    with pytest.raises(InputError, match=r"estimate = 'no' must be true or false"):
        ehl.solve(scene, physics="thermal", options={**GRID, "estimate": "no"})
    with pytest.raises(InputError, match=r"\['max_points', 'time_budget'\] with estimate = False"):
        ehl.solve(scene, physics="thermal", options={"estimate": False, "max_points": 1025, "time_budget": 5})


def test_a_start_of_another_grid_contact_or_physics_is_refused_naming_it(scene, curve):
    with pytest.raises(InputError, match=r"start was solved on points = 129.*asks for points = 257"):
        ehl.solve(scene, physics="thermal", options={"points": 257, "nz": 8, "start": curve[0]})
    other = load_scene("page63_line_2000N")
    with pytest.raises(InputError, match=r"scene 'appendix_c_line_4240N', which differs from scene "
                                         r"'page63_line_2000N' in more than its slip"):
        ehl.solve(other, physics="thermal", options={**GRID, "start": curve[0]})
    steady = ehl.solve(scene, options={"points": 129})
    with pytest.raises(InputError, match=r"start = a steady Solution"):
        ehl.solve(scene, physics="thermal", options={**GRID, "start": steady})
    with pytest.raises(InputError, match=r"start with a point contact"):
        ehl.solve("appendix_d_point", physics="thermal", options={"points": 129, "nz": 8, "start": curve[0]})


def test_a_starved_curve_continues_each_meniscus_search_from_the_previous_slip(tmp_path):
    from thermal.tehl.line import TEHLOptions, tehl_traction_curve

    d = load_scene("roller_bearing_inner_race").to_dict()
    d["supply"] = {"hoil": 2e-8}
    scene = Scene.from_dict(d)
    # 129 points, nz = 4 (no estimate): a fresh search at S = 0.5 ends elsewhere than the one
    # continued from S = 0.05 there too (other meniscus history and Hc), at half the cost of 257, 8
    opts = {"points": 129, "nz": 4}
    sols = []
    for s in (0.05, 0.5):
        sols.append(ehl.solve(scene, physics="thermal", accuracy=None,
                              options={**opts, "slip": s, "estimate": False, "start": sols[-1] if sols else None}))
    direct = tehl_traction_curve(scene, [0.05, 0.5], TEHLOptions(**opts))
    for sol, r in zip(sols, direct, strict=True):
        assert sol.details.starved is not None and sol.details.starved.meniscus_x == r.starved["meniscus_x"]
        assert sol.Hc == r.Hc and sol.Hm == r.Hm
        assert sol.raw.result.starved["meniscus_history"] == r.starved["meniscus_history"]
