"""Parameter sweeps over any scene value, run in parallel through ``concurrent.futures``.

* Parameters are dotted scene paths (``operating.us``, ``roughness.Rq``, ``lubricant.tau0``)
  or, without a dot, options passed to the task (``M``, ``L`` for Moes-only solves).
* Cases are the Cartesian product of the parameter values. Each finished case is written at
  once to ``<outdir>/cases/case_<key>.json`` (and ``.h5`` when the task returns a Result), by
  temporary file and rename, so an interrupted sweep resumes without redoing finished cases.
* ``key`` fingerprints the whole case: the scene it runs (every value, after the sweep's
  changes), the task and its options. A rerun into the same folder reuses exactly the cases
  whose key matches and computes the others, so a sweep with other values, another scene or
  other options never returns the rows of an earlier one.
* Local worker processes die with the sweep: interrupted (Ctrl-C, SIGTERM) the sweep stops them,
  and killed outright (SIGKILL) its workers notice the lost parent and exit.
* The sweep folder is locked while the sweep runs (a second command into it is refused at
  once, naming the PID that holds it); the temporary files of dead runs in it and in
  ``cases/`` are removed when the next sweep takes the lock. An interrupted sweep still writes
  the table of its finished cases (``complete`` false in ``table.json``).
* Progress goes to stderr: a bar on a terminal, a line at most every few seconds otherwise.
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
import signal
import threading
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..model.atomic import atomic_path, deferred_signals, fault_point, write_text_atomic
from ..model.errors import ConvergenceError, InputError
from ..model.output_folder import output_lock, remove_leftovers
from ..model.scene import Scene
from .console import Progress, report_leftovers

STATUS_OK = "ok"
STATUS_FAILED = "failed"  # clear error raised by the model (input or convergence)
STATUS_ERROR = "error"  # unexpected exception: a bug

#: Most cases one sweep may hold (the case list is built in memory; split larger studies).
MAX_CASES = 100_000
#: Most local worker processes a sweep may start.
MAX_WORKERS = 256


def parse_values(spec: str, field: str = "values") -> list[float]:
    """``"a,b,c"`` or ``"min:max:n"`` or ``"min:max:n:log"`` -> list of finite floats; errors
    name ``field`` (e.g. ``"--param operating.us"``)."""
    spec = spec.strip()
    if ":" in spec:
        parts = spec.split(":")
        if len(parts) not in (3, 4) or (len(parts) == 4 and parts[3] != "log"):
            raise InputError(f"{field}: range {spec!r} must be min:max:n or min:max:n:log")
        try:
            lo, hi, n_f = float(parts[0]), float(parts[1]), float(parts[2])
        except ValueError:
            raise InputError(f"{field}: range {spec!r} must be numbers min:max:n (n an integer)") from None
        if not (math.isfinite(lo) and math.isfinite(hi)):
            raise InputError(f"{field}: range {spec!r} needs finite ends")
        if not (n_f.is_integer() and 1 <= n_f <= MAX_CASES):
            raise InputError(f"{field}: range {spec!r}: n = {parts[2]} must be an integer in [1, {MAX_CASES}]")
        n = int(n_f)
        if len(parts) == 4:
            if lo <= 0 or hi <= 0:
                raise InputError(f"{field}: range {spec!r}: a log range needs positive ends")
            return [float(v) for v in np.geomspace(lo, hi, n)]
        return [float(v) for v in np.linspace(lo, hi, n)]
    try:
        values = [float(v) for v in spec.split(",") if v.strip()]
    except ValueError:
        raise InputError(f"{field}: values {spec!r} must be numbers separated by commas") from None
    if not values:
        raise InputError(f"{field}: no values given")
    if not all(math.isfinite(v) for v in values):
        raise InputError(f"{field}: values {spec!r} must be finite numbers")
    if len(values) > MAX_CASES:
        raise InputError(f"{field}: {len(values)} values; at most {MAX_CASES}")
    return values


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

    def case_inputs(self, values: dict[str, float]) -> tuple[dict[str, Any], dict[str, Any], dict[str, Any]]:
        """``(scene_changes, task_options, scene_dict)`` of the case with parameter ``values``."""
        scene_changes = {k: v for k, v in values.items() if "." in k}
        opts = dict(self.options)
        opts.update({k: v for k, v in values.items() if "." not in k})
        return scene_changes, opts, self.scene.to_dict()

    def case_key(self, values: dict[str, float]) -> str:
        """Fingerprint of one case: the scene it runs (every value, after the case's changes),
        the task and the task options. Equal keys mean the same computation."""
        changes, opts, scene_dict = self.case_inputs(values)
        try:
            scene = apply_changes(scene_dict, changes)
        except InputError:
            scene = {"base": scene_dict, "changes": changes}  # the case will fail; still a distinct key
        return _digest({"scene": scene, "task": self.task, "options": opts})

    def fingerprint(self) -> str:
        """Fingerprint of the whole sweep: every case's key, in order, and the parameter names."""
        return _digest({"params": list(self.params), "cases": [self.case_key(v) for v in self.cases()]})


def _digest(obj: Any) -> str:
    blob = json.dumps(obj, sort_keys=True, default=_jsonable, allow_nan=True)
    return hashlib.sha256(blob.encode()).hexdigest()[:20]


def check_spec(spec: SweepSpec) -> None:
    """Refuse, before any case runs, what would make every case fail: too many cases, a
    parameter path that is not a table of the scene, or a key the scene does not know."""
    n = math.prod(len(v) for v in spec.params.values())
    if n > MAX_CASES:
        raise InputError(f"the sweep has {n} cases; at most {MAX_CASES} (split it into several sweeps)")
    base = spec.scene.to_dict()
    for name, values in spec.params.items():
        if "." not in name:
            continue
        try:
            Scene.from_dict(apply_changes(base, {name: values[0]}), origin=f"sweep parameter {name}")
        except InputError as exc:
            if "unknown key" in str(exc) or "is not a table" in str(exc):
                raise InputError(f"--param {name}: {exc}") from None
            # a bad value fails its own cases only (recorded in the table)


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
    write_text_atomic(path, json.dumps(payload, default=_jsonable, allow_nan=True))


def run_case(scene_dict: dict[str, Any], task: str, scene_changes: dict[str, float], options: dict[str, Any],
             index: int, outdir: str, case_values: dict[str, float], key: str) -> dict[str, Any]:
    """Run one case and write its JSON ``case_<key>.json`` (top-level so process and dask
    executors can pickle it)."""
    from .tasks import get_task

    t0 = time.perf_counter()
    record: dict[str, Any] = {"index": index, "params": case_values, "key": key}
    try:
        scene = Scene.from_dict(apply_changes(scene_dict, scene_changes), origin=f"sweep case {index}")
        out = get_task(task)(scene, **options)
        result = out.pop("result", None)
        if result is not None:
            result.save(Path(outdir) / f"case_{key}.h5")
            record["hdf5"] = f"case_{key}.h5"
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
    _write_json_atomic(Path(outdir) / f"case_{key}.json", record)
    return record


def _finished(outdir: Path, keys: set[str]) -> dict[str, dict[str, Any]]:
    """Finished case records in ``outdir`` whose key is in ``keys`` (others belong to other
    sweeps that used the folder, or to an older format, and are left alone)."""
    done = {}
    for f in outdir.glob("case_*.json"):
        try:
            rec = json.loads(f.read_text())
        except (json.JSONDecodeError, OSError):
            continue  # torn file from a crash: redo the case
        key = rec.get("key") if isinstance(rec, dict) else None
        if key in keys and f.name == f"case_{key}.json":
            done[key] = rec
    return done


def make_executor(workers: int | None = None, scheduler: str | None = None) -> cf.Executor:
    """Local process pool (spawn: safe with numba threads) whose workers die with this process,
    or a dask.distributed executor."""
    if scheduler:
        try:
            from distributed import Client
        except ImportError:
            raise InputError("a scheduler address needs the optional extra: pip install 'ehl-multigrid[dask]'") from None
        try:
            client = Client(scheduler, timeout="10s")
        except (OSError, TimeoutError, ValueError, TypeError) as exc:
            raise InputError(f"--scheduler {scheduler!r}: cannot connect to a dask scheduler there "
                             f"({type(exc).__name__}: {' '.join(str(exc).split())[:200]})") from None
        return client.get_executor()
    workers = workers or os.cpu_count() or 1
    return cf.ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("spawn"),
                                  initializer=die_with_parent, initargs=(os.getpid(),))


