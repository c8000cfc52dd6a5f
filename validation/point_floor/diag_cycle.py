"""Where in a W cycle the point solver's floor comes back: the finest grid's scaled residual
after pre-smoothing, after the coarse-grid correction and after post-smoothing, per cycle.
Usage: python diag_cycle.py [points] [cycles]"""
import sys

import numpy as np

import ehl_multigrid.point.fas as fas
from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.point import numerics as nm
from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.point.solve import point_solver

n = int(sys.argv[1]) if len(sys.argv) > 1 else 1025
nc = int(sys.argv[2]) if len(sys.argv) > 2 else 6
pb = problem_from_moes(20, 10)
o = PointOptions.build(None, points=n, cycles=1, tol=1e-12, tol_load=1e-12, max_cycles=nc,
                       half=True, raise_on_failure=False, adapt=False)
solver = point_solver(pb, o)
hz = solver.hierarchy
top = len(hz.levels) - 1


def where(tag):
    lev = hz.levels[top]
    r = hz.residual(lev)
    sr = np.empty_like(r)
    nm.scaled_residual(r, lev.H, lev.rho, lev.eps, float(lev.Kc[0, 0]), lev.hx, lev.hy, True, sr, 0.0)
    a = np.abs(sr[:-1, 1:-1])
    j, i = np.unravel_index(int(np.argmax(a)), a.shape)
    print(f"  {tag:>12} rel_res {hz.rel_residual(lev):.2e} max {a.max() / lev.P.max():.2e} at X {lev.X[i + 1]:.4f} Y {lev.Y[j]:.4f}"
          f"  H00 {hz.H00:.8f}")


orig_correct = fas.PointHierarchy.correct
orig_restrict = fas.PointHierarchy.restrict


def restrict(self, k, s):
    if k == top and len(self.levels[top].P) and self.solver.cycles_done_top:
        where("pre-smoothed")
    return orig_restrict(self, k, s)


def correct(self, k, P0, s):
    orig_correct(self, k, P0, s)
    if k == top and self.solver.cycles_done_top:
        where("corrected")


fas.PointHierarchy.restrict = restrict
fas.PointHierarchy.correct = correct
solver.cycles_done_top = 0


def cb(info):
    if info.get("level") == top:
        solver.cycles_done_top += 1
        print(f"cycle {solver.cycles_done_top}: res {info.get('residual'):.2e} load {info.get('load_error'):.1e}")


solver.solve(callback=cb)
