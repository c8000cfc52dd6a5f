"""Study 4: speed targets. 513^2 and 1025^2 circular contact at (M, L) = (20, 10), Roelands +
DH, FAS W cycles + FFT, 2 threads (``--threads``); each run in a fresh process (numba cache warm), repeated;
solver wall time, whole-process wall time, peak resident memory, machine load, Hc against
the extrapolated value of tests/point/reference.json (target: within 0.5 %).

    python validation/point/targets.py [--repeats 3]
"""

import argparse
import json
import os
import subprocess
import sys
import time

from common import HERE, OUT

CODE = r"""
import json, resource, time
t0 = time.perf_counter()
from ehl_multigrid.point import problem_from_moes, solve_fas, build_result
import numpy as np
pb = problem_from_moes(20.0, 10.0)
# warm the numba cache / kernels on a tiny grid so the timing is the solve itself
solve_fas(pb, points=33, n_coarse=16)
t1 = time.perf_counter()
c1 = time.process_time()
sol = solve_fas(pb, points=%d, threads=%d)
t2 = time.perf_counter()
c2 = time.process_time()
res = build_result(sol)
print(json.dumps({"solver_wall_s": sol.report.wall_s, "solve_cpu_s": c2 - c1, "solve_call_s": t2 - t1, "process_s": t2 - t0,
                  "Hc": res.scalars["Hc"], "Hm": res.scalars["Hm"], "converged": res.scalars["converged"],
                  "cycles": res.scalars["cycles"], "work_units": sol.report.work_units,
                  "load_error": res.scalars["load_error"], "residual": res.scalars["final_residual"],
                  "maxrss_MB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))
"""


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--tag", default="")
    a = ap.parse_args()
    ref = json.loads((HERE.parents[1] / "tests" / "point" / "reference.json").read_text())
    ext = ref["Hc_extrapolated"]
    out = {"Hc_extrapolated": ext, "targets_s": {"513": 2.5, "1025": 10.0},
           "classic_C_s": {"513": 4.8, "1025": 18.0}, "runs": {}}
    for n in (513, 1025):
        runs = []
        for _ in range(a.repeats):
            la = os.getloadavg()[0]
            t = time.perf_counter()
            p = subprocess.run([sys.executable, "-c", CODE % (n, a.threads)], capture_output=True, text=True,
                               cwd=str(HERE.parents[1]), timeout=600)
            row = json.loads(p.stdout.strip().splitlines()[-1])
            row.update(load_before=la, load_after=os.getloadavg()[0], subprocess_s=time.perf_counter() - t,
                       Hc_err_pct=100 * (row["Hc"] / ext - 1))
            runs.append(row)
            print(n, row, flush=True)
        out["runs"][str(n)] = runs
        walls = sorted(r["solver_wall_s"] for r in runs)
        out[f"best_{n}_s"] = walls[0]
        out[f"median_{n}_s"] = walls[len(walls) // 2]
    out["threads"] = a.threads
    (OUT / f"targets{a.tag}.json").write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
