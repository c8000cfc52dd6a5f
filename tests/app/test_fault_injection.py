"""Fault injection: ``ehl run``, ``ehl solve``, ``ehl sweep`` and ``ehl transient`` stopped by
SIGTERM or killed by SIGKILL at given moments leave an output folder that holds only complete,
valid files (HDF5 that opens and says whether it is complete, PNG with its IEND chunk, JSON and
CSV that parse, indexes that list only existing files), and the next run into the folder leaves
no temporary file and no staging folder.

The moments are chosen with the test hook of :func:`ehl_multigrid.model.atomic.fault_point`
(``EHL_FAULT_AT=<point>``, ``EHL_FAULT_SIGNAL=TERM|KILL``, ``EHL_FAULT_COUNT=n``: the process
signals itself the n-th time it reaches the point), or by watching the output folder (SIGTERM
while the real traction stage writes its first figure, the issue's reproduction). SIGTERM runs
in this process through ``ehl_multigrid.app.cli.main`` (its handler turns the signal into an
exception); SIGKILL needs a child process. The default set takes about a minute; the full
matrix of points and signals is marked slow.
"""

from __future__ import annotations

import csv
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import h5py
import pytest

import ehl_multigrid.model.atomic as atomic
from ehl_multigrid.app.cli import main

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
PNG_END = b"IEND\xaeB`\x82"
#: hidden files an output folder keeps: the indexes of the runs (the lock file ``.ehl.lock`` is
#: deleted by its holder; a killed holder's stays until the next command)
INDEX_PREFIXES = (".ehl-run-", ".ehl-files-")

RUN = ["run", "page63_line_500N", "--fidelity", "fast"]
SOLVE = ["solve", "--contact", "line", "--M", "20", "--L", "10", "--points", "129", "--accuracy", "none"]
SWEEP = ["sweep", "page63_line_500N", "--task", "fit", "--param", "operating.us=1,2,3", "--workers", "1"]


# -- checks ------------------------------------------------------------------------------------
def assert_complete_file(path: Path) -> None:
    """``path`` is a whole file of its kind."""
    data = path.read_bytes()
    suffix = path.suffix.lower()
    if suffix == ".png":
        assert data.startswith(PNG_SIGNATURE) and data.endswith(PNG_END), \
            f"{path.name}: truncated PNG ({len(data)} bytes)"
        import matplotlib.image

        assert matplotlib.image.imread(path).size > 0
    elif suffix == ".gif":
        assert data.startswith(b"GIF8") and data.endswith(b";"), f"{path.name}: truncated GIF"
    elif suffix == ".h5":
        with h5py.File(path, "r") as f:
            assert "complete" in f.attrs, f"{path.name} does not say whether it is complete"
            assert_complete_attribute_is_right(path, f)
    elif suffix == ".json":
        json.loads(data)
    elif suffix == ".csv":
        rows = list(csv.reader(data.decode().splitlines()))
        assert rows and rows[0], f"{path.name}: no header"
        assert all(len(r) == len(rows[0]) for r in rows), f"{path.name}: ragged rows (truncated?)"
    elif suffix == ".md":
        text = data.decode()
        assert text.startswith("# ") and text.endswith("\n"), f"{path.name}: truncated report"
    else:
        raise AssertionError(f"unexpected file {path.name} in the output folder")


def assert_complete_attribute_is_right(path: Path, f: h5py.File) -> None:
    complete = bool(f.attrs["complete"])
    if f.attrs.get("kind") == "collection":  # ehl run: complete when every planned stage ran
        planned = json.loads(f.attrs["stages_planned"])
        ran = json.loads(f.attrs["stages_run"])
        assert complete == (ran == planned), f"{path.name}: complete = {complete}, stages {ran} of {planned}"
        assert set(f.keys()) <= set(ran)
        report = path.with_name(f"{path.stem}_report.md")
        if report.exists():
            assert ("Incomplete run" in report.read_text()) == (not complete), \
                f"{report.name} and {path.name} disagree on completeness"
    if "planned_steps" in f.attrs and "last_step" in f.attrs:  # ehl transient: every step ran
        done = int(f.attrs["last_step"]) == int(f.attrs["planned_steps"])
        assert done or not complete, \
            f"{path.name}: complete after step {f.attrs['last_step']} of {f.attrs['planned_steps']}"


