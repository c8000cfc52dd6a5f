"""A stop (Ctrl-C, SIGTERM) during ``ehl solve``'s accuracy sequence writes the most accurate
finished solve, marked inaccurate with the stop named, and exits 130 / 143; through the front
door the stop carries that solution (``ehl_multigrid.solve``, Raises)."""

import json

import pytest

import ehl_multigrid
from ehl_multigrid.app import console
from ehl_multigrid.app.cli import main
from ehl_multigrid.model.errors import Terminated
from ehl_multigrid.model.results import Result
from ehl_multigrid.solution import MoesProblem, Status


def _stop_at_the_first_refinement(stop):
    def progress(text):
        if "refining" in text:
            raise stop
    return progress


def test_front_door_stop_carries_the_most_accurate_finished_solution():
    # line (20, 10) at 0.1 %: 4097 points estimated, then a refinement, stopped
    with pytest.raises(KeyboardInterrupt) as info:
        ehl_multigrid.solve(MoesProblem("line", 20, 10), accuracy=0.001,
                            progress=_stop_at_the_first_refinement(KeyboardInterrupt()))
    sol = info.value.solution
    assert sol.status is Status.INACCURATE and not sol.success
    assert sol.Hc > 0 and sol.Hm > 0 and sol.fields
    assert sol.error.Hc > 0.001 or sol.error.Hm > 0.001  # why it was refining
    assert "interrupted (Ctrl-C) during the refinement to" in sol.message
    # the answer is the film a solve without a target gives on that grid (to its iteration
    # tolerance; the next grid's differs by about the stated error, above 0.1 %)
    ref = ehl_multigrid.solve(MoesProblem("line", 20, 10), accuracy=None, options={"points": sol.grid.points})
    assert sol.Hm == pytest.approx(ref.Hm, rel=1e-5)


def test_a_stop_before_any_finished_solve_carries_nothing():
    def progress(text):
        raise KeyboardInterrupt  # at the first line, before any estimate
    with pytest.raises(KeyboardInterrupt) as info:
        ehl_multigrid.solve(MoesProblem("line", 20, 10), accuracy=0.001, progress=progress)
    assert getattr(info.value, "solution", None) is None


@pytest.mark.parametrize("stop, code, word", [(KeyboardInterrupt(), 130, "interrupted"),
                                              (Terminated(), 143, "terminated")])
def test_ehl_solve_writes_the_kept_solve_and_exits_with_the_stop(tmp_path, capsys, monkeypatch, stop, code, word):
    said = console.Progress.say

    def say(self, text, *a, **k):
        said(self, text, *a, **k)
        _stop_at_the_first_refinement(stop)(text)

    monkeypatch.setattr(console.Progress, "say", say)
    rc = main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--accuracy", "0.001", "--no-plots",
               "--out", str(tmp_path), "--json"])
    cap = capsys.readouterr()
    assert rc == code
    h5 = tmp_path / "line_M20_L10.h5"
    failed = json.loads(cap.out.strip().splitlines()[-1])
    assert failed["error"] == word and str(h5) in failed["message"] and failed["hdf5"] == str(h5)
    assert f"ehl solve: {word}; the most accurate finished solve (" in cap.err
    saved = Result.load(h5)
    assert saved.scalars["status"] == "inaccurate"
    assert word in saved.scalars["message"] and saved.scalars["Hm_error"] > 0


def test_ehl_run_keeps_the_film_stage_a_stop_ended_and_runs_no_later_stage(tmp_path, capsys, monkeypatch):
    import ehl_multigrid.multigrid.controller as ctl

    def stop(*a, **k):  # called once a solve is finished and estimated, before refining it
        raise KeyboardInterrupt

    monkeypatch.setattr(ctl, "predicted_seconds", stop)
    monkeypatch.setenv("EHL_WARMUP", "0")
    rc = main(["run", "appendix_c_line_4240N", "--tolerance", "0.001", "--out", str(tmp_path), "--json",
               "--no-plots"])
    cap = capsys.readouterr()
    assert rc == 130
    assert "ehl run: interrupted; the most accurate finished solve (" in cap.err
    assert "as the film stage's film; the stages after it did not run" in cap.err
    import h5py

    with h5py.File(tmp_path / "appendix_c_line_4240N.h5") as f:
        assert not f.attrs["complete"] and json.loads(f.attrs["stages_run"]) == ["film"]
    film = Result.load(tmp_path / "appendix_c_line_4240N.h5", "film")
    assert film.scalars["status"] == "inaccurate" and "interrupted (Ctrl-C)" in film.scalars["message"]


def test_ehl_solve_stopped_before_any_solve_finished_says_nothing_was_written(tmp_path, capsys, monkeypatch):
    said = console.Progress.say

    def say(self, text, *a, **k):
        said(self, text, *a, **k)
        raise KeyboardInterrupt  # at the first solve's line, before its estimate

    monkeypatch.setattr(console.Progress, "say", say)
    rc = main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--accuracy", "0.001", "--no-plots",
               "--out", str(tmp_path), "--json"])
    cap = capsys.readouterr()
    failed = json.loads(cap.out.strip().splitlines()[-1])
    assert rc == 130 and "hdf5" not in failed
    assert "no solve had finished, so nothing was written" in failed["message"]
    assert not list(tmp_path.glob("*.h5"))


def test_ehl_run_stopped_before_any_stage_finished_says_nothing_was_written(tmp_path, capsys, monkeypatch):
    from ehl_multigrid.app.stages import RunContext

    def stop(self, *a, **k):
        raise KeyboardInterrupt

    monkeypatch.setattr(RunContext, "solve", stop)
    monkeypatch.setenv("EHL_WARMUP", "0")
    rc = main(["run", "appendix_c_line_4240N", "--tolerance", "0.001", "--out", str(tmp_path), "--json",
               "--no-plots"])
    err = capsys.readouterr().err
    assert rc == 130 and "no stage had finished, so nothing was written" in err
    assert not list(tmp_path.glob("*.h5"))
