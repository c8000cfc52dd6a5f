"""Time-dependent isothermal EHL line contact: surface features passing through the contact.

Each time step ``T_n = n dT`` (``T = t u_m / b``) solves the implicit (BDF2; the first step
backward Euler) discrete Reynolds, film and load equations at the new time level by FAS
cycles of the shared multilevel driver on :class:`TransientLineHierarchy`, starting from the
previous solution extrapolated in time. The load is constant (``h sum P = pi/2`` every step,
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

import math
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from ..line.problem import LineProblem
from ..line.solver import HINT, LINE_POLICY, line_settings, solve_line_problem
from ..model.errors import ConvergenceError, InputError, require_choice, require_range
from ..multigrid.driver import MultilevelSolver
from ..multigrid.options import LineOptions
from ..multigrid.policy import RobustnessPolicy
from ..multigrid.result import EHLResult
from .features import Feature, Smooth, feature_speed, require_in
from .hierarchy import TransientLineHierarchy
from .result import TransientResult

SCHEMES = ("bdf2", "euler")
#: A step may move the feature at most this fraction of its length scale (wavelength, width):
#: beyond it a step cannot resolve the feature's passage (the implicit scheme stays stable
#: but damps and delays it, and the per-step nonlinear solve loses its good start).
MAX_STEP_FRACTION = 0.25
MAX_STEPS = 200_000

#: Default numerics of a time step: FFT deformation (exact), a tighter residual than the
#: steady default so the algebraic error of a step stays below its time error.
TRANSIENT_DEFAULTS = {"points": 257, "deformation": "fft", "tol": 1e-6, "tol_load": 1e-8,
                      "max_cycles": 40, "raise_on_failure": False}


def transient_options(options: LineOptions | None = None, **kw: Any) -> LineOptions:
    """Line options for the time steps: :data:`TRANSIENT_DEFAULTS` below ``options`` and
    keywords."""
    base = LineOptions.build(None, **TRANSIENT_DEFAULTS) if options is None else options
    return LineOptions.build(base, **{**kw, "raise_on_failure": False})


def max_time_step(feature: Feature, speed: float) -> float:
    """Largest ``dT`` accepted: the feature (speed ``speed``) and the free film waves (speed 1,
    the mean speed) move at most :data:`MAX_STEP_FRACTION` of the feature's length scale."""
    return MAX_STEP_FRACTION * feature.length_scale / max(abs(speed), 1.0)


def _step_coefficients(scheme: str, n: int, dt: float, q1: np.ndarray, q0: np.ndarray | None):
    if scheme == "euler" or n == 1 or q0 is None:
        return 1.0 / dt, q1 / dt
    return 1.5 / dt, (2.0 * q1 - 0.5 * q0) / dt


