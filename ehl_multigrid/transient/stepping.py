"""The time loop shared by the line and point contacts: input checks of a run, the start
(steady solution or a given state, then the feature frozen at ``T = 0``), and the implicit
steps.

Each step ``T_n = n dT`` solves the BDF2 (first step backward Euler) equations at the new time
level by one FAS solve of the contact's hierarchy, started from the previous solution
extrapolated linearly in time; a step whose cycles stall below ``accept_stall`` is accepted
and flagged, a step whose solve fails is solved again as two half steps (variable-step BDF2,
down to 2^-:data:`MAX_HALVINGS` of the step; docs/robustness.md), a step that still fails or
whose film closes ends the run (:class:`ConvergenceError`, or a stop with ``failed_step``
set). The contact supplies a :class:`Stepper` (its unknowns, film, step solve and stall
rule); the result object records every step.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from ..model.atomic import deferred_signals
from ..model.errors import (
    ConvergenceError,
    InputError,
    Terminated,
    require_choice,
    require_range,
    signal_cause,
)
from ..multigrid.driver import MultilevelSolver
from ..multigrid.policy import RobustnessPolicy
from ..multigrid.result import EHLResult
from .checkpoint import restore
from .features import require_in
from .oil_balance import require_mass_tol

SCHEMES = ("bdf2", "euler")
#: cavitation models of the time steps
CAVITATION_MODELS = ("projection", "mass-conserving")
#: A step may move the feature at most this fraction of its length scale (wavelength, width):
#: beyond it a step cannot resolve the feature's passage (the implicit scheme stays stable
#: but damps and delays it, and the per-step nonlinear solve loses its good start).
MAX_STEP_FRACTION = 0.25
MAX_STEPS = 200_000


class Stepper:
    """The contact's side of the time loop: the hierarchy ``hz`` of one step (``fine``,
    ``set_step``, ``solver``), solved by the shared driver with the contact's ``settings``,
    robustness ``policy`` and ``hint``; ``name`` (``"line"``, ``"point"``) and ``grid_text``
    (the finest grid) for messages. Subclasses give the film constant, the film and the rule
    that accepts a stalled step."""

    name: str
    hint: str
    policy: Any
    settings: Callable[[Any, Any], Any]

    def __init__(self, hz: Any, problem: Any, opts: Any) -> None:
        self.hz, self.problem, self.opts = hz, problem, opts

    @property
    def grid_text(self) -> str:
        raise NotImplementedError

    @property
    def H0(self) -> float:
        """The finest grid's film constant (``H0`` line, ``H00`` point)."""
        raise NotImplementedError

    def set_unknowns(self, P: np.ndarray, H0: float) -> None:
        """Set the finest grid's pressure and film constant."""
        raise NotImplementedError

    def film(self) -> tuple[np.ndarray, np.ndarray]:
        """``(H, rho H)`` of the finest grid's iterate."""
        raise NotImplementedError

    def accept_stalled(self, res: EHLResult, accept_stall: float) -> bool:
        """Whether an unsuccessful, finite step is accepted as stalled below ``accept_stall``."""
        raise NotImplementedError

    def content(self) -> np.ndarray | None:
        """A copy of the finest grid's film content ``theta`` (mass-conserving cavitation), or
        None (the projection ``P >= 0``)."""
        theta = getattr(self.hz.fine, "theta", None)
        return None if theta is None else theta.copy()

    def set_content(self, theta: np.ndarray | None) -> None:
        """Set the finest grid's film content (ignored without one)."""
        if theta is not None and hasattr(self.hz.fine, "theta"):
            self.hz.fine.theta = np.array(theta, dtype=float)

    def zone(self) -> np.ndarray:
        """The finest grid's contact zone where the time error is measured: within 1.5
        Hertzian half-widths of the centre along X (and, for a point contact, 1.5 semi-axes
        ``b/a`` along Y)."""
        fine = self.hz.fine
        if np.ndim(fine.P) == 1:
            return np.abs(fine.X) <= 1.5
        boa = float(getattr(self.hz, "boa", 1.0))
        return (np.abs(fine.X)[None, :] <= 1.5) & (np.abs(fine.Y)[:, None] <= 1.5 * boa)

    #: the supplied layer as a function of time (mass-conserving cavitation), or None
    supply: Callable[[float], float] | None = None

    def set_time(self, T: float) -> None:
        """Set what depends on the time ``T`` of the step about to be solved besides the
        geometry: the supplied oil layer ``supply(T)`` (``hz.set_hoil``), when there is one."""
        if self.supply is None:
            return
        hoil = float(self.supply(T))
        require_hoil(hoil, T)
        self.hz.set_hoil(hoil)

    def unknowns(self) -> tuple[np.ndarray, float]:
        """A copy of the finest grid's pressure and its film constant."""
        return self.hz.fine.P.copy(), self.H0

    def solve_step(self) -> EHLResult:
        """One FAS solve of the step set by ``hz.set_step``."""
        solver = MultilevelSolver(self.hz, self.opts, type(self).settings(self.problem, self.opts),
                                  RobustnessPolicy(self.policy, self.opts.adapt), self.hint)
        return solver.solve()


