"""Parameter sweeps over any scene value, run in parallel through ``concurrent.futures``.

* Parameters are dotted scene paths (``operating.us``, ``roughness.Rq``, ``lubricant.tau0``)
  or, without a dot, options passed to the task (``M``, ``L`` for Moes-only solves).
* Cases are the Cartesian product of the parameter values. Each finished case is written at
  once to ``<outdir>/cases/case_<i>.json`` (and ``.h5`` when the task returns a Result), by
  temporary file and rename, so an interrupted sweep resumes without redoing finished cases.
* Any :class:`concurrent.futures.Executor` can run the cases: processes locally by default, or
  a ``dask.distributed`` cluster when a scheduler address is given (optional extra ``dask``).
* :func:`gather` collects the cases into one table (JSON and CSV), and into an
  ``xarray.Dataset`` when xarray is installed.
"""

from __future__ import annotations

import concurrent.futures as cf
import csv
import hashlib
import itertools
import json
import math
import multiprocessing
import os
import tempfile
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..model.errors import ConvergenceError, InputError
from ..model.scene import Scene

STATUS_OK = "ok"
STATUS_FAILED = "failed"  # clear error raised by the model (input or convergence)
STATUS_ERROR = "error"  # unexpected exception: a bug


def parse_values(spec: str) -> list[float]:
    """``"a,b,c"`` or ``"min:max:n"`` or ``"min:max:n:log"`` -> list of floats."""
    spec = spec.strip()
    if ":" in spec:
        parts = spec.split(":")
        if len(parts) not in (3, 4) or (len(parts) == 4 and parts[3] != "log"):
            raise InputError(f"range {spec!r} must be min:max:n or min:max:n:log")
        lo, hi, n = float(parts[0]), float(parts[1]), int(parts[2])
        if n < 1:
            raise InputError(f"range {spec!r}: n = {n} must be >= 1")
        if len(parts) == 4:
            if lo <= 0 or hi <= 0:
                raise InputError(f"range {spec!r}: a log range needs positive ends")
            return list(np.geomspace(lo, hi, n))
        return list(np.linspace(lo, hi, n))
    try:
        return [float(v) for v in spec.split(",") if v.strip()]
    except ValueError:
        raise InputError(f"values {spec!r} must be numbers separated by commas") from None


@dataclass
class SweepSpec:
    """What to sweep: a scene, a task name, parameter values and fixed task options."""

    scene: Scene
    task: str
    params: dict[str, list[float]]
    options: dict[str, Any] = field(default_factory=dict)

    def cases(self) -> list[dict[str, float]]:
        names = list(self.params)
        return [dict(zip(names, combo, strict=True)) for combo in itertools.product(*(self.params[n] for n in names))]

    def fingerprint(self) -> str:
        """Identifies the sweep so a resume never mixes cases of different sweeps."""
        blob = json.dumps(
            {"scene": self.scene.to_dict(), "task": self.task, "options": self.options, "params": list(self.params)},
            sort_keys=True, default=str,
        )
        return hashlib.sha256(blob.encode()).hexdigest()[:16]


def apply_changes(scene_dict: dict[str, Any], changes: dict[str, float]) -> dict[str, Any]:
    """Set dotted paths in a scene dictionary (a copy); ``operating.pmax`` replaces the load."""
    d = json.loads(json.dumps(scene_dict, default=_jsonable))  # deep copy, inf-safe
    for path, value in changes.items():
        keys = path.split(".")
        node = d
        for k in keys[:-1]:
            node = node.setdefault(k, {})
            if not isinstance(node, dict):
                raise InputError(f"sweep parameter {path!r}: {k!r} is not a table")
        node[keys[-1]] = value
        if path == "operating.pmax":
            d["operating"].pop("load", None)
        if path == "operating.load":
            d["operating"].pop("pmax", None)
    return d


def _jsonable(o: Any) -> Any:
    if isinstance(o, (np.floating, np.integer)):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    return str(o)


def _write_json_atomic(path: Path, payload: dict[str, Any]) -> None:
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    with os.fdopen(fd, "w") as f:
        json.dump(payload, f, default=_jsonable, allow_nan=True)
    os.replace(tmp, path)


def run_case(scene_dict: dict[str, Any], task: str, scene_changes: dict[str, float], options: dict[str, Any],
             index: int, outdir: str, case_values: dict[str, float], fingerprint: str) -> dict[str, Any]:
    """Run one case and write its JSON (top-level so process and dask executors can pickle it)."""
    from .tasks import get_task

    t0 = time.perf_counter()
    record: dict[str, Any] = {"index": index, "params": case_values, "fingerprint": fingerprint}
    try:
        scene = Scene.from_dict(apply_changes(scene_dict, scene_changes), origin=f"sweep case {index}")
        out = get_task(task)(scene, **options)
        result = out.pop("result", None)
        if result is not None:
            result.save(Path(outdir) / f"case_{index:05d}.h5")
            record["hdf5"] = f"case_{index:05d}.h5"
        record["status"] = STATUS_OK
        record["outputs"] = out
    except (InputError, ConvergenceError) as exc:
        record["status"] = STATUS_FAILED
        record["error"] = f"{type(exc).__name__}: {exc}"
    except Exception as exc:  # a bug: keep the traceback, do not stop the sweep
        record["status"] = STATUS_ERROR
        record["error"] = f"{type(exc).__name__}: {exc}"
        record["traceback"] = traceback.format_exc()
    record["wall_s"] = time.perf_counter() - t0
    _write_json_atomic(Path(outdir) / f"case_{index:05d}.json", record)
    return record


