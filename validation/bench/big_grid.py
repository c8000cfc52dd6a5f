"""One large point solve for the speed issue's 4097^2 target: circular (20, 10), Roelands +
Dowson-Higginson, residual stop, after a 129^2 warm-up (numba compilation). Prints one JSON line
(wall and CPU time, work units, cycles, peak RSS, Hc, the policy's actions).

Usage: ``python validation/bench/big_grid.py POINTS half|full`` (the thread count is numba's:
``NUMBA_NUM_THREADS``). To keep the line, redirect it to the study's folder, e.g.
``python validation/bench/big_grid.py 4097 half > build/validation/bench/big_grid_4097.json``.
"""

import json
import resource
import sys
import time

from ehl_multigrid.point import solve_point

n = int(sys.argv[1])
half = sys.argv[2] == "half"
solve_point(20.0, 10.0, points=129, estimate=False)
t = time.perf_counter()
c0 = time.process_time()
s = solve_point(20.0, 10.0, points=n, half=half, estimate=False, raise_on_failure=False)
row = {"points": n, "half": half, "status": s.status_name, "Hc": s.scalars["Hc"], "Hm": s.scalars["Hm"],
       "work_units": s.work_units, "cycles": s.cycles, "wall_s": time.perf_counter() - t,
       "cpu_s": time.process_time() - c0, "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
       "actions": s.actions}
print(json.dumps(row), flush=True)
