"""Compiled kernels of the point-contact solver: lubricant relations, the discrete Reynolds
operator, zebra line relaxation and grid transfers.

Arrays are ``[j, i]`` = (Y row, X column); lines run along X. ``sym`` marks a half-domain
grid whose row 0 is the centre line Y = 0 (mirror neighbour row 1).

Discretisation of ``d/dX(eps dP/dX) + d/dY(eps dP/dY) - d(rho H)/dX``: central 5-point
Poiseuille terms with ``eps`` averaged to the cell faces; the wedge term upwind, second order
``(1.5 q_i - 2 q_{i-1} + 0.5 q_{i-2})/hx`` (first order next to the inlet boundary), or first
order when ``order == 1``.

The relaxation sweeps, the lubricant properties and the local film update run their rows in
parallel (``prange``). The single streaming passes (film, operator, residual, transfers) are
serial: together they take under 5 % of a point solve, and ``parallel=True`` makes a kernel's
compilation two to five times longer, which a fresh environment pays on its first run.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from ..multigrid.rheology import density, log_viscosity


# -- lubricant ---------------------------------------------------------------------------------
@njit(cache=True, parallel=True)
def fluid_properties(P, H, par, lam, rho, eps):
    """Fill ``rho`` (rho/rho0) and ``eps = rho H^3/(eta lambda)`` from P and H, with the
    viscosity (Roelands (2.6) or Barus (2.4)) and density (Dowson-Higginson (2.7) or constant)
    of the packed parameters ``par`` (:func:`ehl_multigrid.multigrid.rheology.pack`).
    Negative pressure counts as zero; a negative film (never at convergence) gives eps = 0.
    """
    ny, nx = P.shape
    # unloaded points (P <= 0: the cavitated outlet and the far field, most of the domain)
    # share one value of the rheology, computed once: the same numbers, without the
    # exponentials and powers
    r0 = density(0.0, par)[0]
    e0 = math.exp(-log_viscosity(0.0, par)[0])
    for j in prange(ny):
        for i in range(nx):
            p = P[j, i]
            h = H[j, i]
            if h < 0.0:
                h = 0.0
            if p <= 0.0:
                rho[j, i] = r0
                eps[j, i] = r0 * h * h * h * e0 / lam
                continue
            r = density(p, par)[0]
            lne = log_viscosity(p, par)[0]
            rho[j, i] = r
            eps[j, i] = r * h * h * h * math.exp(-lne) / lam


@njit(cache=True, parallel=True)
def local_film_update(H, P, P_old, K, sym):
    """``H += sum K[|dj|, |di|] (P - P_old)[j + dj, i + di]`` over ``|dj| < K.shape[0]``,
    ``|di| < K.shape[1]``: the near part of the deformation's change (K = cd times the cell
    kernel's nearest offsets; rows mirrored at Y = 0 when ``sym``)."""
    ny, nx = H.shape
    ky, kx = K.shape
    for j in prange(ny):
        for i in range(nx):
            s = 0.0
            for dj in range(-ky + 1, ky):
                jj = j + dj
                if sym and jj < 0:
                    jj = -jj
                if jj < 0 or jj >= ny:
                    continue
                kr = dj if dj >= 0 else -dj
                for di in range(-kx + 1, kx):
                    ii = i + di
                    if ii < 0 or ii >= nx:
                        continue
                    d = P[jj, ii] - P_old[jj, ii]
                    if d != 0.0:
                        s += K[kr, di if di >= 0 else -di] * d
            H[j, i] += s


@njit(cache=True)
def film(W, X, Y, H00, theta, cd, H):
    """``H = H00 + X^2/2 + theta Y^2/2 + cd W``."""
    ny, nx = W.shape
    for j in range(ny):
        gy = 0.5 * theta * Y[j] * Y[j]
        for i in range(nx):
            H[j, i] = H00 + 0.5 * X[i] * X[i] + gy + cd * W[j, i]


