"""Discrete mass-conserving (Elrod-Adams) line-contact Reynolds equation, numba kernels.

Venner's dimensionless line contact (thesis (2.1)-(2.3) in the form of Venner & Lubrecht
2000) with the film content ``theta`` (fraction of the gap filled with oil) in the wedge term:

``L_i = [eps_{i+1/2}(P_{i+1}-P_i) - eps_{i-1/2}(P_i-P_{i-1})]/h^2 - D_i(theta rho H)``,
``P_i (1 - theta_i) = 0``, ``P_i >= 0``, ``0 < theta_i <= 1`` (Elrod & Adams 1974; Elrod 1981).

``D_i`` is the flooded solver's upwind difference (ehl_multigrid.line.discrete) wherever the
film is full, written as a difference of face fluxes (:func:`wedge_row`,
:func:`elrod_adams_residual`). Every interior point satisfies the equation (no inequality as in
the Reynolds condition): a pressurised point (``theta = 1``) has ``P`` as its unknown, a cavitated or
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
face (upstream of the meniscus the layer's flux is uniform); faces next to a point that is
not full are first order (:func:`face_weights`). Without the inlet face rule, the discrete problem
also has a spurious solution with the meniscus on the inlet node and part of the supply
pushed back out through the boundary (measured on 65 points, M = 20, L = 10, Hoil = 0.05:
inflow 0.025 and a film a quarter of the right one).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..line.discrete import FINE_H, add_wedge_band
from ..multigrid.flux import eps_face


@njit(cache=True)
def face_weights(i, theta, order, starved):
    """Weights ``(w_i, w_{i-1})`` of the upwind face value ``Q_{i+1/2} = w_i q_i + w_{i-1} q_{i-1}``:
    second order (1.5, -0.5); with a starved inlet, first order (1, 0) where either point is
    well below full (a front or a cavitated zone: the second-order extrapolation across the
    jump of ``theta`` at the meniscus undershoots -- measured: a meniscus cell emptied below
    the supplied flux and a relaxation stuck at a residual of 0.4), the share of second order
    falling continuously with the content (:func:`second_order_share`: a switch at full made
    the residual jump when a pressurised point's content fell below 1, and a dent's steps
    stalled with a point flipping between the regimes); the first face: ``q_0`` at a
    starved inlet, ``(q_0 + q_1)/2`` at a flooded one (the flooded solver's first-order
    difference at i = 1). With a flooded inlet the scheme is the flooded solver's everywhere
    (``theta`` only enters behind the rupture point)."""
    if i == 0:
        if starved or order == 1:
            return 1.0, 0.0
        return 0.5, 0.5  # weights of (q_0, q_1): see wedge_row
    if order == 2 and not starved:
        return 1.5, -0.5
    if order == 2:
        b = second_order_share(theta[i]) * second_order_share(theta[i - 1])
        return 1.0 + 0.5 * b, -0.5 * b
    return 1.0, 0.0


#: film content below which a starved inlet's face value is first order (see face_weights)
THETA_FIRST_ORDER = 0.9


@njit(cache=True)
def second_order_share(t):
    """Share of the second-order face value a point of film content ``t`` allows: 1 in a
    full film, 0 at or below :data:`THETA_FIRST_ORDER`, linear between (continuous, so that
    the residual is a continuous function of ``theta``)."""
    if t >= 1.0:
        return 1.0
    if t <= THETA_FIRST_ORDER:
        return 0.0
    return (t - THETA_FIRST_ORDER) / (1.0 - THETA_FIRST_ORDER)


@njit(cache=True)
def second_order_slope(t):
    """Derivative of :func:`second_order_share` (from below at ``t = 1``: the content of a
    full point can only fall)."""
    if THETA_FIRST_ORDER < t <= 1.0:
        return 1.0 / (1.0 - THETA_FIRST_ORDER)
    return 0.0


@njit(cache=True)
def wedge_share_terms(i, theta, q, order, starved):
    """``d(Q_{i+1/2} - Q_{i-1/2})/d theta_{i-mm}``, ``mm = 0, 1, 2``, through the faces'
    second-order shares alone (the part :func:`wedge_row`'s weights times ``rho H`` leave out;
    ``q = rho H``); zero unless the inlet is starved and the scheme second order."""
    e0 = 0.0
    e1 = 0.0
    e2 = 0.0
    if order != 2 or not starved:
        return e0, e1, e2
    d = 0.5 * (theta[i] * q[i] - theta[i - 1] * q[i - 1])  # face i+1/2
    e0 += d * second_order_slope(theta[i]) * second_order_share(theta[i - 1])
    e1 += d * second_order_share(theta[i]) * second_order_slope(theta[i - 1])
    if i >= 2:  # face i-1/2 (the first face of a starved inlet is first order)
        d = 0.5 * (theta[i - 1] * q[i - 1] - theta[i - 2] * q[i - 2])
        e1 -= d * second_order_slope(theta[i - 1]) * second_order_share(theta[i - 2])
        e2 -= d * second_order_share(theta[i - 1]) * second_order_slope(theta[i - 2])
    return e0, e1, e2


@njit(cache=True)
def wedge_row(i, theta, order, starved):
    """Upwind weights ``(c_0, c_1, c_2)`` of ``q_i, q_{i-1}, q_{i-2}`` (times ``h``) in the
    wedge difference ``(Q_{i+1/2} - Q_{i-1/2})/h`` at interior point ``i``; equal to the
    flooded solver's ``wedge_coefficients`` where the film is full."""
    a0, a1 = face_weights(i, theta, order, starved)
    c0, c1, c2 = a0, a1, 0.0
    if i == 1:
        b0, b1 = face_weights(0, theta, order, starved)
        if b1 != 0.0:  # flooded first face (q_0 + q_1)/2
            c0 -= b1
            c1 -= b0
        else:
            c1 -= b0
    else:
        b0, b1 = face_weights(i - 1, theta, order, starved)
        c1 -= b0
        c2 -= b1
    return c0, c1, c2