def require_hoil(hoil: float, T: float) -> None:
    """Refuse a supplied layer that is not positive (at time ``T``)."""
    if not hoil > 0.0:
        raise InputError(f"hoil = {hoil!r} at T = {T:g} is outside the allowed range (0, inf] "
                         f"(Venner units: the oil layer ahead of the contact)")


def model_inputs(scheme: str, cavitation: str, hoil: float | Callable[[float], float],
                 time_tol: float | None, mass_tol: float | None
                 ) -> tuple[Callable[[float], float] | None, float, float | None]:
    """Checked scheme, cavitation model, supply, time and mass tolerances of a run: returns
    the supply as a function of time (None for a constant layer), the layer at ``T = 0`` and
    the mass tolerance (:func:`~.oil_balance.require_mass_tol`). A finite or time-varying
    layer needs mass-conserving cavitation."""
    require_choice("scheme", scheme, SCHEMES)
    require_choice("cavitation", cavitation, CAVITATION_MODELS)
    if time_tol is not None:
        require_range("time_tol", time_tol, 1e-8, 0.1, "- (relative film error per step)")
    supply = hoil if callable(hoil) else None
    hoil0 = float(supply(0.0)) if supply is not None else float(hoil)
    require_hoil(hoil0, 0.0)
    if (supply is not None or math.isfinite(hoil0)) and cavitation != "mass-conserving":
        raise InputError(f"hoil = {hoil0:g} (a starved inlet) needs cavitation = 'mass-conserving' "
                         f"(the projection has no oil layer to starve); got {cavitation!r}")
    return supply, hoil0, require_mass_tol(mass_tol, cavitation)


def step_coefficients(scheme: str, n: int, dt: float, q1: np.ndarray,
                      q0: np.ndarray | None, dt_prev: float | None = None) -> tuple[float, np.ndarray]:
    """``(c_t, s)`` of ``d(rho H)/dT ~ c_t (rho H)^(n+1) - s`` at step ``n`` from the films
    ``q1 = (rho H)^n`` and ``q0 = (rho H)^(n-1)`` (BDF2; backward Euler for ``"euler"``, the
    first step, or without ``q0``). ``dt_prev`` (default ``dt``) is the interval between ``q0``
    and ``q1``: the variable-step BDF2 of ratio ``w = dt/dt_prev``,
    ``[(1 + 2w)/(1 + w) q^(n+1) - (1 + w) q^n + w^2/(1 + w) q^(n-1)] / dt``."""
    if scheme == "euler" or n == 1 or q0 is None:
        return 1.0 / dt, q1 / dt
    w = 1.0 if dt_prev is None else dt / dt_prev
    return (1.0 + 2.0 * w) / ((1.0 + w) * dt), ((1.0 + w) * q1 - w * w / (1.0 + w) * q0) / dt


def max_time_step(feature: Any, speed: float) -> float:
    """Largest ``dT`` accepted: the feature (speed ``speed``) and the free film waves (speed 1,
    the mean speed) move at most :data:`MAX_STEP_FRACTION` of the feature's length scale."""
    return MAX_STEP_FRACTION * feature.length_scale / max(abs(speed), 1.0)