@njit(cache=True)
def _wedge(rho, H, j, i, hx, order, ct=0.0):
    """Upwind ``d(rho H)/dX`` plus ``ct rho H``, the new-time part of a BDF squeeze term
    ``d(rho H)/dT`` (``ct = 0``: steady)."""
    if order == 2 and i >= 2:
        return (1.5 * rho[j, i] * H[j, i] - 2.0 * rho[j, i - 1] * H[j, i - 1]
                + 0.5 * rho[j, i - 2] * H[j, i - 2]) / hx + ct * rho[j, i] * H[j, i]
    return (rho[j, i] * H[j, i] - rho[j, i - 1] * H[j, i - 1]) / hx + ct * rho[j, i] * H[j, i]


@njit(cache=True)
def _poiseuille(P, eps, j, jm, jp, i, hx2, hy2):
    e = eps[j, i]
    exm = 0.5 * (eps[j, i - 1] + e)
    exp_ = 0.5 * (eps[j, i + 1] + e)
    eym = 0.5 * (eps[jm, i] + e)
    eyp = 0.5 * (eps[jp, i] + e)
    p = P[j, i]
    return ((exm * (P[j, i - 1] - p) + exp_ * (P[j, i + 1] - p)) / hx2
            + (eym * (P[jm, i] - p) + eyp * (P[jp, i] - p)) / hy2)


@njit(cache=True)
def operator(P, H, rho, eps, hx, hy, sym, order, out, ct=0.0):
    """Discrete Reynolds operator ``L(P)`` at interior points (0 on the boundary)."""
    ny, nx = P.shape
    hx2, hy2 = hx * hx, hy * hy
    j0 = 0 if sym else 1
    for j in range(ny):
        for i in range(nx):
            out[j, i] = 0.0
        if j < j0 or j > ny - 2:
            continue
        jm = 1 if (sym and j == 0) else j - 1
        for i in range(1, nx - 1):
            out[j, i] = _poiseuille(P, eps, j, jm, j + 1, i, hx2, hy2) - _wedge(rho, H, j, i, hx, order, ct)


@njit(cache=True)
def residual(P, H, rho, eps, f, hx, hy, sym, order, out, ct=0.0):
    """Complementarity residual: ``f - L(P)`` where P > 0; where P = 0 only the part that
    would raise P (``min(r, 0)``) counts (cavitation as complementarity)."""
    operator(P, H, rho, eps, hx, hy, sym, order, out, ct)
    ny, nx = P.shape
    j0 = 0 if sym else 1
    for j in range(j0, ny - 1):
        for i in range(1, nx - 1):
            r = f[j, i] - out[j, i]
            if P[j, i] <= 0.0 and r > 0.0:
                r = 0.0
            out[j, i] = r


@njit(cache=True)
def scaled_residual(r, H, rho, eps, K00, hx, hy, sym, out, ct=0.0):
    """Residual divided by the magnitude of the operator's diagonal,
    ``|sum of face eps|/h^2 + 1.5 rho K00/hx`` (K00 = cd K[0,0], the film self-response): the
    pressure change (in units of pmax) that one Jacobi step would make. Unlike the raw
    residual it does not give weight to the cavitation front far from the contact, where
    eps/h^2 is huge but P ~ 0. Infinite where the diagonal vanishes and the residual does not
    (rigid surfaces in contact)."""
    ny, nx = r.shape
    hx2, hy2 = hx * hx, hy * hy
    j0 = 0 if sym else 1
    for j in range(ny):
        for i in range(nx):
            out[j, i] = 0.0
        if j < j0 or j > ny - 2:
            continue
        jm = 1 if (sym and j == 0) else j - 1
        for i in range(1, nx - 1):
            e = eps[j, i]
            d = ((0.5 * (eps[j, i - 1] + e) + 0.5 * (eps[j, i + 1] + e)) / hx2
                 + (0.5 * (eps[jm, i] + e) + 0.5 * (eps[j + 1, i] + e)) / hy2
                 + (1.5 / hx + ct) * rho[j, i] * K00)
            if d > 0.0:
                out[j, i] = r[j, i] / d
            elif r[j, i] != 0.0:
                # no flow and no film response (rigid surfaces that touch: eps = 0, K00 = 0):
                # a residual there cannot be relaxed away
                out[j, i] = np.inf


