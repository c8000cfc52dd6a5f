"""What the first ``ehl run`` on a fresh machine compiles, and how long each kernel takes.

The default main job (``ehl run`` on the default scene, figures included) runs in a fresh
subprocess with an empty ``NUMBA_CACHE_DIR`` (the *cold* run: every kernel is compiled), then
again in a fresh subprocess on the cache that run left (the *warm* run: every kernel loads from
the cache). In each subprocess a listener on numba's ``"numba:compile"`` event
(:mod:`numba.core.event`) records every specialisation that is compiled: the kernel, its
argument types, the kernel that asked for it, its inclusive seconds (with the kernels it calls
compiled inside it), its exclusive seconds (without them) and the part of those spent holding
the LLVM lock (optimisation and machine code). A listener on ``"numba:compiler_lock"`` sums the
seconds spent holding numba's compiler lock at the outermost level (compiling, or loading from
and saving to the cache). The JSON also holds the film and friction numbers of the run's
summary, so that two runs (before/after a change) can be checked to give the same answer.

    python validation/bench/cold_start.py --label after

writes ``build/validation/bench/cold_start[_<label>].json`` and, beside it,
``cold_start[_<label>]_signatures.pkl``: the argument types of the kernels the job compiled from
Python. ``--compile-only PKL`` compiles just those specialisations in a fresh process on an
empty cache (no solve), a quicker and less load-sensitive measure of the compile time alone
after a change to the kernels (the argument types must still be the ones the job passes).

Walls are of the whole process (interpreter start, imports, solve, output), like the
``ehl run`` a user starts. The load average before and after each run is recorded: on a loaded
machine a cold run is slower by roughly the load, so compare runs taken under the same load
only (``--source DIR`` runs another source tree, put first on ``PYTHONPATH``, e.g. an exported
older commit, so that a before/after pair can be taken back to back).
"""

from __future__ import annotations

import argparse
import importlib
import json
import os
import pickle
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("bench")

# what the summary of the default job must keep unchanged (the film and the friction)
_ANSWER_KEYS = {
    "film": ("Hc", "Hm", "hc", "hm", "p_spike", "points", "status"),
    "traction": ("friction_coefficient_at_operating_slip",),
}


class _Recorder:
    """Listeners on numba's compile, compiler-lock and LLVM-lock events."""

    def __init__(self) -> None:
        from numba.core import event as ev

        self.compiles: list[dict[str, Any]] = []
        self.top: list[tuple[str, str, tuple]] = []  # compiled from Python: (module, qualname, types)
        self.lock_s = 0.0
        stack: list[dict[str, Any]] = []
        lock = {"depth": 0, "t0": 0.0}
        rec_self = self

        class Compile(ev.Listener):
            def on_start(self, event: ev.Event) -> None:
                fn = event.data["dispatcher"].py_func
                if not stack:
                    rec_self.top.append((fn.__module__, fn.__qualname__, tuple(event.data["args"])))
                stack.append({
                    "kernel": f"{fn.__module__}.{fn.__qualname__}",
                    "args": ", ".join(str(a) for a in event.data["args"]),
                    "parent": stack[-1]["kernel"] if stack else None,
                    "t0": time.perf_counter(), "nested": 0.0, "llvm_s": 0.0,
                })

            def on_end(self, event: ev.Event) -> None:
                rec = stack.pop()
                inclusive = time.perf_counter() - rec.pop("t0")
                rec["inclusive_s"] = inclusive
                rec["exclusive_s"] = inclusive - rec.pop("nested")
                rec["depth"] = len(stack)
                if stack:
                    stack[-1]["nested"] += inclusive
                rec_self.compiles.append(rec)

        class LLVM(ev.Listener):
            # each call into LLVM (optimisation, machine code), given to the innermost kernel
            def on_start(self, event: ev.Event) -> None:
                if stack:
                    stack[-1]["llvm_t0"] = time.perf_counter()

            def on_end(self, event: ev.Event) -> None:
                if stack and "llvm_t0" in stack[-1]:
                    stack[-1]["llvm_s"] += time.perf_counter() - stack[-1].pop("llvm_t0")

        class Lock(ev.Listener):
            def on_start(self, event: ev.Event) -> None:
                if lock["depth"] == 0:
                    lock["t0"] = time.perf_counter()
                lock["depth"] += 1

            def on_end(self, event: ev.Event) -> None:
                lock["depth"] -= 1
                if lock["depth"] == 0:
                    rec_self.lock_s += time.perf_counter() - lock["t0"]

        ev.register("numba:compile", Compile())
        ev.register("numba:compiler_lock", Lock())
        ev.register("numba:llvm_lock", LLVM())

    def dump(self, events_path: Path, **extra: Any) -> None:
        with open(events_path.with_suffix(".pkl"), "wb") as fh:
            pickle.dump(self.top, fh)
        events_path.write_text(json.dumps({"compiles": self.compiles, "compiler_lock_s": self.lock_s, **extra}))


def _clean_path() -> None:
    # this folder and validation/ hold modules named like the packages (bench/thermal.py,
    # validation/thermal/): off the path, so that the child imports the real packages
    here = Path(__file__).resolve().parent
    sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() not in (here, here.parent)]