def time_steps(feature: Any, speed: float, mesh: float, dt: float | None, steps: int | None,
               t_end: float | None, snapshot_every: int, accept_stall: float, length: str,
               default_end: Callable[[], float]) -> tuple[float, int, int]:
    """Checked ``(dt, steps, snapshot_every)`` of a run: ``dt`` defaults to one mesh size
    ``mesh`` per step at the faster of the feature and the mean flow (Courant 1), ``steps`` to
    ``t_end`` (default ``default_end()``) over ``dt``. ``length`` names the length unit of
    ``T = t u_m/length`` in messages."""
    # the largest step as printed is accepted (0.25 * 0.3 / 1.5 rounds below 0.05)
    dt_max = float(f"{max_time_step(feature, speed):.6g}")
    if dt is None:
        dt = min(mesh / max(abs(speed), 1.0), dt_max)
    require_in("dt", dt, 0.0, dt_max, "-",
               f"T = t u_m/{length}; a step moves at most {MAX_STEP_FRACTION:g} of the feature's length "
               f"scale {feature.length_scale:g} at speed {max(abs(speed), 1.0):g}", lo_open=True)
    if steps is None:
        if t_end is None:
            t_end = default_end()
        require_range("t_end", t_end, dt, dt * MAX_STEPS, f"- (T = t u_m/{length})")
        steps = int(math.ceil(t_end / dt - 1e-9))
    if isinstance(steps, bool) or int(steps) != steps:
        raise InputError(f"steps = {steps!r} must be an integer in [1, {MAX_STEPS}]")
    require_range("steps", steps, 1, MAX_STEPS, "time steps")
    require_range("snapshot_every", snapshot_every, 1, MAX_STEPS, "steps")
    require_range("accept_stall", accept_stall, 0.0, 0.01, "- (relative residual)")
    return dt, int(steps), int(snapshot_every)


def require_steady_start(name: str, steady: EHLResult, initial: Any, hint: str) -> None:
    """Raise when the steady solution a run starts from (no ``initial``) failed."""
    if not steady.success and initial is None:
        raise ConvergenceError(f"transient {name} solver: the steady start failed: {steady.message}",
                               steady.report, hint)


def start(stepper: Stepper, out: Any, P_steady: np.ndarray, H0_steady: float,
          initial: tuple[np.ndarray, float] | None, presolve: bool, t0: float) -> None:
    """Put the start on the finest grid and record it as step 0: ``initial`` ``(P, H0)``, or
    the steady ``(P_steady, H0_steady)`` followed (``presolve``) by the steady equations with
    the feature frozen at its ``T = 0`` position."""
    hz = stepper.hz
    fine = hz.fine
    if initial is not None:
        P0, H00 = initial
        P0 = np.asarray(P0, dtype=float)
        if P0.shape != fine.P.shape:
            raise InputError(f"initial P has shape {P0.shape}; the finest grid has {stepper.grid_text}")
        stepper.set_unknowns(np.maximum(P0, 0.0), float(H00))
        hz.set_step(0.0, 0.0, np.zeros_like(fine.P))
    else:
        stepper.set_unknowns(P_steady, float(H0_steady))
        hz.set_step(0.0, 0.0, np.zeros_like(fine.P))
        if presolve:
            res = stepper.solve_step()
            if not res.success:
                raise ConvergenceError(f"transient {stepper.name} solver: the steady start with the "
                                       f"feature at T = 0 failed: {res.message}", res.report, stepper.hint)
    out.record(0, 0.0, hz, None, 0.0, keep=True)
    out.setup_s = time.perf_counter() - t0


def start_and_march(stepper: Stepper, out: Any, steady: EHLResult, theta0: np.ndarray | None,
                    initial: tuple[np.ndarray, float] | None, presolve: bool,
                    resume: dict[str, Any] | None, t0: float, **march_kw: Any) -> None:
    """A run's start (:func:`start` from the steady solution ``steady`` and the film content
    ``theta0``, or the completed steps of the checkpoint ``resume``), then its steps
    (:func:`march` with ``march_kw``)."""
    if resume is None:
        stepper.set_content(theta0)
        start(stepper, out, steady.P.copy(), steady.H0, initial, presolve, t0)
    else:
        restore(out, resume, march_kw["snapshot_every"])
    march(stepper, out, t0=t0, **march_kw)


