"""The steady isothermal EHL line contact on the shared multilevel driver.

:class:`LineHierarchy` is the line contact's grid hierarchy for
:class:`~ehl_multigrid.multigrid.driver.MultilevelSolver` (FAS/FMG, V/W/F cycles):

* relaxation: collective line relaxation (:meth:`LineLevel.relax`) switching between
  Gauss-Seidel changes where ``eps/h^2 >= switch`` and Jacobi-distributive changes where it is
  smaller or where ``eps`` is below the film-scale switch (:func:`default_switch_eps`),
  under-relaxed with ``omega``/``omega_jd``, negative pressures projected to 0;
* film constant: each grid holds its own ``H0``; on the coarse grids of a cycle ``H0`` moves
  with the load error, ``H0 += h00_gain (h sum P - g)``; the coarsest grid is solved exactly
  for ``(P, H0)`` by a damped semismooth Newton iteration (newton.py), so the load balance is
  enforced through the FAS load right-hand side ``g`` on every grid;
* transfers: injection of ``P``, full weighting of residuals, linear interpolation of
  corrections, cubic FMG interpolation; coarse points next to the fine free boundary are
  frozen (Brandt & Cryer);
* local Newton: on fine grids a windowed Newton solve settles the outlet pressure drop where the
  residual concentrates, after each post-relaxation (and each pre-relaxation at high
  ``alpha_bar``, before the restriction);
* deformation on each grid by MLMI, FFT or the direct sum (deformation.py).

At high load the FMG starts on a finer grid so the first coarse solution has a positive film,
and a stalled solve on a grid small enough is finished by dense Newton. Convergence means the
relative complementarity residual is below ``tol`` AND the relative load error below
``tol_load``.
"""

from __future__ import annotations

import dataclasses
import math
import re
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from ..model.errors import ConvergenceError, InputError, require_range
from ..multigrid.accuracy import (
    DOMAIN_REUSE_BELOW,
    LINE_DOMAIN_SAFETY,
    PROBE_FILM_TOL,
    film_change,
    film_tol,
    solve_to_accuracy,
)
from ..multigrid.controller import check_deadline
from ..multigrid.driver import Measurement, MultilevelSolver
from ..multigrid.flux import FACE_MODES
from ..multigrid.gridchoice import solver_grid
from ..multigrid.options import LineOptions, build_scene_options, scene_solver_table
from ..multigrid.policy import PolicyParameters, RobustnessPolicy, Settings
from ..multigrid.result import EHLResult, ended_relaxation, tightened, tightening
from ..multigrid.rheology import density, log_viscosity
from ..multigrid.transfer import full_weighting, inject, interpolate_cubic, interpolate_linear
from .discrete import projected
from .level import LineLevel, State
from .newton import NewtonFailure, local_newton, newton_solve
from .problem import LineProblem, box_ratio, check_grid, fit_central_film

#: the steady solver's face coefficient is logarithmic from this ``alpha_bar`` on (``face =
#: "auto"``): the mean of an exponential interpolant of ``eps`` where the viscosity varies
#: exponentially across the outlet (docs/accuracy.md, "Face coefficient of the Poiseuille flux")
FACE_LOG_ALPHA = 1.0
#: Largest grid solved directly by Newton at the start of FMG (dense Jacobian).
MAX_START_POINTS = 2049
#: A start grid whose coarser neighbour converged with a film that is not positive is first
#: solved by at most this many FAS cycles from that neighbour's solution (its coarser grids as
#: coarse grids), stopped when Hc changes by under START_CYCLE_HC relative and the residual is
#: under START_CYCLE_RESIDUAL; else by dense Newton (docs/accuracy.md, "Cycled start").
START_CYCLES = 12
START_CYCLE_HC = 1e-4
START_CYCLE_RESIDUAL = 1e-3
#: Largest grid an accuracy target may refine to: Hm at 0.5 % needs 131073 points at M >= 3000
#: and 262145 at L = 25, M 2000-4000 ((2000, 25): 4.8 s, 390 MB peak; docs/accuracy.md)
MAX_ACCURACY_POINTS = 262145

HINT = ("more levels or points (finer coarsest grid), W cycles (--cycle W), a smaller "
        "h00_gain, smaller under-relaxation (omega/omega_jd), or a longer inlet (--xmin)")

#: Cycle acceptance of the line solvers, tuned on a test set of 17 (M, L, N) cases: reject 20x
#: growth, retry with halved under-relaxation; on a stall V -> W, a wider Jacobi-distributive
#: zone, give up (docs/robustness.md, "Line solver defaults").
LINE_POLICY = PolicyParameters()
#: The steady line solver's stall ladder: V -> W, then up to three hierarchy steps of
#: :meth:`LineHierarchy.raise_switch`, then give up (the starved and transient solvers keep
#: :data:`LINE_POLICY`; docs/robustness.md, "Line solver defaults").
STEADY_LINE_POLICY = PolicyParameters(
    stall_ladder=(("W",), ("switch",), ("switch",), ("switch",), ("fail",)))


#: film tolerance of a domain probe started from the solution (line_domain_change)
GUESS_PROBE_FILM_TOL = 1e-6
#: the coarsest mesh (points per default box) on which a box probe may first look: coarse and
#: fine meshes measure the same box change from about 513 points ((20, 10) Hc 1.62e-4 on 513
#: points, 1.60e-4 on 2049; docs/accuracy.md, "Domain error"), while 65 points overstate it
#: five to seven times
COARSE_PROBE_POINTS = 513

#: most Newton steps of a coarse solve on a grid whose Newton failed before in the same solve
NEWTON_AFTER_FAILURE = 20
#: a dense Newton solve running longer than this many seconds reports each iteration to the
#: progress callable, at most once per this interval (a 4097-point solve: about 1.5 s per step)
NEWTON_PROGRESS_EVERY = 5.0

#: local Newton (:meth:`LineHierarchy.relax`): where the largest complementarity residual
#: exceeds this multiple of the mean, in a window of this half width
LOCAL_NEWTON_FACTOR = 20.0
LOCAL_NEWTON_HALF = 48
#: ... after the pre-relaxations too (before the FAS restriction) where ``alpha_bar`` exceeds this,
#: so the coarse problems are built from a settled outlet drop; below 20 it only costs work or
#: loses collapsing films (docs/robustness.md, "Line solver defaults").
LOCAL_NEWTON_PRE_ALPHA = 20.0


def start_key(problem: LineProblem, options: LineOptions, n: int, x0: float, x1: float,
              order: int) -> tuple:
    """The key of an FMG start grid of ``n`` points on ``[x0, x1]`` in a start cache
    (:meth:`LineHierarchy.start_key`)."""
    return (repr(problem), n, x0, x1, order, options.deformation, options.mlmi_order,
            options.mlmi_radius)


def filmless_start_key(problem: LineProblem, options: LineOptions) -> tuple:
    """The key of the discrete solution of the largest dense start grid
    (:data:`MAX_START_POINTS`) of ``problem`` when its film is not positive (the solve ended
    ``start_failed``; :attr:`LineHierarchy.filmless_starts`)."""
    return (repr(problem), options.deformation, options.mlmi_order, options.mlmi_radius,
            options.wedge_order)


def coarse_points(M: float, box: float = 1.0) -> int:
    """Default coarsest grid: at high load a coarse grid cannot carry a positive film
    (Venner & Lubrecht), so the coarsest grid is refined with M. ``box``: the box length over
    the default one (:func:`~ehl_multigrid.line.problem.box_ratio`); a longer box keeps the
    coarsest mesh size, with proportionally more points (at twice the mesh size a probe of twice
    the box at M = 2000 has no coarse film; docs/accuracy.md, "Cycled start")."""
    n = 65 if M <= 50 else (129 if M <= 200 else (257 if M <= 1000 else 513))
    return (n - 1) * 2 ** max(0, round(math.log2(box))) + 1


#: above this M an isoviscous steady solve starts its FMG on at least :data:`CYCLE_FLOOR_POINTS`
#: points (the 513-point grid holds no positive film there, and its failed Newton start cost
#: 0.4 s at (5000, 0)), and its cycles from a given solution coarsen no further than that grid
CYCLE_FLOOR_M = 2000.0
#: ... solved there by Newton: at isoviscous (5000, 0) a 513-point coarsest grid leaves a slow
#: film mode (a solve from a given solution on 32769 points: 14 cycles ending 0.1 % off the
#: discrete solution, against 6 cycles; docs/performance.md, "Line contacts at high load")
CYCLE_FLOOR_POINTS = 1025