# -- line relaxation -------------------------------------------------------------------------
@njit(cache=True)
def _gfun(Kc, d, jd):
    """Film change at offset d along the line caused by a unit change of type jd at 0:
    GS (jd=0) ``K[0,|d|]``; Jacobi-distributive (jd=1) the Laplacian-distributed pattern."""
    a = abs(d)
    if jd == 0:
        return Kc[0, a]
    return Kc[0, a] - 0.25 * (Kc[0, abs(d - 1)] + Kc[0, abs(d + 1)] + 2.0 * Kc[1, a])


@njit(cache=True)
def _wedge_weight(s, ns):
    """Weight of ``rho H`` at ``i - s`` in the upwind wedge term: second order (ns = 3) or first."""
    if ns == 3:
        return 1.5 if s == 0 else (-2.0 if s == 1 else 0.5)
    return 1.0 if s == 0 else -1.0


@njit(cache=True)
def _solve_band5(A, rhs):
    """Solve the pentadiagonal system ``A[r, 2 + (c - r)]`` (overwritten, as ``rhs``) by
    banded elimination without pivoting (diagonally dominant in practice); None when the
    solution is not finite (a singular line, e.g. zero film)."""
    n = rhs.shape[0]
    for r in range(n):
        piv = A[r, 2]
        if piv == 0.0 or not math.isfinite(piv):
            piv = -1e-30
            A[r, 2] = piv
        for rr in range(r + 1, min(n, r + 3)):
            fac = A[rr, 2 + r - rr] / piv
            if fac != 0.0:
                for c in range(r, min(n, r + 3)):
                    A[rr, 2 + c - rr] -= fac * A[r, 2 + c - r]
                rhs[rr] -= fac * rhs[r]
    dlt = np.zeros(n)
    for r in range(n - 1, -1, -1):
        sm = rhs[r]
        for c in range(r + 1, min(n, r + 3)):
            sm -= A[r, 2 + c - r] * dlt[c]
        dlt[r] = sm / A[r, 2]
    for r in range(n):
        if not math.isfinite(dlt[r]):
            return None
    return dlt


