"""Thermal elastohydrodynamic line contact (TEHL): pressure, film and temperature solved
together, with the Eyring law acting on the flow.

The outer iteration (a fixed point in the across-film fields):

1. the isothermal Newtonian solve of the core (:func:`ehl_multigrid.line.solve_line_problem`)
   gives ``P_0``, ``H_0`` (and ``Hc_isothermal``);
2. the thermal layer (:func:`thermal.line.solve_thermal_line`: Eyring law (3.3), momentum
   (3.4) with the stress slope ``h dp/dx`` of the current pressure, energy (3.5) across and
   along the film, moving-heat-source surface temperatures (3.6)-(3.7)) gives ``T(x, z)`` and
   ``tau(x, z)`` on the current ``P``, ``H`` (the first solve, on the isothermal film, keeps
   that film's Poiseuille flux instead: see :meth:`LineContact.thermal_layer`);
3. the generalised Reynolds factors ``a``, ``c`` (:mod:`thermal.tehl.coefficients`) of that
   field are under-relaxed (in their logarithm, Anderson-mixed) and handed to the multilevel
   solve of the :class:`~thermal.tehl.hierarchy.FactorLineHierarchy` on the shared driver,
   started from the previous ``P``, which gives the next ``P``, ``H``;
4. steps 2-3 repeat (:func:`thermal.tehl.outer.coupled_solve`, the geometry as
   :class:`LineContact`) until the changes of P (relative L2), of the films (Hc, Hm,
   relative) and of the temperature (max, kelvin) between outer iterations are all below
   their tolerances. The temperature and friction returned belong to the final P.

The thermal stations are the EHL grid's nodes (the whole box, inlet back flow included) and
the thermal grid has ``nz`` intervals across the film. Friction, temperature and the heat
budget come from that one thermal solution.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.line.solution import finish_line_result
from ehl_multigrid.line.solver import HINT, LINE_POLICY, line_settings, solve_line_problem
from ehl_multigrid.model.errors import ConvergenceError, InputError
from ehl_multigrid.model.scene import Scene
from ehl_multigrid.multigrid.driver import MultilevelSolver
from ehl_multigrid.multigrid.options import LineOptions
from ehl_multigrid.multigrid.policy import RobustnessPolicy
from ehl_multigrid.multigrid.transfer import interpolate_cubic

from ..line import Surroundings, ThermalLineSolution, solve_thermal_line
from ..profiles import profile_from_arrays
from ..traction import wall_speeds
from .coefficients import film_factors
from .hierarchy import FactorLineHierarchy
from .options import TEHLOptions
from .outer import OUTER_HINT, Iterate, coupled_solve, surroundings
from .results import TEHLResult
from .starved import find_meniscus, flux_summary, tehl_face_fluxes

#: supply tolerance of the meniscus search, relative to ``tol_H``: a tenth, so that the
#: mismatch stays below the films' own iteration tolerance on every grid of an error estimate
SUPPLY_TOL = 0.1


@dataclass(kw_only=True)
class TEHLLineResult(TEHLResult):
    """A converged TEHL line solution (SI units unless stated; Venner's X, P, H), besides the
    :class:`~thermal.tehl.results.TEHLResult` fields.

    X, P, H : grid x/b, p/pmax, h R/b^2 of the TEHL solution; x [m], p [Pa], h [m];
    Z : z/h nodes; T : temperature (X, Z) [degC]; tau : shear stress (X, Z) [Pa];
    hc, hm [m]; friction [N] on the line length; heat : budget per unit length [W/m]
    (:func:`interior_heat_budget`; its ``whole_box_balance`` is the thermal layer's budget
    from the inlet station on); heat_balance_error : |shear - conduction - convection| / shear
    (interior budget); flux_in : mass flux through the box's first face (Venner units:
    ``rho0 (u1 + u2)/2 b^2/R``) of the generalised Reynolds equation the solution satisfies
    (:func:`thermal.tehl.starved.tehl_face_fluxes`); flux_balance : the largest relative
    deviation from it over the faces up to the pressure maximum;
    starved : for a finite ``[supply] hoil`` (:func:`solve_tehl_line`), the starvation
        observables (meniscus, supply, flooded film, mass balance), else None.
    isothermal : the isothermal start the outer iteration began from (flooded inlets; it does
        not depend on the slip: :func:`continuation` hands it to a solve of another slip).
    """

    problem: LineProblem
    u1: float
    u2: float
    H0: float
    Z: np.ndarray
    T: np.ndarray
    tau: np.ndarray
    thermal: ThermalLineSolution = field(repr=False)
    flux_in: float = math.nan
    flux_balance: float = math.nan
    starved: dict[str, Any] | None = None
    isothermal: Iterate | None = field(default=None, repr=False)

    @property
    def x(self) -> np.ndarray:
        return self.X * self.problem.b

    @property
    def p(self) -> np.ndarray:
        return self.P * self.problem.pmax

    @property
    def h(self) -> np.ndarray:
        return self.H * self.problem.b ** 2 / self.problem.R

    @property
    def film_reduction(self) -> float:
        """Thermal reduction factor of the central film: ``Hc / Hc_isothermal``; for a starved
        film ``Hc / Hc_isothermal_starved``, the isothermal starved film at the same supply and
        grid (``Hc_isothermal`` is the isothermal film on the thermal solve's box, which ends at
        another meniscus: it carries another supply). NaN when that solve failed."""
        st = self.starved or {}
        if not st or st.get("inlet_flooded", True):
            return self.Hc / self.Hc_isothermal
        return self.Hc / st.get("Hc_isothermal_starved", math.nan)

    def _own_keys(self) -> dict[str, Any]:
        return {"momentum": self.report.extra.get("momentum", "gradient"),
                "compressive_heating": self.options.compressive_heating,
                **{k: v for k, v in (self.starved or {}).items() if not isinstance(v, (list, dict))}}


def _films(problem: LineProblem, X: np.ndarray, P: np.ndarray, H: np.ndarray) -> tuple[float, float]:
    """Moes (Hc, Hm) as the core defines them (Hc at X = 0; Hm over |X| <= 1.5 or P > 0)."""
    zone = (np.abs(X) <= 1.5) | (P > 0)
    return problem.moes_from_venner(float(np.interp(0.0, X, H))), problem.moes_from_venner(float(np.min(H[zone])))


def line_problem(scene: Scene, options: TEHLOptions) -> LineProblem:
    if scene.kind != "line":
        raise InputError(f"contact.kind = {scene.kind!r}: solve_tehl_line needs a line contact")
    pb = LineProblem.from_scene(scene, xmin=options.xmin, xmax=options.xmax)
    if options.box != 1.0:
        pb = replace(pb, xmin=pb.xmax - options.box * (pb.xmax - pb.xmin))
    return pb


def isothermal_start(scene: Scene, options: TEHLOptions) -> Iterate:
    """The core isothermal Newtonian solve on the TEHL grid."""
    pb = line_problem(scene, options)
    res = solve_line_problem(pb, options.line_options(), scene=scene)
    if not res.success:
        raise ConvergenceError(f"TEHL: the isothermal start did not converge: {res.message}", res.report, HINT)
    Hc, Hm = _films(pb, res.X, res.P, res.H)
    return Iterate(res.P.copy(), res.H.copy(), float(res.H0), Hc, Hm)


#: statuses of an outer iteration's V-cycle multilevel solve that are tried again with W cycles
W_RETRY_STATUSES = ("diverged", "stalled")


class LineContact:
    """The line contact of a coupled TEHL solve (:class:`~thermal.tehl.outer.Contact`): the
    factor hierarchy on the box of ``pb`` and one thermal layer on the EHL grid's nodes."""

    label, alternation, hint = "TEHL", " between cycles", HINT

    def __init__(self, scene: Scene, pb: LineProblem, opts: TEHLOptions, env: Surroundings) -> None:
        self.scene, self.pb, self.opts, self.env = scene, pb, opts, env
        self.options = opts.line_options()
        self.topt = opts.thermal_options()
        self.hierarchy = FactorLineHierarchy(pb, self.options)
        self.X = self.hierarchy.levels[-1].X
        self.notes: list[str] = []
        #: momentum mode of each thermal solve of the iteration ("gradient" or "flux")
        self.modes: list[str] = []
        self.last: ThermalLineSolution | None = None  # the previous outer iteration's thermal solution
        self.w_retries, self.w_note = 0, 0  # multilevel solves tried again with W cycles, and their note

    def multilevel(self) -> tuple[Any, np.ndarray, np.ndarray, float]:
        res = self._cycles(self.options)
        if not res.success and res.status_name in W_RETRY_STATUSES and self.options.cycle != "W":
            # V cycles that diverge slowly from a converged start (the spur gear at S = 0.5 on
            # 4097 points: residual 5e-7 -> 8e-6, then rejected), where W cycles converge
            first = res.message.splitlines()[0]
            res = self._cycles(replace(self.options, cycle="W"))
            self.w_retries += 1
            note = (f"a multilevel solve {first[:100]}; solved again from the same start with W "
                    f"cycles: {res.status_name}" + (f" ({self.w_retries} such solves)" if self.w_retries > 1 else ""))
            if self.w_retries == 1:
                self.w_note = len(self.notes)
                self.notes.append(note)
            else:
                self.notes[self.w_note] = note
        return res, res.P.copy(), res.H.copy(), float(res.H0)

    def friction(self, thermal: ThermalLineSolution) -> float:
        return float(thermal.force_per_length)

    def _cycles(self, lopts: LineOptions) -> Any:
        hz = self.hierarchy
        solver = MultilevelSolver(hz, lopts, line_settings(self.pb, lopts), RobustnessPolicy(LINE_POLICY, lopts.adapt),
                                  HINT)
        hz.solver = solver
        res = finish_line_result(solver.solve(), solver, self.scene)
        hz.solver = None
        return res

    def films(self, P: np.ndarray, H: np.ndarray) -> tuple[float, float]:
        return _films(self.pb, self.X, P, H)

    def factors(self, th: ThermalLineSolution) -> tuple[np.ndarray, np.ndarray]:
        # a line contact's flow factor stays frozen within a solve: with the viscosity response the
        # sliding line contacts of the slow tier stalled at outer iteration 1 (docs/thermal.md)
        e = self.env
        return film_factors(th.profile.p, th.T, th.tau, e.lubricant, e.T_oil, e.u1, e.u2, self.opts.shear_thinning)

    def finer_factor(self, f: np.ndarray) -> np.ndarray:
        return np.exp(interpolate_cubic(np.log(f)))

    def thermal(self, st: Iterate) -> tuple[ThermalLineSolution, np.ndarray]:
        """The thermal layer on ``st`` in the outer iteration: from the previous one's
        temperatures (``warm_thermal``), with the flux of the generalised Reynolds solve when
        the stress slope runs away."""
        start = self.last if self.opts.warm_thermal else None
        try:
            th = self.thermal_layer(st, start=start)
            self.modes.append("gradient")
        except ConvergenceError as exc:
            # the fixed gradient ran away (NaN): the flux of the generalised Reynolds solve
            th = self.thermal_layer(st, flux_factor=self.hierarchy.levels[-1].a, start=start)
            self.modes.append("flux")
            if len(self.modes) == 1 or self.modes[-2] != "flux":
                self.notes.append(f"thermal solve {len(self.modes)}: the stress slope h dp/dx ran away "
                                  f"({str(exc).splitlines()[0][:80]}); the slope keeps the solve's Poiseuille flux")
        self.last = th
        return th, th.T

    def thermal_layer(self, st: Iterate, flux_factor: np.ndarray | None = None,
                      start: ThermalLineSolution | None = None) -> ThermalLineSolution:
        """The thermal layer on the current P, H (its sweeps from ``start`` when given).

        Default: stress slope ``h dp/dx`` of the current pressure (momentum (3.4)). With
        ``flux_factor`` (the flow factor ``a`` of the generalised Reynolds solve that gave P,
        ones for the isothermal film) the slope instead carries the pressure-driven flux
        ``-h^3 a/(12 eta(p, T_oil)) dp/dx`` of that solve (the thermal layer's ``flux`` mode,
        as for its EHL input). The first solve on the isothermal film uses it: its steep outlet
        gradient would drive an Eyring Poiseuille flow that its own heat thins further, the
        runaway the thermal layer documents for a fixed gradient (measured here: NaN
        temperatures at thermal loading 0.38 with slip).
        """
        scene, pb, X = self.scene, self.pb, self.X
        visc = None
        if flux_factor is not None:
            lub, T0 = scene.lubricant, scene.T_oil
            fac = np.asarray(flux_factor, dtype=float)

            def visc(p: np.ndarray) -> np.ndarray:
                # called on the EHL nodes (x = X b): the effective viscosity of the flow factor
                return np.asarray(lub.viscosity(p, T0), dtype=float) / fac
        prof = profile_from_arrays(X * pb.b, st.P * pb.pmax, st.H * pb.b ** 2 / pb.R, b=pb.b, nx=X.size,
                                   width=scene.length, x_in=None, x_out=None, source="tehl", viscosity=visc)
        topt = self.topt.with_changes(momentum="flux") if flux_factor is not None else self.topt
        sol = solve_thermal_line(prof, self.env, topt, kernel_length=scene.length, start=start)
        if not sol.report.converged:
            raise ConvergenceError(f"TEHL: the thermal solve did not converge: {sol.report.message}",
                                   sol.report, OUTER_HINT)
        return sol


