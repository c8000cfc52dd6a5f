"""Discrete line-contact EHL equations (Reynolds, film and load in Venner's form), numba kernels.

On a uniform grid ``X_i = X_0 + i h``, ``i = 0 .. n-1``, with ``P_0 = P_{n-1} = 0``:

* film: ``H_i = H0 + X_i^2/2 - (1/pi) W_i``, ``W_i = sum_j K_|i-j| P_j`` (kernel.py);
* Reynolds: ``L_i = [eps_{i+1/2}(P_{i+1}-P_i) - eps_{i-1/2}(P_i-P_{i-1})]/h^2 - D_i(rho H)``
  with ``eps = rho H^3/(eta lambda)``, ``eps_{i+1/2}`` the face coefficient of the neighbours
  (arithmetic mean by default, :mod:`~ehl_multigrid.multigrid.flux`), and
  ``D_i`` the upwind wedge difference: second order
  ``(1.5 q_i - 2 q_{i-1} + 0.5 q_{i-2})/h`` (first order ``(q_i - q_{i-1})/h`` at ``i = 1``
  or when ``order == 1``);
* load: ``h sum_i P_i = pi/2`` (trapezoid rule; P vanishes at both ends).

The residual is ``r = f - L(P)`` (``f = 0`` on the finest grid, the FAS right-hand side on
coarse grids). Cavitation (``P >= 0``) makes it a complementarity problem: at a point with
``P_i = 0`` a residual that would push the pressure negative (``r_i > 0``, because
``dL_i/dP_i < 0``) is satisfied; :func:`projected` zeroes it.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..multigrid.flux import face_coefficients
from ..multigrid.rheology import density, log_viscosity
from .band import solve_band_columns

#: grids finer than this use the h-scaled switch threshold (line_relaxation_system)
FINE_H = 0.012


@njit(cache=True)
def fluid_state(P, W, X, H0, par, lam, elastic):
    """Film ``H``, density ``rho``, ``drho/dP``, ``ln eta``, ``d ln eta/dP`` and ``eps``."""
    n = P.shape[0]
    H = np.empty(n)
    rho = np.empty(n)
    drho = np.empty(n)
    lne = np.empty(n)
    dlne = np.empty(n)
    eps = np.empty(n)
    inv_pi = 1.0 / np.pi
    for i in range(n):
        Hi = H0 + 0.5 * X[i] * X[i]
        if elastic:
            Hi -= inv_pi * W[i]
        H[i] = Hi
        r, dr = density(P[i], par)
        a, da = log_viscosity(P[i], par)
        rho[i], drho[i], lne[i], dlne[i] = r, dr, a, da
        if Hi > 0.0:
            eps[i] = r * Hi * Hi * Hi * np.exp(-a) / lam
        else:
            eps[i] = 0.0
    return H, rho, drho, lne, dlne, eps


@njit(cache=True)
def wedge_coefficients(i, order):
    """Upwind weights ``c_m`` of ``q_{i-m}``, ``m = 0, 1, 2``, times ``h``."""
    if order == 2 and i >= 2:
        return 1.5, -2.0, 0.5
    return 1.0, -1.0, 0.0


@njit(cache=True)
def reynolds_residual(P, H, rho, eps, h, f, order, face=0):
    """Residual ``r = f - L(P)`` (zero at the boundary points) and the sum of the absolute
    Poiseuille and wedge terms (the scale of :func:`relative_residual`); ``face`` the code of
    the Poiseuille face coefficient (:mod:`~ehl_multigrid.multigrid.flux`)."""
    return residual_from_faces(P, H, rho, face_coefficients(eps, face), h, f, order)


@njit(cache=True)
def residual_from_faces(P, H, rho, faces, h, f, order):
    """:func:`reynolds_residual` from the face coefficients ``faces``
    (:func:`~ehl_multigrid.multigrid.flux.face_coefficients`)."""
    n = P.shape[0]
    r = np.zeros(n)
    scale = 0.0
    ih2 = 1.0 / (h * h)
    for i in range(1, n - 1):
        ep = faces[i]
        em = faces[i - 1]
        pois = (ep * (P[i + 1] - P[i]) - em * (P[i] - P[i - 1])) * ih2
        c0, c1, c2 = wedge_coefficients(i, order)
        q = c0 * rho[i] * H[i] + c1 * rho[i - 1] * H[i - 1]
        if c2 != 0.0:
            q += c2 * rho[i - 2] * H[i - 2]
        wedge = q / h
        r[i] = f[i] - (pois - wedge)
        scale += abs(pois) + abs(wedge)
    return r, scale


@njit(cache=True)
def projected(r, P):
    """Complementarity residual: ``r_i`` where ``P_i > 0``, ``min(r_i, 0)`` where ``P_i = 0``."""
    out = r.copy()
    for i in range(r.shape[0]):
        if P[i] <= 0.0 and out[i] > 0.0:
            out[i] = 0.0
    return out


@njit(cache=True)
def add_wedge_band(A, i, k, c, H, rho, drho, K, h, elastic, wq, row=-1):
    """Subtract from row ``i`` of the band Jacobian ``A`` (``A[i, wq + d] = dL_i/dP_{i+d}``,
    ``|d| <= wq``) the wedge term ``c q_k / h`` of ``q_k = rho_k H_k`` (``c`` its upwind weight,
    times the film content where there is one): ``dq_k/dP_j = rho_k dH_k/dP_j + drho_k H_k
    delta_kj`` with ``dH_k/dP_j = -K_|k-j|/pi``. ``row`` >= 0: write that row of ``A`` instead
    (a one-row buffer)."""
    n = H.shape[0]
    if row < 0:
        row = i
    inv_pi = 1.0 / np.pi
    for d in range(-wq, wq + 1):
        j = i + d
        if j < 1 or j > n - 2:
            continue
        val = 0.0
        if elastic:
            dist = k - j if k >= j else j - k
            val = -rho[k] * K[dist] * inv_pi
        if j == k:
            val += drho[k] * H[k]
        A[row, wq + d] -= c * val / h


@njit(cache=True)
def line_relaxation_system(P, H, rho, drho, eps, r, K, h, order, elastic, threshold, q, frozen,
                           threshold_h=0.0, jd_free=False, threshold_eps=0.0, face=0):
    """Banded system of one collective (line) relaxation sweep.

    The changes of all points are solved at once (Venner's line relaxation; in 1-D the line
    is the whole grid). Point ``j`` is a Gauss-Seidel point (change ``delta_j`` at ``j``) when
    ``eps_j/h^2 >= threshold`` and a Jacobi-distributive point otherwise (change ``delta_j``
    at ``j`` and ``-delta_j/2`` at ``j +- 1``), which makes the effect of the change on the
    film local so the band approximation of the dense Jacobian holds in the contact.
    ``eps`` is frozen (Picard); the film's dependence on ``P`` is kept within the band.

    The switch is ``eps/h^2 < max(threshold, threshold_h/h)`` on grids finer than
    ``FINE_H`` (``eps/h^2 < threshold`` on coarser ones): on fine grids the elastic
    part of the wedge term (a Hilbert transform, symbol ``O(|k|)``) competes with the Poiseuille
    term (``eps k^2``) up to ``eps k ~ 1`` i.e. ``eps/h ~ O(1)``, so the classic fixed threshold
    (0.3, tuned on coarse grids) leaves points Gauss-Seidel whose elastic coupling the band
    cannot represent (measured: relaxation diverges at L = 0, 2049 points).

    ``threshold_eps``: also Jacobi-distributive wherever ``eps < threshold_eps`` on every
    grid, whatever ``h`` (the steady solver's film-scale switch, ``solver.default_switch_eps``):
    the collective system solves the Poiseuille part of a Gauss-Seidel zone exactly but only the
    band of its elastic coupling, so where ``eps k^2 << 1`` for the contact's own smooth modes
    (``k = O(1)`` in units of the Hertzian half-width) those modes are amplified, on any grid.

    ``frozen[i]`` keeps point ``i`` unchanged (coarse-grid points next to the fine grid's
    cavitation boundary, see solver.py).

    ``jd_free``: a point next to a cavitated one or the boundary is always Gauss-Seidel (not
    next to a frozen coarse-grid point, which costs cycles on fine long-inlet grids). A
    distributive change moves its neighbours by ``-delta/2``; at a fixed neighbour that move is
    either not applied (frozen, boundary) or projected away (``P = 0``), so the system solved
    is not the one applied and the free boundary oscillates from sweep to sweep (seen where the
    Jacobi-distributive zone reaches the outlet's cavitation point: isoviscous (100, 0), 4097
    points).

    Returns ``(ab, rhs, jac)``: LAPACK band storage (``q`` sub- and super-diagonals) of the
    matrix for the interior points, the right-hand side, and the Jacobi flags
    (:func:`relaxation_system_columns` builds it in the column storage of
    :mod:`~ehl_multigrid.line.band`).
    """
    m = P.shape[0] - 2
    cols = np.zeros((m, 3 * q + 1))
    rhs, jac = relaxation_system_columns(P, H, rho, drho, eps, face_coefficients(eps, face), r, K,
                                         h, order, elastic, threshold, q, frozen, threshold_h,
                                         jd_free, threshold_eps, cols)
    ab = np.empty((2 * q + 1, m))
    for j in range(m):
        for t in range(2 * q + 1):
            ab[t, j] = cols[j, q + t]
    return ab, rhs, jac


@njit(cache=True)
def relaxation_system_columns(P, H, rho, drho, eps, faces, r, K, h, order, elastic, threshold, q,
                              frozen, threshold_h, jd_free, threshold_eps, ab):
    """The system of :func:`line_relaxation_system` written into ``ab``, the column storage of
    :mod:`~ehl_multigrid.line.band` (shape ``(n - 2, 3 q + 1)``; every entry the LU reads is
    written, the zero fill-in included, so ``ab`` need not be cleared), with the face
    coefficients ``faces`` of ``eps`` (:func:`~ehl_multigrid.multigrid.flux.face_coefficients`);
    returns ``(rhs, jac)``."""
    n = P.shape[0]
    m = n - 2  # interior unknowns 1 .. n-2
    wq = q + 1
    ih2 = 1.0 / (h * h)
    jac = np.zeros(n, dtype=np.bool_)
    fix = np.zeros(n, dtype=np.bool_)
    fix[0] = fix[n - 1] = True
    for i in range(1, n - 1):
        fix[i] = P[i] <= 0.0 and r[i] >= 0.0
    thr = max(threshold, threshold_h / h) if h < FINE_H else threshold
    for j in range(1, n - 1):
        # the largest eps of the stencil decides, so a point next to a steep rise of eps
        # (the flank of the pressure spike) is not treated as integral-equation dominated
        e = max(eps[j - 1], eps[j], eps[j + 1])
        jac[j] = e * ih2 < thr or e < threshold_eps
        if jd_free and (fix[j - 1] or fix[j + 1]):
            jac[j] = False
    # fixed unknowns (cavitated or frozen): their rows are the identity, their columns zero
    fixed = np.empty(n, dtype=np.bool_)
    for i in range(n):
        fixed[i] = fix[i] or frozen[i]
    rhs = np.zeros(m)
    inv_pi = 1.0 / np.pi
    # row i of the Jacobian of L with eps frozen, A[i, i + d] for |d| <= q + 1, built per row
    # (a whole n x (2q + 3) matrix cost more in memory traffic than its arithmetic); the film
    # of point i - mm responds to P_(i+d) by -K_|d+mm|/pi
    A = np.zeros(2 * wq + 1)
    for i in range(1, n - 1):
        row = i - 1
        for t in range(q):  # fill-in entries of column `row` (band.py)
            ab[row, t] = 0.0
        if fixed[i]:
            for d in range(-q, q + 1):
                if 0 <= row + d < m:
                    ab[row + d, 2 * q - d] = 1.0 if d == 0 else 0.0
            continue
        A[:] = 0.0
        ep = faces[i]
        em = faces[i - 1]
        A[wq - 1] += em * ih2
        A[wq] += -(ep + em) * ih2
        A[wq + 1] += ep * ih2
        c0, c1, c2 = wedge_coefficients(i, order)
        for mm in range(3):
            c = c0 if mm == 0 else (c1 if mm == 1 else c2)
            if c == 0.0:
                continue
            k = i - mm
            w = c / h
            if elastic:
                g = w * rho[k] * inv_pi
                for d in range(max(-wq, 1 - i), min(wq, n - 2 - i) + 1):
                    A[wq + d] += g * K[abs(d + mm)]
            if k >= 1:  # the density's own response (j = k, an unknown)
                A[wq - mm] -= w * drho[k] * H[k]
        rhs[row] = r[i]
        for d in range(-q, q + 1):
            j = i + d
            if j < 1 or j > n - 2:
                continue
            if fixed[j] and d != 0:
                b = 0.0
            else:
                b = A[wq + d]
                if jac[j]:
                    if j - 1 >= 1:
                        b -= 0.5 * A[wq + d - 1]
                    if j + 1 <= n - 2:
                        b -= 0.5 * A[wq + d + 1]
            # column storage (band.py): A[row, col] at ab[col, 2 q + row - col]
            ab[j - 1, 2 * q - d] = b
    return rhs, jac


@njit(cache=True)
def relaxation_sweep(P, H, rho, drho, eps, faces, r, K, h, order, elastic, threshold, q, frozen,
                     threshold_h, jd_free, threshold_eps, omega, omega_jd, work):
    """One collective line-relaxation sweep in one kernel: the system of
    :func:`line_relaxation_system` built in ``work`` (column storage, ``(n - 2, 3 q + 1)``),
    solved by banded LU (:func:`~ehl_multigrid.line.band.solve_band_columns`; point Jacobi
    where singular) and applied by :func:`distribute_changes`; ``faces`` the face coefficients
    of ``eps``. Returns the new pressures."""
    n = P.shape[0]
    rhs, jac = relaxation_system_columns(P, H, rho, drho, eps, faces, r, K, h, order, elastic,
                                         threshold, q, frozen, threshold_h, jd_free, threshold_eps,
                                         work)
    delta = solve_band_columns(work, rhs, q)
    return distribute_changes(P, delta, jac, omega, omega_jd, np.ones(n), frozen)


@njit(cache=True)
def distribute_changes(P, delta, jac, omega_gs, omega_jac, damp, frozen):
    """Apply the under-relaxed changes (distributive at Jacobi points) and project to P >= 0.

    ``damp[j]`` (<= 1) further reduces the Gauss-Seidel change where ``eps`` varies steeply
    (spike flank), where the frozen-``eps`` update overshoots."""
    n = P.shape[0]
    dP = np.zeros(n)
    for j in range(1, n - 1):
        d = delta[j - 1]
        if jac[j]:
            d *= omega_jac
            dP[j] += d
            if j - 1 >= 1:
                dP[j - 1] -= 0.5 * d
            if j + 1 <= n - 2:
                dP[j + 1] -= 0.5 * d
        else:
            dP[j] += omega_gs * damp[j] * d
    out = P.copy()
    for j in range(1, n - 1):
        if frozen[j]:
            continue
        v = P[j] + dP[j]
        out[j] = v if v > 0.0 else 0.0
    out[0] = 0.0
    out[n - 1] = 0.0
    return out