@njit(cache=True)
def _relax_line(P, H, rho, eps, f, D, Kc, hx, hy, j, sym, thr, w_gs, order, ct=0.0):
    ny, nx = P.shape
    n = nx - 2
    hx2, hy2 = hx * hx, hy * hy
    jm = 1 if (sym and j == 0) else j - 1
    jp = j + 1
    A = np.zeros((n, 5))  # band: A[r, 2 + (c - r)]
    rhs = np.zeros(n)
    typ = np.zeros(n, dtype=np.int64)
    c0 = np.zeros(n)
    cw = np.zeros(n)
    ce = np.zeros(n)
    cy = np.zeros(n)
    for r in range(n):
        i = r + 1
        e = eps[j, i]
        exm = 0.5 * (eps[j, i - 1] + e)
        exp_ = 0.5 * (eps[j, i + 1] + e)
        eym = 0.5 * (eps[jm, i] + e)
        eyp = 0.5 * (eps[jp, i] + e)
        cw[r] = exm / hx2
        ce[r] = exp_ / hx2
        cy[r] = (eym + eyp) / hy2
        c0[r] = -(cw[r] + ce[r] + cy[r])
        lp = (cw[r] * (P[j, i - 1] - P[j, i]) + ce[r] * (P[j, i + 1] - P[j, i])
              + (eym * (P[jm, i] - P[j, i]) + eyp * (P[jp, i] - P[j, i])) / hy2)
        rhs[r] = f[j, i] - (lp - _wedge(rho, H, j, i, hx, order, ct))
        if e / hx2 < thr and P[j, i] > 0.0:
            typ[r] = 1
    for r in range(n):
        i = r + 1
        if P[j, i] <= 0.0 and rhs[r] >= 0.0:
            A[r, 2] = 1.0
            rhs[r] = 0.0
            continue
        # wedge weights (1/hx) sum_s ws[s] rho[i-s] H[i-s]
        if order == 2 and i >= 2:
            ns = 3
        else:
            ns = 2
        for c in range(max(0, r - 2), min(n, r + 3)):
            k = c + 1
            jd = typ[c]
            # Poiseuille (eps frozen)
            a = 0.0
            if jd == 0:
                if c == r:
                    a = c0[r]
                elif c == r - 1:
                    a = cw[r]
                elif c == r + 1:
                    a = ce[r]
            else:
                if c == r:
                    a = c0[r] - 0.25 * (cw[r] + ce[r] + cy[r])
                elif c == r - 1:
                    a = cw[r] - 0.25 * c0[r]
                elif c == r + 1:
                    a = ce[r] - 0.25 * c0[r]
                elif c == r - 2:
                    a = -0.25 * cw[r]
                else:
                    a = -0.25 * ce[r]
            # wedge through the film
            wsum = 0.0
            for s in range(ns):
                ws = _wedge_weight(s, ns) + (ct * hx if s == 0 else 0.0)
                m = i - s
                wsum += ws * rho[j, m] * _gfun(Kc, m - k, jd)
            a -= wsum / hx
            A[r, 2 + c - r] = a
    dlt = _solve_band5(A, rhs)
    if dlt is None:
        return  # singular line (e.g. zero film): leave it for this sweep
    for r in range(n):
        i = r + 1
        if typ[r] == 0:
            v = P[j, i] + w_gs * dlt[r]
            P[j, i] = v if v > 0.0 else 0.0
        else:
            D[j, i] = dlt[r]


@njit(cache=True, parallel=True)
def relax_sweep(P, H, rho, eps, f, D, Kc, hx, hy, sym, thr, w_gs, w_jd, order, ct=0.0):
    """One zebra line-relaxation sweep along X (Venner-style).

    Lines of even j, then odd j, are each relaxed in parallel (prange); within a line the
    points with ``eps/hx^2 >= thr`` (or P = 0) take a Gauss-Seidel change, the others a
    Jacobi-distributive change, all from one banded (pentadiagonal) system that includes the
    local film response through the kernel ``Kc = cd K[0:2, 0:6]``. The distributive changes
    are applied after the sweep: ``P += w_jd (D - (sum of 4 neighbours of D)/4)``, then P is
    projected to ``P >= 0``. H, rho and eps are NOT updated here (the caller recomputes them).
    """
    ny, nx = P.shape
    j0 = 0 if sym else 1
    for j in range(ny):
        for i in range(nx):
            D[j, i] = 0.0
    for colour in range(2):
        first = j0 if (j0 % 2) == colour else j0 + 1
        nl = (ny - 2 - first) // 2 + 1 if first <= ny - 2 else 0
        for t in prange(nl):
            j = first + 2 * t
            _relax_line(P, H, rho, eps, f, D, Kc, hx, hy, j, sym, thr, w_gs, order, ct)
    if w_jd != 0.0:
        for j in prange(j0, ny - 1):
            jm = 1 if (sym and j == 0) else j - 1
            for i in range(1, nx - 1):
                dd = D[j, i] - 0.25 * (D[j, i - 1] + D[j, i + 1] + D[jm, i] + D[j + 1, i])
                if dd != 0.0:
                    v = P[j, i] + w_jd * dd
                    P[j, i] = v if v > 0.0 else 0.0