@njit(cache=True)
def elrod_adams_residual(P, H, rho, theta, eps, h, f, order, starved, face=0):
    """Residual ``r = f - L(P, theta)`` (zero at the boundary points) and the sum of the
    absolute Poiseuille and wedge terms (the scale of the relative residual). No pressure
    flow passes the first face of a starved inlet."""
    n = P.shape[0]
    r = np.zeros(n)
    scale = 0.0
    ih2 = 1.0 / (h * h)
    for i in range(1, n - 1):
        ep = eps_face(eps[i], eps[i + 1], face)
        em = eps_face(eps[i], eps[i - 1], face)
        if i == 1 and starved:
            em = 0.0
        pois = (ep * (P[i + 1] - P[i]) - em * (P[i] - P[i - 1])) * ih2
        c0, c1, c2 = wedge_row(i, theta, order, starved)
        q = c0 * theta[i] * rho[i] * H[i] + c1 * theta[i - 1] * rho[i - 1] * H[i - 1]
        if c2 != 0.0:
            q += c2 * theta[i - 2] * rho[i - 2] * H[i - 2]
        wedge = q / h
        r[i] = f[i] - (pois - wedge)
        scale += abs(pois) + abs(wedge)
    return r, scale


@njit(cache=True)
def march_cavitated_content(P, theta, q, eps, f, h, order, starved, cav, ct, hist, face=0):
    """Film content ``theta_i`` of the cavitated points ``cav`` (ascending) that makes row ``i``
    of :func:`elrod_adams_residual` zero given its upwind neighbours and ``P`` (in place,
    clipped to [0, 1]); ``q = rho H``; a time step's rows add ``ct theta_i q_i - hist_i``
    (``ct = 0`` for a steady problem)."""
    ih2 = 1.0 / (h * h)
    for k in range(cav.shape[0]):
        i = cav[k]
        ep = eps_face(eps[i], eps[i + 1], face)
        em = 0.0 if (i == 1 and starved) else eps_face(eps[i], eps[i - 1], face)
        pois = (ep * (P[i + 1] - P[i]) - em * (P[i] - P[i - 1])) * ih2
        c0, c1, c2 = wedge_row(i, theta, order, starved)
        rest = c1 * theta[i - 1] * q[i - 1]
        if c2 != 0.0:
            rest += c2 * theta[i - 2] * q[i - 2]
        t = (h * (pois - f[i] + hist[i]) - rest) / ((c0 + h * ct) * q[i])
        theta[i] = min(max(t, 0.0), 1.0)


