"""One `ehl run` of a built-in scene in a fresh process, shared by the plan studies."""

from __future__ import annotations

import subprocess
import sys
import time


def run_scene(name: str, fidelity: str, out: str) -> tuple[subprocess.CompletedProcess, float]:
    """``ehl run <name> --fidelity F --no-plots --json --out <out>``; the finished process
    and its wall time [s]."""
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, "-m", "ehl_multigrid", "run", name, "--fidelity", fidelity,
                        "--no-plots", "--json", "--out", out], capture_output=True, text=True)
    return p, time.perf_counter() - t0