def cycle_floor_points(M: float, L: float) -> int:
    """The coarsest grid the steady solver's cycles visit when they start from a given solution
    above the dense start grids (0: no floor): for isoviscous contacts above
    :data:`CYCLE_FLOOR_M` the coarser grids' corrections of the film level are too poor. With
    a pressure viscosity the floor cost more than it saved ((5000, 5): 0.27 -> 0.53 s for its
    16385-point solve; box probes of (5000, 25) 0.22 -> 0.35 s). The same number of points on a
    longer box (a box probe): a Newton solve on 2049 points at every cycle costs more than the
    cycles it saves ((5000, 0), 8193 points on twice the box: 1.95 s against 0.96 s)."""
    return CYCLE_FLOOR_POINTS if M > CYCLE_FLOOR_M and L <= 0.0 else 0


def default_switch_h(problem: LineProblem) -> float:
    """Fine-grid switch constant (Jacobi-distributive where ``eps/h^2 < switch_h/h``).

    Chosen from measured convergence on a test set of 17 (M, L, N) cases: with little
    pressure-viscosity (``alpha_bar < 1``) ``eps`` stays large in the contact and Gauss-Seidel
    there diverges unless ``switch_h ~ 1``; at moderate ``alpha_bar`` a small h-scaled switch
    (0.1) removes the stalls of the classic fixed switch on fine grids; at high ``alpha_bar``
    (> 100) the classic switch alone works best.
    """
    if not problem.elastic:
        return 0.0
    abar = problem.alpha_bar
    return 1.0 if abar < 1.0 else (0.1 if abar <= 100.0 else 0.0)


#: Film-scale switch: Jacobi-distributive wherever ``eps`` is below this multiple of the
#: contact's film-scale ``eps`` (:func:`default_switch_eps`); fine-grid relaxation diverges below
#: 0.4-1.8 times the central ``eps`` (docs/robustness.md, "Line solver defaults").
JD_FILM_FACTOR = 2.0
#: ... and at most this: where the flat film's ``eps`` exceeds it the Poiseuille term holds the
#: contact's smooth modes and Gauss-Seidel is stable, while a Jacobi-distributive zone there
#: stalls M = 1 and 2 (docs/robustness.md, "Line solver defaults").
JD_FILM_MAX = 0.05


def line_face(face: str, alpha_bar: float) -> str:
    """The face coefficient an option names: ``"auto"`` is logarithmic from
    :data:`FACE_LOG_ALPHA` on, arithmetic below."""
    if face == "auto":
        return "logarithmic" if alpha_bar >= FACE_LOG_ALPHA else "arithmetic"
    return face


def default_switch_eps(problem: LineProblem) -> float:
    """Absolute switch: Jacobi-distributive where ``eps < JD_FILM_FACTOR eps_c`` on every grid,
    ``eps_c = rho H_c^3/(eta lambda)`` at the Hertzian maximum (P = 1) with the Moes-fit
    central film ``H_c`` (0 for rigid surfaces).

    The classic switch on ``eps/h^2`` (Venner & Lubrecht 2000, "Multilevel methods in
    lubrication": Jacobi-distributive where the Poiseuille term is small on the grid's scale)
    and its h-scaled form leave more Gauss-Seidel points in the contact as the grid is refined.
    The collective line system holds the Poiseuille part of a Gauss-Seidel zone exactly but its
    elastic coupling (symbol ``O(1)`` against ``eps k^2``) only within the band, so the
    contact's smooth modes (``k = O(1)`` in units of the Hertzian half-width), which need
    ``eps k^2 >~ 1``, are amplified when Gauss-Seidel points reach the flat film: the threshold
    is on ``eps`` itself, not on ``eps/h^2``. Jacobi-distributive changes act locally on the
    film, so the band holds their coupling. With this switch isoviscous (20, 0), (20, 0.5) and
    (20, 1) converge within FMG at 4097-16385 points, where the ``eps/h^2`` switches stall
    (docs/robustness.md, "Line solver defaults"). At high ``alpha_bar`` ``eps_c`` is tiny and the
    switch changes nothing.
    """
    if not problem.elastic:
        return 0.0
    par = problem.rheology()
    H = fit_central_film(problem.M, problem.L)
    eps_c = density(1.0, par)[0] * H ** 3 * math.exp(-log_viscosity(1.0, par)[0]) / problem.lam
    return min(JD_FILM_FACTOR * float(eps_c), JD_FILM_MAX)


def line_levels(options: LineOptions, M: float, box: float = 1.0) -> int:
    """Number of grids: the options' value, else down to :func:`coarse_points` (M, box)."""
    if options.levels is not None:
        check_grid(options.points, options.levels)
        return int(options.levels)
    n = options.points - 1
    nc = min(coarse_points(M, box) - 1, n)
    levels = max(1, int(round(math.log2(max(n, 1) / max(nc, 1)))) + 1)
    check_grid(options.points, levels)
    return levels


