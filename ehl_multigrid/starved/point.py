"""Starved, mass-conserving point contact: Elrod-Adams film content on the point hierarchy.

The steady Reynolds equation (thesis (2.1), boundary conditions (2.2)-(2.3)) with the
Elrod-Adams cavitation model (Elrod 1981; Woloszynski et al. 2015 for the complementarity
form), in the point core's dimensionless variables:

    d/dX(eps dP/dX) + d/dY(eps dP/dY) - d(theta rho H)/dX = 0,
    P >= 0,  0 <= theta <= 1,  P (1 - theta) = 0,

with a uniform supplied layer ``Hoil`` at the inlet boundary (``theta rho H = Hoil`` at
``X = xmin``, the layer at ambient pressure and density; ``Hoil = inf`` floods the inlet).
The meniscus, the curve where the film fills the gap, is found inside the iteration.

Discretisation: the point core's five-point Poiseuille terms and an upwind wedge on the mass
flux ``q = theta rho H`` in flux form (so the sum of the residuals telescopes into the
boundary fluxes: discrete mass conservation): first order (``wedge_order = 1``, the default)
or second order where the film is full and first order at the meniscus and in the cavitated
outlet (``wedge_order = 2``; face values in :mod:`.point_wedge`, the line kernel of the core
with a defect-corrected right-hand side, coarse grids first order). Relaxation on the universal variable: the point
core's zebra X-line relaxation on P with the density replaced by ``theta rho`` (P held at
zero where ``theta < 1``), then a march along X in the unpressurised points that solves each
point's mass balance for ``theta`` (capped at 1: the point joins the pressurised zone at the
next sweep; a pressurised point has ``theta = 1``, a point whose P is projected to 0 frees its
``theta``). Coarse grids: FAS in P and theta on the grid below the current one and on those
that resolve the starved inlet (:data:`COARSE_THETA_MESH`), ``theta`` frozen (injected) below.

Robustness (validation/starved/REPORT.md): pressurised points that a projected Jacobi step
would cavitate are projected to P = 0 after each sweep; a solve the default coarse-grid rule
does not converge is repeated with theta frozen on every coarse grid; a converged solve whose
mass imbalance exceeds :data:`MASS_TOL`, or one that still did not converge, is repeated with
an exact solve of the Poiseuille-dominated zone after every finest-grid cycle
(:mod:`.point_mass`: sparse primal-dual active set on P and theta; :data:`EXACT_EPS`,
``PointOptions.exact_rules``), and as a last resort at a tighter tolerance. A result whose
boundary flows do not balance fails (:mod:`.gate`), whatever its iteration said. On the
55-supply map every supply converges and conserves mass to 1e-6 with either wedge order. First
order: the flooded Hc 2-8 % above the core's second-order film; second order: the core's
flooded film, Hc converging at second order, as robust and as conservative as first order at
1.8x its wall time, not the default (docs/starvation.md, "Solver defaults").

The supply may vary across the track (one layer per finest-grid row, e.g. side ridges).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np
from scipy import ndimage

from ..model.errors import ConvergenceError, InputError, require_range
from ..multigrid.accuracy import (
    GRID_SAFETY,
    LOAD_SENSITIVITY,
    ErrorEstimate,
    attach_estimate,
    floor_film_spread,
    iteration_error,
)
from ..multigrid.controller import Refinement, Resolution, control
from ..multigrid.driver import MultilevelSolver
from ..multigrid.options import PointOptions
from ..multigrid.policy import RobustnessPolicy, Settings
from ..multigrid.result import EHLResult
from ..multigrid.threads import preserved_threads
from ..point import numerics as nm
from ..point.fas import HINT, POINT_POLICY, Level, PointHierarchy, point_settings
from ..point.postprocess import build_result
from ..point.problem import PointProblem, min_points
from .gate import apply_mass_gate
from .point_mass import inlet_solve
from .point_wedge import face_value, flux_operator, march_theta, wedge_correction
from .refine import StarvedControl, compare_flooded, note_not_refined, supply_ratio
from .supply import check_hoil, check_profile

#: default tolerance of the starved solve on the core's scaled residual (a pressure change
#: relative to max P): tight, since in the inlet eps/h^2 ~ 1e6 turns a pressure error of 1e-10
#: into 1e-4 of the flow (docs/starvation.md, "Solver defaults").
STARVED_TOL = 1e-8

#: The film content moves (FAS in P and theta) on the grid below the current one and on coarser
#: grids whose mesh is at most this fraction of ``sqrt(2 Hoil)`` (over which a starved inlet's gap
#: doubles the supplied layer); frozen (injected) below them (docs/starvation.md).
COARSE_THETA_MESH = 0.2

#: Second coarse-grid rule of a solve that the default rule does not converge: theta frozen
#: (injected) on every grid below the current one (``coarse_theta = 0``); it converges the
#: default rule's residual floors but stalls a case the default converges (docs/starvation.md).
FALLBACK_COARSE_THETA = 0

#: relative mass imbalance a starved solve aims for: a larger one is solved again with the exact
#: zone solve (:data:`EXACT_EPS`), then at the tolerance times MASS_TOL_FACTOR (at most twice its
#: cycles + 10), keeping a smaller converged imbalance (docs/starvation.md, "Solver defaults").
MASS_TOL = 1e-6
MASS_TOL_FACTOR = 0.01

#: exact solve of the Poiseuille-dominated zone (:func:`.point_mass.inlet_solve`, points with
#: ``eps/hx^2 >= EXACT_EPS``) MASS_PASSES times after every finest-grid cycle of a mass re-solve:
#: it removes the cycles' fixed-point imbalance (docs/starvation.md, "Solver defaults").
EXACT_EPS = 10.0
MASS_PASSES = 1
#: unpressurised points of the exact solve's zone: those within this many points (4-neighbour
#: steps) of its pressurised points (:meth:`StarvedPointHierarchy.exact_zone_mask`): 29-32 % of
#: the grid at 2 Hc_ff instead of about 95 % (docs/starvation.md, "Solver defaults").
EXACT_MARGIN = 4
#: extra finest-grid cycles of a starved solve: measured at (179, 4.17) 257^2 the moderate
#: supplies (Hoil = 1.5 ... 0.4 Hc_ff) converge in 62-94 cycles.
STARVED_MAX_CYCLES = 100
#: the same with the second-order wedge: measured at (179, 4.17) 257^2, Hoil = Hc_ff the
#: residual falls by ~0.9 per cycle after the meniscus has settled (1.3e-8 after 100 cycles)
STARVED_MAX_CYCLES_2 = 150

#: The point core's policy, but a cycle is rejected only when its residual grows 30x over the
#: best of the last 4 (the core: 3x over the best ever): while the meniscus travels from the
#: flooded FMG state to its starved place the residual rises for several cycles.
STARVED_POLICY = replace(POINT_POLICY, growth=30.0, growth_window=4)

#: default upwind order of the wedge term ``d(theta rho H)/dX`` (``wedge_order`` option; 2: the
#: per-face second-order flux of :mod:`.point_wedge`, as robust but 1.8x the wall time); changing
#: it changes every starved result (docs/starvation.md, "Solver defaults").
STARVED_WEDGE_ORDER = 1

#: upwind order of the film-response Jacobian in the point core's line kernel when the wedge
#: is the per-face second-order one (the right-hand side carries the defect correction)
KERNEL_ORDER = 1

#: second-order wedge: extra finest-grid sweeps once the cycles stall below POLISH_BELOW (less
#: than a fall to POLISH_RATE over two cycles); once stuck (POLISH_STUCK) every second cycle skips
#: the coarse-grid correction, which undoes their gain at the meniscus (docs/starvation.md).
POLISH_SWEEPS = 8
POLISH_BELOW = 1e-6
POLISH_RATE = 0.7
POLISH_STUCK = 0.95

#: wedge order of the coarse grids (FAS: the fine grid's residual carries its order)
COARSE_WEDGE_ORDER = 1


def face_fluxes(P: np.ndarray, H: np.ndarray, rho: np.ndarray, eps: np.ndarray, theta: np.ndarray,
                hx: float, hy: float, half: bool, order: int = 1) -> dict[str, float]:
    """Mass flow through the boundaries of the cells whose discrete operator telescopes (flux
    form, columns 1 .. nx-2): in at the inlet face, out at the outlet face and the side faces (a
    half domain counts the centre row once, i.e. the full-domain flow halved). The x faces carry
    ``Q_{i+1/2} - eps dP/dX`` with the operator's face values ``Q``
    (:func:`.point_wedge.face_value`: first order, or second order where the film is full)."""
    ny, nx = P.shape
    rq = np.ascontiguousarray(theta * rho)
    rows, w = balance_rows(ny, half)

    def xflux(i: int) -> np.ndarray:  # flux through the face between columns i and i + 1
        conv = np.array([face_value(rq, H, theta, j, i, order) for j in rows])
        ex = 0.5 * (eps[rows, i] + eps[rows, i + 1])
        return conv - ex * (P[rows, i + 1] - P[rows, i]) / hx

    cols = slice(1, nx - 1)
    ey = 0.5 * (eps[ny - 2, cols] + eps[ny - 1, cols])
    side = float((-ey * (P[ny - 1, cols] - P[ny - 2, cols]) / hy).sum() * hx)
    if not half:
        ey0 = 0.5 * (eps[0, cols] + eps[1, cols])
        side += float((ey0 * (P[1, cols] - P[0, cols]) / hy).sum() * hx)
    return {"in": float((w * xflux(0)).sum() * hy), "out": float((w * xflux(nx - 2)).sum() * hy),
            "side": side}


def supply_rows(hoil: Any, ny: int, Y: np.ndarray | None = None) -> np.ndarray:
    """The supplied layer per row of the finest grid: a number (uniform), a profile of
    exactly ``ny`` layers, or a function of the rows' ``Y`` (a profile independent of the
    grid, e.g. a scene's ``[supply] hoil_profile``); each layer in ``(0, inf]``
    (:class:`InputError` otherwise)."""
    if callable(hoil):
        if Y is None:
            raise InputError("a supply profile given as a function needs the grid's rows Y")
        return check_profile(np.asarray([hoil(float(y)) for y in Y], dtype=float), ny)
    if np.ndim(hoil) == 0:
        return np.full(ny, check_hoil(hoil))
    return check_profile(hoil, ny)


def mean_layer(rows: np.ndarray, half: bool) -> float:
    """Mean supplied layer over the rows whose inlet flow the mass balance counts (those of
    :func:`face_fluxes`: a half domain's centre row with weight 1/2); ``inf`` when any of
    them is flooded."""
    j, w = balance_rows(rows.size, half)
    r = rows[j]
    if not np.all(np.isfinite(r)):
        return math.inf
    return float((w * r).sum() / w.sum())


def balance_rows(ny: int, half: bool) -> tuple[np.ndarray, np.ndarray]:
    """The rows of a grid with ``ny`` rows whose boundary flows the mass balance counts (the
    interior rows, and a half domain's centre row) and their weights (that centre row 1/2:
    the full-domain flow halved)."""
    rows = np.arange(0 if half else 1, ny - 1)
    w = np.ones(rows.size)
    if half:
        w[0] = 0.5
    return rows, w


class StarvedPointHierarchy(PointHierarchy):
    """Point hierarchy with an Elrod-Adams film content ``theta`` and a supplied layer ``hoil``
    (Venner units ``h R/a^2``; ``inf``: flooded): a number, or one layer per row of the finest
    grid across the track (a profile over Y, :func:`~.supply.check_profile`).

    Its operator, relaxation, theta march and exact zone solve carry the core's squeeze
    coefficient :attr:`~ehl_multigrid.point.fas.PointHierarchy.ct` (the new-time part
    ``ct theta rho H`` of a BDF time step's ``d(theta rho H)/dT``): 0 in a steady solve, set by
    the time-step hierarchy of :mod:`ehl_multigrid.transient.cavitated`."""

    name = "starved point"
    can_alternate = False  # its own sweep relaxes X lines only
    local_update = False
    grid_stop = False  # the mass balance needs the residual, not only the films
    far_field_ok = False  # the supply, not the far field, feeds the inlet

    def __init__(self, problem: PointProblem, options: PointOptions, hoil: Any,
                 coarse_theta: int | None = None) -> None:
        super().__init__(problem, options)
        rows = supply_rows(hoil, self.levels[-1].ny, self.levels[-1].Y)
        self.hoil_rows = rows
        self.hoil = mean_layer(rows, options.half)
        self.coarse_theta = coarse_theta
        self.order = int(options.wedge_order)
        for lev in self.levels[:-1]:
            lev.order = min(self.order, COARSE_WEDGE_ORDER)
        self.levels[-1].order = self.order
        #: free film content on a coarse grid whose mesh resolves the starved inlet
        self.theta_mesh = COARSE_THETA_MESH * math.sqrt(2.0 * min(float(rows.min()), 1e150))
        top = len(self.levels) - 1
        for k, lev in enumerate(self.levels):
            lev.theta = np.ones(lev.shape)
            # the rows of grid k are every 2^(top - k)-th row of the finest grid
            lev.hoil_rows = np.ascontiguousarray(np.minimum(rows[::2 ** (top - k)], 1e300))
        self._top = 0
        #: residuals of the finest grid after each cycle (for :meth:`_polishing`)
        self._fine_res: list[float] = []
        self._polish = 0
        self._seen = 0
        #: exact solve of the Poiseuille-dominated zone after each finest-grid cycle
        self.exact = False
        self._post = False
        #: notes of failed exact solves (for the result's actions)
        self.exact_notes: list[str] = []

    # -- discrete operators ---------------------------------------------------------------
    def _q_density(self, lev: Level) -> np.ndarray:
        return np.ascontiguousarray(lev.theta * lev.rho)

    def _operator(self, lev: Level, out: np.ndarray) -> None:
        """``L(P, theta)`` into ``out``: the core's first-order operator (``order = 1``) or the
        conservative per-face second-order wedge (:func:`.point_wedge.flux_operator`)."""
        self._apply(lev, lev.P, lev.theta, out)

    def _apply(self, lev: Level, P: np.ndarray, theta: np.ndarray, out: np.ndarray) -> None:
        """``L(P, theta)`` at the level's frozen film into ``out``, with the new-time part
        ``ct theta rho H`` of a time step's squeeze term (the core's :attr:`ct`; 0 steady)."""
        rq = np.ascontiguousarray(theta * lev.rho)
        if lev.order == 1:
            nm.operator(P, lev.H, rq, lev.eps, lev.hx, lev.hy, self.options.half, 1, out, self.ct)
        else:
            flux_operator(P, lev.H, rq, lev.eps, theta, lev.hx, lev.hy, self.options.half,
                          lev.order, out, self.ct)

    def _march(self, lev: Level) -> None:
        nm.fluid_properties(lev.P, lev.H, self.par, self.lam, lev.rho, lev.eps)
        march_theta(lev.P, lev.H, lev.rho, lev.eps, lev.theta, lev.f, lev.hx, lev.hy,
                    self.options.half, lev.hoil_rows, lev.order, self.ct)

    def _sweep_rhs(self, lev: Level, rq: np.ndarray, dry: np.ndarray) -> np.ndarray:
        """Right-hand side of a line sweep on P: ``f`` with the wedge's defect correction
        (order 2), and a value the kernel reads as "cavitated, stays at zero" at the
        unpressurised points ``dry`` (the line systems hold them fixed instead of solving for
        them and resetting them)."""
        if lev.order == 1:
            return np.where(dry, 1e300, lev.f)
        # defect correction: the kernel's wedge (core second order) replaced by the per-face
        # limited one at the sweep's frozen film (see point_wedge)
        corr = np.empty_like(lev.f)
        wedge_correction(rq, lev.H, lev.theta, lev.hx, self.options.half, lev.order, KERNEL_ORDER, corr)
        return np.where(dry, 1e300, lev.f + corr)

    def _sweep_free(self, lev: Level, s: Settings, free: bool) -> None:
        """One X-line sweep on P (density ``theta rho``; P stays 0 where ``theta < 1``), then,
        when the free boundaries move on this grid, the ``theta`` march."""
        self.threads.for_size(lev.npts)
        rq = self._q_density(lev)
        dry = lev.theta < 1.0
        lev.P[dry] = 0.0
        fr = self._sweep_rhs(lev, rq, dry)
        nm.relax_sweep(lev.P, lev.H, rq, lev.eps, fr, lev.D, lev.Kc, lev.hx, lev.hy,
                       self.options.half, s.switch, s.omega, s.omega_jd,
                       1 if lev.order == 1 else KERNEL_ORDER, self.ct)
        lev.P[dry] = 0.0
        self.update_film(lev)
        if free:
            self._release(lev)
            self._march(lev)

    def _release(self, lev: Level) -> None:
        """Project to P = 0 the pressurised points that a projected Jacobi step would cavitate
        (``0 < P <= (f - L)/diag``): the line kernel holds a point at P = 0 where it wants to
        fall, but the Jacobi-distributive changes of its neighbours lift it to a tiny P
        again, where it then counts in the residual and in the mass balance as a full
        pressurised point (one such point at the side of the pressurised zone holds (179, 4.17) at
        257^2, Hoil = 0.25 Hc_ff, at a residual of 2.3e-5 without this)."""
        self._operator(lev, lev.r)
        r = np.subtract(lev.f, lev.r, out=lev.r)  # in place: lev.r is the grids' shared buffer
        sr = np.empty_like(r)
        nm.scaled_residual(r, lev.H, lev.rho, lev.eps, float(lev.Kc[0, 0]), lev.hx, lev.hy,
                           self.options.half, sr, self.ct)
        inner = self._interior(np.ones(r.shape, dtype=bool))
        drop = inner & (lev.P > 0.0) & (sr >= lev.P)
        if drop.any():
            lev.P[drop] = 0.0
            self.update_film(lev)

    def _sweep(self, lev: Level, s: Settings) -> None:  # used by the core's coarse solve
        self._sweep_free(lev, s, self._free(self.levels.index(lev)))

    def residual(self, lev: Level) -> np.ndarray:
        """``f - L(P, theta)`` at the interior points: the P equation where ``theta = 1``, the
        mass balance that the ``theta`` march solves where ``P = 0``; where ``theta = 0`` (a dry
        point: the march clipped a negative content) only a surplus counts."""
        self.threads.for_size(lev.npts)
        self._operator(lev, lev.r)
        # in place: lev.r is a view of the buffer all grids share (PointHierarchy)
        r = self._interior(np.subtract(lev.f, lev.r, out=lev.r))
        r[(lev.theta <= 0.0) & (r > 0.0)] = 0.0
        return r

    def _interior(self, r: np.ndarray) -> np.ndarray:
        """``r`` with its boundary points (those outside the balance) set to 0, in place."""
        ny, nx = r.shape
        j0 = 0 if self.options.half else 1
        r[:j0] = 0.0
        r[ny - 1:] = 0.0
        r[:, 0] = 0.0
        r[:, nx - 1] = 0.0
        return r

    def _free(self, k: int) -> bool:
        """Does ``theta`` move on grid ``k``? On the current fine grid and the grid below it
        always; on coarser grids when ``coarse_theta`` (grids below the current one) says so,
        or by default when their mesh ``hx <= COARSE_THETA_MESH sqrt(2 Hoil)`` resolves the
        starved inlet."""
        depth = self._top - k
        if self.coarse_theta is not None:
            return depth <= self.coarse_theta
        return depth <= 1 or self.levels[k].hx <= self.theta_mesh

    def rule_key(self, rule: int | None) -> int | None:
        """The coarse-grid theta rule that frees the same grids as ``rule`` (:meth:`_free`):
        the default (None) is rule 1 where no grid three or more below the finest resolves the
        inlet."""
        if rule is None and (len(self.levels) < 3 or self.levels[-3].hx > self.theta_mesh):
            return 1
        return rule

    def measure(self, k: int) -> Any:
        m = super().measure(k)
        if k == len(self.levels) - 1:
            self._fine_res.append(float(m.residual))
        return m

    def _polishing(self, k: int) -> bool:
        """Second-order wedge only: :data:`POLISH_SWEEPS` extra finest-grid sweeps per
        relaxation once the finest residual is below :data:`POLISH_BELOW` and falls by less
        than to :data:`POLISH_RATE` over two cycles; when it falls by less than to
        :data:`POLISH_STUCK` (a fixed point of the cycle at the meniscus) every second cycle
        also skips the coarse-grid correction (:meth:`correct`). Both stay on for the rest of
        the solve."""
        r = self._fine_res
        if k != len(self.levels) - 1 or self.order == 1:
            return False
        if len(r) >= 3 and r[-1] < POLISH_BELOW and self._seen != len(r):
            self._seen = len(r)
            # stays on for the rest of the solve; 2: without the coarse-grid correction
            if r[-1] > POLISH_STUCK * r[-3]:
                self._polish = 2
            elif r[-1] > POLISH_RATE * r[-3]:
                self._polish = max(self._polish, 1)
        return self._polish > 0

    def relax(self, k: int, sweeps: int, s: Settings, coarse: bool, post: bool = False) -> float:
        lev = self.levels[k]
        if not coarse:
            self._top = k
        if self._polishing(k):
            sweeps += POLISH_SWEEPS
        for _ in range(sweeps):
            self._sweep_free(lev, s, self._free(k))
        work = sweeps * self.sweep_work * self.work(k)
        if self._post and not coarse and k == len(self.levels) - 1:
            self._post = False
            if self.exact:
                work += self.exact_zone(lev)
        return work

    def _raw_residual(self, lev: Level, P: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """``f - L(P, theta)`` at the level's frozen film (0 on the boundary)."""
        out = np.empty_like(P)
        self._apply(lev, P, theta, out)
        return self._interior(lev.f - out)

    def exact_zone(self, lev: Level) -> float:
        """Exact solve of the discrete balance on :meth:`exact_zone_mask` (see
        :data:`EXACT_EPS`): :func:`.point_mass.inlet_solve`, :data:`MASS_PASSES` times with the
        film updated in between, then the theta march. A failed solve (singular system, active
        set not settling) keeps the cycle's state and is noted in ``exact_notes``. Returns the
        work (one finest-grid sweep per pass)."""
        for _ in range(MASS_PASSES):
            zone = self.exact_zone_mask(lev)
            ok, _it, note = inlet_solve(lev.P, lev.H, lev.rho, lev.eps, lev.theta, lev.f, lev.hx,
                                        lev.hy, self.options.half, lev.order, zone,
                                        lambda P, t: self._raw_residual(lev, P, t), self.ct)
            self.update_film(lev)
            if not ok:
                if note != "empty region" and len(self.exact_notes) < 3:
                    self.exact_notes.append(note)
                break
        self._march(lev)
        return MASS_PASSES * self.work(len(self.levels) - 1)

    def restrict(self, k: int, s: Settings) -> tuple[tuple[np.ndarray, np.ndarray], None]:
        lev, c = self.levels[k], self.levels[k - 1]
        r = self.residual(lev)
        c.P = np.ascontiguousarray(lev.P[::2, ::2])
        c.theta = np.ascontiguousarray(lev.theta[::2, ::2])
        P0 = c.P.copy()
        theta0 = c.theta.copy()
        self.update_film(c)
        Lc = np.empty_like(c.P)
        self._operator(c, Lc)
        Rr = np.empty_like(c.P)
        nm.restrict_full_weighting(r, self.options.half, Rr)
        c.f = Lc + Rr
        c.g = self.load(c) + (lev.g - self.load(lev))
        return (P0, theta0), None

    def correct(self, k: int, token: tuple[np.ndarray, np.ndarray], s: Settings) -> None:
        lev, c = self.levels[k], self.levels[k - 1]
        P0, theta0 = token
        self._post = k == len(self.levels) - 1
        if self._polish == 2 and k == len(self.levels) - 1 and len(self._fine_res) % 2 == 0:
            # stalled at the meniscus: only H00 (the load balance) comes from the coarse grids
            self.update_film(lev)
            return
        nm.add_bilinear(lev.P, c.P - P0, True)
        if self._free(k - 1):
            # film content corrected where the fine grid is unpressurised (theta < 1)
            t = lev.theta - 1.0
            nm.add_bilinear(t, c.theta - theta0, False)
            dry = lev.theta < 1.0
            lev.theta[dry] = np.clip(t[dry] + 1.0, 0.0, 1.0)
        lev.P[lev.theta < 1.0] = 0.0
        self.update_film(lev)

    def exact_zone_mask(self, lev: Level, e: float = EXACT_EPS) -> np.ndarray:
        """The points of the exact solve (:meth:`exact_zone`): the pressurised points (film
        full) with ``eps/hx^2 >= e`` (the Poiseuille terms dominate the film's self-response:
        the inlet, the side rows; not the Hertzian zone), and the unpressurised points within
        :data:`EXACT_MARGIN` points of them (the meniscus moves inside the zone; the other
        unpressurised points keep the march, which solves their balance exactly)."""
        full = (lev.theta >= 1.0) | (lev.P > 0.0)
        core = full & (lev.eps >= e * lev.hx * lev.hx)
        near = ndimage.binary_dilation(core, iterations=EXACT_MARGIN)
        return core | (near & ~full)

    def fmg_interpolate(self, k: int, s: Settings) -> float:
        cost = super().fmg_interpolate(k, s)
        lev, c = self.levels[k], self.levels[k - 1]
        t = np.ones(lev.shape)
        nm.add_bilinear(t, c.theta - 1.0, False)
        lev.theta = np.ascontiguousarray(np.clip(t, 0.0, 1.0))
        lev.P[lev.theta < 1.0] = 0.0
        self._top = k
        self.update_film(lev)
        self._march(lev)
        return cost

    def start(self, solver: MultilevelSolver) -> int:
        """The core's start; from a given solution (:attr:`guess`, ``start_on_guess``) the film
        content of its unpressurised points follows from the supply (the theta march)."""
        k = super().start(solver)
        if self.start_on_guess and self.guess is not None:
            self._top = k
            self._march(self.levels[k])
        return k

    def snapshot(self, k: int) -> tuple[np.ndarray, float, np.ndarray]:
        return (self.levels[k].P.copy(), self.H00, self.levels[k].theta.copy())

    def restore(self, k: int, saved: tuple[np.ndarray, float, np.ndarray]) -> None:
        self.levels[k].theta = saved[2].copy()
        super().restore(k, saved[:2])



def meniscus_x(X: np.ndarray, theta: np.ndarray, row: int) -> float:
    """First X along grid row ``row`` where the film fills the gap (``theta = 1``), linearly
    placed between the last unfilled and first filled node by ``theta``; ``xmin`` when
    flooded."""
    t = theta[row]
    full = np.nonzero(t >= 1.0)[0]
    if full.size == 0:
        return math.nan
    i = int(full[0])
    if i == 0:
        return float(X[0])
    # the unfilled node's film content tells how far into the cell the meniscus sits
    return float(X[i - 1] + (X[i] - X[i - 1]) * (1.0 - t[i - 1]))


def boundary_flows(hz: StarvedPointHierarchy) -> tuple[dict[str, float], float]:
    """The boundary flows of the finest grid (:func:`face_fluxes`) and their relative
    imbalance ``|in - out - side| / in``."""
    f = hz.levels[-1]
    fl = face_fluxes(f.P, f.H, f.rho, f.eps, f.theta, f.hx, f.hy, hz.options.half, hz.order)
    return fl, abs(fl["in"] - fl["out"] - fl["side"]) / max(abs(fl["in"]), 1e-300)


def imbalance_of(hz: StarvedPointHierarchy) -> float:
    """Relative imbalance of the boundary flows of the finest grid (in - out - side)/in."""
    return boundary_flows(hz)[1]


def _solve_once(problem: PointProblem, hoil: float, opt: PointOptions, coarse_theta: int | None,
                exact: bool = False,
                guess: tuple[np.ndarray, np.ndarray, np.ndarray, float] | None = None,
                ) -> tuple[EHLResult, StarvedPointHierarchy]:
    with preserved_threads():
        hz = StarvedPointHierarchy(problem, opt, hoil, coarse_theta)
        hz.exact = exact
        hz.guess, hz.start_on_guess = guess, guess is not None
        solver = MultilevelSolver(hz, opt, point_settings(problem, opt),
                                  RobustnessPolicy(STARVED_POLICY, opt.adapt), HINT)
        hz.solver = solver
        sol = solver.solve()
    hz.solver = None
    return sol, hz


def _exact_resolve(problem: Any, hoil: float, opt: PointOptions, rule: int | None, guess: Any,
                   sol: EHLResult, hz: Any, mb: float, why: str,
                   failed_counts: bool) -> tuple[EHLResult, Any, float]:
    """Solve again with the exact solve of the Poiseuille-dominated zone under the coarse-grid
    theta ``rule`` and keep the better of the two: the new solve when it converged or its mass
    imbalance is smaller (an unconverged new solve competes on its imbalance only when
    ``failed_counts``). The step, headed by ``why``, goes into the kept solve's actions.
    Returns the kept ``(sol, hz, imbalance)``."""
    new, hz_new = _solve_once(problem, hoil, opt, rule, exact=True, guess=guess)
    mb_new = imbalance_of(hz_new) if (new.success or failed_counts) else math.inf
    keep = (failed_counts and new.success) or mb_new < mb
    what = (f"{why}: re-solved with the exact solve of the zone eps/hx^2 >= {EXACT_EPS:g} "
            f"(coarse theta rule {rule}): {new.status_name}, imbalance {mb_new:.2g}")
    if hz_new.exact_notes:
        what += f" (exact solves failed: {'; '.join(hz_new.exact_notes)})"
    what += f"; kept the {'second' if keep else 'first'}"
    sol, hz = _kept((sol, hz), (new, hz_new), keep, what)
    return sol, hz, mb_new if keep else mb


def _rule_tried(hz: StarvedPointHierarchy, rule: int | None, tried: set[int | None]) -> bool:
    """Was the coarse-grid theta ``rule``, or one that frees the same grids of ``hz``'s
    hierarchy (:meth:`StarvedPointHierarchy.rule_key`), solved already?"""
    return hz.rule_key(rule) in {hz.rule_key(r) for r in tried}


def _kept(old: tuple[EHLResult, Any], new: tuple[EHLResult, Any], keep: bool,
          what: str) -> tuple[EHLResult, Any]:
    """``new`` (a re-solve and its hierarchy) after ``old``'s actions when ``keep``, else
    ``old``, with the step ``what`` in the actions."""
    if keep:
        new[0].actions[:0] = old[0].actions
        old = new
    old[0].actions.append(what)
    return old


def solve_starved_point(problem: PointProblem, hoil: Any, options: PointOptions | None = None,
                        coarse_theta: int | None = None, *,
                        guess: tuple[np.ndarray, np.ndarray, np.ndarray, float] | None = None,
                        **kw: Any) -> EHLResult:
    """One multilevel (FMG + cycles) solve of a point contact with a supplied layer ``hoil``
    (Venner units ``h R/a^2``, total on both surfaces at ambient density; ``inf``: flooded
    inlet) and Elrod-Adams cavitation, the meniscus found inside the iteration. ``hoil`` is a
    number (uniform) or a profile across the track: one layer per row of the finest grid
    (``Y`` of the result; e.g. the side ridges left by the previous over-rolling).

    Without ``options`` the residual tolerance is ``STARVED_TOL`` and the wedge order
    ``STARVED_WEDGE_ORDER`` (keywords win); an options object is taken as given.

    No continuation in the supply here (the flooded solution first, the supply halved from
    twice its central film, each solve cycling on the finest grid from the previous one): at
    (100, 5) 257^2 and (179, 4.17) 129^2 it reaches the same or worse residuals at 3-6 times the
    cost. A scene solve continues from a thinner layer only where this solve fails
    (:meth:`_StarvedPointControl._continued`).

    The result carries ``theta`` (``sol.extra["theta"]``), ``meniscus_x`` (centre line),
    ``mass_balance_error`` (relative imbalance of the boundary flows), ``outlet_layer`` (mean
    ``theta rho H`` leaving at the outlet face, per width), ``hoil`` (the mean supplied layer
    over the rows of the balance), ``hoil_rows`` and ``hoil_centre``; ``coarse_theta`` the
    coarse-grid theta rule of the kept solve, ``rescued`` whether only the exact zone solve
    converged it (see ``PointOptions.exact_rules``, docs/robustness.md).

    ``guess``: ``(X, Y, P, H00)`` of a solution of the same contact (e.g. on the grid with half
    the intervals): the cycles start on the finest grid from it instead of the FMG, the film
    content of its unpressurised points from the supply. A result whose mass balance fails
    the gate of :mod:`.gate` gets a failed status."""
    if not callable(hoil) and np.ndim(hoil) == 0:
        hoil = check_hoil(hoil)
    explicit = set(kw)
    if options is None:  # the tighter default; an options object's tolerance is the caller's
        kw.setdefault("tol", STARVED_TOL)
        kw.setdefault("wedge_order", STARVED_WEDGE_ORDER)
        kw.setdefault("max_cycles", STARVED_MAX_CYCLES if kw["wedge_order"] == 1 else STARVED_MAX_CYCLES_2)
    opt = PointOptions.build(options, **kw)
    # the fallback and exact re-solves below need the failed attempt back, not an exception:
    # a failure is raised (when asked) only for the solve that is finally kept
    asked, opt = opt.raise_on_failure, replace(opt, raise_on_failure=False)
    sol, hz = _solve_once(problem, hoil, opt, coarse_theta, guess=guess)
    if not sol.success and coarse_theta is None and math.isfinite(hz.hoil):
        # the other coarse-grid rule converges where this one stops (see FALLBACK_COARSE_THETA)
        first = (sol.status_name, float(sol.residual_history[-1]) if len(sol.residual_history) else math.inf)
        sol2, hz2 = _solve_once(problem, hoil, opt, FALLBACK_COARSE_THETA, guess=guess)
        res2 = float(sol2.residual_history[-1]) if len(sol2.residual_history) else math.inf
        if sol2.success or res2 < first[1]:
            sol, hz = sol2, hz2
        sol.actions.append(f"default coarse-grid theta rule: {first[0]} (residual {first[1]:.3g}); "
                           f"theta frozen on every coarse grid: {sol2.status_name} (residual "
                           f"{res2:.3g}); kept the {'second' if hz is hz2 else 'first'}")
    exact_rules: set[int | None] = set()  # rules already solved with the exact zone solve
    rescued = False
    if not sol.success and math.isfinite(hz.hoil):
        # cycles stopped short of convergence: solved again with the exact solve of the
        # Poiseuille-dominated zone (see PointOptions.exact_rules)
        rules = (hz.coarse_theta,) if coarse_theta is not None else \
            (hz.coarse_theta,) + tuple(r for r in opt.exact_rules if r != hz.coarse_theta)
        mb = imbalance_of(hz)
        for rule in rules:
            if _rule_tried(hz, rule, exact_rules):
                continue
            exact_rules.add(rule)
            sol, hz, mb = _exact_resolve(problem, hoil, opt, rule, guess, sol, hz, mb,
                                         f"{sol.status_name} with imbalance {mb:.2g}", failed_counts=True)
            if sol.success:
                rescued = True
                break
    if sol.success and math.isfinite(hz.hoil) and options is None and "tol" not in explicit:
        mb = imbalance_of(hz)
        if mb > MASS_TOL:
            # the residual tolerance does not see the inlet's mass balance (see MASS_TOL):
            # solved again with the exact solve of the Poiseuille-dominated zone, under the
            # coarse-grid theta rules of PointOptions.exact_rules in turn
            for rule in (hz.coarse_theta,) + tuple(r for r in opt.exact_rules if r != hz.coarse_theta):
                if _rule_tried(hz, rule, exact_rules):
                    continue
                exact_rules.add(rule)
                sol, hz, mb = _exact_resolve(problem, hoil, opt, rule, guess, sol, hz, mb,
                                             f"mass imbalance {mb:.2g}", failed_counts=False)
                if mb <= MASS_TOL:
                    break
        if mb > MASS_TOL:
            # a tighter residual tolerance (see MASS_TOL_FACTOR)
            tight = replace(opt, tol=opt.tol * MASS_TOL_FACTOR,
                            max_cycles=min(2 * len(sol.residual_history) + 10, 200))
            sol3, hz3 = _solve_once(problem, hoil, tight, hz.coarse_theta, hz.exact, guess=guess)
            # the tighter solve counts when it meets the requested tolerances, even short of
            # its own (measured, second-order wedge, (179, 4.17) 257^2, Hoil = 1.5 Hc_ff: 142
            # cycles end at a residual of 2.8e-10 with the imbalance 2.2e-5 -> 6.3e-7)
            met = (sol3.success or (sol3.status_name == "max_cycles" and len(sol3.residual_history)
                                    and sol3.residual_history[-1] < opt.tol
                                    and abs(sol3.load_error_history[-1]) < opt.tol_load))
            mb3 = imbalance_of(hz3) if met else math.inf
            keep = mb3 < mb
            what = (f"mass imbalance {mb:.2g} at tol {opt.tol:.3g}: re-solved with tol {tight.tol:.3g}: "
                    f"{sol3.status_name}")
            if met and not sol3.success:
                what += f" at a residual of {sol3.residual_history[-1]:.2g} (within tol {opt.tol:.3g})"
            what += f", imbalance {mb3:.2g}; kept the {'second' if keep else 'first'}"
            if keep and not sol3.success:
                sol3.set_status(0, "")
                tight = replace(tight, tol=opt.tol)  # what the kept solve meets
            sol, hz = _kept((sol, hz), (sol3, hz3), keep, what)
            opt = tight if keep else opt
    fine = hz.levels[-1]
    sol.contact, sol.solver, sol.problem, sol.options = "point", "starved-fas", problem, opt
    sol.X, sol.Y, sol.P, sol.H = fine.X, fine.Y, fine.P.copy(), fine.H.copy()
    sol.H0, sol.half, sol.levels = hz.H00, opt.half, len(hz.levels)
    row = 0 if opt.half else (fine.ny - 1) // 2
    fl, imbalance = boundary_flows(hz)
    width = float(balance_rows(fine.ny, opt.half)[1].sum()) * fine.hy
    i0 = int(np.argmin(np.abs(fine.X)))
    sol.extra.update(theta=fine.theta.copy(), rho=fine.rho.copy(), hoil=hz.hoil,
                     hoil_rows=hz.hoil_rows.copy(), hoil_centre=float(hz.hoil_rows[row]),
                     meniscus_x=meniscus_x(fine.X, fine.theta, row),
                     mass_balance_error=imbalance, fluxes=fl,
                     outlet_layer=fl["out"] / width if math.isfinite(hz.hoil) else math.nan,
                     rho_c=float(fine.rho[row, i0]), domain=(hz.xmin, hz.xmax, hz.ymax),
                     coarse_theta=hz.coarse_theta, rescued=rescued, from_guess=guess is not None,
                     exact_zone=hz.exact)
    sol.builder = build_result
    sol.scalars = dict(build_result(sol, None, fields=False).scalars)
    sol.scalars.update(meniscus_x=sol.extra["meniscus_x"],
                       mass_balance_error=sol.extra["mass_balance_error"])
    if math.isfinite(hz.hoil):
        # a result that does not conserve mass is not a starved solution, whatever its iteration
        apply_mass_gate(sol, sol.extra["mass_balance_error"],
                        supply_ratio(sol.extra["rho_c"], float(sol.scalars["Hc_venner"]), float(hz.hoil_rows[row])))
    sol.scalars["converged"] = bool(sol.success)
    sol.options = replace(sol.options, raise_on_failure=asked)
    if asked and not sol.success:
        raise ConvergenceError(f"starved point solver: {sol.message}", sol.report, HINT)
    return sol


#: finest grid of a scene solve without ``points`` (the coarser estimate solve uses half of it)
SCENE_POINTS = 257
#: largest grid an accuracy target refines a starved point solve to (513^2 half domain: about
#: 4x the 257^2 cost, 10-40 s on the shared 2-core machine; ``max_points`` raises it)
SCENE_MAX_POINTS = 513
#: statuses of a solve whose films enter an estimate: its iteration converged (its own accuracy
#: verdict does not matter)
ESTIMATE_STATUSES = ("converged", "inaccurate")
#: the coarsest grid whose film enters the three-grid estimate (:func:`starved_point_error`)
COARSEST_ESTIMATE_POINTS = 65
#: an accuracy-driven solve that ends at its relaxation's residual floor (above
#: ``STARVED_TOL``) counts as converged where its films spread by less than this fraction of
#: the target over the last cycles and it conserves mass to ``MASS_TOL`` (:func:`_accept_floor`)
FLOOR_FILM_FRACTION = 0.01


def _accept_floor(res: EHLResult, accuracy: float | None) -> EHLResult:
    """``res`` converged where it stopped at its residual floor with its films still to
    :data:`FLOOR_FILM_FRACTION` of ``accuracy`` over the last cycles and the mass balanced to
    :data:`MASS_TOL`; the spread then joins the algebraic error (``extra["floor_spread"]``).
    Appendix D with a 50 nm layer (M 216, L 8.9) stopped at a residual of 2.95e-8 against
    1e-8 with films moving by 5e-10 / 2e-9 per cycle and a mass imbalance of 1.3e-7, and was
    reported as a failure (docs/starvation.md, "Residual floor")."""
    if accuracy is None or res.status_name != "residual_floor":
        return res
    spread = floor_film_spread(res.history)
    mb = float(res.extra.get("mass_balance_error", math.inf))
    if spread is None or not (math.isfinite(spread["Hc"]) and math.isfinite(spread["Hm"])):
        return res
    if max(spread["Hc"], spread["Hm"]) >= FLOOR_FILM_FRACTION * accuracy or not mb <= MASS_TOL:
        return res
    r = float(res.residual_history[-1]) if len(res.residual_history) else math.nan
    res.set_status(0, "converged")
    if "converged" in res.scalars:
        res.scalars["converged"] = True
    res.extra["floor_spread"] = {"Hc": spread["Hc"], "Hm": spread["Hm"]}
    res.actions.append(f"the residual stopped at {r:.3g}, above the tolerance, with the films "
                       f"within {spread['Hc']:.2g} (Hc) and {spread['Hm']:.2g} (Hm) over the last "
                       f"cycles and a mass imbalance of {mb:.2g}: accepted as converged, the spread "
                       "counted in the algebraic error")
    return res


#: side outflow (relative to the inflow) above which the box's side boundary Y = ymax is
#: taken to shape the solution (domain error unknown)
SIDE_FLOW_LIMIT = 1e-4
#: what the result says about the discretisation order
ORDER_NOTE = ("the starved point solver is first order in the wedge term: its flooded Hc lies "
              "2-8 % above the core's second-order film on the same grid; Hc_flooded and the "
              "ratios use its own flooded film")
#: the same for the second-order wedge (``wedge_order = 2``)
ORDER_NOTE_2 = ("the starved point solver's wedge term is second order where the film is full (first "
                "order at the meniscus and in the cavitated outlet): its flooded film is the core's "
                "second-order film; Hc_flooded and the ratios use it")

#: grid order (Hc, Hm) per wedge order assumed by the two-grid Richardson estimate of
#: :func:`starved_point_error`: first order for both wedges, since a second-order estimate
#: misses the error on the chapter-6 scene and in Hm (docs/starvation.md, "Solver defaults").
GRID_ORDER = {1: (1.0, 1.0), 2: (1.0, 1.0)}


def order_note(order: int) -> str:
    """What a result says about its wedge discretisation."""
    return ORDER_NOTE if int(order) == 1 else ORDER_NOTE_2


#: how many times faster than the scheme's ``2^p`` the differences of three grids must fall for
#: the last one to count as small by accident (:func:`_grid_term`; the default scene's 100 and
#: 300 nm layers that set it: docs/starvation.md)
ACCIDENT_RATIO = 4.0


def _same_minimum(fine: Any, coarse: Any, coarser: Any) -> bool:
    """Does the minimum film lie at the same place on the three grids: within two cells (of the
    coarsest grid) of the finest grid's minimum? A wide contact's Hm can move from the side edge
    to the centre as the grids resolve them (the 6205 with a 50 nm layer: at Y = 9.2 a on 129
    and 257 points, at the centre on 513), and the coarser films are then of another minimum.
    True where the places are not known."""
    places = [(r.scalars.get("X_Hm"), r.scalars.get("Y_Hm")) for r in (fine, coarse, coarser)]
    X, Y = getattr(coarser, "X", None), getattr(coarser, "Y", None)
    if any(x is None or y is None for x, y in places) or X is None or Y is None or len(X) < 2 or len(Y) < 2:
        return True
    hx, hy = abs(X[1] - X[0]), abs(Y[1] - Y[0])
    x0, y0 = places[0]
    return all(abs(x - x0) <= 2.0 * hx and abs(abs(y) - abs(y0)) <= 2.0 * hy for x, y in places[1:])


def _grid_term(f: float, c: float, cc: float | None, p: float, same: bool = True) -> float:
    """Absolute grid error of the film ``f`` from the films ``c`` and ``cc`` of the grids with
    half and a quarter of the intervals, order ``p`` assumed: Richardson ``|d2|/(2^p - 1)``;
    where the differences fall more slowly than ``2^p`` per grid (ratio ``r = d1/d2`` below it)
    the observed ratio continued, ``|d2|/(r - 1)``; where they change sign (the films swing
    about a limit not yet in reach) the span of both swings, ``|d1| + |d2|``. No bound (inf)
    where two grids are all there is (``cc`` None) and where the differences do not fall. The
    default scene with a 200 nm layer, Hc on 65/129/257/513/1025 points 0.06445, 0.06610,
    0.06525, 0.06428, 0.06362 (a sign change, then ratio 1.49): the 257-point film lies more than
    2.5 % (about 4.8 % at the observed ratio) from its limit, where half the difference before,
    or the two-grid first-order term, gives 1.96 % and the span 3.9 % (5.8 % with the safety
    factor). Where the differences of one quantity (``same``: for Hm, a minimum at the same
    place on the three grids, :func:`_same_minimum`) fall more than :data:`ACCIDENT_RATIO`
    times faster than ``2^p``, at least half the difference before: the same scene with 300 nm,
    Hm on 65/129/257 points 0.029481, 0.033516, 0.033583 (ratio 60, the minimum at the side
    lobe on each) stated 0.30 % on 257 points, where 513 and 1025 points give 0.033359 and
    0.033083, at least 1.5 % away."""
    d2 = f - c
    if cc is None:
        return math.inf
    d1 = c - cc
    if d1 != 0.0 and d2 != 0.0 and (d1 > 0) == (d2 > 0):
        r = d1 / d2
        if r <= 1.0:
            return math.inf  # the differences do not fall: no bound
        if r < 2.0**p:
            return abs(d2) / (r - 1.0)
        if r > ACCIDENT_RATIO * 2.0**p and same:
            # falling far faster than the scheme's order: the last difference may be small by
            # accident (a pre-asymptotic coarsest grid), so at least half the one before
            return max(abs(d2) / (2.0**p - 1.0), 0.5 * abs(d1))
        return abs(d2) / (2.0**p - 1.0)
    return abs(d1) + abs(d2)


def starved_point_error(fine: EHLResult, coarse: EHLResult | None,
                        coarser: EHLResult | None = None) -> ErrorEstimate:
    """Error estimate of a starved point solve (relative, Hc and Hm).

    * grid: Richardson from ``coarse`` (the same supply on the grid with half the intervals)
      to ``fine`` with the order of the solve's wedge discretisation (:data:`GRID_ORDER`), or
      the observed ratio of the differences where ``coarser`` (a quarter of the intervals)
      shows them falling more slowly, at least half the difference before where they change
      sign (:func:`_grid_term`), times the core's safety factor ``GRID_SAFETY`` (1.5); without
      a converged coarse solve, unknown (NaN). The first-order wedge's films converge at
      observed orders 0.5-1.2 on fine grids (the report's 20 nm ball: Hm ratios 1.43, 1.41 on
      1025-4097 points, where a first-order two-grid estimate stated 0.37 % at 1025 for a true
      0.42-0.6 %; docs/starvation.md, "Three grids");
    * algebraic: the last finest-grid change of the film times the contraction factor, the
      load error times the core's film sensitivity, plus the relative mass imbalance (in the
      starved limit the film carries the supply, so a mass error is a film error);
    * domain: 0 when the film is unfilled at the inlet boundary in every row (the boundary
      carries only the supplied layer at zero pressure) and the side outflow is below
      :data:`SIDE_FLOW_LIMIT`; otherwise unknown (NaN).
    """
    Hc, Hm = float(fine.scalars["Hc_venner"]), float(fine.scalars["Hm_venner"])
    order = int(fine.options.wedge_order)
    notes = [order_note(order)]
    # the coarse solve's iteration must have converged; its own accuracy verdict does not
    # matter (a refinement step passes the previous, 'inaccurate' solve as the coarse one)
    ok = ESTIMATE_STATUSES
    if coarse is not None and coarse.status_name in ok:
        pc, pm = GRID_ORDER[order]
        three = coarser is not None and coarser.status_name in ok
        if not three:
            notes.append("no converged solve two grids below: grid error unknown")
        cc = {k: float(coarser.scalars[k]) if three else None for k in ("Hc_venner", "Hm_venner")}
        grid = {"Hc": GRID_SAFETY * _grid_term(Hc, float(coarse.scalars["Hc_venner"]), cc["Hc_venner"], pc) / abs(Hc),
                "Hm": GRID_SAFETY * _grid_term(Hm, float(coarse.scalars["Hm_venner"]), cc["Hm_venner"], pm,
                                               same=not three or _same_minimum(fine, coarse, coarser)) / abs(Hm)}
        xc = Hc + (Hc - float(coarse.scalars["Hc_venner"])) / (2.0**pc - 1.0)
    else:
        grid = {"Hc": math.nan, "Hm": math.nan}
        xc = math.nan
        notes.append("no converged solve on the coarser grid: grid error unknown")
    top = fine.levels - 1
    fin = [h for h in fine.history if h.level == top]
    le = abs(float(fine.load_error_history[-1])) if len(fine.load_error_history) else math.inf
    mb = float(fine.extra["mass_balance_error"])
    if len(fin) >= 2:
        alg = {"Hc": iteration_error([h.Hc for h in fin]) / abs(Hc),
               "Hm": iteration_error([h.Hm for h in fin]) / abs(Hm)}
    else:
        alg = dict(grid)
    floor = fine.extra.get("floor_spread", {})
    alg = {k: v + LOAD_SENSITIVITY * le + mb + floor.get(k, 0.0) for k, v in alg.items()}
    theta = fine.extra["theta"]
    fl = fine.extra["fluxes"]
    side = abs(fl["side"]) / max(abs(fl["in"]), 1e-300)
    j0 = 0 if fine.half else 1
    inlet_dry = bool(np.all(theta[j0:-1, 1] < 1.0))
    if inlet_dry and side < SIDE_FLOW_LIMIT:
        dom = {"Hc": 0.0, "Hm": 0.0}
        notes.append("meniscus inside the box and no side outflow: no domain error")
    else:
        dom = {"Hc": math.nan, "Hm": math.nan}
        notes.append("the film fills the gap at the inlet boundary (flooded inlet) or oil leaves "
                     f"through the side boundary ({side:.2g} of the inflow): domain error not measured")
    budget = {"grid": grid, "domain": dom, "algebraic": alg}
    tot = {k: grid[k] + alg[k] + dom[k] for k in ("Hc", "Hm")}
    return ErrorEstimate(tot["Hc"], tot["Hm"], budget, math.nan, math.nan, xc, notes)


def starved_point_result(sol: EHLResult, scene: Any = None) -> Any:
    """Package :class:`~ehl_multigrid.model.results.Result` (kind ``"ehl_point"``) with the
    film content ``theta`` beside ``P`` and ``H`` and the starved scalars."""
    from ..point.postprocess import full_fields

    res = build_result(sol, scene, {k: sol.scalars[k] for k in SCENE_KEYS if k in sol.scalars})
    _, Tf, _ = full_fields(sol.X, sol.Y, sol.extra["theta"], sol.H, sol.half)
    res.add_field("theta", Tf.T.copy(), "-", ("X", "Y"), "film content (Elrod-Adams)")
    res.meta["starved_notes"] = order_note(sol.options.wedge_order)
    return res


#: starved scalars of a scene solve, in the payload of ``ehl solve`` and in the saved result
SCENE_KEYS = ("Hc_flooded", "Hm_flooded", "Hc_flooded_venner", "Hm_flooded_venner", "Hc_ratio",
              "Hm_ratio", "meniscus_x", "mass_balance_error", "hoil", "hoil_venner",
              "outlet_layer", "rho_c_Hc_over_hoil", "side_flow", "wedge_order", "flooded_status")


def starved_point_payload(sol: EHLResult, res: Any) -> dict[str, Any]:
    """JSON payload of ``ehl solve`` for a starved point scene: the point payload of ``res``
    plus :data:`SCENE_KEYS` and the note on the wedge order."""
    from ..point.postprocess import summary_payload

    out = summary_payload(res)
    out.update({k: sol.scalars[k] for k in SCENE_KEYS if k in sol.scalars})
    out["note"] = order_note(sol.options.wedge_order)
    return out


def _scene_solve(pb: PointProblem, Hoil: float, options: PointOptions | None, points: int,
                 kw: dict[str, Any], start: EHLResult | None = None) -> EHLResult:
    """One solve of a scene's sequence; from the converged solve ``start`` of a coarser grid
    (its coarse-grid theta rule, cycles from its solution) when given.

    A refinement starts from the previous grid's film when the FMG fails on the finer grid, or
    failed on the previous one (the exact zone solve rescued it there): there the finer FMG can
    diverge while the start from the coarser film converges; where the FMG converges nothing
    changes (docs/starvation.md, "Solver defaults")."""
    if start is None:
        return solve_starved_point(pb, Hoil, options, points=points, **kw)
    return solve_starved_point(pb, Hoil, options, start.extra["coarse_theta"], points=points,
                               guess=(start.X, start.Y, start.P, start.H0), **kw)


#: supply fractions of a continuation in the supply (:meth:`_StarvedPointControl._continued`),
#: tried in turn for its first film: a thinner layer converges where the layer does not (the
#: meniscus nearer the contact, the Poiseuille-dominated inlet shorter)
CONTINUATION_FRACTIONS = (0.5, 0.25)
#: most solves of a continuation after its first film
CONTINUATION_STEPS = 3
#: finest grid a continuation is tried on: finer grids start from its film, and its failed
#: ladders cost 15-20 s per exact zone solve on 513 points (6205, 150 nm)
CONTINUATION_MAX_POINTS = 257


def _finite_layer(Hoil: Any) -> bool:
    """Is the supply a layer, not a flooded inlet: a profile across the track (a function of
    ``Y``) or a number or array with a finite value somewhere?"""
    return callable(Hoil) or bool(np.any(np.isfinite(np.asarray(Hoil, dtype=float))))


def _scaled_layer(Hoil: Any, f: float) -> Any:
    """The supply ``Hoil`` (a number, a profile across the track or a function of ``Y``)
    times ``f``."""
    if callable(Hoil):
        return lambda Y: f * Hoil(Y)
    return f * Hoil if np.ndim(Hoil) == 0 else f * np.asarray(Hoil, dtype=float)


def _hard_for_fmg(res: EHLResult) -> bool:
    """Did ``res`` need more than the FMG of the default coarse-grid rule: the exact zone solve
    (kept or rescuing) or a start from a neighbouring grid's film? Its neighbours then start
    from its film (:meth:`_StarvedPointControl.solve`, ``coarse_of``)."""
    return bool(res.extra.get("rescued") or res.extra.get("exact_zone") or res.extra.get("from_guess")
                or res.extra.get("continued"))


def _start_from(res: EHLResult) -> bool:
    """Do ``res``'s neighbours start from its film? Where the FMG needed help for it
    (:func:`_hard_for_fmg`) and its iteration got near a solution: converged, or stopped at its
    residual floor or cycle limit with a finite pressure (the start is only a first iterate;
    the neighbour is judged on its own iteration)."""
    near = res.success or res.status_name in ("residual_floor", "max_cycles")
    return (near and _hard_for_fmg(res) and res.P is not None and bool(np.all(np.isfinite(res.P)))
            and math.isfinite(res.H0))


class _StarvedPointControl(StarvedControl):
    """A starved point scene solve under the accuracy controller: the grid is the one
    refinement (the meniscus lies inside the box), estimated by :func:`starved_point_error`
    from the grids with half and a quarter of the intervals; a refinement starts from the
    previous grid's film (:func:`_scene_solve`)."""

    dimensions = 2
    raise_hint = " (--max-points of ehl run or ehl solve raises it)"
    not_worth = "a finer grid is not predicted to lower the error by 10 %: the iteration part dominates"

    def __init__(self, pb: PointProblem, Hoil: Any, options: PointOptions | None, kw: dict[str, Any],
                 accuracy: float | None, estimate: bool, max_points: int) -> None:
        super().__init__(accuracy, estimate, max_points)
        self.pb, self.Hoil, self.options, self.kw = pb, Hoil, options, kw
        self.prev: EHLResult | None = None  # the previous grid's converged result
        self.solved: dict[int, EHLResult] = {}  # the sequence's solves by points

    def solve(self, at: Resolution) -> EHLResult:
        prev, n = self.prev, at.points
        if prev is None and self.with_estimate:
            prev = self._below(n)
        # a refinement starts from the previous grid's film (see _scene_solve) when the FMG
        # needed help there (_hard_for_fmg), or when the FMG fails here
        res = self._solve(n, prev if prev is not None and _hard_for_fmg(prev) else None)
        if prev is not None and not res.success and not res.extra.get("from_guess"):
            first = f"{res.status_name} from the FMG"
            res = self._solve(n, prev)
            res.actions.insert(0, f"{n} points: {first}; solved again from the "
                                  f"{prev.X.size}-point film")
        if not res.success:
            res = self._continued(n, res)
        self.solved[n] = res  # a failed one too: the estimate of the next grid does not repeat it
        return res

    def _below(self, n: int) -> EHLResult | None:
        """The first grid's estimate grids, solved before it, coarsest first, each from the
        film below where the FMG needed help there (appendix D with a 50 nm layer: the FMG
        ladder of its first grid, 257 points, costs 8 s; 65 and 129 points 0.5 s, then 257
        from the 129-point film 0.6 s). Returns the grid with half the intervals of ``n``
        (None when ``n`` has no estimate grids)."""
        grids = [m for m in ((n - 1) // 4 + 1, (n - 1) // 2 + 1) if m >= COARSEST_ESTIMATE_POINTS]
        if len(grids) < 2:
            return None
        below = None
        for m in grids:
            if m not in self.solved:
                self.solved[m] = self._solve_near(m, below)
            below = self.solved[m]
        return below if _start_from(below) else None

    def _solve_near(self, n: int, neighbour: EHLResult | None) -> EHLResult:
        """The grid of ``n`` points from ``neighbour``'s film where :func:`_start_from` says
        so, the FMG ladder otherwise or when that start fails; by continuation in the supply
        (:meth:`_continued`) when both fail."""
        if neighbour is None or not _start_from(neighbour):
            res = self._solve(n)
        else:
            res = self._solve(n, neighbour)
            if not res.success:
                res = self._solve(n)
        return res if res.success else self._continued(n, res)

    def _continued(self, n: int, failed: EHLResult) -> EHLResult:
        """The grid of ``n`` points (at most :data:`CONTINUATION_MAX_POINTS`) by continuation
        in the supply: a thinner layer (:data:`CONTINUATION_FRACTIONS` of it, the first that
        converges), then the layer from that film; a step that fails is halved (in the log of
        the layer) and the layer tried again from the film it reached, at most
        :data:`CONTINUATION_STEPS` steps. The 6205 inner race with a 100 nm layer
        (Hoil/Hc_flooded about 0.6) ends at a residual floor with a mass imbalance of 7-9 from
        the FMG and at max_cycles from the exact zone solves on 129 points; 50 nm converges
        there, and 100 nm from its film in 41 cycles (0.2 s). ``failed`` comes back, with the
        attempt in its actions, when the layer is not reached."""
        if n > CONTINUATION_MAX_POINTS or not _finite_layer(self.Hoil):
            return failed
        tried: list[str] = []
        for f in CONTINUATION_FRACTIONS:
            film = self._solve(n, Hoil=_scaled_layer(self.Hoil, f))
            tried.append(f"{f:.0%} of the layer: {film.status_name}")
            if film.success:
                break
        else:
            failed.actions.append(f"continuation in the supply on {n} points: {'; '.join(tried)}")
            return failed
        goal = 1.0
        for _ in range(CONTINUATION_STEPS):
            res = self._solve(n, film, Hoil=None if goal == 1.0 else _scaled_layer(self.Hoil, goal))
            tried.append(f"{goal:.0%} from the {f:.0%} film: {res.status_name}")
            if res.success and goal == 1.0:
                res.actions.insert(0, f"{n} points: {failed.status_name} from the FMG and the exact "
                                      f"zone solves; by continuation in the supply ({'; '.join(tried)})")
                res.extra["continued"] = True
                return res
            if res.success:
                film, f, goal = res, goal, 1.0
            else:
                goal = math.sqrt(f * goal)
        failed.actions.append(f"continuation in the supply on {n} points: {'; '.join(tried)}")
        return failed

    def _solve(self, n: int, start: EHLResult | None = None, Hoil: Any = None) -> EHLResult:
        return _accept_floor(_scene_solve(self.pb, self.Hoil if Hoil is None else Hoil, self.options, n,
                                          self.kw, start), self.accuracy)

    def remedy(self, result: EHLResult, at: Resolution, first: bool) -> Resolution | None:
        # a failed first grid coarser than the flooded solver's smallest for this load: the
        # chapter-6 1.93 GPa ball (M 10282) with a 50 nm layer has a negative film on 257
        # points (mass_not_conserved) and a film on 513; the 6205 inner race (M 3620) converges
        # on 257 and fails by FMG on 513, so the start stays 257 (docs/starvation.md)
        finer = at.finer()
        if first and finer.points <= self.max_points and at.points < min_points(self.pb.M, self.pb.b_over_a):
            return finer
        return None

    def coarse_of(self, points: int, record: Any = None) -> EHLResult:
        """The solve on the grid with half the intervals of ``points`` (made once)."""
        n = (points - 1) // 2 + 1
        if n not in self.solved:
            # from the finer grid's film where the FMG needed help there, as a refinement
            # does (appendix D, 50 nm, 129 points: 0.2 s, its FMG ladder 1.6 s)
            self.solved[n] = self._solve_near(n, self.solved.get(points))
            if record is not None:
                record(Refinement(n, 1.0, 1.0, math.nan, math.nan, self.solved[n].wall_s, "levels"))
        return self.solved[n]

    def coarser_of(self, points: int, record: Any = None) -> EHLResult | None:
        """The solve on the grid with a quarter of the intervals of ``points`` (made once;
        None below :data:`COARSEST_ESTIMATE_POINTS`)."""
        n = (points - 1) // 4 + 1
        if n < COARSEST_ESTIMATE_POINTS:
            return None
        return self.coarse_of((points - 1) // 2 + 1, record)

    def estimate(self, res: EHLResult, at: Resolution, record: Any) -> tuple[float, float]:
        self.prev = res
        if not self.with_estimate:
            return math.nan, math.nan
        self.solved[at.points] = res  # the coarse solve of the next grid
        coarse, coarser = self.coarse_of(at.points, record), self.coarser_of(at.points, record)
        if coarser is not None and coarser.status_name not in ESTIMATE_STATUSES \
                and coarse.status_name in ESTIMATE_STATUSES:
            # without the third grid the grid error is unknown: the quarter grid again, from
            # the half grid's converged film
            n = (at.points - 1) // 4 + 1
            again = self._solve(n, coarse)
            if again.status_name in ESTIMATE_STATUSES:
                self.solved[n] = coarser = again
        est = starved_point_error(res, coarse, coarser)
        attach_estimate(res, est, self.accuracy)
        return est.Hc, est.Hm

    def predicted(self, res: EHLResult, b: dict[str, dict[str, float]]) -> float:
        if any(math.isinf(b["grid"][k]) for k in ("Hc", "Hm")):
            return math.nan  # differences that do not fall yet: the finer grid measures on
        pc = GRID_ORDER[int(res.options.wedge_order)][0]
        return max(b["grid"][k] / 2.0**pc + b["algebraic"][k] + b["domain"][k] for k in ("Hc", "Hm"))


def solve_starved_point_scene(scene: Any, hoil: float | None = None, options: PointOptions | None = None,
                              *, flooded: bool = True, viscosity: str = "roelands",
                              density: str = "dowson-higginson", accuracy: float | None = None,
                              estimate: bool = True, max_points: int = SCENE_MAX_POINTS,
                              time_budget: float = math.inf,
                              progress: Callable[[str], None] | None = None, **kw: Any) -> EHLResult:
    """Starved point (circular) contact of a point-contact ``scene`` at its operating point,
    supplied with the scene's ``[supply] hoil`` [m] (or ``hoil`` [m]): ``Hoil = hoil Rx/a^2``.

    With ``flooded`` the flooded film of the same discretisation is solved too (scalars
    ``Hc_flooded``, ``Hm_flooded`` (Moes, as ``Hc``), ``Hc_ratio``, ``Hm_ratio``). Films in
    metres: ``hc``, ``hm``; ``hoil`` [m]. Solved on the half domain Y >= 0 by default (the
    contact is symmetric); keywords are :class:`PointOptions` fields (default grid
    :data:`SCENE_POINTS`).

    With ``estimate`` the same supply is also solved on the grid with half the intervals and
    the result carries ``Hc_error``, ``Hm_error`` (:func:`starved_point_error`); ``accuracy``
    (relative) judges them (status ``"inaccurate"`` when missed) and, without an explicit
    ``points``, refines the grid up to ``max_points`` until they meet it; ``progress(text)``
    receives one line per solve of that sequence.

    The wedge order (:data:`STARVED_WEDGE_ORDER` by default) is the keyword ``wedge_order``
    or, without it, the scene's ``[solver.ehl]`` ``wedge_order`` (or ``order``).
    """
    from ..point.problem import problem_from_scene
    from .supply import hoil_venner, layer_across_track

    pb = problem_from_scene(scene, viscosity=viscosity, density=density)
    h_m = scene.supply.hoil if hoil is None else hoil
    Hoil: Any = hoil_venner(h_m, pb.a, pb.Rx)
    if hoil is None and scene.supply.hoil_profile:
        Hoil = layer_across_track(scene.supply, pb.a, pb.Rx)
    if accuracy is not None:
        require_range("accuracy", accuracy, 1e-5, 0.5, "- (relative error)")
    require_range("max_points", max_points, 65, 65537, "points")
    kw.setdefault("half", True)
    if options is None and "wedge_order" not in kw and "order" not in kw:
        # the scene's [solver.ehl] wedge order (``wedge_order`` or ``order``) selects the
        # starved wedge too; the other keys of that table are the flooded solver's
        from ..multigrid.options import scene_solver_table

        table = scene_solver_table(scene, "point")[1]
        for key in ("wedge_order", "order"):
            if key in table:
                kw["wedge_order"] = table[key]
                break
    explicit = "points" in kw or options is not None
    n = int(kw.pop("points", options.points if options is not None else SCENE_POINTS))
    starved = _StarvedPointControl(pb, Hoil, options, kw, accuracy, estimate, max_points)
    out = control(starved, Resolution(n), accuracy, refine=estimate and not explicit,
                  max_points=max_points, progress=progress, time_budget=time_budget)
    res = out.result
    if not out.converged and estimate:
        # a failed solve still states what its estimate would be (the coarse grid's difference)
        attach_estimate(res, starved_point_error(res, starved.coarse_of(n), starved.coarser_of(n)), accuracy)
    elif out.converged and out.why:
        note_not_refined(res, out, action=True)
    scale = pb.a**2 / pb.Rx
    fl = res.extra["fluxes"]
    Hoil_c = Hoil(0.0) if callable(Hoil) else Hoil  # the centre's layer
    res.scalars.update(hoil=h_m, hoil_venner=Hoil_c, hc=res.scalars["Hc_venner"] * scale,
                       hm=res.scalars["Hm_venner"] * scale, rho_c_Hc_over_hoil=supply_ratio(res.extra["rho_c"], res.scalars["Hc_venner"], Hoil_c),
                       outlet_layer=res.extra["outlet_layer"],
                       side_flow=fl["side"] / fl["in"] if fl["in"] else math.nan,
                       wedge_order=int(res.options.wedge_order))
    if flooded:
        ff = solve_starved_point(pb, math.inf, res.options)
        Hc_ff, Hm_ff = ff.scalars["Hc_venner"], ff.scalars["Hm_venner"]
        compare_flooded(res.scalars, Hc_ff, Hm_ff, Hc_ff * pb.moes_factor, Hm_ff * pb.moes_factor)
        res.scalars["flooded_status"] = ff.status_name
    res.scalars["converged"] = bool(res.success)
    res.builder = starved_point_result
    return res
