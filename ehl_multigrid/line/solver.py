"""Venner-style multilevel solver for the steady isothermal EHL line contact (MODEL.md 5).

Full Approximation Scheme (FAS) V or W cycles inside Full Multigrid (FMG):

* relaxation: collective line relaxation (:meth:`LineLevel.relax`) switching between
  Gauss-Seidel changes where ``eps/h^2 >= threshold`` and Jacobi-distributive changes where it
  is smaller, under-relaxed with ``omega_gs``/``omega_jac``, negative pressures projected to 0;
* film constant: on the coarse levels of a cycle ``H0`` is relaxed with the load error,
  ``H0 += h0_factor (h sum P - g)``; the coarsest grid is solved exactly for ``(P, H0)`` by a
  damped semismooth Newton iteration (newton.py), so the load balance is enforced through
  the FAS load right-hand side ``g`` on every level;
* transfers: injection of ``P``, full weighting of residuals, linear interpolation of
  corrections, cubic FMG interpolation;
* deformation on each grid by MLMI, FFT or the direct sum (deformation.py).

Robustness: a cycle that increases the residual (or produces NaN) is undone and repeated with
halved under-relaxation (adaptive damping); at high load the FMG starts on a finer grid so
the first coarse solution has a positive film; every action is recorded in
``solver.actions``. Divergence, NaN or a stall raise :class:`ConvergenceError` with what to
try. Convergence means the relative complementarity residual is below ``tol`` AND the relative
load error below ``tol_load``.

The interface follows pyamg's ``MultilevelSolver``: the object exposes ``levels``,
``cycle`` and ``residuals`` and ``solve(callback=...)``.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from ..model.convergence import ConvergenceReport
from ..model.errors import ConvergenceError, InputError, require_choice, require_range
from ..model.fits import moes_line_central
from .deformation import METHODS
from .discrete import projected
from .level import LineLevel, State, full_weighting, inject, interpolate_cubic, interpolate_linear
from .newton import NewtonFailure, newton_solve
from .problem import LineProblem, check_grid

if TYPE_CHECKING:
    from .solution import LineSolution

#: Largest grid solved directly by Newton at the start of FMG (dense Jacobian).
MAX_START_POINTS = 2049

HINT = ("more levels or points (finer coarsest grid), W cycles (--cycle W), a smaller H0 factor "
        "(h0_factor), smaller under-relaxation (omega_gs/omega_jac), or a longer inlet (--xmin)")


def coarse_points(M: float) -> int:
    """Default coarsest grid: at high load a coarse grid cannot carry a positive film
    (MODEL.md 5 "Numerical facts"), so the coarsest grid is refined with M."""
    return 65 if M <= 50 else (129 if M <= 200 else (257 if M <= 1000 else 513))


def default_threshold_h(problem: LineProblem) -> float:
    """Fine-grid switch constant (Jacobi-distributive where ``eps/h^2 < threshold_h/h``).

    Chosen from measured convergence on a test set of 17 (M, L, N) cases (REPORT.md): with
    little pressure-viscosity (``alpha_bar < 1``) ``eps`` stays large in the contact and
    Gauss-Seidel there diverges unless ``threshold_h ~ 1``; at moderate ``alpha_bar`` a small
    h-scaled threshold (0.1) removes the stalls of the classic fixed threshold on fine grids;
    at high ``alpha_bar`` (> 100) the classic threshold alone works best.
    """
    if not problem.elastic:
        return 0.0
    abar = problem.alpha_bar
    return 1.0 if abar < 1.0 else (0.1 if abar <= 100.0 else 0.0)


@dataclass
class LineSolverOptions:
    """Numerical options of :class:`MultilevelLineSolver` (defaults in brackets).

    points [1025] finest-grid points (2^k + 1); levels [coarsest grid from coarse_points(M)];
    cycle ["V"] or "W"; cycles [2] FAS cycles per FMG level; max_cycles [60] extra cycles on
    the finest grid to reach the tolerances; nu1, nu2 [2, 1] pre/post relaxations;
    deformation ["mlmi"], "fft" or "direct"; mlmi_order, mlmi_radius [12, 48];
    threshold [0.3], threshold_h [default_threshold_h]: Jacobi-distributive where
    ``eps/h^2 < max(threshold, threshold_h/h)`` (discrete.line_relaxation_system), else Gauss-Seidel; omega_gs, omega_jac
    [0.5, 0.3] under-relaxation; band [4] half band width of the line systems;
    h0_factor [0.1 V, 0.05 W; /4 if L > 10 or M > 1000] H0 relaxation on coarse levels;
    tol [1e-5] relative complementarity residual (Hc then changes < ~1e-5 relative per
    cycle, far below the discretisation error); tol_load [1e-6] relative load error;
    wedge_order [2] upwind order of the wedge term; fmg_start_points [auto] grid on which FMG
    starts (finer at high M so the first film is positive); raise_on_failure [True].
    """

    points: int = 1025
    levels: int | None = None
    cycle: str = "V"
    cycles: int = 2
    max_cycles: int = 60
    nu1: int = 2
    nu2: int = 1
    deformation: str = "mlmi"
    mlmi_order: int = 12
    mlmi_radius: int = 48
    threshold: float = 0.3
    threshold_h: float | None = None
    omega_gs: float = 0.5
    omega_jac: float = 0.3
    band: int = 4
    h0_factor: float | None = None
    tol: float = 1e-5
    tol_load: float = 1e-6
    wedge_order: int = 2
    fmg_start_points: int | None = None
    raise_on_failure: bool = True
    correction_mask: float | None = None
    fmg_match_film: bool = True

    def validate(self, M: float = 20.0) -> None:
        if self.levels is None:
            n = self.points - 1
            nc = min(coarse_points(M) - 1, n)
            self.levels = max(1, int(round(math.log2(max(n, 1) / max(nc, 1)))) + 1)
        check_grid(self.points, self.levels)
        require_choice("cycle", self.cycle, ("V", "W"))
        require_range("cycles", self.cycles, 1, 50, "cycles per FMG level")
        require_range("max_cycles", self.max_cycles, 0, 10000, "cycles")
        require_range("nu1", self.nu1, 0, 50)
        require_range("nu2", self.nu2, 0, 50)
        if self.nu1 + self.nu2 < 1:
            raise InputError("nu1 + nu2 must be >= 1 (at least one relaxation per level)")
        require_choice("deformation", self.deformation, METHODS)
        require_range("threshold", self.threshold, 0.0, 1e6)
        if self.threshold_h is not None:
            require_range("threshold_h", self.threshold_h, 0.0, 1e3)
        require_range("omega_gs", self.omega_gs, 0.0, 1.5, lo_open=True)
        require_range("omega_jac", self.omega_jac, 0.0, 1.0, lo_open=True)
        require_range("band", self.band, 1, 8)
        require_range("tol", self.tol, 1e-14, 1e-1, lo_open=False)
        require_range("tol_load", self.tol_load, 1e-14, 1e-1)
        require_choice("wedge_order", self.wedge_order, (1, 2))
        if self.h0_factor is not None:
            require_range("h0_factor", self.h0_factor, 0.0, 1.0)


@dataclass
class CycleRecord:
    """What one cycle did: finest-grid residual and load error, per-level residuals."""

    level: int
    cycle: int
    residual: float
    load_error: float
    level_residuals: list[float] = field(default_factory=list)
    Hc: float = math.nan


class MultilevelLineSolver:
    """FAS/FMG solver for one :class:`LineProblem`.

    Attributes
    ----------
    problem : LineProblem
    options : LineSolverOptions
    levels : list of LineLevel, coarsest first
    cycle : "V" or "W"
    residuals : list of float -- relative residual of the finest grid after each cycle
    history : list of CycleRecord (every cycle of the FMG, every grid)
    fmg_differences : list of dict -- per FMG level, ``|P_h - I P_2h|`` and ``Hc`` change
    actions : list of str -- robustness measures taken
    work_units : float -- relaxations counted in finest-grid sweeps
    """

    def __init__(self, problem: LineProblem, options: LineSolverOptions | None = None, **kw: Any) -> None:
        if options is None:
            options = LineSolverOptions(**kw)
        elif kw:
            options = LineSolverOptions(**{**asdict(options), **kw})
        options.validate(problem.M)
        self.problem = problem
        self.options = options
        self.cycle = options.cycle
        par = problem.rheology()
        n_f = options.points
        self.levels = [
            LineLevel(
                (n_f - 1) // 2 ** (options.levels - 1 - k) + 1, problem.xmin, problem.xmax, par,
                problem.lam, problem.elastic, options.deformation, options.wedge_order,
                options.mlmi_order, options.mlmi_radius,
            )
            for k in range(options.levels)
        ]
        if options.h0_factor is None:
            c = 0.1 if options.cycle == "V" else 0.05
            if problem.L > 10 or problem.M > 1000:
                c /= 4.0
            options.h0_factor = c
        if options.threshold_h is None:
            options.threshold_h = default_threshold_h(problem)
        self._h0_default = options.h0_factor
        self._stall_from = 0
        self.omega = [options.omega_gs, options.omega_jac]
        self.residuals: list[float] = []
        self.load_errors: list[float] = []
        self.history: list[CycleRecord] = []
        self.fmg_differences: list[dict[str, float]] = []
        self.actions: list[str] = []
        self.work_units = 0.0
        self.newton_iterations = 0
        self._level_res: list[float] = []

    # -- helpers --------------------------------------------------------------------------
    def _wu(self, lv: LineLevel) -> float:
        return (lv.n - 1) / (self.levels[-1].n - 1)

    def relative_residual(self, lv: LineLevel, st: State | None = None) -> float:
        st = lv.state() if st is None else st
        denom = st.scale / max(lv.n - 2, 1)
        return lv.residual_norm(st) / denom if denom > 0 else math.inf

    def load_error(self, lv: LineLevel) -> float:
        """Relative load error ``h sum P / (pi/2) - 1`` (finest grid, g = pi/2)."""
        return lv.load() / (0.5 * math.pi) - 1.0

    def central_film(self, lv: LineLevel, st: State | None = None) -> float:
        st = lv.state() if st is None else st
        return float(np.interp(0.0, lv.X, st.H))

    # -- relaxation and cycles -------------------------------------------------------------
    def _relax(self, k: int, sweeps: int, coarse_h0: bool) -> None:
        lv = self.levels[k]
        o = self.options
        for _ in range(sweeps):
            lv.relax(o.threshold, self.omega[0], self.omega[1], o.band, threshold_h=o.threshold_h)
            self.work_units += self._wu(lv)
            if coarse_h0:
                lv.H0 += o.h0_factor * (lv.load() - lv.g)

    def _coarse_solve(self, k: int) -> None:
        lv = self.levels[k]
        saved = (lv.P.copy(), lv.H0)
        try:
            its = newton_solve(lv)
        except NewtonFailure as exc:
            lv.P, lv.H0 = saved
            self.actions.append(f"coarse Newton failed ({exc}); relaxed instead")
            for _ in range(20):
                self._relax(k, 1, True)
            return
        lv.P = np.maximum(lv.P, 0.0)
        self.newton_iterations += its
        self.work_units += its * self._wu(lv)

    def _cycle(self, k: int, top: int) -> None:
        """One FAS cycle with level ``k`` as the current fine grid (``top`` = FMG level)."""
        if k == 0:
            self._coarse_solve(0)
            return
        o = self.options
        lv, cv = self.levels[k], self.levels[k - 1]
        self._relax(k, o.nu1, k != top)
        st = lv.state()
        self._level_res.append(self.relative_residual(lv, st))
        # FAS restriction
        cv.P = inject(lv.P)
        cv.H0 = lv.H0
        # Brandt & Cryer: a coarse point is free only if its fine neighbourhood is free
        # (positive pressure, not frozen); the others keep their value, so the coarse grid
        # never moves the free (cavitation) boundary -- relaxation does
        free = (lv.P > 0.0) & ~lv.frozen
        cfree = free[::2].copy()
        cfree[1:] &= free[1::2]
        cfree[:-1] &= free[1::2]
        cv.frozen = ~cfree
        cv.frozen[0] = cv.frozen[-1] = False
        P_start, H0_start = cv.P.copy(), cv.H0
        cv.f = np.zeros(cv.n)
        cst = cv.state()
        rc = full_weighting(projected(st.r, lv.P))
        # f_H = L_H(I P_h) + R r_h, with L = f - r on the coarse grid at f = 0
        cv.f = -cst.r + rc
        cv.f[0] = cv.f[-1] = 0.0
        cv.g = cv.load() + (lv.g - lv.load())
        for _ in range(1 if self.cycle == "V" or k == 1 else 2):
            self._cycle(k - 1, top)
        corr = interpolate_linear(np.where(cv.frozen, 0.0, cv.P - P_start))
        # no correction in the cavitated zone: the free boundary moves by relaxation only
        # (Brandt & Cryer); a coarse correction there fights the fine-grid complementarity
        corr[lv.P <= 0.0] = 0.0
        if self.options.correction_mask is not None:
            # where Poiseuille flow dominates (eps/h^2 huge: inlet and outlet) the line
            # relaxation solves the local problem exactly; a coarse correction there only
            # disturbs the free boundary
            xi = st.eps / lv.h**2
            corr[xi > self.options.correction_mask] = 0.0
        lv.P = np.maximum(lv.P + corr, 0.0)
        lv.P[0] = lv.P[-1] = 0.0
        lv.H0 += cv.H0 - H0_start
        self._relax(k, o.nu2, k != top)

    # -- FMG ------------------------------------------------------------------------------
    def _initial_guess(self, lv: LineLevel) -> None:
        """Hertzian pressure and the H0 that gives the Moes-fit central film."""
        pb = self.problem
        Hc_fit = moes_line_central(pb.M, pb.L) * math.pi / (8.0 * pb.M)
        # Hertzian shape; rigid surfaces: the same shape over the width 2 sqrt(2 Hc)
        a = 1.0 if pb.elastic else min(1.0, 2.0 * math.sqrt(2.0 * Hc_fit))
        lv.P = np.where(np.abs(lv.X) < a, np.sqrt(np.clip(1.0 - (lv.X / a) ** 2, 0.0, None)) / a, 0.0)
        lv.P[0] = lv.P[-1] = 0.0
        W = lv.deform(lv.P)
        lv.H0 = Hc_fit + float(np.interp(0.0, lv.X, W)) / math.pi
        lv.f = np.zeros(lv.n)
        lv.g = 0.5 * math.pi

    def _start_level(self) -> int:
        """FMG start grid: the coarsest grid unless the load is high, where a coarse grid
        cannot hold a positive film (MODEL.md 5 "Numerical facts")."""
        o = self.options
        if o.fmg_start_points is not None:
            want = o.fmg_start_points
        else:
            want = coarse_points(self.problem.M)
        for k, lv in enumerate(self.levels):
            if lv.n >= want:
                return k
        return len(self.levels) - 1

    def _film_ok(self, lv: LineLevel) -> bool:
        st = lv.state()
        zone = lv.P > 0
        return bool(np.all(np.isfinite(st.H))) and self.central_film(lv, st) > 0 and \
            (not zone.any() or float(st.H[zone].min()) > 0)

    def _start(self, k0: int) -> int:
        """Solve the FMG start grid by Newton; refine the start grid while the discrete film
        is not positive (too coarse for this load). Returns the start level."""
        top = len(self.levels) - 1
        k = k0
        while True:
            lv = self.levels[k]
            self._initial_guess(lv)
            last = k == top or self.levels[k + 1].n > MAX_START_POINTS
            try:
                its = newton_solve(lv, max_iter=120)
            except NewtonFailure as exc:
                if not last:
                    self.actions.append(f"FMG start on {lv.n} points: Newton failed ({exc}); "
                                        f"start moved to {self.levels[k + 1].n} points")
                    k += 1
                    continue
                self.actions.append(f"FMG start on {lv.n} points: Newton failed ({exc}); continuation in M")
                its = self._continuation(lv)
            lv.P = np.maximum(lv.P, 0.0)
            self.newton_iterations += its
            self.work_units += its * self._wu(lv)
            if self._film_ok(lv) or last:
                break
            self.actions.append(f"the {lv.n}-point grid gives a non-positive film at M = "
                                f"{self.problem.M:.4g}: FMG start moved to {self.levels[k + 1].n} points")
            k += 1
        if not self._film_ok(lv):
            capped = k < top and self.levels[k + 1].n > MAX_START_POINTS
            hint = (f"the dense Newton start is limited to {MAX_START_POINTS} points, so more points do "
                    f"not help: this (M, L) is beyond the line solver's range (use the Moes fit)"
                    if capped else "more points (--points), or lower M")
            raise ConvergenceError(
                f"line solver: the discrete film is not positive on the {lv.n}-point start grid "
                f"(M = {self.problem.M:.4g}, L = {self.problem.L:.4g} needs finer grids)",
                self._report(False, math.nan), hint)
        if k > 0:
            self.actions.append(f"FMG started on the {lv.n}-point grid (cycles still coarsen to {self.levels[0].n})")
        return k

    def _continuation(self, lv: LineLevel) -> int:
        import dataclasses

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
                total += newton_solve(lv, max_iter=200)
            except NewtonFailure as exc:
                lv.par, lv.lam = pb.rheology(), pb.lam
                raise ConvergenceError(
                    f"line solver: the first coarse solution failed even with continuation "
                    f"(M = {M:.4g}, L = {L:.4g}: {exc})", None, HINT) from None
        lv.par, lv.lam = pb.rheology(), pb.lam
        return total

    # -- driver ---------------------------------------------------------------------------
    def solve(self, callback: Callable[[dict[str, Any]], None] | None = None,
              residuals: list[float] | None = None) -> LineSolution:
        """Run FMG then extra finest-grid cycles until converged; return a LineSolution.

        ``callback(info)`` is called after every cycle with a dict (level, points, cycle,
        residual, load_error, Hc_venner, work_units); ``residuals``, if a list, receives the
        finest-grid residual history (as in pyamg's ``MultilevelSolver.solve``).
        """
        from .solution import LineSolution

        with np.errstate(all="ignore"):
            sol = self._solve(callback, LineSolution)
        if residuals is not None:
            residuals.extend(self.residuals)
        return sol

    def _solve(self, callback: Callable | None, LineSolution: type) -> LineSolution:
        t0 = time.perf_counter()
        o = self.options
        k0 = self._start(self._start_level())
        top = len(self.levels) - 1
        Hc_prev = self.central_film(self.levels[k0])
        for k in range(k0 + 1, top + 1):
            lv, cv = self.levels[k], self.levels[k - 1]
            lv.P = np.maximum(interpolate_cubic(cv.P), 0.0)
            lv.P[0] = lv.P[-1] = 0.0
            # carry the central film, not H0, to the finer grid: the two grids' deformations
            # differ by their discretisation error, which is comparable to H at high load
            lv.H0 = cv.H0
            lv.f = np.zeros(lv.n)
            lv.g = 0.5 * math.pi
            if self.options.fmg_match_film:
                lv.H0 += self.central_film(cv) - self.central_film(lv)
            for c in range(o.cycles):
                self._run_cycle(k, c, callback)
            Hc = self.central_film(lv)
            diff = float(np.max(np.abs(inject(lv.P) - cv.P)))
            self.fmg_differences.append({"points": lv.n, "max_dP": diff, "dHc": Hc - Hc_prev, "Hc": Hc})
            Hc_prev = Hc
        if top == k0 and top > 0:
            self._run_cycle(top, 0, callback)
        # converge on the finest grid
        fin = self.levels[top]
        converged = self._is_converged(fin)
        extra = 0
        try:
            while not converged and extra < o.max_cycles:
                self._run_cycle(top, o.cycles + extra, callback)
                extra += 1
                converged = self._is_converged(fin)
                self._check_stall(extra)
        except ConvergenceError:
            # stall or divergence: on grids small enough, finish with a dense Newton solve
            if fin.n > MAX_START_POINTS or not self._finest_newton(fin, callback):
                raise
            converged = True
        wall = time.perf_counter() - t0
        report = self._report(converged, wall)
        if not converged and o.raise_on_failure:
            raise ConvergenceError(
                f"line solver did not converge in {o.max_cycles} extra cycles: residual "
                f"{self.residuals[-1]:.3g} (tol {o.tol:.3g}), load error {self.load_errors[-1]:.3g} "
                f"(tol {o.tol_load:.3g})", report, HINT)
        return LineSolution.from_solver(self, report)

    def _finest_newton(self, fin: LineLevel, callback: Callable | None) -> bool:
        """Last resort when the cycles stall on a grid small enough for a dense solve: Newton
        on the finest grid from the multigrid iterate (the full-system path of MODEL.md 5)."""
        saved = (fin.P.copy(), fin.H0)
        fin.frozen[:] = False
        try:
            its = newton_solve(fin, max_iter=60)
        except NewtonFailure as exc:
            fin.P, fin.H0 = saved
            self.actions.append(f"finest-grid Newton after the multigrid stall failed: {exc}")
            return False
        fin.P = np.maximum(fin.P, 0.0)
        self.newton_iterations += its
        self.work_units += its  # one finest-grid Newton step counted as one work unit (dense!)
        st = fin.state()
        res = self.relative_residual(fin, st)
        le = fin.load() / fin.g - 1.0
        self.residuals.append(res)
        self.load_errors.append(le)
        self.history.append(CycleRecord(len(self.levels) - 1, -1, res, le, [], self.central_film(fin, st)))
        self.actions.append(f"multigrid stalled: finished by {its} dense Newton iterations on the "
                            f"{fin.n}-point grid")
        if callback is not None:
            callback({"level": len(self.levels) - 1, "points": fin.n, "cycle": -1, "residual": res,
                      "load_error": le, "Hc_venner": self.central_film(fin, st),
                      "work_units": self.work_units})
        return self._is_converged(fin)

    def _is_converged(self, lv: LineLevel) -> bool:
        o = self.options
        if not self.residuals:
            return False
        return self.residuals[-1] < o.tol and abs(self.load_errors[-1]) < o.tol_load

    def _run_cycle(self, k: int, c: int, callback: Callable | None) -> None:
        lv = self.levels[k]
        saved = [(v.P.copy(), v.H0) for v in self.levels[: k + 1]]
        prev = self.history[-1] if self.history and self.history[-1].level == k else None
        recent = [h.residual for h in self.history[-4:] if h.level == k]
        before = min(recent) if recent else math.inf
        le_before = abs(prev.load_error) if prev else 0.05
        for _attempt in range(7):
            self._level_res = []
            try:
                self._cycle(k, k) if k > 0 else self._coarse_solve(0)
                st = lv.state()
                res = self.relative_residual(lv, st)
                le = lv.load() / lv.g - 1.0
                ok = (np.all(np.isfinite(lv.P)) and np.isfinite(lv.H0) and np.isfinite(res)
                      and np.all(np.isfinite(st.H)) and self.central_film(lv, st) > 0.0)
                # the load error guards against the trivial all-cavitated state (P = 0
                # everywhere has a zero complementarity residual)
                good = ok and abs(le) < max(0.1, 3.0 * le_before) and (
                    res < self.options.tol or (res < 20.0 * before and res < 0.5))
            except (np.linalg.LinAlgError, FloatingPointError, ValueError) as exc:
                res, good = math.inf, False
                self.actions.append(f"cycle {c} on {lv.n} points failed: {exc}")
            if good:
                # recover the under-relaxation gradually after a rejected cycle
                o = self.options
                self.omega = [min(o.omega_gs, 1.25 * self.omega[0]), min(o.omega_jac, 1.25 * self.omega[1])]
                o.h0_factor = min(self._h0_default, 1.25 * o.h0_factor)
                break
            for v, (P, H0) in zip(self.levels, saved, strict=False):
                v.P, v.H0 = P.copy(), H0
            self.omega = [0.5 * w for w in self.omega]
            self.options.h0_factor *= 0.5
            self.actions.append(
                f"cycle {c} on {lv.n} points rejected (residual {res:.3g}, before {before:.3g}): "
                f"repeated with omega_gs = {self.omega[0]:.3g}, omega_jac = {self.omega[1]:.3g}, "
                f"h0_factor = {self.options.h0_factor:.3g}")
        else:
            raise ConvergenceError(
                f"line solver diverged on the {lv.n}-point grid (residual {res:.3g}) even with "
                f"under-relaxation reduced 128-fold", self._report(False, math.nan), HINT)
        le = lv.load() / lv.g - 1.0
        Hc = self.central_film(lv, st)
        rec = CycleRecord(k, c, res, le, list(self._level_res), Hc)
        self.history.append(rec)
        if k == len(self.levels) - 1:
            self.residuals.append(res)
            self.load_errors.append(le)
        if callback is not None:
            callback({"level": k, "points": lv.n, "cycle": c, "residual": res, "load_error": le,
                      "Hc_venner": Hc, "work_units": self.work_units})

    def _check_stall(self, extra: int) -> None:
        r = self.residuals[self._stall_from:]
        if len(r) >= 8 and r[-1] > 0.9 * r[-8] and r[-1] > self.options.tol:
            if self.cycle == "V":
                # W cycles visit the coarse grids more often and cure most V-cycle stalls
                self.cycle = "W"
                self._stall_from = len(self.residuals)
                self.actions.append(f"V cycles stalled at residual {r[-1]:.3g}: switched to W cycles")
                return
            if self.options.threshold_h < 1.0:
                # more Jacobi-distributive points on the fine grids (discrete.py, threshold_h)
                self.options.threshold_h = 1.0
                self.omega = [self.options.omega_gs, self.options.omega_jac]
                self._stall_from = len(self.residuals)
                self.actions.append(f"W cycles stalled at residual {r[-1]:.3g}: switch threshold "
                                    f"raised to eps/h^2 < 1/h on fine grids")
                return
            le = self.load_errors[-1]
            raise ConvergenceError(
                f"line solver stalled: the residual fell only from {r[-8]:.3g} to {r[-1]:.3g} over "
                f"7 cycles (load error {le:.3g})", self._report(False, math.nan), HINT)

    def _report(self, converged: bool, wall: float) -> ConvergenceReport:
        o = self.options
        msg = "converged" if converged else "not converged"
        per_level = [rec.level_residuals for rec in self.history]
        width = max((len(v) for v in per_level), default=0)
        lvl = np.full((len(per_level), max(width, 1)), np.nan)
        for i, v in enumerate(per_level):
            lvl[i, : len(v)] = v
        return ConvergenceReport(
            converged=converged, message=msg, iterations=len(self.residuals),
            residual_history=np.asarray(self.residuals), load_error_history=np.asarray(self.load_errors),
            tolerances={"residual": o.tol, "load": o.tol_load}, work_units=self.work_units, wall_s=wall,
            extra={
                "cycle_level": np.array([rec.level for rec in self.history]),
                "cycle_points": np.array([self.levels[rec.level].n for rec in self.history]),
                "cycle_residual": np.array([rec.residual for rec in self.history]),
                "cycle_load_error": np.array([rec.load_error for rec in self.history]),
                "cycle_Hc_venner": np.array([rec.Hc for rec in self.history]),
                "level_residuals": lvl,
                "fmg_points": np.array([d["points"] for d in self.fmg_differences]),
                "fmg_max_dP": np.array([d["max_dP"] for d in self.fmg_differences]),
                "fmg_dHc_venner": np.array([d["dHc"] for d in self.fmg_differences]),
                "actions": list(self.actions),
            },
        )


def solve_line(
    M: float | None = None, L: float | None = None, *, scene: Any = None,
    viscosity: str = "roelands", density: str = "dowson-higginson",
    alpha: float | None = None, eta0: float | None = None, p0: float | None = None,
    xmin: float | None = None, xmax: float = 1.5, elastic: bool = True,
    callback: Callable[[dict[str, Any]], None] | None = None, **options: Any,
) -> LineSolution:
    """Solve the steady isothermal EHL line contact (MODEL.md 5).

    Give either Moes ``M, L`` (oil data ``alpha``, ``eta0``, ``p0`` default to
    ``MOES_ONLY_DEFAULTS``) or a line-contact ``scene``. Numerical ``options`` are those of
    :class:`LineSolverOptions` (points, levels, cycle, deformation, tol, ...).

    Returns a :class:`~ehl_multigrid.line.solution.LineSolution`; ``.to_result()`` gives the
    core :class:`~ehl_multigrid.results.Result` (kind ``"ehl_line"``).

    Examples
    --------
    >>> sol = solve_line(20, 10, points=257)              # doctest: +SKIP
    >>> round(sol.Hc, 2), sol.converged                   # doctest: +SKIP
    """
    if scene is not None:
        if M is not None or L is not None:
            raise InputError("give either a scene or M and L, not both")
        pb = LineProblem.from_scene(scene, viscosity=viscosity, density=density, xmin=xmin,
                                    xmax=xmax, elastic=elastic)
    else:
        if M is None or L is None:
            raise InputError("solve_line needs M and L (Moes groups) or a scene")
        pb = LineProblem.from_moes(M, L, viscosity=viscosity, density=density, alpha=alpha,
                                   eta0=eta0, p0=p0, xmin=xmin, xmax=xmax, elastic=elastic)
    return MultilevelLineSolver(pb, **options).solve(callback=callback)
