"""Prototype of the transient point contact on the shared driver -- runs only once
``point_squeeze.diff`` (the squeeze coefficient ``ct`` of the point kernels) is applied to
``ehl_multigrid/point``; kept here as the measured basis of that proposal, not as a solver.

``python point_prototype.py POINTS [S] [A/Hc]``: a cosine-Gaussian dent (default depth 0.5 Hc,
W = 0.5 a) on body 1 from X = -2 through a circular contact (M = 20, L = 10) at Courant number
1, BDF2 (first step backward Euler), one FAS solve per step by ``MultilevelSolver``.
Measured in a scratch copy with the patch (2-core box, loaded): ct = 0 bit-identical to the
steady point solver (Hc 4.13288925937158 at (20, 10), 129 points) and tests/point 68 passed;
65^2: 32 steps, 5.3 cycles/step, 0.07 s/step; 129^2: 64 steps, 4.6 (S = 0) and 4.2 (S = 1)
cycles/step, 0.22-0.23 s/step.
"""

from __future__ import annotations

import math
import sys
import time

import numpy as np

from ehl_multigrid.multigrid.driver import MultilevelSolver
from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.multigrid.policy import RobustnessPolicy
from ehl_multigrid.point import numerics as nm
from ehl_multigrid.point import point_solver
from ehl_multigrid.point.fas import POINT_POLICY, PointHierarchy, point_settings
from ehl_multigrid.point.problem import problem_from_moes

if "ct" not in nm.relax_sweep.py_func.__code__.co_varnames:
    raise SystemExit("point_prototype.py needs point_squeeze.diff applied to ehl_multigrid/point "
                     "(without it the squeeze term would be silently missing)")


class TransientPointHierarchy(PointHierarchy):
    """The point hierarchy with the geometry ``R(X - c T, Y)`` in the film and the squeeze
    term (``ct`` on every grid, history ``-hist`` as the finest grid's ``f``)."""

    name = "transient point"

    def __init__(self, problem, options, geometry):
        super().__init__(problem, options)
        self.geometry = geometry
        for lev in self.levels:
            lev.R = np.zeros_like(lev.P)

    def update_film(self, lev):
        self.threads.for_size(lev.npts)
        lev.W = lev.defo(lev.P, out=lev.W)
        lev.W -= lev.R / self.cd  # H = H00 + X^2/2 + theta Y^2/2 + cd W - R
        nm.film(lev.W, lev.X, lev.Y, self.H00, self.theta, self.cd, lev.H)
        nm.fluid_properties(lev.P, lev.H, self.par, self.lam, lev.rho, lev.eps)

    def set_step(self, shift, ct, hist):
        for lev in self.levels:
            lev.R = np.ascontiguousarray(self.geometry(lev.X[None, :] - shift, lev.Y[:, None]))
        self.ct = ct
        fine = self.levels[-1]
        fine.f = np.ascontiguousarray(-hist)
        fine.g = self.g_target
        self.update_film(fine)

    def start(self, solver):
        self.solver = solver
        self.gain = solver.settings.h00_gain
        return len(self.levels) - 1


def run(n, A, W, x0, dt, steps, S=0.0):
    pb = problem_from_moes(20, 10)
    opts = PointOptions.build(None, points=n, tol=1e-5, tol_load=1e-6, raise_on_failure=False,
                              max_cycles=40)
    steady = point_solver(pb, opts)
    steady.solve()
    sh = steady.hierarchy

    def geom(X, Y):
        r = np.sqrt((X - x0) ** 2 + Y**2)
        return A * 10.0 ** (-10.0 * (r / W) ** 2) * np.cos(2 * math.pi * r / W)

    hz = TransientPointHierarchy(pb, opts, geom)
    fine = hz.levels[-1]
    fine.P, hz.H00 = sh.levels[-1].P.copy(), sh.H00
    c = 1 + S / 2

    def step(ct, hist, shift):
        hz.set_step(shift, ct, hist)
        return MultilevelSolver(hz, opts, point_settings(pb, opts),
                                RobustnessPolicy(POINT_POLICY, opts.adapt)).solve()

    step(0.0, np.zeros_like(fine.P), 0.0)
    q_prev, q_now = None, fine.rho * fine.H
    out = []
    t0 = time.time()
    for k in range(1, steps + 1):
        ct, hist = (1 / dt, q_now / dt) if k == 1 else (1.5 / dt, (2 * q_now - 0.5 * q_prev) / dt)
        r = step(ct, hist, c * k * dt)
        if r.status != 0:
            print("step", k, r.status, r.message)
            break
        q_prev, q_now = q_now, fine.rho * fine.H
        out.append((k * dt, hz.central_film(fine), float(fine.H.min()), len(r.residual_history),
                    float(fine.P.max())))
    return out, time.time() - t0


if __name__ == "__main__":
    n = int(sys.argv[1])
    S = float(sys.argv[2]) if len(sys.argv) > 2 else 0.0
    afac = float(sys.argv[3]) if len(sys.argv) > 3 else -0.5
    hx = 6.0 / (n - 1)
    r0 = point_solver(problem_from_moes(20, 10), PointOptions.build(None, points=n, raise_on_failure=False)).solve()
    Hc0 = float(r0.history[-1].Hc)
    c = 1 + S / 2
    out, wall = run(n, afac * Hc0, 0.5, -2.0, hx / max(c, 1.0), int(3.0 / hx * max(c, 1.0) / c), S)
    arr = np.array(out)
    print("steps", len(out), "s/step", wall / max(len(out), 1), "cycles/step", arr[:, 3].mean(), arr[:, 3].max())
    print("Hc/Hc0 min max", arr[:, 1].min() / Hc0, arr[:, 1].max() / Hc0, "Hmin/Hc0", arr[:, 2].min() / Hc0,
          "Pmax", arr[:, 4].max())