class LineHierarchy:
    """Grids of one line-contact solve, coarsest first (protocol of the multilevel driver)."""

    name = "line"
    #: the driver may stop on the grid rule (``options.grid_stop``); False in subclasses
    #: whose convergence carries more than the films
    grid_stop = True
    #: the film rule stops after at least this many finest-grid cycles, so the iteration
    #: error is estimated from a measured contraction, not from one change (a stop after two
    #: cycles can leave several times the stated error: docs/robustness.md)
    film_stop_films = 3

    #: the grid type (subclasses add unknowns or terms to a grid)
    level_type = LineLevel

    def __init__(self, problem: LineProblem, options: LineOptions) -> None:
        self.problem = problem
        self.options = options
        par = problem.rheology()
        nlev = self.grid_count()
        n_f = options.points
        self.levels = [
            self.level_type((n_f - 1) // 2 ** (nlev - 1 - k) + 1, problem.xmin, problem.xmax, par,
                            problem.lam, problem.elastic, options.deformation, options.wedge_order,
                            options.mlmi_order, options.mlmi_radius)
            for k in range(nlev)
        ]
        #: the kernels' code of the Poiseuille face coefficient (subclasses that build their own
        #: grids give it to them)
        self.face = FACE_MODES[line_face(options.face, problem.alpha_bar)]
        for lv in self.levels:
            lv.face = self.face
        self.newton_iterations = 0
        #: grids whose coarse Newton failed in this solve: their later attempts stop after
        #: NEWTON_AFTER_FAILURE steps
        self.newton_failed: set[int] = set()
        self.solver: MultilevelSolver | None = None
        #: coarsest grid the cycles visit (solved by Newton like level 0); raised on a stall to
        #: ``film_floor``, the FMG start grid when the start moved up because the grids below
        #: cannot hold a positive film (or their Newton failed)
        self.floor = 0
        self.film_floor = 0
        #: the h-scaled switch on the current FMG grid only (a stall step, raise_switch)
        self.classic_coarse_switch = False
        #: the steady solver's extra stall steps (line_solver sets it; the starved and
        #: transient hierarchies keep the plain switch step)
        self.stall_steps = False
        #: grids of at least this many points end a post-relaxation by local Newton where the
        #: residual concentrates (line_solver sets it from the options; None: never)
        self.local_newton: int | None = None
        #: ... and after each pre-relaxation too, before the FAS restriction (line_solver sets it
        #: where alpha_bar > LOCAL_NEWTON_PRE_ALPHA)
        self.local_newton_pre = False
        self.local_newton_solves = 0
        #: the steady solver's solves stop between Newton iterations when the time budget of
        #: their sequence runs out (check_deadline; line_solver sets it)
        self.deadline_checks = False
        #: ``progress(text)``: where a long dense Newton solve is (line_solver sets it)
        self.progress: Callable[[str], None] | None = None
        #: film-scale switch: Jacobi-distributive where ``eps`` is below it on every grid
        #: (line_solver sets it, :func:`default_switch_eps`; 0: the ``eps/h^2`` rules only)
        self.switch_eps = 0.0
        #: optional start ``(X, P, H0)`` from a solution of the same contact (another grid or
        #: box): the start grid's Newton begins from it instead of the Hertzian guess
        self.guess: tuple[np.ndarray, np.ndarray, float] | None = None
        #: start the cycles on the finest grid from ``guess`` instead of FMG
        self.start_on_guess = False
        #: converged FMG start grids ``start_key -> (P, H0)`` shared by the solves of one
        #: accuracy sequence (None: not kept)
        self.start_cache: dict | None = None
        #: where a solve that ends ``start_failed`` leaves its largest start grid's discrete
        #: solution ``(X, P, H0)`` (film not positive) under :func:`filmless_start_key` (None:
        #: not kept; :func:`from_start_grid`)
        self.filmless_starts: dict | None = None
        #: a converged solve of the same discrete problem on one of this solve's coarser grids:
        #: the FMG goes on from its solution there (:meth:`_resumed_start`)
        self.resume: EHLResult | None = None
        #: the FMG films of ``resume`` below the grid it starts on (the driver keeps them)
        self.resumed_fmg: list[dict[str, float]] = []

    def grid_count(self) -> int:
        """Number of grids (:func:`line_levels`)."""
        return line_levels(self.options, self.problem.M, box_ratio(self.problem))

    # -- observables ----------------------------------------------------------------------
    def work(self, k: int) -> float:
        return (self.levels[k].n - 1) / (self.levels[-1].n - 1)

    @staticmethod
    def relative_residual(lv: LineLevel, st: State) -> float:
        denom = st.scale / max(lv.n - 2, 1)
        return lv.residual_norm(st) / denom if denom > 0 else math.inf

    @staticmethod
    def central_film(lv: LineLevel, st: State | None = None) -> float:
        st = lv.state() if st is None else st
        return float(np.interp(0.0, lv.X, st.H))

    def measure(self, k: int) -> Measurement:
        lv = self.levels[k]
        st = lv.state()
        res = self.relative_residual(lv, st)
        Hc = self.central_film(lv, st)
        ok = bool(np.all(np.isfinite(lv.P)) and np.isfinite(lv.H0) and np.isfinite(res)
                  and np.all(np.isfinite(st.H)) and Hc > 0.0)
        zone = (np.abs(lv.X) <= 1.5) | (lv.P > 0)
        Hm = float(np.min(st.H[zone])) if zone.any() else math.nan
        return Measurement(res, lv.load() / lv.g - 1.0, Hc, ok, Hm)

    def finite(self) -> bool:
        return self.finite_at(len(self.levels) - 1)

    def finite_at(self, k: int) -> bool:
        lv = self.levels[k]
        return bool(np.all(np.isfinite(lv.P)) and math.isfinite(lv.H0))

    def snapshot(self, k: int) -> list[tuple[np.ndarray, float]]:
        return [(v.P.copy(), v.H0) for v in self.levels[: k + 1]]

    def restore(self, k: int, saved: list[tuple[np.ndarray, float]]) -> None:
        for v, (P, H0) in zip(self.levels, saved, strict=False):
            v.P, v.H0 = P.copy(), H0
        if self.stall_steps and self.floor < self.film_floor and self.solver is not None:
            # a rejected cycle (the driver restores the iterate) also leaves the grids below a
            # moved FMG start out (raise_switch, step 1): a wide-box probe at M = 1000 diverges
            # through them otherwise (docs/robustness.md, "Line solver defaults")
            self.floor = self.film_floor
            self.solver.note(f"cycle rejected: grids below the {self.levels[self.floor].n}-point "
                             f"FMG start (no positive film there) left out of the cycles")

    # -- cycle pieces ---------------------------------------------------------------------
    def relax(self, k: int, sweeps: int, s: Settings, coarse: bool, post: bool = False) -> float:
        if k < self.floor:
            return 0.0
        lv = self.levels[k]
        # after the stall step of raise_switch: the classic switch on the cycle's coarse grids
        sh = 0.0 if coarse and self.classic_coarse_switch and s.switch_h < 1.0 else s.switch_h
        st = None
        for _ in range(sweeps):
            st = lv.relax(s.switch, s.omega, s.omega_jd, self.options.band, switch_h=sh,
                          switch_eps=self.switch_eps)
            if coarse:
                lv.H0 += s.h00_gain * (lv.load() - lv.g)
        work = sweeps * self.work(k)
        if (post or self.local_newton_pre) and st is not None and self.local_newton is not None \
                and lv.n >= self.local_newton:
            work += self._local_newton(k, st)
        return work

    def _local_newton(self, k: int, st: State) -> float:
        """Local Newton at the largest residual when it exceeds LOCAL_NEWTON_FACTOR times the
        mean (judged on the state before the last sweep, which costs nothing extra).

        The relaxation freezes ``eps``, and at the outlet pressure drop of high-``alpha_bar``
        oils ``eps/h^2`` jumps from 1e-8 to 1e4 between two points, where 96 % of the residual
        sits; the window solve after every post-relaxation on grids of at least 1025 points
        converges the cycles that diverge or stall without it (docs/robustness.md). Where
        ``alpha_bar > LOCAL_NEWTON_PRE_ALPHA`` it also ends each pre-relaxation, so the
        restricted residual does not carry the drop the sweeps unsettled.
        """
        lv = self.levels[k]
        rp = np.abs(projected(st.r, lv.P))
        rp[lv.frozen] = 0.0
        inner = rp[1:-1]
        c = int(np.argmax(inner)) + 1
        if not inner[c - 1] > LOCAL_NEWTON_FACTOR * float(np.mean(inner)):
            return 0.0
        self.local_newton_solves += 1
        local_newton(lv, c, LOCAL_NEWTON_HALF)
        return self.work(k)  # one deformation of the grid; the window's own work is O(half^2)

    def restrict(self, k: int, s: Settings) -> tuple[Any, float]:
        if k <= self.floor:
            return None, None  # the grids below the floor are not visited
        lv, cv = self.levels[k], self.levels[k - 1]
        st = lv.state()
        lres = self.relative_residual(lv, st)
        P_start, H0_start = fas_coarse_problem(lv, cv, projected(st.r, lv.P))
        return (P_start, H0_start, st), lres

    def correct(self, k: int, token: Any, s: Settings) -> float | None:
        if k < self.floor:
            return None
        if k == self.floor:
            # the floor grid is the cycles' coarsest grid: solved for (P, H0) like level 0
            return self._floor_solve(k, s)
        lv, cv = self.levels[k], self.levels[k - 1]
        P_start, H0_start, st = token
        corr = interpolate_linear(np.where(cv.frozen, 0.0, cv.P - P_start))
        # no correction in the cavitated zone: the free boundary moves by relaxation only
        # (Brandt & Cryer); a coarse correction there fights the fine-grid complementarity
        corr[lv.P <= 0.0] = 0.0
        if self.options.correction_mask is not None:
            # where Poiseuille flow dominates (eps/h^2 huge: inlet and outlet) the line
            # relaxation solves the local problem exactly; a coarse correction there only
            # disturbs the free boundary
            corr[st.eps / lv.h**2 > self.options.correction_mask] = 0.0
        lv.P = np.maximum(lv.P + corr, 0.0)
        lv.P[0] = lv.P[-1] = 0.0
        lv.H0 += cv.H0 - H0_start

    def _floor_solve(self, k: int, s: Settings) -> None:
        self.solver.work_units += self.coarse_solve(k, s)

    def newton_check(self, lv: LineLevel, what: str) -> Callable[[int], None] | None:
        """The ``check`` of a dense Newton solve on ``lv`` (``what``: its role, for the
        messages): the time budget between iterations (:attr:`deadline_checks`) and a progress
        line at most every :data:`NEWTON_PROGRESS_EVERY` seconds."""
        if not self.deadline_checks and self.progress is None:
            return None
        t0 = time.perf_counter()
        said = [t0]

        def check(it: int) -> None:
            where = f"{what} Newton iteration {it} on the {lv.n}-point grid (M = {self.problem.M:.4g})"
            if self.deadline_checks:
                check_deadline(where)
            now = time.perf_counter()
            if self.progress is not None and now - said[0] >= NEWTON_PROGRESS_EVERY:
                said[0] = now
                self.progress(f"{where}: {now - t0:.0f} s in this dense solve")
        return check

    def coarse_solve(self, k: int, s: Settings) -> float:
        if k < self.floor:
            return 0.0
        lv = self.levels[k]
        saved = (lv.P.copy(), lv.H0)
        try:
            # after a failure on this grid (an isoviscous contact at M >= 3000 started from a
            # given solution, its coarse film not positive), the later attempts that succeed
            # take few steps: a failing one stops early (docs/robustness.md)
            its = newton_solve(lv, keep=True,
                               max_iter=NEWTON_AFTER_FAILURE if k in self.newton_failed else 80,
                               check=self.newton_check(lv, "coarse-grid"))
        except NewtonFailure as exc:
            lv.P, lv.H0 = saved
            if k not in self.newton_failed:
                self.solver.note(f"coarse Newton failed on {lv.n} points ({exc}); relaxed "
                                 f"instead (later attempts on this grid stop after "
                                 f"{NEWTON_AFTER_FAILURE} steps)")
            self.newton_failed.add(k)
            return self.relax(k, 20, s, True)
        lv.P = np.maximum(lv.P, 0.0)
        self.newton_iterations += its
        return its * self.work(k)

    def fmg_interpolate(self, k: int, s: Settings) -> float:
        lv, cv = self.levels[k], self.levels[k - 1]
        lv.P = np.maximum(interpolate_cubic(cv.P), 0.0)
        lv.P[0] = lv.P[-1] = 0.0
        lv.H0 = cv.H0
        lv.f = np.zeros(lv.n)
        lv.g = 0.5 * math.pi
        if self.options.fmg_match_film:
            # carry the central film, not H0, to the finer grid: the two grids' deformations
            # differ by their discretisation error, which is comparable to H at high load
            lv.H0 += self.central_film(cv) - self.central_film(lv)
        return 0.0

    def raise_switch(self, s: Settings) -> str:
        """The stall ladder's hierarchy step, the first that applies of: (1) leave the grids
        that could not hold a positive film at the FMG start out of the cycles; (2) keep the
        h-scaled switch (``switch_h`` in (0, 1)) on the current FMG grid only, the classic
        switch on the cycle's coarse grids; (3) widen the Jacobi-distributive zone
        (``switch_h = 1``). Steps (1) and (2) only in the steady solver (``stall_steps``).

        Steps (1) and (2) each converge stalled cases but lose others when applied from the
        first cycle, so they are stall steps, not defaults (docs/robustness.md, "Line solver
        defaults")."""
        if self.stall_steps and self.floor < self.film_floor:
            self.floor = self.film_floor
            s.omega, s.omega_jd = s.defaults[0], s.defaults[1]
            return (f"grids below the {self.levels[self.floor].n}-point FMG start (no positive film "
                    f"there) left out of the cycles")
        if s.switch_h >= 1.0:
            return ""
        if self.stall_steps and s.switch_h > 0.0 and not self.classic_coarse_switch:
            self.classic_coarse_switch = True
            s.omega, s.omega_jd = s.defaults[0], s.defaults[1]
            return "h-scaled switch kept on the finest grid only (classic switch on the coarse grids)"
        # more Jacobi-distributive points on the fine grids (discrete.py, switch_h)
        s.switch_h = 1.0
        s.omega, s.omega_jd = s.defaults[0], s.defaults[1]
        return "switch raised to eps/h^2 < 1/h on fine grids"

    # -- FMG start ------------------------------------------------------------------------
    def _initial_guess(self, lv: LineLevel) -> None:
        """Hertzian pressure and the H0 that gives the Moes-fit central film."""
        pb = self.problem
        Hc_fit = fit_central_film(pb.M, pb.L)
        # Hertzian shape; rigid surfaces: the same shape over the width 2 sqrt(2 Hc)
        a = 1.0 if pb.elastic else min(1.0, 2.0 * math.sqrt(2.0 * Hc_fit))
        lv.P = np.where(np.abs(lv.X) < a, np.sqrt(np.clip(1.0 - (lv.X / a) ** 2, 0.0, None)) / a, 0.0)
        lv.P[0] = lv.P[-1] = 0.0
        W = lv.deform(lv.P)
        lv.H0 = Hc_fit + float(np.interp(0.0, lv.X, W)) / math.pi
        lv.f = np.zeros(lv.n)
        lv.g = 0.5 * math.pi
        if self.guess is not None:
            X, P, H0 = self.guess
            lv.P = np.interp(lv.X, X, P, left=0.0, right=0.0)
            lv.P[0] = lv.P[-1] = 0.0
            lv.H0 = float(H0)

    def start_key(self, k: int) -> tuple:
        """What defines grid ``k``'s discrete problem (the key of :attr:`start_cache`)."""
        lv = self.levels[k]
        return start_key(self.problem, self.options, lv.n, float(lv.X[0]), float(lv.X[-1]), lv.order)

    def _start_level(self) -> int:
        want = self.options.fmg_start_points or max(coarse_points(self.problem.M, box_ratio(self.problem)),
                                                    cycle_floor_points(self.problem.M, self.problem.L) if self.stall_steps else 0)
        for k, lv in enumerate(self.levels):
            if lv.n >= want:
                return k
        return len(self.levels) - 1

    def _film_ok(self, lv: LineLevel) -> bool:
        st = lv.state()
        zone = lv.P > 0
        return bool(np.all(np.isfinite(st.H))) and self.central_film(lv, st) > 0 and \
            (not zone.any() or float(st.H[zone].min()) > 0)

    def _from_guess(self) -> None:
        """The cycles start from a given solution above the dense start grids: the steady
        solver's cycles coarsen no further than :func:`cycle_floor_points` from here on."""
        if self.stall_steps:
            want = cycle_floor_points(self.problem.M, self.problem.L)
            top = len(self.levels) - 1
            self.floor = max(self.floor, next((k for k, lv in enumerate(self.levels) if lv.n >= want), top))

    def start(self, solver: MultilevelSolver) -> int:
        """Solve the FMG start grid by Newton; refine the start grid while the discrete film
        is not positive (too coarse for this load). Returns the start level. A steady solve whose
        cycles start from a given solution above its dense start grids then coarsens no further
        than :func:`cycle_floor_points`."""
        self.solver = solver
        top = len(self.levels) - 1
        if self.resume is not None:
            j = self._resumed_start(self.resume, solver)
            if j is not None:
                return j
        if self.start_on_guess and self.guess is not None:
            self._from_guess()  # box probes and tolerance steps
            self._initial_guess(self.levels[top])
            solver.note(f"started on the {self.levels[top].n}-point grid from the given solution (no FMG)")
            return top
        k = k_want = self._start_level()
        # a start grid an earlier solve of the sequence converged on, from its solution; grids
        # on which an earlier solve found no start (film not positive, Newton failed) are not
        # solved again
        starts = {} if self.start_cache is None else self.start_cache
        known = [j for j in range(k, top + 1) if starts.get(self.start_key(j)) is not None]
        if known and self.levels[known[0]].n <= MAX_START_POINTS:
            k = known[0]
        no_film = [j for j in range(k, top + 1) if self.start_key(j) in starts
                   and starts[self.start_key(j)] is None]
        while k in no_film and k < top and self.levels[k + 1].n <= MAX_START_POINTS:
            k += 1
        if k in no_film and self.guess is not None:
            self._from_guess()
            j = self._guess_start_above(k, solver)
            if j is not None:
                return j
            fin = self.levels[top]
            self._initial_guess(fin)
            solver.note(f"no positive film on the start grids up to {self.levels[k].n} points (an "
                        f"earlier solve of this contact): started on the {fin.n}-point grid from "
                        "the given solution")
            return top
        from_coarser = False
        while True:
            lv = self.levels[k]
            cached = starts.get(self.start_key(k))
            if cached is not None:
                self._initial_guess(lv)
                lv.P, lv.H0 = cached[0].copy(), cached[1]
            elif from_coarser:
                # the coarser start grid's converged Newton solution (its film not positive
                # somewhere) is a closer start than the Hertzian guess: (3000, 6) at 2049
                # points, 5 Newton iterations instead of 7 (0.4 s each)
                self.fmg_interpolate(k, solver.settings)
            else:
                self._initial_guess(lv)
            last = k == top or self.levels[k + 1].n > MAX_START_POINTS
            its = 0
            try:
                if not ((from_coarser or cached is not None) and k > 0 and self._cycled_start(k, solver)):
                    its = newton_solve(lv, max_iter=120, single=True,
                                       check=self.newton_check(lv, "FMG start"))
            except NewtonFailure as exc:
                if from_coarser:  # the Hertzian start before giving up on this grid
                    from_coarser = False
                    continue
                if not last:
                    solver.note(f"FMG start on {lv.n} points: Newton failed ({exc}); "
                                f"start moved to {self.levels[k + 1].n} points")
                    starts[self.start_key(k)] = None
                    k += 1
                    continue
                solver.note(f"FMG start on {lv.n} points: Newton failed ({exc}); continuation in M")
                its = self._continuation(lv)
            lv.P = np.maximum(lv.P, 0.0)
            self.newton_iterations += its
            solver.work_units += its * self.work(k)
            starts[self.start_key(k)] = (lv.P.copy(), float(lv.H0)) if self._film_ok(lv) else None
            if self._film_ok(lv) or last:
                break
            solver.note(f"the {lv.n}-point grid gives a non-positive film at M = "
                        f"{self.problem.M:.4g}: FMG start moved to {self.levels[k + 1].n} points")
            k += 1
            from_coarser = True
        if not self._film_ok(lv):
            capped = k < top and self.levels[k + 1].n > MAX_START_POINTS
            if capped and self.guess is not None:
                self._from_guess()
                # the given solution replaces the direct start: cycles on the finest grid
                # from it (the coarser grids still serve as coarse-grid corrections)
                fin = self.levels[top]
                self._initial_guess(fin)
                solver.note(f"no positive film on the {lv.n}-point start grid (the dense Newton "
                            f"start is limited to {MAX_START_POINTS} points): started on the "
                            f"{fin.n}-point grid from the given solution")
                return top
            if capped and self.filmless_starts is not None:
                # the largest start grid's discrete solution, film not positive: a start for
                # cycles on the finest grid (from_start_grid), closer than the continuation in M
                self.filmless_starts[filmless_start_key(self.problem, self.options)] = (
                    lv.X.copy(), lv.P.copy(), float(lv.H0))
            hint = (f"the dense Newton start is limited to {MAX_START_POINTS} points, so more points do "
                    f"not help: this (M, L) is beyond the line solver's range (use the Moes fit)"
                    if capped else "more points (--points), or lower M")
            raise ConvergenceError(
                f"the discrete film is not positive on the {lv.n}-point start grid "
                f"(M = {self.problem.M:.4g}, L = {self.problem.L:.4g} needs "
                + (f"a start grid finer than the dense start's {MAX_START_POINTS} points)" if capped
                   else "finer grids)"), None, hint)
        if k > k_want:
            # the grids below the start cannot carry a positive film (or their Newton failed):
            # a stall step leaves them out of the cycles (raise_switch)
            self.film_floor = k
        if k > 0:
            solver.note(f"FMG started on the {lv.n}-point grid (cycles still coarsen to "
                        f"{self.levels[0].n})")
        return k

    def _resumed_start(self, prev: EHLResult, solver: MultilevelSolver) -> int | None:
        """Start the FMG on the grid ``prev`` (a converged solve of the same discrete problem on
        one of this solve's coarser grids) was solved on, from its solution: the grids below
        would repeat ``prev``'s FMG (the same start, cycles and films), so their FMG films are
        taken from it. None where no grid of this solve is ``prev``'s."""
        X = prev.X
        j = next((k for k, lv in enumerate(self.levels[:-1]) if lv.n == X.size
                  and lv.X[0] == X[0] and lv.X[-1] == X[-1]), None)
        below = [d for d in prev.fmg if d.get("level", -1) < j] if j is not None else []
        if j is None or not (below or cycle_floor_points(self.problem.M, self.problem.L)) or prev.P is None:
            return None
        lv = self.levels[j]
        lv.P, lv.H0 = np.array(prev.P, dtype=float), float(prev.H0)
        lv.f = np.zeros(lv.n)
        lv.g = 0.5 * math.pi
        self.resumed_fmg = [dict(d) for d in below]
        # prev started on its own finest grid from a given solution: so does this one, in effect
        if not below:
            self._from_guess()
        first = min((d["level"] for d in below), default=0)  # where prev's own FMG started
        self.film_floor = first if first > self._start_level() else 0
        solver.note(f"FMG resumed on the {lv.n}-point grid from the converged solve there")
        return j

    def _guess_start_above(self, k: int, solver: MultilevelSolver) -> int | None:
        """FMG from the grid above ``k`` (the largest dense start grid, found without a positive
        film by an earlier solve of the sequence), solved by cycles from the given solution,
        instead of cycles on the finest grid from it, where the coarse grids' Newton fails and
        the estimate lacks FMG films (docs/accuracy.md, "Cycled start"). None when that grid's
        cycles fail or settle on no positive film, and for isoviscous contacts."""
        j = k + 1
        if j >= len(self.levels) - 1 or self.problem.L <= 0.0:
            # isoviscous: FMG through the fine grids rejects cycle after cycle, slower than the
            # finest-grid start (docs/accuracy.md, "Cycled start")
            return None
        lv = self.levels[j]
        self._initial_guess(lv)
        if not (self._cycled_start(j, solver, "the given solution") and self._film_ok(lv)):
            return None
        if lv.n <= MAX_START_POINTS:
            # a floor is solved by dense Newton in every cycle after a rejection: above the
            # dense start's limit that cost 55 s per cycle (36 factorisations on 4097 points,
            # M = 4904 in a continuation), so the grids below stay in the cycles there
            self.film_floor = j
        solver.note(f"no positive film on the start grids up to {self.levels[k].n} points (an "
                    "earlier solve of this contact)")
        return j

    def _cycled_start(self, k: int, solver: MultilevelSolver, source: str = "") -> bool:
        """Solve start grid ``k`` from its present iterate (a converged neighbour's solution)
        by FAS cycles through the grids below it, which carry no positive film of their own
        but serve as coarse grids ((3000, 6) at 0.5 %: 6 cycles on 2049 points instead of four
        dense single-precision factorisations). True when the cycles settle (on
        a positive film or not: the grid's own discrete solution either way); False, with the
        iterate restored, when they fail or do not settle within :data:`START_CYCLES`."""
        lv = self.levels[k]
        saved = self.snapshot(k)
        # what a failed trial would change besides the iterate: the coarse grids' Newton record
        failed, actions = set(self.newton_failed), len(solver.actions)
        factors = [getattr(v, "kept_factor", None) for v in self.levels[:k]]
        prev = math.nan
        for _ in range(START_CYCLES):
            try:
                m = solver.trial_cycle(k)
            except (np.linalg.LinAlgError, FloatingPointError, ValueError, NewtonFailure):
                break
            if not (math.isfinite(m.residual) and math.isfinite(m.Hc) and self.finite_at(k)):
                break
            # settled: this grid's discrete solution, whether or not its film is positive (the
            # film may pass through non-positive values on the way from a coarser grid's)
            if abs(m.Hc - prev) <= START_CYCLE_HC * abs(m.Hc) and m.residual <= START_CYCLE_RESIDUAL:
                if self._film_ok(lv):
                    solver.note(f"FMG start on {lv.n} points solved by FAS cycles from "
                                + (source or f"the {self.levels[k - 1].n}-point solution"))
                return True
            prev = m.Hc
        self.restore(k, saved)
        self.newton_failed = failed
        del solver.actions[actions:]
        for v, f in zip(self.levels, factors, strict=False):
            v.kept_factor = f
        return False

    def _continuation(self, lv: LineLevel) -> int:
        pb = self.problem
        total = 0
        steps = [0.1, 0.25, 0.5, 0.75, 1.0]
        for s in steps:
            M = max(pb.M * s, min(pb.M, 5.0))
            L = pb.L * s
            sub = dataclasses.replace(pb, M=M, L=L, pmax=math.nan) if pb.source == "moes" else \
                dataclasses.replace(pb, M=M, L=L, pmax=pb.pmax * math.sqrt(M / pb.M))
            lv.par, lv.lam = sub.rheology(), sub.lam
            if s == steps[0]:
                self._initial_guess(lv)
            try:
                total += newton_solve(lv, max_iter=200,
                                      check=self.newton_check(lv, f"start continuation (M = {M:.4g})"))
            except NewtonFailure as exc:
                lv.par, lv.lam = pb.rheology(), pb.lam
                raise ConvergenceError(
                    f"the first coarse solution failed even with continuation "
                    f"(M = {M:.4g}, L = {L:.4g}: {exc})", None, HINT) from None
        lv.par, lv.lam = pb.rheology(), pb.lam
        return total

    # -- last resort ----------------------------------------------------------------------
    def last_resort(self, k: int, solver: MultilevelSolver) -> bool:
        """When the cycles stall or diverge on a grid small enough for a dense solve: Newton
        on the finest grid from the multigrid iterate (the full-system path)."""
        fin = self.levels[k]
        if fin.n > MAX_START_POINTS:
            return False
        saved = (fin.P.copy(), fin.H0)
        fin.frozen[:] = False
        try:
            its = newton_solve(fin, max_iter=60, check=self.newton_check(fin, "finest-grid"))
        except NewtonFailure as exc:
            fin.P, fin.H0 = saved
            solver.note(f"finest-grid Newton after the multigrid stall failed: {exc}")
            return False
        fin.P = np.maximum(fin.P, 0.0)
        self.newton_iterations += its
        solver.work_units += its  # one dense finest-grid Newton step counted as one work unit
        solver.note(f"multigrid stalled: finished by {its} dense Newton iterations on the "
                    f"{fin.n}-point grid")
        solver.record(k, -1, self.measure(k))
        return solver.converged()


