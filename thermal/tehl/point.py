"""Thermal EHL point contact: the line contact's outer iteration (:mod:`thermal.tehl.outer`,
the geometry as :class:`PointContact`) on the shared point hierarchy, with the thermal layer
solved on each grid row along the rolling direction (the thesis's slicing of a point contact,
3.2.2.2 and (3.20), here on the EHL solution's own rows).

* pressure and film: :class:`FactorPointHierarchy`, the core
  :class:`~ehl_multigrid.point.fas.PointHierarchy` whose ``eps`` carries the flow factor
  ``a(X, Y)`` (both directions) and whose wedge density carries the Couette factor ``c(X, Y)``;
  with ``a = c = 1`` it is the core operator;
* temperature: one :func:`thermal.line.solve_thermal_line` per row ``Y_j >= 0`` that carries
  pressure (the solution is symmetric in Y), strip length of the surface kernel the transverse
  contact width 2b as in the thermal layer's slices. Convection and conduction across the
  rows (along Y) are neglected, as in the thesis's slices; rows without pressure keep the
  inlet temperature and ``a = c = 1``.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ehl_multigrid.model.errors import ConvergenceError, InputError
from ehl_multigrid.model.fits import nijenbanning_central
from ehl_multigrid.model.scene import Scene
from ehl_multigrid.multigrid.driver import MultilevelSolver
from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.multigrid.policy import RobustnessPolicy
from ehl_multigrid.multigrid.threads import preserved_threads
from ehl_multigrid.point.fas import HINT, POINT_POLICY, PointHierarchy, point_settings
from ehl_multigrid.point.numerics import fluid_properties, interpolate_cubic
from ehl_multigrid.point.postprocess import film_metrics, full_fields
from ehl_multigrid.point.problem import PointProblem, problem_from_scene, resolve_domain
from ehl_multigrid.point.solve import solve_fas

from ..line import Surroundings, ThermalLineSolution
from ..parallel import LineJob, solve_thermal_lines
from ..profiles import profile_from_arrays
from .coefficients import response_multiplier, solution_factors_and_response
from .hierarchy import GivenStart
from .line import heat_partition, interior_heat_budget
from .options import TEHLOptions
from .outer import Iterate, coupled_solve, surroundings
from .results import TEHLResult


class FactorPointHierarchy(GivenStart, PointHierarchy):
    """:class:`PointHierarchy` with flow and Couette factors (frozen during a solve), started
    on the finest grid from a given iterate."""

    name = "point (generalised Reynolds)"
    grid_stop = False  # started on the finest grid: no FMG grids to estimate from
    local_update = False  # eps carries the flow factors: every refresh goes through update_film
    far_field_ok = False  # the far field is derived for the isothermal Reynolds equation

    def __init__(self, problem: PointProblem, options: PointOptions) -> None:
        super().__init__(problem, options)
        for lev in self.levels:
            lev.a = np.ones(lev.shape)
            lev.c = np.ones(lev.shape)
            lev.w = None  # viscosity response (coefficients.viscosity_response): finest grid only
            lev.kref = None  # rho/(eta lambda) of the start iterate, where w is set

    def set_response(self, w: np.ndarray | None) -> None:
        """The flow's viscosity response ``w`` on the finest grid (None: the flow factor stays
        frozen as it is); the coarse grids keep their factors frozen (injected there, the
        coarsest grid's film constant ran away: docs/thermal.md)."""
        if w is None or not np.any(w > 0.0):
            for lev in self.levels:
                lev.w = None
            return
        for lev in self.levels[:-1]:
            lev.w = None
        self.levels[-1].w = np.ascontiguousarray(w, dtype=float)

    def flow_factor(self) -> np.ndarray:
        """The flow factor the finest grid's Poiseuille term carries at its pressure and film:
        ``a``, times the viscosity response's correction (:meth:`_apply`)."""
        lev = self.levels[-1]
        if lev.w is None or lev.kref is None:
            return lev.a
        rho, eps = np.empty_like(lev.P), np.empty_like(lev.P)
        fluid_properties(lev.P, lev.H, self.par, self.lam, rho, eps)
        return lev.a * response_multiplier(lev.w, self._log_ratio(lev, eps))

    @staticmethod
    def _log_ratio(lev: Any, eps: np.ndarray) -> np.ndarray:
        """``ln((rho/eta)(P_ref)/(rho/eta)(P))`` from ``eps`` of the current pressure and film
        (0 where either is not defined)."""
        H3 = lev.H * lev.H * lev.H
        ok = (eps > 0.0) & (H3 > 0.0) & np.isfinite(lev.kref)
        ratio = np.ones_like(eps)
        np.divide(lev.kref * H3, eps, out=ratio, where=ok)
        return np.log(ratio)

    def _apply(self, lev: Any) -> None:
        a = getattr(lev, "a", None)
        if a is None:
            return
        lev.rho *= lev.c
        if lev.w is None or lev.kref is None:
            lev.eps *= a
            return
        # the flow factor holds the effective viscosity of the start iterate to the degree w it
        # does not follow the pressure: eps = a (rho/eta)(P)^(1 - w) (rho/eta)(P_ref)^w H^3/lambda
        lev.eps *= a * response_multiplier(lev.w, self._log_ratio(lev, lev.eps))

    def update_film(self, lev: Any) -> None:
        super().update_film(lev)
        self._apply(lev)

    def coarse_solve(self, k: int, s: Any, sweeps: int | None = None) -> float:
        # the core's coarse solve refreshes rho and eps without the factors after each
        # film-constant step: one sweep at a time, factors applied in between
        lev = self.levels[k]
        n = self.options.coarse_sweeps if sweeps is None else sweeps
        cost = 0.0
        for _ in range(n):
            cost += super().coarse_solve(k, s, 1)
            self._apply(lev)
        return cost

    def start(self, solver: MultilevelSolver) -> int:
        P, H00 = self.given_start()
        self.solver = solver
        self.gain = solver.settings.h00_gain
        self._last_err = None
        top = len(self.levels) - 1
        lev = self.levels[top]
        lev.P = np.ascontiguousarray(P)
        self.H00 = H00
        self.h00_step_max = 0.1 * nijenbanning_central(self.pb.M, self.pb.L, self.theta) / self.pb.moes_factor
        lev.f = np.zeros_like(lev.P)
        lev.g = self.g_target
        lev.kref = None
        if lev.w is not None:
            PointHierarchy.update_film(self, lev)
            H3 = lev.H * lev.H * lev.H
            lev.kref = np.full_like(lev.eps, np.nan)
            np.divide(lev.eps, H3, out=lev.kref, where=(lev.eps > 0.0) & (H3 > 0.0))
        self.update_film(lev)
        return top


@dataclass(kw_only=True)
class TEHLPointResult(TEHLResult):
    """A converged TEHL point solution (half domain Y >= 0, rows ``[j, i]``), besides the
    :class:`~thermal.tehl.results.TEHLResult` fields.

    X, Y, P, H : grid (x/a, y/a) and Venner's fields; Hc, Hm : Moes central (X = Y = 0) and
    minimum films; T_mid, T_surface1, T_surface2 : mid-film and surface temperature maps [degC]
    (rows without pressure hold the oil temperature); heat budget [W] summed over the rows
    (interior budgets); extra : ``thermal_rows``, the rows solved.
    """

    problem: PointProblem
    Y: np.ndarray
    T_mid: np.ndarray
    T_surface1: np.ndarray
    T_surface2: np.ndarray
    extra: dict[str, Any] = field(default_factory=dict)
    #: the largest temperature across the film at each node (Y, X) [degC], whose maximum is
    #: ``T_max``; the grid part of T_max's error compares it between grids
    T_peak: np.ndarray | None = None


@dataclass
class _Rows:
    """Thermal solutions of the loaded rows and their Y weights (both halves)."""

    rows: list[int]
    sols: list[ThermalLineSolution]
    widths: np.ndarray
    T: np.ndarray  # (row, X, Z) stacked for the change measure

    def friction(self) -> float:
        """Traction force [N] over the rows."""
        return float(sum(s.force_per_length * w for s, w in zip(self.sols, self.widths, strict=True)))

    def heat(self, lubricant: Any) -> dict[str, float]:
        """Heat budget [W] summed over the rows' interior budgets (:func:`interior_heat_budget`)."""
        keys = ("shear", "compression", "conduction1", "conduction2", "convection")
        heat = dict.fromkeys(keys, 0.0)
        for s, w in zip(self.sols, self.widths, strict=True):
            hb = interior_heat_budget(s, lubricant)
            for k in keys:
                heat[k] += hb[k] * w
        heat["balance"] = ((heat["shear"] + heat["compression"] - heat["conduction1"] - heat["conduction2"]
                            - heat["convection"]) / heat["shear"] if heat["shear"] > 0 else 0.0)
        return heat


class PointContact:
    """The point contact of a coupled TEHL solve (:class:`~thermal.tehl.outer.Contact`): the
    half domain's factor hierarchy and one thermal layer per grid row that carries pressure."""

    label, alternation, hint = "TEHL point", "", HINT

    def __init__(self, scene: Scene, pb: PointProblem, opts: TEHLOptions, options: PointOptions,
                 env: Surroundings, X: np.ndarray, Y: np.ndarray, threads: int | None) -> None:
        self.scene, self.pb, self.opts, self.options, self.env = scene, pb, opts, options, env
        self.X, self.Y, self.threads = X, Y, threads
        self.hierarchy = FactorPointHierarchy(pb, options)
        self.topt = opts.thermal_options()
        self.notes: list[str] = []
        self.last: dict[int, Any] = {}  # each row's thermal solution of the previous outer iteration

    def multilevel(self) -> tuple[Any, np.ndarray, np.ndarray, float]:
        hz, popts = self.hierarchy, self.options
        with preserved_threads():
            solver = MultilevelSolver(hz, popts, point_settings(self.pb, popts),
                                      RobustnessPolicy(POINT_POLICY, popts.adapt), HINT)
            hz.solver = solver
            res = solver.solve()
            hz.solver = None
        fine = hz.levels[-1]
        return res, fine.P.copy(), fine.H.copy(), float(hz.H00)

    def friction(self, thermal: Any) -> float:
        return float(thermal.friction())

    def films(self, P: np.ndarray, H: np.ndarray) -> tuple[float, float]:
        Yf, Pf, Hf = full_fields(self.X, self.Y, P, H, True)
        m = film_metrics(self.X, Yf, Pf, Hf)
        return m["Hc_center"] * self.pb.moes_factor, m["Hm"] * self.pb.moes_factor

    def thermal(self, st: Iterate) -> tuple[_Rows, np.ndarray]:
        """The thermal layer on every loaded row, with the flux of the generalised Reynolds
        solve where the stress slope ``h dp/dx`` runs away (as the line contact does: the
        outlet spike's gradient drives an Eyring Poiseuille flow its own heat thins further,
        docs/thermal.md)."""
        try:
            return self._thermal(st, flux=False)
        except ConvergenceError as exc:
            note = (f"the stress slope h dp/dx ran away ({str(exc).splitlines()[0][:80]}); "
                    "the slope keeps the solve's Poiseuille flux")
            if note not in self.notes:
                self.notes.append(note)
            return self._thermal(st, flux=True)

    def _thermal(self, st: Iterate, flux: bool) -> tuple[_Rows, np.ndarray]:
        X, Y, pb, a_len, b_len = self.X, self.Y, self.pb, self.pb.a, self.scene.hertz.b
        lub, T0 = self.scene.lubricant, self.scene.T_oil
        topt = self.topt.with_changes(momentum="flux") if flux else self.topt
        hy = float(Y[1] - Y[0])
        rows = [j for j in range(st.P.shape[0]) if np.max(st.P[j]) > 0.0]
        flow = self.hierarchy.flow_factor() if flux else None
        jobs = []
        widths = []
        for jj in rows:
            w = hy * a_len * (1.0 if jj == 0 else 2.0)
            visc = None
            if flux:
                fac = np.asarray(flow[jj], dtype=float)

                def visc(p: np.ndarray, fac: np.ndarray = fac) -> np.ndarray:
                    # on the EHL nodes of the row: the effective viscosity of its flow factor
                    return np.asarray(lub.viscosity(p, T0), dtype=float) / fac
            prof = profile_from_arrays(X * a_len, st.P[jj] * pb.pmax, st.H[jj] * a_len**2 / pb.Rx, b=a_len,
                                       nx=X.size, width=w, x_in=None, x_out=None, Y=float(Y[jj]) * a_len / b_len,
                                       contact_half=math.sqrt(max(1.0 - (Y[jj] * a_len / b_len) ** 2, 0.0)),
                                       source="tehl", viscosity=visc)
            # strip length of the surface kernel: the transverse contact width 2b
            jobs.append(LineJob(prof, self.env, topt, 2.0 * b_len,
                                self.last.get(jj) if self.opts.warm_thermal else None))
            widths.append(w)
        sols = list(solve_thermal_lines(jobs, threads=self.threads))
        T = np.full((st.P.shape[0], X.size, self.opts.nz + 1), float(self.scene.T_oil))
        for jj, s in zip(rows, sols, strict=True):
            T[jj] = s.T
        self.last = dict(zip(rows, sols, strict=True))
        return _Rows(rows, sols, np.array(widths), T), T

    def factors(self, th: _Rows) -> tuple[np.ndarray, np.ndarray]:
        shape = th.T.shape[:2]
        a = np.ones(shape)
        c = np.ones(shape)
        w = np.zeros(shape)
        for jj, s in zip(th.rows, th.sols, strict=True):
            a[jj], c[jj], w[jj] = solution_factors_and_response(s, self.env, self.opts.shear_thinning)
        self.hierarchy.set_response(w)
        return a, c

    def finer_factor(self, f: np.ndarray) -> np.ndarray:
        # in the logarithm, as the line contact: the flow factor spans 1 to 1e24 under an
        # Eyring stress, and cubic interpolation of the factor itself overshoots below zero
        return np.exp(interpolate_cubic(np.ascontiguousarray(np.log(f)), True))

def require_flooded_point(scene: Scene) -> None:
    """Refuse a point contact with a finite ``[supply] hoil`` (InputError naming it): the thermal
    point solve has a flooded inlet only, and a starved contact must not get a flooded film."""
    hoil = scene.supply.hoil
    if math.isfinite(hoil) or scene.supply.hoil_profile:
        raise InputError(f"[supply] hoil = {hoil:g} m: the thermal EHL point-contact solve models flooded "
                         f"inlets only (allowed: hoil = inf, no hoil_profile); the starved point contact "
                         f"is solved isothermally by 'ehl solve' without --thermal, and thermal starved "
                         f"solves are available for line contacts")


def solve_tehl_point(scene: Scene, slip: float | None = None, options: TEHLOptions | None = None, *,
                     threads: int | None = None, coarse: TEHLPointResult | None = None,
                     **changes: Any) -> TEHLPointResult:
    """Solve the thermal EHL point contact of ``scene`` at ``slip``.

    ``options`` as for :func:`~thermal.tehl.line.solve_tehl_line` (``points`` along X, default
    257 here when not given; ``multigrid`` overrides the core :class:`PointOptions`); the
    half domain Y >= 0 is solved. ``threads``: thread pool of the row thermal solves.
    ``coarse``: the solution of the same contact on the grid with half the intervals (same box
    and nz): its across-film factors, interpolated, start the outer iteration after one
    multilevel solve with them (nested iteration; the fixed point is the same within the outer
    tolerances, in fewer iterations: appendix D at S = 1 on 513 points 15 -> 11). A finite
    ``[supply] hoil`` is refused (:func:`require_flooded_point`).
    """
    t0 = time.perf_counter()
    if scene.kind == "line":
        raise InputError(f"scene {scene.name!r} is a line contact: use solve_tehl_line")
    require_flooded_point(scene)
    if options is None and "points" not in changes:
        changes["points"] = 257
    opts = (options or TEHLOptions()).with_changes(**changes) if changes else options
    if coarse is not None and 2 * coarse.X.size - 1 != opts.points:
        raise InputError(f"coarse has {coarse.X.size} points along X; the options ask for {opts.points}, so it "
                         f"needs {(opts.points - 1) // 2 + 1}")
    slip = scene.slip if slip is None else float(slip)
    env = surroundings(scene, slip)
    pb = problem_from_scene(scene)
    mg = dict(opts.multigrid)
    if opts.box != 1.0:
        box = resolve_domain(pb, mg.get("xmin"), mg.get("xmax"), mg.get("ymax"))
        mg.update(xmin=opts.box * box[0], xmax=opts.box * box[1], ymax=opts.box * box[2])
    if mg.get("far_field"):
        raise InputError("far_field = True: the thermal point solver holds P = 0 on its boundary")
    # P = 0 on the boundary, as the thermal hierarchy (far_field_ok): the isothermal start
    # and reference films on the same problem
    popts = PointOptions.build(None, **{"points": opts.points, "half": True, "raise_on_failure": False,
                                        **mg, "far_field": False})
    with preserved_threads():
        iso = solve_fas(pb, popts, scene=scene)
    if not iso.success:
        raise ConvergenceError(f"TEHL point: the isothermal start did not converge: {iso.message}", iso.report, HINT)
    # the outer iteration's solves stop on the films (see TEHLOptions.multigrid); the
    # isothermal start keeps the core's residual rule
    popts_outer = PointOptions.build(popts, film_tol=mg.get("film_tol", 0.25 * opts.tol_H))
    contact = PointContact(scene, pb, opts, popts_outer, env, iso.X, iso.Y, threads)
    Hc_iso, Hm_iso = contact.films(iso.P, iso.H)
    st = Iterate(iso.P.copy(), iso.H.copy(), float(iso.H0), Hc_iso, Hm_iso)
    th, T = contact.thermal(st)
    decoupled = th.friction()
    shape = iso.P.shape
    if coarse is not None and (2 * coarse.a.shape[0] - 1, 2 * coarse.a.shape[1] - 1) != shape:
        raise InputError(f"coarse has the grid {coarse.a.shape[::-1]} (X, Y); the options ask for "
                         f"{shape[::-1]}, so it needs half the intervals of each")
    done = coupled_solve(contact, st, th, T, np.ones(shape), np.ones(shape), opts, coarse)
    th = done.thermal
    F = th.friction()
    heat = th.heat(scene.lubricant)
    return TEHLPointResult(
        scene=scene, slip=slip, problem=pb, X=iso.X, Y=iso.Y, P=done.state.P, H=done.state.H, Hc=done.state.Hc,
        Hm=done.state.Hm, Hc_isothermal=Hc_iso, Hm_isothermal=Hm_iso, T_mid=th.T[:, :, (opts.nz + 1) // 2],
        T_surface1=th.T[:, :, 0], T_surface2=th.T[:, :, -1], friction=F, friction_coefficient=F / scene.load,
        friction_decoupled=decoupled, T_max=float(np.max(th.T)), T_peak=th.T.max(axis=2), heat=heat, heat_partition=heat_partition(heat),
        heat_balance_error=float(abs(heat["balance"])), a=done.a, c=done.c, outer=done.outer,
        report=done.report, wall_s=time.perf_counter() - t0, extra={"thermal_rows": len(th.rows)}, options=opts,
    )
