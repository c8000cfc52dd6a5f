"""One grid of the mass-conserving line solver: a :class:`~ehl_multigrid.line.level.LineLevel`
(coordinates, deformation operator, FAS right-hand sides, ``P``, ``H0``) with the film
content ``theta`` and the inlet oil layer."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..line.discrete import fluid_state
from ..line.level import LineLevel, State, solve_band
from .discrete import (
    apply_changes,
    band_jacobian,
    cavitated,
    elrod_adams_residual,
    face_fluxes,
    line_system,
    regime_update,
)

#: most re-solves of one sweep's band system while the regimes change
ACTIVE_SET_STEPS = 8
#: the active-set re-solve is used only when the first solve moves at most this many points
#: across the regime boundary (the meniscus and the rupture point)
ACTIVE_SET_MAX_SWITCH = 4


@dataclass
class StarvedState(State):
    """State of an iterate with its film content (``theta[0]`` set by the inlet supply) and
    the flux ``q = theta rho H``."""

    theta: np.ndarray = None
    q: np.ndarray = None


@dataclass
class StarvedLevel(LineLevel):
    """Line grid with the film content ``theta`` (1 where pressurised) and the supplied layer
    ``hoil`` (Venner units; ``inf``: flooded inlet)."""

    hoil: float = math.inf
    starved_inlet: bool = False
    theta: np.ndarray = field(init=False)

    def __post_init__(self) -> None:
        super().__post_init__()
        self.theta = np.ones(self.n)

    def inlet_theta(self, H_inlet: float) -> float:
        """Film content at the inlet node: the supplied layer fills ``hoil/H`` of the gap of a
        starved inlet (``starved_inlet``); 1 at a flooded inlet."""
        if not self.starved_inlet or H_inlet <= self.hoil:
            return 1.0
        return self.hoil / H_inlet

    def content_rate(self) -> tuple[float, np.ndarray]:
        """``(ct, hist)`` of the time derivative ``d(theta rho H)/dT = ct theta rho H - hist``
        in the rows of this grid: ``(0, 0)`` for a steady problem."""
        return 0.0, np.zeros(self.n)

    def state(self, P: np.ndarray | None = None, H0: float | None = None,
              theta: np.ndarray | None = None) -> StarvedState:
        P = self.P if P is None else P
        H0 = self.H0 if H0 is None else H0
        th = (self.theta if theta is None else theta).copy()
        W = self.deform(P)
        H, rho, drho, lne, dlne, eps = fluid_state(P, W, self.X, H0, self.par, self.lam, self.elastic)
        th[0] = self.inlet_theta(H[0])
        q = th * rho * H
        r, scale = elrod_adams_residual(P, H, rho, th, eps, self.h, self.f, self.order, bool(th[0] < 1.0),
                                        self.face)
        return StarvedState(H, rho, drho, lne, dlne, eps, r, scale, th, q)

    def residual_norm(self, st: State) -> float:
        """Mean absolute residual of the interior (frozen points excluded): every point of the
        mass-conserving formulation satisfies the equation, cavitated ones through ``theta``."""
        r = st.r.copy()
        r[self.frozen] = 0.0
        return float(np.mean(np.abs(r[1:-1])))

    def fluxes(self, st: StarvedState) -> np.ndarray:
        """Mass flux through every face (:func:`face_fluxes`)."""
        return face_fluxes(self.P, st.theta, st.q, st.eps, self.h, self.order, bool(st.theta[0] < 1.0), self.face)

    def jacobian(self, st: StarvedState, q0_fixed: bool, band: int) -> tuple[np.ndarray, np.ndarray]:
        """Band parts ``(AP, AT)`` of the Jacobian of the sweep (:func:`band_jacobian`)."""
        return band_jacobian(self.P, st.theta, q0_fixed, st.H, st.rho, st.drho, st.eps,
                             self.kernel, self.h, self.order, self.elastic, band, self.face)

    def relax(self, switch: float, omega: float, omega_jd: float, band: int = 4,
              st: State | None = None, switch_h: float = 0.0, omega_theta: float = 1.0,
              active_set_steps: int = ACTIVE_SET_STEPS) -> StarvedState:
        """One collective line-relaxation sweep in the universal variable at fixed H0: the
        band system (discrete.band_jacobian, discrete.line_system) is re-solved with the
        regimes its solution asks for until they agree (at most ``active_set_steps``; the
        point at the meniscus otherwise flips between the regimes from sweep to sweep:
        measured at M = 20, L = 10, Hoil = 0.05, 257 points, a residual stuck at 0.4).
        Returns the state before the sweep."""
        st = self.state() if st is None else st
        self.theta[0] = st.theta[0]
        cav = cavitated(self.P, self.theta, st.r, self.frozen, st.H)
        q0_fixed = bool(st.theta[0] < 1.0)
        AP, AT = self.jacobian(st, q0_fixed, band)
        for step in range(active_set_steps):
            ab, rhs, jac = line_system(AP, AT, st.r, self.P, self.theta, cav, self.frozen, st.eps,
                                       self.h, switch, switch_h, band)
            delta = solve_band(ab, rhs, band)
            cav_new, changed = regime_update(self.P, self.theta, delta, cav, self.frozen)
            if changed == 0 or (step == 0 and changed > ACTIVE_SET_MAX_SWITCH):
                # far from the solution whole zones change regime: the projected sweep
                # moves them gradually (the known moves are not under-relaxed)
                break
            cav = cav_new
        self.P, self.theta = apply_changes(self.P, self.theta, delta, jac, cav, omega, omega_jd,
                                           omega_theta, self.frozen)
        return st
