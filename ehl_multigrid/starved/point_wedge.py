"""Conservative wedge term ``d(theta rho H)/dX`` of the starved point contact with a per-face
order: second order where the film is full, first order at the fronts (numba kernels).

The wedge term at an interior point is a difference of face values of the mass flux
``q = theta rho H`` (Elrod 1981; the flux form of Venner & Lubrecht 2000, ch. 4, with the
Elrod-Adams film content of Woloszynski et al. 2015):

    W_i = (Q_{i+1/2} - Q_{i-1/2}) / hx,

    Q_{i+1/2} = 1.5 q_i - 0.5 q_{i-1}   where the upstream point is full (theta_{i-1} = 1),
    Q_{i+1/2} = q_i                      otherwise (behind an unfilled point: the starved
                                         inlet, the meniscus, inside the cavitated outlet),
    Q_{1/2}   = (q_0 + q_1)/2            at a flooded inlet node (theta_0 = 1), else q_0.

Where the film is full the scheme is the point core's second-order upwind difference
``(1.5 q_i - 2 q_{i-1} + 0.5 q_{i-2})/hx`` (and its first-order difference at ``i = 1``, which
is the central first face), so a flooded inlet reproduces the core's default (second-order)
flooded film. The faces telescope: the sum of the residuals is the imbalance of the boundary
flows, whatever the face orders (discrete mass conservation). The line contact
(:func:`ehl_multigrid.starved.discrete.face_weights`) blends to first order as either point's
content falls below full (continuously, for its dense Newton); here the
order of a face must not depend on the film content of the point whose balance it closes
(see :func:`face_value`): only the first cavitated point's outgoing face extrapolates across
the rupture, where ``q`` is continuous.

The relaxation uses the point core's line kernel unchanged, with a *defect correction* of the
right-hand side, ``f + (W_lim - W_core)``, computed from the sweep's frozen film
(:func:`wedge_correction`): each line system then solves the per-face equation at the sweep's
film, only its film-response Jacobian is the kernel's (first-order weights,
``starved.point.KERNEL_ORDER``; measured faster than the second-order ones at the meniscus).
"""

from __future__ import annotations

from numba import njit, prange

from ..point import numerics as nm


@njit(cache=True)
def face_value(rq, H, theta, j, i, order):
    """Convective face value ``Q_{i+1/2}`` of row ``j`` (``q = rq H``, ``rq = theta rho``):
    ``order = 1`` first-order upwind everywhere; ``order = 2`` the second-order upwind value
    ``q_i + (q_i - q_{i-1})/2`` where the film is full at the upstream point ``i - 1`` (the
    first face: central ``(q_0 + q_1)/2`` when the inlet node is full), first order
    ``q_i`` otherwise. The order does not depend on ``theta_i``: each point's mass balance is
    then continuous in its own film content (a face that turns second order when
    ``theta_i`` reaches 1 leaves a gap of ``(q_i - q_{i-1})/2`` in which neither
    ``theta_i < 1`` nor ``P_i > 0`` balances the point; measured: the flooded (20, 10) solve
    at 129^2 stalled at a residual of 6e-6 on the rupture line)."""
    qi = rq[j, i] * H[j, i]
    if order == 2:
        if i >= 1:
            if theta[j, i - 1] >= 1.0:
                return 1.5 * qi - 0.5 * rq[j, i - 1] * H[j, i - 1]
        elif theta[j, 0] >= 1.0:
            return 0.5 * (qi + rq[j, 1] * H[j, 1])
    return qi


@njit(cache=True)
def _limited_wedge_row(rq, H, theta, j, hx, order, out):
    """``out[j, i] = (Q_{i+1/2} - Q_{i-1/2})/hx`` at the interior points of row ``j``, with the
    face values of :func:`face_value` (shared by the operator and the defect correction)."""
    nx = H.shape[1]
    qm = face_value(rq, H, theta, j, 0, order)
    for i in range(1, nx - 1):
        qp = face_value(rq, H, theta, j, i, order)
        out[j, i] = (qp - qm) / hx
        qm = qp


