"""Peak resident memory of one point solve, and where it happens (issue "Speed": peak memory).

A thread samples the resident set (``/proc/self/statm``) every 3 ms and keeps the main
thread's stack at each new peak, so the peak is attributed to the line of code that reached it
(``ru_maxrss`` alone gives the number, not the place; ``tracemalloc`` misses memory that numpy
allocates lazily and glibc keeps). Circular (20, 10), Roelands + Dowson-Higginson, residual stop,
after a 129^2 warm-up.

    NUMBA_NUM_THREADS=1 python validation/bench/peak_memory.py 2049 full [--label LABEL]

appends one record (commit, points, domain, baseline and peak MB, the stack at the peak, work
units) to ``build/validation/bench/peak_memory_<label>.json``; a record of another commit under the same label is
dropped (a label holds the runs of one code version). The measured peaks (per-grid against
shared arrays: 2049^2 full 833 -> 727 MB, half 636 -> 484 MB; 4097^2 half 1308 MB) are in
validation/bench/REPORT.md, section "Memory".
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import threading
import time
import traceback
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1]))
sys.path.insert(0, str(HERE.parent))
from _paths import out_dir  # noqa: E402


def rss_mb() -> float:
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize() / 2**20


def main() -> None:
    from ehl_multigrid.point import solve_point

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("points", type=int)
    ap.add_argument("domain", choices=("half", "full"))
    ap.add_argument("--label", default="latest")
    a = ap.parse_args()
    solve_point(20.0, 10.0, points=129, estimate=False)
    base = rss_mb()
    peak: list = [0.0, ""]
    main_id = threading.main_thread().ident
    stop = threading.Event()

    def sample() -> None:
        while not stop.is_set():
            r = rss_mb()
            if r > peak[0] + 1.0:
                frame = sys._current_frames().get(main_id)
                peak[0], peak[1] = r, "".join(traceback.format_stack(frame)[-5:]) if frame else ""
            time.sleep(0.003)

    th = threading.Thread(target=sample, daemon=True)
    th.start()
    t = time.perf_counter()
    sol = solve_point(20.0, 10.0, points=a.points, half=a.domain == "half", estimate=False,
                      raise_on_failure=False)
    wall = time.perf_counter() - t
    stop.set()
    th.join()
    commit = subprocess.run(["git", "-C", str(HERE), "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip() or "unknown"
    rec = {"commit": commit, "points": a.points, "domain": a.domain, "baseline_mb": base, "peak_mb": peak[0],
           "ru_maxrss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0,
           "stack_at_peak": peak[1], "work_units": sol.work_units, "status": sol.status_name,
           "wall_s": wall}
    out = out_dir("bench") / f"peak_memory_{a.label}.json"
    rows = [r for r in (json.loads(out.read_text()) if out.is_file() else []) if r.get("commit") == commit]
    rows.append(rec)
    tmp = out.with_suffix(".tmp")
    tmp.write_text(json.dumps(rows, indent=1))
    tmp.replace(out)
    print(f"{a.points}^2 {a.domain}: baseline {base:.0f} MB, peak {peak[0]:.0f} MB "
          f"(ru_maxrss {rec['ru_maxrss_mb']:.0f} MB)\n{peak[1]}")


if __name__ == "__main__":
    main()