def fas_coarse_problem(lv: LineLevel, cv: LineLevel, r_fine: np.ndarray) -> tuple[np.ndarray, float]:
    """Set up the FAS problem of the coarse grid ``cv`` from the fine grid ``lv`` and its
    residual ``r_fine`` (already restricted to what the coarse grid may correct): injected P
    and H0, the Brandt & Cryer free set, ``f_H = L_H(I P_h) + R r_h`` and the load target.
    Returns the coarse start ``(P, H0)`` the correction is measured from.

    Brandt & Cryer: a coarse point is free only if its fine neighbourhood is free (positive
    pressure, not frozen); the others keep their value, so the coarse grid never moves the
    free (cavitation) boundary -- relaxation does."""
    cv.P = inject(lv.P)
    cv.H0 = lv.H0
    free = (lv.P > 0.0) & ~lv.frozen
    cfree = free[::2].copy()
    cfree[1:] &= free[1::2]
    cfree[:-1] &= free[1::2]
    cv.frozen = ~cfree
    cv.frozen[0] = cv.frozen[-1] = False
    P_start, H0_start = cv.P.copy(), cv.H0
    cv.f = np.zeros(cv.n)
    cst = cv.state()
    # with f = 0 the coarse residual is -L_H(I P_h)
    cv.f = -cst.r + full_weighting(r_fine)
    cv.f[0] = cv.f[-1] = 0.0
    cv.g = cv.load() + (lv.g - lv.load())
    return P_start, H0_start


