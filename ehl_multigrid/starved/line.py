"""The starved, mass-conserving EHL line contact on the shared multilevel driver.

Equations (Venner's dimensionless line contact, thesis (2.1)-(2.3), Roelands (2.6) and
Dowson-Higginson (2.7)) with Elrod-Adams cavitation: a film content ``theta`` in ``(0, 1]``,
``P (1 - theta) = 0``, ``P >= 0``, in the wedge term ``d(theta rho H)/dX`` (discrete.py). The
inlet node carries the supplied oil layer ``Hoil = hoil R/b^2`` (Venner units; both surfaces
together, at ambient density): ``theta = Hoil/H`` there, so a uniform layer ahead of the
contact fills the gap up to the meniscus, which the solver finds (a layer thicker than the
inlet gap floods the inlet). Behind the contact the film ruptures and the surfaces carry the
outlet flux away: the layer left on the track is ``rho theta H`` at the outlet.

:class:`StarvedLineHierarchy` reuses the flooded line solver's grids, deformation operators,
rheology, transfers, FMG start rules and the driver (:class:`MultilevelSolver`) with:

* relaxation: the collective line relaxation in the universal variable (``P`` where
  pressurised, ``theta`` where cavitated or starved), Jacobi-distributive in the contact as
  in the flooded solver (level.py);
* coarse grids (FAS): ``P`` and ``theta`` injected, coarse points next to a fine point that
  is not pressurised frozen (the free boundaries -- meniscus and rupture -- move by
  fine-grid relaxation only), corrections of ``P`` only;
* coarsest and FMG start grid: dense semismooth Newton in the universal variable
  (newton.py), started from the flooded solution and, when that fails, by continuation in
  ``Hoil``.

``solve_starved_line`` also solves the flooded problem (the core line solver on the same
grid) for ``Hc_flooded``, ``Hm_flooded`` and as the start; it reports the meniscus, the
rupture point, the outlet layer and the mass balance.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..line.problem import LineProblem
from ..line.solution import finish_line_result
from ..line.solver import (
    HINT,
    LINE_POLICY,
    MAX_ACCURACY_POINTS,
    LineHierarchy,
    line_levels,
    line_settings,
    solve_line_problem,
)
from ..model.errors import ConvergenceError, InputError, require_range
from ..model.lubricant import density_ratio_dh
from ..multigrid.accuracy import film_change, film_tol, solve_to_accuracy
from ..multigrid.driver import Measurement, MultilevelSolver
from ..multigrid.options import LineOptions
from ..multigrid.policy import RobustnessPolicy, Settings
from ..multigrid.result import EHLResult
from ..multigrid.transfer import full_weighting, inject, interpolate_cubic, interpolate_linear
from .discrete import face_fluxes
from .level import StarvedLevel
from .newton import StarvedNewtonFailure, newton_solve
from .supply import check_hoil

#: largest grid the dense Newton may finish after a multigrid stall
MAX_DENSE_POINTS = 1025
#: default tolerances of the mass-conserving solve: the mass balance is the sum of the
#: residuals, so the residual tolerance is tighter than the flooded solver's
STARVED_TOL = 1e-7
STARVED_TOL_LOAD = 1e-7


class StarvedLineHierarchy(LineHierarchy):
    """Grids of one mass-conserving line-contact solve (protocol of the multilevel driver)."""

    name = "starved line"

    def __init__(self, problem: LineProblem, options: LineOptions, hoil: float,
                 flooded: EHLResult) -> None:
        self.problem = problem
        self.options = options
        self.hoil = hoil
        self.flooded = flooded
        par = problem.rheology()
        nlev = line_levels(options, problem.M)
        n_f = options.points
        self.levels = [
            StarvedLevel((n_f - 1) // 2 ** (nlev - 1 - k) + 1, problem.xmin, problem.xmax, par,
                         problem.lam, problem.elastic, options.deformation, options.wedge_order,
                         options.mlmi_order, options.mlmi_radius, hoil=hoil)
            for k in range(nlev)
        ]
        self.flux_flooded = flooded_flux(self.levels[-1], flooded)
        #: a starved inlet lets in exactly Hoil; a supply above what the flooded contact takes
        #: floods it (the excess flows back: the meniscus lies beyond any inlet)
        self.starved_inlet = bool(hoil < self.flux_flooded)
        for lv in self.levels:
            lv.starved_inlet = self.starved_inlet
        self.newton_iterations = 0
        self.solver: MultilevelSolver | None = None

    # -- observables ----------------------------------------------------------------------
    def measure(self, k: int) -> Measurement:
        lv = self.levels[k]
        st = lv.state()
        res = self.relative_residual(lv, st)
        Hc = self.central_film(lv, st)
        ok = bool(np.all(np.isfinite(lv.P)) and np.all(np.isfinite(lv.theta)) and np.isfinite(lv.H0)
                  and np.isfinite(res) and np.all(np.isfinite(st.H)) and Hc > 0.0)
        zone = (np.abs(lv.X) <= 1.5) | (lv.P > 0)
        Hm = float(np.min(st.H[zone])) if zone.any() else math.nan
        return Measurement(res, lv.load() / lv.g - 1.0, Hc, ok, Hm)

    def finite(self) -> bool:
        lv = self.levels[-1]
        return bool(np.all(np.isfinite(lv.P)) and np.all(np.isfinite(lv.theta)) and math.isfinite(lv.H0))

    def snapshot(self, k: int) -> list[tuple[np.ndarray, np.ndarray, float]]:
        return [(v.P.copy(), v.theta.copy(), v.H0) for v in self.levels[: k + 1]]

    def restore(self, k: int, saved: list[tuple[np.ndarray, np.ndarray, float]]) -> None:
        for v, (P, T, H0) in zip(self.levels, saved, strict=False):
            v.P, v.theta, v.H0 = P.copy(), T.copy(), H0

    # -- cycle pieces ---------------------------------------------------------------------
    def relax(self, k: int, sweeps: int, s: Settings, coarse: bool) -> float:
        lv = self.levels[k]
        # the film content follows the pressure's under-relaxation when the policy halves it
        omega_theta = min(1.0, 2.0 * s.omega)
        for _ in range(sweeps):
            lv.relax(s.switch, s.omega, s.omega_jd, self.options.band, switch_h=s.switch_h,
                     omega_theta=omega_theta)
            if coarse:
                lv.H0 += s.h00_gain * (lv.load() - lv.g)
        return sweeps * self.work(k)

    def restrict(self, k: int, s: Settings) -> tuple[Any, float]:
        lv, cv = self.levels[k], self.levels[k - 1]
        st = lv.state()
        lres = self.relative_residual(lv, st)
        cv.P = inject(lv.P)
        cv.theta = inject(lv.theta)
        cv.H0 = lv.H0
        # a coarse point is free only if its fine neighbourhood is pressurised and free: the
        # meniscus and the rupture point move by fine-grid relaxation only (Brandt & Cryer)
        free = (lv.P > 0.0) & ~lv.frozen
        cfree = free[::2].copy()
        cfree[1:] &= free[1::2]
        cfree[:-1] &= free[1::2]
        cv.frozen = ~cfree
        cv.frozen[0] = cv.frozen[-1] = False
        P_start, H0_start = cv.P.copy(), cv.H0
        cv.f = np.zeros(cv.n)
        cst = cv.state()
        rc = full_weighting(np.where(lv.frozen, 0.0, st.r))
        cv.f = -cst.r + rc
        cv.f[0] = cv.f[-1] = 0.0
        cv.g = cv.load() + (lv.g - lv.load())
        return (P_start, H0_start, st), lres

    def correct(self, k: int, token: Any, s: Settings) -> None:
        lv, cv = self.levels[k], self.levels[k - 1]
        P_start, H0_start, st = token
        corr = interpolate_linear(np.where(cv.frozen, 0.0, cv.P - P_start))
        corr[lv.P <= 0.0] = 0.0
        corr[lv.frozen] = 0.0
        lv.P = np.maximum(lv.P + corr, 0.0)
        lv.P[0] = lv.P[-1] = 0.0
        lv.H0 += cv.H0 - H0_start

    def coarse_solve(self, k: int, s: Settings) -> float:
        lv = self.levels[k]
        saved = (lv.P.copy(), lv.theta.copy(), lv.H0)
        try:
            its = newton_solve(lv)
        except StarvedNewtonFailure as exc:
            lv.P, lv.theta, lv.H0 = saved
            self.solver.note(f"coarse Newton failed ({exc}); relaxed instead")
            return self.relax(k, 20, s, True)
        self.newton_iterations += its
        return its * self.work(k)

    def fmg_interpolate(self, k: int, s: Settings) -> float:
        lv, cv = self.levels[k], self.levels[k - 1]
        lv.P = np.maximum(interpolate_cubic(cv.P), 0.0)
        lv.P[0] = lv.P[-1] = 0.0
        lv.theta = np.clip(interpolate_linear(cv.theta), 1e-12, 1.0)
        lv.theta[lv.P > 0.0] = 1.0
        lv.H0 = cv.H0
        lv.f = np.zeros(lv.n)
        lv.g = 0.5 * math.pi
        lv.frozen[:] = False
        if self.options.fmg_match_film:
            lv.H0 += self.central_film(cv) - self.central_film(lv)
        return 0.0

    # -- FMG start ------------------------------------------------------------------------
    def _from_flooded(self, lv: StarvedLevel) -> None:
        """The flooded solution on grid ``lv`` (injected), with the central film matched."""
        fl = self.flooded
        stride = (fl.X.shape[0] - 1) // (lv.n - 1)
        lv.P = np.maximum(fl.P[::stride].copy(), 0.0)
        lv.theta = np.ones(lv.n)
        lv.f = np.zeros(lv.n)
        lv.g = 0.5 * math.pi
        lv.frozen[:] = False
        lv.H0 = fl.H0
        lv.H0 += float(np.interp(0.0, fl.X, fl.H)) - self.central_film(lv)

    def start(self, solver: MultilevelSolver) -> int:
        """Solve the FMG start grid by dense Newton from the flooded solution; when that
        fails, by continuation in ``Hoil`` (halved from the flooded central film)."""
        self.solver = solver
        k = self._start_level()
        lv = self.levels[k]
        self._from_flooded(lv)
        try:
            its = newton_solve(lv, max_iter=120)
        except StarvedNewtonFailure as exc:
            solver.note(f"FMG start on {lv.n} points: Newton from the flooded solution failed "
                        f"({exc}); continuation in Hoil")
            its = self._continuation(lv)
        self.newton_iterations += its
        solver.work_units += its * self.work(k)
        if k > 0:
            solver.note(f"FMG started on the {lv.n}-point grid (cycles still coarsen to {self.levels[0].n})")
        return k

    def _continuation(self, lv: StarvedLevel) -> int:
        target = self.hoil
        steps = [target]
        while steps[-1] * 2.0 < 0.9 * self.flux_flooded:
            steps.append(steps[-1] * 2.0)
        self._from_flooded(lv)
        total = 0
        for hoil in reversed(steps):
            lv.hoil = hoil
            try:
                total += newton_solve(lv, max_iter=120)
            except StarvedNewtonFailure as exc:
                lv.hoil = target
                raise ConvergenceError(
                    f"the starved start failed even with continuation in Hoil (at Hoil = {hoil:.4g}: "
                    f"{exc})", None, HINT) from None
        lv.hoil = target
        return total

    # -- last resort ----------------------------------------------------------------------
    def last_resort(self, k: int, solver: MultilevelSolver) -> bool:
        """A stalled solve on a grid small enough: dense Newton on the finest grid."""
        fin = self.levels[k]
        if fin.n > MAX_DENSE_POINTS:
            return False
        saved = (fin.P.copy(), fin.theta.copy(), fin.H0)
        fin.frozen[:] = False
        try:
            its = newton_solve(fin, max_iter=60)
        except StarvedNewtonFailure as exc:
            fin.P, fin.theta, fin.H0 = saved
            solver.note(f"finest-grid Newton after the multigrid stall failed: {exc}")
            return False
        self.newton_iterations += its
        solver.work_units += its
        solver.note(f"multigrid stalled: finished by {its} dense Newton iterations on the {fin.n}-point grid")
        solver.record(k, -1, self.measure(k))
        return solver.converged()


def flooded_flux(lv: StarvedLevel, flooded: EHLResult) -> float:
    """Mass flux through the flooded contact (Venner units), at the face next to the
    pressure maximum (where the flux is all Couette), evaluated on grid ``lv``'s
    discretisation of the flooded solution."""
    stride = (flooded.X.shape[0] - 1) // (lv.n - 1)
    P = np.maximum(flooded.P[::stride], 0.0)
    st = lv.state(P, flooded.H0, np.ones(lv.n))
    F = face_fluxes(P, st.q, st.eps, lv.h, lv.order, False)
    return float(F[min(int(np.argmax(P)), F.shape[0] - 1)])


# -- results --------------------------------------------------------------------------------
def _crossing(X: np.ndarray, theta: np.ndarray, idx: np.ndarray) -> float:
    """X where ``theta`` reaches 1 between the nodes ``idx - 1`` and ``idx`` (linear)."""
    if idx <= 0:
        return float(X[0])
    t0, t1 = theta[idx - 1], theta[idx]
    if t1 == t0:
        return float(X[idx])
    return float(X[idx - 1] + (1.0 - t0) / (t1 - t0) * (X[idx] - X[idx - 1]))


def starved_scalars(lv: StarvedLevel, hoil: float, flooded: EHLResult, pb: LineProblem) -> dict[str, Any]:
    """Observables of the mass-conserving solution (Venner units unless named Moes)."""
    st = lv.state()
    theta = st.theta.copy()
    F = lv.fluxes(st)
    X = lv.X
    wet = np.flatnonzero(theta[:-1] >= 1.0)
    s: dict[str, Any] = {}
    s["hoil_venner"] = hoil
    s["Hoil"] = pb.moes_from_venner(hoil) if math.isfinite(hoil) else math.inf
    s["inlet_flooded"] = bool(theta[0] >= 1.0)
    # meniscus: where the film content first reaches 1 coming from the inlet
    s["meniscus_x"] = _crossing(X, theta, int(wet[0])) if wet.size else math.nan
    # rupture: the last pressurised node's downstream face, where theta falls below 1
    pres = np.flatnonzero(lv.P > 0.0)
    s["cavitation_x"] = float(X[pres[-1] + 1]) if pres.size else math.nan
    s["flux_in"] = float(F[0])
    s["flux_out"] = float(F[-1])
    s["mass_balance_error"] = float(abs(F[-1] - F[0]) / abs(F[0]))
    s["supplied_flux"] = float(hoil) if math.isfinite(hoil) and theta[0] < 1.0 else float(st.q[0])
    # the layer the surfaces carry away (ambient density): the outlet flux, all Couette
    s["outlet_layer_venner"] = float(F[-1])
    s["outlet_layer"] = pb.moes_from_venner(F[-1])
    rho_c = float(np.interp(0.0, X, st.rho))
    Hc = float(np.interp(0.0, X, st.H))
    s["rho_c"] = rho_c
    s["rho_c_Hc_over_hoil"] = rho_c * Hc / hoil if math.isfinite(hoil) else math.nan
    s["Hc_flooded_venner"] = float(flooded.scalars["Hc_venner"])
    s["Hm_flooded_venner"] = float(flooded.scalars["Hm_venner"])
    s["Hc_flooded"] = float(flooded.scalars["Hc"])
    s["Hm_flooded"] = float(flooded.scalars["Hm"])
    s["rho_bar_pmax"] = float(density_ratio_dh(pb.pmax)) if pb.density == "dowson-higginson" else 1.0
    return s


def finish_starved_result(sol: EHLResult, solver: MultilevelSolver, flooded: EHLResult,
                          scene: Any = None) -> EHLResult:
    """Fill the fields and scalars of a driver's result (line scalars plus the starved ones)."""
    hz = solver.hierarchy
    finish_line_result(sol, solver, scene)
    sol.contact = "line"
    lv = hz.levels[-1]
    st = lv.state()
    theta = st.theta.copy()
    # the outlet node is in no equation: its content carries the outlet flux on
    theta[-1] = min(1.0, st.q[-2] / (st.rho[-1] * st.H[-1]))
    sol.extra["theta"] = theta
    sol.extra["flooded"] = flooded
    sol.scalars.update(starved_scalars(lv, hz.hoil, flooded, hz.problem))
    sol.scalars["Hc_ratio"] = sol.scalars["Hc_venner"] / sol.scalars["Hc_flooded_venner"]
    sol.scalars["Hm_ratio"] = sol.scalars["Hm_venner"] / sol.scalars["Hm_flooded_venner"]
    sol.builder = None
    return sol