#: Seconds between a worker's checks that the sweep process still lives (where the kernel cannot
#: signal it directly).
PARENT_POLL_S = 1.0


def die_with_parent(parent_pid: int) -> None:
    """Worker initializer: end this worker when the sweep process ``parent_pid`` ends, even by
    SIGKILL. Linux delivers SIGKILL at the parent's death (``prctl(PR_SET_PDEATHSIG)``); a daemon
    thread that watches for re-parenting covers other systems and the race at start-up."""
    if os.getppid() != parent_pid:
        os._exit(1)
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        PR_SET_PDEATHSIG = 1
        libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    except (OSError, AttributeError):
        pass  # not Linux: the watcher below does it within PARENT_POLL_S
    if os.getppid() != parent_pid:  # the parent died before prctl took effect
        os._exit(1)

    def watch() -> None:
        while True:
            time.sleep(PARENT_POLL_S)
            if os.getppid() != parent_pid:
                os._exit(1)

    threading.Thread(target=watch, name="ehl-sweep-parent-watch", daemon=True).start()


def _stop_workers(ex: cf.Executor) -> None:
    """Terminate the processes of a local pool at once (an interrupted sweep must not wait for
    the running cases; their results would be discarded anyway)."""
    for proc in list((getattr(ex, "_processes", None) or {}).values()):
        try:
            proc.terminate()
        except (OSError, AttributeError):
            pass


