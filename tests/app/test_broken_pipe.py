"""``ehl`` writing into a pipe whose reader has gone (``ehl show default | head -2``) ends
quietly: no traceback, no 'Exception ignored' at exit, exit code 141 (or 0 if everything was
written before the reader left)."""

import os
import subprocess
import sys

import pytest

EHL = [sys.executable, "-m", "ehl_multigrid"]


def run_into_closed_pipe(argv):
    """Run ``ehl argv`` with stdout a pipe whose read end is closed before it starts: every
    write fails (deterministic, unlike racing ``head``)."""
    read, write = os.pipe()
    os.close(read)
    try:
        proc = subprocess.run([*EHL, *argv], stdout=write, stderr=subprocess.PIPE, timeout=120)
    finally:
        os.close(write)
    return proc.returncode, proc.stderr.decode()


@pytest.mark.parametrize("argv", [["show", "default"],
                                  pytest.param(["scenes", "--json"], marks=pytest.mark.solver)])
def test_output_into_a_closed_pipe_ends_quietly_with_141(argv):
    rc, err = run_into_closed_pipe(argv)
    assert rc == 141, err
    assert "Traceback" not in err and "BrokenPipe" not in err and "Exception ignored" not in err


def test_reader_that_leaves_after_two_lines_gets_no_traceback():
    # 'ehl show default | head -2': the writer may or may not still be writing when head leaves
    proc = subprocess.Popen([*EHL, "show", "default"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    first = [proc.stdout.readline() for _ in range(2)]
    proc.stdout.close()
    err = proc.stderr.read().decode()
    proc.stderr.close()
    rc = proc.wait(timeout=120)
    assert first[0].startswith(b"# scene default")
    assert rc in (0, 141) and "Traceback" not in err and "BrokenPipe" not in err