# -- public API -----------------------------------------------------------------------------
def starved_options(options: LineOptions | None = None, **kw: Any) -> LineOptions:
    """Line options with the mass-conserving solve's tighter default tolerances (explicit
    ``tol``/``tol_load`` keywords or options win)."""
    base = {"tol": STARVED_TOL, "tol_load": STARVED_TOL_LOAD} if options is None else {}
    return LineOptions.build(options, **{**base, **kw})


def solve_starved_problem(problem: LineProblem, hoil: float, options: LineOptions,
                          flooded: EHLResult | None = None,
                          callback: Callable[[dict[str, Any]], None] | None = None,
                          scene: Any = None) -> EHLResult:
    """One mass-conserving solve as given (no error estimate). ``flooded``: the flooded
    solution of the same problem and grid (solved here when None)."""
    if flooded is None:
        flooded = solve_line_problem(problem, dataclasses.replace(
            options, raise_on_failure=False, film_tol=None))
    if not flooded.success:
        res = EHLResult(status=5, message=f"the flooded start solve failed: {flooded.message}")
        if options.raise_on_failure:
            raise ConvergenceError(f"starved line solver: {res.message}", None, HINT)
        return res
    hz = StarvedLineHierarchy(problem, options, hoil, flooded)
    solver = MultilevelSolver(hz, options, line_settings(problem, options),
                              RobustnessPolicy(LINE_POLICY, options.adapt), HINT)
    hz.solver = solver
    res = solver.solve(callback=callback)
    out = finish_starved_result(res, solver, flooded, scene)
    hz.solver = None
    return out


