"""FAS / FMG multilevel solver for the point-contact EHL problem (MODEL.md 5).

Venner-style: Full Approximation Scheme inside Full Multigrid, zebra line relaxation along X
(Gauss-Seidel where ``eps/hx^2 >= thr``, Jacobi-distributive elsewhere), injection of P and
full weighting of residuals, bilinear coarse-grid corrections, cubic FMG interpolation, the
film constant H00 updated from the (FAS) load error on the coarsest grid. The deformation is
recomputed after every sweep by the selected O(N log N) path.

Robustness: when a cycle increases the residual, produces NaN or a negative central film, the
solver restores the best state seen and halves the under-relaxation and H00 step, switches V to
W cycles and, on the coarse start, refines the coarsest grid; every action is recorded in
``report.extra['actions']``.
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, field, replace

import numba
import numpy as np

from ..model.convergence import ConvergenceReport
from ..model.errors import ConvergenceError, InputError, require_range
from ..model.fits import nijenbanning_central
from . import numerics as nm
from .deformation import cell_kernel, make_deformation, set_fft_workers
from .problem import PointProblem, coarse_intervals, domain_scale, min_points, resolve_domain

#: grids with fewer points than this run single-threaded (see FASSolver._threads_for)
SERIAL_BELOW = 129 * 129


@dataclass
class SolverOptions:
    """Options of :func:`solve_fas` (defaults after MODEL.md 5 "numerical facts").

    points : finest-grid points per axis (2^k n0 + 1)
    levels : number of levels (None: coarsest grid ``n_coarse`` intervals)
    n_coarse : intervals of the coarsest grid along X (None: :func:`problem.coarse_intervals`)
    xmin, xmax, ymax : domain in units of a (None: :func:`problem.default_domain`, which is
        [-4.5, 1.5] x [-3, 3] b/a except at low M)
    y_ratio : (points along Y - 1)/(points - 1), a power of 2 (None: the one that makes the
        mesh closest to square, so elliptic contacts keep hy ~ hx; 1 for circular contacts)
    half : solve Y >= 0 only (symmetric contact)
    cycle : V or W; nu1, nu2 pre/post sweeps; cycles : cycles per FMG level
    max_cycles : extra finest-level cycles allowed to reach the tolerances
    deformation : fft | mlmi | direct
    thr : eps/hx^2 switch GS/Jacobi-distributive (None: :func:`default_threshold`); w_gs, w_jd : under-relaxation
    c_h00 : H00 step per unit load error (None: 0.1 V / 0.05 W, /4 when L > 10 or M > 1000;
        at least ``H_fit/(10 load)`` where the film is thick (:func:`problem.domain_scale` > 1),
        from the rigid sensitivity ``d load/d H00 ~ -2 load/H``)
    coarse_sweeps : sweeps on the coarsest grid per visit
    tol : relative residual tolerance ``||r||_2/||d(rho H)/dX||_2``; tol_load : relative load error
    order : wedge discretisation order (1 or 2)
    threads : numba threads and FFT workers (None: all)
    raise_on_failure : raise ConvergenceError instead of returning converged=False
    """

    points: int = 129
    levels: int | None = None
    n_coarse: int | None = None
    xmin: float | None = None
    xmax: float | None = None
    ymax: float | None = None
    y_ratio: float | None = None
    half: bool = False
    cycle: str = "W"
    nu1: int = 2
    nu2: int = 1
    cycles: int = 2
    max_cycles: int = 30
    deformation: str = "fft"
    thr: float | None = None
    w_gs: float = 0.6
    w_jd: float = 0.3
    c_h00: float | None = None
    coarse_sweeps: int = 10
    tol: float = 1e-4
    tol_load: float = 1e-5
    order: int = 2
    threads: int | None = None
    elastic: bool = True  # False: rigid surfaces (deformation off, for the rigid limit)
    adapt: bool = True  # False: fixed settings like the classic code (for comparison only)
    raise_on_failure: bool = False
    verbose: bool = False

    def validate(self) -> None:
        require_range("points", self.points, 9, 8193)
        if self.cycle not in ("V", "W"):
            raise InputError(f"cycle = {self.cycle!r} is not one of ['V', 'W']")
        if self.deformation not in ("fft", "mlmi", "direct"):
            raise InputError(f"deformation = {self.deformation!r} is not one of ['mlmi', 'fft', 'direct']")
        if self.xmin is not None:
            require_range("xmin", self.xmin, -2000.0, -1.05, "-")
        if self.xmax is not None:
            require_range("xmax", self.xmax, 1.05, 2000.0, "-")
        if self.ymax is not None:
            require_range("ymax", self.ymax, 0.5, 2000.0, "-")
        if self.y_ratio is not None:
            require_range("y_ratio", self.y_ratio, 0.125, 8.0, "-")
            if abs(math.log2(self.y_ratio) - round(math.log2(self.y_ratio))) > 1e-12:
                raise InputError(f"y_ratio = {self.y_ratio:g} must be a power of 2 in [1/8, 8]")
        require_range("cycles", self.cycles, 1, 50)
        require_range("max_cycles", self.max_cycles, 0, 1000)
        require_range("tol", self.tol, 1e-14, 1.0, "-", lo_open=True)
        require_range("tol_load", self.tol_load, 1e-14, 1.0, "-", lo_open=True)
        require_range("order", self.order, 1, 2)
        if self.levels is not None:
            require_range("levels", self.levels, 1, 12)


@dataclass
class Level:
    nx: int
    ny: int
    hx: float
    hy: float
    X: np.ndarray
    Y: np.ndarray
    defo: object
    Kc: np.ndarray
    P: np.ndarray = None
    H: np.ndarray = None
    W: np.ndarray = None
    rho: np.ndarray = None
    eps: np.ndarray = None
    f: np.ndarray = None
    D: np.ndarray = None
    r: np.ndarray = None
    g: float = 0.0

    @property
    def npts(self) -> int:
        return self.nx * self.ny


@dataclass
class FASOutput:
    """Solution and diagnostics of :func:`solve_fas`."""

    problem: PointProblem
    options: SolverOptions
    X: np.ndarray
    Y: np.ndarray
    P: np.ndarray  # [j, i]
    H: np.ndarray
    H00: float
    report: ConvergenceReport
    levels: int
    half: bool
    cycle_Hc: list = field(default_factory=list)
    fmg_Hc: list = field(default_factory=list)


def default_threshold(visc: int, alpha_bar: float, elastic: bool = True) -> float:
    """GS/Jacobi-distributive switch ``eps/hx^2`` (see FASSolver): 1 by default, 10 for strong
    pressure spikes (Barus alpha_bar >= 8, Roelands >= 20), 40 for Roelands alpha_bar >= 30."""
    if not elastic:
        return 1.0
    if visc == 1:
        return 10.0 if alpha_bar >= 8.0 else 1.0
    return 40.0 if alpha_bar >= 30.0 else (10.0 if alpha_bar >= 20.0 else 1.0)


def y_ratio(length_x: float, length_y: float, coarse_x: int) -> float:
    """Power of 2 closest (in log) to ``length_y/length_x``, in [1/8, 8], leaving at least 4
    intervals along Y on the coarsest grid (``coarse_x`` intervals along X)."""
    r = 2.0 ** round(math.log2(length_y / length_x))
    r = min(max(r, 0.125, 4.0 / coarse_x), 8.0)
    return 2.0 ** math.ceil(math.log2(r) - 1e-12)


def load_integral(P: np.ndarray, hx: float, hy: float, half: bool) -> float:
    """``∫∫ P dX dY`` (trapezoid; P = 0 on the boundary); half domains count row 0 once."""
    if half:
        return hx * hy * (P[0].sum() + 2.0 * P[1:].sum())
    return hx * hy * P.sum()


class FASSolver:
    """One FAS/FMG solve; see :func:`solve_fas`."""

    def __init__(self, problem: PointProblem, opt: SolverOptions) -> None:
        opt.validate()
        self.pb = problem
        xmin, xmax, ymax = resolve_domain(problem, opt.xmin, opt.xmax, opt.ymax)
        opt = replace(opt, xmin=xmin, xmax=xmax, ymax=ymax)
        self.opt = opt
        self.nthreads = numba.config.NUMBA_NUM_THREADS
        if opt.threads is not None:
            self.nthreads = max(1, min(int(opt.threads), numba.config.NUMBA_NUM_THREADS))
        numba.set_num_threads(self.nthreads)
        self._cur_threads = self.nthreads
        set_fft_workers(self.nthreads)
        self.visc = 0 if problem.viscosity == "roelands" else 1
        self.dens = 0 if problem.density == "dowson-higginson" else 1
        self.lnr = problem.ln_eta_ratio
        self.z = problem.roelands_z
        self.pmax = problem.pmax
        self.abar = problem.alpha_bar
        self.lam = problem.lam
        self.cd = problem.cd if opt.elastic else 0.0
        self.theta = problem.theta
        self.boa = problem.b_over_a
        self.g_target = problem.load
        self.w_gs = opt.w_gs
        self.w_jd = opt.w_jd
        self.cycle = opt.cycle
        if opt.c_h00 is None:
            c = 0.1 if opt.cycle == "V" else 0.05
            if problem.L > 10 or problem.M > 1000:
                c *= 0.25
            if domain_scale(problem) > 1.0:  # thick film: the rigid sensitivity sets the gain
                H_fit = nijenbanning_central(problem.M, problem.L, problem.theta) / problem.moes_factor
                c = max(c, 0.1 * H_fit / problem.load)
            self.c_h = c
        else:
            self.c_h = opt.c_h00
        self.gain = self.c_h
        self._last_err = None
        self._n_soft = 0
        # measured: strong spikes need more Gauss-Seidel lines. Barus (alpha_bar >= 8): thr 10
        # converges (20, 10) at 513^2 in 9 W cycles where thr 1 diverges; at low alpha_bar
        # thr 1 is better (Barus (50, 2.5) at 129^2: thr 1 converges, thr 10 stalls). Roelands
        # converges equally well with 1 and 10 at (20, 10) (alpha_bar 10); from alpha_bar 20 on
        # thr 10 and from 30 on thr 40: (200, 20) (alpha_bar 43) converges at 257^2 with 10
        # (thr 1 does not) and at 513^2 only with 40; (100, 20) (34) at 257^2 only with 40
        self.thr = opt.thr if opt.thr is not None else default_threshold(self.visc, problem.alpha_bar, opt.elastic)
        self.actions: list[str] = []
        self.work = 0.0
        self.res_hist: list[float] = []
        self.load_hist: list[float] = []
        self.cyc_Hc: list[float] = []
        self.fmg_Hc: list[float] = []
        self._build_levels()

    # -- grids -------------------------------------------------------------------------------
    def _build_levels(self) -> None:
        opt = self.opt
        n = int(opt.points)
        nc = opt.n_coarse
        if nc is None:
            nc = coarse_intervals(self.pb.M, opt.xmax - opt.xmin, n, domain_scale(self.pb))
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
        ymax = float(opt.ymax)
        self.ymax = ymax
        ratio = opt.y_ratio
        if ratio is None:
            ratio = y_ratio(opt.xmax - opt.xmin, 2.0 * ymax, (n - 1) // 2 ** (nlev - 1))
        self.y_ratio = ratio
        self.levels: list[Level] = []
        for k in range(nlev):
            nk = (n - 1) // 2 ** (nlev - 1 - k) + 1
            nyf = int(round((nk - 1) * ratio)) + 1  # full-domain points along Y
            hx = (opt.xmax - opt.xmin) / (nk - 1)
            hy = 2.0 * ymax / (nyf - 1)
            X = opt.xmin + hx * np.arange(nk)
            if opt.half:
                nyk = (nyf - 1) // 2 + 1
                Y = hy * np.arange(nyk)
            else:
                nyk = nyf
                Y = -ymax + hy * np.arange(nyf)
            defo = make_deformation(opt.deformation, nk, nyk, hx, hy, opt.half)
            K = cell_kernel(6, 2, hx, hy)
            lev = Level(nk, nyk, hx, hy, X, Y, defo, np.ascontiguousarray(self.cd * K))
            shape = (nyk, nk)
            lev.P = np.zeros(shape)
            lev.H = np.zeros(shape)
            lev.W = np.zeros(shape)
            lev.rho = np.ones(shape)
            lev.eps = np.zeros(shape)
            lev.f = np.zeros(shape)
            lev.D = np.zeros(shape)
            lev.r = np.zeros(shape)
            lev.g = self.g_target
            self.levels.append(lev)
        self.nfine = self.levels[-1].npts

    # -- pieces ------------------------------------------------------------------------------
    def _threads_for(self, lev: Level) -> None:
        """Coarse grids run on one thread: their kernels are too small to pay for a
        thread barrier, which on a busy machine can cost a scheduler time slice each."""
        want = 1 if lev.npts < SERIAL_BELOW else self.nthreads
        if want != self._cur_threads:
            numba.set_num_threads(want)
            self._cur_threads = want

    def update_film(self, lev: Level) -> None:
        self._threads_for(lev)
        lev.W = lev.defo(lev.P) if self.cd != 0.0 else np.zeros_like(lev.P)
        nm.film(lev.W, lev.X, lev.Y, self.H00, self.theta, self.cd, lev.H)
        nm.fluid_properties(lev.P, lev.H, self.visc, self.dens, self.lnr, self.z, self.pmax,
                            self.pb.p_r, self.abar, self.lam, lev.rho, lev.eps)

    def relax(self, lev: Level) -> None:
        self._threads_for(lev)
        nm.relax_sweep(lev.P, lev.H, lev.rho, lev.eps, lev.f, lev.D, lev.Kc, lev.hx, lev.hy,
                       self.opt.half, self.thr, self.w_gs, self.w_jd, self.opt.order)
        self.work += lev.npts / self.nfine
        self.update_film(lev)

    def load(self, lev: Level) -> float:
        return load_integral(lev.P, lev.hx, lev.hy, self.opt.half)

    def residual(self, lev: Level) -> np.ndarray:
        self._threads_for(lev)
        nm.residual(lev.P, lev.H, lev.rho, lev.eps, lev.f, lev.hx, lev.hy, self.opt.half,
                    self.opt.order, lev.r)
        return lev.r

    def rel_residual(self, lev: Level) -> float:
        """RMS of the diagonally scaled residual (a pressure change, units of pmax) over the
        interior, relative to max P: see :func:`numerics.scaled_residual`."""
        r = self.residual(lev)
        sr = np.empty_like(r)
        nm.scaled_residual(r, lev.H, lev.rho, lev.eps, float(lev.Kc[0, 0]), lev.hx, lev.hy,
                           self.opt.half, sr)
        ny, nx = r.shape
        j0 = 0 if self.opt.half else 1
        inner = sr[j0:ny - 1, 1:nx - 1]
        rms = math.sqrt(float(np.mean(inner * inner)))
        return rms / max(float(lev.P.max()), 1e-300)

    def coarse_solve(self, lev: Level, sweeps: int) -> None:
        """Relax on the coarsest grid, moving H00 against the (FAS) load error after each
        sweep. The gain halves when the error changes sign (overshoot) and recovers slowly
        (x1.25, up to ``c_h``) while it keeps its sign and falls slowly."""
        for _ in range(sweeps):
            self.relax(lev)
            err = lev.g - self.load(lev)
            last = self._last_err
            if last is not None and err * last < 0.0:
                self.gain = max(self.gain * 0.5, self.c_h / 256.0)
            elif last is not None and abs(err) > 0.5 * abs(last):
                self.gain = min(self.gain * 1.25, self.c_h)
            self._last_err = err
            step = self.gain * err
            self.H00 -= max(-self.h00_step_max, min(self.h00_step_max, step))
            nm.film(lev.W, lev.X, lev.Y, self.H00, self.theta, self.cd, lev.H)
            nm.fluid_properties(lev.P, lev.H, self.visc, self.dens, self.lnr, self.z, self.pmax,
                                self.pb.p_r, self.abar, self.lam, lev.rho, lev.eps)

    def fas_cycle(self, k: int) -> None:
        lev = self.levels[k]
        if k == 0:
            self.coarse_solve(lev, self.opt.coarse_sweeps)
            return
        for _ in range(self.opt.nu1):
            self.relax(lev)
        r = self.residual(lev)
        c = self.levels[k - 1]
        c.P = np.ascontiguousarray(lev.P[::2, ::2])
        P0 = c.P.copy()
        self.update_film(c)
        Lc = np.empty_like(c.P)
        nm.operator(c.P, c.H, c.rho, c.eps, c.hx, c.hy, self.opt.half, self.opt.order, Lc)
        Rr = np.empty_like(c.P)
        nm.restrict_full_weighting(r, self.opt.half, Rr)
        c.f = Lc + Rr
        c.g = self.load(c) + (lev.g - self.load(lev))
        ncalls = 1 if (self.cycle == "V" or k == 1) else 2
        for _ in range(ncalls):
            self.fas_cycle(k - 1)
        nm.add_bilinear(lev.P, c.P - P0, True)
        self.update_film(lev)
        for _ in range(self.opt.nu2):
            self.relax(lev)

    # -- observables -------------------------------------------------------------------------
    def central_film(self, lev: Level) -> float:
        i = int(np.argmin(np.abs(lev.X)))
        j = 0 if self.opt.half else (lev.ny - 1) // 2
        return float(lev.H[j, i])

    def _state(self) -> tuple:
        lev = self.levels[-1]
        return (lev.P.copy(), self.H00)

    def _restore(self, st: tuple, k: int) -> None:
        lev = self.levels[k]
        lev.P = st[0].copy()
        self.H00 = st[1]
        self.update_film(lev)

    def _diverged(self, lev: Level) -> bool:
        if not (np.all(np.isfinite(lev.P)) and math.isfinite(self.H00)):
            return True
        return abs(self.load(lev) - self.g_target) > 0.3 * self.g_target

    def _soften(self, why: str) -> None:
        """Adapt after a stall or divergence. Odd calls raise the GS/JD switch x4 (up to 64:
        more Gauss-Seidel lines, which cures the under-resolved Barus spike); even calls halve
        the under-relaxation and the H00 gain and switch V to W cycles."""
        if not self.opt.adapt:
            self.actions.append(f"{why}: adaptation disabled, nothing changed")
            return
        self._n_soft += 1
        if self._n_soft % 2 == 1 and self.thr < 64.0:
            self.thr = min(4.0 * self.thr, 64.0)
            msg = f"{why}: GS/JD switch eps/hx^2 -> {self.thr:.3g}"
        else:
            self.w_gs = max(0.5 * self.w_gs, 0.1)
            self.w_jd = max(0.5 * self.w_jd, 0.05)
            self.c_h = max(0.5 * self.c_h, 1e-3)
            self.gain = min(self.gain, self.c_h)
            msg = f"{why}: w_gs -> {self.w_gs:.3g}, w_jd -> {self.w_jd:.3g}, c_h00 -> {self.c_h:.3g}"
            if self.cycle == "V":
                self.cycle = "W"
                msg += ", V -> W cycles"
        self.actions.append(msg)

    # -- driver ------------------------------------------------------------------------------
    def initial_guess(self) -> None:
        lev = self.levels[0]
        XX = lev.X[None, :]
        YY = lev.Y[:, None] / self.boa
        lev.P = np.ascontiguousarray(np.sqrt(np.clip(1.0 - XX**2 - YY**2, 0.0, None)))
        lev.P[:, 0] = lev.P[:, -1] = 0.0
        lev.P[-1] = 0.0
        if not self.opt.half:
            lev.P[0] = 0.0
        Hc_fit = nijenbanning_central(self.pb.M, self.pb.L, self.theta) / self.pb.moes_factor
        self.H00 = 0.0
        lev.W = lev.defo(lev.P)
        i = int(np.argmin(np.abs(lev.X)))
        j = 0 if self.opt.half else (lev.ny - 1) // 2
        self.H00 = float(Hc_fit - self.cd * lev.W[j, i])
        self.h00_step_max = 0.1 * float(Hc_fit)
        self.update_film(lev)

    def run(self) -> FASOutput:
        t0 = time.perf_counter()
        opt = self.opt
        nlev = len(self.levels)
        self.initial_guess()
        # coarse start: retry softer if it diverges (NaN or negative central film)
        for attempt in range(4):
            st = (self.levels[0].P.copy(), self.H00)
            self.coarse_solve(self.levels[0], 4 * opt.coarse_sweeps)
            lev0 = self.levels[0]
            if np.all(np.isfinite(lev0.P)) and math.isfinite(self.H00) and np.all(np.isfinite(lev0.H)):
                break
            self.levels[0].P, self.H00 = st
            self.update_film(self.levels[0])
            self._soften(f"coarse start diverged (attempt {attempt + 1})")
        self.fmg_Hc.append(self.central_film(self.levels[0]))
        for k in range(1, nlev):
            lev = self.levels[k]
            lev.P = nm.interpolate_cubic(self.levels[k - 1].P, opt.half)
            lev.f = np.zeros_like(lev.P)
            lev.g = self.g_target
            self.update_film(lev)
            for _ in range(opt.cycles):
                st = (lev.P.copy(), self.H00)
                self.fas_cycle(k)
                if self._diverged(lev):
                    self._restore(st, k)
                    self._soften(f"divergence (NaN or load error > 30 %) on FMG level {k}")
            self.fmg_Hc.append(self.central_film(lev))
        fine = self.levels[-1]
        res = self.rel_residual(fine)
        lerr = abs(self.load(fine) - self.g_target) / self.g_target
        self.res_hist.append(res)
        self.load_hist.append(lerr)
        self.cyc_Hc.append(self.central_film(fine))
        best = (res, self._state())
        converged = res < opt.tol and lerr < opt.tol_load
        extra = 0
        stall = 0
        while not converged and extra < opt.max_cycles:
            self.fas_cycle(nlev - 1)
            extra += 1
            ok = not self._diverged(fine)
            res = self.rel_residual(fine) if ok else math.inf
            lerr = abs(self.load(fine) - self.g_target) / self.g_target if ok else math.inf
            if not math.isfinite(res) or res > 3.0 * best[0] or self.central_film(fine) <= 0:
                self._restore(best[1], nlev - 1)
                why = (f"residual {res:.3g} > 3x best {best[0]:.3g}" if res > 3.0 * best[0]
                       else "negative central film")
                self._soften(f"cycle {extra}: {why}")
                res = self.rel_residual(fine)
                lerr = abs(self.load(fine) - self.g_target) / self.g_target
            elif res > 0.95 * self.res_hist[-1] and res > opt.tol:
                stall += 1
                if stall >= 3:
                    self._soften(f"cycle {extra}: residual stalled at {res:.3g}")
                    stall = 0
            else:
                stall = 0
            if res < best[0]:
                best = (res, self._state())
            self.res_hist.append(res)
            self.load_hist.append(lerr)
            self.cyc_Hc.append(self.central_film(fine))
            if opt.verbose:
                print(f"cycle {extra}: res {res:.3e} load {lerr:.3e} Hc {self.cyc_Hc[-1]:.6g}")
            converged = res < opt.tol and lerr < opt.tol_load
        wall = time.perf_counter() - t0
        numba.set_num_threads(self.nthreads)
        finite = bool(np.all(np.isfinite(fine.P)) and np.all(np.isfinite(fine.H)))
        msg = ("converged" if converged else
               f"not converged after {extra} extra cycles: residual {res:.3g} (tol {opt.tol:g}), "
               f"load error {lerr:.3g} (tol {opt.tol_load:g})")
        report = ConvergenceReport(
            converged=bool(converged and finite), message=msg, iterations=len(self.res_hist) - 1 + (nlev - 1) * opt.cycles,
            residual_history=np.array(self.res_hist), load_error_history=np.array(self.load_hist),
            tolerances={"residual": opt.tol, "load": opt.tol_load}, work_units=self.work, wall_s=wall,
            extra={"actions": list(self.actions), "fmg_Hc": np.array(self.fmg_Hc),
                   "cycle_Hc": np.array(self.cyc_Hc), "final_w_gs": self.w_gs, "final_w_jd": self.w_jd,
                   "final_c_h00": self.c_h, "final_cycle": self.cycle,
                   "final_thr": self.thr},
        )
        if not finite:
            raise ConvergenceError("point-contact solve produced NaN/inf", report,
                                   "use W cycles, a finer coarsest grid (--levels fewer), or smaller relaxation")
        if not converged and opt.points < min_points(self.pb.M, self.boa):
            report.message += (f"; at M = {self.pb.M:.4g} a grid of {opt.points} points is too coarse for "
                               f"this solver: use points >= {min_points(self.pb.M, self.boa)}")
        if not converged and lerr > 1e-2:
            report.message += ("; the load cannot be balanced: at low M the inlet of this domain is too "
                               "short (extend xmin/ymax), at high M the grid is too coarse (more points)")
        if not report.converged and opt.raise_on_failure:
            raise ConvergenceError(msg, report, "raise --max-cycles, use W cycles, a longer inlet or fewer levels")
        return FASOutput(self.pb, opt, fine.X, fine.Y, fine.P.copy(), fine.H.copy(), self.H00, report,
                         nlev, opt.half, list(self.cyc_Hc), list(self.fmg_Hc))


def solve_fas(problem: PointProblem, options: SolverOptions | None = None, **kw) -> FASOutput:
    """Solve the point-contact EHL problem with FAS/FMG; keyword arguments override options."""
    opt = SolverOptions(**{**(asdict(options) if options else {}), **kw})
    return FASSolver(problem, opt).run()