def check_output_folder(out: Path, leftovers_allowed: bool = False) -> dict[str, int]:
    """Every visible file of ``out`` (and ``out/cases``) is complete and valid, every index
    lists only existing files; without ``leftovers_allowed`` there is no temporary file and no
    staging folder. Returns the leftovers found: name -> bytes."""
    leftovers: dict[str, int] = {}
    for p in sorted(out.rglob("*")):
        rel = p.relative_to(out)
        hidden = any(part.startswith(".") for part in rel.parts)
        top_hidden = p.parent == out and p.name.startswith(".")
        if p.is_dir():
            if hidden:
                leftovers[str(rel)] = sum(q.stat().st_size for q in p.rglob("*") if q.is_file())
            continue
        if hidden or p.name.endswith(".tmp") or ".tmp." in p.name:
            if top_hidden and p.name.startswith(INDEX_PREFIXES) and p.name.endswith(".json"):
                continue
            if not any(str(rel).startswith(d) for d in leftovers):
                leftovers[str(rel)] = p.stat().st_size
            continue
        assert_complete_file(p)
    for index in out.glob(".ehl-*.json"):
        listed = json.loads(index.read_text())["files"]
        missing = [n for n in listed if not (out / n).is_file()]
        assert not missing, f"{index.name} lists files that do not exist: {missing}"
    table = out / "table.json"
    if table.exists():
        t = json.loads(table.read_text())
        assert t["complete"] == (len(t["rows"]) == t["planned"])
    if not leftovers_allowed:
        assert not leftovers, f"left over in {out}: {leftovers}"
    return leftovers


# -- running -----------------------------------------------------------------------------------
@pytest.fixture
def fault(monkeypatch):
    """``fault(point, count=1)``: arm the hook for an in-process run (SIGTERM)."""
    monkeypatch.setattr(atomic, "_fault_hits", {})

    def arm(point: str | None, count: int = 1) -> None:
        atomic._fault_hits.clear()
        if point is None:
            monkeypatch.delenv("EHL_FAULT_AT", raising=False)
            return
        monkeypatch.setenv("EHL_FAULT_AT", point)
        monkeypatch.setenv("EHL_FAULT_SIGNAL", "TERM")
        monkeypatch.setenv("EHL_FAULT_COUNT", str(count))

    monkeypatch.setenv("MPLBACKEND", "Agg")
    yield arm
    atomic._fault_hits.clear()


def ehl_child(argv: list[str], point: str | None = None, sig: str = "KILL", count: int = 1,
              timeout: float = 300.0) -> subprocess.CompletedProcess:
    """``ehl argv`` in a child process, killed by ``sig`` at the fault point ``point``."""
    env = {k: v for k, v in os.environ.items() if k not in atomic.FAULT_ENV}
    env.update(MPLBACKEND="Agg", EHL_PROGRESS="lines", EHL_PROGRESS_INTERVAL="0")
    if point is not None:
        env.update(EHL_FAULT_AT=point, EHL_FAULT_SIGNAL=sig, EHL_FAULT_COUNT=str(count))
    return subprocess.run([sys.executable, "-m", "ehl_multigrid", *argv], env=env, capture_output=True,
                          text=True, timeout=timeout)


def killed(proc: subprocess.CompletedProcess, sig: str) -> None:
    expected = -signal.SIGKILL if sig == "KILL" else 143
    assert proc.returncode == expected, f"exit {proc.returncode}, stderr: {proc.stderr[-800:]}"


def transient_scene(folder: Path) -> Path:
    """A TOML scene with a dent passing through the page 63 line contact (2000 N)."""
    from ehl_multigrid.line.problem import LineProblem
    from ehl_multigrid.model.scene import Scene, load_scene

    d = load_scene("page63_line_2000N").to_dict()
    pb = LineProblem.from_scene(Scene.from_dict(d), xmin=-4.5)
    d["feature"] = {"kind": "dent", "amplitude": 0.5 * 0.0084 * pb.b**2 / pb.R, "width": 0.5 * pb.b, "x0": -3.0}
    d["name"] = "dent"
    path = folder / "dent.toml"
    path.write_text(Scene.from_dict(d).to_toml())
    return path


def transient_args(scene: Path) -> list[str]:
    return ["transient", str(scene), "--accuracy", "none", "--points", "129", "--steps", "4"]


