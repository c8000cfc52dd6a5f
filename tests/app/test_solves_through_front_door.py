"""Every ``ehl`` subcommand that solves a film calls the front door ``ehl_multigrid.solve``
(issue 42) and keeps its exit code when the front door returns a failure: a solve that
computed nothing exits 3 naming why. The front door is replaced by one that records the call
and fails, so no film is solved here."""

from __future__ import annotations

import time

import pytest

import ehl_multigrid.front as front
from ehl_multigrid.app.cli import main
from ehl_multigrid.model.errors import ConvergenceError
from ehl_multigrid.model.scene import Scene, load_scene
from ehl_multigrid.solution import MoesProblem

MARK = "no film from the recording front door (marker 7731)"


@pytest.fixture
def calls(monkeypatch, tmp_path):
    """The calls of the front door, which returns a failed solution without computing anything;
    run in a temporary folder (a command without ``--out`` writes into ``./ehl_out``)."""
    monkeypatch.chdir(tmp_path)
    seen: list[dict] = []

    def recording(problem, *, physics=None, accuracy=0.005, options=None, callback=None, progress=None):
        seen.append({"problem": problem, "physics": physics, "accuracy": accuracy,
                     "options": dict(options or {}), "callback": callback, "progress": progress})
        contact = problem.contact if isinstance(problem, MoesProblem) else (
            problem.kind if isinstance(problem, Scene) else load_scene(problem).kind)
        return front.failed_solution(physics or "steady", contact, ConvergenceError(MARK), accuracy,
                                     time.perf_counter(), problem if isinstance(problem, Scene) else None)

    monkeypatch.setattr(front, "solve", recording)
    return seen


def _scene_file(folder, base, name, **tables):
    d = load_scene(base).to_dict()
    d.update(tables, name=name)
    path = folder / f"{name}.toml"
    path.write_text(Scene.from_dict(d).to_toml())
    return str(path)


def _dent_scene(folder):
    from ehl_multigrid.line.problem import LineProblem

    pb = LineProblem.from_scene(load_scene("page63_line_2000N"), xmin=-4.5)
    feature = {"kind": "dent", "amplitude": 0.5 * 0.0084 * pb.b**2 / pb.R, "width": 0.5 * pb.b, "x0": -3.0}
    return _scene_file(folder, "page63_line_2000N", "dent", feature=feature)


CASES = {
    "solve-moes-line": (lambda d: ["solve", "--contact", "line", "--M", "20", "--L", "10", "--points", "129"],
                        "steady"),
    "solve-point-scene": (lambda d: ["solve", "appendix_d_point", "--points", "65", "--accuracy", "none"], "steady"),
    "solve-newton": (lambda d: ["solve", "--contact", "point", "--M", "20", "--L", "10", "--solver", "newton",
                                "--points", "65"], "steady"),
    "solve-starved-line": (lambda d: ["solve", _scene_file(d, "roller_bearing_inner_race", "sl",
                                                           supply={"hoil": "0.15 um"})], "starved"),
    "solve-starved-point": (lambda d: ["solve", _scene_file(d, "appendix_d_point", "sp", supply={"hoil": 5e-8}),
                                       "--points", "65"], "starved"),
    "solve-thermal": (lambda d: ["solve", "page63_line_2000N", "--thermal", "--points", "129", "--nz", "8"],
                      "thermal"),
    "tehl-one-slip": (lambda d: ["tehl", "page63_line_2000N", "--points", "129", "--nz", "8"], "thermal"),
    "tehl-no-estimate": (lambda d: ["tehl", "page63_line_2000N", "--points", "129", "--nz", "8", "--no-estimate"],
                         "thermal"),
    "tehl-curve": (lambda d: ["tehl", "page63_line_2000N", "--slip", "0,0.5", "--points", "129", "--nz", "8"],
                   "thermal"),
    "traction-coupled": (lambda d: ["traction", "page63_line_2000N", "--coupled", "--slip", "0,0.5", "--points",
                                    "129", "--nz", "8"], "thermal"),
    "run-film-stage": (lambda d: ["run", "default"], "steady"),
    "transient": (lambda d: ["transient", _dent_scene(d), "--points", "129", "--steps", "2"], "transient"),
}


@pytest.mark.parametrize("case", list(CASES))
def test_each_film_solving_subcommand_calls_the_front_door_and_exits_3_on_its_failure(case, calls, tmp_path,
                                                                                       capsys):
    make, physics = CASES[case]
    argv = make(tmp_path)
    if argv[0] not in ("tehl", "traction"):  # (a TEHL curve writes no file)
        argv += ["--no-plots", "--out", str(tmp_path / "o")]
    rc = main(argv)
    err = capsys.readouterr().err
    assert rc == 3, err
    assert MARK in err  # the failure's own message, one line on stderr
    assert [c["physics"] for c in calls] == [physics]


