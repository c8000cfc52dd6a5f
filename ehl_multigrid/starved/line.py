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

:func:`solve_starved_problem` solves one problem as given: with ``Hoil`` below the flooded
flux the meniscus is found inside the multilevel iteration (the fully coupled Elrod-Adams
inlet; converges from the starved guess at moderate starvation, not robust at severe
starvation, see validation/starved); with ``Hoil = inf`` the inlet is flooded and only the
rupture is Elrod-Adams. The public solver (:func:`ehl_multigrid.starved.solve_starved_line`)
locates the meniscus by an outer root search over flooded-inlet solves (meniscus.py).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..line.newton import NewtonFailure
from ..line.newton import newton_solve as flooded_newton
from ..line.problem import LineProblem
from ..line.solution import finish_line_result
from ..line.solver import (
    HINT,
    LINE_POLICY,
    LineHierarchy,
    coarse_points,
    fas_coarse_problem,
    line_levels,
    line_settings,
    solve_line_problem,
)
from ..model.errors import ConvergenceError
from ..model.lubricant import density_ratio_dh
from ..multigrid.driver import Measurement, MultilevelSolver
from ..multigrid.options import LineOptions
from ..multigrid.policy import RobustnessPolicy, Settings
from ..multigrid.result import EHLResult
from ..multigrid.transfer import inject, interpolate_linear
from .discrete import face_fluxes
from .gate import apply_mass_gate
from .level import StarvedLevel
from .newton import StarvedNewtonFailure, newton_solve
from .refine import supply_ratio

#: largest grid the dense Newton may finish on the start grid
MAX_DENSE_POINTS = 513
#: largest grid the dense Newton may finish after a multigrid stall or a failed first cycle
#: (the box solves of a meniscus within 0.006 a of the Hertzian edge on the default 1025
#: points: a 2047-unknown system, about 0.3 s per iteration)
LAST_RESORT_POINTS = 1025
#: relaxation sweeps per visit of the coarsest grid
COARSE_SWEEPS = 30
#: most relaxation sweeps on the FMG start grid, and the fraction of the cycles' film-constant
#: gain used there (measured at M = 20, L = 10, 257 points, Hoil = 0.02: the full gain 0.1
#: per sweep drives the film through zero, a tenth of it settles in 500 sweeps)
START_SWEEPS = 4000
START_GAIN = 0.1
#: a flooded inlet's start (the flooded solution, the film content 1 behind the rupture) is
#: relaxed on its grid until its relative residual is below SETTLE_RESIDUAL, at most
#: SETTLE_SWEEPS sweeps, before any coarse-grid correction: the content behind the rupture
#: settles in 1-6 sweeps (more the closer the box's inlet lies to the Hertzian edge), and a
#: cycle taken before it diverges for an inlet within 0.006 a of the edge (page 63 at 16000 N,
#: X_m = -1.002 and -1.006 on 2049-8193 points: every attempt of the first cycle rejected)
SETTLE_RESIDUAL = 1e-2
SETTLE_SWEEPS = 20
#: start-grid resolution of the starved inlet: mesh at most this fraction of the rigid inlet length
#: sqrt(2 Hc) of the starved film (Hc ~ Hoil/rho_c); at (20, 10) h = 0.045 converges Hoil = 0.02
#: (0.25) and leaves a negative film at the meniscus for Hoil = 0.002 (0.78)
START_RESOLUTION = 0.25
#: smallest FMG start grid (the flooded solver's coarse-grid rule applies above it)
MIN_START_POINTS = 129
#: default tolerances of the mass-conserving solve: the mass balance is the sum of the
#: residuals, so the residual tolerance is tighter than the flooded solver's
STARVED_TOL = 1e-7
STARVED_TOL_LOAD = 1e-7