def _extrapolate(P_now: np.ndarray, P_prev: np.ndarray, w: float = 1.0) -> np.ndarray:
    """Linear extrapolation in time over ``w`` times the last interval, projected on ``P >= 0``
    with ``P = 0`` on the boundary."""
    P = np.maximum(P_now + w * (P_now - P_prev), 0.0)
    for axis in range(P.ndim):
        edges = [slice(None)] * P.ndim
        for end in (0, -1):
            edges[axis] = end
            P[tuple(edges)] = 0.0
    return P


#: A step whose solve fails is solved again as two steps of half the size, each of which may be
#: halved again, down to 2^-MAX_HALVINGS of the step; the output times stay those of the step
MAX_HALVINGS = 3


def _advance(stepper: Stepper, speed: float, scheme: str, n: int, T0: float, h: float,
             last: dict[str, Any], accept_stall: float, halvings: int
             ) -> tuple[EHLResult, dict[str, Any], int, bool]:
    """Solve the interval ``[T0, T0 + h]`` from ``last`` (the state at ``T0``: ``P``, ``H0``,
    ``q`` and the level before it, ``P_prev``, ``H0_prev``, ``q_prev``, ``dt_prev`` apart).
    A solve that fails (not converged and not an accepted stall, or not finite) is repeated as
    two halves while ``halvings`` remain. Returns the last solve, the state at ``T0 + h``, the
    number of solves the interval took and whether the accepted solve was a stall."""
    fine = stepper.hz.fine
    dt_prev = last.get("dt_prev", h)
    ct, hist = step_coefficients(scheme, n, h, last["q"], last["q_prev"], dt_prev)
    if n > 1 or last["q_prev"] is not None:  # linear extrapolation in time: the start iterate
        w = h / dt_prev
        stepper.set_unknowns(_extrapolate(last["P"], last["P_prev"], w),
                             last["H0"] + w * (last["H0"] - last["H0_prev"]))
    else:
        stepper.set_unknowns(last["P"].copy(), last["H0"])
    stepper.set_content(last.get("theta"))
    stepper.set_time(T0 + h)
    stepper.hz.set_step(speed * (T0 + h), ct, hist)
    res = stepper.solve_step()
    finite = bool(np.all(np.isfinite(fine.P)) and math.isfinite(stepper.H0))
    stalled_ok = not res.success and finite and stepper.accept_stalled(res, accept_stall)
    if (res.success or stalled_ok) and finite or halvings <= 0 or res.status == 7:
        P, H0 = stepper.unknowns()
        state = {"P": P, "H0": H0, "q": stepper.film()[1].copy(), "P_prev": last["P"],
                 "H0_prev": last["H0"], "q_prev": last["q"], "dt_prev": h,
                 "q_prev2": last["q_prev"], "dt_prev2": last.get("dt_prev"),
                 "theta": stepper.content()}
        return res, state, 1, bool(stalled_ok and finite)
    half = 0.5 * h
    res1, mid, k1, _ = _advance(stepper, speed, scheme, n, T0, half, last, accept_stall, halvings - 1)
    if not (res1.success or stepper.accept_stalled(res1, accept_stall)):
        return res1, mid, k1, False
    # the second half: BDF2 on the half step's own levels (the first step of a run included)
    res2, end, k2, stalled = _advance(stepper, speed, scheme, max(n, 2), T0 + half, half, mid,
                                      accept_stall, halvings - 1)
    return res2, end, k1 + k2, stalled


#: BDF2's local error over the difference between its solution and the quadratic extrapolation
#: through the three levels before it (Milne's device: error constants 2/9 and 1 at constant
#: step; measured 0.20 on y' = y at dT = 0.1)
MILNE_FACTOR = 0.2
#: an adaptive step grows or shrinks by at most these factors, with this safety factor
STEP_GROWTH, STEP_SHRINK, STEP_SAFETY = 2.0, 0.2, 0.9
#: the smallest adaptive step, and the first step of a run, as fractions of the output step
MIN_STEP_FRACTION = 1.0 / 64.0
START_STEP_FRACTION = 1.0 / 16.0


