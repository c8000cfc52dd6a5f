"""A toy grid hierarchy for the multilevel driver: 1-D Poisson ``-u'' = f`` on (0, 1) with
``u(0) = u(1) = 0`` and the known solution ``u = sin(pi x)`` (``f = pi^2 sin(pi x)``).

Second-order differences, weighted Jacobi smoothing (weight 2/3 -- textbook smoothing factor
1/3), FAS restriction by injection and full weighting, linear correction, cubic FMG
interpolation and an exact tridiagonal solve on the coarsest grid. Switches let a test make
the relaxation unstable (``unstable_above``: weight 1.5 while ``omega`` exceeds it) or remove
the coarse-grid correction (``no_correction``: smoothing only, so the solve stalls).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.linalg

from ehl_multigrid.multigrid import (
    Measurement,
    MultigridOptions,
    MultilevelSolver,
    PolicyParameters,
    RobustnessPolicy,
    Settings,
)
from ehl_multigrid.multigrid.transfer import (
    full_weighting,
    inject,
    interpolate_cubic,
    interpolate_linear,
)


class ToyLevel:
    def __init__(self, n: int) -> None:
        self.n = n
        self.h = 1.0 / (n - 1)
        self.x = np.linspace(0.0, 1.0, n)
        self.u = np.zeros(n)
        self.f = math.pi**2 * np.sin(math.pi * self.x)

    shape = property(lambda self: (self.n,))
    spacing = property(lambda self: (self.h,))
    npts = property(lambda self: self.n)

    def apply(self, u: np.ndarray) -> np.ndarray:
        out = np.zeros_like(u)
        out[1:-1] = (2.0 * u[1:-1] - u[:-2] - u[2:]) / self.h**2
        return out

    def residual(self) -> np.ndarray:
        r = self.f - self.apply(self.u)
        r[0] = r[-1] = 0.0
        return r


class PoissonHierarchy:
    name = "poisson"

    def __init__(self, points: int, levels: int, unstable_above: float = math.inf,
                 no_correction: bool = False) -> None:
        self.levels = [ToyLevel((points - 1) // 2 ** (levels - 1 - k) + 1) for k in range(levels)]
        self.unstable_above = unstable_above
        self.no_correction = no_correction
        self.switch_raised = False

    def work(self, k: int) -> float:
        return (self.levels[k].n - 1) / (self.levels[-1].n - 1)

    def start(self, solver) -> int:
        self.coarse_solve(0, solver.settings)
        return 0

    def relax(self, k, sweeps, s: Settings, coarse: bool, post: bool = False) -> float:
        lv = self.levels[k]
        w = 1.5 if s.omega > self.unstable_above else 2.0 / 3.0
        for _ in range(sweeps):
            lv.u[1:-1] += w * lv.residual()[1:-1] * lv.h**2 / 2.0
        return sweeps * self.work(k)

    def restrict(self, k, s):
        lv, cv = self.levels[k], self.levels[k - 1]
        r = lv.residual()
        cv.u = inject(lv.u)
        cv.f = cv.apply(cv.u) + full_weighting(r)
        return cv.u.copy(), None

    def correct(self, k, token, s) -> None:
        if not self.no_correction:
            self.levels[k].u += interpolate_linear(self.levels[k - 1].u - token)

    def coarse_solve(self, k, s) -> float:
        lv = self.levels[k]
        m = lv.n - 2
        ab = np.zeros((3, m))
        ab[0, 1:] = ab[2, :-1] = -1.0 / lv.h**2
        ab[1] = 2.0 / lv.h**2
        lv.u[1:-1] = scipy.linalg.solve_banded((1, 1), ab, lv.f[1:-1])
        return 0.0

    def fmg_interpolate(self, k, s) -> float:
        self.levels[k].u = interpolate_cubic(self.levels[k - 1].u)
        return 0.0

    def snapshot(self, k):
        return [lv.u.copy() for lv in self.levels[: k + 1]]

    def restore(self, k, saved) -> None:
        for lv, u in zip(self.levels, saved, strict=False):
            lv.u = u.copy()

    def measure(self, k) -> Measurement:
        lv = self.levels[k]
        res = float(np.linalg.norm(lv.residual()) / np.linalg.norm(lv.f))
        ok = bool(np.all(np.isfinite(lv.u)))
        return Measurement(res, 0.0, float(lv.u[(lv.n - 1) // 2]), ok)

    def raise_switch(self, s) -> str:
        if self.switch_raised:
            return ""
        self.switch_raised = True
        return "switch raised"

    def error(self) -> float:
        lv = self.levels[-1]
        return float(np.max(np.abs(lv.u - np.sin(math.pi * lv.x))))


def toy_solver(points: int = 129, levels: int = 5, params: PolicyParameters | None = None,
               hierarchy: PoissonHierarchy | None = None, **kw) -> MultilevelSolver:
    opts = MultigridOptions.build(points=points, levels=levels, **kw)
    hz = hierarchy or PoissonHierarchy(points, levels)
    settings = Settings.start(opts, 0.0, 0.0)
    return MultilevelSolver(hz, opts, settings, RobustnessPolicy(params or PolicyParameters(), opts.adapt),
                            hint="toy")
