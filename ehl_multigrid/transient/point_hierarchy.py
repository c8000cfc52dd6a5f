"""Grid hierarchy of one implicit time step of the point contact, for the shared multilevel
driver.

It is the steady point hierarchy (:class:`~ehl_multigrid.point.fas.PointHierarchy`: zebra
line relaxation, transfers, H00 on the coarsest grid) with two changes on every grid:

* the film holds the moving surface geometry ``-R(X - c T, Y)`` at the new time level,
  evaluated on each grid's own nodes (it enters the film kernel as an extra deformation
  ``-R/cd``, so every film evaluation of the core carries it);
* the Reynolds operator holds the new-time part ``ct rho H`` of the BDF squeeze term through
  the core's squeeze coefficient :attr:`PointHierarchy.ct`; the history part ``s`` of
  ``d(rho H)/dT = ct rho H - s`` is a constant of the step: the finest grid's right-hand
  side is ``f = -s`` and the FAS coarse-grid equations inherit it through the residual.

Both are :class:`PointTimeStepGrids`, mixed into the steady hierarchy here and into the
starved (mass-conserving) one in :mod:`.point_cavitated`.

The load ``int int P = 2 pi b/(3a)`` holds at every step (constant load; H00 free).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..multigrid.driver import MultilevelSolver
from ..multigrid.options import PointOptions
from ..point import numerics as nm
from ..point.fas import Level, PointHierarchy
from ..point.problem import PointProblem
from .stepping import StepGrids


class PointTimeStepGrids(StepGrids):
    """What a time step's hierarchy adds to a steady point hierarchy (mixed in before it):
    the moving geometry ``R`` on every grid and the squeeze term (:meth:`set_step`), the start
    on the finest grid (no FMG). Call :meth:`_init_step_grids` after the steady hierarchy's
    ``__init__``."""

    local_update = False  # its time steps were measured with the full refresh after every sweep
    geometry: Callable[[np.ndarray, np.ndarray], np.ndarray]
    levels: list[Level]

    def _init_step_grids(self, geometry: Callable[[np.ndarray, np.ndarray], np.ndarray]) -> None:
        self.geometry = geometry
        for lev in self.levels:
            lev.R = np.zeros_like(lev.P)
            lev.W = np.zeros_like(lev.P)  # its film subtracts the surface from W on every grid
        self.hist = np.zeros_like(self.fine.P)

    def update_film(self, lev: Level) -> None:
        self.threads.for_size(lev.npts)
        lev.W = lev.defo(lev.P, out=lev.W)
        lev.W -= lev.R / self.cd  # H = H00 + X^2/2 + theta Y^2/2 + cd W - R
        nm.film(lev.W, lev.X, lev.Y, self.H00, self.theta, self.cd, lev.H)
        nm.fluid_properties(lev.P, lev.H, self.par, self.lam, lev.rho, lev.eps)

    def set_step(self, shift: float, ct: float, hist: np.ndarray) -> None:
        """Geometry displaced by ``shift`` along X on every grid, squeeze coefficient ``ct``,
        history ``hist`` (the finest grid's ``f = -hist``)."""
        for lev in self.levels:
            lev.R = np.ascontiguousarray(self.geometry(lev.X[None, :] - shift, lev.Y[:, None]),
                                         dtype=float)
        self.ct = float(ct)
        self.hist = np.ascontiguousarray(hist, dtype=float).copy()
        fine = self.fine
        fine.f = -self.hist
        fine.g = self.g_target
        self._last_err = None
        self.update_film(fine)

    def squeeze(self) -> np.ndarray:
        """``d(rho H)/dT`` on the finest grid (the BDF difference)."""
        fine = self.fine
        return self.ct * fine.rho * fine.H - self.hist

    def start(self, solver: MultilevelSolver) -> int:
        self.gain = solver.settings.h00_gain
        return super().start(solver)


class TransientPointHierarchy(PointTimeStepGrids, PointHierarchy):
    """Grids of one time step, coarsest first (driver protocol). The finest grid holds the
    start iterate when the driver starts (:meth:`start` returns the finest level: no FMG)."""

    name = "transient point"
    far_field_ok = False  # a time step on the core's box, as measured (docs/transient.md)

    def __init__(self, problem: PointProblem, options: PointOptions,
                 geometry: Callable[[np.ndarray, np.ndarray], np.ndarray]) -> None:
        if not options.elastic or problem.cd == 0.0:
            raise ValueError("the transient point hierarchy needs elastic surfaces")
        super().__init__(problem, options)
        self._init_step_grids(geometry)