def test_ehl_solve_hands_its_options_and_progress_to_the_front_door(calls, tmp_path, capsys):
    main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--points", "129", "--viscosity", "barus",
          "--rigid", "--accuracy", "0.01", "--no-plots", "--out", str(tmp_path)])
    (call,) = calls
    assert call["problem"] == MoesProblem("line", 20.0, 10.0, viscosity="barus")
    assert call["accuracy"] == 0.01
    assert call["options"] == {"points": 129, "elastic": False}
    assert callable(call["progress"]) and callable(call["callback"])


@pytest.mark.parametrize("extra, accuracy, options", [
    ([], 0.005, {}),  # refined towards the default accuracy, as 'ehl solve --thermal'
    (["--points", "257", "--accuracy", "0.02"], 0.02, {"points": 257}),  # a given grid is judged
    (["--accuracy", "none"], None, {}),
])
def test_ehl_tehl_at_one_slip_hands_its_accuracy_to_the_front_door(calls, capsys, extra, accuracy, options):
    main(["tehl", "page63_line_2000N", "--slip", "0.5", *extra])
    (call,) = calls
    assert call["physics"] == "thermal" and call["accuracy"] == accuracy
    assert call["options"] == {**options, "compressive_heating": True, "slip": 0.5}


def test_a_tehl_curve_takes_its_grid_from_the_accuracy_loop_at_its_largest_slip(calls, capsys):
    assert main(["tehl", "page63_line_2000N", "--slip=-1.5,0.5,1", "--accuracy", "0.01"]) == 3  # (the stand-in fails)
    (call,) = calls
    assert call["physics"] == "thermal" and call["accuracy"] == 0.01
    assert call["options"] == {"compressive_heating": True, "slip": -1.5}
    calls.clear()
    # a given grid is the curve's own: no calibrating solve; each slip solved alone on it, judged
    # on its outer iteration (the curve is judged afterwards at three of its slips)
    assert main(["tehl", "page63_line_2000N", "--slip", "0.2,0.4", "--points", "129", "--nz", "8",
                 "--json"]) == 3
    (call,) = calls  # the stand-in fails the first slip: the curve ends there
    assert call["physics"] == "thermal" and call["accuracy"] is None
    assert call["options"] == {"points": 129, "nz": 8, "box": 1.0, "compressive_heating": True, "slip": 0.2,
                               "estimate": False, "start": None}


def test_ehl_tehl_without_its_estimate_asks_the_front_door_for_the_film_alone(calls, capsys):
    main(["tehl", "page63_line_2000N", "--slip", "0.5", "--no-estimate"])
    (call,) = calls
    # no estimate, so no accuracy to confirm: judged on the outer iteration, as before
    assert call["physics"] == "thermal" and call["accuracy"] is None
    assert call["options"] == {"compressive_heating": True, "slip": 0.5, "estimate": False}


def test_the_newton_path_is_judged_on_its_iteration_alone(calls, tmp_path, capsys):
    main(["solve", "--contact", "point", "--M", "20", "--L", "10", "--solver", "newton", "--points", "65",
          "--no-plots", "--out", str(tmp_path)])
    (call,) = calls
    assert call["accuracy"] is None and call["options"]["solver"] == "newton"
    assert call["options"]["points"] == 65 and "raise_on_failure" not in call["options"]


def test_ehl_transient_hands_its_checkpoint_to_the_front_door(calls, tmp_path, capsys):
    from ehl_multigrid.transient.checkpoint import Checkpoint

    main(["transient", _dent_scene(tmp_path), "--accuracy", "none", "--points", "129", "--steps", "2", "--no-plots",
          "--out", str(tmp_path / "o")])
    (call,) = calls
    assert call["accuracy"] is None
    assert isinstance(call["options"]["checkpoint"], Checkpoint) and call["options"]["resume"] is None
    assert call["options"]["points"] == 129 and call["options"]["steps"] == 2


def test_ehl_run_hands_its_grid_cap_and_time_budget_to_the_film_stage(calls, tmp_path, capsys):
    # a starved point scene (a grease-lubricated bearing) whose 513-point cap is too coarse
    scene = _scene_file(tmp_path, "bearing_6205_inner_race", "grease", supply={"hoil": 3e-8})
    assert main(["run", scene, "--max-points", "1025", "--time-budget", "300", "--no-plots",
                 "--out", str(tmp_path / "o")]) == 3  # (the stand-in fails)
    (call,) = calls
    assert call["physics"] == "starved" and call["options"] == {"max_points": 1025, "time_budget": 300.0}


@pytest.mark.parametrize("bad", ["1000", "33", "x"])
def test_a_grid_cap_that_is_no_grid_size_is_refused_naming_it(bad, calls, tmp_path, capsys):
    with pytest.raises(SystemExit) as stop:
        main(["run", "default", "--max-points", bad, "--no-plots", "--out", str(tmp_path / "o")])
    assert stop.value.code == 2 and f"max-points = {bad if bad != 'x' else repr(bad)}" in capsys.readouterr().err
    assert calls == []
