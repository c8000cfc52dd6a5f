"""What a user gets from `ehl solve SCENE` on every built-in scene at the default accuracy.

Each scene is solved by the command line, as a user would run it (`ehl solve SCENE --json
--no-plots`, default accuracy 0.5 %), in its own process with a time limit, and the status,
estimated errors and their budget, the grid and the wall time of the whole accuracy sequence
are recorded. Resumable: a scene already solved by the same code is not solved again.

    NUMBA_NUM_THREADS=1 python validation/accuracy/builtin_scenes.py [--timeout 1800] [--only NAME ...]

Writes ``build/validation/accuracy/builtin_scenes.json``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from tqdm import tqdm

from ehl_multigrid.model.scene import builtin_scene_names

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "validation"))
from _paths import out_dir  # noqa: E402


def code_version() -> str:
    """The committed tree of the package (``+dirty`` with uncommitted changes to it): other
    commits (reports, studies) do not invalidate the records."""
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD:ehl_multigrid"], cwd=ROOT,
                          capture_output=True, text=True).stdout.strip()
    dirty = subprocess.run(["git", "status", "--porcelain", "ehl_multigrid"], cwd=ROOT,
                           capture_output=True, text=True).stdout.strip()
    return head + ("+dirty" if dirty else "")


def solve(name: str, timeout: float) -> dict:
    keys = ("status", "Hc", "Hm", "Hc_error", "Hm_error", "error_budget", "points", "cycles",
            "wall_total_s", "message")
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        try:
            p = subprocess.run([sys.executable, "-m", "ehl_multigrid", "solve", name, "--json",
                                "--no-plots", "--out", tmp], capture_output=True, text=True,
                               timeout=timeout, env=os.environ.copy())
        except subprocess.TimeoutExpired:
            return {"status": "timeout", "message": f"over {timeout:g} s"}
        wall = time.perf_counter() - t0
    try:
        d = json.loads(p.stdout)
    except json.JSONDecodeError:
        return {"status": "no output", "exit": p.returncode, "message": p.stderr.strip()[-300:],
                "wall_process_s": wall}
    return {**{k: d.get(k) for k in keys}, "exit": p.returncode, "wall_process_s": wall}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--timeout", type=float, default=1800.0)
    ap.add_argument("--only", nargs="*", default=None)
    a = ap.parse_args()
    OUT = out_dir("accuracy") / "builtin_scenes.json"
    done = json.loads(OUT.read_text()) if OUT.is_file() else {}
    version = code_version()
    names = a.only or builtin_scene_names()
    for name in tqdm(names):
        if done.get(name, {}).get("code") == version:
            continue
        done[name] = {**solve(name, a.timeout), "code": version}
        tmp = OUT.with_suffix(".tmp")
        tmp.write_text(json.dumps(done, indent=1))
        tmp.replace(OUT)
    for name in names:
        r = done[name]
        print(f"{name:32s} {r['status']:12s} Hc_err {r.get('Hc_error')} Hm_err {r.get('Hm_error')} "
              f"points {r.get('points')} wall {r.get('wall_total_s')}")


if __name__ == "__main__":
    main()
