"""``ehl transient`` keeps what it computed: a step that fails, Ctrl-C, SIGTERM and SIGKILL
leave the completed steps in the HDF5, marked ``complete = False`` with the reason, and
``--resume`` continues such a file exactly where the run stopped."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from ehl_multigrid.app.cli import Terminated, main
from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.model.errors import ConvergenceError
from ehl_multigrid.model.results import is_complete
from ehl_multigrid.model.scene import Scene, load_scene
from ehl_multigrid.transient import load_series
from ehl_multigrid.transient import solve as line_solve
from ehl_multigrid.transient.checkpoint import Checkpoint

H5 = "transient_dent_line.h5"


@pytest.fixture
def dent_scene(tmp_path):
    """A line scene with a shallow dent (a quarter of the film deep) as a TOML file."""
    d = load_scene("page63_line_2000N").to_dict()
    d["name"] = "dent_line"
    pb = LineProblem.from_scene(Scene.from_dict(d))
    d["feature"] = {"kind": "dent", "amplitude": 0.25 * 0.0084 * pb.b**2 / pb.R, "width": 0.5 * pb.b,
                    "x0": -3.0}
    path = tmp_path / "dent_line.toml"
    path.write_text(Scene.from_dict(d).to_toml())
    return str(path)


def _failing_after(monkeypatch, k, how):
    """Make the line steps after the first ``k`` fail: a NaN pressure, a raised
    ConvergenceError, or Ctrl-C (the first solve is the start with the feature frozen)."""
    original = line_solve._LineStepper.solve_step
    calls = {"n": 0}

    def step(self):
        calls["n"] += 1
        if calls["n"] > k + 1:
            if how == "raise":
                raise ConvergenceError("forced divergence")
            if how == "interrupt":
                raise KeyboardInterrupt
            if how == "signal in a kernel":  # numba turns the handler's exception into this
                raise SystemError("CPUDispatcher returned a result with an exception set") \
                    from Terminated()
        res = original(self)
        if calls["n"] > k + 1:
            self.hz.fine.P[3] = np.nan
        return res

    monkeypatch.setattr(line_solve._LineStepper, "solve_step", step)


@pytest.mark.solver
@pytest.mark.parametrize("how", ["nan", "raise"])
def test_a_failing_step_keeps_the_steps_before_it_marked_incomplete_with_exit_3(
        dent_scene, tmp_path, monkeypatch, capsys, how):
    _failing_after(monkeypatch, 4, how)
    out = tmp_path / "out"
    rc = main(["transient", dent_scene, "--accuracy", "none", "--points", "129", "--steps", "10", "--snapshot-every", "3",
               "--out", str(out), "--json"])
    assert rc == 3
    f = load_series(out / H5)
    assert not f["complete"] and not is_complete(out / H5)
    assert list(f["series"]["step"]) == [0, 1, 2, 3, 4]
    assert "step 5" in f["stop_reason"] and "steps 0..4" in f["stop_reason"]
    assert list(f["snapshots"]["step"]) == [0, 3, 4]  # the kept steps and the last completed one
    assert f["state"]["step"] == 4 and np.all(np.isfinite(f["state"]["P"]))
    err = capsys.readouterr().err
    assert re.search(r"\bsteps 0\.\.4\b.*\b10\b", err) and "complete = False" in err
    assert not [p for p in os.listdir(out) if p.endswith(".tmp")]


@pytest.mark.parametrize(("cavitation", "extra"), [("projection", []), ("mass-conserving", []),
                                                   ("mass-conserving", ["--time-tol", "1e-3"])])
def test_an_interrupted_run_resumed_repeats_the_uninterrupted_run(dent_scene, tmp_path, monkeypatch,
                                                                  cavitation, extra):
    args = ["transient", dent_scene, "--accuracy", "none", "--points", "129", "--steps", "12", "--snapshot-every", "5",
            "--no-plots", "--cavitation", cavitation, *extra]
    with monkeypatch.context() as m:
        _failing_after(m, 7, "interrupt")
        assert main([*args, "--out", str(tmp_path / "a")]) == 130
    stopped = load_series(tmp_path / "a" / H5)
    assert not stopped["complete"] and "interrupted" in stopped["stop_reason"]
    assert stopped["state"]["step"] == 7 if not extra else 1 <= stopped["state"]["step"] < 7
    assert main([*args, "--out", str(tmp_path / "a"), "--resume"]) == 0
    assert main([*args, "--out", str(tmp_path / "b")]) == 0
    resumed, straight = load_series(tmp_path / "a" / H5), load_series(tmp_path / "b" / H5)
    assert resumed["complete"] and "state" not in resumed
    for k in ("step", "T", "Hc", "Hm", "H0", "dP", "cycles"):
        assert np.array_equal(resumed["series"][k], straight["series"][k]), k
    assert np.array_equal(resumed["snapshots"]["step"], straight["snapshots"]["step"])
    assert np.array_equal(resumed["snapshots"]["P"], straight["snapshots"]["P"])
    if cavitation == "mass-conserving":  # the film content is part of the state
        assert np.array_equal(resumed["snapshots"]["theta"], straight["snapshots"]["theta"])
        assert np.array_equal(resumed["series"]["mass_error"], straight["series"]["mass_error"],
                              equal_nan=True)


def test_a_signal_surfacing_from_a_compiled_kernel_stops_the_run_as_a_signal(
        dent_scene, tmp_path, monkeypatch, capsys):
    _failing_after(monkeypatch, 3, "signal in a kernel")
    out = tmp_path / "out"
    assert main(["transient", dent_scene, "--accuracy", "none", "--points", "129", "--steps", "10", "--out", str(out)]) == 143
    f = load_series(out / H5)
    assert not f["complete"] and f["stop_reason"].startswith("terminated (SIGTERM) during step 4")
    assert "Traceback" not in capsys.readouterr().err


def test_a_signal_while_a_step_is_recorded_keeps_the_series_and_the_state_together(
        dent_scene, tmp_path, monkeypatch):
    # SIGTERM lands between the step's series entry and its state (the race CI once hit)
    from ehl_multigrid.transient.result import TransientResult
    original = TransientResult.record

    def record(self, n, *args, **kwargs):
        original(self, n, *args, **kwargs)
        if n == 3:
            os.kill(os.getpid(), signal.SIGTERM)

    monkeypatch.setattr(TransientResult, "record", record)
    out = tmp_path / "out"
    assert main(["transient", dent_scene, "--accuracy", "none", "--points", "129", "--steps", "10", "--no-plots",
                 "--out", str(out)]) == 143
    f = load_series(out / H5)
    assert not f["complete"] and "terminated (SIGTERM)" in f["stop_reason"]
    assert f["state"]["step"] == 3
    assert {len(v) for v in f["series"].values()} == {4}


def test_resume_refuses_a_complete_file_and_other_options(dent_scene, tmp_path, capsys):
    args = ["transient", dent_scene, "--accuracy", "none", "--points", "129", "--steps", "2", "--no-plots", "--out", str(tmp_path)]
    assert main([*args, "--resume"]) == 2
    assert "no checkpoint" in capsys.readouterr().err
    assert main(args) == 0
    assert main([*args, "--resume"]) == 2
    assert "complete run" in capsys.readouterr().err


def _start(dent_scene, out, *extra):
    """``ehl transient`` in a subprocess on a run far too long to finish; returns it once its
    first checkpoint (the start) is on disk."""
    proc = subprocess.Popen([sys.executable, "-m", "ehl_multigrid", "transient", dent_scene,
                             "--accuracy", "none", "--points", "129", "--steps", "100000", "--no-plots", "--out", str(out),
                             *extra], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while not (out / H5).exists():
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() < deadline, "no checkpoint within 120 s"
        time.sleep(0.1)
    return proc


@pytest.mark.solver
def test_sigterm_leaves_a_valid_file_of_the_finished_steps_marked_incomplete(dent_scene, tmp_path):
    out = tmp_path / "out"
    proc = _start(dent_scene, out)
    time.sleep(1.0)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 143, err
    f = load_series(out / H5)
    assert not f["complete"] and "terminated (SIGTERM)" in f["stop_reason"]
    n = f["state"]["step"]
    assert n >= 1 and len(f["series"]["step"]) == n + 1 and f["snapshots"]["step"][-1] == n
    assert f"steps 0..{n}" in err and "--resume" in err
    assert not [p for p in os.listdir(out) if p.endswith(".tmp")]


@pytest.mark.solver
def test_sigkill_leaves_the_last_checkpoint(dent_scene, tmp_path):
    out = tmp_path / "out"
    proc = _start(dent_scene, out, "--checkpoint-every", "0.2")
    time.sleep(1.5)
    proc.kill()
    proc.communicate(timeout=60)
    f = load_series(out / H5)
    assert not f["complete"] and f["stop_reason"].startswith("running: checkpoint after step")
    n = f["state"]["step"]
    assert len(f["series"]["step"]) == n + 1 and f["snapshots"]["step"][-1] == n


class _Run:
    """The parts of a result that :class:`Checkpoint` reads."""

    def __init__(self):
        self.steps, self.planned_steps, self.complete, self.stop_reason = 0, 100, True, ""
        self.series = {"T": [0.0]}
        self.written = []

    def to_hdf5(self, path):
        self.written.append((self.steps, self.complete, self.stop_reason))
        return path


def test_checkpoints_follow_the_interval_and_keep_their_writing_cost_small(tmp_path):
    now = [0.0]
    cost = [0.0]

    def clock():
        return now[0]

    run = _Run()
    ck = Checkpoint(tmp_path / "x.h5", every_s=30.0, clock=clock)

    def to_hdf5(path):  # each write takes `cost` seconds
        run.written.append((run.steps, run.complete, run.stop_reason))
        now[0] += cost[0]
        return path

    run.to_hdf5 = to_hdf5
    for step, t in enumerate([0.0, 10.0, 29.0, 31.0, 50.0, 62.0]):
        run.steps, now[0] = step, t
        ck.step(run)
    assert [w[0] for w in run.written] == [0, 3, 5]  # the start, then every 30 s
    assert all(not w[1] and w[2].startswith("running") for w in run.written)
    assert run.complete and run.stop_reason == ""  # the run itself is not marked
    cost[0] = 4.0  # a slow write: the next one waits 4 / 0.05 = 80 s instead of 30
    run.steps, now[0] = 6, 100.0
    ck.step(run)
    run.steps, now[0] = 7, 104.0 + 79.0
    ck.step(run)
    run.steps, now[0] = 8, 104.0 + 81.0
    ck.step(run)
    assert [w[0] for w in run.written] == [0, 3, 5, 6, 8]
