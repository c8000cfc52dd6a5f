"""The squeeze term of the time-dependent line-contact Reynolds equation (numba kernels).

Venner's dimensionless transient Reynolds equation of a line contact (Venner & Lubrecht 2000,
ch. 12) is

``d/dX(eps dP/dX) - d(rho H)/dX - d(rho H)/dT = 0``,  ``T = t u_m / b``,

with ``X = x/b``, ``H = h R/b^2``, ``u_m = (u1 + u2)/2``: the wedge and squeeze terms carry the
same factor ``u_m b/R`` in physical units, so neither has a coefficient. The time derivative
is the backward difference of order 1 or 2 (BDF1 = backward Euler, BDF2) at constant step
``dT``:

``d(rho H)/dT ~ c_t (rho H)^{n+1} - s``,
BDF1: ``c_t = 1/dT``, ``s = (rho H)^n/dT``;
BDF2: ``c_t = 3/(2 dT)``, ``s = (4 (rho H)^n - (rho H)^{n-1})/(2 dT)``.

The steady kernels of the line contact (``line.discrete``) evaluate everything else; the
squeeze term enters their residual as a right-hand side (``f + c_t rho H - s``) and their
collective relaxation matrix through :func:`add_squeeze_band`.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..line.discrete import add_wedge_band
from ..multigrid.flux import eps_face


@njit(cache=True)
def add_squeeze_band(ab, P, H, rho, drho, r, K, ct, q, jac, frozen, elastic):
    """Add the squeeze term's Jacobian ``-c_t d(rho H)_i/dP_j`` to a collective line-relaxation
    matrix built by ``line.discrete.line_relaxation_system`` (LAPACK band storage, ``q`` sub-
    and super-diagonals), with that kernel's rules: Jacobi-distributive columns (``jac``)
    take ``S_ij - (S_i,j-1 + S_i,j+1)/2``; rows and columns of fixed points (cavitated with
    ``r >= 0``, or ``frozen``) are left as the identity.

    ``d(rho H)_i/dP_j = -rho_i K_|i-j|/pi + drho_i H_i delta_ij`` (film equation; ``eps``
    frozen as in the steady relaxation).
    """
    n = P.shape[0]
    inv_pi = 1.0 / np.pi
    for i in range(1, n - 1):
        if (P[i] <= 0.0 and r[i] >= 0.0) or frozen[i]:
            continue
        row = i - 1
        for d in range(-q, q + 1):
            j = i + d
            if j < 1 or j > n - 2:
                continue
            if (P[j] <= 0.0 and r[j] >= 0.0) or frozen[j]:
                continue
            b = 0.0
            for jj in range(j - 1, j + 2):
                if jj < 1 or jj > n - 2:
                    continue
                if jj != j and not jac[j]:
                    continue
                s = 0.0
                if elastic:
                    dist = i - jj if i >= jj else jj - i
                    s = ct * rho[i] * K[dist] * inv_pi
                if jj == i:
                    s -= ct * drho[i] * H[i]
                b += s if jj == j else -0.5 * s
            ab[q + row - (j - 1), j - 1] += b


def squeeze_jacobian(H: np.ndarray, rho: np.ndarray, drho: np.ndarray, K: np.ndarray,
                     elastic: bool = True) -> np.ndarray:
    """``d(rho H)_i/dx_j`` for the inner points ``i = 1 .. n-2`` and the unknowns
    ``x = (P_1 .. P_{n-2}, H0)`` of the coarse Newton iteration (``line.newton``): an
    ``(n-2, n-1)`` array. Times ``c_t`` it is the squeeze term's part of the dense Jacobian.

    ``d(rho H)_i/dP_j = -rho_i K_|i-j|/pi + drho_i H_i delta_ij`` (film equation, as in
    :func:`add_squeeze_band`), ``d(rho H)_i/dH0 = rho_i``.
    """
    n = H.shape[0]
    idx = np.arange(1, n - 1)
    out = np.zeros((n - 2, n - 1))
    if elastic:
        out[:, :-1] = -rho[idx, None] * K[np.abs(idx[:, None] - idx[None, :])] / np.pi
    out[np.arange(n - 2), np.arange(n - 2)] += drho[idx] * H[idx]
    out[:, -1] = rho[idx]
    return out


@njit(cache=True)
def flux_balance(P, H, rho, eps, h, dq_dt, i0, i1, face=0):
    """Discrete mass balance of the control volume of nodes ``i0 .. i1``:
    ``h sum_i d(rho H)_i/dT - (F_in - F_out)``, with the Poiseuille flux
    ``eps_{i+1/2}(P_{i+1} - P_i)/h`` (``face``: :mod:`~ehl_multigrid.multigrid.flux`) and the second-order upwind Couette flux
    ``1.5 (rho H)_i - 0.5 (rho H)_{i-1}`` through the faces ``i0 - 1/2`` and ``i1 + 1/2``.
    Zero (to the residual) when the discrete equations are in conservation form."""
    q = rho * H
    # face i-1/2 of node i (i >= 2): Couette 1.5 q_{i-1} - 0.5 q_{i-2}
    fin_c = 1.5 * q[i0 - 1] - 0.5 * q[i0 - 2]
    fout_c = 1.5 * q[i1] - 0.5 * q[i1 - 1]
    fin_p = eps_face(eps[i0 - 1], eps[i0], face) * (P[i0] - P[i0 - 1]) / h
    fout_p = eps_face(eps[i1], eps[i1 + 1], face) * (P[i1 + 1] - P[i1]) / h
    storage = 0.0
    for i in range(i0, i1 + 1):
        storage += h * dq_dt[i]
    # inflow of rho H u: Couette in minus Poiseuille in (flux = -eps dP/dX + rho H)
    return storage - ((fin_c - fin_p) - (fout_c - fout_p))


@njit(cache=True)
def add_content_squeeze(AP, AT, theta, H, rho, drho, K, h, ct, elastic, band):
    """Add the squeeze term ``-c_t theta_i (rho H)_i`` of the mass-conserving (Elrod-Adams)
    time step to the band parts of a sweep's Jacobian (``starved.discrete.band_jacobian``):
    ``dL_i/dtheta_i -= c_t (rho H)_i`` and, through the film's elastic dependence on ``P``
    within the band, ``dL_i/dP_j -= c_t theta_i d(rho H)_i/dP_j``."""
    n = H.shape[0]
    wq = band + 1
    for i in range(1, n - 1):
        AT[i, 0] -= ct * rho[i] * H[i]
        # the wedge-term helper subtracts c q_i/h: c = c_t h theta_i gives the squeeze term
        add_wedge_band(AP, i, i, ct * h * theta[i], H, rho, drho, K, h, elastic, wq)
