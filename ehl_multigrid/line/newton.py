"""Coarsest-grid solver: damped semismooth Newton on the full discrete system.

Unknowns ``(P_1 .. P_{n-2}, H0)``; equations: the Reynolds complementarity
``min(P_i, s_i r_i) = 0`` (``r = f - L(P)``, ``s_i = 1/|dL_i/dP_i|``, cavitation as complementarity)
and the load ``h sum P = g``. The Jacobian is dense (the film depends on every pressure through
the log kernel, and ``eps`` on the film, density and viscosity), so this is only used on the
coarsest grid (tens to a few hundred points), where it makes the bottom of every cycle
an exact solve including the film constant H0.
"""

from __future__ import annotations

import warnings

import numpy as np
import scipy.linalg

from .discrete import fluid_state, reynolds_residual, wedge_coefficients
from .level import LineLevel


class NewtonFailure(RuntimeError):
    """The coarse Newton iteration did not converge (the caller tries something else)."""


def _system(level: LineLevel, P: np.ndarray, H0: float, Kmat: np.ndarray, jacobian: bool):
    # overflow/NaN in a trial step is detected by the caller (non-finite merit -> step halved)
    with np.errstate(all="ignore"):
        return _system_unguarded(level, P, H0, Kmat, jacobian)


def _system_unguarded(level: LineLevel, P: np.ndarray, H0: float, Kmat: np.ndarray, jacobian: bool):
    n, h = level.n, level.h
    W = level.deform(P)
    H, rho, drho, lne, dlne, eps = fluid_state(P, W, level.X, H0, level.par, level.lam, level.elastic)
    r, _ = reynolds_residual(P, H, rho, eps, h, level.f, level.order)
    if not jacobian:
        return r, None
    inv_pi = 1.0 / np.pi
    dH = -Kmat * inv_pi if level.elastic else np.zeros((n, n))
    pos = H > 0.0
    Hs = np.where(pos, H, 1.0)
    # columns: P_0 .. P_{n-1}, then H0
    deps = np.zeros((n, n + 1))
    deps[:, :n] = (eps * 3.0 / Hs)[:, None] * dH
    deps[np.arange(n), np.arange(n)] += eps * (drho / rho - dlne)
    deps[:, n] = eps * 3.0 / Hs
    deps[~pos] = 0.0
    dq = np.zeros((n, n + 1))
    dq[:, :n] = rho[:, None] * dH
    dq[np.arange(n), np.arange(n)] += drho * H
    dq[:, n] = rho
    ih2 = 1.0 / (h * h)
    dL = np.zeros((n, n + 1))
    i = np.arange(1, n - 1)
    ep = 0.5 * (eps[i] + eps[i + 1])
    em = 0.5 * (eps[i] + eps[i - 1])
    dep = 0.5 * (deps[i] + deps[i + 1])
    dem = 0.5 * (deps[i] + deps[i - 1])
    dL[i] = ih2 * (dep * (P[i + 1] - P[i])[:, None] - dem * (P[i] - P[i - 1])[:, None])
    dL[i, i + 1] += ih2 * ep
    dL[i, i] -= ih2 * (ep + em)
    dL[i, i - 1] += ih2 * em
    for k in range(1, n - 1):
        c0, c1, c2 = wedge_coefficients(k, level.order)
        dL[k] -= (c0 * dq[k] + c1 * dq[k - 1] + (c2 * dq[k - 2] if c2 != 0.0 else 0.0)) / h
    return r, dL


def _phi(level: LineLevel, P: np.ndarray, r: np.ndarray, s: np.ndarray, P_frozen: np.ndarray) -> np.ndarray:
    inner = slice(1, level.n - 1)
    phi = np.empty(level.n - 1)
    with np.errstate(all="ignore"):
        phi[:-1] = np.minimum(P[inner], s * r[inner])
    fr = level.frozen[inner]
    phi[:-1][fr] = (P[inner] - P_frozen[inner])[fr]
    phi[-1] = level.h * np.sum(P) - level.g
    return phi


def newton_solve(level: LineLevel, max_iter: int = 80, tol: float = 1e-10) -> int:
    """Solve the level's problem in place (``level.P``, ``level.H0``); return iterations.

    Raises :class:`NewtonFailure` when the damped iteration stalls or the film collapses.
    """
    n = level.n
    Kmat = scipy.linalg.toeplitz(level.kernel) if level.elastic else np.zeros((n, n))
    P, H0 = level.P.copy(), float(level.H0)
    P_frozen = level.P.copy()
    inner = np.arange(1, n - 1)
    frozen = level.frozen[1:-1]
    for it in range(1, max_iter + 1):
        r, dL = _system(level, P, H0, Kmat, True)
        diag = np.abs(dL[inner, inner])
        s = 1.0 / np.maximum(diag, 1e-300)
        phi = _phi(level, P, r, s, P_frozen)
        with np.errstate(all="ignore"):
            norm0 = float(np.linalg.norm(phi))
        if not np.isfinite(norm0):
            raise NewtonFailure("non-finite residual in the coarse Newton iteration")
        if np.max(np.abs(phi)) < tol:
            level.P, level.H0 = P, H0
            return it - 1
        J = np.zeros((n - 1, n - 1))
        active = (P[inner] <= s * r[inner]) | frozen
        rows = -s[:, None] * dL[inner][:, np.r_[inner, n]]  # d(s r)/dx = -s dL/dx
        J[:-1] = rows
        J[:-1][active] = 0.0
        J[np.flatnonzero(active), np.flatnonzero(active)] = 1.0
        J[-1, :-1] = level.h
        try:
            # scipy's LAPACK: numpy's threaded OpenBLAS is ~700x slower on a busy 2-core box
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", scipy.linalg.LinAlgWarning)
                step = scipy.linalg.solve(J, -phi, check_finite=False)
        except (np.linalg.LinAlgError, scipy.linalg.LinAlgError, ValueError) as exc:
            raise NewtonFailure(f"singular coarse Jacobian: {exc}") from None
        t = 1.0
        while True:
            Pt = P.copy()
            Pt[inner] += t * step[:-1]
            H0t = H0 + t * step[-1]
            rt, _ = _system(level, Pt, H0t, Kmat, False)
            with np.errstate(all="ignore"):
                norm = float(np.linalg.norm(_phi(level, Pt, rt, s, P_frozen)))
            if np.isfinite(norm) and norm <= (1.0 - 1e-4 * t) * norm0:
                break
            t *= 0.5
            if t < 1e-6:
                if np.max(np.abs(phi)) < 1e3 * tol:  # round-off floor reached: accept
                    level.P, level.H0 = P, H0
                    return it - 1
                raise NewtonFailure(f"coarse Newton line search failed at iteration {it} "
                                    f"(|phi| = {norm0:.3g})")
        P, H0 = Pt, H0t
    raise NewtonFailure(f"coarse Newton did not converge in {max_iter} iterations")
