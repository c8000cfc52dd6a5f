"""Thermal EHL point contact: the line contact's outer iteration (:mod:`thermal.tehl.outer`)
on the shared point hierarchy, with the thermal layer solved on each grid row along the
rolling direction (the thesis's slicing of a point contact, 3.2.2.2 and (3.20), here on the
EHL solution's own rows).

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
from ehl_multigrid.point.numerics import interpolate_cubic
from ehl_multigrid.point.postprocess import film_metrics, full_fields
from ehl_multigrid.point.problem import PointProblem, problem_from_scene, resolve_domain
from ehl_multigrid.point.solve import solve_fas

from ..line import Surroundings, ThermalLineSolution
from ..parallel import LineJob, solve_thermal_lines
from ..profiles import profile_from_arrays
from ..traction import wall_speeds
from .coefficients import film_factors
from .line import TEHLOptions, grid_film_keys, interior_heat_budget
from .outer import Iterate, outer_iteration


class FactorPointHierarchy(PointHierarchy):
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
        self._start: tuple[np.ndarray, float] | None = None

    def set_factors(self, a: np.ndarray, c: np.ndarray) -> None:
        top = len(self.levels) - 1
        if a.shape != self.levels[top].shape or c.shape != a.shape:
            raise ValueError(f"factors must have the finest grid's shape {self.levels[top].shape}")
        for k, lev in enumerate(self.levels):
            step = 2 ** (top - k)
            lev.a = np.ascontiguousarray(a[::step, ::step])
            lev.c = np.ascontiguousarray(c[::step, ::step])

    def set_iterate(self, P: np.ndarray, H00: float) -> None:
        self._start = (np.asarray(P, dtype=float).copy(), float(H00))

    def _apply(self, lev: Any) -> None:
        a = getattr(lev, "a", None)
        if a is not None:
            lev.rho *= lev.c
            lev.eps *= a

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
        if self._start is None:
            raise ValueError("set_iterate() before a solve: the hierarchy starts from a given iterate")
        self.solver = solver
        self.gain = solver.settings.h00_gain
        self._last_err = None
        top = len(self.levels) - 1
        lev = self.levels[top]
        lev.P = np.ascontiguousarray(self._start[0])
        self.H00 = self._start[1]
        self.h00_step_max = 0.1 * nijenbanning_central(self.pb.M, self.pb.L, self.theta) / self.pb.moes_factor
        lev.f = np.zeros_like(lev.P)
        lev.g = self.g_target
        self.update_film(lev)
        return top


@dataclass
class TEHLPointResult:
    """A converged TEHL point solution (half domain Y >= 0, rows ``[j, i]``).

    X, Y, P, H : grid (x/a, y/a) and Venner's fields; Hc, Hm : Moes central (X = Y = 0) and
    minimum films, with their isothermal values; T_mid, T_surface1, T_surface2 : mid-film and
    surface temperature maps [degC] (rows without pressure hold the oil temperature);
    friction [N], friction_coefficient, friction_decoupled [N]; T_max [degC]; heat budget [W]
    summed over the rows (interior budgets), heat_partition, heat_balance_error; outer history;
    options : the :class:`TEHLOptions` of the solve.
    """

    scene: Scene
    slip: float
    problem: PointProblem
    X: np.ndarray
    Y: np.ndarray
    P: np.ndarray
    H: np.ndarray
    Hc: float
    Hm: float
    Hc_isothermal: float
    Hm_isothermal: float
    T_mid: np.ndarray
    T_surface1: np.ndarray
    T_surface2: np.ndarray
    friction: float
    friction_coefficient: float
    friction_decoupled: float
    T_max: float
    heat: dict[str, float]
    heat_partition: tuple[float, float]
    heat_balance_error: float
    a: np.ndarray
    c: np.ndarray
    outer: list[dict[str, float]]
    report: Any
    wall_s: float = math.nan
    extra: dict[str, Any] = field(default_factory=dict)
    options: TEHLOptions | None = None
    #: (Hc, Hm) of the grid when the reported films are extrapolated over the grids
    #: (:func:`thermal.tehl.accuracy.corrected_result`), else None
    grid_films: tuple[float, float] | None = None

    def summary(self) -> dict[str, Any]:
        return {"Hc": self.Hc, "Hm": self.Hm, "Hc_isothermal": self.Hc_isothermal,
                "Hm_isothermal": self.Hm_isothermal, "friction": self.friction,
                "friction_coefficient": self.friction_coefficient, "friction_decoupled": self.friction_decoupled,
                "T_max": self.T_max, "heat_partition": list(self.heat_partition),
                "heat_balance_error": self.heat_balance_error, "outer_iterations": len(self.outer),
                "converged": bool(self.report.converged), "slip": self.slip, "wall_s": self.wall_s,
                **grid_film_keys(self.grid_films)}


@dataclass
class _Rows:
    """Thermal solutions of the loaded rows and their Y weights (both halves)."""

    rows: list[int]
    sols: list[ThermalLineSolution]
    widths: np.ndarray
    T: np.ndarray  # (row, X, Z) stacked for the change measure


def _films(pb: PointProblem, X: np.ndarray, Y: np.ndarray, P: np.ndarray, H: np.ndarray) -> tuple[float, float]:
    Yf, Pf, Hf = full_fields(X, Y, P, H, True)
    m = film_metrics(X, Yf, Pf, Hf)
    return m["Hc_center"] * pb.moes_factor, m["Hm"] * pb.moes_factor


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
    u1, u2 = wall_speeds(scene.us, slip)
    env = Surroundings(scene.lubricant, scene.body1, scene.body2, u1, u2, scene.T_oil,
                       scene.T_surface1, scene.T_surface2)
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
    # the outer iteration's solves stop on the films (see TEHLOptions.multigrid); the
    # isothermal start keeps the core's residual rule
    popts_outer = PointOptions.build(popts, film_tol=mg.get("film_tol", 0.25 * opts.tol_H))
    notes: list[str] = []
    topt = opts.thermal_options()
    lub = scene.lubricant
    a_len = pb.a
    b_len = scene.hertz.b
    with preserved_threads():
        iso = solve_fas(pb, popts, scene=scene)
    if not iso.success:
        raise ConvergenceError(f"TEHL point: the isothermal start did not converge: {iso.message}", iso.report, HINT)
    X, Y = iso.X, iso.Y
    Hc_iso, Hm_iso = _films(pb, X, Y, iso.P, iso.H)
    hy = float(Y[1] - Y[0])
    hz = FactorPointHierarchy(pb, popts_outer)
    shape = iso.P.shape
    nzp = opts.nz + 1
    klen = 2.0 * b_len

    last: dict[int, Any] = {}  # each row's thermal solution of the previous outer iteration

    def thermal(st: Iterate) -> tuple[_Rows, np.ndarray]:
        rows = [j for j in range(shape[0]) if np.max(st.P[j]) > 0.0]
        jobs = []
        widths = []
        for j in range(len(rows)):
            jj = rows[j]
            w = hy * a_len * (1.0 if jj == 0 else 2.0)
            prof = profile_from_arrays(X * a_len, st.P[jj] * pb.pmax, st.H[jj] * a_len**2 / pb.Rx, b=a_len,
                                       nx=X.size, width=w, x_in=None, x_out=None, Y=float(Y[jj]) * a_len / b_len,
                                       contact_half=math.sqrt(max(1.0 - (Y[jj] * a_len / b_len) ** 2, 0.0)),
                                       source="tehl")
            jobs.append(LineJob(prof, env, topt, klen, last.get(jj) if opts.warm_thermal else None))
            widths.append(w)
        sols = list(solve_thermal_lines(jobs, threads=threads))
        T = np.full((shape[0], X.size, nzp), float(scene.T_oil))
        for jj, s in zip(rows, sols, strict=True):
            T[jj] = s.T
        last.clear()
        last.update(zip(rows, sols, strict=True))
        return _Rows(rows, sols, np.array(widths), T), T

    def factors(th: _Rows) -> tuple[np.ndarray, np.ndarray]:
        a = np.ones(shape)
        c = np.ones(shape)
        for jj, s in zip(th.rows, th.sols, strict=True):
            a[jj], c[jj] = film_factors(s.profile.p, s.T, s.tau, lub, scene.T_oil, u1, u2, opts.shear_thinning)
        return a, c

    def ehl(a: np.ndarray, c: np.ndarray, st: Iterate, it: int) -> Iterate:
        hz.set_factors(a, c)
        hz.set_iterate(st.P, st.H0)
        with preserved_threads():
            solver = MultilevelSolver(hz, popts_outer, point_settings(pb, popts_outer),
                                      RobustnessPolicy(POINT_POLICY, popts_outer.adapt), HINT)
            hz.solver = solver
            res = solver.solve()
            hz.solver = None
        top = len(hz.levels) - 1
        fin = [h for h in res.history if h.level == top][-2:]
        noise = (max(abs(fin[1].Hc - fin[0].Hc) / abs(fin[1].Hc), abs(fin[1].Hm - fin[0].Hm) / abs(fin[1].Hm))
                 if len(fin) == 2 else math.inf)
        if not res.success and res.status == 1 and res.residual_history[-1] < popts_outer.tol and noise < 10.0 * opts.tol_H:
            # as for the line contact: films alternating at the residual tolerance are accepted,
            # their alternation carried as the films' uncertainty
            notes.append(f"outer iteration {it}: films alternate by {noise:.2g} at residual "
                         f"{res.residual_history[-1]:.3g}; accepted as their uncertainty")
        elif not res.success:
            raise ConvergenceError(f"TEHL point outer iteration {it}: the multilevel solve failed: {res.message}",
                                   res.report, HINT)
        fine = hz.levels[-1]
        P, H = fine.P.copy(), fine.H.copy()
        Hc, Hm = _films(pb, X, Y, P, H)
        return Iterate(P, H, float(hz.H00), Hc, Hm, {"cycles": int(res.cycles), "film_noise": min(noise, 1.0)})

    st = Iterate(iso.P.copy(), iso.H.copy(), float(iso.H0), Hc_iso, Hm_iso)
    th, T = thermal(st)
    decoupled = float(sum(s.force_per_length * w for s, w in zip(th.sols, th.widths, strict=True)))
    a0, c0 = np.ones(shape), np.ones(shape)
    if coarse is not None:
        if (2 * coarse.a.shape[0] - 1, 2 * coarse.a.shape[1] - 1) != shape:
            raise InputError(f"coarse has the grid {coarse.a.shape[::-1]} (X, Y); the options ask for "
                             f"{shape[::-1]}, so it needs half the intervals of each")
        # the coarse fixed point's factors with the film they give on this grid: a consistent
        # start (the interpolated coarse pressure itself is not: its spike is a grid off)
        a0, c0 = (interpolate_cubic(np.ascontiguousarray(f), True) for f in (coarse.a, coarse.c))
        st = ehl(a0, c0, st, 0)
        th, T = thermal(st)
        notes.append(f"outer iteration started from the factors of the solve on {coarse.X.size} points")
    done = outer_iteration(st, th, T, a0, c0, factors=factors, ehl=ehl,
                           solve_thermal=thermal, relax=opts.relax, anderson=opts.anderson,
                           max_outer=opts.max_outer, tol_P=opts.tol_P, tol_H=opts.tol_H, tol_T=opts.tol_T)
    st, th = done.state, done.thermal
    done.report.extra["actions"] = notes + list(done.report.extra.get("actions", []))
    F = float(sum(s.force_per_length * w for s, w in zip(th.sols, th.widths, strict=True)))
    keys = ("shear", "compression", "conduction1", "conduction2", "convection")
    heat = dict.fromkeys(keys, 0.0)
    for s, w in zip(th.sols, th.widths, strict=True):
        hb = interior_heat_budget(s, lub)
        for k in keys:
            heat[k] += hb[k] * w
    heat["balance"] = ((heat["shear"] + heat["compression"] - heat["conduction1"] - heat["conduction2"] - heat["convection"]) / heat["shear"]
                       if heat["shear"] > 0 else 0.0)
    cond = heat["conduction1"] + heat["conduction2"]
    part = (float(heat["conduction1"] / cond), float(heat["conduction2"] / cond)) if cond > 0 else (math.nan, math.nan)
    T_mid = th.T[:, :, nzp // 2]
    return TEHLPointResult(
        scene=scene, slip=slip, problem=pb, X=X, Y=Y, P=st.P, H=st.H, Hc=st.Hc, Hm=st.Hm, Hc_isothermal=Hc_iso,
        Hm_isothermal=Hm_iso, T_mid=T_mid, T_surface1=th.T[:, :, 0], T_surface2=th.T[:, :, -1], friction=F,
        friction_coefficient=F / scene.load, friction_decoupled=decoupled, T_max=float(np.max(th.T)), heat=heat,
        heat_partition=part, heat_balance_error=float(abs(heat["balance"])), a=done.a, c=done.c, outer=done.outer,
        report=done.report, wall_s=time.perf_counter() - t0, extra={"thermal_rows": len(th.rows)}, options=opts,
    )
