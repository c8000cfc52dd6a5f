"""Progress when stderr is not a terminal (a log file, a pipe, a batch job): plain lines on
stderr, at most one every interval (seconds, ``EHL_PROGRESS_INTERVAL``), nothing on stdout
(which may carry the ``--json`` payload); ``EHL_PROGRESS=off`` silences them."""

from __future__ import annotations

import json
import re

import pytest

import ehl_multigrid.app.mainjob as mainjob
from ehl_multigrid.app.cli import main
from ehl_multigrid.app.console import Progress, progress_mode

LINE = re.compile(r"^ehl [a-z]+.*: .+ \(\d+\.\d s\)$")


class Clock:
    def __init__(self):
        self.t = 0.0

    def __call__(self):
        return self.t


class Log:
    """What a test wrote to stderr (captured by pytest: not a terminal)."""

    def __init__(self, capsys):
        self.capsys = capsys

    def getvalue(self) -> str:
        return self.capsys.readouterr().err


@pytest.fixture
def log(monkeypatch, capsys):
    monkeypatch.delenv("EHL_PROGRESS", raising=False)
    monkeypatch.delenv("EHL_PROGRESS_INTERVAL", raising=False)
    return Log(capsys)


def test_lines_are_rate_limited_but_the_last_step_and_forced_ones_always_show(log):
    clock = Clock()
    p = Progress("ehl demo", total=4, unit="cases", interval=10.0, clock=clock)
    assert p.mode == "lines"
    p.status("first")  # the first line is shown at once
    clock.t = 3.0
    p.status("too soon")
    p.advance()
    clock.t = 12.0
    p.advance(text="1 failed")  # 10 s after the last line
    clock.t = 13.0
    p.advance()
    p.status("stage x", force=True)
    p.advance()  # the last step
    p.close()
    lines = log.getvalue().splitlines()
    assert lines == ["ehl demo: first (0.0 s)", "ehl demo: 2/4 cases, 1 failed (12.0 s)",
                     "ehl demo: stage x (13.0 s)", "ehl demo: 4/4 cases (13.0 s)"]


def test_solver_cycles_become_lines_naming_grid_residual_and_load_error(log):
    p = Progress("ehl solve", interval=0.0)
    p.solver_callback({"level": 3, "points": 1025, "cycle": 2, "residual": 2.1e-7, "load_error": 3e-5})
    p.say("1025 points, box x1: estimated error Hc 0.21%, Hm 0.40% (12.3 s)")
    line, said = log.getvalue().splitlines()
    assert "grid 1025 points" in line and "cycle 2" in line and "residual 2.1e-07" in line and "3e-05" in line
    assert said == "ehl solve: 1025 points, box x1: estimated error Hc 0.21%, Hm 0.40% (12.3 s)"


def test_progress_can_be_switched_off_or_forced(monkeypatch, log):
    monkeypatch.setenv("EHL_PROGRESS", "off")
    assert progress_mode() == "off"
    with Progress("ehl demo", total=1) as p:
        p.status("x", force=True)
        p.say("y")
        p.advance()
    assert log.getvalue() == ""
    monkeypatch.setenv("EHL_PROGRESS", "bar")
    with Progress("ehl demo", total=2, unit="cases") as p:
        p.advance()
    bar = log.getvalue()
    assert "ehl demo" in bar and "1/2" in bar and "\r" in bar  # tqdm's bar


def test_solve_off_a_terminal_prints_progress_lines_on_stderr_and_only_json_on_stdout(tmp_path, capsys,
                                                                                       monkeypatch):
    monkeypatch.setenv("EHL_PROGRESS_INTERVAL", "0")
    assert main(["solve", "--contact", "line", "--M", "20", "--L", "10", "--points", "129", "--accuracy",
                 "none", "--no-plots", "--json", "--out", str(tmp_path)]) == 0
    captured = capsys.readouterr()
    assert json.loads(captured.out)["points"] == 129  # stdout is the payload alone
    lines = [ln for ln in captured.err.splitlines() if ln.startswith("ehl solve")]
    cycles = [ln for ln in lines if "grid " in ln and "residual" in ln]
    assert len(cycles) >= 3 and all(LINE.match(ln) for ln in cycles)
    assert any("grid 129 points" in ln for ln in cycles)


def test_run_off_a_terminal_prints_a_line_per_stage(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(mainjob, "registered_stages", lambda: [])
    from ehl_multigrid.model.scene import load_scene

    mainjob.run_main_job(load_scene("page63_line_500N"),
                         mainjob.MainJobOptions(out_dir=tmp_path, fidelity="fast", plots=False, quiet=True))
    captured = capsys.readouterr()
    assert captured.out == ""
    lines = captured.err.splitlines()
    assert lines[0].startswith("ehl run page63_line_500N: stage 1/1 film")
    assert lines[-1].startswith("ehl run page63_line_500N: 1/1 stages") and LINE.match(lines[-1])


def test_sweep_off_a_terminal_counts_its_cases(tmp_path, capsys):
    import concurrent.futures as cf

    from ehl_multigrid.app.sweep import SweepSpec, run_sweep
    from ehl_multigrid.model.scene import load_scene

    spec = SweepSpec(load_scene("page63_line_500N"), "fit", {"operating.us": [1.0, 2.0, 3.0]})
    with cf.ThreadPoolExecutor(1) as ex:
        run_sweep(spec, tmp_path, executor=ex)
    err = capsys.readouterr().err.splitlines()
    assert err and err[-1].startswith("ehl sweep fit: 3/3 cases")