class StarvedLineHierarchy(LineHierarchy):
    """Grids of one mass-conserving line-contact solve (protocol of the multilevel driver)."""

    name = "starved line"
    grid_stop = False  # the mass balance needs the residual, not only the films
    level_type = StarvedLevel

    def __init__(self, problem: LineProblem, options: LineOptions, hoil: float,
                 flooded: EHLResult) -> None:
        self.hoil = hoil
        self.flooded = flooded
        self.n_start = start_points(problem, options, hoil, flooded)
        super().__init__(problem, options)
        self.flux_flooded = flooded_flux(self.levels[-1], flooded)
        #: a starved inlet lets in exactly Hoil; a supply above what the flooded contact takes
        #: floods it (the excess flows back: the meniscus lies beyond any inlet)
        self.starved_inlet = bool(hoil < self.flux_flooded)
        for lv in self.levels:
            lv.hoil = hoil
            lv.starved_inlet = self.starved_inlet

    def grid_count(self) -> int:
        """The flooded solver's grids, or down to the starved FMG start grid when it differs
        (:func:`start_points`)."""
        options, n_f = self.options, self.options.points
        if options.levels is None and self.n_start == n_f:
            return line_levels(options, self.problem.M)
        nlev = int(options.levels) if options.levels is not None else \
            int(round(math.log2((n_f - 1) / (self.n_start - 1)))) + 1
        line_levels(dataclasses.replace(options, levels=nlev), self.problem.M)  # validates the grid
        return nlev

    # -- observables ----------------------------------------------------------------------
    def measure(self, k: int) -> Measurement:
        m = super().measure(k)
        m.ok = m.ok and bool(np.all(np.isfinite(self.levels[k].theta)))
        return m

    def finite(self) -> bool:
        lv = self.levels[-1]
        return bool(np.all(np.isfinite(lv.P)) and np.all(np.isfinite(lv.theta)) and math.isfinite(lv.H0))

    def snapshot(self, k: int) -> list[tuple[np.ndarray, np.ndarray, float]]:
        return [(v.P.copy(), v.theta.copy(), v.H0) for v in self.levels[: k + 1]]

    def restore(self, k: int, saved: list[tuple[np.ndarray, np.ndarray, float]]) -> None:
        for v, (P, T, H0) in zip(self.levels, saved, strict=False):
            v.P, v.theta, v.H0 = P.copy(), T.copy(), H0

    # -- cycle pieces ---------------------------------------------------------------------
    def relax(self, k: int, sweeps: int, s: Settings, coarse: bool, post: bool = False) -> float:
        lv = self.levels[k]
        for _ in range(sweeps):
            self._sweep(lv, s, s.h00_gain if coarse else None)
        return sweeps * self.work(k)

    def _sweep(self, lv: StarvedLevel, s: Settings, gain: float | None) -> None:
        """One relaxation sweep of grid ``lv``, then, with a ``gain``, the film constant
        following the load error."""
        # the film content follows the pressure's under-relaxation when the policy halves it
        lv.relax(s.switch, s.omega, s.omega_jd, self.options.band, switch_h=s.switch_h,
                 omega_theta=min(1.0, 2.0 * s.omega))
        if gain is not None:
            lv.H0 += gain * (lv.load() - lv.g)

    def restrict(self, k: int, s: Settings) -> tuple[Any, float]:
        lv, cv = self.levels[k], self.levels[k - 1]
        st = lv.state()
        lres = self.relative_residual(lv, st)
        # the meniscus and the rupture point move by fine-grid relaxation only (the core's
        # Brandt & Cryer free set); the film content is injected like P
        cv.theta = inject(lv.theta)
        P_start, H0_start = fas_coarse_problem(lv, cv, np.where(lv.frozen, 0.0, st.r))
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
        """Flooded inlet: the flooded solver's dense Newton for ``(P, H0)`` (the coarse points
        that are not pressurised are frozen; its rows are the flooded residual, also next to
        points whose film content is below 1); starved
        inlet: relaxation sweeps with the film constant following the load. Newton failing,
        relaxation too."""
        lv = self.levels[k]
        if not self.starved_inlet:
            saved = (lv.P.copy(), lv.H0)
            try:
                its = flooded_newton(lv)
                lv.P = np.maximum(lv.P, 0.0)
                self.newton_iterations += its
                return its * self.work(k)
            except NewtonFailure as exc:
                lv.P, lv.H0 = saved
                self.solver.note(f"coarse Newton failed ({exc}); relaxed instead")
        return self.relax(k, COARSE_SWEEPS, s, True)

    def fmg_interpolate(self, k: int, s: Settings) -> float:
        """The flooded solver's interpolation of ``P`` and ``H0`` (the film does not depend on
        ``theta``), the film content interpolated linearly, 1 where pressurised."""
        cost = super().fmg_interpolate(k, s)
        lv = self.levels[k]
        lv.theta = np.clip(interpolate_linear(self.levels[k - 1].theta), 1e-12, 1.0)
        lv.theta[lv.P > 0.0] = 1.0
        lv.frozen[:] = False
        return cost

    # -- FMG start ------------------------------------------------------------------------
    def _from_flooded(self, lv: StarvedLevel) -> None:
        """The flooded solution on grid ``lv`` (injected), with the central film matched."""
        fl = self.flooded
        lv.P = flooded_pressure(lv, fl)
        lv.theta = np.ones(lv.n)
        lv.f = np.zeros(lv.n)
        lv.g = 0.5 * math.pi
        lv.frozen[:] = False
        lv.H0 = fl.H0
        lv.H0 += float(np.interp(0.0, fl.X, fl.H)) - self.central_film(lv)
        if self.starved_inlet:
            # starved guess: the film that carries the supply, no pressure upstream of the
            # point where the gap shrinks to Hoil, the film content carrying Hoil elsewhere
            st = lv.state()
            rho_c = float(np.interp(0.0, lv.X, st.rho))
            Hc = self.central_film(lv, st)
            lv.H0 += min(self.hoil / rho_c, Hc) - Hc
            st = lv.state()
            peak = int(np.argmax(lv.P))
            wide = np.flatnonzero((np.arange(lv.n) >= peak) | (st.H <= self.hoil))
            first = int(wide[0]) if wide.size else peak
            lv.P[:first] = 0.0
            lv.theta[:first] = np.minimum(1.0, self.hoil / st.H[:first])
            out = (np.arange(lv.n) > peak) & (lv.P <= 0.0)
            lv.theta[out] = np.minimum(1.0, self.hoil / np.maximum(st.H[out], 1e-12))

    def _start_level(self) -> int:
        for k, lv in enumerate(self.levels):
            if lv.n >= self.n_start:
                return k
        return len(self.levels) - 1

    def start(self, solver: MultilevelSolver) -> int:
        """Solve the FMG start grid from the flooded solution: relaxation sweeps with the film
        constant following the load slowly (a tenth of the cycles' gain: the starved film
        settles to the supplied flux first), then dense Newton to finish when the grid is
        small enough. The start grid resolves the starved inlet (:func:`start_points`)."""
        self.solver = solver
        k = self._start_level()
        lv = self.levels[k]
        self._from_flooded(lv)
        if not self.starved_inlet:
            # the flooded solution on the same grid is the start: only the film content
            # behind the rupture is new, and it settles by relaxation first
            sweeps = 0
            while sweeps < SETTLE_SWEEPS and self.measure(k).residual > SETTLE_RESIDUAL:
                self._sweep(lv, solver.settings, None)
                sweeps += 1
            solver.work_units += sweeps * self.work(k)
            return k
        s = solver.settings
        tol, tol_load = 0.1 * solver.options.tol, 0.1 * solver.options.tol_load
        sweeps = 0
        while sweeps < START_SWEEPS:
            self._sweep(lv, s, START_GAIN * s.h00_gain)
            sweeps += 1
            if sweeps % 50 == 0:
                m = self.measure(k)
                if not m.ok and not np.all(np.isfinite(lv.P)):
                    raise ConvergenceError(f"the starved start on {lv.n} points produced NaN after "
                                           f"{sweeps} sweeps", None, HINT)
                if m.residual < tol and abs(m.load_error) < tol_load:
                    break
        solver.work_units += sweeps * self.work(k)
        m = self.measure(k)
        solver.note(f"FMG start on {lv.n} points: {sweeps} relaxation sweeps from the flooded "
                    f"solution (residual {m.residual:.3g}, load error {m.load_error:.3g})")
        if lv.n <= MAX_DENSE_POINTS and not (m.residual < tol and abs(m.load_error) < tol_load):
            its = self._newton(lv, 40, solver, "FMG start: dense Newton did not finish the start grid ({})")
            if its is not None:
                solver.work_units += its * self.work(k)
        return k

    def _newton(self, lv: StarvedLevel, max_iter: int, solver: MultilevelSolver, failed: str) -> int | None:
        """Dense Newton on grid ``lv`` (:func:`.newton.newton_solve`): its iterations, or None
        with the grid restored and ``failed`` (formatted with the reason) noted."""
        saved = (lv.P.copy(), lv.theta.copy(), lv.H0)
        try:
            its = newton_solve(lv, max_iter=max_iter)
        except StarvedNewtonFailure as exc:
            lv.P, lv.theta, lv.H0 = saved
            solver.note(failed.format(exc))
            return None
        self.newton_iterations += its
        return its

    # -- last resort ----------------------------------------------------------------------
    def last_resort(self, k: int, solver: MultilevelSolver) -> bool:
        """A stalled solve on a grid small enough: dense Newton on the finest grid."""
        fin = self.levels[k]
        if fin.n > LAST_RESORT_POINTS:
            return False
        fin.frozen[:] = False
        its = self._newton(fin, 60, solver, "finest-grid Newton after the multigrid stall failed: {}")
        if its is None:
            return False
        solver.work_units += its
        solver.note(f"multigrid stalled: finished by {its} dense Newton iterations on the {fin.n}-point grid")
        solver.record(k, -1, self.measure(k))
        return solver.converged()


