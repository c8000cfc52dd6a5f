"""The outer (fixed-point) iteration of a TEHL solve, shared by line and point contacts.

One outer iteration: the across-film factors of the last thermal solution, damped in their
logarithm and Anderson-mixed, go to the multilevel solve of the pressure and film; the thermal
solve on the new pressure and film gives the next temperature field. It stops when the changes
of P (relative L2 norm), of the films (Hc, Hm) and of T (max, kelvin) between two iterations,
divided by the iteration's damping, are all below their tolerances (the film tolerance
widened to twice the films' algebraic uncertainty when an inner solve reports one), or when it
has settled at the inner solves' noise floor (:func:`settled`).

The geometry enters as a :class:`Contact` strategy (:class:`thermal.tehl.line.LineContact`,
:class:`thermal.tehl.point.PointContact`): its factor hierarchy and multilevel solve, its films,
its thermal solve and the across-film factors of that solve. :func:`coupled_solve` runs the
iteration on it, from a coarser grid's factors when given (nested iteration).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from ehl_multigrid.model.convergence import ConvergenceReport
from ehl_multigrid.model.errors import ConvergenceError
from ehl_multigrid.multigrid.controller import check_deadline

from ..kernels import _anderson_step
from ..line import Surroundings
from ..traction import wall_speeds

#: smallest under-relaxation of the outer iteration before it is declared divergent
MIN_RELAX = 1.0 / 64.0
#: an iteration still converging at ``max_outer`` goes on while the trend of its last
#: :data:`TREND_WINDOW` iterations reaches the tolerances within this many times ``max_outer``
#: in all (the roller bearing at S = 1 on 1025 points: 70 iterations; docs/thermal.md)
EXTEND_OUTER = 2.5
TREND_WINDOW = 20
#: changes whose trend over the last :data:`CREEP_WINDOW` iterations at one damping rises by more
#: than this factor per iteration grow, even when noise hides it from iteration to iteration
#: (the spur gear at S = 0.5 on 1025 points: +10 % per iteration at 0.5 for 25 iterations)
CREEP_GROWTH = 1.03
CREEP_WINDOW = 10

#: settled at the inner solves' noise floor (:func:`settled`): over this many iterations at one
#: damping, changes within NOISE_RAW tolerances (the spur gear on 2049 points: outlet
#: temperatures jitter by up to 4.2 tol_T) and a drift within them (docs/thermal.md)
NOISE_WINDOW = 10
NOISE_RAW = 5.0

OUTER_HINT = ("lower relax (under-relaxation of the across-film factors), raise max_outer, or "
              "check the thermal loading (oil temperature limits, slip, speed)")


class CoarseStartError(ConvergenceError):
    """The multilevel solve with a coarser grid's factors, which starts a nested outer
    iteration, failed (the same grid may still converge from its own isothermal start)."""


@dataclass
class Iterate:
    """Pressure and film of one outer iteration (Venner's P, H; Moes Hc, Hm)."""

    P: np.ndarray
    H: np.ndarray
    H0: float
    Hc: float
    Hm: float
    extra: dict[str, Any] = field(default_factory=dict)


class Contact(Protocol):
    """The geometry of a coupled TEHL solve (a line or a point contact).

    ``hierarchy`` : the factor hierarchy (``set_factors``, ``set_iterate``, ``levels``) and
    ``options`` its multilevel options (``tol``); ``label``, ``alternation``, ``hint`` : the
    words of the multilevel steps' notes and failures; ``notes`` : the solve's actions so far,
    the report's first; ``multilevel()`` : the multilevel solve with the factors and start set,
    ``(result, P, H, H0)``; ``films(P, H)`` : Moes ``(Hc, Hm)``; ``thermal(state)`` : the
    thermal solve, ``(solution, temperature array)``; ``factors(solution)`` : the flow and
    Couette factors ``(a, c)``, handing the hierarchy the flow's viscosity response of that
    solution (``coefficients.viscosity_response``) as well; ``finer_factor(f)`` : a factor of the grid with half the
    intervals interpolated to this one; ``friction(solution)`` : the friction force of a thermal
    solution (any unit: its relative changes are compared).
    """

    label: str
    alternation: str
    hint: str
    hierarchy: Any
    options: Any
    notes: list[str]

    def multilevel(self) -> tuple[Any, np.ndarray, np.ndarray, float]: ...
    def films(self, P: np.ndarray, H: np.ndarray) -> tuple[float, float]: ...
    def thermal(self, state: Iterate) -> tuple[Any, np.ndarray]: ...
    def factors(self, thermal: Any) -> tuple[np.ndarray, np.ndarray]: ...
    def finer_factor(self, f: np.ndarray) -> np.ndarray: ...
    def friction(self, thermal: Any) -> float: ...


def surroundings(scene: Any, slip: float) -> Surroundings:
    """What the film of ``scene`` sees at ``slip`` (the wall speeds checked for its range)."""
    u1, u2 = wall_speeds(scene.us, slip)
    return Surroundings(scene.lubricant, scene.body1, scene.body2, u1, u2, scene.T_oil,
                        scene.T_surface1, scene.T_surface2)


#: an inner solve that meets its residual tolerance with films alternating by less than this
#: many outer film tolerances is accepted (a ball at 1.6 GPa and S = 0.5 on 257 points: 1.6e-3
#: at residual 6e-5; docs/thermal.md, "Films alternating at the relaxation's floor")
ALTERNATION_ACCEPTED = 30.0


def film_noise(history: list[Any], top: int) -> float:
    """Relative change of Hc and Hm over the last two cycles on grid ``top`` of a multilevel
    solve's ``history`` (the algebraic uncertainty of its films; inf with fewer than two)."""
    fin = [h for h in history if h.level == top][-2:]
    if len(fin) < 2:
        return math.inf
    a, b = fin
    return float(max(abs(b.Hc - a.Hc) / abs(b.Hc), abs(b.Hm - a.Hm) / abs(b.Hm)))


def log_trend(values: list[float]) -> tuple[float, float]:
    """Least-squares slope of ``log(values)`` per iteration and its standard error."""
    x = np.arange(len(values), dtype=float)
    y = np.log(np.asarray(values, dtype=float))
    slope, icept = np.polyfit(x, y, 1)
    resid = y - (slope * x + icept)
    se = math.sqrt(float(resid @ resid) / max(len(values) - 2, 1) / float(((x - x.mean()) ** 2).sum()))
    return float(slope), se


def iterations_to_converge(hist: list[float], window: int = TREND_WINDOW) -> float:
    """Outer iterations still needed for the convergence measure ``hist`` (changes over
    tolerances, divided by the damping; converged below 1) to fall below 1, from the
    least-squares trend of its logarithm over the last ``window`` iterations (inf when the
    trend does not fall or there are fewer than ``window`` values)."""
    if len(hist) < window:
        return math.inf
    slope = log_trend(hist[-window:])[0]
    return math.log(hist[-1]) / -slope if slope < 0.0 else math.inf


def creeping(raw: list[float], steps: int) -> bool:
    """Whether the changes ``raw`` (over tolerances) of the last ``steps`` iterations at one
    damping rise by more than :data:`CREEP_GROWTH` per iteration over the last
    :data:`CREEP_WINDOW`: the least-squares trend of their logarithm, by more than twice its
    standard error (a noisy plateau near the tolerances is no trend)."""
    if steps < CREEP_WINDOW or len(raw) < CREEP_WINDOW:
        return False
    slope, se = log_trend(raw[-CREEP_WINDOW:])
    return slope > math.log(CREEP_GROWTH) and slope > 2.0 * se


def settled(outer: list[dict[str, float]], fields: list[tuple[np.ndarray, np.ndarray]], raw: list[float],
            w: float, tol_P: float, tol_H: float, tol_T: float) -> dict[str, float] | None:
    """The noise floor the outer iteration settled at, or None: the iterates ``fields`` (P, T)
    and ``outer`` records of the last :data:`NOISE_WINDOW` iterations at damping ``w``, their
    changes ``raw`` over the tolerances all at most :data:`NOISE_RAW`, and the drift per
    iteration divided by ``w`` (the distance to the fixed point it implies, as the changes'
    test assumes) within the tolerances: half-window means of P (relative L2) and T (max,
    kelvin), least-squares trends of Hc, Hm (relative) and T_max. Returns the drifts and the
    window's spreads (Hc, Hm relative, T_max kelvin, P the largest relative change)."""
    k = NOISE_WINDOW
    if len(fields) < k or len(outer) < k or len(raw) < k or max(raw[-k:]) > NOISE_RAW:
        return None
    h = k // 2
    P1, P2 = (np.mean([f[0] for f in part], axis=0) for part in (fields[-k:-h], fields[-h:]))
    T1, T2 = (np.mean([f[1] for f in part], axis=0) for part in (fields[-k:-h], fields[-h:]))
    steps = k - h  # iterations between the two half-windows' centres (k even)
    out = {"P": float(np.linalg.norm(P2 - P1) / np.linalg.norm(P2)) / steps / w,
           "T": float(np.max(np.abs(T2 - T1))) / steps / w}
    x = np.arange(k, dtype=float)
    for key in ("Hc", "Hm", "T_max"):
        v = np.array([o[key] for o in outer[-k:]], dtype=float)
        slope = float(np.polyfit(x, v, 1)[0])
        scale = 1.0 if key == "T_max" else abs(v[-1])
        out[key] = abs(slope) / scale / w
        out[f"spread_{key}"] = float(v.max() - v.min()) / scale
    out["spread_P"] = float(max(o["dP"] for o in outer[-k:]))
    ok = (out["P"] < tol_P and out["T"] < tol_T and out["T_max"] < tol_T
          and max(out["Hc"], out["Hm"]) < tol_H)
    return out if ok else None


def films_settled(outer: list[dict[str, float]], fields: list[tuple[np.ndarray, np.ndarray]],
                  tol_P: float, tol_H: float, tol_T: float) -> dict[str, float] | None:
    """Where the temperature field does not settle but what the solve reports does: over the
    last :data:`NOISE_WINDOW` iterations (at any dampings) the changes of P and the films stay
    within :data:`NOISE_RAW` tolerances, and the drift per iteration (the median step), divided
    by the smallest damping of the window, of Hc, Hm, the friction (relative) and T_max (kelvin)
    meets the tolerances; the temperature at some nodes still moves (at a stationary surface:
    the far inlet's dividing streamline, docs/thermal.md "Limits"). The drift and spread of each are its iteration
    error (:func:`thermal.tehl.accuracy.estimate_error`). Returns them, the drift of P
    (half-window means) and the largest temperature change of the window (``dT``) with where it
    is (the node's indices, ``node``), or None."""
    k = NOISE_WINDOW
    if len(fields) < k or len(outer) < k:
        return None
    win = outer[-k:]
    w = min(o["relax"] for o in win)
    if max(max(o["dP"] / tol_P, max(o["dHc"], o["dHm"]) / max(tol_H, 2.0 * o.get("film_noise", 0.0)))
           for o in win) > NOISE_RAW:
        return None
    h = k // 2
    P1, P2 = (np.mean([f[0] for f in part], axis=0) for part in (fields[-k:-h], fields[-h:]))
    out = {"P": float(np.linalg.norm(P2 - P1) / np.linalg.norm(P2)) / (k - h) / w}
    for key in ("Hc", "Hm", "T_max", "friction"):
        v = np.array([o[key] for o in win], dtype=float)
        scale = 1.0 if key == "T_max" else abs(v[-1])
        # the median step is the steady approach; a jump of an inner solve (one more cycle
        # moves the temperature at the node by kelvins) lies in the spread
        out[key] = abs(float(np.median(np.diff(v)))) / scale / w
        out[f"spread_{key}"] = float(v.max() - v.min()) / scale
    out["spread_P"] = float(max(o["dP"] for o in win))
    dT = np.max([np.abs(b[1] - a[1]) for a, b in zip(fields[-k:-1], fields[-k + 1:], strict=True)], axis=0)
    at = np.unravel_index(int(np.argmax(dT)), dT.shape)
    out.update(dT=float(dT[at]), node=tuple(int(i) for i in at), films_only=True)
    noise = max(o.get("film_noise", 0.0) for o in win)
    ok = (out["T_max"] < tol_T and out["friction"] < tol_H and max(out["Hc"], out["Hm"]) < max(tol_H, 2.0 * noise))
    return out if ok else None


def grows(raw: list[float]) -> bool:
    """Whether the changes ``raw`` (over their tolerances) grow: above 10 tolerances and doubled
    in one iteration or risen in two in a row."""
    return len(raw) >= 2 and raw[-1] > 10.0 and (raw[-1] > 2.0 * raw[-2] or (len(raw) >= 3 and raw[-1] > raw[-2] > raw[-3]))


def films_settled_note(it: int, floor: dict[str, float]) -> str:
    return (f"iteration {it}: the films, pressure, friction and largest temperature settled (drift per "
            f"iteration over the damping: P {floor['P']:.2g}, Hc {floor['Hc']:.2g}, Hm {floor['Hm']:.2g}, "
            f"friction {floor['friction']:.2g}, T_max {floor['T_max']:.2g} K) while the temperature at "
            f"index {floor['node']} of the temperature array still changes by up to {floor['dT']:.2g} K per iteration: "
            f"the temperature field there is not converged; the drift and spread of the last "
            f"{NOISE_WINDOW} iterations are the iteration error of what is reported")


def multilevel_step(contact: Contact, a: np.ndarray, c: np.ndarray, state: Iterate, it: int,
                    tol_H: float) -> Iterate:
    """Pressure and film of the factors ``a``, ``c``, the multilevel solve started from
    ``state`` (outer iteration ``it``; raises :class:`ConvergenceError` when it fails)."""
    hz = contact.hierarchy
    hz.set_factors(a, c)
    hz.set_iterate(state.P, state.H0)
    res, P, H, H0 = contact.multilevel()
    noise = film_noise(res.history, len(hz.levels) - 1)
    if (not res.success and res.status in (1, 8) and res.residual_history[-1] < contact.options.tol
            and noise < ALTERNATION_ACCEPTED * tol_H):
        # the residual tolerance is met but the films alternate between two states (the
        # outlet free boundary flips between nodes; a line's Hm by up to 6e-4 at residual
        # 2.5e-6), whether the cycles ran out or stopped at the relaxation's floor (status 8;
        # a traction drive at 2.5 GPa, Hm by 3e-4 at 6e-6 on 257 points): accepted, the
        # alternation carried into the outer iteration and the estimate as their uncertainty
        contact.notes.append(f"outer iteration {it}: films alternate by {noise:.2g}{contact.alternation} at "
                             f"residual {res.residual_history[-1]:.3g}; accepted as their uncertainty")
    elif not res.success:
        raise ConvergenceError(f"{contact.label} outer iteration {it}: the multilevel solve failed: {res.message}",
                               res.report, contact.hint)
    Hc, Hm = contact.films(P, H)
    return Iterate(P, H, H0, Hc, Hm, {"cycles": int(res.cycles), "film_noise": min(noise, 1.0)})


@dataclass
class OuterOutcome:
    state: Iterate
    thermal: Any
    a: np.ndarray
    c: np.ndarray
    outer: list[dict[str, float]]
    report: ConvergenceReport


def coupled_solve(contact: Contact, state: Iterate, thermal: Any, T: np.ndarray, a: np.ndarray, c: np.ndarray,
                  options: Any, coarse: Any = None) -> OuterOutcome:
    """Run the outer iteration of ``contact`` from ``state`` and its thermal solution
    ``thermal`` (temperature array ``T``) with the factors ``a``, ``c`` in use, by the
    relaxation and tolerances of ``options`` (:class:`~thermal.tehl.options.TEHLOptions`).

    ``coarse``: a solution on half the intervals whose factors, interpolated, start the
    iteration after one multilevel solve with them. The contact's notes lead the report's
    actions. Raises :class:`ConvergenceError` on non-finite values, divergence (changes
    growing at the smallest damping) or when ``max_outer`` iterations do not meet the tolerances
    (an iteration whose trend still reaches them goes on, up to :data:`EXTEND_OUTER` times
    ``max_outer``: :func:`iterations_to_converge`); raises
    :class:`~ehl_multigrid.multigrid.controller.TimeBudgetSpent` before an iteration that would
    start after the time budget of the accuracy-driven solve ran out.
    """
    relax, anderson, max_outer = options.relax, options.anderson, options.max_outer
    tol_P, tol_H, tol_T = options.tol_P, options.tol_H, options.tol_T
    if coarse is not None:
        # the coarse fixed point's factors with the film they give on this grid: a consistent
        # start (the interpolated coarse pressure itself is not: its spike is a grid off)
        a, c = (contact.finer_factor(f) for f in (coarse.a, coarse.c))
        contact.factors(thermal)  # (for the flow's viscosity response of this grid's start)
        try:
            state = multilevel_step(contact, a, c, state, 0, tol_H)
        except ConvergenceError as exc:
            raise CoarseStartError(str(exc).split("\n  what to try:")[0], exc.report, exc.hint) from exc
        thermal, T = contact.thermal(state)
        contact.notes.append(f"outer iteration started from the factors of the solve on {coarse.X.size} points")
    t0 = time.perf_counter()
    shape = a.shape
    n = a.size
    outer: list[dict[str, float]] = []
    hist: list[float] = []
    raw: list[float] = []
    raw_films: list[float] = []  # the changes of P and the films alone, over their tolerances
    actions: list[str] = []
    t_only = False  # noted that only the temperature grows at the smallest damping
    converged = False
    w = relax
    AX = np.empty((anderson + 1, 2 * n))
    AF = np.empty_like(AX)
    count = 0
    plain_until = 0  # outer iterations up to this one take plain damped steps
    since = 0  # the iteration after which the damping (and Anderson history) last changed
    w_since = 0  # ... the damping alone (the noise floor's window spans Anderson restarts)
    extended = False
    fields: list[tuple[np.ndarray, np.ndarray]] = []
    floor: dict[str, float] | None = None
    for it in range(1, int(EXTEND_OUTER * max_outer) + 1):
        if it > max_outer:
            # past max_outer only while the trend still reaches the tolerances within the cap
            need = iterations_to_converge(hist)
            if not it - 1 + need <= EXTEND_OUTER * max_outer:
                break
            if not extended:
                extended = True
                actions.append(f"iteration {it - 1}: not converged but converging (the changes' trend "
                               f"meets the tolerances in about {need:.0f} more): max_outer {max_outer} extended")
        # a solve at a stationary surface can take many minutes (docs/thermal.md, "Limits")
        check_deadline(f"{contact.label} outer iteration {it}")
        ti = time.perf_counter()
        a_new, c_new = contact.factors(thermal)
        if not (np.all(np.isfinite(a_new)) and np.all(a_new > 0) and np.all(np.isfinite(c_new)) and np.all(c_new > 0)):
            raise ConvergenceError(f"TEHL outer iteration {it}: non-finite or non-positive across-film factors",
                                   None, OUTER_HINT)
        dfac = float(max(np.max(np.abs(np.log(a_new / a))), np.max(np.abs(np.log(c_new / c)))))
        w_used = w
        x_old = np.concatenate([np.log(a).ravel(), np.log(c).ravel()])
        g = (1.0 - w) * x_old + w * np.concatenate([np.log(a_new).ravel(), np.log(c_new).ravel()])
        if anderson > 0:
            x_mix, count = _anderson_step(AX, AF, count, x_old, g, anderson)
            if it <= plain_until:  # the history records the plain steps (see below)
                x_mix = g
        else:
            x_mix = g
        # an Anderson step (a single history entry gives g itself)
        extrapolated = anderson > 0 and count >= 2 and it > plain_until
        x_new = np.concatenate([np.log(a_new).ravel(), np.log(c_new).ravel()])
        while True:
            a = np.exp(x_mix[:n]).reshape(shape)
            c = np.exp(x_mix[n:]).reshape(shape)
            try:
                new = multilevel_step(contact, a, c, state, it, tol_H)
                break
            except ConvergenceError as exc:
                # a multilevel solve that fails on a large step of the factors: a smaller step
                # from the same iterate (plain damping, Anderson history restarted)
                if w <= MIN_RELAX:
                    raise
                w = max(0.5 * w, MIN_RELAX)
                w_used = w
                count, since, w_since = 0, it, it
                x_mix = (1.0 - w) * x_old + w * x_new
                actions.append(f"iteration {it}: multilevel solve failed ({str(exc).splitlines()[0][:120]}); "
                               f"retried with the under-relaxation halved to {w:g}")
        if not (np.all(np.isfinite(new.P)) and np.all(np.isfinite(new.H))):
            raise ConvergenceError(f"TEHL outer iteration {it}: NaN in the pressure or film", None, OUTER_HINT)
        thermal_new, T_new = contact.thermal(new)
        # relative L2 change: the max norm is dominated by the spike, which the algebraic
        # tolerance of each multilevel solve leaves uncertain at the 1e-4 level
        dP = float(np.linalg.norm(new.P - state.P) / np.linalg.norm(new.P))
        dHc = abs(new.Hc - state.Hc) / new.Hc
        dHm = abs(new.Hm - state.Hm) / new.Hm
        dT = float(np.max(np.abs(T_new - T)))
        outer.append({"iteration": it, "dP": dP, "dHc": dHc, "dHm": dHm, "dT": dT, "factor_change": dfac,
                      "relax": w_used, "cycles": int(new.extra.get("cycles", 0)), "Hc": new.Hc, "Hm": new.Hm,
                      "T_max": float(np.max(T_new)), "friction": float(contact.friction(thermal_new)),
                      "wall_s": time.perf_counter() - ti})
        if not all(math.isfinite(v) for v in (dP, dHc, dHm, dT)):
            raise ConvergenceError(f"TEHL outer iteration {it}: NaN in the pressure, film or temperature",
                                   None, OUTER_HINT)
        state_prev = state
        state, thermal, T = new, thermal_new, T_new
        # changes of a damped iteration understate its distance to the fixed point: divided
        # by the damping, a small under-relaxation cannot pass for convergence
        # the films cannot settle below the algebraic uncertainty of the inner solves
        noise = max(float(new.extra.get("film_noise", 0.0)), float(state_prev.extra.get("film_noise", 0.0)))
        outer[-1]["film_noise"] = noise
        raw_films.append(max(dP / tol_P, max(dHc, dHm) / max(tol_H, 2.0 * noise)))
        raw.append(max(raw_films[-1], dT / tol_T))
        hist.append(raw[-1] / w_used)
        if hist[-1] < 1.0:
            converged = True
            break
        fields = (fields + [(state.P.copy(), np.array(T, copy=True))])[-NOISE_WINDOW:]
        if it - w_since >= NOISE_WINDOW and w_used == w:
            floor = settled(outer, fields, raw, w, tol_P, max(tol_H, 2.0 * noise), tol_T)
            if floor is not None:
                converged = True
                actions.append(
                    f"iteration {it}: settled at the inner solves' noise floor: over {NOISE_WINDOW} "
                    f"iterations at {w:g} the changes stay within {max(raw[-NOISE_WINDOW:]):.2g} tolerances "
                    f"and their drift meets the tolerances (P {floor['P']:.2g}, T {floor['T']:.2g} K, Hc "
                    f"{floor['Hc']:.2g}, Hm {floor['Hm']:.2g}); the window's spread is the iteration error")
                break
        # growth is judged on the changes themselves (divided by the damping they would grow
        # by themselves each time the damping halves); growth near the tolerance is the
        # algebraic noise of the inner solves, not divergence
        # (a trend rising over many iterations is growth near the tolerances too; it halves the
        # damping but never declares divergence)
        growing = grows(raw) or (len(raw) >= 2 and raw[-1] > 2.0 and w > MIN_RELAX and creeping(raw, it - since))
        if growing and extrapolated:
            # an Anderson step that overshot: the history restarts and the next `anderson`
            # steps are plain damped ones at the same under-relaxation, so that the next
            # extrapolation has that many secants; one secant of inner solves with algebraic
            # noise overshoots again (page63 2000 N at 20 m/s, S = 0: dP alternating 2e-5 /
            # 1e-3 down to MIN_RELAX, docs/thermal.md)
            count, plain_until, since = 0, it + anderson, it
            actions.append(f"iteration {it}: changes grew ({raw[-2]:.3g} -> {raw[-1]:.3g} tolerances) "
                           f"after an Anderson step; {anderson} plain steps ({w:g}) before the next")
        elif growing:
            if w <= MIN_RELAX:
                floor = films_settled(outer, fields, tol_P, tol_H, tol_T)
                if floor is not None:
                    converged = True
                    actions.append(films_settled_note(it, floor))
                    break
                if not grows(raw_films):
                    # only the temperature grows (a node the films do not feel, at a stationary
                    # surface): iterate on, within max_outer, until the films settle
                    if not t_only:
                        t_only = True
                        actions.append(f"iteration {it}: the temperature changes grow ({dT:.3g} K) at the "
                                       f"smallest under-relaxation while P and the films do not; iterating on")
                    continue
                rep = ConvergenceReport(converged=False, message="diverged", iterations=len(outer),
                                        residual_history=np.array(hist), tolerances={"P": tol_P, "H": tol_H, "T_K": tol_T},
                                        wall_s=time.perf_counter() - t0, extra={"outer": outer, "actions": actions})
                raise ConvergenceError(
                    f"TEHL outer iteration diverged: at iteration {it} the changes (dP {dP:.3g}, dHc "
                    f"{dHc:.3g}, dHm {dHm:.3g}, dT {dT:.3g} K) grew with the under-relaxation already at "
                    f"{MIN_RELAX:g}", rep, OUTER_HINT)
            w = max(0.5 * w, MIN_RELAX)
            count, since, w_since = 0, it, it  # restart the Anderson history with the new damping
            actions.append(f"iteration {it}: changes grew ({raw[-2]:.3g} -> {raw[-1]:.3g} tolerances); "
                           f"under-relaxation halved to {w:g}")
    report = ConvergenceReport(
        converged=converged,
        message="converged" if converged else f"outer iteration not converged in {len(outer)} iterations",
        iterations=len(outer), residual_history=np.array(hist),
        tolerances={"P": tol_P, "H": tol_H, "T_K": tol_T},
        wall_s=time.perf_counter() - t0, extra={"outer": outer, "actions": actions})
    if floor is not None:
        report.extra["noise_floor"] = floor
    if not converged:
        floor = films_settled(outer, fields, tol_P, tol_H, tol_T)
        if floor is not None:
            converged = True
            actions.append(films_settled_note(len(outer), floor))
            report.converged, report.message = True, "converged"
            report.extra["noise_floor"] = floor
    if not converged:
        last = outer[-1]
        raise ConvergenceError(
            f"TEHL: the outer iteration did not converge in {len(outer)} iterations (last dP "
            f"{last['dP']:.3g}, dHc {last['dHc']:.3g}, dHm {last['dHm']:.3g}, dT {last['dT']:.3g} K)",
            report, OUTER_HINT)
    report.extra["actions"] = contact.notes + actions
    return OuterOutcome(state, thermal, a, c, outer, report)