@njit(cache=True)
def face_fluxes(P, theta, q, eps, h, order, starved, face=0):
    """Mass flux ``Q_{i+1/2} - eps_{i+1/2} (P_{i+1} - P_i)/h`` through every face
    ``i + 1/2``, ``i = 0 .. n-2`` (the fluxes whose differences are the discrete operator)."""
    n = P.shape[0]
    F = np.empty(n - 1)
    for i in range(n - 1):
        e = eps_face(eps[i], eps[i + 1], face)
        w0, w1 = face_weights(i, theta, order, starved)
        if i == 0:
            Q = w0 * q[0] + w1 * q[1]
            if starved:
                e = 0.0
        else:
            Q = w0 * q[i] + w1 * q[i - 1]
        F[i] = Q - e * (P[i + 1] - P[i]) / h
    return F


@njit(cache=True)
def cavitated(P, theta, r, frozen, H):
    """Regime of each interior point: True where ``theta`` is the unknown (``P = 0`` and either
    ``theta < 1`` or a residual that would push the pressure negative, ``r > 0``). A point
    whose gap is closed (``H <= 0``, a coarse grid's elastic dent at a sharp meniscus) keeps
    the pressure as its unknown: there ``dL/dtheta`` changes sign, so a film-content change
    would empty it for good (measured: an empty, negative-gap pocket at the meniscus that
    stopped the relaxation at a residual of 0.4)."""
    n = P.shape[0]
    cav = np.zeros(n, dtype=np.bool_)
    for i in range(1, n - 1):
        if frozen[i] or H[i] <= 0.0:
            continue
        if P[i] <= 0.0 and (theta[i] < 1.0 or r[i] > 0.0):
            cav[i] = True
    return cav


@njit(cache=True)
def band_jacobian(P, theta, q0_fixed, H, rho, drho, eps, K, h, order, elastic, band, face=0):
    """Band parts of the Jacobian of ``L`` for one collective line-relaxation sweep.

    ``AP[i, band + 1 + d] = dL_i/dP_{i+d}`` for ``|d| <= band + 1``, with ``eps`` and the film
    content frozen (Picard) and the film's elastic dependence on ``P`` kept within the band;
    ``AT[i, mm] = dL_i/dtheta_{i-mm} = -c_mm rho H/h`` (upwind weights, ``mm = 0, 1, 2``; the
    faces' second-order shares held: with their derivative, which the dense Newton keeps, the
    coupled starved start of (20, 10) fed 0.05 on 257 points diverged).
    ``q0_fixed``: a starved inlet's flux ``q_0 = Hoil`` does not depend on ``P``, and no
    pressure flow passes its first face.
    """
    n = P.shape[0]
    wq = band + 1
    AP = np.zeros((n, 2 * wq + 1))
    AT = np.zeros((n, 3))
    ih2 = 1.0 / (h * h)
    for i in range(1, n - 1):
        ep = eps_face(eps[i], eps[i + 1], face)
        em = eps_face(eps[i], eps[i - 1], face)
        if i == 1 and q0_fixed:
            em = 0.0
        AP[i, wq - 1] += em * ih2
        AP[i, wq] += -(ep + em) * ih2
        AP[i, wq + 1] += ep * ih2
        c0, c1, c2 = wedge_row(i, theta, order, q0_fixed)
        for mm in range(3):
            c = c0 if mm == 0 else (c1 if mm == 1 else c2)
            if c == 0.0:
                continue
            k = i - mm
            AT[i, mm] = -c * rho[k] * H[k] / h
            if k == 0 and q0_fixed:
                continue
            add_wedge_band(AP, i, k, c * theta[k], H, rho, drho, K, h, elastic, wq)
    return AP, AT


