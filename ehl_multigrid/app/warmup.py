"""Compile the later stages' numba kernels in a helper process while the film stage runs.

On a fresh machine the first ``ehl run`` compiles every kernel it calls, one after another: the
film stage's point kernels, then the traction stage's thermal kernels (docs/performance.md,
"First use"). The layers register, in the entry-point group ``ehl.warmups``, a module with
``cold(kind) -> bool`` (whether its kernels for a ``"line"`` or ``"point"`` scene are missing
from numba's cache) and ``compile_kernels(kind)`` (a small computation that compiles them and
writes the cache). :func:`start` runs ``compile_kernels`` of every cold layer in a helper
process, on one numba thread, while the main process solves the film on the other core; the
stage that needs the kernels then loads them from the cache (or compiles what is still missing
itself). Nothing else is written: no output file, no lock.

``EHL_WARMUP=0`` in the environment turns the helpers off.
"""

from __future__ import annotations

import os
import subprocess
import sys
from importlib.metadata import entry_points
from typing import Any

#: seconds a helper still running at the end of the job is given to stop after SIGTERM
STOP_WAIT_S = 5.0


def _layers() -> dict[str, Any]:
    return {ep.name: ep for ep in entry_points(group="ehl.warmups")}


def start(kind: str) -> list[subprocess.Popen]:
    """One helper process per layer whose kernels for a ``kind`` scene (``"line"`` or any
    point contact) are not in numba's cache; none when ``EHL_WARMUP=0``."""
    if os.environ.get("EHL_WARMUP", "1") == "0":
        return []
    kind = "line" if kind == "line" else "point"
    helpers = []
    for name, ep in sorted(_layers().items()):
        try:
            cold = ep.load().cold(kind)
        except Exception:  # a layer that cannot say: its stage compiles as before
            cold = False
        if cold:
            env = {**os.environ, "NUMBA_NUM_THREADS": "1"}
            helpers.append(subprocess.Popen([sys.executable, "-m", "ehl_multigrid.app.warmup", name, kind],
                                            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                            stderr=subprocess.DEVNULL, env=env))
    return helpers


def stop(helpers: list[subprocess.Popen]) -> None:
    """End the helpers still running (numba writes each cache file whole, by renaming)."""
    for p in helpers:
        if p.poll() is None:
            p.terminate()
    for p in helpers:
        try:
            p.wait(STOP_WAIT_S)
        except subprocess.TimeoutExpired:
            p.kill()
            p.wait()


def main(argv: list[str]) -> int:
    name, kind = argv
    _layers()[name].load().compile_kernels(kind)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
