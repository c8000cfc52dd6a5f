"""One command at a time per output folder: ``ehl run``, ``ehl solve``, ``ehl sweep`` and
``ehl transient`` take the folder's lock (``fcntl.flock`` on ``<out>/.ehl.lock``); a second
process writing into the same folder is refused at once (exit 2) with a message naming the
folder and the PID that holds it, and the lock of a process that dies is released."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.output_folder import LOCK_NAME, OutputLocked, output_lock

HOLD = ("import sys\n"
        "from ehl_multigrid.model.output_folder import output_lock\n"
        "with output_lock(sys.argv[1], 'ehl run'):\n"
        "    print('locked', flush=True)\n"
        "    sys.stdin.read()\n")


@pytest.fixture
def holder():
    """``holder(folder)``: a child process that holds the lock of ``folder`` until the test ends."""
    procs = []

    def start(folder):
        p = subprocess.Popen([sys.executable, "-c", HOLD, str(folder)], stdin=subprocess.PIPE,
                             stdout=subprocess.PIPE, text=True)
        assert p.stdout.readline().strip() == "locked"
        procs.append(p)
        return p

    yield start
    for p in procs:
        if p.poll() is None:
            p.stdin.close()
            p.wait(10)


COMMANDS = {
    "run": ["run", "page63_line_500N", "--fidelity", "fast", "--no-plots"],
    "solve": ["solve", "--contact", "line", "--M", "20", "--L", "10", "--points", "129", "--no-plots"],
    "sweep": ["sweep", "page63_line_500N", "--param", "operating.us=1,2", "--workers", "1"],
}


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_a_second_command_into_a_locked_folder_is_refused_at_once_naming_folder_and_pid(
        command, tmp_path, holder, capsys):
    out = tmp_path / "out"
    out.mkdir()
    (out / "earlier.h5").write_text("an earlier result")
    other = holder(out)
    t0 = time.perf_counter()
    assert main([*COMMANDS[command], "--out", str(out)]) == 2
    assert time.perf_counter() - t0 < 20.0  # refused, not computed
    err = capsys.readouterr().err
    assert str(out) in err and f"PID {other.pid}" in err and "Traceback" not in err
    assert len([ln for ln in err.splitlines() if "error" in ln]) == 1
    assert sorted(p.name for p in out.iterdir()) == [LOCK_NAME, "earlier.h5"]  # nothing written


def test_transient_into_a_locked_folder_is_refused(tmp_path, holder, capsys, scene_with_feature):
    out = tmp_path / "out"
    other = holder(out)
    scene = scene_with_feature("page63_line_2000N", {"kind": "bump", "amplitude": 1e-8, "width": 1e-5, "x0": -3.0})
    toml = tmp_path / "bump.toml"
    toml.write_text(scene.to_toml())
    assert main(["transient", str(toml), "--points", "129", "--steps", "3", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert str(out) in err and f"PID {other.pid}" in err


def test_the_lock_of_a_killed_process_is_released(tmp_path, holder):
    other = holder(tmp_path)
    with pytest.raises(OutputLocked, match=f"PID {other.pid}"):
        with output_lock(tmp_path, "ehl test"):
            pass
    other.send_signal(signal.SIGKILL)
    other.wait(10)
    with output_lock(tmp_path, "ehl test"):
        assert (tmp_path / LOCK_NAME).read_text().split() == [str(os.getpid()), "ehl", "test"]


def test_the_refusal_is_an_input_error_so_the_exit_code_is_2(tmp_path, holder):
    other = holder(tmp_path)
    with pytest.raises(InputError, match=rf"--out .*{tmp_path.name}.*PID {other.pid}"):
        with output_lock(tmp_path):
            pass


def test_one_process_may_take_the_lock_of_a_folder_twice(tmp_path):
    # a command that calls another writer into the same folder (ehl solve -> the line solve)
    with output_lock(tmp_path, "outer"), output_lock(tmp_path, "inner") as removed:
        assert removed == []
        assert (tmp_path / LOCK_NAME).read_text().startswith(f"{os.getpid()} outer")
    assert not (tmp_path / LOCK_NAME).exists()  # the holder deletes it
    # released when the outer block ends: another process can take it
    code = f"from ehl_multigrid.model.output_folder import output_lock\nwith output_lock({str(tmp_path)!r}):\n    pass\n"
    assert subprocess.run([sys.executable, "-c", code], capture_output=True).returncode == 0
