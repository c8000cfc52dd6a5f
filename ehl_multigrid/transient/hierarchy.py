"""Grid hierarchy of one implicit time step of the line contact, for the shared multilevel
driver (:class:`~ehl_multigrid.multigrid.driver.MultilevelSolver`).

It is the steady line hierarchy (:class:`~ehl_multigrid.line.solver.LineHierarchy`: its
collective line relaxation, transfers, Brandt-Cryer freezing and film-constant handling)
with two changes to the discrete operator on every grid:

* the film holds the moving surface geometry ``-R(X - c T)`` at the new time level, evaluated
  on each grid's own nodes (so the coarse grids see the feature where it is);
* the Reynolds equation holds the squeeze term ``d(rho H)/dT`` of the BDF1/BDF2 step
  (discrete.py). The history part ``s`` is a constant of the step and cancels in the FAS
  coarse-grid equations, so only the finest grid carries it; ``c_t`` is the same on all grids.

The load balance ``h sum P = pi/2`` holds at every step (constant load); ``H0`` is free. The
coarsest grid is relaxed (with the film-constant update) instead of the steady path's dense
Newton, whose Jacobian has no squeeze term.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ..line.discrete import (
    distribute_changes,
    fluid_state,
    line_relaxation_system,
    reynolds_residual,
)
from ..line.level import LineLevel, State, solve_band
from ..line.problem import LineProblem
from ..line.solver import LineHierarchy
from ..multigrid.driver import MultilevelSolver
from ..multigrid.options import LineOptions
from ..multigrid.policy import Settings
from .discrete import add_squeeze_band
from .stepping import StepGrids

#: relaxation sweeps of one coarsest-grid visit
COARSE_SWEEPS = 20


class TransientLineLevel(LineLevel):
    """One grid of a time step: :class:`LineLevel` plus the geometry ``R`` at the new time,
    the squeeze coefficient ``ct`` and the history ``hist`` (``d(rho H)/dT = ct rho H - hist``).
    """

    def __post_init__(self) -> None:
        super().__post_init__()
        self.R = np.zeros(self.n)
        self.ct = 0.0
        self.hist = np.zeros(self.n)

    def state(self, P: np.ndarray | None = None, H0: float | None = None) -> State:
        P = self.P if P is None else P
        H0 = self.H0 if H0 is None else H0
        # the surface geometry enters as an extra "deformation" pi R: H = H0 + X^2/2 - R - W/pi
        W = self.deform(P) + math.pi * self.R
        H, rho, drho, lne, dlne, eps = fluid_state(P, W, self.X, H0, self.par, self.lam, True)
        squeeze = self.ct * rho * H - self.hist
        r, scale = reynolds_residual(P, H, rho, eps, self.h, self.f + squeeze, self.order, self.face)
        scale += float(np.sum(np.abs(squeeze[1:-1])))
        return State(H, rho, drho, lne, dlne, eps, r, scale)

    def squeeze(self, st: State) -> np.ndarray:
        """``d(rho H)/dT`` of the state (the BDF difference)."""
        return self.ct * st.rho * st.H - self.hist

    def relax(self, switch: float, omega: float, omega_jd: float, band: int = 4,
              st: State | None = None, switch_h: float = 0.0, switch_eps: float = 0.0) -> State:
        """One collective line-relaxation sweep (the steady system plus the squeeze term's
        Jacobian) at fixed H0; returns the state before the sweep. (``switch_eps``: the
        steady solver's film-scale switch; a time step's hierarchy keeps it 0.)"""
        st = self.state() if st is None else st
        ab, rhs, jac = line_relaxation_system(
            self.P, st.H, st.rho, st.drho, st.eps, st.r, self.kernel, self.h, self.order,
            True, switch, band, self.frozen, switch_h, False, switch_eps, self.face)
        if self.ct != 0.0:
            add_squeeze_band(ab, self.P, st.H, st.rho, st.drho, st.r, self.kernel, self.ct, band,
                             jac, self.frozen, True)
        delta = solve_band(ab, rhs, band)
        self.P = distribute_changes(self.P, delta, jac, omega, omega_jd, np.ones(self.n), self.frozen)
        return st


class TimeStepGrids(StepGrids):
    """What a time step's hierarchy adds to a steady line hierarchy (mixed in before it):
    the moving geometry and the squeeze term on every grid (:meth:`set_step`), the start on
    the finest grid (no FMG), the coarsest grid relaxed, no dense-Newton last resort. The
    grids' levels carry ``R``, ``ct`` and ``hist``."""

    geometry: Callable[[np.ndarray], np.ndarray]

    def set_step(self, shift: float, ct: float, hist: np.ndarray) -> None:
        """Geometry displaced by ``shift`` (``R(X - shift)``) on every grid, squeeze
        coefficient ``ct`` on every grid, history ``hist`` on the finest grid."""
        for lv in self.levels:
            lv.R = np.asarray(self.geometry(lv.X - shift), dtype=float)
            lv.ct = float(ct)
            lv.hist = np.zeros(lv.n)
        self.fine.hist = np.asarray(hist, dtype=float).copy()
        self.fine.f = np.zeros(self.fine.n)
        self.fine.g = 0.5 * math.pi
        self.fine.frozen[:] = False

    def coarse_solve(self, k: int, s: Settings) -> float:
        return self.relax(k, COARSE_SWEEPS, s, True)

    def last_resort(self, k: int, solver: MultilevelSolver) -> bool:
        # the dense Newton finish of the steady path has no squeeze term
        return False


class TransientLineHierarchy(TimeStepGrids, LineHierarchy):
    """Grids of one time step, coarsest first (driver protocol). The finest grid holds the
    start iterate when the driver starts (:meth:`start` returns the finest level: no FMG)."""

    name = "transient line"
    level_type = TransientLineLevel

    def __init__(self, problem: LineProblem, options: LineOptions,
                 geometry: Callable[[np.ndarray], np.ndarray]) -> None:
        super().__init__(problem, options)
        self.geometry = geometry