def heat_partition(heat: dict[str, float]) -> tuple[float, float]:
    """(share into solid 1, share into solid 2) of the heat conducted in a budget ``heat``
    (NaN when nothing is conducted)."""
    cond = heat.get("conduction1", 0.0) + heat.get("conduction2", 0.0)
    return (float(heat["conduction1"] / cond), float(heat["conduction2"] / cond)) if cond > 0 else (math.nan, math.nan)


def interior_heat_budget(sol: ThermalLineSolution, lubricant: Any) -> dict[str, float]:
    """Heat budget per unit length [W/m] over the stations downstream of the inlet station.

    The thermal layer holds the oil at the inlet temperature on the first station; where the
    thick inlet has reverse flow, the warm back flow meets that station in a one-cell boundary
    layer, and a whole-box budget (:func:`thermal.line.heat_budget`) counts the heat it carries
    out through the inlet as a residual. This budget starts at the second station, with the
    same independent quadratures (trapezoid in Z and x, second-order differences of T in x):
    ``balance = (shear + compression - conduction1 - conduction2 - convection) / shear``
    (compression: the work of compression when the solve carried it, else 0).
    """
    from ..line import heat_budget
    from ..profiles import LineProfile

    prof = sol.profile
    k = slice(1, None)
    sub = LineProfile(prof.X[k], prof.b, prof.p[k], prof.h[k], prof.width, prof.source,
                      gradient=None if prof.gradient is None else prof.gradient[k])
    return heat_budget(sub, sol.T[k], sol.u[k], sol.heat_rate[k], sol.q1[k], sol.q2[k], lubricant,
                       compression=sol.compressive_heating)


