"""Sweeps: parallel cases, resume after interruption, failures recorded, gathered table."""

import concurrent.futures as cf
import json
import threading

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


def test_parse_values_forms():
    assert parse_values("1,2,3") == [1.0, 2.0, 3.0]
    assert parse_values("1:3:3") == [1.0, 2.0, 3.0]
    np.testing.assert_allclose(parse_values("1:100:3:log"), [1, 10, 100])
    with pytest.raises(InputError, match="min:max:n"):
        parse_values("1:2")


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


def test_sweep_cli_json(capsys, tmp_path):
    from ehl_multigrid.app.cli import main

    assert main(["sweep", "page63_line_500N", "--param", "operating.us=0.01,0.1", "--workers", "1",
                 "--out", str(tmp_path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["counts"]["ok"] == 2