def starved_domain_change(problem: LineProblem, hoil: float, options: LineOptions,
                          sol: EHLResult) -> tuple[float, float] | None:
    """Relative change of (Hc, Hm) when the inlet moves upstream by the box length at equal
    mesh size (two solves two grids below the finest, not below the FMG start grid)."""
    top = sol.levels - 1
    k0 = max(top - 2, min(d["level"] for d in sol.fmg))
    wide = dataclasses.replace(problem, xmin=problem.xmin - (problem.xmax - problem.xmin))
    n_p = (sol.X.shape[0] - 1) // 2 ** (top - k0) + 1

    def solve(pb: LineProblem, n: int) -> EHLResult:
        o = dataclasses.replace(options, points=n, levels=None, fmg_start_points=None,
                                raise_on_failure=False, film_tol=None)
        return solve_starved_problem(pb, hoil, o)

    return film_change(lambda: solve(problem, n_p), lambda: solve(wide, 2 * (n_p - 1) + 1))


def solve_starved_line(problem: LineProblem, hoil: float, options: LineOptions | None = None,
                       accuracy: float | None = None, *, estimate: bool = True,
                       callback: Callable[[dict[str, Any]], None] | None = None,
                       max_points: int = MAX_ACCURACY_POINTS, scene: Any = None,
                       **kw: Any) -> EHLResult:
    """Solve the starved, mass-conserving isothermal EHL line contact.

    Parameters
    ----------
    problem : the :class:`~ehl_multigrid.line.problem.LineProblem` (M, L, oil, domain).
    hoil : supplied oil layer ahead of the contact in Venner units, ``Hoil = hoil R/b^2``
        (both surfaces together, at ambient density; Moes units: ``Hoil 8M/pi``). ``inf``
        or any layer thicker than the inlet gap gives a flooded inlet (still with the
        mass-conserving outlet). Allowed: ``(0, inf]``.
    options : :class:`~ehl_multigrid.multigrid.options.LineOptions` (default: the line
        defaults with ``tol = tol_load = 1e-7``, so the mass balance, the sum of the
        residuals, closes to about 1e-7); keywords override its fields.
    accuracy : relative target for Hc and Hm (as :func:`ehl_multigrid.line.solve_line`): the
        grid is refined until the estimated error meets it or ``max_points`` is reached.
    estimate : attach the error estimate (grid part: Richardson from the FMG levels; domain
        part: two coarse solves with a doubled box; algebraic part: last-cycle change).

    Returns
    -------
    EHLResult
        Line scalars (``Hc``, ``Hm`` in Moes units, ``Hc_venner`` ...) plus ``Hc_flooded``,
        ``Hm_flooded`` (the core flooded solver on the same grid), ``Hc_ratio``,
        ``Hm_ratio``, ``meniscus_x``, ``cavitation_x``, ``mass_balance_error`` (relative
        difference of the mass flux through the first and last face), ``outlet_layer``
        (the layer left behind the contact, Moes units; ``outlet_layer_venner``),
        ``rho_c_Hc_over_hoil``; ``extra['theta']`` the film content. Histories: residual,
        load error, cycles as every driver result.

    Raises
    ------
    InputError : bad ``hoil`` (negative, zero, NaN) or options.
    ConvergenceError : divergence, a stall or NaN (``raise_on_failure``, the default).
    """
    hoil = check_hoil(hoil)
    opts = starved_options(options, **kw)
    if accuracy is not None:
        require_range("accuracy", accuracy, 1e-5, 0.5, "- (relative error)")
    if not estimate:
        return solve_starved_problem(problem, hoil, opts, callback=callback, scene=scene)
    explicit = "points" in kw or (options is not None and accuracy is None)

    def solve(n: int, box: float, tol_factor: float) -> EHLResult:
        p = problem if box == 1.0 else dataclasses.replace(
            problem, xmin=problem.xmax - box * (problem.xmax - problem.xmin))
        o = dataclasses.replace(opts, points=n, tol=opts.tol * tol_factor,
                                tol_load=opts.tol_load * tol_factor, raise_on_failure=False,
                                film_tol=film_tol(opts, accuracy, tol_factor))
        return solve_starved_problem(p, hoil, o, callback=callback, scene=scene)

    def probe(res: EHLResult, box: float) -> tuple[float, float] | None:
        return starved_domain_change(res.problem, hoil, res.options, res)

    res = solve_to_accuracy(solve, probe, accuracy, opts.points, max_points,
                            refine=accuracy is not None and not explicit)
    if not res.success and opts.raise_on_failure:
        raise ConvergenceError(f"starved line solver: {res.message}", res.report, HINT)
    return res


def validate_problem(problem: Any) -> LineProblem:
    if not isinstance(problem, LineProblem):
        raise InputError(f"problem = {type(problem).__name__}: expected a LineProblem")
    return problem
