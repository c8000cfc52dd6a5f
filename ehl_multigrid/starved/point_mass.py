"""Exact zone solve of the starved point contact: the discrete Elrod-Adams mass balance of the
finest grid, where the Poiseuille terms dominate, solved by a primal-dual active-set
(semismooth Newton) method with a sparse direct solve.

Why: in a thick-film contact at mild starvation the meniscus lies far upstream, where
``eps/h^2 ~ 2e4 ... 2e6``. The multigrid cycle stops (its scaled residual, a pressure change,
is at the tolerance) with an unscaled residual of one sign spread over the pressurised inlet
(measured at (M, L) = (20, 10), 129^2, Hoil = 2 Hc_ff: 46 % of it on the first pressurised point
of each row, the rest decaying over the next ~6 columns), and the sum of the residuals is the
imbalance of the boundary flows (3.6e-5 of the inflow there). Further cycles do not remove it
(a fixed point of the cycle: its coarse-grid film content is not consistent with the fine
grid's inlet balance) and line relaxation reduces it by ~0.2 % per sweep.

What: on a zone of the finest grid (``region``; the starved hierarchy passes the points with
``eps/hx^2 >= 10`` and the unpressurised inlet) the unknowns are ``P`` where the film is full
and ``theta`` where it is not (Elrod 1981; the complementarity form of Woloszynski et al. 2015:
``P >= 0``, ``0 <= theta <= 1``, ``P (1 - theta) = 0``); the points outside hold their values.
For a fixed active set the discrete balance (thesis (2.1) in the starved operator's flux form:
the point core's five-point Poiseuille terms, the upwind face values of
:func:`.point_wedge.face_value`) is linear in these unknowns at the frozen film ``H``, density
and ``eps``; it is solved by a sparse direct solve, the active set updated (``P < 0``:
unpressurised; ``theta > 1``: pressurised) and solved again until it no longer changes
(Hintermueller, Ito & Kunisch 2002: primal-dual active set = semismooth Newton). Where the
Poiseuille terms dominate, the film's response to the change is small; the caller updates the
film after the solve (the next cycle's solve starts from it). The zone's residuals then vanish, and by the flux form its share
of the imbalance moves to the faces of its rim, where the cycle's scaled residual sees it.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable

import numpy as np
import scipy.sparse as sps
import scipy.sparse.linalg as spla

#: largest number of active-set iterations of one inlet solve
MAX_ACTIVE_SET = 30


def _coefficient_of_theta(rho: np.ndarray, H: np.ndarray, theta: np.ndarray, order: int) -> np.ndarray:
    """``dQ_{i+1/2}/dtheta_i`` of the face values of :func:`.point_wedge.face_value` for an
    unpressurised point ``i >= 1`` (``theta_i < 1``): ``rho_i H_i`` times 1.5 where the second
    order's upstream point ``i - 1`` is full, else 1."""
    c = rho * H
    if order == 2:
        c = c.copy()
        full_up = np.zeros_like(theta, dtype=bool)
        full_up[:, 1:] = theta[:, :-1] >= 1.0
        c[full_up] *= 1.5
    return c