def line_settings(problem: LineProblem, options: LineOptions) -> Settings:
    gain = options.h00_gain if options.h00_gain is not None else \
        options.default_h00_gain(problem.M, problem.L)
    switch_h = options.switch_h if options.switch_h is not None else default_switch_h(problem)
    return Settings.start(options, gain, options.switch if options.switch is not None else 0.3, switch_h)


def line_solver(problem: LineProblem, options: LineOptions,
                progress: Callable[[str], None] | None = None,
                deadline_checks: bool = False) -> MultilevelSolver:
    """The multilevel solver of one line-contact problem (not yet run); ``progress(text)``
    hears of a long dense Newton solve. With ``deadline_checks`` it stops when the time budget
    of the sequence it runs in (:func:`~ehl_multigrid.multigrid.controller.deadline`) runs
    out: status ``time_budget``."""
    hz = LineHierarchy(problem, options)
    hz.stall_steps = True
    hz.deadline_checks = deadline_checks
    hz.progress = progress
    hz.local_newton = options.local_newton
    hz.local_newton_pre = problem.alpha_bar > LOCAL_NEWTON_PRE_ALPHA
    hz.switch_eps = options.switch_eps if options.switch_eps is not None else \
        default_switch_eps(problem)
    solver = MultilevelSolver(hz, options, line_settings(problem, options),
                              RobustnessPolicy(STEADY_LINE_POLICY, options.adapt), HINT)
    hz.solver = solver
    solver.deadline_checks = deadline_checks
    return solver


