"""Tight solve of (20, 10), half domain, one W cycle per FMG level, 16 more cycles: finest-grid
Hc, load error and residual per cycle. Usage: python tight.py 1025 "{'adapt': False}"
(the ALTERNATE_FROM rows of REPORT.md set ``ehl_multigrid.point.fas.ALTERNATE_FROM`` first)."""

import sys
import time

from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.point.solve import solve_point

n = int(sys.argv[1])
kw = eval(sys.argv[2]) if len(sys.argv) > 2 else {}
o = PointOptions(points=n, cycles=1, tol=1e-12, tol_load=1e-12, max_cycles=16, half=True,
                 raise_on_failure=False, **kw)
t = time.perf_counter()
r = solve_point(20, 10, options=o, estimate=False)
top = max(h.level for h in r.history)
hs = [h for h in r.history if h.level == top]
print(n, kw, f"wall {time.perf_counter() - t:.1f}", "status", r.status)
print(" Hc", " ".join(f"{h.Hc:.7f}" for h in hs))
print(" le", " ".join(f"{h.load_error:.1e}" for h in hs))
print(" res", " ".join(f"{h.residual:.1e}" for h in hs))
print(" actions", r.actions[:5])
