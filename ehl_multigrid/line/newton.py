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
from collections.abc import Callable

import numpy as np
import scipy.linalg
from numba import njit

from ..multigrid.flux import eps_face_d
from ..multigrid.threads import serial_blas
from .discrete import fluid_state, reynolds_residual, wedge_coefficients
from .level import LineLevel


class NewtonFailure(RuntimeError):
    """The coarse Newton iteration did not converge (the caller tries something else)."""


def _fluid(level: LineLevel, P: np.ndarray, H0: float):
    """Residual ``r`` and the film state ``(H, rho, drho, dlne, eps)`` the Jacobian needs."""
    # overflow/NaN in a trial step is detected by the caller (non-finite merit -> step halved)
    with np.errstate(all="ignore"):
        W = level.deform(P)
        H, rho, drho, lne, dlne, eps = fluid_state(P, W, level.X, H0, level.par, level.lam,
                                                   level.elastic)
        factored = getattr(level, "factored", None)
        if factored is not None:
            # generalised Reynolds (thermal EHL): frozen flow and Couette density factors; the
            # Jacobian follows from eps, rho, drho and dlne
            eps, rho, drho, dlne = factored(eps, rho, drho, lne, dlne)
        r, _ = reynolds_residual(P, H, rho, eps, level.h, level.f, level.order, level.face)
    return r, (H, rho, drho, dlne, eps)


def _system(level: LineLevel, P: np.ndarray, H0: float, jacobian: bool):
    """Residual ``r`` and, with ``jacobian``, the rows ``dr/d(P_1..P_{n-2}, H0)`` of the inner
    points (negated: ``dL``). A level with terms of its own (the squeeze term of a time step)
    gives both by its ``newton_system(P, H0, jacobian)``."""
    own = getattr(level, "newton_system", None)
    if own is not None:
        return own(P, H0, jacobian)
    r, (H, rho, drho, dlne, eps) = _fluid(level, P, H0)
    if not jacobian:
        return r, None
    return r, reynolds_jacobian(P, H, rho, drho, dlne, eps, level.kernel, level.h,
                                level.order, level.elastic, level.face)


def reynolds_jacobian(P, H, rho, drho, dlne, eps, kernel, h, order, elastic, face=0):
    """``dL_i/dx_j`` of the discrete Reynolds operator (discrete.py) for the inner points
    ``i = 1 .. n-2`` and the unknowns ``x = (P_1 .. P_{n-2}, H0)``: an ``(n-2, n-1)`` array.

    ``eps`` depends on ``P_j`` through the film (``dH_m/dP_j = -K_|m-j|/pi``), the density and
    the viscosity; ``rho H`` through the film and the density; ``H0`` shifts every film.
    Points with ``H <= 0`` carry ``eps = 0`` and no ``eps`` derivative."""
    return reynolds_jacobian_block(P, H, rho, drho, dlne, eps, kernel, h, order, elastic,
                                   1, P.shape[0] - 1, True, face)