#: A solve whose FMG start grids (up to MAX_START_POINTS) cannot hold a positive film starts from
#: the same contact at M/2, itself continued from M/4 when its own start fails, and so on up to
#: this many halvings: isoviscous (5000, 0) needs one (docs/robustness.md, "Line solver defaults").
CONTINUATION_HALVINGS = 3


def neighbour_problem(problem: LineProblem, factor: float) -> LineProblem:
    """The same contact at ``factor`` times the load parameter M (same L and lubricant model,
    ``pmax`` scaled so that ``alpha pmax = alpha_bar(M, L)``): a start for continuation in M."""
    return dataclasses.replace(problem, M=problem.M * factor, pmax=problem.pmax * math.sqrt(factor))


def continued_in_m(problem: LineProblem, options: LineOptions, callback: Any = None,
                   scene: Any = None, start_cache: dict | None = None,
                   progress: Callable[[str], None] | None = None,
                   why: list[str] | None = None) -> EHLResult | None:
    """Solve ``problem`` from a converged solution at a smaller M (continuation in M, see
    :data:`CONTINUATION_HALVINGS`); None when no halving starts or a step back up fails, the
    failed step's result (status ``time_budget``) when the time budget ran out in a step.
    ``start_cache``: that of the failed solve (:func:`solve_line_problem`), so the steps do not
    solve again the start grids it found without a positive film (isoviscous (5000, 0): 6 s).
    ``progress(text)`` receives one line per step; ``why`` (a list) receives what failed
    when the continuation does not reach ``problem`` (the step, its grid and its failure)."""
    starts = {} if start_cache is None else start_cache
    # a failed step is this search's answer (None), not an error: its solves return failures
    options = dataclasses.replace(options, raise_on_failure=False)
    n = options.points
    t0 = time.perf_counter()

    def step(q: LineProblem, what: str, **kw: Any) -> EHLResult:
        if progress is not None:
            progress(f"{n} points: continuation in M to {problem.M:.4g}, {what} M = {q.M:.4g} "
                     f"({time.perf_counter() - t0:.1f} s in the continuation)")
        r = solve_line_problem(q, options, callback=callback, progress=progress, start_cache=starts,
                               deadline_checks=True, **kw)
        if r.status_name == "time_budget":
            r.message = (f"{r.message} (in the continuation in M to {problem.M:.4g} on {n} points, "
                         f"{what} M = {q.M:.4g}, after {time.perf_counter() - t0:.1f} s in it)")
        return r

    def failed(r: EHLResult, what: str) -> None:
        if why is not None:
            # the driver names the failed grid by its level ("diverged on grid 4"): in points
            # here; else the last grid cycled on
            lvl = re.search(r"on grid (\d+)", r.message)
            last = int(lvl.group(1)) if lvl else (r.history[-1].level if r.history else r.levels - 1)
            at = (n - 1) // 2 ** max(r.levels - 1 - last, 0) + 1
            why.append(f"the continuation in M {what} ended {r.status_name} on the {at}-point grid "
                       f"({r.message.split(';')[0]})")

    chain = [problem]
    start: EHLResult | None = None
    for _ in range(CONTINUATION_HALVINGS):
        if chain[-1].M / 2.0 < 0.1:
            return None
        q = neighbour_problem(chain[-1], 0.5)
        r = step(q, "a start at", scene=None)
        if r.success:
            start = r
            break
        if r.status_name == "time_budget":
            return r
        if r.status_name != "start_failed":
            failed(r, f"started at M = {q.M:.4g}:")
            return None
        chain.append(q)
    if start is None:
        return None
    path = [f"{start.problem.M:.4g}"]
    for q in reversed(chain):
        r = step(q, f"from M = {start.problem.M:.4g} up to", scene=scene if q is problem else None,
                 guess=(start.X, start.P, start.H0))
        if r.status_name == "time_budget":
            return r
        if not r.success:
            failed(r, f"from M = {' -> '.join(path)}, its step to M = {q.M:.4g}")
            return None
        start = r
        path.append(f"{q.M:.4g}")
    start.actions.append("the start grids hold no positive film at this M: continued in M from "
                         + " -> ".join(path) + " (CONTINUATION_HALVINGS)")
    return start


#: :func:`from_start_grid` stops on this fraction of the film tolerance: its start is farther
#: from the discrete solution than the continuation's, and at the full tolerance the accuracy
#: loop's grid choice moved (docs/performance.md, "Line contacts at high load")
FROM_START_GRID_FILM_TOL = 0.25


def from_start_grid(problem: LineProblem, options: LineOptions, filmless: dict,
                    callback: Any = None, scene: Any = None, start_cache: dict | None = None,
                    progress: Callable[[str], None] | None = None) -> EHLResult | None:
    """Solve ``problem``, whose solve ended ``start_failed`` and left its largest start grid's
    discrete solution (film not positive) in ``filmless`` (:func:`filmless_start_key`), by
    cycles on its finest grid from that solution: the pressure is close, and the cycles on the
    fine grid give the film its sign. None where ``filmless`` holds no such solution or the
    cycles fail (the continuation in M, :func:`continued_in_m`, is then tried); the failed
    result where the time budget ran out.

    Isoviscous (3000-5000, 0) and (5000, 5) on 16385 points: 5-8 cycles, about as many as from
    the continuation's converged solution at M/2, without that solve (docs/performance.md, "Line
    contacts at high load")."""
    settled = filmless.get(filmless_start_key(problem, options))
    if settled is None:
        return None
    X = settled[0]
    if progress is not None:
        progress(f"{options.points} points: cycles from the {X.size}-point start grid's solution "
                 f"(its film not positive)")
    tight = {} if options.film_tol is None else {"film_tol": options.film_tol * FROM_START_GRID_FILM_TOL}
    r = solve_line_problem(problem, dataclasses.replace(options, raise_on_failure=False, **tight),
                           callback=callback, scene=scene, guess=settled, start_cache=start_cache,
                           progress=progress, deadline_checks=True)
    if r.status_name == "time_budget":
        return r
    if not r.success:
        return None
    r.actions.append(f"the start grids hold no positive film at this M: cycles on the "
                     f"{options.points}-point grid from the {X.size}-point start grid's solution")
    return r


