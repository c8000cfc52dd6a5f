"""The point- and elliptic-contact EHL problem on the shared multilevel driver.

:class:`PointHierarchy` is the point contact's grid hierarchy for
:class:`~ehl_multigrid.multigrid.driver.MultilevelSolver`: Venner-style zebra line relaxation
along X (Gauss-Seidel where ``eps/hx^2 >= switch``, Jacobi-distributive elsewhere), injection
of P and full weighting of residuals, bilinear coarse-grid corrections, cubic FMG
interpolation, the film constant H00 (one for all grids) moved by the FAS load error on the
coarsest grid. Contacts long in the rolling direction (b/a < 0.5) alternate the X-line sweep
with a Y-line sweep, the alternating-direction line relaxation Venner & Lubrecht (2000,
"Multilevel methods in lubrication") recommend for strong coupling across the X lines; in
solves of >= 513 points along X other contacts alternate on their grids of >= 129 points, where
the resolved pressure spike's ridge runs obliquely to the X lines and couples them strongly. The
deformation is recomputed after every sweep by the selected O(N log N) path; coarse grids run
on one thread.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np

from ..model.errors import InputError
from ..model.fits import nijenbanning_central
from ..multigrid.driver import Measurement, MultilevelSolver
from ..multigrid.options import PointOptions
from ..multigrid.policy import PolicyParameters, RobustnessPolicy, Settings
from ..multigrid.threads import ThreadBudget, resolve_threads
from . import numerics as nm
from .deformation import cell_kernel, make_deformation
from .farfield import boundary_excess, far_field_for, far_field_on
from .farfield_angular import hertz_central_deformation
from .postprocess import subgrid_min_film
from .problem import (
    WIDE_CONTACT,
    PointProblem,
    coarse_intervals,
    domain_scale,
    resolve_domain,
    rigid_coarse_intervals,
    rigid_film,
    rigid_film_length,
    rigid_length,
)

HINT = "raise max_cycles, use W cycles, a longer inlet, more points or fewer levels"

#: Cycle acceptance and ladders of the point solver, tuned on its robustness set; ``quiet_below``
#: ends a residual wandering below 1e-5 as ``residual_floor`` instead of stirring it into a
#: divergence (docs/robustness.md, "Point solver defaults").
POINT_POLICY = PolicyParameters(
    growth=3.0, growth_window=None, residual_cap=math.inf, quiet_below=1e-5, load_cap=0.3, load_factor=0.0,
    first_load_error=0.0, max_retries=8, stall_window=4, stall_factor=0.95**3,
    reject_ladder=(("alternate",), ("switch",), ("halve", "W")),
    stall_ladder=(("alternate",), ("switch",), ("halve", "W")),
    cyclic_reject=True, cyclic_stall=True, shared_ladder=True, floors=(0.1, 0.05, 1e-3),
    recover=1.0)


#: Contacts with b/a below this relax X lines and Y lines alternately: X lines alone diverge or
#: stall on narrow contacts, while at b/a = 0.64 alternation only costs work (docs/robustness.md).
ALTERNATE_BELOW = 0.5
#: Wider contacts alternate in solves of at least ALTERNATE_FINEST points along X, on their grids
#: of at least ALTERNATE_FROM points, where the resolved spike's oblique ridge couples the X lines;
#: smaller solves converge with X lines alone at less work (docs/robustness.md).
ALTERNATE_FROM = 129
ALTERNATE_FINEST = 513
#: Grids from LOCAL_UPDATE_FROM to LOCAL_UPDATE_TO points along X refresh the film between an
#: alternating sweep's X and Y halves locally (:func:`numerics.local_film_update`), at the same
#: statuses and work as a whole deformation; 2049 points stall with it (docs/robustness.md).
LOCAL_UPDATE_FROM = 257
LOCAL_UPDATE_TO = 1025
#: ``Y_OMEGA_JD`` of those fine-grid alternations (narrow contacts keep their tuned value): at
#: 2049^2 0.75 leaves the residual at 1.3e-5, 0.5 reaches 1.4e-6; raising ``Y_OMEGA`` to 1
#: instead diverges (docs/robustness.md).
FINE_Y_OMEGA_JD = 0.5
#: Y sweep's treatment of the points with ``eps/hx^2 < switch`` (``relax_sweep_y``'s ``jd_mode``):
#: Gauss-Seidel (0); leaving them to the X sweep (1) or Jacobi-distributive changes along Y (2)
#: diverge or stall narrow contacts (docs/robustness.md).
Y_JD_MODE = 0
#: Under-relaxation of the Y sweep's changes: ``Y_OMEGA omega`` where ``eps/hx^2 >= switch``,
#: ``Y_OMEGA_JD omega_jd`` elsewhere (0.3 and 0.225 by default), the one pair tried that converges
#: all 14 narrow test contacts: a narrow window (docs/robustness.md).
Y_OMEGA = 0.5
Y_OMEGA_JD = 0.75


class Level:
    """One grid ``[j, i]`` (Y row, X column) with its iterate and FAS right-hand sides."""

    def __init__(self, nx: int, ny: int, hx: float, hy: float, X: np.ndarray, Y: np.ndarray,
                 defo: Any, Kc: np.ndarray, g: float, Ky: np.ndarray | None = None) -> None:
        self.nx, self.ny, self.hx, self.hy, self.X, self.Y = nx, ny, hx, hy, X, Y
        self.defo, self.Kc, self.g = defo, Kc, g
        self.Ky = Kc if Ky is None else Ky
        #: relax X lines and Y lines alternately on this grid
        self.alternate = False
        #: P before the X half of an alternating sweep (LOCAL_UPDATE_FROM)
        self.P_old: np.ndarray | None = None
        shape = (ny, nx)
        self.P = np.zeros(shape)
        self.H = np.zeros(shape)
        #: the elastic deformation; ``None`` where the film is built in place (every grid but
        #: the coarsest, whose load balance moves H00 on a fixed W: see
        #: :meth:`PointHierarchy.share_work_arrays`)
        self.W: np.ndarray | None = np.zeros(shape)
        self.rho = np.ones(shape)
        self.eps = np.zeros(shape)
        self.f = np.zeros(shape)
        #: scratch of a relaxation sweep (its distributive changes)
        self.D = np.zeros(shape)
        #: the residual, written by :meth:`PointHierarchy.residual`
        self.r = np.zeros(shape)

    @property
    def npts(self) -> int:
        return self.nx * self.ny

    @property
    def shape(self) -> tuple[int, int]:
        return (self.ny, self.nx)

    @property
    def spacing(self) -> tuple[float, float]:
        return (self.hy, self.hx)


#: Grids with a mesh ``hx`` (units of a) no larger than FINE_SWITCH_HX (the box [-4.5, 1.5] on 2049
#: points) relax with the switch times FINE_SWITCH_FACTOR; keyed on the mesh, so a widened box
#: keeps the switch its mesh was tuned with (docs/robustness.md, "Point solver defaults").
FINE_SWITCH_HX = 6.0 / 2048
FINE_SWITCH_FACTOR = 4.0


#: least relaxations per coarsest-grid visit of a rigid-surface solve, and at least twice its
#: intervals along X: its coarsest grid keeps 64 intervals or more (rigid_coarse_intervals),
#: which 10 sweeps leave far from solved (docs/robustness.md, "Rigid surfaces")
RIGID_COARSE_SWEEPS = 50


def sweep_switch(switch: float, hx: float) -> float:
    """The GS/JD switch a relaxation sweep uses on a grid of mesh size ``hx`` (units of a)."""
    return switch * FINE_SWITCH_FACTOR if hx <= FINE_SWITCH_HX * (1.0 + 1e-9) else switch


def default_switch(visc: int, alpha_bar: float, elastic: bool = True) -> float:
    """GS/Jacobi-distributive switch ``eps/hx^2``: 1 by default, 10 for strong pressure spikes
    (Barus alpha_bar >= 8, Roelands >= 20), 40 for Roelands alpha_bar >= 30.

    Each threshold is where the smaller switch stops converging (docs/robustness.md, "Point solver
    defaults")."""
    if not elastic:
        # no film response to the pressure for a distributive change to balance: the rigid
        # Reynolds equation is a diffusion problem, which Gauss-Seidel smooths everywhere
        return 0.0
    if visc == 1:
        return 10.0 if alpha_bar >= 8.0 else 1.0
    return 40.0 if alpha_bar >= 30.0 else (10.0 if alpha_bar >= 20.0 else 1.0)


def y_ratio(length_x: float, length_y: float, coarse_x: int, b_over_a: float = 1.0) -> float:
    """(points along Y - 1)/(points along X - 1): the power of 2 closest (in log) to
    ``length_y/length_x / (b/a)``, in [1/8, 8], leaving at least 4 intervals along Y on the
    coarsest grid (``coarse_x`` intervals along X): cells stretched with the ellipse,
    ``hy/hx ~ b/a``, since the film varies over ``a`` along X but over ``b`` along Y (on the
    default box, as many points along Y as along X).

    Contacts wider than long (``b/a > 1``, the ball-bearing ellipses): Y points do not move Hc in
    the fourth digit, at an eighth of the cost of square cells. Contacts long in the rolling
    direction (``b/a < 1``), whose minimum film sits in the side lobes near ``|Y| = b``: Hm
    converges with the cells across b, so these cells give the Hm of the next finer square grid
    at half its cost (docs/robustness.md, "Point solver defaults")."""
    r = 2.0 ** round(math.log2(length_y / length_x / b_over_a))
    r = min(max(r, 0.125, 4.0 / coarse_x), 8.0)
    return 2.0 ** math.ceil(math.log2(r) - 1e-12)


def load_integral(P: np.ndarray, hx: float, hy: float, half: bool) -> float:
    """``∫∫ P dX dY`` (trapezoid; P = 0 on the boundary); half domains count row 0 once."""
    if half:
        return hx * hy * (P[0].sum() + 2.0 * P[1:].sum())
    return hx * hy * P.sum()


def grid_layout(problem: PointProblem, opt: PointOptions,
                domain: tuple[float, float, float]) -> tuple[int, float]:
    """Number of grid levels and cell aspect ``y_ratio`` of a solve of ``problem`` with the
    options ``opt`` on ``domain = (xmin, xmax, ymax)``: the coarse intervals of
    :func:`~.problem.coarse_intervals` (or ``opt.n_coarse``/``opt.levels``), the aspect of
    :func:`y_ratio` (or ``opt.y_ratio``). Raises :class:`InputError` for a point count that
    does not coarsen."""
    xmin, xmax, ymax = domain
    n = int(opt.points)
    nc = opt.n_coarse
    if nc is None and not opt.elastic:
        nc = rigid_coarse_intervals(xmax - xmin, n, rigid_film_length(problem))
    elif nc is None:
        nc = coarse_intervals(problem.M, xmax - xmin, n, domain_scale(problem), rigid_length(problem),
                              problem.b_over_a)
    if opt.levels is not None:
        nlev = int(opt.levels)
        if (n - 1) % (2 ** (nlev - 1)) or (n - 1) // 2 ** (nlev - 1) < 4:
            raise InputError(
                f"points = {n} with levels = {nlev}: points - 1 must be divisible by 2^(levels-1) "
                f"and leave >= 4 intervals on the coarsest grid")
    else:
        if (n - 1) % nc:
            nc = 16 if (n - 1) % 16 == 0 else 8
        m = (n - 1) // nc
        if (n - 1) % nc or m & (m - 1):
            raise InputError(f"points = {n} must be 2^k * 16 + 1 (for example 65, 129, 257, 513, 1025)")
        nlev = int(round(math.log2(m))) + 1
    if (n - 1) % 2 ** (nlev - 1):
        raise InputError(f"points = {n} must be 2^k + 1")
    ratio = opt.y_ratio
    if ratio is None:
        ratio = y_ratio(xmax - xmin, 2.0 * ymax, (n - 1) // 2 ** (nlev - 1), problem.b_over_a)
    return nlev, ratio


class PointHierarchy:
    """Grids of one point-contact solve, coarsest first (protocol of the multilevel driver)."""

    name = "point"
    #: refresh the film locally between the X and Y halves of an alternating sweep on fine
    #: grids (:data:`LOCAL_UPDATE_FROM`); False in subclasses whose film or lubricant
    #: properties carry more than the core's (flow factors, moving geometry)
    local_update = True
    #: the policy's "alternate" step may switch this hierarchy's grids to X/Y alternation
    #: (False in subclasses whose own sweep relaxes X lines only)
    can_alternate = True
    #: the driver may stop on the grid rule (``options.grid_stop``): steady films only; False
    #: in subclasses whose convergence carries more than the films (mass balance, time step,
    #: flow factors)
    grid_stop = True
    #: the far-field boundary (point.farfield) may apply: the steady flooded solve only (False
    #: in subclasses whose inlet is a supplied layer, a time step or carries flow factors)
    far_field_ok = True

    def __init__(self, problem: PointProblem, options: PointOptions) -> None:
        self.pb = self.problem = problem
        xmin, xmax, ymax = resolve_domain(problem, options.xmin, options.xmax, options.ymax,
                                          options.elastic)
        self.xmin, self.xmax, self.ymax = xmin, xmax, ymax
        self.options = options
        self.threads = ThreadBudget(resolve_threads(options.threads), options.serial_below)
        self.par = problem.rheology()
        self.lam = problem.lam
        self.cd = problem.cd if options.elastic else 0.0
        self.theta = problem.theta
        self.boa = problem.b_over_a
        alt = options.alternating
        #: every grid alternates (narrow contacts, or ``alternating=True``); with
        #: ``alternating=None`` wider contacts alternate on grids of >= ALTERNATE_FROM points
        self.alternating = (self.boa < ALTERNATE_BELOW) if alt is None else bool(alt)
        self.sweep_work = 2.0 if self.alternating else 1.0
        self.g_target = problem.load
        #: far-field boundary values and the load beyond the box (point.farfield)
        if options.far_field and not self.far_field_ok:
            raise InputError(f"far_field = True is for the steady flooded point solver, not the "
                             f"{self.name} solver (its inlet boundary is not the undeformed gap's far field)")
        self.far = self.far_field_ok and far_field_on(options.far_field)
        #: the far field's ``c2 = 2 H00`` and ``k`` of its far deformation ``k/r`` (elastic: the
        #: deformation constant x load), and the far field itself (point.farfield)
        self.far_c2 = self.far_k = 0.0
        self.far_field = far_field_for(problem.theta) if self.far else None
        if self.far:
            self.far_k = self.cd * self.g_target
            # H00 = central film - the Hertzian pressure's central deformation (also for thick
            # films, where it holds (5, 5) closer to the wide box: docs/accuracy.md)
            d0 = self.cd * hertz_central_deformation(self.boa)
            self.far_c2 = 2.0 * (rigid_film(problem) if not options.elastic else
                                 float(nijenbanning_central(problem.M, problem.L, problem.theta))
                                 / problem.moes_factor - d0)
        #: squeeze coefficient of a BDF time step (the new-time part ``ct rho H`` of
        #: ``d(rho H)/dT``; the history part goes into the finest grid's ``f``); 0: steady
        self.ct = 0.0
        self.H00 = 0.0
        self.h00_step_max = math.inf
        self.gain = math.nan
        self._last_err: float | None = None
        self.solver: MultilevelSolver | None = None
        #: a converged solution of the same contact on another grid, box or cell aspect,
        #: ``(X, Y, P, H00)`` (``Y >= 0`` when it is a half domain): with ``start_on_guess`` the
        #: cycles start on the finest grid from it instead of the FMG
        self.guess: tuple[np.ndarray, np.ndarray, np.ndarray, float] | None = None
        self.start_on_guess = False
        self._build_levels()

    # -- grids ----------------------------------------------------------------------------
    def _build_levels(self) -> None:
        opt = self.options
        n = int(opt.points)
        nlev, ratio = grid_layout(self.pb, opt, (self.xmin, self.xmax, self.ymax))
        self.y_ratio = ratio
        self.levels: list[Level] = []
        for k in range(nlev):
            nk = (n - 1) // 2 ** (nlev - 1 - k) + 1
            nyf = int(round((nk - 1) * ratio)) + 1  # full-domain points along Y
            hx = (self.xmax - self.xmin) / (nk - 1)
            hy = 2.0 * self.ymax / (nyf - 1)
            X = self.xmin + hx * np.arange(nk)
            if opt.half:
                nyk = (nyf - 1) // 2 + 1
                Y = hy * np.arange(nyk)
            else:
                nyk = nyf
                Y = -self.ymax + hy * np.arange(nyf)
            defo = make_deformation(opt.deformation, nk, nyk, hx, hy, opt.half, self.threads.threads)
            K = cell_kernel(6, 2, hx, hy)
            Ky = cell_kernel(4, 7, hx, hy)  # [Y offset, X offset] of the Y-line film response
            lev = Level(nk, nyk, hx, hy, X, Y, defo, np.ascontiguousarray(self.cd * K),
                        self.g_target, np.ascontiguousarray(self.cd * Ky))
            lev.alternate = self.alternating or (opt.alternating is None and n >= ALTERNATE_FINEST
                                                 and nk >= ALTERNATE_FROM)
            lev.Pb, lev.far_load = None, 0.0
            if self.far:
                Pb = self.far_field.pressure(self.lam, X[None, :], Y[:, None], self.far_c2, self.far_k)
                inner = (slice(0 if opt.half else 1, -1), slice(1, -1))
                Pb[inner] = 0.0
                lev.Pb = Pb
                lev.far_load = (self.far_field.load_outside(self.lam, self.xmin, self.xmax, self.ymax,
                                                            self.far_c2, self.far_k)
                                - boundary_excess(Pb, hx, hy, opt.half))
            self.levels.append(lev)
        self.nfine = self.levels[-1].npts
        self.share_work_arrays()

    def share_work_arrays(self) -> None:
        """One sweep scratch ``D`` and one residual ``r`` for all grids (views of two arrays of
        the finest grid's size: no two grids relax or take residuals at once), and no
        deformation array on the grids above the coarsest (the deformation is written into H
        and the film built in place): 3.3 fine-grid arrays fewer. Peak RSS of a (20, 10) solve
        at 2049^2, one thread (with the result's scalars taken without mirrored copies and its
        fields without copies): full domain 833 -> 727 MB, half domain 636 -> 484 MB."""
        big = max(lev.npts for lev in self.levels)
        d_buf, r_buf = np.zeros(big), np.zeros(big)
        for k, lev in enumerate(self.levels):
            lev.D = d_buf[: lev.npts].reshape(lev.shape)
            lev.r = r_buf[: lev.npts].reshape(lev.shape)
            if k > 0:
                lev.W = None

    def work(self, k: int) -> float:
        return self.levels[k].npts / self.nfine

    def sweep_cost(self, k: int) -> float:
        """Work units of one sweep on grid ``k`` (an alternating sweep counts as two)."""
        return (2.0 if self.levels[k].alternate else 1.0) * self.work(k)

    # -- discrete operators ---------------------------------------------------------------
    def update_properties(self, lev: Level) -> None:
        """Density and ``eps`` from the level's P and H."""
        nm.fluid_properties(lev.P, lev.H, self.par, self.lam, lev.rho, lev.eps)

    def refreshes_locally(self, lev: Level) -> bool:
        """Whether an alternating sweep on ``lev`` refreshes the film locally between its X
        and Y halves (:data:`LOCAL_UPDATE_FROM`, :data:`LOCAL_UPDATE_TO`)."""
        return bool(lev.alternate and self.local_update and self.options.local_film_update
                    and LOCAL_UPDATE_FROM <= lev.nx <= LOCAL_UPDATE_TO)

    def update_film(self, lev: Level) -> None:
        self.threads.for_size(lev.npts)
        # the deformation goes into the level's W, or into H where no W is kept (the film is
        # then built in place): no large temporary per evaluation
        W = lev.H if lev.W is None else lev.W
        if self.cd != 0.0:
            lev.defo(lev.P, out=W)
        else:
            W.fill(0.0)
        nm.film(W, lev.X, lev.Y, self.H00, self.theta, self.cd, lev.H)
        self.update_properties(lev)

    def _sweep(self, lev: Level, s: Settings) -> None:
        """One X-line sweep; with alternating relaxation followed by one Y-line sweep (film and
        lubricant properties recomputed after each; between the two locally on fine grids,
        :data:`LOCAL_UPDATE_FROM`)."""
        self.threads.for_size(lev.npts)
        local = self.refreshes_locally(lev)
        if local:
            if lev.P_old is None or lev.P_old.shape != lev.P.shape:
                lev.P_old = np.empty_like(lev.P)
            np.copyto(lev.P_old, lev.P)
        switch = sweep_switch(s.switch, lev.hx)
        nm.relax_sweep(lev.P, lev.H, lev.rho, lev.eps, lev.f, lev.D, lev.Kc, lev.hx, lev.hy,
                       self.options.half, switch, s.omega, s.omega_jd, self.options.wedge_order,
                       self.ct)
        if local:
            nm.local_film_update(lev.H, lev.P, lev.P_old, lev.Kc[:2, :2], self.options.half)
            self.update_properties(lev)
        else:
            self.update_film(lev)
        if lev.alternate:
            y_jd = Y_OMEGA_JD if self.alternating else FINE_Y_OMEGA_JD
            nm.relax_sweep_y(lev.P, lev.H, lev.rho, lev.eps, lev.f, lev.D, lev.Ky, lev.hx,
                             lev.hy, self.options.half, switch, s.omega * Y_OMEGA,
                             s.omega_jd * y_jd, self.options.wedge_order, Y_JD_MODE, self.ct)
            self.update_film(lev)

    def load(self, lev: Level) -> float:
        return load_integral(lev.P, lev.hx, lev.hy, self.options.half) + lev.far_load

    def set_boundary(self, lev: Level) -> None:
        """The boundary values: zero, or the far-field pressure (:attr:`far`)."""
        P = lev.P
        P[:, 0] = P[:, -1] = 0.0
        P[-1] = 0.0
        if not self.options.half:
            P[0] = 0.0
        if lev.Pb is not None:
            P += lev.Pb

    def residual(self, lev: Level) -> np.ndarray:
        self.threads.for_size(lev.npts)
        nm.residual(lev.P, lev.H, lev.rho, lev.eps, lev.f, lev.hx, lev.hy, self.options.half,
                    self.options.wedge_order, lev.r, self.ct)
        return lev.r

    def rel_residual(self, lev: Level) -> float:
        """RMS of the diagonally scaled residual (a pressure change, units of pmax) over the
        interior, relative to max P: see :func:`numerics.scaled_residual`."""
        r = self.residual(lev)
        sr = lev.D  # the sweep scratch: free between sweeps
        nm.scaled_residual(r, lev.H, lev.rho, lev.eps, float(lev.Kc[0, 0]), lev.hx, lev.hy,
                           self.options.half, sr, self.ct)
        ny, nx = r.shape
        j0 = 0 if self.options.half else 1
        inner = sr[j0:ny - 1, 1:nx - 1]
        rms = math.sqrt(float(np.mean(inner * inner)))
        return rms / max(float(lev.P.max()), 1e-300)

    def central_film(self, lev: Level) -> float:
        i = int(np.argmin(np.abs(lev.X)))
        j = 0 if self.options.half else (lev.ny - 1) // 2
        return float(lev.H[j, i])

    # -- protocol of the driver -----------------------------------------------------------
    def relax(self, k: int, sweeps: int, s: Settings, coarse: bool, post: bool = False) -> float:
        lev = self.levels[k]
        alt = lev.alternate
        # options.y_pre False: fine grids of wider contacts relax Y lines after the correction only
        lev.alternate = alt and (post or self.options.y_pre or self.alternating)
        try:
            for _ in range(sweeps):
                self._sweep(lev, s)
            return sweeps * self.sweep_cost(k)
        finally:
            lev.alternate = alt

    def coarse_solve(self, k: int, s: Settings, sweeps: int | None = None) -> float:
        """Relax on the coarsest grid, moving H00 against the (FAS) load error after each
        sweep. The gain halves when the error changes sign (overshoot) and recovers slowly
        (x1.25, up to ``h00_gain``) while it keeps its sign and falls slowly."""
        lev = self.levels[k]
        if sweeps is None:
            sweeps = self.options.coarse_sweeps
            if not self.options.elastic:
                sweeps = max(sweeps, RIGID_COARSE_SWEEPS, 2 * (lev.nx - 1))
        c_h = s.h00_gain
        self.gain = min(self.gain, c_h)
        for _ in range(sweeps):
            self._sweep(lev, s)
            err = lev.g - self.load(lev)
            last = self._last_err
            if last is not None and err * last < 0.0:
                self.gain = max(self.gain * 0.5, c_h / 256.0)
            elif last is not None and abs(err) > 0.5 * abs(last):
                self.gain = min(self.gain * 1.25, c_h)
            self._last_err = err
            step = self.gain * err
            self.H00 -= max(-self.h00_step_max, min(self.h00_step_max, step))
            nm.film(lev.W, lev.X, lev.Y, self.H00, self.theta, self.cd, lev.H)
            self.update_properties(lev)
        return sweeps * self.sweep_cost(k)

    def restrict(self, k: int, s: Settings) -> tuple[np.ndarray, None]:
        lev, c = self.levels[k], self.levels[k - 1]
        r = self.residual(lev)
        c.P = np.ascontiguousarray(lev.P[::2, ::2])
        P0 = c.P.copy()
        self.update_film(c)
        Lc = np.empty_like(c.P)
        nm.operator(c.P, c.H, c.rho, c.eps, c.hx, c.hy, self.options.half, self.options.wedge_order, Lc,
                    self.ct)
        Rr = np.empty_like(c.P)
        nm.restrict_full_weighting(r, self.options.half, Rr)
        c.f = Lc + Rr
        c.g = self.load(c) + (lev.g - self.load(lev))
        return P0, None

    def correct(self, k: int, P0: np.ndarray, s: Settings) -> None:
        lev, c = self.levels[k], self.levels[k - 1]
        nm.add_bilinear(lev.P, c.P - P0, True)
        self.update_film(lev)

    def fmg_interpolate(self, k: int, s: Settings) -> float:
        lev = self.levels[k]
        lev.P = nm.interpolate_cubic(self.levels[k - 1].P, self.options.half)
        self.set_boundary(lev)
        lev.f = np.zeros_like(lev.P)
        lev.g = self.g_target
        self.update_film(lev)
        return 0.0

    def snapshot(self, k: int) -> tuple[np.ndarray, float]:
        return (self.levels[k].P.copy(), self.H00)

    def restore(self, k: int, saved: tuple[np.ndarray, float]) -> None:
        lev = self.levels[k]
        lev.P = saved[0].copy()
        self.H00 = saved[1]
        self.update_film(lev)

    def measure(self, k: int) -> Measurement:
        lev = self.levels[k]
        ok = bool(np.all(np.isfinite(lev.P)) and math.isfinite(self.H00))
        res = self.rel_residual(lev) if ok else math.inf
        lerr = abs(self.load(lev) - self.g_target) / self.g_target if ok else math.inf
        Hc = self.central_film(lev)
        # a coarse FMG grid may not hold a positive central film at high load (M >= 1000); the
        # finer grids make it positive, so only the finest grid must have one
        positive = Hc > 0.0 or k < len(self.levels) - 1
        finite = ok and bool(np.all(np.isfinite(lev.H)))
        return Measurement(res, lerr, Hc, finite and positive, float(lev.H.min()),
                           subgrid_min_film(lev.H, self.options.half) if finite else math.nan)

    def finite(self) -> bool:
        lev = self.levels[-1]
        return bool(np.all(np.isfinite(lev.P)) and np.all(np.isfinite(lev.H)))

    def alternate_all(self, s: Settings) -> str:
        """Policy step ``"alternate"``: relax X and Y lines alternately on every grid from now
        on (``""`` when they already do, when the options forbid it, or for a subclass whose
        own sweep relaxes X lines only, ``can_alternate = False``, as the starved solver's)."""
        if (self.alternating and all(lev.alternate for lev in self.levels)) \
                or self.options.alternating is False or not self.can_alternate:
            return ""
        self.alternating = True
        self.sweep_work = 2.0
        for lev in self.levels:
            lev.alternate = True
        return "X and Y line relaxation alternate on every grid"

    def raise_switch(self, s: Settings) -> str:
        if s.switch >= 64.0 or not self.options.elastic:
            return ""
        s.switch = min(4.0 * s.switch, 64.0)
        return f"GS/JD switch eps/hx^2 -> {s.switch:.3g}"

    # -- FMG start ------------------------------------------------------------------------
    def _initial_guess(self) -> None:
        lev = self.levels[0]
        XX = lev.X[None, :]
        YY = lev.Y[:, None] / self.boa
        rigid = not self.options.elastic
        if rigid:
            # the rigid film's pressure sits within its inlet length s of the centre, not on
            # the Hertz circle: a semi-ellipsoid of half-axes s and s/sqrt(theta) that carries
            # the load
            Hc_fit = rigid_film(self.pb)
            sx = rigid_film_length(self.pb)
            sy = sx / math.sqrt(self.theta)
            XX, YY = XX / sx, lev.Y[:, None] / sy
        lev.P = np.ascontiguousarray(np.sqrt(np.clip(1.0 - XX**2 - YY**2, 0.0, None)))
        lev.P[:, 0] = lev.P[:, -1] = 0.0
        lev.P[-1] = 0.0
        if not self.options.half:
            lev.P[0] = 0.0
        if rigid:
            # the load the interior carries: the target less the far field's (point.farfield)
            want = self.g_target - lev.far_load
            if lev.Pb is not None:
                want -= load_integral(lev.Pb, lev.hx, lev.hy, self.options.half)
            lev.P *= max(want, 0.1 * self.g_target) / max(
                load_integral(lev.P, lev.hx, lev.hy, self.options.half), 1e-300)
        else:
            Hc_fit = nijenbanning_central(self.pb.M, self.pb.L, self.theta) / self.pb.moes_factor
        self.set_boundary(lev)
        self.H00 = 0.0
        lev.W = lev.defo(lev.P)
        i = int(np.argmin(np.abs(lev.X)))
        j = 0 if self.options.half else (lev.ny - 1) // 2
        self.H00 = float(Hc_fit - self.cd * lev.W[j, i])
        self.h00_step_max = 0.1 * float(Hc_fit)
        self.update_film(lev)

    def _start_from_guess(self) -> None:
        """The finest grid's P from :attr:`guess` (bilinear in X and Y, zero outside its box,
        mirrored into Y < 0 from a half domain) and its H00."""
        from scipy.interpolate import RegularGridInterpolator

        Xg, Yg, Pg, H00 = self.guess
        if Yg[0] == 0.0:
            # a half domain (Y from 0 up): mirrored, so every target row finds its values
            Yg = np.concatenate([-Yg[:0:-1], Yg])
            Pg = np.concatenate([Pg[:0:-1], Pg])
        lev = self.levels[-1]
        interp = RegularGridInterpolator((Yg, Xg), Pg, method="linear", bounds_error=False,
                                         fill_value=0.0)
        YY, XX = np.meshgrid(lev.Y, lev.X, indexing="ij")
        P = interp(np.stack([YY.ravel(), XX.ravel()], axis=1)).reshape(lev.shape)
        lev.P = np.ascontiguousarray(np.maximum(P, 0.0))
        self.set_boundary(lev)
        lev.f = np.zeros_like(lev.P)
        lev.g = self.g_target
        self.H00 = float(H00)
        self.update_film(lev)
        Hc = self.central_film(lev)
        self.h00_step_max = 0.1 * abs(Hc) if Hc != 0.0 else math.inf

    def start(self, solver: MultilevelSolver) -> int:
        """Hertzian start on the coarsest grid, solved by long relaxation with H00 moving;
        retried with the policy's next step while it diverges (NaN). With
        :attr:`start_on_guess` the finest grid starts from :attr:`guess` instead (no FMG)."""
        self.solver = solver
        s = solver.settings
        self.gain = s.h00_gain
        if self.start_on_guess and self.guess is not None:
            self._start_from_guess()
            top = len(self.levels) - 1
            solver.note(f"started on the {self.levels[top].nx}-point grid from the given solution (no FMG)")
            return top
        self._initial_guess()
        lev0 = self.levels[0]
        for attempt in range(4):
            saved = (lev0.P.copy(), self.H00)
            solver.work_units += self.coarse_solve(0, s, 4 * self.options.coarse_sweeps)
            if np.all(np.isfinite(lev0.P)) and math.isfinite(self.H00) and np.all(np.isfinite(lev0.H)):
                break
            lev0.P, self.H00 = saved
            self.update_film(lev0)
            what = solver.policy.on_reject(s, self)
            solver.note(f"coarse start diverged (attempt {attempt + 1}): {what}")
        return 0


#: Cycle type of a steady point solve that starts with X-line relaxation (``cycle=None``): on 108
#: cases F converges as many as W at 0.95 of its work units and 0.89 of its wall time
#: (docs/robustness.md).
STEADY_CYCLE = "F"
#: Cycle type where every grid alternates from the start (narrow contacts, ``alternating=True``,
#: the retry of a failed X-line solve) and of the solvers built on the point hierarchy whose
#: iterations were tuned with W cycles (starved, transient, thermal).
ALTERNATING_CYCLE = "W"


#: Wide contacts (b/a >= WIDE_CONTACT) run W cycles on finest grids of at least this many points
#: along X: F cycles there reject cycles and cost 1.2-7x the work (docs/robustness.md)
WIDE_W_FROM = 513


def point_cycle(options: PointOptions, alternating: bool, wide: bool = False) -> str:
    """The cycle type of a steady point solve: the options' own, else :data:`STEADY_CYCLE`
    when it starts with X lines, :data:`ALTERNATING_CYCLE` when every grid alternates or the
    contact is wide (``wide``: b/a >= :data:`~.problem.WIDE_CONTACT` on a finest grid of at
    least :data:`WIDE_W_FROM` points)."""
    if options.cycle is not None:
        return options.cycle
    return ALTERNATING_CYCLE if alternating or wide else STEADY_CYCLE


def point_settings(problem: PointProblem, options: PointOptions, cycle: str | None = None) -> Settings:
    """Start settings of a point solve (``cycle``: the cycle type when the options leave it
    open; W by default)."""
    if options.cycle is None:
        options = replace(options, cycle=cycle or ALTERNATING_CYCLE)
    if options.h00_gain is None:
        c = options.default_h00_gain(problem.M, problem.L)
        if domain_scale(problem) > 1.0:  # thick film: the rigid sensitivity sets the gain
            H_fit = nijenbanning_central(problem.M, problem.L, problem.theta) / problem.moes_factor
            c = max(c, 0.1 * H_fit / problem.load)
    else:
        c = options.h00_gain
    visc = 0 if problem.viscosity == "roelands" else 1
    switch = options.switch if options.switch is not None else \
        default_switch(visc, problem.alpha_bar, options.elastic)
    return Settings.start(options, c, switch)


def point_solver(problem: PointProblem, options: PointOptions,
                 guess: tuple[np.ndarray, np.ndarray, np.ndarray, float] | None = None) -> MultilevelSolver:
    """The multilevel solver of one point-contact problem (not yet run); with ``guess``
    ``(X, Y, P, H00)``, a solution of the same contact, its cycles start on the finest grid
    from that solution (:meth:`PointHierarchy.start`)."""
    hz = PointHierarchy(problem, options)
    hz.guess, hz.start_on_guess = guess, guess is not None
    cycle = point_cycle(options, hz.alternating,
                        problem.b_over_a >= WIDE_CONTACT and options.points >= WIDE_W_FROM)
    solver = MultilevelSolver(hz, options, point_settings(problem, options, cycle),
                              RobustnessPolicy(POINT_POLICY, options.adapt), HINT)
    hz.solver = solver
    return solver
