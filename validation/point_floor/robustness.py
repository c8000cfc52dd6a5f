"""Default solves (half domain) of other contacts at 513 points: the fine-grid alternation
against X lines alone. Usage: python robustness.py"""
import json
import time

from ehl_multigrid.point.solve import solve_point

CASES = [(200.0, 20.0, 1.0), (1000.0, 10.0, 1.0), (50.0, 5.0, 1.0), (20.0, 10.0, 0.2), (100.0, 10.0, 0.05)]
for M, L, theta in CASES:
    for alt in (False, None):
        t = time.perf_counter()
        r = solve_point(M, L, theta=theta, points=513, half=True, alternating=alt, estimate=False,
                        raise_on_failure=False)
        print(json.dumps(dict(M=M, L=L, theta=theta, alternating=alt, status=r.status_name,
                              wu=round(r.work_units, 1), Hc=r.scalars["Hc"], Hm=r.scalars["Hm"],
                              wall=round(time.perf_counter() - t, 1))), flush=True)