@njit(cache=True)
def _gfun_y(Ky, d, s, jd):
    """Film change at Y offset ``d`` and X offset ``s`` (upstream) caused by a unit change of
    type ``jd`` on a Y line: GS (jd=0) ``Ky[|d|, s]``; Jacobi-distributive (jd=1) the
    Laplacian-distributed pattern (neighbours at Y offsets d -+ 1 and X offsets s -+ 1)."""
    a = abs(d)
    if jd == 0:
        return Ky[a, s]
    return Ky[a, s] - 0.25 * (Ky[abs(d - 1), s] + Ky[a + 1, s] + Ky[a, abs(s - 1)] + Ky[a, s + 1])


@njit(cache=True)
def _relax_line_y(P, H, rho, eps, f, D, Ky, hx, hy, i, sym, thr, w_gs, w_jd, order, jd_mode, ct=0.0):
    """One line along Y at column ``i`` (see :func:`relax_sweep_y`)."""
    ny, nx = P.shape
    j0 = 0 if sym else 1
    n = ny - 1 - j0
    hx2, hy2 = hx * hx, hy * hy
    kmax = Ky.shape[0]
    A = np.zeros((n, 5))  # band: A[r, 2 + (c - r)]
    rhs = np.zeros(n)
    typ = np.zeros(n, dtype=np.int64)
    c0 = np.zeros(n)
    cs = np.zeros(n)
    cn = np.zeros(n)
    cx = np.zeros(n)
    for r in range(n):
        j = r + j0
        jm = 1 if (sym and j == 0) else j - 1
        jp = j + 1
        e = eps[j, i]
        exm = 0.5 * (eps[j, i - 1] + e)
        exp_ = 0.5 * (eps[j, i + 1] + e)
        eym = 0.5 * (eps[jm, i] + e)
        eyp = 0.5 * (eps[jp, i] + e)
        cs[r] = eym / hy2
        cn[r] = eyp / hy2
        cx[r] = (exm + exp_) / hx2
        c0[r] = -(cs[r] + cn[r] + cx[r])
        lp = ((exm * (P[j, i - 1] - P[j, i]) + exp_ * (P[j, i + 1] - P[j, i])) / hx2
              + cs[r] * (P[jm, i] - P[j, i]) + cn[r] * (P[jp, i] - P[j, i]))
        rhs[r] = f[j, i] - (lp - _wedge(rho, H, j, i, hx, order, ct))
        if e / hx2 < thr and P[j, i] > 0.0:
            typ[r] = 1
    if order == 2 and i >= 2:
        ns = 3
    else:
        ns = 2
    for r in range(n):
        j = r + j0
        if P[j, i] <= 0.0 and rhs[r] >= 0.0:
            A[r, 2] = 1.0
            rhs[r] = 0.0
            continue
        if typ[r] == 1 and jd_mode == 1:
            # frozen here: the X sweep's Jacobi-distributive changes handle this point
            A[r, 2] = 1.0
            rhs[r] = 0.0
            continue
        for c in range(max(0, r - 2), min(n, r + 3)):
            ll = c + j0
            jd = typ[c] if jd_mode == 2 else 0
            # Poiseuille (eps frozen); on the centre line both Y neighbours are row 1
            cm = cs[r]
            cp = cn[r]
            if sym and j == 0:
                cm = 0.0
                cp = cs[r] + cn[r]
            a = 0.0
            if jd == 0:
                if c == r:
                    a = c0[r]
                elif c == r - 1:
                    a = cm
                elif c == r + 1:
                    a = cp
            else:
                if c == r:
                    a = c0[r] - 0.25 * (cs[r] + cn[r] + cx[r])
                elif c == r - 1:
                    a = cm - 0.25 * c0[r]
                elif c == r + 1:
                    a = cp - 0.25 * c0[r]
                elif c == r - 2:
                    a = -0.25 * cm
                else:
                    a = -0.25 * cp
            # wedge through the film at columns i - s (full-domain mirror image on a half grid)
            wsum = 0.0
            for s in range(ns):
                ws = _wedge_weight(s, ns) + (ct * hx if s == 0 else 0.0)
                g = _gfun_y(Ky, j - ll, s, jd)
                if sym and ll > 0 and j + ll + 1 < kmax:
                    g += _gfun_y(Ky, j + ll, s, jd)
                wsum += ws * rho[j, i - s] * g
            a -= wsum / hx
            A[r, 2 + c - r] = a
    dlt = _solve_band5(A, rhs)
    if dlt is None:
        return
    for r in range(n):
        j = r + j0
        if typ[r] == 0:
            v = P[j, i] + w_gs * dlt[r]
            P[j, i] = v if v > 0.0 else 0.0
        elif jd_mode == 0:
            v = P[j, i] + w_jd * dlt[r]
            P[j, i] = v if v > 0.0 else 0.0
        elif jd_mode == 2:
            D[j, i] = dlt[r]