def solve_tehl_line(scene: Scene, slip: float | None = None, options: TEHLOptions | None = None, *,
                    us: float | None = None, load: float | None = None, start: Iterate | None = None,
                    guess: TEHLLineResult | None = None, meniscus: float | None = None,
                    coarse: TEHLLineResult | None = None, **changes: Any) -> TEHLLineResult:
    """Solve the thermal EHL line contact of ``scene`` at ``slip`` (S = 2 (u1 - u2)/(u1 + u2)).

    A scene with a finite ``[supply] hoil`` is solved starved (:func:`solve_tehl_line_starved`:
    the inlet meniscus that makes the contact carry the supplied layer), else with a flooded
    inlet.

    Parameters
    ----------
    scene : a line-contact scene (oil, solids, temperatures, operating point, supply).
    slip : slide-to-roll ratio in [-2, 2] (None: the scene's).
    options : :class:`TEHLOptions`; keyword ``changes`` update it.
    us, load : sum velocity [m/s] and load [N] replacing the scene's.
    start : the isothermal start of an earlier solve of the same scene, grid and box
        (:func:`isothermal_start`; it does not depend on the slip); flooded inlets only.
    guess : a TEHL solution of the same scene, grid and box (another slip) to start the
        outer iteration from (pressure, film constant and across-film factors); flooded
        inlets only.
    coarse : a TEHL solution of the same scene, slip and box on half the intervals: its
        across-film factors, interpolated, start the outer iteration after one multilevel
        solve with them (nested iteration; flooded inlets, without ``guess``).
    meniscus : starved inlets: the meniscus X = x/b the search starts from (None: the
        isothermal starved solver's on the same grid).

    Raises :class:`InputError` for a slip outside [-2, 2] or bad options, and
    :class:`ConvergenceError` when a multilevel or thermal solve fails, the fields become
    non-finite, the outer iteration does not meet its tolerances in ``max_outer``, or (starved)
    no meniscus carries the supply.
    """
    opts = (options or TEHLOptions()).with_changes(**changes) if changes else (options or TEHLOptions())
    if us is not None or load is not None:
        scene = scene.with_operating(**{k: v for k, v in (("us", us), ("load", load)) if v is not None})
    if scene.kind != "line":
        raise InputError(f"contact.kind = {scene.kind!r}: solve_tehl_line needs a line contact")
    slip = scene.slip if slip is None else float(slip)
    wall_speeds(scene.us, slip)  # the slip's range, before any solve
    if math.isfinite(scene.supply.hoil):
        if start is not None or guess is not None or coarse is not None:
            raise InputError("start, guess and coarse apply to flooded inlets: a starved solve (finite "
                             "[supply] hoil) searches its own meniscus, and each box has its own start")
        return solve_tehl_line_starved(scene, slip, opts, meniscus=meniscus)
    if guess is not None and coarse is not None:
        raise InputError("give guess (a solution on the same grid) or coarse (one on half the intervals), "
                         "not both: each sets the factors the outer iteration starts from")
    return _solve_flooded(scene, slip, opts, start, guess, coarse)


