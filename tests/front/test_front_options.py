"""The options of the front door that the ``ehl`` command line needs (issue 42): progress
lines, the model laws of a scene, the Newton path, the thermal solve's threads and a transient
run's checkpoint."""

from __future__ import annotations

import math

import numba
import pytest

import ehl_multigrid as ehl
from ehl_multigrid.model.errors import ConvergenceError, InputError
from ehl_multigrid.model.scene import Scene, load_scene


def test_progress_gets_the_lines_of_the_steady_accuracy_sequence():
    lines: list[str] = []
    sol = ehl.solve(ehl.MoesProblem("line", 20, 10), options={"points": 129}, progress=lines.append)
    assert sol.grid.points == 129
    # one line per solve of the sequence, naming its grid (as 'ehl solve' prints on stderr)
    assert lines and all(isinstance(t, str) for t in lines)
    assert any("129" in t for t in lines)


def test_progress_gets_the_lines_of_the_starved_accuracy_sequence():
    d = load_scene("page63_line_500N").to_dict()
    d["supply"] = {"hoil": 1.5e-8}
    lines: list[str] = []
    sol = ehl.solve(Scene.from_dict(d), options={"points": 257}, progress=lines.append)
    assert sol.physics == "starved" and sol.grid.points == 257
    assert any("257 points" in t and "estimated error" in t for t in lines), lines


def test_a_progress_that_is_not_callable_is_refused_naming_it():
    with pytest.raises(InputError, match="progress"):
        ehl.solve(ehl.MoesProblem("line", 20, 10), progress="stderr")


def test_a_scene_takes_its_viscosity_law_as_an_option_as_solve_line_does():
    from ehl_multigrid.line import solve_line

    scene = load_scene("page63_line_2000N")
    sol = ehl.solve(scene, accuracy=None, options={"points": 129, "viscosity": "barus"})
    direct = solve_line(scene=scene, viscosity="barus", points=129, accuracy=None, raise_on_failure=False)
    roelands = ehl.solve(scene, accuracy=None, options={"points": 129})
    assert sol.raw.problem.viscosity == "barus"
    assert sol.Hc == direct.scalars["Hc"] and sol.Hm == direct.scalars["Hm"]
    assert sol.Hc != roelands.Hc


@pytest.mark.parametrize("key", ["viscosity", "density"])
def test_a_moes_problem_refuses_the_model_options_naming_them(key):
    with pytest.raises(InputError, match=key):
        ehl.solve(ehl.MoesProblem("line", 20, 10), options={key: "barus"})


def test_the_newton_path_refuses_an_accuracy_target_it_cannot_judge():
    with pytest.raises(InputError, match=r"accuracy = 0.005.*newton"):
        ehl.solve(ehl.MoesProblem("point", 20, 10), options={"solver": "newton", "points": 65})


def test_the_newton_path_refuses_the_options_of_the_fas_solver_naming_them():
    with pytest.raises(InputError, match=r"\['cycle'\].*Newton"):
        ehl.solve(ehl.MoesProblem("point", 20, 10), accuracy=None, options={"solver": "newton", "cycle": "W"})


def test_an_unknown_point_solver_is_refused_naming_the_allowed_ones():
    with pytest.raises(InputError, match=r"solver.*'multigrid'.*fas.*newton"):
        ehl.solve(ehl.MoesProblem("point", 20, 10), options={"solver": "multigrid"})


@pytest.mark.slow
def test_the_newton_path_equals_solve_point_called_directly():
    from ehl_multigrid.point import solve_point

    sol = ehl.solve(ehl.MoesProblem("point", 20, 10), accuracy=None, options={"solver": "newton", "points": 65})
    direct = solve_point(20, 10, solver="newton", points=65)
    assert sol.success and not sol.grid.half
    assert sol.Hc == direct.scalars["Hc"] and sol.Hm == direct.scalars["Hm"]


def test_thermal_threads_outside_their_range_are_refused_naming_them():
    with pytest.raises(InputError, match=r"threads = 0"):
        ehl.solve("appendix_c_line_4240N", physics="thermal", options={"threads": 0})


@pytest.mark.skipif(numba.config.NUMBA_NUM_THREADS < 2, reason="needs two numba threads to tell them apart")
def test_thermal_threads_hold_for_the_solve_and_the_callers_setting_is_restored(monkeypatch):
    import thermal.tehl.accuracy as accuracy

    seen = []

    def solve_tehl_to_accuracy(*args, **kw):
        seen.append(numba.get_num_threads())
        raise ConvergenceError("stub: the thread count is all this solve looks at")

    monkeypatch.setattr(accuracy, "solve_tehl_to_accuracy", solve_tehl_to_accuracy)
    numba.set_num_threads(2)
    sol = ehl.solve("appendix_c_line_4240N", physics="thermal", options={"threads": 1})
    assert seen == [1] and numba.get_num_threads() == 2
    assert not sol.success and "stub" in sol.message


def test_a_transient_checkpoint_holds_the_run_and_not_the_time_error_run(tmp_path):
    from ehl_multigrid.transient.checkpoint import Checkpoint
    from ehl_multigrid.transient.result import load_series

    d = load_scene("page63_line_2000N").to_dict()
    d["feature"] = {"kind": "bump", "amplitude": 1e-8, "width": 1e-5, "x0": -3.0}
    path = tmp_path / "run.h5"
    sol = ehl.solve(Scene.from_dict(d), physics="transient", accuracy=None,
                    options={"points": 129, "steps": 4, "dt": 0.001, "time_error": True,
                             "checkpoint": Checkpoint(path, every_steps=1)})
    assert sol.success and math.isfinite(sol.error.parts["time"].Hc)  # the second run was made
    saved = load_series(path)["summary"]
    # the file is the run's own (4 steps of dt), not the second run's (2 steps of 2 dt)
    assert saved["dt"] == pytest.approx(sol.details.dt) and saved["steps"] == 4


@pytest.mark.parametrize("contact, allowed", [("line", r"\[0\.1, 20000\]"), ("point", r"\(0, 1e\+06\]")])
def test_a_moes_problem_names_the_load_range_of_its_contact(contact, allowed):
    # (as 'ehl solve --M' did before it went through the front door)
    with pytest.raises(InputError, match=rf"^M = -1 .*{allowed}"):
        ehl.MoesProblem(contact, -1.0, 10)


def test_a_moes_problem_of_a_non_number_says_so_naming_the_group():
    with pytest.raises(InputError, match=r"^L = 'ten'.*number"):
        ehl.MoesProblem("point", 20, "ten")