def inlet_solve(P: np.ndarray, H: np.ndarray, rho: np.ndarray, eps: np.ndarray, theta: np.ndarray,
                f: np.ndarray, hx: float, hy: float, half: bool, order: int, region: np.ndarray,
                residual: Callable[[np.ndarray, np.ndarray], np.ndarray],
                ct: float = 0.0) -> tuple[bool, int, str]:
    """Solve the discrete Elrod-Adams balance exactly on the interior points of ``region``
    (P and theta outside held), in place in ``P`` and ``theta``; ``order`` is the wedge's
    (1, or 2: the per-face order of :func:`.point_wedge.face_value`); ``ct``: the squeeze
    coefficient of a BDF time step (``d(theta rho H)/dT = ct theta rho H - s``, ``s`` in the
    residual's right-hand side; 0: steady).

    ``residual(P, theta) -> r`` is the operator's residual ``f - L(P, theta)`` at the frozen
    film (0 on the boundary). Returns (done, active-set iterations, note)."""
    ny, nx = P.shape
    j0 = 0 if half else 1
    inner = np.zeros((ny, nx), dtype=bool)
    inner[j0:ny - 1, 1:nx - 1] = True
    J, I = np.nonzero(region & inner)
    n = J.size
    if n == 0:
        return False, 0, "empty region"
    idx = -np.ones((ny, nx), dtype=np.int64)
    idx[J, I] = np.arange(n)
    press = (P[J, I] > 0.0) | (theta[J, I] >= 1.0)
    P0, t0 = P.copy(), theta.copy()
    hx2, hy2 = hx * hx, hy * hy
    e = eps[J, I]
    exm = 0.5 * (eps[J, I - 1] + e)
    exp_ = 0.5 * (eps[J, I + 1] + e)
    Jm = np.where(half & (J == 0), 1, J - 1)
    eym = 0.5 * (eps[Jm, I] + e)
    eyp = 0.5 * (eps[J + 1, I] + e)
    diagP = (exm + exp_) / hx2 + (eym + eyp) / hy2
    k = idx[J, I]
    for it in range(1, MAX_ACTIVE_SET + 1):
        # the state of the active set: P = 0 where unpressurised, theta = 1 where pressurised
        P[J[~press], I[~press]] = 0.0
        theta[J[press], I[press]] = 1.0
        r = residual(P, theta)
        c = _coefficient_of_theta(rho, H, theta, order)
        ri, ci, vi = [], [], []
        # pressurised: unknown P; r = f - Pois + W, dr/dP_c = +diagP, dr/dP_nb = -e_face/h^2
        ri.append(k[press])
        ci.append(k[press])
        vi.append(diagP[press])
        for (dj, di, coef) in ((0, -1, exm / hx2), (0, 1, exp_ / hx2), (None, 0, eym / hy2),
                               (1, 0, eyp / hy2)):
            Jn = Jm if dj is None else J + dj
            In = I + di
            kn = idx[Jn, In]
            pn = np.zeros_like(press)
            inside = kn >= 0
            pn[inside] = press[kn[inside]]
            m = inside & pn  # the neighbour's P is an unknown (P of unpressurised points is 0)
            ri.append(k[m])
            ci.append(kn[m])
            vi.append(-coef[m])
        # unpressurised: unknown theta; its face Q_{i+1/2} enters r_i (+c/hx), r_{i+1} (-c/hx)
        un = ~press
        cu = c[J[un], I[un]] / hx
        ri.append(k[un])
        ci.append(k[un])
        # the squeeze term ct theta_i rho_i H_i of a time step adds to the diagonal only
        vi.append(cu + ct * rho[J[un], I[un]] * H[J[un], I[un]])
        kd = idx[J[un], I[un] + 1]
        m = kd >= 0
        ri.append(kd[m])
        ci.append(k[un][m])
        vi.append(-cu[m])
        A = sps.csr_matrix((np.concatenate(vi), (np.concatenate(ri), np.concatenate(ci))), shape=(n, n))
        rhs = -r[J, I]
        try:
            with warnings.catch_warnings():
                # a singular zone system is caught below (not finite): no warning on stderr
                warnings.simplefilter("ignore", spla.MatrixRankWarning)
                d = spla.spsolve(A.tocsc(), rhs)
        except Exception as exc:  # noqa: BLE001 (a singular inlet: keep the cycle's state)
            P[:], theta[:] = P0, t0
            return False, it, f"sparse solve failed: {exc}"
        if not np.all(np.isfinite(d)):
            P[:], theta[:] = P0, t0
            return False, it, "sparse solve not finite"
        P[J[press], I[press]] += d[press]
        theta[J[un], I[un]] += d[un]
        newp = np.where(press, P[J, I] > 0.0, theta[J, I] > 1.0)
        if np.array_equal(newp, press):
            bad = (~press) & (theta[J, I] < 0.0)
            if bad.any():
                theta[J[bad], I[bad]] = 0.0
            return True, it, ""
        press = newp
    P[:], theta[:] = P0, t0
    return False, MAX_ACTIVE_SET, "active set did not settle"
