"""What two threads can gain on this machine at all: the issue's target (two threads >= 1.6x one
thread on a point solve) against the speed-up of kernels with no serial part.

Three numba kernels, each parallel over rows with nothing serial, on a field of the size of a
point grid (513^2 .. 2049^2 doubles):

* ``compute``: 40 exp/sinh per point, a few bytes of memory traffic per flop (compute bound);
* ``stream``: ``y = a x + y`` (memory bound: 24 bytes per point and two flops);
* ``line``: a tridiagonal (Thomas) solve along every row, the pattern of X-line relaxation
  (one dependent recurrence per row, rows independent).

Each kernel runs on one and on two threads (``numba.set_num_threads``) alternately, median of
``--repeat`` runs each. The load average before and after is recorded: on a busy machine the
gains mean nothing.

    python validation/bench/thread_ceiling.py --label LABEL

writes ``build/validation/bench/thread_ceiling_<label>.json`` and ``.md``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import sys
import time
from pathlib import Path

import numba
import numpy as np
from numba import njit, prange

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("bench")


@njit(parallel=True, cache=True)
def compute(x, out):
    ny, nx = x.shape
    for j in prange(ny):
        for i in range(nx):
            v = x[j, i]
            s = 0.0
            for _ in range(20):
                s += math.exp(-v * s * 1e-3) + math.sinh(v * 1e-3)
            out[j, i] = s


@njit(parallel=True, cache=True)
def stream(a, x, y):
    ny, nx = x.shape
    for j in prange(ny):
        for i in range(nx):
            y[j, i] = a * x[j, i] + y[j, i]


@njit(parallel=True, cache=True)
def line(b, r, c, x):
    ny, nx = b.shape
    for j in prange(ny):
        cj = c[j]
        cj[0] = -1.0 / b[j, 0]
        rr = r[j, 0] / b[j, 0]
        x[j, 0] = rr
        for i in range(1, nx):
            m = b[j, i] + cj[i - 1]
            cj[i] = -1.0 / m
            x[j, i] = (r[j, i] + x[j, i - 1]) / m
        for i in range(nx - 2, -1, -1):
            x[j, i] -= cj[i] * x[j, i + 1]


def kernels(n: int) -> dict:
    rng = np.random.default_rng(0)
    x = rng.random((n, n))
    y = rng.random((n, n))
    out = np.empty((n, n))
    b = 4.0 + rng.random((n, n))
    c = np.empty((n, n))
    return {
        "compute": lambda: compute(x, out),
        "stream": lambda: stream(1.0001, x, y),
        "line": lambda: line(b, y, c, out),
    }


def timed(fn, repeat: int) -> float:
    ts = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t)
    return statistics.median(ts)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--label", required=True)
    ap.add_argument("--points", type=int, nargs="+", default=[513, 1025, 2049])
    ap.add_argument("--repeat", type=int, default=9)
    ap.add_argument("--rounds", type=int, default=3)
    a = ap.parse_args()
    if numba.config.NUMBA_NUM_THREADS < 2:
        raise SystemExit("NUMBA_NUM_THREADS must be at least 2 for this benchmark")
    rows = []
    for n in a.points:
        ks = kernels(n)
        for name, fn in ks.items():
            fn()  # compile / load
            one, two = [], []
            load0 = os.getloadavg()[0]
            for _ in range(a.rounds):
                numba.set_num_threads(1)
                one.append(timed(fn, a.repeat))
                numba.set_num_threads(2)
                two.append(timed(fn, a.repeat))
            t1, t2 = statistics.median(one), statistics.median(two)
            rows.append({"kernel": name, "points": n, "one_thread_s": t1, "two_threads_s": t2,
                         "gain": t1 / t2, "load": [load0, os.getloadavg()[0]]})
            print(json.dumps(rows[-1]), flush=True)
    OUT.mkdir(exist_ok=True)
    (OUT / f"thread_ceiling_{a.label}.json").write_text(json.dumps(rows, indent=1))
    lines = ["| kernel | grid | one thread [ms] | two threads [ms] | gain | load before/after |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['kernel']} | {r['points']}^2 | {1e3 * r['one_thread_s']:.2f} | "
                     f"{1e3 * r['two_threads_s']:.2f} | {r['gain']:.2f} | {r['load'][0]:.2f}/{r['load'][1]:.2f} |")
    (OUT / f"thread_ceiling_{a.label}.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
