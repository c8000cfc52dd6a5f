"""The outer (fixed-point) iteration of a TEHL solve, shared by line and point contacts.

One outer iteration: the across-film factors of the last thermal solution, damped in their
logarithm and Anderson-mixed, go to the multilevel solve of the pressure and film; the thermal
solve on the new pressure and film gives the next temperature field. It stops when the changes
of P (relative L2 norm), of the films (Hc, Hm) and of T (max, kelvin) between two iterations,
divided by the iteration's damping, are all below their tolerances (the film tolerance
widened to twice the films' algebraic uncertainty when an inner solve reports one).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ehl_multigrid.model.convergence import ConvergenceReport
from ehl_multigrid.model.errors import ConvergenceError

from ..kernels import _anderson_step

#: smallest under-relaxation of the outer iteration before it is declared divergent
MIN_RELAX = 1.0 / 64.0

OUTER_HINT = ("lower relax (under-relaxation of the across-film factors), raise max_outer, or "
              "check the thermal loading (oil temperature limits, slip, speed)")


@dataclass
class Iterate:
    """Pressure and film of one outer iteration (Venner's P, H; Moes Hc, Hm)."""

    P: np.ndarray
    H: np.ndarray
    H0: float
    Hc: float
    Hm: float
    extra: dict[str, Any] = field(default_factory=dict)


@dataclass
class OuterOutcome:
    state: Iterate
    thermal: Any
    a: np.ndarray
    c: np.ndarray
    outer: list[dict[str, float]]
    report: ConvergenceReport


def outer_iteration(
    state: Iterate, thermal: Any, T: np.ndarray, a: np.ndarray, c: np.ndarray, *,
    factors: Callable[[Any], tuple[np.ndarray, np.ndarray]],
    ehl: Callable[[np.ndarray, np.ndarray, Iterate, int], Iterate],
    solve_thermal: Callable[[Iterate], tuple[Any, np.ndarray]],
    relax: float, anderson: int, max_outer: int, tol_P: float, tol_H: float, tol_T: float,
) -> OuterOutcome:
    """Run the outer iteration from ``state`` and its thermal solution ``thermal`` (temperature
    array ``T``) with the factors ``a``, ``c`` in use.

    ``factors(thermal) -> (a, c)``; ``ehl(a, c, state, iteration) -> Iterate`` (raises on
    failure); ``solve_thermal(state) -> (thermal, T)``. Raises :class:`ConvergenceError` on
    non-finite values, divergence (changes growing at the smallest damping) or when
    ``max_outer`` iterations do not meet the tolerances.
    """
    t0 = time.perf_counter()
    shape = a.shape
    n = a.size
    outer: list[dict[str, float]] = []
    hist: list[float] = []
    raw: list[float] = []
    actions: list[str] = []
    converged = False
    w = relax
    AX = np.empty((anderson + 1, 2 * n))
    AF = np.empty_like(AX)
    count = 0
    for it in range(1, max_outer + 1):
        ti = time.perf_counter()
        a_new, c_new = factors(thermal)
        if not (np.all(np.isfinite(a_new)) and np.all(a_new > 0) and np.all(np.isfinite(c_new)) and np.all(c_new > 0)):
            raise ConvergenceError(f"TEHL outer iteration {it}: non-finite or non-positive across-film factors",
                                   None, OUTER_HINT)
        dfac = float(max(np.max(np.abs(np.log(a_new / a))), np.max(np.abs(np.log(c_new / c)))))
        w_used = w
        x_old = np.concatenate([np.log(a).ravel(), np.log(c).ravel()])
        g = (1.0 - w) * x_old + w * np.concatenate([np.log(a_new).ravel(), np.log(c_new).ravel()])
        if anderson > 0:
            x_mix, count = _anderson_step(AX, AF, count, x_old, g, anderson)
        else:
            x_mix = g
        x_new = np.concatenate([np.log(a_new).ravel(), np.log(c_new).ravel()])
        while True:
            a = np.exp(x_mix[:n]).reshape(shape)
            c = np.exp(x_mix[n:]).reshape(shape)
            try:
                new = ehl(a, c, state, it)
                break
            except ConvergenceError as exc:
                # a multilevel solve that fails on a large step of the factors: a smaller step
                # from the same iterate (plain damping, Anderson history restarted)
                if w <= MIN_RELAX:
                    raise
                w = max(0.5 * w, MIN_RELAX)
                w_used = w
                count = 0
                x_mix = (1.0 - w) * x_old + w * x_new
                actions.append(f"iteration {it}: multilevel solve failed ({str(exc).splitlines()[0][:120]}); "
                               f"retried with the under-relaxation halved to {w:g}")
        if not (np.all(np.isfinite(new.P)) and np.all(np.isfinite(new.H))):
            raise ConvergenceError(f"TEHL outer iteration {it}: NaN in the pressure or film", None, OUTER_HINT)
        thermal_new, T_new = solve_thermal(new)
        # relative L2 change: the max norm is dominated by the spike, which the algebraic
        # tolerance of each multilevel solve leaves uncertain at the 1e-4 level
        dP = float(np.linalg.norm(new.P - state.P) / np.linalg.norm(new.P))
        dHc = abs(new.Hc - state.Hc) / new.Hc
        dHm = abs(new.Hm - state.Hm) / new.Hm
        dT = float(np.max(np.abs(T_new - T)))
        outer.append({"iteration": it, "dP": dP, "dHc": dHc, "dHm": dHm, "dT": dT, "factor_change": dfac,
                      "relax": w_used, "cycles": int(new.extra.get("cycles", 0)), "Hc": new.Hc, "Hm": new.Hm,
                      "T_max": float(np.max(T_new)), "wall_s": time.perf_counter() - ti})
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
        raw.append(max(dP / tol_P, max(dHc, dHm) / max(tol_H, 2.0 * noise), dT / tol_T))
        hist.append(raw[-1] / w_used)
        if hist[-1] < 1.0:
            converged = True
            break
        # growth is judged on the changes themselves (divided by the damping they would grow
        # by themselves each time the damping halves); growth near the tolerance is the
        # algebraic noise of the inner solves, not divergence
        growing = len(raw) >= 2 and raw[-1] > 10.0 and (raw[-1] > 2.0 * raw[-2]
                                      or (len(raw) >= 3 and raw[-1] > raw[-2] > raw[-3]))
        if growing:
            if w <= MIN_RELAX:
                rep = ConvergenceReport(converged=False, message="diverged", iterations=len(outer),
                                        residual_history=np.array(hist), tolerances={"P": tol_P, "H": tol_H, "T_K": tol_T},
                                        wall_s=time.perf_counter() - t0, extra={"outer": outer, "actions": actions})
                raise ConvergenceError(
                    f"TEHL outer iteration diverged: at iteration {it} the changes (dP {dP:.3g}, dHc "
                    f"{dHc:.3g}, dHm {dHm:.3g}, dT {dT:.3g} K) grew with the under-relaxation already at "
                    f"{MIN_RELAX:g}", rep, OUTER_HINT)
            w = max(0.5 * w, MIN_RELAX)
            count = 0  # restart the Anderson history with the new damping
            actions.append(f"iteration {it}: changes grew ({raw[-2]:.3g} -> {raw[-1]:.3g} tolerances); "
                           f"under-relaxation halved to {w:g}")
    report = ConvergenceReport(
        converged=converged,
        message="converged" if converged else f"outer iteration not converged in {max_outer} iterations",
        iterations=len(outer), residual_history=np.array(hist),
        tolerances={"P": tol_P, "H": tol_H, "T_K": tol_T},
        wall_s=time.perf_counter() - t0, extra={"outer": outer, "actions": actions})
    if not converged:
        last = outer[-1]
        raise ConvergenceError(
            f"TEHL: the outer iteration did not converge in {max_outer} iterations (last dP "
            f"{last['dP']:.3g}, dHc {last['dHc']:.3g}, dHm {last['dHm']:.3g}, dT {last['dT']:.3g} K)",
            report, OUTER_HINT)
    return OuterOutcome(state, thermal, a, c, outer, report)
