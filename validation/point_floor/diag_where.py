"""Per finest-grid cycle of (20, 10) (half domain, one W per FMG level): the scaled residual's
RMS and its largest nodes (X, Y, eps/hx^2, P/pmax). Usage:
python diag_where.py points "{'nu2': 2, 'switch': 4.0}" [cycles]"""
import sys

import numpy as np

from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.point import numerics as nm
from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.point.solve import point_solver

n = int(sys.argv[1])
kw = eval(sys.argv[2]) if len(sys.argv) > 2 else {}
nc = int(sys.argv[3]) if len(sys.argv) > 3 else 8
kw.setdefault("adapt", False)
o = PointOptions.build(None, points=n, cycles=1, tol=1e-12, tol_load=1e-12, max_cycles=nc,
                       half=True, raise_on_failure=False, **kw)
solver = point_solver(problem_from_moes(20, 10), o)
hz = solver.hierarchy
top = len(hz.levels) - 1


def cb(info):
    if info["level"] != top:
        return
    lev = hz.levels[top]
    r = hz.residual(lev)
    sr = np.empty_like(r)
    nm.scaled_residual(r, lev.H, lev.rho, lev.eps, float(lev.Kc[0, 0]), lev.hx, lev.hy, True, sr, 0.0)
    a = np.abs(sr[:-1, 1:-1]) / lev.P.max()
    idx = np.argsort(a.ravel())[::-1][:4]
    print(f"cycle {info['cycle']} res {info['residual']:.2e} load {info['load_error']:.1e} Hc {info['Hc_venner']:.7f}"
          f" switch {solver.settings.switch}")
    for k in idx:
        j, i = np.unravel_index(k, a.shape)
        i += 1
        print(f"    X {lev.X[i]:.4f} Y {lev.Y[j]:.4f} sr {a[j, i - 1]:.1e} eps/h2 {lev.eps[j, i] / lev.hx**2:.2f}"
              f" P {lev.P[j, i] / lev.P.max():.3f}")


solver.solve(callback=cb)