def run_sweep(spec: SweepSpec, outdir: str | os.PathLike, executor: cf.Executor | None = None,
              workers: int | None = None, scheduler: str | None = None, progress: bool = True) -> SweepTable:
    """Run every case not already finished; returns the gathered table.

    An interruption (Ctrl-C, SIGTERM) cancels the pending cases; finished cases stay on disk,
    the table of the finished ones is written (``complete`` false), and a second call with the
    same spec runs only the rest. ``outdir`` is locked meanwhile
    (:func:`~ehl_multigrid.model.output_folder.output_lock`: another process writing into it makes
    this call raise :class:`~ehl_multigrid.model.paths.OutputLocked`).
    """
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    with output_lock(outdir, "ehl sweep", subfolders=("cases",)) as removed:
        report_leftovers("ehl sweep", removed)
        return _run_sweep_locked(spec, outdir, executor, workers, scheduler, progress)


def _run_sweep_locked(spec: SweepSpec, outdir: Path, executor: cf.Executor | None, workers: int | None,
                      scheduler: str | None, progress: bool) -> SweepTable:
    """:func:`run_sweep` once ``outdir`` is locked."""
    casedir = outdir / "cases"
    casedir.mkdir(parents=True, exist_ok=True)
    cases = spec.cases()
    keys = [spec.case_key(v) for v in cases]
    _write_json_atomic(outdir / "sweep.json", {
        "task": spec.task, "params": spec.params, "options": spec.options,
        "fingerprint": _digest({"params": list(spec.params), "cases": keys}),
        "scene": spec.scene.to_dict(),
        "cases": [{"index": i, "key": k, "params": v} for i, (k, v) in enumerate(zip(keys, cases, strict=True))],
    })
    done = _finished(casedir, set(keys))
    todo = [i for i in range(len(cases)) if keys[i] not in done]
    scene_dict = spec.scene.to_dict()
    own = executor is None
    ex = executor or make_executor(workers, scheduler)
    prog = Progress(f"ehl sweep {spec.task}", total=len(cases), unit="cases", initial=len(cases) - len(todo),
                    enabled=progress and bool(todo))
    futures = []
    interrupted = False
    failed = 0
    try:
        for i in todo:
            scene_changes, opts, _ = spec.case_inputs(cases[i])
            futures.append(ex.submit(run_case, scene_dict, spec.task, scene_changes, opts, i, str(casedir),
                                     cases[i], keys[i]))
        for fut in cf.as_completed(futures):
            rec = fut.result()
            failed += rec.get("status") != STATUS_OK
            prog.advance(text=f"{failed} failed" if failed else "")
            fault_point("sweep.case")
    except BaseException:
        interrupted = True
        for fut in futures:
            fut.cancel()
        raise
    finally:
        prog.close()
        if own:
            if interrupted:
                _stop_workers(ex)
            try:
                ex.shutdown(wait=True, cancel_futures=True)
            except TypeError:  # dask's ClientExecutor has no cancel_futures
                ex.shutdown(wait=True)
            client = getattr(ex, "_client", None)
            if client is not None:
                client.close()
        if interrupted:
            with deferred_signals():
                if own:  # the stopped workers' temporary files
                    remove_leftovers(casedir)
                try:  # the finished cases, marked incomplete; not the table of an earlier sweep
                    gather(outdir).save(outdir)
                except (InputError, OSError):
                    pass
    fault_point("sweep.table")
    table = gather(outdir)
    table.save(outdir)
    return table