def _solve_flooded(scene: Scene, slip: float, opts: TEHLOptions, start: Iterate | None = None,
                   guess: TEHLLineResult | None = None,
                   coarse: TEHLLineResult | None = None) -> TEHLLineResult:
    """The TEHL solve with a flooded inlet on the box of ``opts`` (see :func:`solve_tehl_line`)."""
    if coarse is not None and 2 * coarse.a.size - 1 != opts.points:
        raise InputError(f"coarse has {coarse.a.size} points; the options ask for {opts.points}, so it needs "
                         f"{(opts.points - 1) // 2 + 1}")
    t0 = time.perf_counter()
    env = surroundings(scene, slip)
    pb = line_problem(scene, opts)
    iso = isothermal_start(scene, opts) if start is None else start
    contact = LineContact(scene, pb, opts, env)
    X = contact.X
    if iso.P.shape != X.shape:
        raise InputError(f"start has {iso.P.size} points; the options ask for {X.size}")
    st = iso
    sol = decoupled = contact.thermal_layer(st, flux_factor=np.ones(X.size))
    a = np.ones(X.size)
    c = np.ones(X.size)
    if guess is not None:
        # warm start from a neighbouring solution (e.g. the previous slip of a curve)
        if guess.P.shape != X.shape:
            raise InputError(f"guess has {guess.P.size} points; the options ask for {X.size}")
        st = Iterate(guess.P.copy(), guess.H.copy(), guess.H0, guess.Hc, guess.Hm)
        sol = contact.thermal_layer(st)
        a, c = guess.a.copy(), guess.c.copy()
    # the first outer iteration's thermal solve starts from this one's temperatures, as the
    # point contact's rows start from their first solves
    contact.last = sol
    done = coupled_solve(contact, st, sol, sol.T, a, c, opts, coarse)
    st, sol, a, c = done.state, done.thermal, done.a, done.c
    done.report.extra["momentum"] = contact.modes[-1] if contact.modes else "gradient"
    heat = interior_heat_budget(sol, scene.lubricant) if opts.thermal else {}
    if heat:
        heat["whole_box_balance"] = sol.heat["balance"]
        heat["inlet_boundary_loss"] = sol.heat["balance"] * sol.heat["shear"]
    F = sol.force_per_length * scene.length
    # the mass flux of the generalised Reynolds equation of the final P, H and factors
    contact.hierarchy.set_factors(a, c)
    flux_in, flux_balance = flux_summary(tehl_face_fluxes(contact.hierarchy.levels[-1], st.P, st.H0), st.P)
    return TEHLLineResult(
        scene=scene, slip=slip, u1=env.u1, u2=env.u2, problem=pb, X=X.copy(), P=st.P, H=st.H, H0=st.H0,
        Z=sol.Z, T=sol.T, tau=sol.tau, Hc=st.Hc, Hm=st.Hm, Hc_isothermal=iso.Hc, Hm_isothermal=iso.Hm,
        friction=F, friction_coefficient=F / scene.load,
        friction_decoupled=decoupled.force_per_length * scene.length, T_max=float(np.max(sol.T)),
        heat=heat, heat_partition=heat_partition(heat), heat_balance_error=abs(heat.get("balance", 0.0)),
        a=a, c=c, outer=done.outer, report=done.report, options=opts, thermal=sol,
        wall_s=time.perf_counter() - t0, flux_in=flux_in, flux_balance=flux_balance, isothermal=iso,
    )


