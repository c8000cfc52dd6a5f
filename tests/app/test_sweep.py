"""Sweeps: parallel cases, resume after interruption, failures recorded, gathered table."""

import concurrent.futures as cf
import json
import os
import re
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

from ehl_multigrid.app.sweep import SweepSpec, gather, parse_values, run_sweep
from ehl_multigrid.app.tasks import register_task
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import load_scene

CALLS: list[float] = []
LOCK = threading.Lock()
STOP_AT = {"n": None}  # module state, not a task option, so the sweep's fingerprint is unchanged


def counting_task(scene, **options):
    with LOCK:
        CALLS.append(scene.us)
        n = len(CALLS)
    if STOP_AT["n"] is not None and n == STOP_AT["n"]:
        raise KeyboardInterrupt  # simulates Ctrl-C in the middle of the sweep
    if scene.us > 50:
        raise InputError("operating.us too high for this test task")
    return {"Hc_fit": scene.central_film_fit()[0]}


register_task("counting", counting_task)


@pytest.fixture
def cases_in_this_process(monkeypatch):
    """``ehl sweep`` runs its cases on one thread of the test process instead of a spawned
    worker process (whose start-up, imports and kernel loading took 1.3 s of a 1.5-1.9 s film
    sweep): for the tests of what a sweep computes and writes. The process pool itself is
    checked by the parallel, killed and fault-injected sweeps."""
    import ehl_multigrid.app.sweep as sweep

    monkeypatch.setattr(sweep, "make_executor", lambda *a, **k: cf.ThreadPoolExecutor(max_workers=1))


def test_parse_values_forms():
    assert parse_values("1,2,3") == [1.0, 2.0, 3.0]
    assert parse_values("1:3:3") == [1.0, 2.0, 3.0]
    np.testing.assert_allclose(parse_values("1:100:3:log"), [1, 10, 100])
    with pytest.raises(InputError, match="min:max:n"):
        parse_values("1:2")


@pytest.mark.solver
def test_sweep_of_100_cases_runs_in_parallel_processes(tmp_path):
    spec = SweepSpec(load_scene("page63_line_500N"), "fit",
                     {"operating.us": parse_values("0.001:10:10:log"), "operating.load": parse_values("100:10000:10:log")})
    table = run_sweep(spec, tmp_path, workers=2, progress=False)
    assert table.counts == {"ok": 100, "failed": 0, "error": 0}
    # each case is the scene at that operating point
    row = next(r for r in table.rows if r["index"] == 37)
    sc = load_scene("page63_line_500N").with_operating(us=row["operating.us"], load=row["operating.load"])
    assert row["Hc_fit"] == pytest.approx(sc.central_film_fit()[0], rel=1e-12)
    assert (tmp_path / "table.csv").exists()


def test_interrupted_sweep_resumes_without_redoing_finished_cases(tmp_path):
    CALLS.clear()
    STOP_AT["n"] = 5
    spec = SweepSpec(load_scene("page63_line_500N"), "counting", {"operating.us": parse_values("0.01:1:12:log")})
    ex = cf.ThreadPoolExecutor(max_workers=1)
    try:
        with pytest.raises(KeyboardInterrupt):
            run_sweep(spec, tmp_path, executor=ex, progress=False)
    finally:
        ex.shutdown(wait=True)  # a case already running when Ctrl-C arrives still finishes
        STOP_AT["n"] = None
    done_files = sorted((tmp_path / "cases").glob("case_*.json"))
    finished_us = {json.loads(f.read_text())["params"]["operating.us"] for f in done_files}
    assert 4 <= len(finished_us) < 12  # the cases before the interruption are on disk
    CALLS.clear()
    table = run_sweep(spec, tmp_path, executor=cf.ThreadPoolExecutor(max_workers=1), progress=False)
    assert len(CALLS) == 12 - len(finished_us)
    assert not finished_us & set(CALLS)
    assert table.counts["ok"] == 12


def test_changed_sweep_does_not_reuse_cases_of_another(tmp_path):
    scene = load_scene("page63_line_500N")
    run_sweep(SweepSpec(scene, "counting", {"operating.us": [0.1, 0.2]}), tmp_path,
              executor=cf.ThreadPoolExecutor(1), progress=False)
    CALLS.clear()
    other = scene.with_operating(load=2000.0)
    table = run_sweep(SweepSpec(other, "counting", {"operating.us": [0.1, 0.2]}), tmp_path,
                      executor=cf.ThreadPoolExecutor(1), progress=False)
    assert len(CALLS) == 2 and table.counts["ok"] == 2


def test_failed_cases_are_recorded_not_fatal(tmp_path):
    spec = SweepSpec(load_scene("page63_line_500N"), "counting", {"operating.us": [1.0, 100.0]})
    table = run_sweep(spec, tmp_path, executor=cf.ThreadPoolExecutor(2), progress=False)
    assert table.counts == {"ok": 1, "failed": 1, "error": 0}
    bad = next(r for r in table.rows if r["status"] == "failed")
    assert "operating.us too high" in bad["error"]


