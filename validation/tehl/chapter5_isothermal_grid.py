"""Isothermal grid convergence at the chapter-5 point condition (series D, disc 3, M = 1595):
half-domain solves at 257-2049 points, the same box; prints Hc, Hm (Venner units) per grid.

Usage: ``python validation/tehl/chapter5_isothermal_grid.py [OUT.json]`` (default
``build/validation/tehl/chapter5_isothermal_grid.json``).
"""

import json
import sys
import time
from pathlib import Path

from ehl_multigrid.model.scene import load_scene
from ehl_multigrid.point import solve_point

sc = load_scene("series_D_disc3_1.93GPa")
rows = []
for n in (257, 513, 1025, 2049):
    t = time.perf_counter()
    s = solve_point(scene=sc, points=n, half=True, estimate=False, raise_on_failure=False)
    rows.append({"points": n, "status": s.status_name, "Hc": s.scalars.get("Hc"), "Hm": s.scalars.get("Hm"),
                 "work_units": s.work_units, "actions": s.actions[-2:], "wall_s": time.perf_counter() - t})
    print(json.dumps(rows[-1]), flush=True)
if len(sys.argv) > 1:
    out = Path(sys.argv[1])
else:
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from _paths import out_dir

    out = out_dir("tehl") / "chapter5_isothermal_grid.json"
with open(out, "w") as fh:
    json.dump(rows, fh, indent=1)