def solve_tehl_line_starved(scene: Scene, slip: float | None = None, options: TEHLOptions | None = None, *,
                            hoil: float | None = None, meniscus: float | None = None) -> TEHLLineResult:
    """The TEHL line contact supplied with an oil layer ``hoil`` [m] (default the scene's
    ``[supply] hoil``): the inlet meniscus found so that the mass flux through the contact
    equals the supply (:mod:`thermal.tehl.starved`).

    Solves the flooded TEHL contact on the box of ``options`` first (the reference of
    ``Hc_ratio``; a supply at or above its flux floods the inlet and that solution is
    returned), then the flooded-inlet TEHL solve on ``[X_m, xmax]`` for each meniscus ``X_m``
    the search tries, from ``meniscus`` (default: the isothermal starved solver's meniscus
    on the same grid, :func:`ehl_multigrid.starved.solve_starved_line`), until
    ``|F/Hoil - 1|`` is below ``SUPPLY_TOL * tol_H``.

    Returns the TEHL solution on the box from the meniscus; ``starved`` holds ``hoil`` [m],
    ``hoil_venner``, ``meniscus_x``, ``supply_mismatch`` (``|F/Hoil - 1|``),
    ``mass_balance_error`` (the larger of it and the flux imbalance of the solution),
    ``flux_flooded``, ``Hc_flooded``, ``Hm_flooded`` (the flooded thermal films, Moes),
    ``Hc_ratio``, ``Hm_ratio`` (these five NaN, with ``flooded_failure`` saying why, when the
    flooded solve fails: the search then runs all the same), ``inlet_flooded``,
    ``meniscus_solves`` (TEHL solves made), ``meniscus_history`` (each box solve: meniscus,
    flux, status) and, when the isothermal starved solve at the same supply and grid converged
    (its meniscus seeds the search), ``meniscus_x_isothermal``,
    ``Hc_isothermal_starved``, ``Hm_isothermal_starved`` and ``hc_isothermal_starved`` [m]
    (its films at the same supply and grid). ``scene`` of the result is the starved scene,
    ``options`` the options asked for (the box, from the meniscus, is ``problem``/``X``).
    """
    from ehl_multigrid.starved import hoil_venner, solve_starved_line

    t0 = time.perf_counter()
    opts = options or TEHLOptions()
    slip = scene.slip if slip is None else float(slip)
    wall_speeds(scene.us, slip)
    hoil_m = scene.supply.hoil if hoil is None else float(hoil)
    flooded_scene = scene.with_supply(hoil=math.inf)
    pb = line_problem(flooded_scene, opts)
    Hoil = hoil_venner(hoil_m, pb.b, pb.R)
    if math.isinf(Hoil):
        return _solve_flooded(flooded_scene, slip, opts)
    try:
        full: TEHLLineResult | None = _solve_flooded(flooded_scene, slip, opts)
    except ConvergenceError as exc:
        # the flooded reference fails (a thick inlet on a coarse grid): the starved film does
        # not need it, only its ratio does
        full, flooded_failure = None, str(exc).splitlines()[0][:200]
    info: dict[str, Any] = {"hoil": hoil_m, "hoil_venner": Hoil,
                            "flux_flooded": full.flux_in if full else math.nan,
                            "Hc_flooded": full.Hc if full else math.nan, "Hm_flooded": full.Hm if full else math.nan}
    if full is None:
        info["flooded_failure"] = flooded_failure
    elif Hoil >= full.flux_in:
        # the layer carries at least what the flooded contact takes: the excess flows back
        info.update(inlet_flooded=True, meniscus_x=-math.inf, supply_mismatch=0.0,
                    mass_balance_error=full.flux_balance, Hc_ratio=1.0, Hm_ratio=1.0, meniscus_solves=1,
                    meniscus_history=[])
        full.scene, full.starved = scene, info
        full.wall_s = time.perf_counter() - t0
        return full
    # the isothermal starved films at the same supply and grid: the thermal reduction of a
    # starved film is at equal supply (film_reduction), and their meniscus seeds the search
    try:
        iso = solve_starved_line(pb, Hoil, None, None, estimate=False, points=opts.points,
                                 raise_on_failure=False)
    except ConvergenceError:
        iso = None
    seed = meniscus
    if iso is not None and iso.success and math.isfinite(iso.scalars.get("meniscus_x", math.nan)):
        info.update(meniscus_x_isothermal=float(iso.scalars["meniscus_x"]),
                    Hc_isothermal_starved=float(iso.scalars["Hc"]), Hm_isothermal_starved=float(iso.scalars["Hm"]),
                    hc_isothermal_starved=float(iso.scalars["Hc_venner"]) * pb.b**2 / pb.R)
        seed = info["meniscus_x_isothermal"] if seed is None else seed
    elif seed is None:
        # no isothermal seed: the search starts at a meniscus a fifth of the contact
        # half-width upstream and brackets outwards
        seed = -1.2

    def solve_box(xm: float) -> TEHLLineResult:
        return _solve_flooded(flooded_scene, slip, opts.with_changes(xmin=min(xm, -1.0 - 1e-9), box=1.0))

    found = find_meniscus(solve_box, lambda r: r.flux_in, Hoil, seed, SUPPLY_TOL * opts.tol_H)
    r = found.result
    info.update(inlet_flooded=False, meniscus_x=found.x, supply_mismatch=found.mismatch,
                mass_balance_error=max(found.mismatch, r.flux_balance), Hc_ratio=r.Hc / info["Hc_flooded"],
                Hm_ratio=r.Hm / info["Hm_flooded"], meniscus_solves=1 + len(found.history),
                meniscus_history=found.history)
    # the options as asked for (the box solve's own carry the meniscus as xmin): solves for an
    # error estimate or a refinement start from them
    r.scene, r.starved, r.options = scene, info, opts
    r.wall_s = time.perf_counter() - t0
    return r


