"""The line contact's multilevel hierarchy with the generalised Reynolds operator of a film
whose viscosity and density vary across it (Yang & Wen 1990), for the shared FAS driver, and
what it shares with the point contact's (:class:`thermal.tehl.point.FactorPointHierarchy`):
the factors injected on the coarse grids and the start from a given iterate.

The discrete equations are the core line contact's (:mod:`ehl_multigrid.line.discrete`),
with two fields along X taken as given (frozen during a multilevel solve, updated by the
thermal solve of the outer iteration, :mod:`thermal.tehl.line`):

* the flow factor ``a``: Venner's ``eps = rho H^3/(eta lambda)`` becomes ``a eps``;
* the Couette factor ``c``: the wedge term ``d(rho H)/dX`` becomes ``d(c rho H)/dX``.

With ``a = c = 1`` every state, residual and relaxation system is the core's, bit for bit.
Coarse grids take the fine factors at their nodes (injection, like ``P``). The coarsest grid
is solved by the core's dense Newton, which scales ``eps``, ``rho`` and ``drho/dP`` by the
level's factors (the Jacobian follows); a multilevel solve starts on the finest grid from the
previous outer iterate, so FMG and its dense start are not needed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ehl_multigrid.line.discrete import fluid_state, reynolds_residual
from ehl_multigrid.line.level import LineLevel, State
from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.line.solver import LineHierarchy, line_levels
from ehl_multigrid.multigrid.driver import MultilevelSolver
from ehl_multigrid.multigrid.options import LineOptions

#: coarsest grid of the outer iteration's multilevel solves (points; the core's default
#: goes down to 65-129): from the converged iterate the cycles on 4097 points stalled
#: and diverged with 7 grids, not with 5 (docs/thermal.md, "Coupled thermal EHL film")
COARSEST_POINTS = 257


@dataclass
class FactorLevel(LineLevel):
    """A :class:`LineLevel` whose Reynolds coefficients carry the flow and Couette factors."""

    a: np.ndarray = field(init=False)
    c: np.ndarray = field(init=False)

    def __post_init__(self) -> None:
        super().__post_init__()
        self.a = np.ones(self.n)
        self.c = np.ones(self.n)

    def factored(self, eps: np.ndarray, rho: np.ndarray, drho: np.ndarray, lne: np.ndarray,
                 dlne: np.ndarray, part: slice = slice(None)
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """``eps``, ``rho``, ``drho/dP`` and ``d ln eta/dP`` of the generalised Reynolds
        equation: the wedge carries ``c rho H``, the Poiseuille term ``a eps`` (factors frozen
        within a solve: Picard; a line contact takes no viscosity response, docs/thermal.md).
        ``lne`` is unused (the point contact's rule takes it). ``part``: the nodes the arrays hold."""
        c = self.c[part]
        return eps * self.a[part], rho * c, drho * c, dlne

    def state(self, P: np.ndarray | None = None, H0: float | None = None) -> State:
        P = self.P if P is None else P
        H0 = self.H0 if H0 is None else H0
        W = self.deform(P)
        H, rho, drho, lne, dlne, eps = fluid_state(P, W, self.X, H0, self.par, self.lam, self.elastic)
        eps, rho, drho, dlne = self.factored(eps, rho, drho, lne, dlne)
        r, scale = reynolds_residual(P, H, rho, eps, self.h, self.f, self.order, self.face)
        return State(H, rho, drho, lne, dlne, eps, r, scale)


class GivenStart:
    """Flow and Couette factors of a hierarchy (frozen during a solve) and the finest-grid
    iterate it starts from, for a line or a point hierarchy."""

    levels: list[Any]
    _start: tuple[np.ndarray, float] | None = None

    def set_factors(self, a: np.ndarray, c: np.ndarray) -> None:
        """Flow and Couette factors on the finest grid; coarse grids inject them."""
        shape = self.levels[-1].shape
        if a.shape != shape or c.shape != shape:
            raise ValueError(f"factors must have the finest grid's shape {shape}")
        for k, lv in enumerate(self.levels):
            every = (slice(None, None, 2 ** (len(self.levels) - 1 - k)),) * a.ndim
            lv.a = np.ascontiguousarray(a[every], dtype=float)
            lv.c = np.ascontiguousarray(c[every], dtype=float)

    def set_iterate(self, P: np.ndarray, H0: float) -> None:
        """The finest-grid pressure and film constant a solve starts from."""
        self._start = (np.asarray(P, dtype=float).copy(), float(H0))

    def given_start(self) -> tuple[np.ndarray, float]:
        if self._start is None:
            raise ValueError("set_iterate() before a solve: the hierarchy starts from a given iterate")
        return self._start


class FactorLineHierarchy(GivenStart, LineHierarchy):
    """:class:`~ehl_multigrid.line.solver.LineHierarchy` on :class:`FactorLevel` grids,
    started on the finest grid from a given iterate."""

    name = "line (generalised Reynolds)"
    grid_stop = False  # started on the finest grid: no FMG grids to estimate from

    def __init__(self, problem: LineProblem, options: LineOptions) -> None:
        super().__init__(problem, options)
        par = problem.rheology()
        nlev = line_levels(options, problem.M)
        if options.levels is None:
            nlev = min(nlev, max(1, round(math.log2((options.points - 1) / (COARSEST_POINTS - 1))) + 1))
        n_f = options.points
        self.levels = [
            FactorLevel((n_f - 1) // 2 ** (nlev - 1 - k) + 1, problem.xmin, problem.xmax, par,
                        problem.lam, problem.elastic, options.deformation, options.wedge_order,
                        options.mlmi_order, options.mlmi_radius)
            for k in range(nlev)
        ]
        for lv in self.levels:
            lv.face = self.face

    def start(self, solver: MultilevelSolver) -> int:
        self.solver = solver
        P, H0 = self.given_start()
        top = len(self.levels) - 1
        lv = self.levels[top]
        lv.P = P.copy()
        lv.H0 = H0
        lv.f = np.zeros(lv.n)
        lv.g = 0.5 * np.pi
        lv.frozen[:] = False
        return top

