"""Dense semismooth Newton for the mass-conserving line problem on one (coarse) grid, in the
Fischer-Burmeister form of the complementarity ``P >= 0``, ``theta <= 1``,
``P (1 - theta) = 0`` (Woloszynski et al. 2015). Used for the FMG start grid, the coarsest
grid and as the last resort of a stalled solve on a small grid.
"""

from __future__ import annotations

import warnings

import numpy as np
import scipy.linalg
from numba import njit

from ..multigrid.flux import eps_faces
from ..multigrid.threads import serial_blas
from .discrete import march_cavitated_content, wedge_row, wedge_share_terms
from .level import StarvedLevel


class StarvedNewtonFailure(RuntimeError):
    """The dense Newton iteration did not converge (the caller tries something else)."""


def _residual(lv: StarvedLevel, P: np.ndarray, theta: np.ndarray, H0: float) -> np.ndarray:
    with np.errstate(all="ignore"):
        st = lv.state(P, H0, theta)
    return st.r


def _jacobian(lv: StarvedLevel, P: np.ndarray, theta: np.ndarray, H0: float, Kmat: np.ndarray):
    """``(r, dL/dP (n x n), dL/dH0, dL/dtheta (n x n, banded), theta with the inlet value)``."""
    n, h = lv.n, lv.h
    st = lv.state(P, H0, theta)  # the grid's own film (a time step's moving geometry included)
    H, rho, drho, dlne, eps, r, th = st.H, st.rho, st.drho, st.dlne, st.eps, st.r, st.theta
    starved = bool(th[0] < 1.0)
    dH = -Kmat / np.pi if lv.elastic else np.zeros((n, n))
    pos = H > 0.0
    Hs = np.where(pos, H, 1.0)
    deps = np.zeros((n, n + 1))
    deps[:, :n] = (3.0 * eps / Hs)[:, None] * dH
    deps[np.arange(n), np.arange(n)] += eps * (drho / rho - dlne)
    deps[:, n] = 3.0 * eps / Hs
    deps[~pos] = 0.0
    dq = np.zeros((n, n + 1))
    dq[:, :n] = (th * rho)[:, None] * dH
    dq[np.arange(n), np.arange(n)] += th * drho * H
    dq[:, n] = th * rho
    if th[0] < 1.0:  # a starved inlet supplies exactly hoil: q_0 is fixed
        dq[0] = 0.0
    ih2 = 1.0 / (h * h)
    dL = np.zeros((n, n + 1))
    dT = np.zeros((n, n))
    i = np.arange(1, n - 1)
    ep, dep_i, dep_n = eps_faces(eps[i], eps[i + 1], lv.face)
    em, dem_i, dem_n = eps_faces(eps[i], eps[i - 1], lv.face)
    dep = dep_i[:, None] * deps[i] + dep_n[:, None] * deps[i + 1]
    dem = dem_i[:, None] * deps[i] + dem_n[:, None] * deps[i - 1]
    dL[i] = ih2 * (dep * (P[i + 1] - P[i])[:, None] - dem * (P[i] - P[i - 1])[:, None])
    dL[i, i + 1] += ih2 * ep
    dL[i, i] -= ih2 * (ep + em)
    dL[i, i - 1] += ih2 * em
    if starved:  # no pressure flow through the first face
        dL[1] += ih2 * dem[0] * (P[1] - P[0])
        dL[1, 1] += ih2 * em[0]
        dL[1, 0] -= ih2 * em[0]
    add_wedge_rows(dL, dT, dq, th, rho, H, h, lv.order, starved)
    ct, _ = lv.content_rate()
    if ct != 0.0:  # a time step's rows carry + ct theta rho H - hist
        dL[i] -= ct * dq[i]
        dT[i, i] -= ct * rho[i] * H[i]
    return r, dL, dT, th


@njit(cache=True)
def add_wedge_rows(dL, dT, dq, theta, rho, H, h, order, starved):
    """Add the wedge term's derivatives to the rows ``1 .. n-2`` of ``dL`` (pressures and
    ``H0``, through ``dq = d(theta rho H)/dx``) and ``dT`` (film contents), in place: the
    upwind weights of :func:`wedge_row` and the second-order shares of
    :func:`wedge_share_terms`. A compiled loop: on a 65-point coarsest grid
    the Python loop was most of a Newton iteration (0.9 ms of it)."""
    n = H.shape[0]
    m = dq.shape[1]
    q = rho * H
    for k in range(1, n - 1):
        e = wedge_share_terms(k, theta, q, order, starved)
        for mm in range(3 if k >= 2 else 2):
            dT[k, k - mm] -= e[mm] / h
        c = wedge_row(k, theta, order, starved)
        for mm in range(3):
            if c[mm] == 0.0:
                continue
            for j in range(m):
                dL[k, j] -= c[mm] * dq[k - mm, j] / h
            dT[k, k - mm] -= c[mm] * rho[k - mm] * H[k - mm] / h