def solve_line_problem(problem: LineProblem, options: LineOptions | None = None,
                       callback: Callable[[dict[str, Any]], None] | None = None,
                       scene: Any = None, guess: tuple[np.ndarray, np.ndarray, float] | None = None,
                       from_guess: bool = False, start_cache: dict | None = None,
                       resume: EHLResult | None = None,
                       progress: Callable[[str], None] | None = None, deadline_checks: bool = False,
                       filmless_starts: dict | None = None, **kw: Any) -> EHLResult:
    """Solve one :class:`LineProblem` as given (no error estimate); keywords override
    ``options``. ``guess = (X, P, H0)``, a solution of the same contact on another grid or box,
    starts the FMG start grid's Newton (the answer is the same; it takes fewer iterations);
    with ``from_guess`` the cycles start on the finest grid from it, without FMG (the FMG
    films, and so the Richardson part of an error estimate, are then missing).
    ``start_cache`` (a dict shared by the solves of one accuracy sequence) keeps the converged
    FMG start grids: a later solve of the sequence starts its Newton there from that solution
    ((3000, 6) at 0.5 %: one dense 2049-point Newton solve of 3-4 s instead of three).
    ``resume``, a converged solve of the same discrete problem on a coarser grid of this one,
    continues its FMG from there (the grids below keep its FMG films). ``progress(text)``
    hears of a long dense Newton solve (:meth:`LineHierarchy.newton_check`); with
    ``deadline_checks`` the solve ends with status ``time_budget`` when the time budget of its
    sequence runs out (between dense Newton iterations and cycles). ``filmless_starts`` (a
    dict) receives the largest start grid's discrete solution when the solve ends
    ``start_failed`` with it (:func:`from_start_grid`).

    A numerical failure is returned (``success`` False, its status and message), or raised as
    :class:`ConvergenceError` with ``raise_on_failure=True``."""
    from .solution import finish_line_result

    opts = LineOptions.build(options, **kw)

    def attempt(o: LineOptions) -> tuple[MultilevelSolver, EHLResult]:
        s = line_solver(problem, o, progress, deadline_checks)
        s.hierarchy.guess = guess
        s.hierarchy.start_on_guess = from_guess
        s.hierarchy.start_cache = start_cache
        s.hierarchy.resume = resume
        s.hierarchy.filmless_starts = filmless_starts
        return s, s.solve(callback=callback)

    solver, res = attempt(opts)
    levels = len(solver.hierarchy.levels)
    while (opts.retry_finer_start and opts.adapt and opts.levels is None and not from_guess
           and res.status_name == "diverged" and res.history and levels > 2
           and res.history[-1].level < levels - 1):
        # a coarse grid whose correction cannot carry this film ((300, 10) on 257 -> 513 points):
        # FMG from a start grid twice as fine
        levels -= 1
        solver.hierarchy.solver = None  # frees the failed attempt's grids
        first, (solver, res) = res, attempt(dataclasses.replace(opts, levels=levels))
        res.work_units += first.work_units
        res.wall_s += first.wall_s
        res.actions.append(f"diverged on grid {first.history[-1].level} of {levels + 1}; solved "
                           f"again on {levels} grids (coarsest twice as fine; retry_finer_start): "
                           f"{res.status_name}")
    out = finish_line_result(res, solver, scene)
    # the face coefficient the grids used (the estimate's rule for Hm depends on it)
    out.extra["face"] = "logarithmic" if solver.hierarchy.levels[-1].face else "arithmetic"
    solver.hierarchy.solver = None  # break the solver <-> hierarchy cycle (frees the grids)
    return out