def test_invalid_scene_value_in_a_case_fails_that_case_only(tmp_path):
    spec = SweepSpec(load_scene("page63_line_500N"), "fit", {"operating.load": [-1.0, 500.0]})
    table = run_sweep(spec, tmp_path, executor=cf.ThreadPoolExecutor(1), progress=False)
    assert table.counts["failed"] == 1 and table.counts["ok"] == 1
    assert "operating.load = -1 N" in next(r for r in table.rows if r["status"] == "failed")["error"]


def test_gathered_table_converts_to_xarray(tmp_path):
    pytest.importorskip("xarray")
    spec = SweepSpec(load_scene("page63_line_500N"), "fit",
                     {"operating.us": [0.01, 0.1, 1.0], "operating.load": [500.0, 2000.0]})
    run_sweep(spec, tmp_path, executor=cf.ThreadPoolExecutor(2), progress=False)
    ds = gather(tmp_path).to_xarray()
    assert ds["Hc_fit"].shape == (3, 2)
    sc = load_scene("page63_line_500N").with_operating(us=0.1, load=2000.0)
    assert float(ds["Hc_fit"].sel({"operating.us": 0.1, "operating.load": 2000.0})) == pytest.approx(sc.central_film_fit()[0])


def test_sweep_runs_on_a_dask_cluster_given_its_address(tmp_path):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None) as cluster:
        spec = SweepSpec(load_scene("page63_line_500N"), "fit", {"operating.us": [0.01, 0.1, 1.0]})
        table = run_sweep(spec, tmp_path, scheduler=cluster.scheduler_address, progress=False)
    assert table.counts["ok"] == 3