def _finished(outdir: Path, fingerprint: str) -> dict[int, dict[str, Any]]:
    done = {}
    for f in outdir.glob("case_*.json"):
        try:
            rec = json.loads(f.read_text())
        except (json.JSONDecodeError, OSError):
            continue  # torn file from a crash: redo the case
        if rec.get("fingerprint") == fingerprint:
            done[int(rec["index"])] = rec
    return done


def make_executor(workers: int | None = None, scheduler: str | None = None) -> cf.Executor:
    """Local process pool (spawn: safe with numba threads) or a dask.distributed executor."""
    if scheduler:
        try:
            from distributed import Client
        except ImportError:
            raise InputError("a scheduler address needs the optional extra: pip install 'ehl-multigrid[dask]'") from None
        return Client(scheduler).get_executor()
    workers = workers or os.cpu_count() or 1
    return cf.ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("spawn"))


def run_sweep(spec: SweepSpec, outdir: str | os.PathLike, executor: cf.Executor | None = None,
              workers: int | None = None, scheduler: str | None = None, progress: bool = True) -> SweepTable:
    """Run every case not already finished; returns the gathered table.

    An interruption (Ctrl-C) cancels the pending cases; finished cases stay on disk and a
    second call with the same spec runs only the rest.
    """
    outdir = Path(outdir)
    casedir = outdir / "cases"
    casedir.mkdir(parents=True, exist_ok=True)
    fp = spec.fingerprint()
    _write_json_atomic(outdir / "sweep.json", {
        "task": spec.task, "params": spec.params, "options": spec.options, "fingerprint": fp,
        "scene": spec.scene.to_dict(),
    })
    cases = spec.cases()
    done = _finished(casedir, fp)
    todo = [i for i in range(len(cases)) if i not in done]
    scene_dict = spec.scene.to_dict()
    own = executor is None
    ex = executor or make_executor(workers, scheduler)
    bar = None
    if progress and todo:
        from tqdm import tqdm

        bar = tqdm(total=len(cases), initial=len(done), desc=f"sweep {spec.task}", unit="case")
    futures = []
    try:
        for i in todo:
            values = cases[i]
            scene_changes = {k: v for k, v in values.items() if "." in k}
            opts = dict(spec.options)
            opts.update({k: v for k, v in values.items() if "." not in k})
            futures.append(ex.submit(run_case, scene_dict, spec.task, scene_changes, opts, i, str(casedir), values, fp))
        for fut in cf.as_completed(futures):
            fut.result()
            if bar is not None:
                bar.update(1)
    except BaseException:
        for fut in futures:
            fut.cancel()
        raise
    finally:
        if bar is not None:
            bar.close()
        if own:
            try:
                ex.shutdown(wait=True, cancel_futures=True)
            except TypeError:  # dask's ClientExecutor has no cancel_futures
                ex.shutdown(wait=True)
            client = getattr(ex, "_client", None)
            if client is not None:
                client.close()
    table = gather(outdir)
    table.save(outdir)
    return table


@dataclass
class SweepTable:
    """All cases of a sweep: one row per case, columns = parameters, status, outputs."""

    params: list[str]
    rows: list[dict[str, Any]]

    def column(self, name: str) -> np.ndarray:
        return np.array([r.get(name, math.nan) for r in self.rows], dtype=object)

    @property
    def counts(self) -> dict[str, int]:
        out = {STATUS_OK: 0, STATUS_FAILED: 0, STATUS_ERROR: 0}
        for r in self.rows:
            out[r["status"]] = out.get(r["status"], 0) + 1
        return out

    def save(self, outdir: str | os.PathLike) -> None:
        outdir = Path(outdir)
        _write_json_atomic(outdir / "table.json", {"params": self.params, "rows": self.rows, "counts": self.counts})
        cols: list[str] = []
        for r in self.rows:
            for k in r:
                if k not in cols and not isinstance(r[k], (list, dict)):
                    cols.append(k)
        fd, tmp = tempfile.mkstemp(dir=outdir)
        with os.fdopen(fd, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
            w.writeheader()
            w.writerows(self.rows)
        os.replace(tmp, outdir / "table.csv")

    def to_xarray(self):
        """An ``xarray.Dataset`` on the parameter grid (needs xarray)."""
        try:
            import xarray as xr
        except ImportError:
            raise InputError("to_xarray needs xarray: pip install xarray") from None
        axes = {p: np.unique(np.array([r[p] for r in self.rows], dtype=float)) for p in self.params}
        shape = tuple(len(a) for a in axes.values())
        scalars = sorted({k for r in self.rows for k, v in r.items()
                          if k not in self.params and isinstance(v, (int, float, bool)) and not isinstance(v, str)})
        data = {}
        for k in scalars:
            arr = np.full(shape, np.nan)
            for r in self.rows:
                idx = tuple(int(np.searchsorted(axes[p], r[p])) for p in self.params)
                v = r.get(k)
                arr[idx] = float(v) if isinstance(v, (int, float, bool)) and v is not None else np.nan
            data[k] = (list(self.params), arr)
        return xr.Dataset(data, coords=axes)


def gather(outdir: str | os.PathLike) -> SweepTable:
    """Collect the finished cases of the sweep in ``outdir``."""
    outdir = Path(outdir)
    meta = json.loads((outdir / "sweep.json").read_text())
    rows = []
    for i, rec in sorted(_finished(outdir / "cases", meta["fingerprint"]).items()):
        row: dict[str, Any] = {"index": i, **rec["params"], "status": rec["status"], "wall_s": rec.get("wall_s")}
        if rec["status"] == STATUS_OK:
            for k, v in rec["outputs"].items():
                row[k] = v
        else:
            row["error"] = rec.get("error", "")
        rows.append(row)
    return SweepTable(list(meta["params"]), rows)
