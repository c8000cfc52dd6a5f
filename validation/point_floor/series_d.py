"""The chapter-5 series D point condition (disc 3, 1.93 GPa, M ~ 1595), isothermal core solve,
half domain, one W cycle per FMG level, adaptation off, tight tolerances: finest-grid
residual, load error, Hc and Hm per cycle, X lines alone against the default smoother.
Usage: python series_d.py [points] [cycles] "{options}" ..."""
import json
import sys
import time

from ehl_multigrid.model.scene import load_scene
from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.point.problem import problem_from_scene
from ehl_multigrid.point.solve import point_solver

n = int(sys.argv[1]) if len(sys.argv) > 1 else 513
nc = int(sys.argv[2]) if len(sys.argv) > 2 else 12
pb = problem_from_scene(load_scene("series_D_disc3_1.93GPa"))
for arg in sys.argv[3:] or ["{'alternating': False}", "{}"]:
    kw = eval(arg)
    kw.setdefault("adapt", False)
    o = PointOptions.build(None, points=n, cycles=1, tol=1e-12, tol_load=1e-12, max_cycles=nc,
                           half=True, raise_on_failure=False, **kw)
    t = time.perf_counter()
    solver = point_solver(pb, o)
    r = solver.solve()
    top = max(h.level for h in r.history)
    hs = [h for h in r.history if h.level == top]
    row = dict(points=n, M=pb.M, L=pb.L, options=arg, wall=round(time.perf_counter() - t, 1),
               residual=[h.residual for h in hs], load_error=[h.load_error for h in hs],
               Hc=[h.Hc for h in hs], Hm=[h.Hm for h in hs])
    print(json.dumps(row))
    print("options", arg, f"M {pb.M:.0f} L {pb.L:.2f}", "wall", row["wall"])
    print("  res", " ".join(f"{x:.1e}" for x in row["residual"]))
    print("  le ", " ".join(f"{x:.1e}" for x in row["load_error"]))
    print("  Hm ", " ".join(f"{x:.6f}" for x in row["Hm"]))