@njit(cache=True, parallel=True)
def flux_operator(P, H, rq, eps, theta, hx, hy, sym, order, out, ct=0.0):
    """Discrete Elrod-Adams operator ``L = Poiseuille - (Q_{i+1/2} - Q_{i-1/2})/hx - ct q_i``
    at the interior points (0 on the boundary), with the face values of :func:`face_value`;
    ``ct q_i`` (``q = rq H``) is the new-time part of a BDF squeeze term ``d(theta rho H)/dT``
    (``ct = 0``: steady)."""
    ny, nx = P.shape
    hx2, hy2 = hx * hx, hy * hy
    j0 = 0 if sym else 1
    for j in prange(ny):
        for i in range(nx):
            out[j, i] = 0.0
        if j < j0 or j > ny - 2:
            continue
        jm = 1 if (sym and j == 0) else j - 1
        _limited_wedge_row(rq, H, theta, j, hx, order, out)
        for i in range(1, nx - 1):
            out[j, i] = (nm._poiseuille(P, eps, j, jm, j + 1, i, hx2, hy2) - out[j, i]
                         - ct * rq[j, i] * H[j, i])


@njit(cache=True, parallel=True)
def wedge_correction(rq, H, theta, hx, sym, order, core_order, out):
    """Defect correction of the line kernel's right-hand side: ``W_lim - W_core`` at the
    interior points, ``W_lim`` the limited wedge of ``order`` and ``W_core`` the point core's
    wedge ``nm._wedge`` of ``core_order`` (the one inside :func:`nm.relax_sweep`)."""
    ny, nx = H.shape
    j0 = 0 if sym else 1
    for j in prange(ny):
        for i in range(nx):
            out[j, i] = 0.0
        if j < j0 or j > ny - 2:
            continue
        _limited_wedge_row(rq, H, theta, j, hx, order, out)
        for i in range(1, nx - 1):
            out[j, i] -= nm._wedge(rq, H, j, i, hx, core_order, 0.0)


@njit(cache=True)
def march_theta(P, H, rho, eps, theta, f, hx, hy, sym, hoil_rows, order=1, ct=0.0):
    """Solve each unpressurised point's discrete mass balance
    ``Q_{i+1/2} - Q_{i-1/2} + hx ct q_i = hx (Poiseuille_i - f_i)`` for ``theta_i`` (marching
    along X with the face values of :func:`face_value`, linear in ``theta_i``); ``theta = 1``
    where ``P > 0``; clipped to ``[0, 1]``. Column 0 of row ``j`` carries the supply
    ``q = hoil_rows[j]`` (``theta <= 1``). ``ct q_i`` is the new-time part of a BDF squeeze
    term ``d(theta rho H)/dT`` (its history part is in ``f``; ``ct = 0``: steady)."""
    ny, nx = P.shape
    hx2, hy2 = hx * hx, hy * hy
    j0 = 0 if sym else 1
    for j in range(ny):
        q0 = hoil_rows[j]
        t0 = q0 / (rho[j, 0] * H[j, 0]) if H[j, 0] > 0.0 else 1.0
        theta[j, 0] = 1.0 if t0 > 1.0 else t0
        if j < j0 or j > ny - 2:
            for i in range(1, nx):  # boundary rows: P = 0, the supply is carried along
                theta[j, i] = theta[j, 0]
            continue
        jm = 1 if (sym and j == 0) else j - 1
        for i in range(1, nx - 1):
            if P[j, i] > 0.0:
                theta[j, i] = 1.0
                continue
            src = hx * (nm._poiseuille(P, eps, j, jm, j + 1, i, hx2, hy2) - f[j, i])
            d = rho[j, i] * H[j, i]
            qm = theta[j, i - 1] * rho[j, i - 1] * H[j, i - 1]
            if order == 2 and i >= 2:
                # Q_out = (1 + m/2) theta_i d - (m/2) q_{i-1}, m: the point i - 1 is full
                qin = qm
                if theta[j, i - 2] >= 1.0:
                    qin = 1.5 * qm - 0.5 * theta[j, i - 2] * rho[j, i - 2] * H[j, i - 2]
                if theta[j, i - 1] >= 1.0:
                    q = (qin + src + 0.5 * qm) / (1.5 + hx * ct)
                else:
                    q = (qin + src) / (1.0 + hx * ct)
            else:
                # first order; at i = 1 also the second-order scheme's balance (the central
                # first face and the second-order second face differ by q_1 - q_0)
                q = (qm + src) / (1.0 + hx * ct)
            t = q / d if d > 0.0 else 1.0
            theta[j, i] = 1.0 if t > 1.0 else (0.0 if t < 0.0 else t)
        theta[j, nx - 1] = theta[j, nx - 2]
