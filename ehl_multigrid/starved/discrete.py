"""Discrete mass-conserving (Elrod-Adams) line-contact Reynolds equation, numba kernels.

Venner's dimensionless line contact (thesis (2.1)-(2.3) in the form of Venner & Lubrecht
2000) with the film content ``theta`` (fraction of the gap filled with oil) in the wedge term:

``L_i = [eps_{i+1/2}(P_{i+1}-P_i) - eps_{i-1/2}(P_i-P_{i-1})]/h^2 - D_i(theta rho H)``,
``P_i (1 - theta_i) = 0``, ``P_i >= 0``, ``0 < theta_i <= 1`` (Elrod & Adams 1974; Elrod 1981).

``D_i`` is the same upwind difference as the flooded solver (ehl_multigrid.line.discrete), so
the residual is :func:`ehl_multigrid.line.discrete.reynolds_residual` with ``theta rho`` in
place of ``rho``. Every interior point satisfies the equation (no inequality as in the Reynolds
condition): a pressurised point (``theta = 1``) has ``P`` as its unknown, a cavitated or
starved point (``P = 0``) has ``theta``. One *universal variable* per point (Elrod's switch
variable; used in the Twente multigrid starvation studies of Venner, Damiens and Lubrecht)
carries either: the relaxation solves for the change of whichever unknown is active, and a
change that crosses ``u = 0`` moves the point to the other regime.

The scheme is conservative: ``L_i = (G_{i+1/2} - G_{i-1/2})/h`` with the face flux
``G = eps dP/dX - Q`` and the upwind face value ``Q_{i+1/2} = 1.5 q_i - 0.5 q_{i-1}``
(``q = theta rho H``), so the mass flux ``Q - eps dP/dX`` through the first and the last
face differ by ``h sum_i r_i`` exactly (:func:`face_fluxes`).

Inlet. A flooded inlet (``theta_0 = 1``) keeps the flooded solver's first face,
``Q_{1/2} = (q_0 + q_1)/2`` with the pressure-driven flux (the first-order difference
``(q_1 - q_0)/h`` at ``i = 1``), so its limit is the core's scheme. A starved inlet lets in
exactly the supplied layer: ``Q_{1/2} = q_0 = Hoil`` and no pressure flow through the first
face (upstream of the meniscus the layer's flux is uniform, ghost ``q_{-1} = q_0``; the
wedge difference at ``i = 1`` is ``1.5 (q_1 - q_0)/h``). Without that, the discrete problem
also has a spurious solution with the meniscus on the inlet node and part of the supply
pushed back out through the boundary (measured on 65 points, M = 20, L = 10, Hoil = 0.05:
inflow 0.025 and a film a quarter of the right one).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..line.discrete import FINE_H, wedge_coefficients


@njit(cache=True)
def wedge_weights(i, order, starved):
    """Upwind weights ``c_m`` of ``q_{i-m}`` (times ``h``): the flooded solver's
    (``wedge_coefficients``), except at ``i = 1`` of a starved inlet (``1.5, -1.5``)."""
    if starved and order == 2 and i == 1:
        return 1.5, -1.5, 0.0
    return wedge_coefficients(i, order)


@njit(cache=True)
def starved_inlet_correction(r, q, eps, P, h, order):
    """Turn the flooded solver's residual at ``i = 1`` into the starved inlet's (in place):
    wedge ``1.5 (q_1 - q_0)/h`` instead of ``(q_1 - q_0)/h`` and no pressure flow through
    the first face."""
    if order == 2:
        r[1] += 0.5 * (q[1] - q[0]) / h
    r[1] -= 0.5 * (eps[0] + eps[1]) * (P[1] - P[0]) / (h * h)


@njit(cache=True)
def face_fluxes(P, q, eps, h, order, starved):
    """Mass flux ``Q_{i+1/2} - eps_{i+1/2} (P_{i+1} - P_i)/h`` through every face
    ``i + 1/2``, ``i = 0 .. n-2`` (the fluxes whose differences are the discrete operator)."""
    n = P.shape[0]
    F = np.empty(n - 1)
    for i in range(n - 1):
        e = 0.5 * (eps[i] + eps[i + 1])
        if order == 2 and i >= 1:
            Q = 1.5 * q[i] - 0.5 * q[i - 1]
        elif order == 2 and not starved:
            Q = 0.5 * (q[0] + q[1])
        else:
            Q = q[i]
        if i == 0 and starved:
            e = 0.0
        F[i] = Q - e * (P[i + 1] - P[i]) / h
    return F


@njit(cache=True)
def cavitated(P, theta, r, frozen):
    """Regime of each interior point: True where ``theta`` is the unknown (``P = 0`` and either
    ``theta < 1`` or a residual that would push the pressure negative, ``r > 0``)."""
    n = P.shape[0]
    cav = np.zeros(n, dtype=np.bool_)
    for i in range(1, n - 1):
        if frozen[i]:
            continue
        if P[i] <= 0.0 and (theta[i] < 1.0 or r[i] > 0.0):
            cav[i] = True
    return cav


@njit(cache=True)
def starved_relaxation_system(P, theta, q0_fixed, H, rho, drho, eps, r, K, h, order, elastic,
                              threshold, band, frozen, cav, threshold_h):
    """Banded system of one collective line-relaxation sweep in the universal variable.

    Pressurised points get the change of ``P`` (Gauss-Seidel, or Jacobi-distributive where
    ``eps/h^2`` is below the switch, as in the flooded solver, when both neighbours are
    pressurised too); cavitated points (``cav``) get the change of ``theta``, whose column is
    ``dL_i/dtheta_j = -c_{i-j} rho_j H_j/h`` (upwind weights). ``eps`` and the film content are
    frozen in the pressure columns (Picard); the film's dependence on ``P`` is kept within the
    band. ``q0_fixed``: the inlet flux ``q_0`` does not depend on ``P`` (a starved inlet
    supplies exactly the oil layer).

    Returns ``(ab, rhs, jac, dP, dT)``: LAPACK band storage of the matrix of the interior
    unknowns, right-hand side, Jacobi flags, and the diagonal derivatives ``dL_i/dP_i`` and
    ``dL_i/dtheta_i`` (to convert a change that crosses the regime boundary).
    """
    n = P.shape[0]
    m = n - 2
    wq = band + 1
    AP = np.zeros((n, 2 * wq + 1))
    AT = np.zeros((n, 3))  # dL_i/dtheta_{i-mm}, mm = 0, 1, 2
    ih2 = 1.0 / (h * h)
    inv_pi = 1.0 / np.pi
    for i in range(1, n - 1):
        ep = 0.5 * (eps[i] + eps[i + 1])
        em = 0.5 * (eps[i] + eps[i - 1])
        if i == 1 and q0_fixed:
            em = 0.0  # no pressure flow through a starved inlet's face
        AP[i, wq - 1] += em * ih2
        AP[i, wq] += -(ep + em) * ih2
        AP[i, wq + 1] += ep * ih2
        c0, c1, c2 = wedge_weights(i, order, q0_fixed)
        for mm in range(3):
            c = c0 if mm == 0 else (c1 if mm == 1 else c2)
            if c == 0.0:
                continue
            k = i - mm
            AT[i, mm] = -c * rho[k] * H[k] / h
            if k == 0 and q0_fixed:
                continue
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
                AP[i, wq + d] -= c * theta[k] * val / h
    jac = np.zeros(n, dtype=np.bool_)
    thr = max(threshold, threshold_h / h) if h < FINE_H else threshold
    for j in range(1, n - 1):
        if cav[j] or cav[j - 1] or cav[j + 1]:
            continue
        e = max(eps[j - 1], eps[j], eps[j + 1])
        jac[j] = e * ih2 < thr
    ab = np.zeros((2 * band + 1, m))
    rhs = np.zeros(m)
    for i in range(1, n - 1):
        row = i - 1
        if frozen[i]:
            ab[band, row] = 1.0
            continue
        rhs[row] = r[i]
        for d in range(-band, band + 1):
            j = i + d
            if j < 1 or j > n - 2 or frozen[j]:
                continue
            if cav[j]:
                mm = i - j
                b = AT[i, mm] if 0 <= mm <= 2 else 0.0
            else:
                b = AP[i, wq + d]
                if jac[j]:
                    if j - 1 >= 1:
                        b -= 0.5 * AP[i, wq + d - 1]
                    if j + 1 <= n - 2:
                        b -= 0.5 * AP[i, wq + d + 1]
            ab[band + row - (j - 1), j - 1] = b
    dP = np.zeros(n)
    dT = np.zeros(n)
    for i in range(1, n - 1):
        dP[i] = AP[i, wq]
        dT[i] = AT[i, 0]
    return ab, rhs, jac, dP, dT


@njit(cache=True)
def apply_changes(P, theta, delta, jac, cav, dP, dT, omega_gs, omega_jac, omega_theta, frozen):
    """Apply the under-relaxed changes of one sweep and move points across the regime
    boundary: a pressure that would fall below 0 becomes a film content below 1 and a film
    content above 1 a positive pressure, converted with the diagonal derivatives so the change
    of the residual is the one the sweep asked for. ``theta`` never falls below a fifth of its
    previous value (it stays positive)."""
    n = P.shape[0]
    dPv = np.zeros(n)
    dTv = np.zeros(n)
    for j in range(1, n - 1):
        if frozen[j]:
            continue
        d = delta[j - 1]
        if cav[j]:
            dTv[j] += omega_theta * d
        elif jac[j]:
            d *= omega_jac
            dPv[j] += d
            dPv[j - 1] -= 0.5 * d
            dPv[j + 1] -= 0.5 * d
        else:
            dPv[j] += omega_gs * d
    Pn = P.copy()
    Tn = theta.copy()
    for j in range(1, n - 1):
        if frozen[j]:
            continue
        if cav[j]:
            t = theta[j] + dTv[j]
            if t > 1.0:
                Tn[j] = 1.0
                ratio = dT[j] / dP[j] if dP[j] != 0.0 else 0.0
                Pn[j] = (t - 1.0) * ratio if ratio > 0.0 else 0.0
            else:
                Tn[j] = max(t, 0.2 * theta[j])
                Pn[j] = 0.0
        else:
            p = P[j] + dPv[j]
            if p >= 0.0:
                Pn[j] = p
                Tn[j] = 1.0
            else:
                Pn[j] = 0.0
                ratio = dP[j] / dT[j] if dT[j] != 0.0 else 0.0
                t = 1.0 + p * ratio if ratio > 0.0 else 1.0
                Tn[j] = min(1.0, max(t, 0.2 * theta[j]))
    Pn[0] = 0.0
    Pn[n - 1] = 0.0
    return Pn, Tn