def _fb(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Fischer-Burmeister function ``a + b - sqrt(a^2 + b^2)`` (zero iff ``a, b >= 0`` and
    ``a b = 0``) and its partial derivatives (a generalised gradient at ``a = b = 0``)."""
    rt = np.sqrt(a * a + b * b)
    safe = np.where(rt > 0.0, rt, 1.0)
    da = np.where(rt > 0.0, 1.0 - a / safe, 1.0 - 1.0 / np.sqrt(2.0))
    db = np.where(rt > 0.0, 1.0 - b / safe, 1.0 - 1.0 / np.sqrt(2.0))
    return a + b - rt, da, db


def _pinned_step(J: np.ndarray, phi: np.ndarray, pinned_rows: np.ndarray,
                 pinned_cols: np.ndarray) -> np.ndarray:
    """The Newton step ``J^-1 (-phi)`` where row ``pinned_rows[k]`` of ``J`` is zero except at
    column ``pinned_cols[k]`` and ``phi`` is zero there: those unknowns do not move, and the
    others solve the system of the remaining rows and columns (the same step, a smaller
    factorisation). Pinned are the frozen points of a coarse grid and, by the
    Fischer-Burmeister rows of a strictly complementary point, ``theta = 1`` where ``P > 0``
    and ``P = 0`` where ``theta < 1``: about half the unknowns, an eighth of the work."""
    if pinned_rows.size == 0:
        return scipy.linalg.solve(J, -phi, check_finite=False)
    rows = np.setdiff1d(np.arange(phi.size), pinned_rows)
    cols = np.setdiff1d(np.arange(phi.size), pinned_cols)
    step = np.zeros_like(phi)
    step[cols] = scipy.linalg.solve(J[np.ix_(rows, cols)], -phi[rows], check_finite=False)
    return step


def newton_solve(lv: StarvedLevel, max_iter: int = 80, tol: float = 1e-10) -> int:
    """Solve the grid's problem in place (``P``, ``theta``, ``H0``); return the iterations.

    Semismooth Newton on the Fischer-Burmeister form (Woloszynski, Podsiadlo & Stachowiak
    2015): unknowns ``P_i``, ``theta_i`` of the interior points and ``H0``; equations: the
    row-scaled Reynolds residual ``s_i r_i = 0``, ``FB(P_i, 1 - theta_i) = 0`` (``P >= 0``,
    ``theta <= 1``, ``P (1 - theta) = 0``) and the load. The squared norm is smooth, so the
    backtracking line search on it always has a descent direction. ``theta`` never falls
    below a fifth of its previous value in one step (it stays positive).

    Raises :class:`StarvedNewtonFailure` when the damped iteration stalls or breaks down.
    The dense factorisations run on one BLAS thread (as the flooded Newton's)."""
    with serial_blas():
        return _newton_solve(lv, max_iter, tol)


def _newton_solve(lv: StarvedLevel, max_iter: int, tol: float) -> int:
    n = lv.n
    m = n - 2
    Kmat = scipy.linalg.toeplitz(lv.kernel) if lv.elastic else np.zeros((n, n))
    P, theta, H0 = lv.P.copy(), lv.theta.copy(), float(lv.H0)
    inner = np.arange(1, n - 1)
    fr = lv.frozen[inner]
    P_fr, T_fr = P.copy(), theta.copy()

    def system(P, theta, H0, s):
        """``phi`` of the iterate and its inlet content (set by the supply)."""
        with np.errstate(all="ignore"):
            st = lv.state(P, H0, theta)
        phi = np.empty(2 * m + 1)
        phi[:m] = s * st.r[inner]
        phi[m:2 * m], _, _ = _fb(P[inner], 1.0 - theta[inner])
        phi[:m][fr] = (P - P_fr)[inner][fr]
        phi[m:2 * m][fr] = (theta - T_fr)[inner][fr]
        phi[-1] = lv.h * np.sum(P) - lv.g
        return phi, st.theta[0]

    s = phi = None
    for it in range(1, max_iter + 1):
        fresh = s is None
        if fresh:
            with np.errstate(all="ignore"):
                r, dL, dT, th = _jacobian(lv, P, theta, H0, Kmat)
            theta[0] = th[0]
            # row scales from the first iterate (fixed, so the merit is one function)
            d = np.where(P[inner] > 0.0, np.abs(dL[inner, inner]), np.abs(dT[inner, inner]))
            s = 1.0 / np.maximum(d, 1e-300)
            phi, _ = system(P, theta, H0, s)
        norm0 = float(np.linalg.norm(phi))
        if not np.isfinite(norm0):
            raise StarvedNewtonFailure("non-finite residual in the dense Newton iteration")
        if np.max(np.abs(phi)) < tol:
            # (phi of an accepted trial is the next iterate's: a converged one needs no Jacobian)
            lv.P, lv.theta, lv.H0 = np.maximum(P, 0.0), np.minimum(theta, 1.0), H0
            exact_cavitation(lv)
            return it - 1
        if not fresh:
            with np.errstate(all="ignore"):
                r, dL, dT, th = _jacobian(lv, P, theta, H0, Kmat)
            theta[0] = th[0]
        J = np.zeros((2 * m + 1, 2 * m + 1))
        J[:m, :m] = -s[:, None] * dL[np.ix_(inner, inner)]
        J[:m, m:2 * m] = -s[:, None] * dT[np.ix_(inner, inner)]
        J[:m, -1] = -s * dL[inner, n]
        _, da, db = _fb(P[inner], 1.0 - theta[inner])
        J[m + np.arange(m), np.arange(m)] = da
        J[m + np.arange(m), m + np.arange(m)] = -db
        J[-1, :m] = lv.h
        for off in (0, m):
            rows = off + np.flatnonzero(fr)
            J[rows] = 0.0
            J[rows, rows] = 1.0
        # unknowns that do not move: frozen, or fixed by their complementarity row
        settled = (phi[m:2 * m] == 0.0) & ~fr
        fixed_P, fixed_T = np.flatnonzero(settled & (db == 0.0)), np.flatnonzero(settled & (da == 0.0))
        frozen = np.flatnonzero(fr)
        pinned_rows = np.concatenate([frozen, m + frozen, m + fixed_P, m + fixed_T])
        pinned_cols = np.concatenate([frozen, m + frozen, fixed_P, m + fixed_T])
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", scipy.linalg.LinAlgWarning)
                step = _pinned_step(J, phi, pinned_rows, pinned_cols)
        except (np.linalg.LinAlgError, scipy.linalg.LinAlgError, ValueError) as exc:
            raise StarvedNewtonFailure(f"singular Jacobian: {exc}") from None
        dPs, dTs = step[:m], step[m:2 * m]
        t = 1.0
        while True:
            Pt, Tt = P.copy(), theta.copy()
            Pt[inner] += t * dPs
            # theta stays positive: projected to at least a fifth of its value
            Tt[inner] = np.maximum(theta[inner] + t * dTs, 0.2 * theta[inner])
            H0t = H0 + t * step[-1]
            phi_t, inlet_t = system(Pt, Tt, H0t, s)
            with np.errstate(all="ignore"):
                norm = float(np.linalg.norm(phi_t))
            if np.isfinite(norm) and norm <= (1.0 - 1e-4 * t) * norm0:
                break
            t *= 0.5
            if t < 1e-8:
                if np.max(np.abs(phi)) < 1e3 * tol:
                    lv.P, lv.theta, lv.H0 = np.maximum(P, 0.0), np.minimum(theta, 1.0), H0
                    exact_cavitation(lv)
                    return it - 1
                raise StarvedNewtonFailure(f"line search failed at iteration {it} (|phi| = {norm0:.3g})")
        P, theta, H0, phi = Pt, Tt, H0t, phi_t
        theta[0] = inlet_t
    raise StarvedNewtonFailure(f"dense Newton did not converge in {max_iter} iterations")


def exact_cavitation(lv: StarvedLevel) -> None:
    """Set the pressure of the cavitated points (``theta < 1``) to exactly zero and march their
    film content from the upwind mass balance with that pressure (in place).

    The converged Newton iterate keeps round-off pressures of order 1e-17 there; where
    ``eps/h^2`` is large (the low-pressure outlet, ~1e7 on 1025 points) clipping them leaves a
    Reynolds residual of ~1e-9 per point, a relative residual of 1.6e-7 at (100, 10) on a box
    0.004 a ahead of the Hertzian edge, above the starved tolerance (measured; after this step
    6e-10). ``theta_i`` solves row ``i`` exactly given its upwind neighbours."""
    st = lv.state()
    cav = np.flatnonzero(st.theta[1:-1] < 1.0) + 1
    if cav.size == 0:
        return
    lv.P[cav] = 0.0
    st = lv.state()
    th = st.theta.copy()
    ct, hist = lv.content_rate()
    march_cavitated_content(lv.P, th, st.rho * st.H, st.eps, lv.f, lv.h, lv.order, bool(th[0] < 1.0), cav,
                            ct, hist, lv.face)
    lv.theta = th