def start_points(problem: LineProblem, options: LineOptions, hoil: float, flooded: EHLResult) -> int:
    """Points of the FMG start grid: the flooded solver's start grid, refined until the mesh
    resolves the starved inlet (``h <= START_RESOLUTION sqrt(2 Hc)`` with the film that the
    supply carries, ``Hc ~ min(Hoil, Hc_ff)/rho_c``), at most the finest grid."""
    if options.fmg_start_points is not None:
        return min(int(options.fmg_start_points), options.points)
    if not hoil < flooded_flux_estimate(flooded):
        return options.points  # flooded inlet: start from the flooded solution itself
    n = max(MIN_START_POINTS, coarse_points(problem.M))
    Hc_ff = float(flooded.scalars["Hc_venner"])
    Hc = min(hoil, Hc_ff)
    h_need = START_RESOLUTION * math.sqrt(2.0 * max(Hc, 1e-12))
    while n < options.points and (problem.xmax - problem.xmin) / (n - 1) > h_need:
        n = 2 * (n - 1) + 1
    return min(n, options.points)


def flooded_flux_estimate(flooded: EHLResult) -> float:
    """Flux of the flooded contact ``rho H`` at the pressure maximum (its Couette part; the
    hierarchy measures it exactly on its own discretisation)."""
    i = int(np.argmax(flooded.P))
    rho = density_ratio_dh(flooded.P[i] * flooded.problem.pmax) if flooded.problem.density == "dowson-higginson" else 1.0
    return float(rho * flooded.H[i])