def _predict(last: dict[str, Any], h: float) -> np.ndarray | None:
    """The film ``q`` at ``h`` after ``last``'s time by quadratic extrapolation through its
    three levels (``q``, ``q_prev`` at ``-dt_prev``, ``q_prev2`` at ``-dt_prev - dt_prev2``);
    None while the run has fewer levels."""
    q0, q1, q2 = last.get("q"), last.get("q_prev"), last.get("q_prev2")
    h1, h2 = last.get("dt_prev"), last.get("dt_prev2")
    if q1 is None or q2 is None or not h1 or not h2:
        return None
    t0, t1, t2 = 0.0, -h1, -h1 - h2  # Lagrange weights at t = h
    w0 = (h - t1) * (h - t2) / ((t0 - t1) * (t0 - t2))
    w1 = (h - t0) * (h - t2) / ((t1 - t0) * (t1 - t2))
    w2 = (h - t0) * (h - t1) / ((t2 - t0) * (t2 - t1))
    return w0 * q0 + w1 * q1 + w2 * q2


def local_time_error(stepper: Stepper, q: np.ndarray, q_pred: np.ndarray) -> float:
    """BDF2's local error of a step relative to the minimum film: :data:`MILNE_FACTOR` times
    the largest change from the prediction in the contact zone (:meth:`Stepper.zone`), over the
    zone's smallest ``theta rho H`` (so the error is relative to the film users read, Hm)."""
    zone = stepper.zone()
    scale = float(np.min(np.abs(q[zone])))
    return MILNE_FACTOR * float(np.max(np.abs(q - q_pred)[zone])) / max(scale, 1e-300)


#: a step that fails with its thinnest film below this fraction of the smooth film's minimum
#: is reported as a feature nearly cutting through the film
THIN_FILM_FRACTION = 0.2


def closure_node(H: np.ndarray, wet: np.ndarray) -> tuple[int, ...]:
    """The node of the thinnest film ``H``, among the pressurised nodes ``wet`` where one of
    them is closed, else anywhere."""
    where = wet if wet.any() and float(H[wet].min()) <= 0.0 else np.ones(H.shape, dtype=bool)
    return tuple(int(i) for i in np.unravel_index(int(np.argmin(np.where(where, H, np.inf))), H.shape))


def closure_site(fine: Any, H: np.ndarray, wet: np.ndarray) -> str:
    """`` at X = .. (, Y = ..)``: the node of the thinnest film on the finest grid ``fine``
    (:func:`closure_node`)."""
    k = closure_node(H, wet)
    if H.ndim == 1:
        return f" at X = {float(fine.X[k[0]]):.4g}"
    return f" at X = {float(fine.X[k[1]]):.4g}, Y = {float(fine.Y[k[0]]):.4g}"


def closed_film(fine: Any, H: np.ndarray, wet: np.ndarray) -> str:
    """`` at X = .. (min H = ..)``: where and how thin a closed film is, the smallest film where
    ``P > 0`` when one there is closed, else the smallest anywhere (:func:`closure_site`)."""
    wet_low = float(H[wet].min()) if wet.any() else math.inf
    low, where = (wet_low, " where P > 0") if wet_low <= 0.0 else (float(np.min(H)), "")
    return f"{closure_site(fine, H, wet)} (min H = {low:.3g}{where})"


#: a feature at most this fraction of the film as deep (or high) cannot close that film: its
#: deformed amplitude is at most its own (Venner & Lubrecht 2000, ch. 12), so half the film
#: stays; a step that ends with a film closed there diverged
SHALLOW_FEATURE_FRACTION = 0.5


def feature_depth(fine: Any) -> float:
    """The feature's depth or height on the finest grid ``fine``: the largest ``|R|`` of the
    surface geometry at the step's time (film units; 0 for smooth surfaces)."""
    R = getattr(fine, "R", None)
    return float(np.max(np.abs(R))) if R is not None and np.size(R) else 0.0


