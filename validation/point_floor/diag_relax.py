"""Diagnose the point solver's residual floor: solve (20, 10) to the floor, then apply the
fine-grid smoother alone (H00 fixed) and report the residual, the load error and where the
residual sits after each sweep. Usage: python diag_relax.py [points] [sweeps] [switch] [omega_jd]"""
import sys

import numpy as np

from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.point import numerics as nm
from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.point.solve import point_solver

n = int(sys.argv[1]) if len(sys.argv) > 1 else 1025
ns = int(sys.argv[2]) if len(sys.argv) > 2 else 10
sw = float(sys.argv[3]) if len(sys.argv) > 3 else None
wjd = float(sys.argv[4]) if len(sys.argv) > 4 else None
pb = problem_from_moes(20, 10)
o = PointOptions.build(None, points=n, cycles=1, tol=1e-12, tol_load=1e-12, max_cycles=6,
                       half=True, raise_on_failure=False, adapt=False)
solver = point_solver(pb, o)
solver.solve()
hz = solver.hierarchy
lev = hz.levels[-1]
s = solver.settings
if sw is not None:
    s.switch = sw
if wjd is not None:
    s.omega_jd = wjd


def report(tag):
    r = hz.residual(lev)
    sr = np.empty_like(r)
    nm.scaled_residual(r, lev.H, lev.rho, lev.eps, float(lev.Kc[0, 0]), lev.hx, lev.hy, True, sr, 0.0)
    a = np.abs(sr[:-1, 1:-1])
    j, i = np.unravel_index(int(np.argmax(a)), a.shape)
    i += 1
    le = (hz.load(lev) - hz.g_target) / hz.g_target
    print(f"{tag:>8} rel_res {hz.rel_residual(lev):.2e} max {a.max() / lev.P.max():.2e} at X {lev.X[i]:.4f} "
          f"Y {lev.Y[j]:.4f} eps/h2 {lev.eps[j, i] / lev.hx**2:.2f} load_err {le:+.2e} Hc {hz.central_film(lev):.7f}")


report("floor")
for k in range(ns):
    hz._sweep(lev, s)
    report(f"sweep{k + 1}")