@njit(cache=True)
def line_system(AP, AT, r, P, theta, cav, frozen, eps, h, threshold, threshold_h, band):
    """Band system of the sweep for a given regime of every point (``cav``: ``theta`` is the
    unknown). A point whose regime differs from its current state starts from the regime
    boundary: its known move there (``P -> 0`` or ``theta -> 1``) goes to the right-hand side,
    so the system is the linearisation of the residual on the new regime (one step of a
    primal-dual active-set iteration). Pressurised points are Jacobi-distributive where
    ``eps/h^2`` is below the switch (as in the flooded solver) and both neighbours are
    pressurised. Returns ``(ab, rhs, jac)`` (LAPACK band storage of the interior unknowns)."""
    n = P.shape[0]
    m = n - 2
    wq = band + 1
    ih2 = 1.0 / (h * h)
    jac = np.zeros(n, dtype=np.bool_)
    thr = max(threshold, threshold_h / h) if h < FINE_H else threshold
    for j in range(1, n - 1):
        if cav[j] or cav[j - 1] or cav[j + 1] or frozen[j]:
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
        for d in range(-wq, wq + 1):
            j = i + d
            if j < 1 or j > n - 2 or frozen[j]:
                continue
            mm = i - j
            # known move of a point that changes regime
            if cav[j] and P[j] > 0.0:
                rhs[row] += AP[i, wq + d] * P[j]
            elif not cav[j] and theta[j] < 1.0 and 0 <= mm <= 2:
                rhs[row] -= AT[i, mm] * (1.0 - theta[j])
            if d < -band or d > band:
                continue
            if cav[j]:
                b = AT[i, mm] if 0 <= mm <= 2 else 0.0
            else:
                b = AP[i, wq + d]
                if jac[j]:
                    b -= 0.5 * AP[i, wq + d - 1]
                    b -= 0.5 * AP[i, wq + d + 1]
            ab[band + row - (j - 1), j - 1] = b
    return ab, rhs, jac


@njit(cache=True)
def regime_update(P, theta, delta, cav, frozen):
    """Regimes after a trial solve: a film content pushed above 1 becomes a pressure, a
    pressure pushed below 0 a film content. Returns the new regimes and how many changed."""
    n = P.shape[0]
    new = cav.copy()
    changed = 0
    for j in range(1, n - 1):
        if frozen[j]:
            continue
        d = delta[j - 1]
        if cav[j]:
            base = theta[j] if P[j] <= 0.0 else 1.0
            if base + d > 1.0:
                new[j] = False
                changed += 1
        else:
            base = P[j] if theta[j] >= 1.0 else 0.0
            if base + d < 0.0:
                new[j] = True
                changed += 1
    return new, changed


@njit(cache=True)
def apply_changes(P, theta, delta, jac, cav, omega_gs, omega_jac, omega_theta, frozen):
    """Apply the under-relaxed changes of one sweep in the regimes ``cav``: a point that
    changed regime starts from the boundary (``P = 0``, ``theta = 1``); pressures are
    projected to ``P >= 0`` and film contents to ``theta <= 1``; ``theta`` never falls below
    a fifth of its previous value (it stays positive)."""
    n = P.shape[0]
    dPv = np.zeros(n)
    for j in range(1, n - 1):
        if frozen[j] or cav[j]:
            continue
        d = delta[j - 1]
        if jac[j]:
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
            base = theta[j] if P[j] <= 0.0 else 1.0
            t = base + omega_theta * delta[j - 1]
            Tn[j] = min(1.0, max(t, 0.2 * theta[j]))
            Pn[j] = 0.0
        else:
            base = P[j] if theta[j] >= 1.0 else 0.0
            p = base + dPv[j]
            Pn[j] = p if p > 0.0 else 0.0
            Tn[j] = 1.0
    Pn[0] = 0.0
    Pn[n - 1] = 0.0
    return Pn, Tn
