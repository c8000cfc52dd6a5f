"""One time step of the line contact with mass-conserving (Elrod-Adams) cavitation.

The transient Reynolds equation of the line contact (Venner & Lubrecht 2000, ch. 12; the
film and load equations of thesis (2.2)-(2.3)) with the film content ``theta`` of the starved
solver (Elrod & Adams 1974; thesis section 6.2 for the starved steady contact):

``d/dX(eps dP/dX) - d(theta rho H)/dX - d(theta rho H)/dT = 0``,
``P (1 - theta) = 0``, ``P >= 0``, ``0 < theta <= 1``.

Where the film ruptures behind the contact or behind a dent, the oil the surfaces carry is
``theta rho H`` and it is conserved as it is carried on and refills the gap downstream
(reformation), unlike the projection ``P >= 0`` of :class:`~.hierarchy.TransientLineHierarchy`,
which creates and destroys oil at the cavitation boundary. The discrete equations are in
conservation form on every node, so the net flux into the whole domain equals the change
of the oil it holds, to the residual (:func:`domain_mass_error`).

The grids, relaxation (collective line relaxation in the universal variable, the regimes by
an active-set re-solve), transfers and inlet rule are the starved solver's
(:class:`~ehl_multigrid.starved.line.StarvedLineHierarchy`); a time step adds the moving
geometry and the squeeze term ``c_t theta rho H - s`` (BDF, discrete.py) as
:class:`~.hierarchy.TimeStepGrids` does for the projection. A finite supplied layer
(``hoil``, Venner units) starves the inlet as in the steady starved solver.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..line.discrete import fluid_state
from ..line.problem import LineProblem
from ..multigrid.options import LineOptions
from ..multigrid.result import EHLResult
from ..starved.discrete import elrod_adams_residual, face_fluxes
from ..starved.level import StarvedLevel, StarvedState
from ..starved.line import StarvedLineHierarchy
from .discrete import add_content_squeeze
from .hierarchy import TimeStepGrids
from .oil_balance import OilBalanceCycles

#: most fine-grid relaxation sweeps that finish a stalled step
FINISH_SWEEPS = 400


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