def flooded_pressure(lv: StarvedLevel, flooded: EHLResult) -> np.ndarray:
    """The flooded solution's pressure injected on grid ``lv`` (a coarser grid of the same box)."""
    return np.maximum(flooded.P[::(flooded.X.shape[0] - 1) // (lv.n - 1)], 0.0)


def flooded_flux(lv: StarvedLevel, flooded: EHLResult) -> float:
    """Mass flux through the flooded contact (Venner units), at the face next to the
    pressure maximum (where the flux is all Couette), evaluated on grid ``lv``'s
    discretisation of the flooded solution."""
    P = flooded_pressure(lv, flooded)
    st = lv.state(P, flooded.H0, np.ones(lv.n))
    F = face_fluxes(P, st.theta, st.q, st.eps, lv.h, lv.order, False, lv.face)
    return float(F[min(int(np.argmax(P)), F.shape[0] - 1)])


# -- results --------------------------------------------------------------------------------
def _crossing(X: np.ndarray, theta: np.ndarray, idx: int) -> float:
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
    s["rho_c_Hc_over_hoil"] = supply_ratio(rho_c, Hc, hoil)
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
    sol.builder = starved_result
    return sol


def starved_result(sol: EHLResult, scene: Any = None) -> Any:
    """Package :class:`~ehl_multigrid.model.results.Result` (kind ``"ehl_line"``) with the
    film content ``theta`` beside ``P`` and ``H`` and the starved scalars."""
    from ..line.solution import line_result

    res = line_result(sol, scene)
    res.add_field("theta", sol.extra["theta"], "-", ("X",), "film content (Elrod-Adams)")
    res.meta["definitions"] += ("; Elrod-Adams film content theta; meniscus_x where theta reaches 1 "
                                "(-inf: flooded inlet); Hc_flooded from the flooded solver on the same "
                                "grid; mass_balance_error relative flux imbalance (and supply mismatch)")
    return res


#: scalars of ``ehl solve --json`` for a starved line contact, beside the core payload
PAYLOAD_KEYS = ("Hc_flooded", "Hm_flooded", "Hc_ratio", "Hm_ratio", "meniscus_x", "cavitation_x",
                "mass_balance_error", "outlet_layer", "outlet_layer_m", "hoil", "Hoil",
                "inlet_flooded", "rho_c_Hc_over_hoil", "meniscus_solves")


def starved_payload(sol: EHLResult) -> dict[str, Any]:
    """The JSON payload of a starved solve: the core payload plus :data:`PAYLOAD_KEYS`."""
    out = sol.payload()
    out.update({k: sol.scalars[k] for k in PAYLOAD_KEYS if k in sol.scalars})
    return out


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
    solution of the same problem and grid (solved here when None).

    A numerical failure (also of the flooded start) is returned (``success`` False, its status
    and message), or raised as :class:`ConvergenceError` with ``options.raise_on_failure``."""
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
    if math.isfinite(hoil):
        # the coupled path's result must conserve the supply like the meniscus search's
        failed = apply_mass_gate(out, out.scalars["mass_balance_error"], out.scalars["rho_c_Hc_over_hoil"])
        if failed and options.raise_on_failure:  # the driver raised only for its own verdict
            raise ConvergenceError(f"starved line solver: {out.message}", out.report, HINT)
    return out
