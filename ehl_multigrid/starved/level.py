"""One grid of the mass-conserving line solver: a :class:`~ehl_multigrid.line.level.LineLevel`
(coordinates, deformation operator, FAS right-hand sides, ``P``, ``H0``) with the film
content ``theta`` and the inlet oil layer."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..line.discrete import fluid_state, reynolds_residual
from ..line.level import LineLevel, State, _solve_band
from .discrete import (
    apply_changes,
    cavitated,
    face_fluxes,
    starved_inlet_correction,
    starved_relaxation_system,
)


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

    def state(self, P: np.ndarray | None = None, H0: float | None = None,
              theta: np.ndarray | None = None) -> StarvedState:
        P = self.P if P is None else P
        H0 = self.H0 if H0 is None else H0
        th = (self.theta if theta is None else theta).copy()
        W = self.deform(P)
        H, rho, drho, lne, dlne, eps = fluid_state(P, W, self.X, H0, self.par, self.lam, self.elastic)
        th[0] = self.inlet_theta(H[0])
        q = th * rho * H
        r, scale = reynolds_residual(P, H, th * rho, eps, self.h, self.f, self.order)
        if th[0] < 1.0:
            starved_inlet_correction(r, q, eps, P, self.h, self.order)
        return StarvedState(H, rho, drho, lne, dlne, eps, r, scale, th, q)

    def residual_norm(self, st: State) -> float:
        """Mean absolute residual of the interior (frozen points excluded): every point of the
        mass-conserving formulation satisfies the equation, cavitated ones through ``theta``."""
        r = st.r.copy()
        r[self.frozen] = 0.0
        return float(np.mean(np.abs(r[1:-1])))

    def fluxes(self, st: StarvedState) -> np.ndarray:
        """Mass flux through every face (:func:`face_fluxes`)."""
        return face_fluxes(self.P, st.q, st.eps, self.h, self.order, bool(st.theta[0] < 1.0))

    def relax(self, switch: float, omega: float, omega_jd: float, band: int = 4,
              st: State | None = None, switch_h: float = 0.0, omega_theta: float = 1.0) -> StarvedState:
        """One collective line-relaxation sweep in the universal variable at fixed H0
        (discrete.starved_relaxation_system). Returns the state before the sweep."""
        st = self.state() if st is None else st
        self.theta[0] = st.theta[0]
        cav = cavitated(self.P, self.theta, st.r, self.frozen)
        q0_fixed = st.theta[0] < 1.0
        ab, rhs, jac, dP, dT = starved_relaxation_system(
            self.P, st.theta, q0_fixed, st.H, st.rho, st.drho, st.eps, st.r, self.kernel, self.h,
            self.order, self.elastic, switch, band, self.frozen, cav, switch_h)
        delta = _solve_band(ab, rhs, band)
        self.P, self.theta = apply_changes(self.P, self.theta, delta, jac, cav, dP, dT, omega,
                                           omega_jd, omega_theta, self.frozen)
        return st