@njit(cache=True, parallel=True)
def relax_sweep_y(P, H, rho, eps, f, D, Ky, hx, hy, sym, thr, w_gs, w_jd, order, jd_mode, ct=0.0):
    """One zebra line-relaxation sweep along Y: columns of even i, then odd i, each relaxed
    in parallel. Alternated with :func:`relax_sweep` it is the alternating-direction line
    relaxation that Venner & Lubrecht (2000, "Multilevel methods in lubrication", ch. 3 and
    ch. 13) recommend when the coupling across the lines of one direction is strong (contacts
    long in the rolling direction, where P varies faster along Y than along X).

    Each line's pentadiagonal system holds the Poiseuille terms along Y and the film response
    of the upwind wedge ``d(rho H)/dX`` to the line's own changes through
    ``Ky = cd K[0:7, 0:4]`` (Y offset, X offset; on a half grid with the mirror image);
    columns ``i - 1, i - 2`` enter the right-hand side. ``jd_mode`` treats the points with
    ``eps/hx^2 < thr``: 0 Gauss-Seidel under-relaxed by ``w_jd``, 1 left unchanged,
    2 Jacobi-distributive under-relaxed by ``w_jd`` (applied after the sweep as in
    :func:`relax_sweep`). Cavitated points with a non-negative residual stay
    at zero. H, rho and eps are NOT updated here.
    """
    ny, nx = P.shape
    j0 = 0 if sym else 1
    for j in range(ny):
        for i in range(nx):
            D[j, i] = 0.0
    for colour in range(2):
        first = 1 if colour == 1 else 2
        nl = (nx - 2 - first) // 2 + 1 if first <= nx - 2 else 0
        for t in prange(nl):
            i = first + 2 * t
            _relax_line_y(P, H, rho, eps, f, D, Ky, hx, hy, i, sym, thr, w_gs, w_jd, order, jd_mode, ct)
    if jd_mode == 2 and w_jd != 0.0:
        for j in prange(j0, ny - 1):
            jm = 1 if (sym and j == 0) else j - 1
            for i in range(1, nx - 1):
                dd = D[j, i] - 0.25 * (D[j, i - 1] + D[j, i + 1] + D[jm, i] + D[j + 1, i])
                if dd != 0.0:
                    v = P[j, i] + w_jd * dd
                    P[j, i] = v if v > 0.0 else 0.0


# -- transfers ---------------------------------------------------------------------------------
@njit(cache=True)
def restrict_full_weighting(r, sym, out):
    """Full weighting (1/16)[1 2 1; 2 4 2; 1 2 1] of fine ``r`` to coarse ``out``."""
    nyc, nxc = out.shape
    ny, nx = r.shape
    for J in range(nyc):
        for I in range(nxc):
            out[J, I] = 0.0
    j0 = 0 if sym else 1
    for J in range(j0, nyc - 1):
        j = 2 * J
        jm = 1 if (sym and j == 0) else j - 1
        for I in range(1, nxc - 1):
            i = 2 * I
            out[J, I] = (4.0 * r[j, i] + 2.0 * (r[j, i - 1] + r[j, i + 1] + r[jm, i] + r[j + 1, i])
                         + r[jm, i - 1] + r[jm, i + 1] + r[j + 1, i - 1] + r[j + 1, i + 1]) / 16.0