def _child_run(run_out: Path, events_path: Path, argv: list[str]) -> int:
    """Run ``ehl run`` in this process with the listeners installed; write the events."""
    import contextlib
    import io

    _clean_path()
    rec = _Recorder()
    from ehl_multigrid.app.cli import main

    buf = io.StringIO()
    t0 = time.perf_counter()
    with contextlib.redirect_stdout(buf):
        rc = main(["run", *argv, "--json", "--out", str(run_out)])
    job_s = time.perf_counter() - t0
    try:
        payload = json.loads(buf.getvalue())
    except json.JSONDecodeError:
        payload = {}
    answer = {stage: {k: payload.get(stage, {}).get(k) for k in keys} for stage, keys in _ANSWER_KEYS.items()}
    rec.dump(events_path, exit_code=rc, job_s=job_s, answer=answer)
    return rc


def _child_compile(signatures: Path, events_path: Path) -> int:
    """Compile the specialisations listed in ``signatures`` (no solve); write the events."""
    _clean_path()
    with open(signatures, "rb") as fh:
        wanted = pickle.load(fh)
    rec = _Recorder()
    t0 = time.perf_counter()
    for module, qualname, types in wanted:
        obj: Any = importlib.import_module(module)
        for part in qualname.split("."):
            obj = getattr(obj, part)
        obj.compile(types)
    rec.dump(events_path, exit_code=0, job_s=time.perf_counter() - t0, answer={})
    return 0


def _subprocess(child_args: list[str], cache: Path, source: Path | None,
                keep_signatures: Path | None = None) -> dict[str, Any]:
    """One child (``--child-run OUT`` or ``--child-compile PKL`` plus its arguments) in a fresh
    interpreter on the numba cache ``cache``; its events, wall and load average."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache), EHL_PROGRESS="off")
    if source is not None:
        env["PYTHONPATH"] = os.pathsep.join(p for p in (str(source), env.get("PYTHONPATH", "")) if p)
    with tempfile.TemporaryDirectory(prefix="ehl-cold-") as tmp:
        events = Path(tmp) / "events.json"
        args = [a.replace("{tmp}", tmp) for a in child_args]
        load_before = os.getloadavg()
        t0 = time.perf_counter()
        proc = subprocess.run([sys.executable, __file__, "--events", str(events), *args],
                              env=env, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        load_after = os.getloadavg()
        if not events.exists():
            raise SystemExit(f"the child failed (exit {proc.returncode}):\n{proc.stderr[-2000:]}")
        rec = json.loads(events.read_text())
        if keep_signatures is not None:
            part = keep_signatures.with_suffix(".pkl.tmp")
            part.write_bytes(events.with_suffix(".pkl").read_bytes())
            part.replace(keep_signatures)
    rec.update(wall_s=wall, load_before=load_before, load_after=load_after)
    return rec


def _per_kernel(compiles: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Specialisations grouped by kernel, slowest (exclusive seconds) first."""
    kernels: dict[str, dict[str, Any]] = {}
    for c in compiles:
        k = kernels.setdefault(c["kernel"], {"kernel": c["kernel"], "count": 0, "exclusive_s": 0.0,
                                             "llvm_s": 0.0, "signatures": []})
        k["count"] += 1
        k["exclusive_s"] = round(k["exclusive_s"] + c["exclusive_s"], 3)
        k["llvm_s"] = round(k["llvm_s"] + c["llvm_s"], 3)
        k["signatures"].append({"args": c["args"], "parent": c["parent"], "exclusive_s": round(c["exclusive_s"], 3)})
    return sorted(kernels.values(), key=lambda k: -k["exclusive_s"])


def _per_module(compiles: list[dict[str, Any]]) -> dict[str, dict[str, float]]:
    """Count and exclusive seconds per module (numba's own overloads under their module)."""
    mods: dict[str, dict[str, float]] = {}
    for c in compiles:
        m = mods.setdefault(c["kernel"].split(".<locals>")[0].rsplit(".", 1)[0], {"count": 0, "exclusive_s": 0.0})
        m["count"] += 1
        m["exclusive_s"] = round(m["exclusive_s"] + c["exclusive_s"], 3)
    return dict(sorted(mods.items(), key=lambda kv: -kv[1]["exclusive_s"]))


def _summary(rec: dict[str, Any]) -> dict[str, Any]:
    compiles = rec["compiles"]
    return {
        "wall_s": round(rec["wall_s"], 2), "job_s": round(rec["job_s"], 2), "exit_code": rec["exit_code"],
        "load_before": [round(v, 2) for v in rec["load_before"]],
        "load_after": [round(v, 2) for v in rec["load_after"]],
        "compile_count": len(compiles),
        "compile_count_package": sum(1 for c in compiles if not c["kernel"].startswith("numba.")),
        "compile_s": round(sum(c["exclusive_s"] for c in compiles), 2),
        "llvm_s": round(sum(c["llvm_s"] for c in compiles), 2),
        "compiler_lock_s": round(rec["compiler_lock_s"], 2),
    }