def continuation(previous: TEHLLineResult | None, scene: Scene) -> dict[str, Any]:
    """The keywords of :func:`solve_tehl_line` that continue ``previous``, a solve of the same
    ``scene`` at another slip on the same grid and box (a traction curve's previous slip):
    flooded -- its isothermal start (it does not depend on the slip) and its solution, where
    the outer iteration starts; starved -- its meniscus, where the search starts. None: no
    keywords (a solve of its own)."""
    if previous is None:
        return {}
    if math.isfinite(scene.supply.hoil):
        xm = (previous.starved or {}).get("meniscus_x")
        return {"meniscus": xm} if xm is not None and math.isfinite(xm) else {}
    if previous.grid_films is not None:
        # extrapolated films (corrected_result): the outer iteration continues from the grid's own
        previous = replace(previous, Hc=previous.grid_films[0], Hm=previous.grid_films[1])
    return {"start": previous.isothermal, "guess": previous}


def tehl_traction_curve(scene: Scene, slips: Any = None, options: TEHLOptions | None = None,
                        **changes: Any) -> list[TEHLLineResult]:
    """TEHL solves over ``slips`` (default: the scene's slip range, else 21 slips over [0, 1]),
    each slip continuing from the previous one (:func:`continuation`): a flooded inlet solves
    the isothermal start once and starts each outer iteration from the previous slip's
    solution; a starved one (finite ``[supply] hoil``) starts each meniscus search from the
    previous slip's meniscus. ``ehl tehl --slip a,b,c`` solves the same sequence through the
    front door (``options={"start": ...}``).
    """
    from ..traction import default_slips

    opts = (options or TEHLOptions()).with_changes(**changes) if changes else (options or TEHLOptions())
    S = default_slips(scene) if slips is None else np.asarray(slips, dtype=float)
    if S.size == 0:
        raise InputError("slip list is empty")
    out: list[TEHLLineResult] = []
    for s in S:
        out.append(solve_tehl_line(scene, float(s), opts, **continuation(out[-1] if out else None, scene)))
    return out
