"""Grid hierarchies of one implicit time step of the line and the point contact, for the
shared multilevel driver (:class:`~ehl_multigrid.multigrid.driver.MultilevelSolver`).

Each is the contact's steady hierarchy (line: :class:`~ehl_multigrid.line.solver.LineHierarchy`,
its collective line relaxation, transfers, Brandt-Cryer freezing and film-constant handling;
point: :class:`~ehl_multigrid.point.fas.PointHierarchy`, zebra line relaxation, transfers, H00 on
the coarsest grid) with two changes to the discrete operator on every grid, and the start on
the finest grid (no FMG: :class:`StepGrids`):

* the film holds the moving surface geometry ``-R(X - c T)`` (point ``-R(X - c T, Y)``) at the
  new time level, evaluated on each grid's own nodes (so the coarse grids see the feature where
  it is; the point contact's enters the film kernel as an extra deformation ``-R/cd``, so every
  film evaluation of the core carries it);
* the Reynolds equation holds the squeeze term ``d(rho H)/dT = c_t rho H - s`` of the BDF1/BDF2
  step (discrete.py). The history part ``s`` is a constant of the step: on the line it cancels
  in the FAS coarse-grid equations, so only the finest grid carries it, with ``c_t`` the same
  on all grids; on the point the core's squeeze coefficient :attr:`PointHierarchy.ct` carries
  ``c_t`` and the finest grid's right-hand side is ``f = -s``, which the FAS coarse-grid
  equations inherit through the residual.

The grids' additions are :class:`TimeStepGrids` (line) and :class:`PointTimeStepGrids` (point),
mixed into the steady hierarchies here and into the starved (mass-conserving) ones in
:mod:`.cavitated`. The load (line ``h sum P = pi/2``, point
``int int P = 2 pi b/(3a)``) holds at every step (constant load); the film constant is free.
The projection's coarsest grid is solved by the steady path's dense Newton iteration with the
squeeze term added to its residual and Jacobian (:meth:`TransientLineLevel.newton_system`); the
mass-conserving line steps (:mod:`.cavitated`) solve theirs, with a flooded inlet, by the
starved solver's dense Newton iteration, whose rows carry the squeeze term. Either is relaxed
(with the film-constant update) where its Newton iteration fails, and so is a starved inlet's.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..line.discrete import (
    distribute_changes,
    fluid_state,
    line_relaxation_system,
    reynolds_residual,
)
from ..line.level import LineLevel, State, solve_band
from ..line.newton import reynolds_jacobian
from ..line.problem import LineProblem
from ..line.solver import LineHierarchy
from ..multigrid.driver import MultilevelSolver
from ..multigrid.options import LineOptions, PointOptions
from ..multigrid.policy import Settings
from ..point import numerics as nm
from ..point.fas import Level, PointHierarchy
from ..point.problem import PointProblem
from .discrete import add_squeeze_band, squeeze_jacobian

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
        self.coarse = False
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

    def newton_system(self, P: np.ndarray, H0: float, jacobian: bool
                      ) -> tuple[np.ndarray, np.ndarray | None]:
        """The residual of ``(P, H0)`` and, with ``jacobian``, its negated derivative ``dL``
        (rows ``1 .. n-2``, columns ``P_1 .. P_{n-2}, H0``) for the dense coarse Newton
        iteration (``line.newton``): the steady system with the step's geometry in the film,
        the squeeze term ``ct rho H - hist`` in the residual and ``ct d(rho H)/dx`` in ``dL``."""
        with np.errstate(all="ignore"):  # a trial step's overflow: the line search halves it
            W = self.deform(P) + math.pi * self.R
            H, rho, drho, lne, dlne, eps = fluid_state(P, W, self.X, H0, self.par, self.lam, True)
            r, _ = reynolds_residual(P, H, rho, eps, self.h, self.f + self.ct * rho * H - self.hist,
                                     self.order, self.face)
        if not jacobian:
            return r, None
        dL = reynolds_jacobian(P, H, rho, drho, dlne, eps, self.kernel, self.h, self.order, True,
                               self.face)
        if self.ct != 0.0:
            dL -= self.ct * squeeze_jacobian(H, rho, drho, self.kernel)
        return r, dL

    def relax(self, switch: float, omega: float, omega_jd: float, band: int = 4,
              st: State | None = None, switch_h: float = 0.0, switch_eps: float = 0.0) -> State:
        """One collective line-relaxation sweep (the steady system plus the squeeze term's
        Jacobian) at fixed H0; returns the state before the sweep. (``switch_eps``: the
        steady solver's film-scale switch; a time step's hierarchy keeps it 0.)"""
        st = self.state() if st is None else st
        ab, rhs, jac = line_relaxation_system(
            self.P, st.H, st.rho, st.drho, st.eps, st.r, self.kernel, self.h, self.order,
            True, squeeze_switch(switch, self.ct, self.h) if self.coarse else switch, band, self.frozen,
            switch_h, False, switch_eps, self.face)
        if self.ct != 0.0:
            add_squeeze_band(ab, self.P, st.H, st.rho, st.drho, st.r, self.kernel, self.ct, band,
                             jac, self.frozen, True)
        delta = solve_band(ab, rhs, band)
        self.P = distribute_changes(self.P, delta, jac, omega, omega_jd, np.ones(self.n), self.frozen)
        return st


#: the largest factor of :func:`squeeze_switch` (4097 points at dT = 0.0025: 11.2 cycles a step
#: on average with 8, 13.6 with 4, 11.4 uncapped)
SQUEEZE_SWITCH_CAP = 8.0


def squeeze_switch(switch: float, ct: float, h: float) -> float:
    """The relaxation's switch ``eps/h^2 < threshold`` (Gauss-Seidel above it, Jacobi-
    distributive below) on the coarse grids of a time step: the threshold scaled by
    ``max(1, ct h)``, at most :data:`SQUEEZE_SWITCH_CAP` times.

    The squeeze term ``ct rho H`` couples a point to every other through the film's elastic
    integral, as the wedge term ``d(rho H)/dX ~ rho H/h`` does, but with ``ct`` in place of
    ``1/h``. Where ``ct h > 1`` (steps shorter than a mesh size of the grid) it dominates the
    band that a Gauss-Seidel line takes, and on the coarse grids, which must reduce the smooth
    errors themselves, a switch made for the wedge term alone left Gauss-Seidel points whose
    dense coupling diverged: page 63 at 500 N with a 3 nm dent, 513 points, failed at dT =
    0.00586 (step 80, T = 0.47) and 0.00293 (step 2), 4097 points at dT = 0.0025 (step 2), each
    "diverged on grid" 3 or 6; scaled there, they complete in 2.2-2.9 cycles a step on 513
    points (docs/transient.md). The finest grid keeps the plain switch (its relaxation only
    smooths): scaled there too, the sub-steps of an adaptive run on 129 points (page 63 at
    2000 N, a 20 nm dent, ``ct h`` up to 70) took 24 cycles a step instead of 1-2.
    """
    return switch * min(SQUEEZE_SWITCH_CAP, max(1.0, ct * h))


class StepGrids:
    """What a time step's hierarchy of either contact adds to a steady one (mixed in before
    it): the finest grid :attr:`fine`, where the driver starts (no FMG: :meth:`start`)."""

    grid_stop = False  # a time step converges on its residual (no FMG grids to estimate from)
    levels: list[Any]

    @property
    def fine(self) -> Any:
        return self.levels[-1]

    def start(self, solver: MultilevelSolver) -> int:
        self.solver = solver
        return len(self.levels) - 1


class TimeStepGrids(StepGrids):
    """What a time step's hierarchy adds to a steady line hierarchy (mixed in before it):
    the moving geometry and the squeeze term on every grid (:meth:`set_step`), the start on
    the finest grid (no FMG), the coarsest grid relaxed (both line hierarchies solve it by
    Newton instead, relaxed where that fails), no dense-Newton last resort (the mass-conserving
    hierarchy has its own, :mod:`.cavitated`). The grids' levels carry ``R``, ``ct`` and
    ``hist``."""

    geometry: Callable[[np.ndarray], np.ndarray]

    def set_step(self, shift: float, ct: float, hist: np.ndarray) -> None:
        """Geometry displaced by ``shift`` (``R(X - shift)``) on every grid, squeeze
        coefficient ``ct`` on every grid, history ``hist`` on the finest grid."""
        for lv in self.levels:
            lv.R = np.asarray(self.geometry(lv.X - shift), dtype=float)
            lv.ct = float(ct)
            lv.hist = np.zeros(lv.n)
            lv.coarse = lv is not self.fine
        self.fine.hist = np.asarray(hist, dtype=float).copy()
        self.fine.f = np.zeros(self.fine.n)
        self.fine.g = 0.5 * math.pi
        self.fine.frozen[:] = False
        # a step's solve depends on its inputs only (a run continued from a checkpoint repeats
        # the uninterrupted one): no coarse Newton failure carried from the last step
        self.newton_failed = set()

    def coarse_solve(self, k: int, s: Settings) -> float:
        return self.relax(k, COARSE_SWEEPS, s, True)

    def last_resort(self, k: int, solver: MultilevelSolver) -> bool:
        # a failed step is halved by the time loop (stepping._advance) instead of finished by a
        # dense solve of its finest grid
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

    def set_step(self, shift: float, ct: float, hist: np.ndarray) -> None:
        super().set_step(shift, ct, hist)
        self.levels[0].kept_factor = None  # nor a coarse Newton factor of the last step

    def coarse_solve(self, k: int, s: Settings) -> float:
        """The coarsest grid solved for ``(P, H0)`` by the steady solver's dense semismooth
        Newton iteration with the step's squeeze term (:meth:`TransientLineLevel.newton_system`),
        relaxed by :data:`COARSE_SWEEPS` sweeps where it fails. Relaxed alone, with ``H0``
        moved by the load error after every sweep, it diverged on a long box at short steps
        (docs/transient.md, "Limits")."""
        return LineHierarchy.coarse_solve(self, k, s)


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