def line_domain_change(problem: LineProblem, options: LineOptions, sol: EHLResult,
                       boxes: tuple[float, ...] = (1.0, 2.0),
                       below_start: Callable[[tuple[float, float]], bool] | None = None,
                       ) -> tuple[float, float] | list[tuple[float, float]] | None:
    """Relative change of (Hc, Hm) when the inlet is moved upstream by the box length at equal
    mesh size, measured by two converged solves on a coarse grid of the solve (two grids below
    the finest, not below the FMG start grid; one grid finer when that does not converge);
    None when no pair converges. ``boxes`` (box lengths in units of the solve's, each twice the
    one before) with more than two entries returns the list of the successive changes, each
    relative to the shorter box (:func:`line_domain_decay`).

    ``below_start(change)``: the grids below the FMG start grid may measure it too (a solve
    started on its finest grid, as the continuation in M does, has no FMG grids below it); a
    change measured there counts only where ``below_start`` accepts it, else a finer grid
    measures it. The box change is an inlet effect that coarse meshes resolve (docs/accuracy.md,
    "Domain error").

    Each probe solve starts its cycles on its finest grid from the solution, with a film
    tolerance of :data:`GUESS_PROBE_FILM_TOL` (FMG at ``PROBE_FILM_TOL`` when that fails): both
    solves stay near the same start, so a loose tolerance biases the change to zero; at 1e-6 the
    change is close to that of tight probes and cheaper than FMG probes (docs/robustness.md)."""
    top = sol.levels - 1
    k_fmg = min(d["level"] for d in sol.fmg)
    k0 = max(top - 2, k_fmg if below_start is None else 0)
    grids = list(range(k0, top + 1))
    n_top = sol.X.shape[0] - 1
    k_look = next((k for k in range(k_fmg, k0) if n_top // 2 ** (top - k) + 1 >= COARSE_PROBE_POINTS), None)
    if below_start is not None and k_look is not None and problem.L > 0.0:
        # a first look on a coarse FMG grid, cheaper than two grids below the finest (1025
        # points instead of 4097 for (1500, 8) at 0.5 %): counted only where far below. Not
        # isoviscous: their coarse grids hardly carry a film at high M, and the look cost more
        # than it saved ((1000, 0) 1.6 -> 2.5 s, (2000, 0) 3.6 -> 4.6 s)
        grids.insert(0, k_look)
    length = problem.xmax - problem.xmin
    solved: dict[tuple[float, int], EHLResult] = {}
    for kp in grids:
        n_p = (sol.X.shape[0] - 1) // 2 ** (top - kp) + 1

        def solve(f: float, n: int) -> EHLResult:
            pb = problem if f == 1.0 else dataclasses.replace(problem, xmin=problem.xmax - f * length)
            opts = dataclasses.replace(options, points=int(round((n - 1) * f)) + 1, levels=None,
                                       fmg_start_points=None, raise_on_failure=False,
                                       film_tol=GUESS_PROBE_FILM_TOL)
            guess = (sol.X, sol.P, sol.H0)
            res = solve_line_problem(pb, opts, guess=guess, from_guess=True)
            if res.success:
                return res
            # several boxes: their changes shrink with each doubling, so the FMG fallback is as
            # tight as the start from the solution
            ftol = PROBE_FILM_TOL if len(boxes) == 2 else GUESS_PROBE_FILM_TOL
            return solve_line_problem(pb, dataclasses.replace(opts, film_tol=ftol), guess=guess)

        def solved_at(f: float, n: int = n_p) -> EHLResult:
            # one solve per box and grid: the wide solve of one doubling is the short one of the next
            if (f, n) not in solved:
                solved[(f, n)] = solve(f, n)
            return solved[(f, n)]

        changes = []
        for f in boxes[:-1]:
            change = film_change(lambda f=f: solved_at(f), lambda f=f: solved_at(2.0 * f))
            if change is None:
                break
            changes.append(change)
        if len(changes) == len(boxes) - 1:
            if kp < max(k_fmg, k0) and below_start is not None and not all(below_start(c) for c in changes):
                continue
            return changes[0] if len(boxes) == 2 else changes
    return None


def line_domain_decay(problem: LineProblem, options: LineOptions, sol: EHLResult
                      ) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The changes of (Hc, Hm) over two successive doublings of the box length (inlet moved
    upstream; 1x -> 2x -> 4x of the solve's box, equal mesh): the input of
    :func:`~ehl_multigrid.multigrid.accuracy.domain_from_decay`. None when a solve fails."""
    changes = line_domain_change(problem, options, sol, boxes=(1.0, 2.0, 4.0))
    if changes is None:
        return None
    return changes[0], changes[1]


#: option fields that change how a line problem is iterated, not the discrete problem solved
ITERATION_FIELDS = ("points", "levels", "tol", "tol_load", "film_tol", "max_cycles", "omega",
                    "omega_jd", "h00_gain", "cycle", "raise_on_failure")


def resumable(grids: dict, n: int, box: float, options: LineOptions) -> EHLResult | None:
    """Of ``grids`` (``(points, box) -> converged solve`` of one accuracy sequence), the solve
    on the finest of ``n`` points' coarser grids on ``box`` with the same discretisation
    options: an FMG to ``n`` points goes on from it (:meth:`LineHierarchy._resumed_start`)."""
    # (a solve started on its finest grid from a given solution has no FMG films to keep; one
    # whose cycles were rejected leaves a fragile start: resumed, page-63 500 N's 8193 points at
    # 0.1 % rejected cycles where the whole FMG did not, 1.4 s against 0.14 s)
    fits = [r for (m, b), r in grids.items() if b == box and m < n and (n - 1) % (m - 1) == 0
            and (any(d.get("level", -1) < r.levels - 1 for d in r.fmg) or cycle_floor_points(r.problem.M, r.problem.L))
            and not any("rejected" in a for a in r.actions)
            and dataclasses.replace(r.options, **{f: getattr(options, f) for f in ITERATION_FIELDS}) == options]
    return max(fits, key=lambda r: r.X.size, default=None)


def solve_line(
    M: float | None = None, L: float | None = None, *, scene: Any = None,
    viscosity: str | None = None, density: str | None = None,
    alpha: float | None = None, eta0: float | None = None, p0: float | None = None,
    xmin: float | None = None, xmax: float | None = None, elastic: bool = True,
    callback: Callable[[dict[str, Any]], None] | None = None,
    options: LineOptions | None = None, accuracy: float | None = None, estimate: bool = True,
    max_points: int = MAX_ACCURACY_POINTS, progress: Callable[[str], None] | None = None,
    time_budget: float | None = None, **kw: Any,
) -> EHLResult:
    """Solve the steady isothermal EHL line contact (Venner's dimensionless Reynolds, film
    and load equations; Roelands (2.6) and Dowson-Higginson (2.7) by default).

    Give either Moes ``M, L`` (oil data ``alpha``, ``eta0``, ``p0`` default to
    :data:`~ehl_multigrid.model.constants.MOES_ONLY_DEFAULTS`) or a line-contact ``scene``,
    whose ``[solver.ehl]`` table (viscosity, density, xmin, xmax and any option) applies
    below the explicit arguments. Defaults: Roelands, Dowson-Higginson, xmax = 1.5.
    Numerical options are a :class:`~ehl_multigrid.multigrid.options.LineOptions` and/or
    its fields as keywords (points, levels, cycle, deformation, tol, ...).

    ``accuracy`` (relative, e.g. 0.005) asks for Hc and Hm within that error: the grid is
    chosen from the measured grid-error constants and refined (one more FMG grid, a wider
    box, tighter tolerances) until the estimated error meets it or ``max_points`` is reached;
    an explicit ``points`` or ``xmin`` is kept and only judged. Every result carries its
    estimated errors (``Hc_error``, ``Hm_error``, ``error.budget``: grid, domain, algebraic)
    unless ``estimate=False``; with an accuracy, ``success`` also requires the estimate to
    meet it (status ``"inaccurate"`` otherwise). ``progress(text)`` receives one line per
    solve of that sequence. ``time_budget`` (seconds) bounds that sequence: no refinement is
    started that is predicted to overrun it, and the most accurate answer so far comes back
    (``"inaccurate"`` when it misses the target).

    Returns
    -------
    EHLResult
        ``.to_result()`` gives the package :class:`~ehl_multigrid.model.results.Result` (kind
        ``"ehl_line"``). By default a numerical failure is returned, not raised: ``success``
        False, a status other than ``converged``, the message, and what was computed.

    Raises
    ------
    InputError
        Bad input (field, value, allowed range).
    ConvergenceError
        Only with ``raise_on_failure=True``: the failure the result would have carried.

    Examples
    --------
    >>> sol = solve_line(20, 10, points=257)              # doctest: +SKIP
    >>> round(sol.Hc, 2), sol.success, sol.status_name    # doctest: +SKIP
    """
    model, table = scene_solver_table(scene, "line") if scene is not None else ({}, {})
    given = {"viscosity": viscosity, "density": density, "xmin": xmin, "xmax": xmax}
    prob = {**{"viscosity": "roelands", "density": "dowson-higginson", "xmax": 1.5}, **model,
            **{k: v for k, v in given.items() if v is not None}}
    if scene is not None:
        if M is not None or L is not None:
            raise InputError("give either a scene or M and L, not both")
        pb = LineProblem.from_scene(scene, elastic=elastic, **prob)
    else:
        if M is None or L is None:
            raise InputError("solve_line needs M and L (Moes groups) or a scene")
        pb = LineProblem.from_moes(M, L, alpha=alpha, eta0=eta0, p0=p0, elastic=elastic, **prob)
    opts = build_scene_options(LineOptions, options, table, kw)
    if not estimate:
        return solve_line_problem(pb, opts, callback=callback, scene=scene)
    if opts.face == "logarithmic" and pb.alpha_bar < FACE_LOG_ALPHA:
        # the estimate's rules for logarithmic faces were checked where "auto" takes them
        raise InputError(f"face = 'logarithmic' with an error estimate needs alpha_bar >= "
                         f"{FACE_LOG_ALPHA:g} (here {pb.alpha_bar:.3g}): use face = 'auto' or "
                         f"'arithmetic', or a plain solve (estimate=False)")
    explicit = "points" in kw or "points" in table or (options is not None and accuracy is None)
    fixed_box = xmin is not None or "xmin" in model
    if accuracy is not None:
        require_range("accuracy", accuracy, 1e-5, 0.5, "- (relative error)")
    require_range("max_points", max_points, 65, 262145, "points")
    if time_budget is not None:
        require_range("time_budget", time_budget, 0.0, math.inf, "s")
    points = opts.points
    if accuracy is not None and not explicit:
        points = min(max(solver_grid("line", pb.M, accuracy).points, 33), max_points)

    last: list[EHLResult] = []  # the previous converged solve starts the next one's Newton
    starts: dict = {}  # the sequence's converged FMG start grids (solve_line_problem)
    filmless: dict = {}  # start grid solutions without a positive film (from_start_grid)
    grids: dict = {}  # the converged solve of each grid and box: a tolerance step continues it
    # the time budget stops any solve but the sequence's first (what a budget of 0 returns) and
    # the continuation in M (docs/accuracy.md, "The accuracy controller")
    checks: list[bool] = [False]

    def solve(n: int, box: float, tol_factor: float) -> EHLResult:
        p = pb if box == 1.0 else dataclasses.replace(pb, xmin=pb.xmax - box * (pb.xmax - pb.xmin))
        o = dataclasses.replace(opts, points=n, tol=opts.tol * tol_factor,
                                tol_load=opts.tol_load * tol_factor, raise_on_failure=False,
                                film_tol=film_tol(opts, accuracy, tol_factor))
        guess = (last[-1].X, last[-1].P, last[-1].H0) if last else None
        prev = grids.get((n, box))
        res = None
        if prev is not None and tightening(prev, o, same=("points",)):
            # a tolerance step: the cycles go on from the converged solve of this grid and box,
            # with the relaxation it ended with
            t = solve_line_problem(p, dataclasses.replace(o, **ended_relaxation(prev)),
                                   callback=callback, scene=scene, guess=(prev.X, prev.P, prev.H0),
                                   from_guess=True, deadline_checks=checks[0])
            res = tightened(prev, t, o) if t.success and t.levels == prev.levels else None
        # isoviscous: FMG through the fine grids rejects cycle after cycle (docs/accuracy.md,
        # "Cycled start"); the resumed attempt failed and cost (3000, 0) 0.6 s
        resume = resumable(grids, n, box, o) if pb.L > 0.0 or cycle_floor_points(pb.M, pb.L) else None
        if res is None and resume is not None:
            res = solve_line_problem(p, o, callback=callback, scene=scene, guess=guess,
                                     start_cache=starts, resume=resume, progress=progress,
                                     deadline_checks=checks[0])
            if not res.success:
                res = None  # the FMG from the start grids, as without the coarser solve
        if res is None:
            res = solve_line_problem(p, o, callback=callback, scene=scene, guess=guess, start_cache=starts,
                                     progress=progress, deadline_checks=checks[0], filmless_starts=filmless)
        if res.status_name == "start_failed" and guess is None:
            res = from_start_grid(p, o, filmless, callback, scene, starts, progress) or res
        if res.status_name == "start_failed" and guess is None:
            why: list[str] = []
            res = continued_in_m(p, o, callback, scene, starts, progress, why) or res
            if why and not res.success:
                # the start grids' film is not all that failed: say where the continuation did
                res.message += f"; {why[0]}"
        checks[0] = True
        if res.success or res.status_name == "inaccurate":
            last[:] = [res]  # only the latest: fine-grid results are large
        if res.success:
            grids[(n, box)] = res
        return res

    def far_below(change: tuple[float, float]) -> bool:
        # a change measured below the grids the solve's FMG reached: trusted where its domain
        # part lies far below the target (coarse and fine meshes measured the same change
        # within a factor 1.2 where it exceeds the probes' noise; docs/accuracy.md)
        return accuracy is not None and (
            LINE_DOMAIN_SAFETY * max(abs(change[0]), abs(change[1])) < DOMAIN_REUSE_BELOW * accuracy)

    def probe(res: EHLResult, box: float) -> tuple[float, float] | None:
        return line_domain_change(res.problem, res.options, res, below_start=far_below)

    def no_film(n: int, box: float) -> bool:
        # a start grid whose dense Newton start found no positive film (start cache None): a
        # repair solve there fails (film_not_positive; (5000, 0) at 2049 points: 0.6 s)
        p = pb if box == 1.0 else dataclasses.replace(pb, xmin=pb.xmax - box * (pb.xmax - pb.xmin))
        key = start_key(p, opts, n, float(p.xmin), float(p.xmax), opts.wedge_order)
        return key in starts and starts[key] is None

    def decay_probe(res: EHLResult, box: float) -> tuple[tuple[float, float], tuple[float, float]] | None:
        return line_domain_decay(res.problem, res.options, res)

    res = solve_to_accuracy(solve, probe, accuracy, points, max_points,
                            refine=accuracy is not None and not (explicit or fixed_box),
                            decay_probe=decay_probe, progress=progress, dimensions=1, extrapolate=True,
                            time_budget=math.inf if time_budget is None else time_budget,
                            domain_safety=LINE_DOMAIN_SAFETY, no_film=no_film)
    if not res.success and opts.raise_on_failure:
        raise ConvergenceError(f"line solver: {res.message}", res.report, HINT)
    return res