@njit(cache=True)
def reynolds_jacobian_block(P, H, rho, drho, dlne, eps, kernel, h, order, elastic, lo, hi, h0, face=0):
    """Rows ``i = lo .. hi-1`` and pressure columns ``j = lo .. hi-1`` of
    :func:`reynolds_jacobian` (``1 <= lo < hi <= n-1``), plus the ``H0`` column when ``h0``:
    the block a windowed Newton step needs (:func:`local_newton`)."""
    n = P.shape[0]
    m = hi - lo
    out = np.zeros((m, m + 1 if h0 else m))
    ih2 = 1.0 / (h * h)
    inv_pi = 1.0 / np.pi
    # per-point factors: d eps_k = a_k dH_k + b_k dP_k, d(rho H)_k = rho_k dH_k + c_k dP_k
    a = np.zeros(n)
    b = np.zeros(n)
    c = np.zeros(n)
    for k in range(max(lo - 2, 0), min(hi + 1, n)):
        if H[k] > 0.0:
            a[k] = 3.0 * eps[k] / H[k]
            b[k] = eps[k] * (drho[k] / rho[k] - dlne[k])
        c[k] = drho[k] * H[k]
    for i in range(lo, hi):
        row = i - lo
        ep, dep_i, dep_n = eps_face_d(eps[i], eps[i + 1], face)
        em, dem_i, dem_n = eps_face_d(eps[i], eps[i - 1], face)
        # Poiseuille response to eps_i, eps_(i+1) (face i+1/2) and eps_i, eps_(i-1) (face i-1/2)
        gpi = dep_i * ih2 * (P[i + 1] - P[i])
        gpn = dep_n * ih2 * (P[i + 1] - P[i])
        gmi = dem_i * ih2 * (P[i] - P[i - 1])
        gmn = dem_n * ih2 * (P[i] - P[i - 1])
        c0, c1, c2 = wedge_coefficients(i, order)
        w0, w1, w2 = c0 / h, c1 / h, c2 / h
        # film response: pressure columns
        if elastic:
            for j in range(lo, hi):
                dHi = -kernel[abs(i - j)] * inv_pi
                dHp = -kernel[abs(i + 1 - j)] * inv_pi
                dHm = -kernel[abs(i - 1 - j)] * inv_pi
                if gpi == gpn and gmi == gmn:  # symmetric faces (arithmetic): Venner's grouping
                    v = gpi * (a[i] * dHi + a[i + 1] * dHp) - gmi * (a[i] * dHi + a[i - 1] * dHm)
                else:
                    v = gpi * a[i] * dHi + gpn * a[i + 1] * dHp - gmi * a[i] * dHi - gmn * a[i - 1] * dHm
                v -= w0 * rho[i] * dHi + w1 * rho[i - 1] * dHm
                if c2 != 0.0:
                    v -= w2 * rho[i - 2] * (-kernel[abs(i - 2 - j)] * inv_pi)
                out[row, j - lo] = v
        # local (diagonal) parts: eps and rho through P_k itself, and the Poiseuille stencil
        for k in range(i - 2, i + 2):
            if k < lo or k >= hi:
                continue
            v = 0.0
            if k == i:
                v += (gpi - gmi) * b[i] - ih2 * (ep + em) - w0 * c[i]
            elif k == i + 1:
                v += gpn * b[i + 1] + ih2 * ep
            elif k == i - 1:
                v += -gmn * b[i - 1] + ih2 * em - w1 * c[i - 1]
            elif k == i - 2:
                v += -w2 * c[i - 2]
            out[row, k - lo] += v
        if h0:
            # H0: every film moves by dH0
            if gpi == gpn and gmi == gmn:
                dP0 = gpi * (a[i] + a[i + 1]) - gmi * (a[i] + a[i - 1])
            else:
                dP0 = gpi * a[i] + gpn * a[i + 1] - gmi * a[i] - gmn * a[i - 1]
            out[row, m] = dP0 \
                - (w0 * rho[i] + w1 * rho[i - 1] + (w2 * rho[i - 2] if c2 != 0.0 else 0.0))
    return out


def _phi(level: LineLevel, P: np.ndarray, r: np.ndarray, s: np.ndarray, P_frozen: np.ndarray) -> np.ndarray:
    inner = slice(1, level.n - 1)
    phi = np.empty(level.n - 1)
    with np.errstate(all="ignore"):
        phi[:-1] = np.minimum(P[inner], s * r[inner])
    fr = level.frozen[inner]
    phi[:-1][fr] = (P[inner] - P_frozen[inner])[fr]
    phi[-1] = level.h * np.sum(P) - level.g
    return phi


def newton_solve(level: LineLevel, max_iter: int = 80, tol: float = 1e-10, keep: bool = False,
                 single: bool = False, check: Callable[[int], None] | None = None) -> int:
    """Solve the level's problem in place (``level.P``, ``level.H0``); return the number of
    Jacobian factorisations (Newton steps; the chord steps that reuse a factorisation while it
    contracts by :data:`CHORD_CONTRACTION` per step are not counted, ``max_iter`` counts all).
    ``keep``: start with chord steps on the factorisation the last ``keep`` solve of this level
    left, and leave the last one for the next (the coarsest grid of the cycles, whose problem
    changes little from cycle to cycle; docs/accuracy.md). ``single``: factorise in single precision on
    grids of :data:`SINGLE_FROM` points and more (a start, which the cycles refine: its
    chord steps converge linearly and stop near ``tol`` instead of far below it). ``check(it)``
    runs before each iteration ``it``: it may raise to stop the solve (a time budget spent) or
    report progress (a dense solve on a fine grid can take a minute).

    Raises :class:`NewtonFailure` when the damped iteration stalls or the film collapses.
    The dense factorisations run on one BLAS thread (:func:`serial_blas`).
    """
    with serial_blas():
        return _newton_solve(level, max_iter, tol, keep, single, check)


#: a factorised Jacobian is reused (chord steps) while each step lowers the merit |phi| by at
#: least this factor; a slower step, or a failed line search, refreshes it (docs/accuracy.md,
#: "What an accuracy costs")
CHORD_CONTRACTION = 0.2
#: start grids of at least this many points may factorise their Jacobian in single precision
#: (``newton_solve(single=True)``; half the time of a 2049-point LU; the residual and the line
#: search stay in double: docs/accuracy.md)
SINGLE_FROM = 1025