@dataclass
class SweepTable:
    """All cases of a sweep: one row per case, columns = parameters, status, outputs."""

    params: list[str]
    rows: list[dict[str, Any]]
    #: number of cases of the sweep (None: not known); ``complete`` when every one has a row
    planned: int | None = None

    @property
    def complete(self) -> bool:
        return self.planned is None or len(self.rows) >= self.planned

    def column(self, name: str) -> np.ndarray:
        return np.array([r.get(name, math.nan) for r in self.rows], dtype=object)

    @property
    def counts(self) -> dict[str, int]:
        out = {STATUS_OK: 0, STATUS_FAILED: 0, STATUS_ERROR: 0}
        for r in self.rows:
            out[r["status"]] = out.get(r["status"], 0) + 1
        return out

    def save(self, outdir: str | os.PathLike) -> None:
        """Write ``table.json`` (rows, counts, ``complete``, ``planned``) and ``table.csv``,
        each through a temporary file and a rename."""
        outdir = Path(outdir)
        _write_json_atomic(outdir / "table.json", {"params": self.params, "rows": self.rows, "counts": self.counts,
                                                   "complete": self.complete, "planned": self.planned})
        cols: list[str] = []
        for r in self.rows:
            for k in r:
                if k not in cols and not isinstance(r[k], (list, dict)):
                    cols.append(k)
        with atomic_path(outdir / "table.csv") as tmp, open(tmp, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
            w.writeheader()
            w.writerows(self.rows)

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
    """Collect the finished cases of the sweep last run in ``outdir`` (the cases listed in its
    ``sweep.json``; records of other sweeps in the folder are not part of it)."""
    outdir = Path(outdir)
    try:
        meta = json.loads((outdir / "sweep.json").read_text())
        listed = meta["cases"]
    except (OSError, json.JSONDecodeError, KeyError, TypeError):
        raise InputError(f"{str(outdir)!r} holds no sweep of this version (no readable sweep.json with its case list)") from None
    done = _finished(outdir / "cases", {c["key"] for c in listed})
    rows = []
    for case in listed:
        rec = done.get(case["key"])
        if rec is None:
            continue
        i = case["index"]
        row: dict[str, Any] = {"index": i, **case["params"], "status": rec["status"], "wall_s": rec.get("wall_s")}
        if rec["status"] == STATUS_OK:
            for k, v in rec["outputs"].items():
                row[k] = v
            if rec.get("hdf5"):
                row["hdf5"] = str(Path("cases") / rec["hdf5"])  # the case's saved result, under outdir
        else:
            row["error"] = rec.get("error", "")
        rows.append(row)
    return SweepTable(list(meta["params"]), rows, planned=len(listed))
