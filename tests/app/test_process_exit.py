"""The ``ehl`` console script ends its process without the interpreter's teardown
(:func:`ehl_multigrid.app.cli.run`) but only after everything the teardown would still have
done for the command: its threads finished, the ``atexit`` handlers run, the output flushed,
and the exit code of :func:`~ehl_multigrid.app.cli.main` returned."""

import json
import subprocess
import sys

EHL = [sys.executable, "-m", "ehl_multigrid"]


def run_with_main(tmp_path, body: str) -> subprocess.CompletedProcess:
    """``cli.run()`` in a fresh process with ``main`` replaced by ``body`` (a function body)."""
    code = ("import atexit, threading, time\n"
            "import ehl_multigrid.app.cli as cli\n"
            f"out = {str(tmp_path)!r}\n"
            "def main():\n" + "".join(f"    {line}\n" for line in body.splitlines()) +
            "cli.main = main\ncli.run()\n")
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)


def test_exit_code_of_main_is_the_process_exit_code(tmp_path):
    assert run_with_main(tmp_path, "return 3").returncode == 3
    assert run_with_main(tmp_path, "return 0").returncode == 0


def test_a_running_thread_and_the_atexit_handlers_finish_before_the_process_ends(tmp_path):
    body = ("def late():\n"
            "    time.sleep(0.5)\n"
            "    open(out + '/thread', 'w').write('done')\n"
            "threading.Thread(target=late).start()\n"
            "atexit.register(lambda: open(out + '/atexit', 'w').write('done'))\n"
            "print('x' * 200000, end='')\n"
            "return 0")
    proc = run_with_main(tmp_path, body)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "thread").read_text() == "done"
    assert (tmp_path / "atexit").read_text() == "done"
    assert len(proc.stdout) == 200000  # buffered output flushed, not lost with the process


def test_a_failing_command_still_says_why_and_exits_with_its_code():
    proc = subprocess.run([*EHL, "fits", "--contact", "line", "--M", "-1", "--L", "10", "--json"], capture_output=True,
                          text=True, timeout=120)
    assert proc.returncode == 2
    assert "M" in proc.stderr and "-1" in proc.stderr


def test_json_output_of_a_command_is_complete():
    proc = subprocess.run([*EHL, "scenes", "--json"], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)