def _jacobian(level: LineLevel, P: np.ndarray, r: np.ndarray, dL: np.ndarray, s: np.ndarray,
              frozen: np.ndarray) -> np.ndarray:
    """The semismooth Jacobian of ``phi`` at ``P``: ``d(s r)/dx`` on the inactive rows, the
    identity on the active (cavitated or frozen) ones, the load row."""
    n = level.n
    inner = np.arange(1, n - 1)
    J = np.empty((n - 1, n - 1))
    active = (P[inner] <= s * r[inner]) | frozen
    np.multiply(dL, -s[:, None], out=J[:-1])  # d(s r)/dx = -s dL/dx
    J[:-1][active] = 0.0
    J[np.flatnonzero(active), np.flatnonzero(active)] = 1.0
    J[-1, :-1] = level.h
    J[-1, -1] = 0.0  # the load does not depend on H0
    return J


def _newton_solve(level: LineLevel, max_iter: int, tol: float, keep: bool = False,
                  single: bool = False, check: Callable[[int], None] | None = None) -> int:
    n = level.n
    P, H0 = level.P.copy(), float(level.H0)
    P_frozen = level.P.copy()
    inner = np.arange(1, n - 1)
    frozen = level.frozen[1:-1]
    lu, s = getattr(level, "kept_factor", None) if keep else None, None
    if lu is not None:
        lu, s = lu
    level.kept_factor = None
    # the iterate of the last factorisation: chord steps that lead where the fresh scaling is
    # not finite are undone, and the solve goes on with plain Newton steps
    chord, last_fresh, chorded = True, (P, H0), False
    factorised = 0
    single = single and n >= SINGLE_FROM
    for it in range(1, max_iter + 1):
        if check is not None:
            check(it)
        fresh = lu is None
        r, dL = _system(level, P, H0, fresh)
        if fresh:
            s = 1.0 / np.maximum(np.abs(np.diagonal(dL)), 1e-300)
        phi = _phi(level, P, r, s, P_frozen)
        with np.errstate(all="ignore"):
            norm0 = float(np.linalg.norm(phi))
        if not np.isfinite(norm0):
            if chorded:
                (P, H0), chord, chorded = last_fresh, False, False
                continue
            raise NewtonFailure("non-finite residual in the coarse Newton iteration")
        if fresh:
            last_fresh, chorded = (P, H0), False
        if np.max(np.abs(phi)) < tol:
            level.P, level.H0 = P, H0
            if keep and lu is not None:
                level.kept_factor = (lu, s)
            return factorised
        if fresh:
            try:
                # scipy's LAPACK on one thread: threaded OpenBLAS is 25-700x slower on a busy
                # 2-core box
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", scipy.linalg.LinAlgWarning)
                    J = _jacobian(level, P, r, dL, s, frozen)
                    if single:
                        J = J.astype(np.float32)
                    lu = scipy.linalg.lu_factor(J, check_finite=False)
            except (np.linalg.LinAlgError, scipy.linalg.LinAlgError, ValueError) as exc:
                raise NewtonFailure(f"singular coarse Jacobian: {exc}") from None
            if not np.all(np.isfinite(lu[0])):
                raise NewtonFailure("singular coarse Jacobian: non-finite factor")
            factorised += 1
        step = scipy.linalg.lu_solve(lu, -phi.astype(lu[0].dtype), check_finite=False).astype(float)
        t = 1.0
        while True:
            Pt = P.copy()
            Pt[inner] += t * step[:-1]
            H0t = H0 + t * step[-1]
            rt, _ = _system(level, Pt, H0t, False)
            with np.errstate(all="ignore"):
                norm = float(np.linalg.norm(_phi(level, Pt, rt, s, P_frozen)))
            if np.isfinite(norm) and norm <= (1.0 - 1e-4 * t) * norm0:
                break
            t *= 0.5
            if t < 1e-6 or (not fresh and t < 0.5):
                break
        if not (np.isfinite(norm) and norm <= (1.0 - 1e-4 * t) * norm0):
            if not fresh:  # the reused factor no longer points downhill: a fresh Jacobian
                lu = None
                continue
            if single:  # a single-precision factor that fails: the step again in double
                single, lu = False, None
                continue
            if np.max(np.abs(phi)) < 1e3 * tol:  # round-off floor reached: accept
                level.P, level.H0 = P, H0
                if keep:
                    level.kept_factor = (lu, s)
                return factorised
            raise NewtonFailure(f"coarse Newton line search failed at iteration {it} "
                                f"(|phi| = {norm0:.3g})")
        if not chord or (not fresh and norm > CHORD_CONTRACTION * norm0):
            lu = None
        chorded = chorded or not fresh
        P, H0 = Pt, H0t
    raise NewtonFailure(f"coarse Newton did not converge in {max_iter} iterations")