# -- ehl run -----------------------------------------------------------------------------------
@pytest.mark.solver
def test_run_stopped_while_a_stage_plots_and_then_killed_leaves_only_whole_files(tmp_path, fault, capsys):
    out = tmp_path / "out"
    # SIGTERM while the traction stage writes its first figure, the run's second (the issue: a
    # 124-byte PNG reached the folder and its index); only the finished film stage is published
    fault("savefig", count=2)
    assert main([*RUN, "--out", str(out)]) == 143
    fault(None)
    err = capsys.readouterr().err
    assert "terminated" in err and "the finished stages (film) were written to" in err
    assert str(out / "page63_line_500N.h5") in err
    check_output_folder(out)
    assert not list(out.glob("traction_*")) and (out / "page63_line_500N_film.png").is_file()
    with h5py.File(out / "page63_line_500N.h5") as f:
        assert not f.attrs["complete"] and list(f.keys()) == ["film"]
    # SIGKILL when the stribeck stage starts: the traction figures stay in the staging folder,
    # the folder still shows the previous (stopped) run
    killed(ehl_child([*RUN, "--out", str(out)], "run.stage.stribeck", "KILL"), "KILL")
    left = check_output_folder(out, leftovers_allowed=True)
    assert any(name.startswith(".ehl-run-") for name in left)
    # the next run removes the dead run's staging folder and the stale figure of the first one
    assert main([*RUN, "--no-plots", "--out", str(out)]) == 0
    err = capsys.readouterr().err
    assert "removed" in err and "leftover" in err
    check_output_folder(out)
    assert sorted(p.name for p in out.iterdir() if not p.name.startswith(".")) == [
        "page63_line_500N.h5", "page63_line_500N_report.md"]


# -- ehl solve ---------------------------------------------------------------------------------
@pytest.mark.solver
def test_solve_stopped_while_plotting_keeps_the_result_and_no_figure_of_the_stopped_call(tmp_path, fault, capsys):
    out = tmp_path / "out"
    assert main([*SOLVE, "--out", str(out), "--csv"]) == 0  # an earlier run with figures
    fault("savefig", count=2)  # stopped while the second figure (the zoom) is being saved
    assert main([*SOLVE, "--out", str(out), "--csv"]) == 143
    check_output_folder(out)
    # the new result and CSV; the earlier run's figures are not left beside the new result
    assert sorted(p.name for p in out.iterdir() if not p.name.startswith(".")) == [
        "line_M20_L10.h5", "line_M20_L10_profile.csv"]
    with h5py.File(out / "line_M20_L10.h5") as f:
        assert f.attrs["complete"]
    # killed with the first figure written but not renamed: nothing of it reaches the folder
    killed(ehl_child([*SOLVE, "--out", str(out)], "savefig", "KILL"), "KILL")
    left = check_output_folder(out, leftovers_allowed=True)
    assert any(name.startswith(".ehl-run-line_M20_L10.pid") for name in left)
    assert set(left) <= {".ehl.lock"} | {n for n in left if n.startswith(".ehl-run-line_M20_L10.pid")}
    fault(None)
    assert main([*SOLVE, "--out", str(out)]) == 0
    check_output_folder(out)
    assert (out / "line_M20_L10_zoom.png").is_file()


# -- ehl sweep ---------------------------------------------------------------------------------
@pytest.mark.solver
def test_sweep_stopped_or_killed_after_a_case_resumes_into_a_clean_complete_table(tmp_path, fault, capsys):
    out = tmp_path / "sweep"
    fault("sweep.case")
    assert main([*SWEEP, "--out", str(out)]) == 143
    check_output_folder(out)
    table = json.loads((out / "table.json").read_text())
    assert table["complete"] is False and 1 <= len(table["rows"]) < 3
    killed(ehl_child([*SWEEP, "--out", str(out)], "sweep.table", "KILL"), "KILL")
    check_output_folder(out, leftovers_allowed=True)
    fault(None)
    assert main([*SWEEP, "--out", str(out)]) == 0
    check_output_folder(out)
    table = json.loads((out / "table.json").read_text())
    assert table["complete"] is True and len(table["rows"]) == 3