def solve_transient_line(
    problem: LineProblem, feature: Feature | None, *, body: int = 1, slide_roll: float = 0.0,
    dt: float | None = None, steps: int | None = None, t_end: float | None = None,
    options: LineOptions | None = None, scheme: str = "bdf2", snapshot_every: int = 10,
    initial: tuple[np.ndarray, float] | None = None, accept_stall: float = 1e-3,
    callback: Callable[[dict[str, Any]], None] | None = None, **kw: Any,
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
        the feature and the mean flow (Courant number 1). Allowed: ``(0, max_time_step]``.
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

    Returns
    -------
    TransientResult : time series (Hc, Hm, H0, pressure fluctuation, feature position and the
        film's deviation there), snapshots, per-step convergence, the steady start.

    Raises
    ------
    InputError : bad feature, time step, step count or options (field, value, allowed range).
    ConvergenceError : a step's multilevel solve failed (diverged, stalled, NaN), naming it.
    """
    if not problem.elastic:
        raise InputError("problem.elastic = False: the transient solver needs elastic surfaces")
    require_choice("scheme", scheme, SCHEMES)
    feature = Smooth() if feature is None else feature
    feature.check_domain(problem.xmin, problem.xmax)
    speed = feature_speed(body, slide_roll)
    opts = transient_options(options, **kw)
    h = (problem.xmax - problem.xmin) / (opts.points - 1)
    dt_max = max_time_step(feature, speed)
    if dt is None:
        dt = min(h / max(abs(speed), 1.0), dt_max)
    require_in("dt", dt, 0.0, dt_max, "-",
               f"T = t u_m/b; a step moves at most {MAX_STEP_FRACTION:g} of the feature's length scale "
               f"{feature.length_scale:g} at speed {max(abs(speed), 1.0):g}", lo_open=True)
    if steps is None:
        if t_end is None:
            t_end = default_end_time(problem, feature, speed)
        require_range("t_end", t_end, dt, dt * MAX_STEPS, "- (T = t u_m/b)")
        steps = int(math.ceil(t_end / dt - 1e-9))
    if isinstance(steps, bool) or int(steps) != steps:
        raise InputError(f"steps = {steps!r} must be an integer in [1, {MAX_STEPS}]")
    require_range("steps", steps, 1, MAX_STEPS, "time steps")
    require_range("snapshot_every", snapshot_every, 1, MAX_STEPS, "steps")
    require_range("accept_stall", accept_stall, 0.0, 0.01, "- (relative residual)")
    steps, snapshot_every = int(steps), int(snapshot_every)

    t0 = time.perf_counter()
    steady = solve_line_problem(problem, opts)
    if not steady.success and initial is None:
        raise ConvergenceError(f"transient line solver: the steady start failed: {steady.message}",
                               steady.report, HINT)
    hz = TransientLineHierarchy(problem, opts, feature.height)
    fine = hz.fine
    out = TransientResult(problem=problem, feature=feature, body=body, slide_roll=slide_roll,
                          speed=speed, dt=float(dt), scheme=scheme, options=opts, steady=steady,
                          X=fine.X.copy())
    if initial is not None:
        P0, H00 = initial
        P0 = np.asarray(P0, dtype=float)
        if P0.shape != (fine.n,):
            raise InputError(f"initial P has shape {P0.shape}; the finest grid has {fine.n} points")
        fine.P, fine.H0 = np.maximum(P0, 0.0), float(H00)
        hz.set_step(0.0, 0.0, np.zeros(fine.n))
    else:
        fine.P, fine.H0 = steady.P.copy(), float(steady.H0)
        hz.set_step(0.0, 0.0, np.zeros(fine.n))
        res = _solve_step(hz, problem, opts)
        if not res.success:
            raise ConvergenceError(f"transient line solver: the steady start with the feature at "
                                   f"T = 0 failed: {res.message}", res.report, HINT)
    out.record(0, 0.0, hz, None, 0.0, keep=True)
    out.setup_s = time.perf_counter() - t0

    q_prev: np.ndarray | None = None
    q_now = _mass(fine)
    P_prev, H0_prev = fine.P.copy(), fine.H0
    for n in range(1, steps + 1):
        T = n * dt
        ct, hist = _step_coefficients(scheme, n, dt, q_now, q_prev)
        P_now, H0_now = fine.P.copy(), fine.H0
        if n > 1:  # linear extrapolation in time: the start iterate of the step
            fine.P = np.maximum(2.0 * P_now - P_prev, 0.0)
            fine.P[0] = fine.P[-1] = 0.0
            fine.H0 = 2.0 * H0_now - H0_prev
        hz.set_step(speed * T, ct, hist)
        ts = time.perf_counter()
        res = _solve_step(hz, problem, opts)
        wall = time.perf_counter() - ts
        finite = bool(np.all(np.isfinite(fine.P)) and math.isfinite(fine.H0))
        stalled_ok = (res.status == 2 and finite and res.residual_history.size > 0
                      and res.residual_history[-1] < accept_stall
                      and abs(res.load_error_history[-1]) < accept_stall)
        if not (res.success or stalled_ok) or not finite:
            out.failed_step = n
            raise ConvergenceError(
                f"transient line solver: time step {n} (T = {T:.5g}, dT = {dt:.4g}) failed: "
                f"{res.message}", res.report,
                "a smaller time step (dt), more points, or a smaller feature amplitude")
        st = fine.state()
        wet = fine.P > 0.0
        if wet.any() and float(st.H[wet].min()) <= 0.0:
            out.failed_step = n
            raise ConvergenceError(
                f"transient line solver: time step {n} (T = {T:.5g}): the film collapsed "
                f"(min H = {float(st.H[wet].min()):.3g} where P > 0); the feature cuts through the "
                f"film, which needs a mixed-lubrication model", None,
                "a smaller feature amplitude")
        P_prev, H0_prev = P_now, H0_now
        q_prev, q_now = q_now, st.rho * st.H
        out.record(n, T, hz, res, wall, keep=(n % snapshot_every == 0 or n == steps))
        out.series["stalled"].append(0.0 if res.success else 1.0)
        if callback is not None:
            callback(out.last_step())
    out.wall_s = time.perf_counter() - t0
    hz.solver = None
    return out


def default_end_time(problem: LineProblem, feature: Feature, speed: float) -> float:
    """A bump: until its centre reaches ``xmax`` (or, when it does not move, one transit of
    the domain at the mean speed). Waviness: one transit of the domain plus three periods."""
    span = problem.xmax - problem.xmin
    if feature.kind == "smooth":
        return 2.0 * span
    if feature.kind == "bump":
        return (problem.xmax - feature.x0) / speed if speed > 1e-9 else span
    if feature.kind == "profile":  # until its tail has left the domain
        return (problem.xmax - float(feature.x[0])) / speed if speed > 1e-9 else span
    period = feature.wavelength / abs(speed) if abs(speed) > 1e-9 else 0.0
    return span + 3.0 * period


def _mass(lv) -> np.ndarray:
    st = lv.state()
    return st.rho * st.H


def _solve_step(hz: TransientLineHierarchy, problem: LineProblem, opts: LineOptions) -> EHLResult:
    solver = MultilevelSolver(hz, opts, line_settings(problem, opts),
                              RobustnessPolicy(LINE_POLICY, opts.adapt), HINT)
    return solver.solve()
