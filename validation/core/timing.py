"""Wall time of the two reference solves a refactor must not slow down: the line contact
(M, L) = (20, 10) on 1025 points and the circular contact (20, 10) on 513^2 (Roelands +
Dowson-Higginson, defaults otherwise). Median of ``--repeat`` solves after one warm-up, in one
process; the load average before and after is recorded. Writes JSON::

    python validation/core/timing.py build/validation/core/timing_before.json
"""

from __future__ import annotations

import json
import os
import statistics
import sys
import time
from pathlib import Path


def main(path: str, repeat: int = 5) -> None:
    import inspect

    from ehl_multigrid.line import solve_line
    from ehl_multigrid.point import solve_point

    # the same single solve before and after the error estimates existed
    kw = {"estimate": False} if "estimate" in inspect.signature(solve_line).parameters else {}
    cases = {
        "line_20_10_1025": lambda: solve_line(20.0, 10.0, points=1025, **kw),
        "point_20_10_513": lambda: solve_point(20.0, 10.0, points=513, **kw),
    }
    out = {"load_before": os.getloadavg()[0], "repeat": repeat}
    for name, fn in cases.items():
        fn()
        times = []
        for _ in range(repeat):
            t0 = time.perf_counter()
            sol = fn()
            times.append(time.perf_counter() - t0)
        out[name] = {"median_s": statistics.median(times), "min_s": min(times), "all_s": times,
                     "Hc": float(sol.Hc), "work_units": float(sol.report.work_units)}
        print(f"{name}: median {statistics.median(times):.3f} s (min {min(times):.3f}) Hc {sol.Hc:.10g}")
    out["load_after"] = os.getloadavg()[0]
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main(sys.argv[1])
