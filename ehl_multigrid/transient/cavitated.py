"""One time step of the line or the point contact with mass-conserving (Elrod-Adams)
cavitation.

The transient Reynolds equation (Venner & Lubrecht 2000, ch. 12 and 13; the film and load
equations of thesis (2.2)-(2.3)) with the film content ``theta`` of the starved solvers (Elrod
& Adams 1974; thesis section 6.2 for the starved steady contact):

``d/dX(eps dP/dX) [+ d/dY(eps dP/dY)] - d(theta rho H)/dX - d(theta rho H)/dT = 0``,
``P (1 - theta) = 0``, ``P >= 0``, ``0 <= theta <= 1``.

Where the film ruptures behind the contact or behind a dent, the oil the surfaces carry is
``theta rho H``; it is conserved as it is carried on and refills the gap downstream
(reformation), unlike the projection ``P >= 0`` of :class:`~.hierarchy.TransientLineHierarchy`
and :class:`~.hierarchy.TransientPointHierarchy`, which creates and destroys oil at the
cavitation boundary. The discrete equations are in conservation form on every node, so the
net flux into the whole domain equals the change of the oil it holds, to the residual
(:func:`domain_mass_error`, :func:`point_domain_mass_error`).

Line (:class:`CavitatedStepHierarchy`): the grids, relaxation (collective line relaxation in
the universal variable, the regimes by an active-set re-solve), transfers and inlet rule are
the starved solver's (:class:`~ehl_multigrid.starved.line.StarvedLineHierarchy`); a time step
adds the moving geometry and the squeeze term ``c_t theta rho H - s`` (BDF, discrete.py) as
:class:`~.hierarchy.TimeStepGrids` does for the projection. Its coarsest grid is solved by the
starved solver's dense semismooth Newton iteration in ``(P, theta, H0)``, whose rows carry the
squeeze term, with a flooded inlet (:meth:`CavitatedStepHierarchy.coarse_solve`).

Point (:class:`CavitatedPointStepHierarchy`): the grids, relaxation (zebra X-line relaxation
on P with the density ``theta rho``, then the ``theta`` march through the unpressurised
points), transfers, wedge discretisation and inlet rule are the starved point solver's
(:class:`~ehl_multigrid.starved.point.StarvedPointHierarchy`); a time step adds the moving
geometry and the squeeze term as :class:`~.hierarchy.PointTimeStepGrids` does for the
projection. The new-time part ``ct theta rho H`` enters the operator, the line relaxation's
Jacobian of the pressurised points (the core kernel's squeeze coefficient) and the ``theta``
march of the unpressurised points (their balance's diagonal ``1 + hx ct``); the history ``s``
is the finest grid's right-hand side ``f = -s``, which the FAS coarse-grid equations inherit.

A finite supplied layer (``hoil``, Venner units ``hoil R/b^2``, point ``hoil Rx/a^2``) starves
the inlet as in the steady starved solvers.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..line.discrete import fluid_state
from ..line.problem import LineProblem
from ..line.solver import NEWTON_AFTER_FAILURE
from ..multigrid.driver import MultilevelSolver
from ..multigrid.options import LineOptions, PointOptions
from ..multigrid.policy import Settings
from ..multigrid.result import EHLResult
from ..point import numerics as nm
from ..point.fas import Y_JD_MODE, Y_OMEGA, Y_OMEGA_JD, Level, sweep_switch
from ..point.problem import PointProblem
from ..starved import point as starved_point
from ..starved.discrete import elrod_adams_residual, face_fluxes
from ..starved.level import StarvedLevel, StarvedState
from ..starved.line import StarvedLineHierarchy
from ..starved.newton import StarvedNewtonFailure, newton_solve
from ..starved.point import COARSE_THETA_MESH, StarvedPointHierarchy
from .discrete import add_content_squeeze
from .hierarchy import PointTimeStepGrids, TimeStepGrids
from .oil_balance import OilBalanceCycles

#: most fine-grid relaxation sweeps that finish a stalled step (:meth:`CavitatedStepHierarchy.last_resort`,
#: :meth:`CavitatedPointStepHierarchy.last_resort`)
FINISH_SWEEPS = 400
#: the point contact's finish measures its residual every this many sweeps
FINISH_CHECK = 10
#: most dense Newton iterations of a line step's coarsest-grid visit (the starved start grid's
#: budget, :meth:`~ehl_multigrid.starved.line.StarvedLineHierarchy.start`)
COARSE_NEWTON_ITERATIONS = 40


@dataclasses.dataclass
class CavitatedStepLevel(StarvedLevel):
    """A starved-solver grid with the surface geometry ``R`` at the new time, the squeeze
    coefficient ``ct`` and the history ``hist`` (``d(theta rho H)/dT = ct theta rho H - hist``)."""

    def __post_init__(self) -> None:
        super().__post_init__()
        self.R = np.zeros(self.n)
        self.ct = 0.0
        self.hist = np.zeros(self.n)

    def state(self, P: np.ndarray | None = None, H0: float | None = None,
              theta: np.ndarray | None = None) -> StarvedState:
        P = self.P if P is None else P
        H0 = self.H0 if H0 is None else H0
        th = (self.theta if theta is None else theta).copy()
        W = self.deform(P) + math.pi * self.R  # H = H0 + X^2/2 - R - W/pi
        H, rho, drho, lne, dlne, eps = fluid_state(P, W, self.X, H0, self.par, self.lam, self.elastic)
        th[0] = self.inlet_theta(H[0])
        q = th * rho * H
        squeeze = self.ct * q - self.hist
        r, scale = elrod_adams_residual(P, H, rho, th, eps, self.h, self.f + squeeze, self.order,
                                        bool(th[0] < 1.0), self.face)
        scale += float(np.sum(np.abs(squeeze[1:-1])))
        return StarvedState(H, rho, drho, lne, dlne, eps, r, scale, th, q)

    def content_rate(self) -> tuple[float, np.ndarray]:
        return self.ct, self.hist

    def squeeze(self, st: StarvedState) -> np.ndarray:
        """``d(theta rho H)/dT`` of the state (the BDF difference)."""
        return self.ct * st.q - self.hist

    def jacobian(self, st: StarvedState, q0_fixed: bool, band: int) -> tuple[np.ndarray, np.ndarray]:
        AP, AT = super().jacobian(st, q0_fixed, band)
        if self.ct != 0.0:
            add_content_squeeze(AP, AT, st.theta, st.H, st.rho, st.drho, self.kernel, self.h,
                                self.ct, self.elastic, band)
        return AP, AT


class CavitatedStepHierarchy(OilBalanceCycles, TimeStepGrids, StarvedLineHierarchy):
    """Grids of one mass-conserving time step (driver protocol): the flooded solver's grids
    (no starved FMG start grid: a step starts on the finest grid from the previous step)."""

    name = "transient line (mass-conserving)"
    level_type = CavitatedStepLevel

    def __init__(self, problem: LineProblem, options: LineOptions,
                 geometry: Callable[[np.ndarray], np.ndarray], steady: EHLResult,
                 hoil: float = math.inf) -> None:
        super().__init__(problem, dataclasses.replace(options, fmg_start_points=options.points),
                         hoil, steady)
        self.geometry = geometry

    def set_hoil(self, hoil: float) -> None:
        """Feed the inlet the layer ``hoil`` (Venner units; ``inf``: flooded) on every grid; a
        layer above the flooded contact's flux floods the inlet."""
        self.hoil = float(hoil)
        self.starved_inlet = bool(self.hoil < self.flux_flooded)
        for lv in self.levels:
            lv.hoil, lv.starved_inlet = self.hoil, self.starved_inlet

    def coarse_solve(self, k: int, s: Settings) -> float:
        """A flooded inlet's coarsest grid solved for ``(P, theta, H0)`` by the starved
        solver's dense semismooth Newton iteration
        (:func:`~ehl_multigrid.starved.newton.newton_solve`), whose rows carry the step's
        squeeze term ``c_t theta rho H - s`` and moving geometry; the frozen points keep their
        values. Where it fails, and with a starved inlet, the grid is relaxed
        (:meth:`~.hierarchy.TimeStepGrids.coarse_solve`); a later visit in the same step tries
        at most :data:`~ehl_multigrid.line.solver.NEWTON_AFTER_FAILURE` iterations.

        A starved inlet keeps the relaxation, as the steady starved solver does (with the
        Newton solve a smooth starved run gained 40 times more oil per step, within its
        tolerance); relaxed alone, the flooded coarsest grid did not converge on a long box at
        short steps (docs/transient.md, "Limits")."""
        lv = self.levels[k]
        if self.starved_inlet:
            return TimeStepGrids.coarse_solve(self, k, s)
        failed_before = k in self.newton_failed
        saved = (lv.P.copy(), lv.theta.copy(), lv.H0)
        try:
            its = newton_solve(lv, max_iter=NEWTON_AFTER_FAILURE if failed_before else COARSE_NEWTON_ITERATIONS)
        except StarvedNewtonFailure as exc:
            lv.P, lv.theta, lv.H0 = saved
            if not failed_before:
                self.solver.note(f"coarse Newton failed on {lv.n} points ({exc}); relaxed instead "
                                 f"(later attempts in this step stop after {NEWTON_AFTER_FAILURE} "
                                 f"iterations)")
            self.newton_failed.add(k)
            return TimeStepGrids.coarse_solve(self, k, s)
        self.newton_iterations += its
        return its * self.work(k)

    def step_mass_error(self) -> float:
        lv = self.fine
        st = lv.state()
        return domain_mass_error(lv.P, st.theta, st.q, st.eps, lv.squeeze(st), lv.h, lv.order, lv.face)

    def last_resort(self, k: int, solver: Any) -> bool:
        """A stalled step (the free boundary in a dent flips between regimes from cycle to
        cycle, so the coarse-grid corrections undo each other): finish it by the starved
        solver's dense semismooth Newton on the finest grid (its rows with the squeeze term)
        where the grid is small enough, else by fine-grid relaxation alone, with the film
        constant following the load, for at most :data:`FINISH_SWEEPS` sweeps."""
        if StarvedLineHierarchy.last_resort(self, k, solver):
            return True
        fin = self.levels[k]
        s = solver.settings
        tol, tol_load = solver.options.tol, solver.options.tol_load
        omega_theta = min(1.0, 2.0 * s.omega)
        for sweep in range(1, FINISH_SWEEPS + 1):
            fin.relax(s.switch, s.omega, s.omega_jd, self.options.band, switch_h=s.switch_h,
                      omega_theta=omega_theta)
            fin.H0 += s.h00_gain * (fin.load() - fin.g)
            if sweep % 10 == 0:
                m = self.measure(k)
                if not m.ok:
                    break
                if m.residual < tol and abs(m.load_error) < tol_load:
                    break
        solver.work_units += sweep * self.work(k)
        solver.note(f"multigrid stalled: {sweep} fine-grid relaxation sweeps")
        solver.record(k, -1, self.measure(k))
        return solver.converged()