def shallow_feature(fine: Any, out: Any, H: np.ndarray, wet: np.ndarray) -> str:
    """`` where the film was .. one step before, and the feature is .. deep (.. % of it)``
    when the feature is at most :data:`SHALLOW_FEATURE_FRACTION` of the last completed step's
    film at the node where the film of ``H`` is thinnest (:func:`closure_node`), else ``""``
    (also when that film is not kept)."""
    last = out.snapshots.get(out.steps) if out.series["T"] else None
    if last is None or np.shape(last["H"]) != H.shape:
        return ""
    before = float(last["H"][closure_node(H, wet)])
    depth = feature_depth(fine)
    if not (before > 0.0 and depth <= SHALLOW_FEATURE_FRACTION * before):
        return ""
    return (f" where the film was {before:.3g} one step before, and the feature is {depth:.3g} "
            f"deep ({100.0 * depth / before:.2g} % of it)")


#: what to try when a step's iteration diverged (measured on page 63 at 100 N on a long box:
#: backward Euler, a longer step and more grid levels each converged where BDF2 failed)
DIVERGED_HINT = ("backward Euler (scheme 'euler'), another time step (dt), or more grid levels "
                 "(levels)")


def _advance_adaptive(stepper: Stepper, speed: float, scheme: str, n: int, T0: float, dt: float,
                      last: dict[str, Any], accept_stall: float, tol: float
                      ) -> tuple[EHLResult, dict[str, Any], int, bool, float, int]:
    """The output interval ``[T0, T0 + dt]`` in steps sized by BDF2's local error
    (:func:`local_time_error` at most ``tol``): a step over it is solved again at the step its
    error asks for (down to :data:`MIN_STEP_FRACTION` of ``dt``), the next step grows by at
    most :data:`STEP_GROWTH`. Each step is an :func:`_advance` (halved on a failed solve).
    Returns the last solve, the state at ``T0 + dt`` (with ``h_next``), the solves, whether the
    last accepted solve was a stall, the largest accepted local error and the rejected steps."""
    end = T0 + dt
    # a run's first steps have no error estimate (the predictor needs three levels): small;
    # ``want`` is the controller's step, ``h`` the one taken (cut to end at the output time)
    want = min(float(last.get("h_next") or START_STEP_FRACTION * dt), dt)
    t, cur = T0, last
    solves = rejected = 0
    err_max = 0.0
    while True:
        rest = end - t
        h = want
        if rest <= h * (1.0 + 1e-9):
            h = rest
        elif rest - h < 0.25 * h:  # no sliver of a step before the output time: two halves
            h = 0.5 * rest
        q_pred = _predict(cur, h) if scheme == "bdf2" else None
        first = n == 1 and t == T0 and cur.get("q_prev") is None
        res, nxt, k, stalled = _advance(stepper, speed, scheme, 1 if first else max(n, 2), t, h, cur,
                                        accept_stall, MAX_HALVINGS)
        solves += k
        finite = bool(np.all(np.isfinite(stepper.hz.fine.P)) and math.isfinite(stepper.H0))
        if not ((res.success or stalled) and finite):
            return res, nxt, solves, stalled, err_max, rejected
        err = local_time_error(stepper, nxt["q"], q_pred) if q_pred is not None else 0.0
        factor = STEP_SAFETY * (tol / err) ** (1.0 / 3.0) if err > 0.0 else STEP_GROWTH
        if err > tol and h > MIN_STEP_FRACTION * dt * (1.0 + 1e-9):
            rejected += 1
            want = max(h * max(STEP_SHRINK, factor), MIN_STEP_FRACTION * dt)
            continue
        err_max = max(err_max, err)
        t += h
        cur = nxt
        # a step cut short by the output time keeps the controller's larger step
        want = min(dt, max(want if h < want else 0.0, h * min(STEP_GROWTH, factor)))
        if end - t <= 1e-9 * dt:
            cur["h_next"] = want
            return res, cur, solves, stalled, err_max, rejected