# -- ehl transient -----------------------------------------------------------------------------
def test_transient_stopped_while_writing_its_file_leaves_only_whole_files(tmp_path, fault, capsys):
    out = tmp_path / "out"
    fault("h5")  # the first HDF5 write: the checkpoint of the start
    assert main([*transient_args(transient_scene(tmp_path)), "--out", str(out)]) == 143
    check_output_folder(out)
    for h5 in out.glob("*.h5"):
        with h5py.File(h5) as f:
            assert not f.attrs["complete"]


@pytest.mark.solver
def test_transient_killed_while_writing_its_file_is_cleaned_by_the_next_run(tmp_path, fault, capsys):
    out = tmp_path / "out"
    scene = transient_scene(tmp_path)
    killed(ehl_child([*transient_args(scene), "--out", str(out)], "h5", "KILL"), "KILL")
    assert check_output_folder(out, leftovers_allowed=True)  # the temporary HDF5 of the dead run
    fault(None)
    assert main([*transient_args(scene), "--out", str(out), "--no-plots"]) == 0
    check_output_folder(out)


# -- the full matrix (slow) --------------------------------------------------------------------
MATRIX = [
    ("run", "run.stage.film"), ("run", "run.stage.traction"), ("run", "run.stage.stribeck"),
    ("run", "h5"), ("run", "run.publish"), ("run", "publish"),
    ("solve", "savefig"), ("solve", "h5"), ("solve", "solve.plots"), ("solve", "publish"), ("solve", "rename"),
    ("sweep", "sweep.case"), ("sweep", "sweep.table"), ("sweep", "rename"),
    ("transient", "h5"), ("transient", "rename"),
]


@pytest.mark.slow
@pytest.mark.parametrize("sig", ["TERM", "KILL"])
@pytest.mark.parametrize("command, point", MATRIX)
def test_every_fault_point_leaves_whole_files_and_the_next_run_cleans_up(command, point, sig, tmp_path):
    out = tmp_path / "out"
    argv = {"run": [*RUN, "--tolerance", "0.05"], "solve": SOLVE, "sweep": SWEEP,
            "transient": transient_args(transient_scene(tmp_path)) if command == "transient" else []}[command]
    if command != "sweep":  # a complete earlier run in the folder (a sweep would resume it: no case left)
        first = ehl_child([*argv, "--out", str(out)])
        assert first.returncode == 0, first.stderr[-800:]
    killed(ehl_child([*argv, "--out", str(out)], point, sig), sig)
    check_output_folder(out, leftovers_allowed=sig == "KILL")
    again = ehl_child([*argv, "--out", str(out)])
    assert again.returncode == 0, again.stderr[-800:]
    check_output_folder(out)


#: a point solve whose accuracy sequence runs several seconds (exit 3 if it misses the target)
SOLVE_POINT = ["solve", "--contact", "point", "--M", "20", "--L", "10", "--accuracy", "0.02",
               "--max-points", "257"]


@pytest.mark.slow
@pytest.mark.parametrize("delay", [1.0, 3.0, 6.0])
@pytest.mark.parametrize("sig", ["TERM", "KILL"])
@pytest.mark.parametrize("command", ["run", "solve", "transient"])
def test_a_signal_at_any_moment_leaves_whole_files(command, sig, delay, tmp_path):
    """Signals at fixed delays after the first progress line, wherever the command then is."""
    out = tmp_path / "out"
    argv = {"run": RUN, "solve": SOLVE_POINT, "transient": transient_args(transient_scene(tmp_path))
            if command == "transient" else []}[command]
    env = {k: v for k, v in os.environ.items() if k not in atomic.FAULT_ENV}
    env.update(MPLBACKEND="Agg", EHL_PROGRESS="lines", EHL_PROGRESS_INTERVAL="0")
    proc = subprocess.Popen([sys.executable, "-m", "ehl_multigrid", *argv, "--out", str(out)], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if command != "transient":
        proc.stderr.readline()  # the first progress line: the work has started
    time.sleep(delay)
    proc.send_signal(getattr(signal, f"SIG{sig}"))
    proc.communicate(timeout=300)
    check_output_folder(out, leftovers_allowed=sig == "KILL")
    again = ehl_child([*argv, "--out", str(out)])
    assert again.returncode in (0, 3), again.stderr[-800:]  # 3: written, short of its accuracy
    check_output_folder(out)