def domain_mass_error(P: np.ndarray, theta: np.ndarray, q: np.ndarray, eps: np.ndarray,
                      squeeze: np.ndarray, h: float, order: int, face: int = 0) -> float:
    """Net oil gained by the whole grid in a step, relative to the inflow: ``(h sum_i
    d(theta rho H)_i/dT - (F_in - F_out)) / F_in`` over the interior nodes, with the face
    fluxes of the conservative scheme (:func:`~ehl_multigrid.starved.discrete.face_fluxes`;
    ``q = theta rho H``, ``squeeze`` its BDF difference, a starved inlet when ``theta[0] < 1``).
    It is ``-h sum_i r_i / F_in`` (the finest grid's right-hand side is 0): zero to the
    solve's tolerance."""
    F = face_fluxes(P, theta, q, eps, h, order, bool(theta[0] < 1.0), face)
    storage = h * float(np.sum(squeeze[1:-1]))
    return (storage - (F[0] - F[-1])) / max(abs(F[0]), 1e-300)


class CavitatedPointStepHierarchy(OilBalanceCycles, PointTimeStepGrids, StarvedPointHierarchy):
    """Grids of one mass-conserving time step of the point contact, coarsest first (driver
    protocol): the starved point hierarchy with the moving geometry and the squeeze term.
    The finest grid holds the start iterate (P, H00 and ``theta``) when the driver starts
    (:meth:`start` returns the finest level: no FMG)."""

    name = "transient point (mass-conserving)"
    #: the policy's "alternate" step may add Y-line sweeps (:meth:`_sweep_free`): with X lines
    #: alone the cycles stall while a deep dent crosses the contact (docs/transient.md)
    can_alternate = True

    def __init__(self, problem: PointProblem, options: PointOptions,
                 geometry: Callable[[np.ndarray, np.ndarray], np.ndarray],
                 hoil: float = math.inf) -> None:
        if not options.elastic or problem.cd == 0.0:
            raise ValueError("the transient point hierarchy needs elastic surfaces")
        super().__init__(problem, options, hoil)
        self._init_step_grids(geometry)

    def set_hoil(self, hoil: float) -> None:
        """Feed the inlet the layer ``hoil`` (Venner units; ``inf``: flooded) on every grid
        (the inlet column's ``theta`` follows at the next march)."""
        self.hoil = float(hoil)
        self.hoil_rows = np.full(self.fine.ny, self.hoil)
        for lev in self.levels:
            lev.hoil_rows = np.full(lev.ny, min(self.hoil, 1e300))
        # the coarse grids whose mesh resolves the starved inlet keep theta free
        self.theta_mesh = COARSE_THETA_MESH * math.sqrt(2.0 * min(self.hoil, 1e150))

    def _sweep_free(self, lev: Level, s: Settings, free: bool) -> None:
        """The starved sweep (X lines on P, then the ``theta`` march); on a grid that
        alternates (after the policy's "alternate" step, :meth:`alternate_all`) the X-line
        sweep is followed by a Y-line sweep on P (Venner & Lubrecht 2000: alternating line
        relaxation where the coupling across the X lines is strong), with the unpressurised
        points held at ``P = 0`` and the wedge's defect correction as in the X sweep, at the
        point core's Y-sweep under-relaxations."""
        if not lev.alternate:
            super()._sweep_free(lev, s, free)
            return
        super()._sweep_free(lev, s, False)
        rq = self._q_density(lev)
        dry = lev.theta < 1.0
        order = 1 if lev.order == 1 else starved_point.KERNEL_ORDER
        fr = self._sweep_rhs(lev, rq, dry)
        nm.relax_sweep_y(lev.P, lev.H, rq, lev.eps, fr, lev.D, lev.Ky, lev.hx, lev.hy,
                         self.options.half, sweep_switch(s.switch, lev.hx), s.omega * Y_OMEGA,
                         s.omega_jd * Y_OMEGA_JD, order, Y_JD_MODE, self.ct)
        lev.P[dry] = 0.0
        self.update_film(lev)
        if free:
            self._release(lev)
            self._march(lev)

    def step_mass_error(self) -> float:
        return point_domain_mass_error(self)

    def squeeze(self) -> np.ndarray:
        """``d(theta rho H)/dT`` on the finest grid (the BDF difference)."""
        fine = self.fine
        return self.ct * fine.theta * fine.rho * fine.H - self.hist

    def start(self, solver: MultilevelSolver) -> int:
        """The finest grid (no FMG); the second-order wedge's polishing state starts afresh
        in every step, and the film content of the unpressurised points is marched for the
        step's geometry and history."""
        k = super().start(solver)
        self._top = k
        self._fine_res, self._polish, self._seen = [], 0, 0
        self._march(self.levels[k])
        return k

    def last_resort(self, k: int, solver: MultilevelSolver) -> bool:
        """A stalled or diverged step (the free boundary around a dent flips between the
        regimes from cycle to cycle, and the coarse-grid corrections, which see the dent's
        cavitated points only through the restricted residual, undo the sweeps' progress there):
        finish it by fine-grid relaxation alone at the options' under-relaxations, with H00
        following the load error after every sweep, for at most :data:`FINISH_SWEEPS` sweeps
        (stopped early by a non-finite iterate or a growing residual). The film-constant gain
        halves when the load error changes sign and recovers while it keeps its sign (the
        core's coarsest-grid rule): at a constant gain H00 and the load oscillate with a
        period of some 60 sweeps, the relaxation lagging behind H00 (measured at (100, 10),
        65^2, a dent 6.8 Hc deep at S = 1: residual 1e-3 ... 1e-2 after 400 sweeps). Every
        :data:`FINISH_CHECK` sweeps the Poiseuille-dominated zone (the inlet) is solved exactly
        (:meth:`~ehl_multigrid.starved.point.StarvedPointHierarchy.exact_zone`): relaxation
        alone leaves the smooth part of the inlet's residual, which the scaled residual hardly
        sees and which is oil gained or lost (measured at (20, 10), 65^2: 8e-4 of the inflow
        in one step at a residual of 5e-8; with the zone solve 2e-8)."""
        fin = self.levels[k]
        s = solver.settings
        tol, tol_load = solver.options.tol, solver.options.tol_load
        omega, omega_jd, gain = s.omega, s.omega_jd, s.h00_gain
        s.omega, s.omega_jd, s.h00_gain = s.defaults
        best = self.measure(k).residual
        sweep = 0
        g, last = s.h00_gain, 0.0
        try:
            for sweep in range(1, FINISH_SWEEPS + 1):
                self._sweep_free(fin, s, True)
                err = fin.g - self.load(fin)
                if err * last < 0.0:
                    g = max(0.5 * g, s.h00_gain / 256.0)
                elif abs(err) > 0.5 * abs(last):
                    g = min(1.25 * g, s.h00_gain)
                last = err
                self.H00 -= max(-self.h00_step_max, min(self.h00_step_max, g * err))
                self.update_film(fin)
                if sweep % FINISH_CHECK == 0:
                    solver.work_units += self.exact_zone(fin)
                    m = self.measure(k)
                    if not m.ok or m.residual > 10.0 * best:
                        break
                    best = min(best, m.residual)
                    if m.residual < tol and m.load_error < tol_load:
                        break
        finally:
            s.omega, s.omega_jd, s.h00_gain = omega, omega_jd, gain
        solver.work_units += sweep * self.sweep_cost(k)
        solver.note(f"cycles stalled: {sweep} fine-grid relaxation sweeps")
        solver.record(k, -1, self.measure(k))
        return solver.converged()


def point_domain_mass_error(hz: CavitatedPointStepHierarchy) -> float:
    """Net oil gained by the whole finest grid in a step, relative to the inflow:
    ``(hx hy sum d(theta rho H)/dT - (F_in - F_out - F_side)) / F_in`` over the interior
    nodes, with the boundary flows of the conservative scheme
    (:func:`~ehl_multigrid.starved.point.face_fluxes`; the squeeze term is the BDF difference).
    It is ``-hx hy sum_i r_i / F_in`` (the finest grid's right-hand side is the history):
    zero to the step's tolerance."""
    lv = hz.fine
    ny, nx = lv.P.shape
    j0 = 0 if hz.options.half else 1
    fl = starved_point.face_fluxes(lv.P, lv.H, lv.rho, lv.eps, lv.theta, lv.hx, lv.hy, hz.options.half, lv.order)
    w = np.ones(ny - 1 - j0)
    if hz.options.half:
        w[0] = 0.5  # the centre row counted once, as the face flows count it
    storage = lv.hx * lv.hy * float((w[:, None] * hz.squeeze()[j0:ny - 1, 1:nx - 1]).sum())
    return (storage - (fl["in"] - fl["out"] - fl["side"])) / max(abs(fl["in"]), 1e-300)

