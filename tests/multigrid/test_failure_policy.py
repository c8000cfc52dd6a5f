"""One failure policy for every film solver: a numerical failure is returned (success False,
a status other than converged, the message), never raised, unless the caller asks with
``raise_on_failure=True``. Each solver family is forced to fail cheaply (a start grid too
coarse for the load, or one cycle against an unreachable tolerance) on a coarse grid."""

import math

import numpy as np
import pytest

from ehl_multigrid.line import LineProblem, solve_line, solve_line_problem
from ehl_multigrid.model.errors import ConvergenceError, InputError
from ehl_multigrid.multigrid.options import LineOptions, PointOptions
from ehl_multigrid.point import solve_point
from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.starved import solve_starved_line, solve_starved_point
from ehl_multigrid.starved.line import starved_options
from ehl_multigrid.transient import solve_transient_line, transient_options

#: one cycle against a tolerance no iteration reaches
UNREACHABLE = {"max_cycles": 1, "tol": 1e-14, "tol_load": 1e-14}


def _returned_failure(res, says):
    assert res.success is False and res.converged is False
    assert res.status_name != "converged" and res.status != 0
    assert says in res.message, res.message


def test_every_solver_family_defaults_to_returning_a_failure():
    assert LineOptions().raise_on_failure is False
    assert PointOptions().raise_on_failure is False
    assert starved_options().raise_on_failure is False
    assert transient_options().raise_on_failure is False


def test_line_start_without_a_positive_film_is_returned_and_raised_on_request():
    # M = 5000, L = 0 on 129 points: the start grid holds no positive film
    res = solve_line(5000.0, 0.0, points=129)
    _returned_failure(res, "not positive")
    assert res.status_name == "start_failed" and math.isnan(res.scalars["Hc"])
    with pytest.raises(ConvergenceError, match=r"not positive.*129-point"):
        solve_line(5000.0, 0.0, points=129, raise_on_failure=True)


def test_line_problem_out_of_cycles_is_returned_and_raised_on_request():
    pb = LineProblem.from_moes(20.0, 10.0)
    res = solve_line_problem(pb, points=129, **UNREACHABLE)
    _returned_failure(res, "1e-14")
    assert res.status_name == "max_cycles" and np.all(np.isfinite(res.P))
    with pytest.raises(ConvergenceError, match=r"line solver\b.*tol 1e-14"):
        solve_line_problem(pb, points=129, raise_on_failure=True, **UNREACHABLE)


def test_point_out_of_cycles_is_returned_and_raised_on_request():
    res = solve_point(20.0, 10.0, points=65, estimate=False, **UNREACHABLE)
    _returned_failure(res, "1e-14")
    assert res.status_name == "max_cycles"
    with pytest.raises(ConvergenceError, match=r"point solver\b.*tol 1e-14"):
        solve_point(20.0, 10.0, points=65, estimate=False, raise_on_failure=True, **UNREACHABLE)


def test_starved_line_failed_flooded_start_is_returned_and_raised_on_request():
    pb = LineProblem.from_moes(20.0, 10.0)
    res = solve_starved_line(pb, 0.05, points=129, max_cycles=0)
    _returned_failure(res, "flooded start")
    assert res.status_name == "start_failed"
    with pytest.raises(ConvergenceError, match=r"starved line solver\b.*flooded start"):
        solve_starved_line(pb, 0.05, points=129, max_cycles=0, raise_on_failure=True)


def test_starved_point_out_of_cycles_is_returned_and_raised_on_request():
    pb = problem_from_moes(20.0, 10.0)
    res = solve_starved_point(pb, 0.3, points=65, half=True, **UNREACHABLE)
    _returned_failure(res, "1e-14")
    assert res.status_name == "max_cycles"
    with pytest.raises(ConvergenceError, match=r"starved point solver\b.*tol 1e-14"):
        solve_starved_point(pb, 0.3, points=65, half=True, raise_on_failure=True, **UNREACHABLE)


def test_transient_line_step_solve_returns_its_failure_to_the_time_loop_or_raises_on_request():
    from ehl_multigrid.transient.features import Smooth
    from ehl_multigrid.transient.hierarchy import TransientLineHierarchy
    from ehl_multigrid.transient.solve import _LineStepper

    pb = LineProblem.from_moes(20.0, 10.0)
    steady = solve_line_problem(pb, points=65, deformation="fft")
    assert steady.success
    for raising in (False, True):
        opts = LineOptions(points=65, deformation="fft", raise_on_failure=raising, **UNREACHABLE)
        stepper = _LineStepper(TransientLineHierarchy(pb, opts, Smooth().height), pb, opts)
        stepper.set_unknowns(steady.P.copy(), steady.H0)
        stepper.hz.set_step(0.0, 0.0, np.zeros_like(steady.P))  # the steady equations
        if raising:
            with pytest.raises(ConvergenceError, match=r"tol 1e-14"):
                stepper.solve_step()
        else:
            _returned_failure(stepper.solve_step(), "1e-14")


def test_transient_line_run_raises_its_failure_and_the_front_door_returns_it_failed():
    # a run has no failed-result form: its failure is raised (with the steps kept as
    # ``partial`` once a step completed), and ehl_multigrid.solve returns it as a failure
    import ehl_multigrid as ehl
    from ehl_multigrid.model.scene import Scene, load_scene

    pb = LineProblem.from_moes(20.0, 10.0)
    with pytest.raises(ConvergenceError, match=r"steady start failed\b.*tol 1e-14"):
        solve_transient_line(pb, None, steps=1, points=65, **UNREACHABLE)
    d = load_scene("page63_line_2000N").to_dict()
    sp = LineProblem.from_scene(Scene.from_dict(d))
    d["feature"] = {"kind": "dent", "amplitude": 0.25 * 0.0084 * sp.b**2 / sp.R, "width": 0.5 * sp.b, "x0": -3.0}
    sol = ehl.solve(Scene.from_dict(d), physics="transient", accuracy=None,
                    options={"points": 65, "steps": 1, **UNREACHABLE})
    assert sol.success is False and sol.status.label != "converged"
    assert "steady start" in sol.message, sol.message


def test_friction_is_not_computed_on_a_film_whose_solve_failed():
    from ehl_multigrid.model.scene import load_scene
    from thermal.traction import solve_traction

    scene = load_scene("page63_line_2000N")
    failed = solve_line(scene=scene, points=129, estimate=False, **UNREACHABLE)
    assert not failed.success
    with pytest.raises(InputError, match=r"\behl\b.*'max_cycles'.*converged"):
        solve_traction(scene, 0.1, input="ehl", ehl=failed.to_result(), nx=20, nz=5)
