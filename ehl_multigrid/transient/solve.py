"""Time-dependent isothermal EHL line contact: surface features passing through the contact.

Each time step ``T_n = n dT`` (``T = t u_m / b``) solves the implicit (BDF2; the first step
backward Euler) discrete Reynolds, film and load equations at the new time level by FAS
cycles of the shared multilevel driver on :class:`TransientLineHierarchy`, starting from the
previous solution extrapolated in time (the time loop of :mod:`.stepping`, shared with the
point contact). The load is constant (``h sum P = pi/2`` every step,
``H0(T)`` free); the elastic deformation is recomputed in every relaxation of every step.

The start is the steady solution with the feature frozen at its ``T = 0`` position (the core
steady line solver, then the steady equations with the feature on the same grids), or a given
initial state.

Limits: cavitation is the projection ``P >= 0`` of the steady solver (not mass-conserving). A dent
much deeper than the film leaving the contact under heavy sliding re-pressurises oil behind the
cavitation boundary, and those nodes can flip between wet and cavitated from cycle to cycle (a
stalled step, :class:`ConvergenceError` above ``accept_stall``). A film that closes (a feature
higher than the film) is mixed lubrication, which this solver does not model.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from ..line.problem import LineProblem
from ..line.solver import HINT, LINE_POLICY, line_settings, solve_line_problem
from ..model.errors import InputError
from ..multigrid.options import LineOptions
from ..multigrid.result import EHLResult
from ..starved.line import STARVED_TOL, STARVED_TOL_LOAD, solve_starved_problem
from .cavitated import CavitatedStepHierarchy
from .checkpoint import Checkpoint
from .features import Feature, Smooth, default_end_time, feature_speed
from .hierarchy import TransientLineHierarchy
from .oil_balance import MASS_TOL
from .result import TransientResult
from .stepping import (
    Stepper,
    model_inputs,
    require_steady_start,
    start_and_march,
    time_steps,
)

#: Default numerics of a time step: FFT deformation (exact), a tighter residual than the
#: steady default so the algebraic error of a step stays below its time error.
TRANSIENT_DEFAULTS = {"points": 257, "deformation": "fft", "tol": 1e-6, "tol_load": 1e-8,
                      "max_cycles": 40, "raise_on_failure": False}


#: The projection's steps: a solve whose V cycles contract by less than 0.3 over 8 cycles
#: (slower than 0.84 a cycle) takes the stall ladder's first step, W cycles (long boxes at
#: short steps; docs/transient.md, "Limits")
PROJECTION_STEP_POLICY = dataclasses.replace(LINE_POLICY, stall_factor=0.3)


def transient_options(options: LineOptions | None = None, **kw: Any) -> LineOptions:
    """Line options for the time steps: :data:`TRANSIENT_DEFAULTS` below ``options`` and
    keywords. ``raise_on_failure`` is always False: a step's failure goes back to the time loop,
    which judges it (``accept_stall``) and ends the run with it."""
    base = LineOptions.build(None, **TRANSIENT_DEFAULTS) if options is None else options
    return LineOptions.build(base, **{**kw, "raise_on_failure": False})


def solve_transient_line(
    problem: LineProblem, feature: Feature | None, *, body: int = 1, slide_roll: float = 0.0,
    dt: float | None = None, steps: int | None = None, t_end: float | None = None,
    options: LineOptions | None = None, scheme: str = "bdf2", snapshot_every: int = 10,
    initial: tuple[np.ndarray, float] | None = None, accept_stall: float = 1e-3,
    callback: Callable[[dict[str, Any]], None] | None = None, checkpoint: Checkpoint | None = None,
    resume: dict[str, Any] | None = None, cavitation: str = "projection",
    hoil: float | Callable[[float], float] = math.inf, time_tol: float | None = None,
    mass_tol: float | None = MASS_TOL, **kw: Any,
) -> TransientResult:
    """Run a surface feature through an EHL line contact at constant load.

    Parameters
    ----------
    problem : the steady :class:`LineProblem` (Moes M, L, lubricant, domain); elastic only.
    feature : :class:`~.features.Waviness` or :class:`~.features.Bump` (Venner units); None
        for smooth surfaces.
    body : the surface carrying the feature (1 or 2); it moves at ``u_body/u_m`` in X.
    slide_roll : ``S = (u1 - u2)/u_m`` in [-2, 2] (0 = pure rolling).
    dt : time step ``dT`` (``T = t u_m/b``); default: one mesh size per step for the faster of
        the feature and the mean flow (Courant number 1). Allowed: ``(0, max_time_step]``
        (:func:`~.stepping.max_time_step`).
    steps, t_end : number of steps, or the end time (default: until a bump has crossed to
        ``xmax``, or three waviness periods past one transit of the domain).
    options : :class:`LineOptions` of every step (defaults :data:`TRANSIENT_DEFAULTS`);
        keywords override fields.
    scheme : ``"bdf2"`` (first step backward Euler) or ``"euler"``.
    snapshot_every : keep P and H every this many steps (and the first and last).
    initial : ``(P, H0)`` on the finest grid to start from instead of the steady solution
        (the feature is then not pre-solved).
    accept_stall : a step whose cycles stall (the residual stops falling: a limit cycle of the
        free boundary, seen when a deep dent leaves the contact) is accepted when its relative
        residual and load error are below this; it is flagged in the ``stalled`` series and
        counted in the summary. 0 accepts no stalled step.
    callback : called after each step with a dict (step, T, Hc, Hm, cycles, residual).
    checkpoint : a :class:`~.checkpoint.Checkpoint` that writes the completed steps while the
        run goes on, and the run so far when it ends early (failure, interrupt, signal).
    resume : a checkpoint of this run (:func:`~.checkpoint.read_checkpoint`) to continue
        after its last completed step (same problem, feature, grid, time step and scheme;
        the steady start is solved again, the feature is not pre-solved).
    cavitation : ``"projection"`` (``P >= 0``: oil is created and lost where the film
        ruptures and reforms) or ``"mass-conserving"`` (Elrod-Adams film content, the
        starved solver's discretisation: :mod:`.cavitated`; 1.0-1.3x the cost per step).
    time_tol : local time error per step (relative film error, e.g. 1e-3): each output step
        ``dt`` is covered by BDF2 steps sized to it (Milne's device; :func:`.stepping.
        _advance_adaptive`), so ``dt`` is the output sampling only. None: one step per ``dt``.
        Allowed: [1e-8, 0.1].
    mass_tol : mass-conserving cavitation: the oil a step may gain or lose over the inflow
        (its domain mass error). Steps whose tolerances hold take more finest-grid cycles
        while it is above ``mass_tol`` and still falling (:mod:`.oil_balance`); None: the
        tolerances alone. Allowed: [1e-12, 1] or None.
    hoil : the oil layer supplied ahead of the contact (Venner units ``hoil R/b^2``, both
        surfaces, ambient density; :func:`~ehl_multigrid.starved.supply.hoil_venner` converts
        metres); ``inf``: a flooded inlet; or a function of ``T`` (a supply that changes in
        time, e.g. a step). A finite layer needs mass-conserving cavitation: the start is the
        starved steady solution of ``hoil(0)`` on the run's grid (the coupled Elrod-Adams
        solve), and every step lets in exactly the layer of its time (the meniscus moves with
        the film; a layer above the flooded contact's flux floods the inlet).

    Returns
    -------
    TransientResult : time series (Hc, Hm, H0, pressure fluctuation, feature position and the
        film's deviation there), snapshots, per-step convergence, the steady start.

    Raises
    ------
    InputError : bad feature, time step, step count or options (field, value, allowed range).
    ConvergenceError : the steady start or a step's multilevel solve failed (diverged, stalled,
        NaN) or the film closed, naming it; its ``partial`` attribute is the result up to the
        last completed step (``complete = False``, ``stop_reason``), also written by
        ``checkpoint`` when given. A run's failure is raised whatever ``raise_on_failure``
        (:class:`~.result.TransientResult` has no success or status to return it with);
        :func:`ehl_multigrid.solve` returns it as a failed Solution with those steps.
        An interrupt or signal during the steps propagates after the same write.
    """
    if not problem.elastic:
        raise InputError("problem.elastic = False: the transient solver needs elastic surfaces")
    supply, hoil, mass_tol = model_inputs(scheme, cavitation, hoil, time_tol, mass_tol)
    feature = Smooth() if feature is None else feature
    feature.check_domain(problem.xmin, problem.xmax)
    speed = feature_speed(body, slide_roll)
    opts = transient_options(options, **kw)
    h = (problem.xmax - problem.xmin) / (opts.points - 1)
    dt, steps, snapshot_every = time_steps(
        feature, speed, h, dt, steps, t_end, snapshot_every, accept_stall, "b",
        lambda: default_end_time(problem.xmin, problem.xmax, feature, speed))

    t0 = time.perf_counter()
    steady = flooded = solve_line_problem(problem, opts)
    require_steady_start("line", steady, initial, HINT)
    if cavitation == "projection":
        stepper = _LineStepper(TransientLineHierarchy(problem, opts, feature.height), problem, opts)
        stepper.policy = PROJECTION_STEP_POLICY
    else:
        hz = CavitatedStepHierarchy(problem, opts, feature.height, flooded, hoil)
        hz.mass_tol = mass_tol
        stepper = _LineStepper(hz, problem, opts)
        if hz.starved_inlet:
            steady = solve_starved_problem(problem, hoil, dataclasses.replace(
                opts, tol=min(opts.tol, STARVED_TOL), tol_load=min(opts.tol_load, STARVED_TOL_LOAD)),
                flooded)
            require_steady_start("line (starved)", steady, initial, HINT)
    out = TransientResult(problem=problem, feature=feature, body=body, slide_roll=slide_roll,
                          speed=speed, dt=float(dt), scheme=scheme, options=opts, steady=steady,
                          X=stepper.hz.fine.X.copy(), cavitation=cavitation, hoil=hoil,
                          mass_tol=getattr(stepper.hz, "mass_tol", None))
    stepper.supply = supply
    # the film content of a starved start (the flooded solution has none)
    start_and_march(stepper, out, steady, steady.extra["theta"] if steady is not flooded else None,
                    initial, True, resume, t0,
                    speed=speed, dt=dt, steps=steps, scheme=scheme, snapshot_every=snapshot_every,
                    accept_stall=accept_stall, on_film_collapse="raise", callback=callback,
                    checkpoint=checkpoint, time_tol=time_tol)
    return out


class _LineStepper(Stepper):
    """The line contact's side of the time loop (either cavitation model); ``supply``
    (optional): the supplied layer as a function of time."""

    name = "line"
    hint = HINT
    policy = LINE_POLICY
    settings = staticmethod(line_settings)

    @property
    def grid_text(self) -> str:
        return f"{self.hz.fine.n} points"

    @property
    def H0(self) -> float:
        return self.hz.fine.H0

    def set_unknowns(self, P: np.ndarray, H0: float) -> None:
        self.hz.fine.P, self.hz.fine.H0 = P, H0

    def film(self) -> tuple[np.ndarray, np.ndarray]:
        st = self.hz.fine.state()
        q = getattr(st, "q", None)  # mass-conserving cavitation: the oil carried, theta rho H
        return st.H, st.rho * st.H if q is None else q

    def accept_stalled(self, res: EHLResult, accept_stall: float) -> bool:
        # the cycles stalled (the residual stopped falling) below accept_stall
        return bool(res.status == 2 and res.residual_history.size > 0
                    and res.residual_history[-1] < accept_stall
                    and abs(res.load_error_history[-1]) < accept_stall)

