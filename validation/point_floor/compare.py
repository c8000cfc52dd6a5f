"""Default solve of (20, 10) (half domain) with the given option sets: status, cycles, work
units, final residual and load error, Hc, wall time. Usage:
python compare.py points "{}" "{'alternating': True}" ..."""
import json
import sys
import time

from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.point.solve import solve_point

n = int(sys.argv[1])
rows = []
for arg in sys.argv[2:]:
    kw = eval(arg)
    kw.setdefault("half", True)
    kw.setdefault("raise_on_failure", False)
    o = PointOptions(points=n, **kw)
    t = time.perf_counter()
    r = solve_point(kw.pop("M", 20), kw.pop("L", 10), options=o, estimate=False)
    wall = time.perf_counter() - t
    top = max(h.level for h in r.history)
    hs = [h for h in r.history if h.level == top]
    row = dict(points=n, options=arg, status=int(r.status), cycles=len(hs), wu=round(r.work_units, 1),
               residual=hs[-1].residual, load_error=hs[-1].load_error, Hc=hs[-1].Hc, wall=round(wall, 1))
    rows.append(row)
    print(json.dumps(row))
