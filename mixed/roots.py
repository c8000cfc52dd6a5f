"""Vectorised bracketed root finding (Illinois regula falsi with bisection safeguard).

Used for the load-sharing unknown ``x = ln(gamma1 - 1)``: many independent monotone scalar
equations (one per sum velocity) solved together, each inside its own bracket, so no point can
wander off or oscillate the way a fixed-point iteration can.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np


@dataclass
class BracketResult:
    """Roots and what it took to find them."""

    x: np.ndarray
    f: np.ndarray
    converged: np.ndarray
    iterations: int
    width_history: list[float] = field(default_factory=list)
    residual_history: list[float] = field(default_factory=list)


def bracketed_root(
    func: Callable[[np.ndarray, np.ndarray], np.ndarray],
    lo: np.ndarray,
    hi: np.ndarray,
    f_lo: np.ndarray,
    f_hi: np.ndarray,
    *,
    xtol: float = 1e-12,
    maxiter: int = 200,
) -> BracketResult:
    """Solve ``func(x, idx) = 0`` for each element, given brackets with ``f_lo * f_hi <= 0``.

    ``func`` receives the trial points and the indices of the elements they belong to (so it
    can evaluate only unfinished elements). Illinois steps, with a bisection step whenever the
    bracket did not shrink by half in two steps. Stops per element when the bracket is narrower
    than ``xtol * max(1, |x|)`` or the residual is exactly zero.
    """
    a = np.array(lo, dtype=float)
    b = np.array(hi, dtype=float)
    fa = np.array(f_lo, dtype=float)
    fb = np.array(f_hi, dtype=float)
    if np.any(np.sign(fa) * np.sign(fb) > 0):
        raise ValueError("bracketed_root: some brackets do not enclose a sign change")
    n = a.size
    x = np.where(np.abs(fa) <= np.abs(fb), a, b)
    fx = np.where(np.abs(fa) <= np.abs(fb), fa, fb)
    done = (fa == 0.0) | (fb == 0.0) | (np.abs(b - a) <= xtol * np.maximum(1.0, np.abs(x)))
    side = np.zeros(n, dtype=int)  # which end was kept last: -1 a, +1 b
    last_width = np.abs(b - a)
    res = BracketResult(x, fx, done.copy(), 0)
    it = 0
    for it in range(1, maxiter + 1):
        act = np.flatnonzero(~done)
        if act.size == 0:
            it -= 1
            break
        A, B, FA, FB = a[act], b[act], fa[act], fb[act]
        with np.errstate(divide="ignore", invalid="ignore"):
            c = B - FB * (B - A) / (FB - FA)
        width = np.abs(B - A)
        bisect = ~np.isfinite(c) | (c <= np.minimum(A, B)) | (c >= np.maximum(A, B))
        if it % 3 == 0:  # safeguard: force a halving when the bracket shrinks slowly
            bisect |= width > 0.5 * last_width[act]
            last_width[act] = width
        c = np.where(bisect, 0.5 * (A + B), c)
        fc = np.asarray(func(c, act), dtype=float)
        if not np.all(np.isfinite(fc)):
            raise FloatingPointError("bracketed_root: residual is not finite")
        same_as_a = np.sign(fc) == np.sign(FA)
        # replace the end with the same sign; Illinois: halve the kept end's value if kept twice
        newA = np.where(same_as_a, c, A)
        newFA = np.where(same_as_a, fc, FA)
        newB = np.where(same_as_a, B, c)
        newFB = np.where(same_as_a, FB, fc)
        kept = np.where(same_as_a, 1, -1)
        twice = (kept == side[act]) & ~bisect
        newFB = np.where(twice & (kept == 1), 0.5 * newFB, newFB)
        newFA = np.where(twice & (kept == -1), 0.5 * newFA, newFA)
        side[act] = kept
        a[act], fa[act], b[act], fb[act] = newA, newFA, newB, newFB
        x[act] = c
        fx[act] = fc
        w = np.abs(newB - newA)
        done[act] = (fc == 0.0) | (w <= xtol * np.maximum(1.0, np.abs(c)))
        res.width_history.append(float(np.max(np.abs(b - a)[~done], initial=0.0)))
        res.residual_history.append(float(np.max(np.abs(fx))))
    res.x, res.f, res.converged, res.iterations = x, fx, done, it
    return res