@njit(cache=True)
def add_bilinear(fine, coarse_delta, clip):
    """``fine += bilinear(coarse_delta)`` where ``fine > 0`` (cavitated points keep P = 0, so a
    smooth coarse correction does not smear the cavitation front); project to >= 0 when ``clip``."""
    ny, nx = fine.shape
    for j in range(ny):
        J = j // 2
        oj = j % 2
        for i in range(nx):
            if clip and fine[j, i] <= 0.0:
                continue
            I = i // 2
            oi = i % 2
            if oj == 0 and oi == 0:
                d = coarse_delta[J, I]
            elif oj == 0:
                d = 0.5 * (coarse_delta[J, I] + coarse_delta[J, I + 1])
            elif oi == 0:
                d = 0.5 * (coarse_delta[J, I] + coarse_delta[J + 1, I])
            else:
                d = 0.25 * (coarse_delta[J, I] + coarse_delta[J, I + 1]
                            + coarse_delta[J + 1, I] + coarse_delta[J + 1, I + 1])
            v = fine[j, i] + d
            if clip and v < 0.0:
                v = 0.0
            fine[j, i] = v


@njit(cache=True)
def _cubic_1d(u, n_out, axis0_sym):
    # 4-point cubic to midpoints along axis 1; ends use one-sided cubic or mirror (sym)
    ny, nc = u.shape
    out = np.empty((ny, n_out))
    for j in range(ny):
        for I in range(nc):
            out[j, 2 * I] = u[j, I]
        for I in range(nc - 1):
            a = u[j, I]
            b = u[j, I + 1]
            if I - 1 >= 0:
                am = u[j, I - 1]
            elif axis0_sym:
                am = u[j, 1]
            else:
                am = -1.0e300
            if I + 2 < nc:
                bp = u[j, I + 2]
            else:
                bp = -1.0e300
            if am == -1.0e300 and bp == -1.0e300:
                v = 0.5 * (a + b)
            elif am == -1.0e300:
                v = (3.0 * a + 6.0 * b - bp) / 8.0
            elif bp == -1.0e300:
                v = (-am + 6.0 * a + 3.0 * b) / 8.0
            else:
                v = (-am + 9.0 * a + 9.0 * b - bp) / 16.0
            out[j, 2 * I + 1] = v
    return out


def interpolate_cubic(coarse: np.ndarray, sym: bool) -> np.ndarray:
    """FMG interpolation: 4-point cubic, tensor product, limited to the range of the four
    surrounding coarse values (no overshoot at the pressure spike, where an overshoot raises
    the viscosity by orders of magnitude with Barus) and projected to >= 0."""
    nyc, nxc = coarse.shape
    t = _cubic_1d(np.ascontiguousarray(coarse), 2 * nxc - 1, False)
    t = _cubic_1d(np.ascontiguousarray(t.T), 2 * nyc - 1, sym).T
    c = coarse
    lo = np.minimum(np.minimum(c[:-1, :-1], c[1:, :-1]), np.minimum(c[:-1, 1:], c[1:, 1:]))
    hi = np.maximum(np.maximum(c[:-1, :-1], c[1:, :-1]), np.maximum(c[:-1, 1:], c[1:, 1:]))
    jj = np.minimum(np.arange(2 * nyc - 1) // 2, nyc - 2)
    ii = np.minimum(np.arange(2 * nxc - 1) // 2, nxc - 2)
    t = np.clip(t, lo[jj][:, ii], hi[jj][:, ii])
    return np.ascontiguousarray(np.maximum(t, 0.0))