def local_newton(level: LineLevel, center: int, half: int = 48, max_iter: int = 20,
                 reduce: float = 1e-3) -> None:
    """Solve the level's equations in the window ``center +- half`` for the window's pressures,
    the rest of ``P`` and ``H0`` fixed: damped semismooth Newton on the windowed complementarity
    system with the exact (dense) Jacobian block, including ``d eps/dP`` through the viscosity.
    Stops when the window's merit fell by ``reduce``, the line search fails or after
    ``max_iter`` steps; updates ``level.P`` in place.

    One deformation of the whole grid; after it the window's films follow from the kernel
    block (``W_i += K_|i-j| dP_j``), so a step costs ``O(half^2)`` whatever the grid.

    This is local relaxation at a singularity (Brandt, Math. Comp. 31, 1977): the collective line
    relaxation freezes ``eps`` (Picard), and where the viscosity changes by orders of magnitude
    between neighbours -- the outlet pressure drop of Barus oils at high ``alpha_bar``, where
    ``eps/h^2`` jumps from 1e-8 to 1e4 in one cell -- that update cannot settle, and the
    residual concentrates on a few points that the cycles never reduce.
    """
    n = level.n
    lo, hi = max(1, center - half), min(n - 1, center + half + 1)
    s0, s1 = max(lo - 2, 0), min(hi + 1, n)  # the stencils of rows lo .. hi-1
    rows = slice(lo - s0, hi - s0)
    fixed = level.frozen[lo:hi]
    W0 = level.deform(level.P)[s0:s1]
    P0 = level.P[s0:s1].copy()
    dist = np.abs(np.arange(s0, s1)[:, None] - np.arange(lo, hi)[None, :])
    Kw = level.kernel[dist]  # film response of the stencil points to the window's pressures

    def window_state(Ps: np.ndarray):
        with np.errstate(all="ignore"):
            W = W0 + Kw @ (Ps[rows] - P0[rows]) if level.elastic else W0
            H, rho, drho, lne, dlne, eps = fluid_state(Ps, W, level.X[s0:s1], level.H0,
                                                       level.par, level.lam, level.elastic)
            factored = getattr(level, "factored", None)
            if factored is not None:
                eps, rho, drho, dlne = factored(eps, rho, drho, lne, dlne, slice(s0, s1))
            r, _ = reynolds_residual(Ps, H, rho, eps, level.h, level.f[s0:s1], level.order, level.face)
        return r[rows], (H, rho, drho, dlne, eps)

    P = P0.copy()
    r, st = window_state(P)
    merit0 = None
    for _ in range(max_iter):
        J = reynolds_jacobian_block(P, *st, level.kernel, level.h, level.order, level.elastic,
                                    lo - s0, hi - s0, False, level.face)
        s = 1.0 / np.maximum(np.abs(np.diagonal(J)), 1e-300)
        with np.errstate(all="ignore"):
            phi = np.minimum(P[rows], s * r)
        phi[fixed] = 0.0
        merit = float(np.linalg.norm(phi))
        if merit0 is None:
            merit0 = merit
        if not np.isfinite(merit) or merit <= reduce * merit0 or merit == 0.0:
            break
        active = (P[rows] <= s * r) | fixed
        Jm = J * -s[:, None]  # d(s r)/dP = -s dL/dP
        Jm[active] = 0.0
        idx = np.flatnonzero(active)
        Jm[idx, idx] = 1.0
        try:
            step = np.linalg.solve(Jm, -phi)
        except np.linalg.LinAlgError:
            break
        t = 1.0
        while t >= 1e-4:
            Pt = P.copy()
            Pt[rows] += t * step
            rt, stt = window_state(Pt)
            with np.errstate(all="ignore"):
                pt = np.minimum(Pt[rows], s * rt)
            pt[fixed] = 0.0
            m = float(np.linalg.norm(pt))
            if np.isfinite(m) and m <= (1.0 - 1e-4 * t) * merit:
                break
            t *= 0.5
        else:
            break
        P, r, st = Pt, rt, stt
    level.P[lo:hi] = np.maximum(P[rows], 0.0)
