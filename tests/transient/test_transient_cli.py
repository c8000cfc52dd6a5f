"""``ehl transient SCENE`` (registered by the lead through the ``ehl.commands`` entry point):
the scene's [feature] table in metres, HDF5 + PNG output and the JSON payload."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import Scene, load_scene
from ehl_multigrid.transient import cli, load_series


def _parser():
    p = argparse.ArgumentParser()
    cli.register(p.add_subparsers(dest="command"))
    return p


def _scene_with(feature):
    d = load_scene("page63_line_2000N").to_dict()
    if feature is not None:
        d["feature"] = feature
    return Scene.from_dict(d)


@pytest.mark.solver
def test_transient_command_writes_series_plots_and_summary(monkeypatch, tmp_path):
    sc = _scene_with(None)
    pb = LineProblem.from_scene(sc, xmin=-4.5)
    depth = 0.5 * 0.0084 * pb.b**2 / pb.R  # half the central film, in metres
    # the depth with units, as a user writes it: the scene converts it to metres
    sc = _scene_with({"kind": "dent", "amplitude": f"{depth * 1e9:.6f} nm", "width": 0.5 * pb.b,
                      "x0": -3.0})
    assert sc.feature["amplitude"] == pytest.approx(depth, rel=1e-6)
    monkeypatch.setattr(cli, "load_scene", lambda name: sc)
    # dT = 0.03 (near the largest the dent allows, 0.031) instead of the default one mesh size
    # per step (0.0234 on 129 points): 75 steps instead of 96 for the dent's passage; 129 points
    # (257: 1.25x the cost) since the output, not the film, is checked
    args = _parser().parse_args(["transient", "x", "--accuracy", "none", "--points", "129", "--dt", "0.03", "--json",
                                 "--out", str(tmp_path), "--threshold", "1e-8", "--animate",
                                 "--snapshot-every", "20"])
    out = args.func(args)
    assert out["converged"] and out["slide_roll"] == sc.slip == 2.0
    assert out["feature"]["kind"] == "bump" and out["feature"]["amplitude"] < 0
    assert 0 < out["hm_min"] < out["hc_min"] <= out["hc_steady"] <= out["hc_max"]
    assert [p.rsplit(".", 1)[1] for p in out["plots"]] == ["png", "png", "gif"]
    assert len(out["fraction_below_threshold"]) > 2
    back = load_series(out["hdf5"])
    assert back["summary"]["steps"] == out["steps"]
    json.dumps(out)


def test_time_error_flag_reports_the_measured_time_part_of_an_adaptive_run(monkeypatch, tmp_path, capsys):
    sc = _scene_with({"kind": "dent", "amplitude": "20 nm", "width": 5e-5, "x0": -1.5e-4})
    monkeypatch.setattr(cli, "load_scene", lambda name: sc)
    args = _parser().parse_args(["transient", "x", "--accuracy", "none", "--points", "129", "--steps", "4", "--time-tol", "1e-2",
                                 "--time-error", "--no-plots", "--out", str(tmp_path),
                                 "--checkpoint-every", "0"])
    out = args.func(args)
    assert out["converged"] and set(out["time_error"]) == {"Hc", "Hm"}
    assert all(0.0 < v < 0.1 for v in out["time_error"].values())
    shown = capsys.readouterr()
    assert "time error (relative to the smooth film)" in shown.out and "not measured" not in shown.err


def test_time_error_flag_says_why_a_fixed_step_run_is_not_measured(monkeypatch, tmp_path, capsys):
    # the default step is the largest the dent allows: twice it is refused, and the line says so
    sc = _scene_with({"kind": "dent", "amplitude": "20 nm", "width": 5e-5, "x0": -3.0e-4})
    monkeypatch.setattr(cli, "load_scene", lambda name: sc)
    args = _parser().parse_args(["transient", "x", "--accuracy", "none", "--points", "129", "--steps", "6", "--time-error",
                                 "--no-plots", "--out", str(tmp_path), "--checkpoint-every", "0"])
    out = args.func(args)
    assert out["converged"] and all(v != v for v in out["time_error"].values())  # NaN: not measured
    shown = capsys.readouterr().out
    assert "time error not measured" in shown and "twice the time step" in shown
    assert ": dent on body 1" in shown  # named as the scene's table names it (a negative bump)


def test_transient_command_without_feature_table_names_it(monkeypatch, tmp_path):
    monkeypatch.setattr(cli, "load_scene", lambda name: _scene_with(None))
    args = _parser().parse_args(["transient", "x", "--out", str(tmp_path)])
    with pytest.raises(InputError, match=r"\[feature\] table"):
        args.func(args)


def test_the_run_header_states_both_surface_speeds_and_the_speed_of_the_feature():
    # us 2 m/s at slip S = -0.5 (SRR -0.25): u1 = 0.75 m/s, u2 = 1.25 m/s (the scene's speeds)
    d = load_scene("page63_line_2000N").to_dict()
    d["operating"].update(us=2.0, slip=-0.5)
    sc = Scene.from_dict(d)
    note = cli.speeds_note(sc.u1, sc.u2, 2)
    assert "u1 = 0.75 m/s" in note and "u2 = 1.25 m/s" in note and "sum 2 m/s" in note
    assert "slip S = 2(u1-u2)/(u1+u2) = -0.5" in note and "SRR = (u1-u2)/(u1+u2) = -0.25" in note
    assert "surface 2 at 1.25 m/s" in note
    assert "surface 1 at 0.75 m/s" in cli.speeds_note(sc.u1, sc.u2, 1)
    assert "feature" not in cli.speeds_note(1.0, 1.0, None)


@pytest.mark.solver
def test_transient_command_runs_a_dent_through_a_point_scene(monkeypatch, tmp_path, capsys):
    from ehl_multigrid.point.problem import problem_from_scene

    d = load_scene("series_B_disc1_1GPa").to_dict()
    d["operating"]["load"] *= 0.064  # pmax 0.4 GPa, M = 14: 65^2 converges (1 GPa: M = 222 needs 257^2)
    pb = problem_from_scene(Scene.from_dict(d))
    depth = 0.1 * pb.a**2 / pb.Rx  # 0.1 film units
    d["feature"] = {"kind": "dent", "amplitude": depth, "width": 0.5 * pb.a, "x0": -2.0, "y0": 0.3}
    sc = Scene.from_dict(d)
    monkeypatch.setattr(cli, "load_scene", lambda name: sc)
    args = _parser().parse_args(["transient", "x", "--accuracy", "none", "--points", "65", "--steps", "12", "--json",
                                 "--out", str(tmp_path), "--threshold", "1e-7", "--snapshot-every", "4"])
    out = args.func(args)
    err = capsys.readouterr().err
    assert "surface speeds u1 = " in err and "time error" in err and "not measured" in err
    assert out["contact"] == "point" and out["points"] == out["points_y"] == 65
    assert out["feature"]["amplitude"] == pytest.approx(-0.1) and out["feature"]["y0"] == 0.3
    assert 0 < out["hm_min"] < out["hc_steady"]
    assert len(out["load_fraction_below_threshold"]) == 4
    assert [p.rsplit(".", 1)[1] for p in out["plots"]] == ["png", "png"]
    back = load_series(out["hdf5"])
    assert back["kind"] == "ehl_transient_point" and back["summary"]["steps"] == 12
    json.dumps(out)


def test_transient_command_rejects_huge_grids(tmp_path):
    args = _parser().parse_args(["transient", "series_B_disc1_1GPa", "--points", "1025", "--out", str(tmp_path)])
    with pytest.raises(InputError, match=r"--points = 1025 .*\[65, 513\]"):
        args.func(args)
    args = _parser().parse_args(["transient", "page63_line_2000N", "--points", "9000", "--out", str(tmp_path)])
    with pytest.raises(InputError, match=r"--points = 9000 .*\[65, 4097\]"):
        args.func(args)


def test_a_run_without_a_target_says_its_films_are_not_verified(monkeypatch, tmp_path, capsys):
    # 'converged' is the steps': the films' grid error is never estimated and the time error only
    # with --time-error (a 1 um dent through a spur gear: hm_min 19 % off at the default step)
    sc = _scene_with({"kind": "dent", "amplitude": "20 nm", "width": 5e-5, "x0": -3.0e-4})
    monkeypatch.setattr(cli, "load_scene", lambda name: sc)
    args = _parser().parse_args(["transient", "x", "--accuracy", "none", "--points", "129", "--steps", "4",
                                 "--no-plots", "--out", str(tmp_path), "--checkpoint-every", "0"])
    out = args.func(args)
    assert out["converged"] and out["films_verified"] is False
    assert out["films_error"] == {"time": "not measured", "grid": "not estimated", "domain": "not estimated"}
    assert "not verified" in capsys.readouterr().err


@pytest.mark.solver
def test_a_run_with_a_target_states_its_time_and_grid_parts_and_exits_3_when_it_misses_it(tmp_path, capsys):
    # a 3 nm dent through page 63 at 500 N on 513 points (the grid fixed) at dT = 0.025: time part
    # Hc 0.89 %, grid part 0.98 %; halving the step does not lower the time part by 10 %
    d = load_scene("page63_line_500N").to_dict()
    d["feature"] = {"kind": "dent", "amplitude": 3e-9, "width": 1e-4, "x0": -1.5}
    path = tmp_path / "dent.toml"
    path.write_text(Scene.from_dict(d).to_toml())
    argv = ["transient", str(path), "--points", "513", "--dt", "0.025", "--t-end", "1.0", "--no-plots", "--json"]
    assert main([*argv, "--accuracy", "0.05", "--out", str(tmp_path / "a")]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["status"] == "converged" and out["converged"] and out["films_verified"] is True
    fe = out["films_error"]
    assert fe["accuracy"] == 0.05 and max(fe["Hc"], fe["Hm"]) <= 0.05
    assert fe["Hc"] == pytest.approx(fe["time"]["Hc"] + fe["grid"]["Hc"] + fe["domain"]["Hc"]) and out["dt"] == 0.025
    assert load_series(out["hdf5"])["summary"]["steps"] == out["steps"] == 40
    assert main([*argv, "--accuracy", "0.015", "--out", str(tmp_path / "b")]) == 3
    captured = capsys.readouterr()
    out = json.loads(captured.out)
    assert out["status"] == "inaccurate" and not out["converged"] and out["films_verified"] is False
    assert max(out["films_error"]["Hc"], out["films_error"]["Hm"]) > 0.015
    assert "above the accuracy 0.015" in out["message"] and Path(out["hdf5"]).exists()
    assert "lowered the time error by less than 10%" in out["message"] and out["dt"] == 0.025
    assert "pair run on 257 points" in captured.err  # progress: every run of the sequence


def test_resume_and_max_points_with_a_target_are_refused(tmp_path, capsys):
    assert main(["transient", "page63_line_2000N", "--resume", "--out", str(tmp_path)]) == 2
    assert "--accuracy none" in capsys.readouterr().err
    assert main(["transient", "page63_line_2000N", "--points", "257", "--max-points", "1025",
                 "--out", str(tmp_path)]) == 2
    assert "--points fixes the grid" in capsys.readouterr().err


def test_a_refinement_stopped_keeps_its_last_finished_answer(monkeypatch, tmp_path, capsys):
    from ehl_multigrid.transient.control import TransientControl

    def stop(self, result, at, record):
        raise KeyboardInterrupt  # as Ctrl-C while the first answer's pairs run

    monkeypatch.setattr(TransientControl, "estimate", stop)
    d = load_scene("page63_line_500N").to_dict()
    d["feature"] = {"kind": "dent", "amplitude": 3e-9, "width": 1e-4, "x0": -1.5}
    path = tmp_path / "dent.toml"
    path.write_text(Scene.from_dict(d).to_toml())
    rc = main(["transient", str(path), "--points", "129", "--steps", "5", "--no-plots", "--out", str(tmp_path / "o")])
    assert rc == 130
    err = capsys.readouterr().err
    assert "the last finished run (129 points" in err and "its error not confirmed" in err
    back = load_series(tmp_path / "o" / "transient_page63_line_500N.h5")
    assert back["summary"]["steps"] == 5 and back["summary"]["points"] == 129