def measure(source: Path | None, run_args: list[str], warm_runs: int, signatures: Path) -> dict[str, Any]:
    """A cold run on an empty numba cache, then ``warm_runs`` runs on the cache it left."""
    with tempfile.TemporaryDirectory(prefix="ehl-numba-cache-") as cache:
        child = ["--child-run", "{tmp}/out", *run_args]
        cold = _subprocess(child, Path(cache), source, keep_signatures=signatures)
        warm = [_subprocess(child, Path(cache), source) for _ in range(warm_runs)]
    return {
        "command": " ".join(["ehl run", *run_args]),
        "source": str(source) if source is not None else "installed package",
        "cpus": os.cpu_count(),
        "cold": _summary(cold),
        "warm": [dict(_summary(w), compiled=sorted({c["kernel"] for c in w["compiles"]})) for w in warm],
        "answer": cold["answer"],
        "answers_identical_warm": all(w["answer"] == cold["answer"] for w in warm),
        "per_module": _per_module(cold["compiles"]),
        "per_kernel": _per_kernel(cold["compiles"]),
    }


def measure_compile(source: Path | None, signatures: Path, repeat: int) -> dict[str, Any]:
    """Compile the job's specialisations (``signatures``) on an empty cache, ``repeat`` times."""
    runs = []
    for _ in range(repeat):
        with tempfile.TemporaryDirectory(prefix="ehl-numba-cache-") as cache:
            runs.append(_subprocess(["--child-compile", str(signatures)], Path(cache), source))
    best = min(runs, key=lambda r: r["wall_s"])
    return {
        "command": f"compile only: {signatures.name}",
        "source": str(source) if source is not None else "installed package",
        "cpus": os.cpu_count(),
        "cold": _summary(best),
        "repeats": [_summary(r) for r in runs],
        "per_module": _per_module(best["compiles"]),
        "per_kernel": _per_kernel(best["compiles"]),
    }


def _print(res: dict[str, Any]) -> None:
    def line(tag: str, s: dict[str, Any]) -> str:
        return (f"{tag}: wall {s['wall_s']:.1f} s, {s['compile_count']} compiled ({s['compile_count_package']} of "
                f"the package) in {s['compile_s']:.1f} s (LLVM {s['llvm_s']:.1f} s; compiler lock "
                f"{s['compiler_lock_s']:.1f} s), load {s['load_before'][0]:.2f} -> {s['load_after'][0]:.2f}")

    print(line("cold", res["cold"]))
    for w in res.get("warm", []):
        print(line("warm", w))
    for r in res.get("repeats", []):
        print(line("  repeat", r))
    print("per module:")
    for m, v in res["per_module"].items():
        print(f"  {v['count']:3d}  {v['exclusive_s']:7.2f} s  {m}")
    print("per kernel (exclusive seconds, LLVM part):")
    for k in res["per_kernel"]:
        print(f"  {k['count']:2d}  {k['exclusive_s']:6.2f} s  {k['llvm_s']:6.2f} s  {k['kernel']}")
        if k["count"] > 1:
            for s in k["signatures"]:
                print(f"            {s['exclusive_s']:6.2f} s  ({s['args']})  from {s['parent']}")
    if "answer" in res:
        print("answer:", json.dumps(res["answer"]))


def _write(path: Path, res: dict[str, Any]) -> None:
    part = path.with_suffix(".json.tmp")
    part.write_text(json.dumps(res, indent=1))
    part.replace(path)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--label", default="", help="suffix of the output files (e.g. before, after)")
    ap.add_argument("--source", type=Path, help="source tree put first on PYTHONPATH (default: the installed package)")
    ap.add_argument("--warm", type=int, default=1, help="warm runs after the cold one (default 1)")
    ap.add_argument("--no-plots", action="store_true", help="pass --no-plots to ehl run")
    ap.add_argument("--compile-only", type=Path, metavar="PKL",
                    help="compile the specialisations of an earlier run's signatures file, no solve")
    ap.add_argument("--repeat", type=int, default=1, help="repeats of --compile-only (the fastest is kept)")
    ap.add_argument("--events", type=Path, help=argparse.SUPPRESS)
    ap.add_argument("--child-run", type=Path, help=argparse.SUPPRESS)
    ap.add_argument("--child-compile", type=Path, help=argparse.SUPPRESS)
    args, rest = ap.parse_known_args(argv)
    run_args = [*rest, *(["--no-plots"] if args.no_plots else [])]
    if args.child_run:
        return _child_run(args.child_run, args.events, run_args)
    if args.child_compile:
        return _child_compile(args.child_compile, args.events)
    source = args.source.resolve() if args.source else None
    stem = f"cold_start_{args.label}" if args.label else "cold_start"
    if args.compile_only:
        res = measure_compile(source, args.compile_only.resolve(), args.repeat)
        path = OUT / f"{stem}_compile.json"
    else:
        res = measure(source, run_args, args.warm, OUT / f"{stem}_signatures.pkl")
        path = OUT / f"{stem}.json"
    _write(path, res)
    _print(res)
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