def test_sweep_cli_json(capsys, tmp_path, cases_in_this_process):
    from ehl_multigrid.app.cli import main

    assert main(["sweep", "page63_line_500N", "--param", "operating.us=0.01,0.1", "--workers", "1",
                 "--out", str(tmp_path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["counts"]["ok"] == 2


def _children(pid: int) -> list[int]:
    out = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == pid:
            out.append(int(stat.parent.name))
    return out


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"


@pytest.mark.solver
@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads process tables from /proc")
def test_sweep_workers_die_when_the_sweep_process_is_killed(tmp_path):
    # a script run as __main__ (as a user's sweep script is): its workers, once past start-up,
    # block on the task queue and used to live on after the sweep process was killed
    script = tmp_path / "sweep_script.py"
    script.write_text(
        "import sys\n"
        "from ehl_multigrid.app.sweep import SweepSpec, run_sweep\n"
        "from ehl_multigrid.model.scene import load_scene\n"
        "if __name__ == '__main__':\n"
        "    spec = SweepSpec(load_scene('page63_line_500N'), 'fit',\n"
        "                     {'operating.us': [0.01 + 1e-5 * i for i in range(5000)]})\n"
        "    run_sweep(spec, sys.argv[1], workers=2, progress=False)\n"
    )
    proc = subprocess.Popen([sys.executable, str(script), str(tmp_path / "sw")],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    workers: list[int] = []
    try:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline:
            workers = [c for c in _children(proc.pid)
                       if "spawn_main" in Path(f"/proc/{c}/cmdline").read_bytes().decode(errors="replace")]
            # well under way (a worker still starting up dies with its pipe anyway)
            if len(workers) == 2 and len(list((tmp_path / "sw" / "cases").glob("case_*.json"))) >= 10:
                break
            time.sleep(0.2)
        assert len(workers) == 2, "the sweep did not start its two workers"
        proc.send_signal(signal.SIGKILL)  # no chance to clean up
        proc.wait(timeout=30)
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline and any(_alive(w) for w in workers):
            time.sleep(0.2)
        assert not any(_alive(w) for w in workers), "sweep workers outlived the killed sweep process"
    finally:
        if proc.poll() is None:
            proc.kill()
        for w in workers:  # do not leave orphans behind when the test fails
            if _alive(w):
                os.kill(w, signal.SIGKILL)


def test_rerun_with_other_values_computes_them_instead_of_returning_old_rows(tmp_path):
    scene = load_scene("page63_line_500N")
    CALLS.clear()
    run_sweep(SweepSpec(scene, "counting", {"operating.us": [0.1, 0.2]}), tmp_path,
              executor=cf.ThreadPoolExecutor(1), progress=False)
    CALLS.clear()
    table = run_sweep(SweepSpec(scene, "counting", {"operating.us": [0.3, 0.2]}), tmp_path,
                      executor=cf.ThreadPoolExecutor(1), progress=False)
    # same parameter names, other values: 0.3 is computed, 0.2 reused case by case, 0.1 not in the table
    assert CALLS == [0.3]
    assert sorted(r["operating.us"] for r in table.rows) == [0.2, 0.3]
    assert gather(tmp_path).rows == table.rows


def test_changed_task_options_are_a_different_case(tmp_path):
    scene = load_scene("page63_line_500N")
    spec_a = SweepSpec(scene, "counting", {"operating.us": [0.1]}, {"label": "a"})
    spec_b = SweepSpec(scene, "counting", {"operating.us": [0.1]}, {"label": "b"})
    assert spec_a.case_key({"operating.us": 0.1}) != spec_b.case_key({"operating.us": 0.1})
    assert spec_a.case_key({"operating.us": 0.1}) == SweepSpec(scene, "counting", {"operating.us": [0.5, 0.1]},
                                                               {"label": "a"}).case_key({"operating.us": 0.1})


@pytest.mark.parametrize("spec, message", [
    # the value given, the part that is wrong and its allowed form or range
    ("1:10:0", r"'1:10:0'.*\bn = 0\b.*\[1, 100000\]"),
    ("1:10:x", r"'1:10:x'.*\bmin:max:n\b"),
    ("1:10:1e9", r"'1:10:1e9'.*\bn = 1e9\b.*\[1, 100000\]"),
    ("abc", r"'abc'.*\bnumbers\b"),
    ("nan,1", r"'nan,1'.*\bfinite\b"),
    ("-1:10:5:log", r"'-1:10:5:log'.*\blog\b.*\bpositive\b"),
])
def test_bad_sweep_values_name_the_parameter(spec, message):
    with pytest.raises(InputError, match=message) as err:
        parse_values(spec, field="--param operating.us")
    assert "--param operating.us" in str(err.value)


@pytest.mark.parametrize("argv, message", [
    (["--param", "operating.sped=1,2"], "sped"),
    (["--param", "operating.us=1", "--workers", "0"], "--workers"),
    (["--param", "operating.us=1", "--workers", "10000"], "--workers"),
    (["--param", "operating.us=0.1:10:1000", "--param", "operating.load=1:100:1000"], "1000000 cases"),
    (["--param", "operating.us=1", "--task", "teleport"], "teleport"),
    (["--param", "operating.us=1", "--option", "x=[1,"], "--option x"),
    (["--param", "operating.us=1", "--option", "x=1e"], "--option x: '1e' is not a valid JSON value"),
    (["--param", "operating.us=1", "--option", "x=1"], "takes no options"),
])
def test_bad_sweep_command_lines_exit_2_naming_the_field(argv, message, tmp_path, capsys):
    from ehl_multigrid.app.cli import main

    assert main(["sweep", "page63_line_500N", "--out", str(tmp_path), "--workers", "1", *argv]) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err


def test_a_film_sweep_solves_each_case_through_the_front_door_and_keeps_its_fields(capsys, tmp_path,
                                                                                  cases_in_this_process):
    import ehl_multigrid as ehl
    from ehl_multigrid.app.cli import main
    from ehl_multigrid.model.results import Result

    assert main(["sweep", "page63_line_2000N", "--task", "film", "--param", "operating.load=1000,4000",
                 "--option", "accuracy=0.02", "--workers", "1", "--out", str(tmp_path), "--json"]) == 0
    rows = gather(tmp_path).rows
    assert [r["solve_status"] for r in rows] == ["converged", "converged"] and all(r["converged"] for r in rows)
    light, heavy = sorted(rows, key=lambda r: r["operating.load"])
    assert heavy["hc"] < light["hc"] and heavy["Hc_error"] <= 0.02  # a heavier load thins the film
    # the same film as the front door's own solve of the case's scene
    d = load_scene("page63_line_2000N").to_dict()
    d["operating"]["load"] = 1000.0
    from ehl_multigrid.model.scene import Scene

    assert light["hc"] == ehl.solve(Scene.from_dict(d), accuracy=0.02).hc
    assert light["hc_over_fit"] == pytest.approx(light["hc"] / light["hc_fit"], rel=1e-12)
    assert Result.load(tmp_path / light["hdf5"]).kind == "ehl_line"  # the row names its case's fields


def test_a_film_sweep_whose_solves_miss_their_accuracy_exits_3_naming_how_many(capsys, tmp_path,
                                                                               cases_in_this_process):
    from ehl_multigrid.app.cli import main

    rc = main(["sweep", "page63_line_2000N", "--task", "film", "--param", "operating.load=1000,4000",
               "--option", "accuracy=0.0001", "--option", "max_points=257", "--workers", "1",
               "--out", str(tmp_path)])
    assert rc == 3
    assert re.search(r"\b2 of 2 cases\b", capsys.readouterr().err)


def test_a_word_option_is_a_string_and_json_literals_keep_their_type():
    from ehl_multigrid.app.cli import task_options

    assert task_options(["physics=thermal", "flag=true", "n=null", "tol=1e-3", "grid=[1, 2]"]) == {
        "physics": "thermal", "flag": True, "n": None, "tol": 1e-3, "grid": [1, 2]}


def test_a_starved_film_case_is_compared_with_the_fit_for_its_supply():
    from ehl_multigrid.app.tasks import film_task
    from ehl_multigrid.model.scene import Scene

    d = load_scene("page63_line_500N").to_dict()
    d["supply"] = {"hoil": 1.5e-8}
    scene = Scene.from_dict(d)
    row = film_task(scene, accuracy=None, points=257)
    assert row["physics"] == "starved" and row["result"].kind == "ehl_line"
    assert row["hc_fit"] == scene.supplied_film_fit()[1] < scene.central_film_fit()[1]  # never the flooded fit