def march(stepper: Stepper, out: Any, *, speed: float, dt: float, steps: int, scheme: str,
          snapshot_every: int, accept_stall: float, on_film_collapse: str,
          callback: Callable[[dict[str, Any]], None] | None, t0: float,
          checkpoint: Any = None, time_tol: float | None = None) -> None:
    """Steps after the recorded start (or after ``out.state``, the last completed step of a
    continued run) up to ``steps``, each recorded in ``out``.

    After every completed step ``out.state`` holds the next step's inputs and ``checkpoint``
    (a :class:`~.checkpoint.Checkpoint`, optional) may write the run so far. A run that ends
    early -- a failed step (:class:`ConvergenceError`), a closed film, an interrupt or a signal
    -- is marked incomplete with the reason and written by ``checkpoint`` when given; the
    exception propagates, carrying ``out`` as its ``partial`` attribute.

    ``time_tol``: each output step ``dt`` is covered by steps sized by BDF2's local film error
    (:func:`_advance_adaptive`); the series ``time_error`` holds the largest accepted local
    error of each output step, ``rejected`` the steps solved again smaller. None: one BDF2
    step per output step (halved only when its solve fails).
    """
    hz = stepper.hz
    fine = hz.fine
    name = stepper.name
    out.planned_steps = steps
    if out.state is None:  # a fresh run: the start is step 0
        P, H0 = stepper.unknowns()
        out.state = {"step": 0, "T": 0.0, "P": P, "H0": H0, "P_prev": P, "H0_prev": H0,
                     "q": stepper.film()[1].copy(), "q_prev": None, "theta": stepper.content()}
        if checkpoint is not None:
            checkpoint.step(out)
    else:
        stepper.set_unknowns(np.array(out.state["P"], dtype=float), float(out.state["H0"]))
        stepper.set_content(out.state.get("theta"))
    n = T = 0
    # a run continued from a file of an earlier version has no substep series
    out.series.setdefault("substeps", [1.0] * len(out.series["T"]))
    try:
        for n in range(int(out.state["step"]) + 1, steps + 1):
            T = n * dt
            # the output levels are dt apart; an adaptive run keeps its own last steps
            last = {**out.state, "dt_prev": out.state.get("dt_prev") or dt}
            ts = time.perf_counter()
            # cycles that stall (a limit cycle of the free boundary) leave an iterate that the
            # contact's rule may accept below accept_stall; a failed solve is halved
            if time_tol is None:
                res, nxt, solves, stalled_ok = _advance(stepper, speed, scheme, n, T - dt, dt, last,
                                                        accept_stall, MAX_HALVINGS)
                terr, rejected = math.nan, 0
            else:
                res, nxt, solves, stalled_ok, terr, rejected = _advance_adaptive(
                    stepper, speed, scheme, n, T - dt, dt, last, accept_stall, time_tol)
            wall = time.perf_counter() - ts
            finite = bool(np.all(np.isfinite(fine.P)) and math.isfinite(stepper.H0))
            H, q = stepper.film()
            wet = fine.P > 0.0
            closed = res.status == 7 or (finite and wet.any() and float(H[wet].min()) <= 0.0)
            # a feature far shallower than the film it passes cannot close it: then a closed
            # or thin film is the step's diverged iteration, not mixed lubrication
            shallow = shallow_feature(fine, out, H, wet) if finite else ""
            if closed and on_film_collapse == "stop":
                out.failed_step = n
                out.mark_incomplete(
                    f"the film closed at step {n} (T = {T:.5g}){closed_film(fine, H, wet)}" +
                    (f"{shallow}: the step's iteration diverged ({res.message})" if shallow else ""))
                break
            if closed and finite and shallow:
                out.failed_step = n
                how = ("converged to a film that is not positive" if res.status == 7 else
                       "did not converge: its iteration diverged to a film that is not positive")
                raise ConvergenceError(
                    f"transient {name} solver: time step {n} (T = {T:.5g}, dT = {dt:.4g}) {how}"
                    f"{closed_film(fine, H, wet)}{shallow}, so the feature does not cut through "
                    f"the film ({res.message})", res.report,
                    "more points" if res.status == 7 else DIVERGED_HINT)
            if closed and finite:
                # before the step's own failure: "not positive on this grid" would only say
                # "more points", where a feature cutting through the film is the usual cause
                out.failed_step = n
                raise ConvergenceError(
                    f"transient {name} solver: time step {n} (T = {T:.5g}): the film collapsed"
                    f"{closed_film(fine, H, wet)}: the feature cuts through the film, which needs a "
                    f"mixed-lubrication model the transient solvers do not have, or the grid is too "
                    f"coarse to carry the film there", res.report,
                    "a smaller feature amplitude, or more points")
            if not (res.success or stalled_ok) or not finite:
                out.failed_step = n
                why = (res.message if finite else
                       f"the pressure or film constant is not finite ({res.message})")
                if finite:
                    # where and how thin the film was: a feature that nearly cuts through it is
                    # the usual cause of a stalled step, unless it is far shallower than the film
                    low, smooth = float(np.min(H)), float(out.steady_film("Hm"))
                    why += f"; thinnest film H = {low:.3g}{closure_site(fine, H, wet)}"
                    if shallow:
                        why += f"{shallow}: not a feature cutting through the film"
                    elif low < THIN_FILM_FRACTION * smooth:
                        why += (f", below {THIN_FILM_FRACTION:g} of the smooth film's minimum "
                                f"{smooth:.3g}: the feature nearly cuts through the film (mixed "
                                f"lubrication, which the transient solvers do not model)")
                raise ConvergenceError(
                    f"transient {name} solver: time step {n} (T = {T:.5g}, dT = {dt:.4g}) failed: "
                    f"{why}", res.report,
                    DIVERGED_HINT if shallow else
                    "a smaller time step (dt), more points, or a smaller feature amplitude")
            with deferred_signals():  # a stop never records a step without its state
                out.record(n, T, hz, res, wall, keep=(n % snapshot_every == 0 or n == steps))
                out.series["stalled"].append(0.0 if res.success else 1.0)
                out.series["substeps"].append(float(solves))
                # the history: the output step before (fixed steps), or the last two steps taken
                prev = {"P_prev": last["P"], "H0_prev": last["H0"], "q_prev": last["q"]}
                if time_tol is not None:
                    out.series.setdefault("time_error", [math.nan] * n).append(terr)
                    out.series.setdefault("rejected", [0.0] * n).append(float(rejected))
                    prev = {k: nxt[k] for k in ("P_prev", "H0_prev", "q_prev", "dt_prev", "q_prev2",
                                                "dt_prev2", "h_next")}
                out.state = {"step": n, "T": T, "P": nxt["P"], "H0": nxt["H0"], "q": q,
                             "theta": nxt["theta"], **prev}
            if checkpoint is not None:
                checkpoint.step(out)
            if callback is not None:
                callback(out.last_step())
    except BaseException as raised:
        # a signal that arrives inside a compiled kernel surfaces as a SystemError caused by
        # it: the run stops for the signal, not for an internal error
        exc = signal_cause(raised) or raised
        out.mark_incomplete(stop_reason(exc, n, T, out))
        out.wall_s = time.perf_counter() - t0
        exc.partial = out  # the caller reports what was kept (no other way to reach it)
        if checkpoint is not None:
            try:
                checkpoint.write(out)
            except Exception as werr:  # the run's own failure is the error to report
                exc.add_note(f"the steps computed so far could not be written: {werr}")
        if exc is raised:
            raise
        raise exc from None
    finally:
        hz.solver = None
    out.wall_s = time.perf_counter() - t0
    if checkpoint is not None and not out.complete:  # stopped at a closed film
        checkpoint.write(out)


def stop_reason(exc: BaseException, n: int, T: float, out: Any) -> str:
    """Why a run ended at step ``n`` (time ``T``) by ``exc``, and what it kept."""
    kept = f"steps 0..{out.steps} (T = 0..{out.series['T'][-1]:.5g}) were kept" if out.series["T"] \
        else "no step was kept"
    if isinstance(exc, KeyboardInterrupt):
        why = "interrupted (Ctrl-C)"
    elif isinstance(exc, Terminated):  # the command line's SIGTERM
        why = "terminated (SIGTERM)"
    elif isinstance(exc, ConvergenceError):
        why = "did not converge: " + str(exc).splitlines()[0]
    else:
        why = f"{type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}"
    at = f"during step {n} (T = {T:.5g})" if out.steps < n else f"after step {n}"
    return f"{why} {at}; {kept}"
