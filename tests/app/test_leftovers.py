"""Nothing half-written and nothing left behind: temporary files and staging folders carry the
writer's PID; the next command into the folder removes those of dead writers (and old ones of
earlier versions) but never a live writer's file or a user's file; atomic writes leave either
the whole new file or the old one; staged outputs publish only finished files."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from matplotlib.figure import Figure

import ehl_multigrid.model.paths as paths
from ehl_multigrid.model.atomic import atomic_savefig, deferred_signals, write_text_atomic
from ehl_multigrid.model.output_folder import StagedOutputs, output_lock, remove_leftovers
from ehl_multigrid.model.paths import record_outputs


def dead_pid() -> int:
    p = subprocess.Popen([sys.executable, "-c", "pass"])
    p.wait()
    return p.pid


@pytest.fixture
def live_child():
    p = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    yield p
    p.kill()
    p.wait()


def make(path: Path, size: int = 100, age_s: float = 0.0) -> Path:
    if path.name.startswith(".ehl-run-") and not path.name.endswith(".json"):  # a staging folder
        path.mkdir()
        (path / "film.png").write_bytes(b"x" * size)
    else:
        path.write_bytes(b"x" * size)
    if age_s:
        t = time.time() - age_s
        os.utime(path, (t, t))
    return path


def test_leftovers_of_dead_writers_are_removed_and_their_sizes_reported(tmp_path):
    pid = dead_pid()
    make(tmp_path / f".ehl-run-scene.pid{pid}.ab12_xyz", 3000)
    make(tmp_path / f".scene.h5.pid{pid}.k2j4h5g6.tmp", 500)
    make(tmp_path / f".anim.gif.pid{pid}.k2j4h5g6.tmp.gif", 50)
    removed = dict((p.name, size) for p, size in remove_leftovers(tmp_path))
    assert removed == {f".ehl-run-scene.pid{pid}.ab12_xyz": 3000, f".scene.h5.pid{pid}.k2j4h5g6.tmp": 500,
                       f".anim.gif.pid{pid}.k2j4h5g6.tmp.gif": 50}
    assert list(tmp_path.iterdir()) == []


def test_a_live_writers_files_are_kept_until_it_dies(tmp_path, live_child):
    staging = make(tmp_path / f".ehl-run-scene.pid{live_child.pid}.ab12_xyz")
    tmp = make(tmp_path / f".scene.h5.pid{live_child.pid}.k2j4h5g6.tmp")
    own = make(tmp_path / f".table.csv.pid{os.getpid()}.k2j4h5g6.tmp")
    assert remove_leftovers(tmp_path) == []
    live_child.kill()
    live_child.wait()
    assert {p for p, _ in remove_leftovers(tmp_path)} == {staging, tmp}
    assert own.exists()  # this process's own temporary file


def test_a_reused_pid_does_not_protect_an_older_leftover(tmp_path, live_child):
    # the leftover was last changed an hour before the process with its PID started
    old = make(tmp_path / f".scene.h5.pid{live_child.pid}.k2j4h5g6.tmp", age_s=3600)
    assert [p for p, _ in remove_leftovers(tmp_path)] == [old]


def test_leftovers_of_earlier_versions_are_removed_once_they_are_old(tmp_path):
    young = make(tmp_path / ".scene.h5.k2j4h5g6.tmp")
    old = [make(tmp_path / ".scene.h5.a1b2c3d4.tmp", age_s=600),
           make(tmp_path / "tmpa1b2c3d4.h5.tmp", age_s=600),
           make(tmp_path / "..ehl-files-scene.json.a1b2c3d4", age_s=600),
           make(tmp_path / ".ehl-write-probe-a1b2c3d4", age_s=600),
           make(tmp_path / ".ehl-run-scene-86__rolk", age_s=600)]
    assert sorted(p for p, _ in remove_leftovers(tmp_path)) == sorted(old)
    assert young.exists()


def test_user_files_results_indexes_and_the_lock_are_never_removed(tmp_path):
    pid = dead_pid()
    keep = [make(tmp_path / n, age_s=3600) for n in (
        "notes.tmp", "scene.h5", ".hidden_notes", ".ehl.lock", ".ehl-run-scene.json", ".ehl-files-scene.json",
        f"my.pid{pid}.data.tmp")]  # not hidden: not a name this package writes
    (tmp_path / "cases").mkdir()
    assert remove_leftovers(tmp_path) == []
    assert all(p.exists() for p in keep)


def test_taking_the_lock_cleans_the_folder_and_the_named_subfolders(tmp_path):
    pid = dead_pid()
    (tmp_path / "cases").mkdir()
    a = make(tmp_path / f".sweep.json.pid{pid}.k2j4h5g6.tmp")
    b = make(tmp_path / "cases" / f".case_1.json.pid{pid}.k2j4h5g6.tmp")
    with output_lock(tmp_path, "ehl sweep", subfolders=("cases",)) as removed:
        assert sorted(p for p, _ in removed) == sorted([a, b])


def test_an_interrupted_figure_leaves_neither_a_partial_file_nor_a_temporary_one(tmp_path):
    target = tmp_path / "maps.png"
    target.write_bytes(b"the previous figure")

    class Stop(BaseException):
        pass

    fig = Figure()
    fig.subplots().plot([0, 1], [0, 1])

    def stop_while_writing(*args, **kwargs):
        Path(args[0]).write_bytes(b"\x89PNG\r\n\x1a\n half")  # a truncated image
        raise Stop

    fig.savefig = stop_while_writing
    with pytest.raises(Stop):
        atomic_savefig(fig, target)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["maps.png"]
    assert target.read_bytes() == b"the previous figure"


def test_a_saved_figure_is_whole_and_has_the_users_file_mode(tmp_path):
    fig = Figure()
    fig.subplots().plot([0, 1], [0, 1])
    old = os.umask(0o022)
    try:
        path = atomic_savefig(fig, tmp_path / "a.png", dpi=50)
    finally:
        os.umask(old)
    data = path.read_bytes()
    assert data.startswith(b"\x89PNG") and data.endswith(b"IEND\xaeB`\x82")
    assert oct(path.stat().st_mode & 0o777) == oct(0o644)
    assert [p.name for p in tmp_path.iterdir()] == ["a.png"]


def test_staged_outputs_publish_only_finished_files_and_forget_the_rest(tmp_path):
    (tmp_path / "r_maps.png").write_text("figure of the previous run")
    record_outputs(tmp_path, "r", [tmp_path / "r_maps.png"])
    with pytest.raises(KeyboardInterrupt):
        with StagedOutputs(tmp_path, "r") as st:
            st.done(write_text_atomic(st.path("r.h5"), "result"))
            st.path("r_profiles.png").write_text("cut short")
            raise KeyboardInterrupt
    assert sorted(p.name for p in tmp_path.iterdir() if not p.name.startswith(".")) == ["r.h5"]
    assert [p for p in tmp_path.iterdir() if p.is_dir()] == []
    index = json.loads((tmp_path / ".ehl-files-r.json").read_text())
    assert index["files"] == ["r.h5"] and index["removing"] == ["r_maps.png"]


def test_the_index_is_written_before_old_files_are_deleted(tmp_path, monkeypatch):
    """A crash between the two leaves the old files named under 'removing', and the next
    run deletes them."""
    for n in ("r.h5", "r_maps.png"):
        (tmp_path / n).write_text("x")
    record_outputs(tmp_path, "r", [tmp_path / "r.h5", tmp_path / "r_maps.png"])

    def crash(folder, names):
        raise KeyboardInterrupt

    monkeypatch.setattr(paths, "_remove_plain_files", crash)
    with pytest.raises(KeyboardInterrupt):
        record_outputs(tmp_path, "r", [tmp_path / "r.h5"])
    index = json.loads((tmp_path / ".ehl-files-r.json").read_text())
    assert index["files"] == ["r.h5"] and (tmp_path / "r_maps.png").exists()
    monkeypatch.undo()
    assert [p.name for p in record_outputs(tmp_path, "r", [tmp_path / "r.h5"])] == ["r_maps.png"]


def test_a_stop_request_waits_for_the_files_being_moved(tmp_path):
    class Stopped(BaseException):
        pass

    def raise_stopped(signum, frame):
        raise Stopped

    previous = signal.signal(signal.SIGTERM, raise_stopped)
    moved = []
    try:
        with pytest.raises(Stopped):
            with deferred_signals():
                os.kill(os.getpid(), signal.SIGTERM)
                time.sleep(0.05)
                moved.append("after the signal")  # still runs
        assert moved == ["after the signal"]
        assert signal.getsignal(signal.SIGTERM) is raise_stopped
    finally:
        signal.signal(signal.SIGTERM, previous)
