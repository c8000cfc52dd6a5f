"""Compiled inner loops of the line-contact thermal model (thesis 3.2.2.2; energy
equation (3.5), Eyring law (3.3), discretisation (3.18)-(3.19)).

One station x_i carries the film profile T(Z), tau(Z), u(Z) on ``nz + 1`` nodes of the mapped
film coordinate Z = z/h (3.14). At each station:

* momentum (3.4): ``tau(Z) = tau_m + G (Z - 1/2)``, linear across the film, with the stress
  slope ``G = h dp/dx`` either taken from the given pressure gradient or, for an EHL field,
  chosen so that the pressure-driven flux equals the one of the EHL solution (see
  :func:`solve_stress_slope`);
* Eyring-Maxwell flow (3.3): ``gdot = (um/G) dtau/dx + (tau0/eta) sinh(tau/tau0)``; the mid-film
  stress ``tau_m`` is fixed by ``h int_0^1 gdot dZ = u2 - u1`` (so u(0) = u1, u(h) = u2);
* energy (3.5) in mapped form with the cross term dropped (3.17):
  ``k/h^2 T_ZZ - rho Cp u T_x + tau gdot_v = 0``, optionally with the compressive heating
  ``+ T alpha* u dp/dx`` (``alpha* = -(1/rho) d rho/dT`` of (3.10), T absolute; off in the
  thesis's model), three-point backward differences in x (3.18)
  (two-point at the first station), central in Z (3.19);
* walls: ``T = T_bulk + sum_j W(i, j) q_j`` (surface.py), with the wall flux from a second-order
  one-sided difference.

The march goes from inlet to outlet; each station is iterated until temperature and shear stress
change by less than the tolerances (the thesis's 3-node sliding window: the two upstream nodes are
already converged and fixed). Influences that point upstream (reverse flow in a thick EHL inlet,
where a first-order forward difference with lagged downstream values is used, and the upstream
reach of the moving-strip surface kernel) are lagged: :func:`sweep_line` does one sweep, and
``thermal.line.solve_thermal_line`` repeats sweeps (Anderson-accelerated) until the field stops changing.
Within a sweep, a reverse-flow zone is relaxed as soon as the march has passed it
(:func:`_zone_relax`: symmetric passes of its energy equation with the coefficients of the last
station iteration), so the heat the recirculation carries upstream does not wait for the next sweep.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, types

from ehl_multigrid.model.lubricant import G_ELASTICITY_OFF

from .properties import (
    I_G,
    I_TAU0,
    conductivity,
    density_at,
    density_pressure_term,
    expansivity,
    roelands_at,
    roelands_log_ratio,
    roelands_pressure_term,
    specific_heat,
)

T_KELVIN = 273.15

try:
    # LAPACK's least-squares solver (dgelsd) through the (private) helper of numba's
    # np.linalg.lstsq: the same result without compiling lstsq's checks, copies and messages
    from numba.np.linalg import _LAPACK, F_INT_nptype

    _gelsd = _LAPACK.numba_ez_gelsd(types.float64)
except (ImportError, AttributeError):  # a numba without that helper: np.linalg.lstsq
    _gelsd = None
_KIND_D = ord("d")  # float64


@njit(cache=True)
def _sinh_cosh(s):
    """``(sinh s, cosh s)`` from one ``expm1`` (accurate near 0, no overflow for |s| <= 700)."""
    a = abs(s)
    em = math.expm1(a)
    inv = 1.0 / (em + 1.0)  # e^-|s|
    sh = 0.5 * (em + em * inv)
    return math.copysign(sh, s), sh + inv


@njit(cache=True)
def _tau_residual(t, d, w, inv_eta, tau0, mx_a, mx_r, target):
    """f(tau_m) = sum_j w_j gdot_j - target and its derivative."""
    f = 0.0
    df = 0.0
    for j in range(d.shape[0]):
        s = (t + d[j]) / tau0
        if s > 700.0:
            s = 700.0
        elif s < -700.0:
            s = -700.0
        sh, ch = _sinh_cosh(s)
        f += w[j] * (tau0 * inv_eta[j] * sh + mx_a * (t + d[j]) + mx_r[j])
        df += w[j] * (inv_eta[j] * ch + mx_a)
    return f - target, df


@njit(cache=True)
def solve_tau_mid(guess, d, w, inv_eta, tau0, mx_a, mx_r, target):
    """Mid-film shear stress tau_m [Pa] from the flow condition (safeguarded Newton).

    The residual is monotone increasing in tau_m. Newton steps from ``guess``; until the root
    is bracketed a step may not exceed a search step that starts at tau0 and doubles (so a
    poor guess cannot throw the iterate into the overflow range of sinh); once bracketed, a
    step leaving the bracket is replaced by bisection. It stops when a step is below 1e-11 tau0,
    or when a Newton step is below 1e-6 tau0 (its remaining error is then below 5e-13 tau0). A
    warm guess (the previous iterate) converges in one to three residual evaluations. Returns
    ``(tau_m, ok)``.
    """
    x = guess
    lo = -math.inf
    hi = math.inf
    step = tau0
    tolx = 1e-11 * tau0
    for _ in range(500):
        f, df = _tau_residual(x, d, w, inv_eta, tau0, mx_a, mx_r, target)
        if f == 0.0:
            return x, True
        if f < 0.0:
            lo = x
        else:
            hi = x
        xn = math.nan
        if df > 0.0 and math.isfinite(df) and math.isfinite(f):
            xn = x - f / df
        newton = True
        bracketed = math.isfinite(lo) and math.isfinite(hi)
        if bracketed:
            if not (lo < xn < hi):
                xn = 0.5 * (lo + hi)
                newton = False
        elif f < 0.0:
            if not (x < xn <= x + step):
                xn = x + step
                step *= 2.0
                newton = False
        elif not (x - step <= xn < x):
            xn = x - step
            step *= 2.0
            newton = False
        if abs(xn - x) <= tolx + 1e-14 * abs(x) or (bracketed and hi - lo <= tolx + 1e-14 * abs(x)):
            return xn, True
        if newton and abs(xn - x) <= 1e-6 * tau0:
            # |f''| <= f'/tau0 (sinh against cosh; the Maxwell terms are linear), so the error
            # left after this Newton step is at most step^2/(2 tau0) <= 5e-13 tau0, below tolx:
            # the confirming evaluation is not needed
            return xn, True
        x = xn
    return x, False


@njit(cache=True)
def _pressure_flow(G, guess, Zc, d, w, inv_eta, tau0, mx_a, mx_r, target):
    """Pressure-driven part of the flow at stress slope ``G`` [Pa].

    Fills ``d = G (Z - 1/2)``, solves ``tau_m`` from the wall-speed condition and returns
    ``(sum_j w_j (Z_j - 1/2) (gdot(tau_m + d_j) - gdot(tau_m)), tau_m, ok)``; the film's
    volume flux is ``h um - h^2`` times that sum, so it is the flux the slope adds to (or takes
    from) the shear flow of the same viscosity profile, divided by ``-h^2``.
    """
    for j in range(d.shape[0]):
        d[j] = G * Zc[j]
    tm, ok = solve_tau_mid(guess, d, w, inv_eta, tau0, mx_a, mx_r, target)
    s0 = tm / tau0
    if s0 > 700.0:
        s0 = 700.0
    elif s0 < -700.0:
        s0 = -700.0
    sh0 = math.sinh(s0)
    B = 0.0
    for j in range(d.shape[0]):
        s = (tm + d[j]) / tau0
        if s > 700.0:
            s = 700.0
        elif s < -700.0:
            s = -700.0
        B += w[j] * Zc[j] * (tau0 * inv_eta[j] * (math.sinh(s) - sh0) + mx_a * d[j])
    return B, tm, ok


@njit(cache=True)
def _slope_residual(G, sgn, b, tm, Zc, d, w, inv_eta, tau0, mx_a, mx_r, target):
    """``asinh(flow / |b|) - asinh(1)`` at slope ``sgn G`` (increasing in G, zero at the root;
    the asinh keeps the exponential growth of the Eyring flow in range)."""
    B, tm, ok = _pressure_flow(sgn * G, tm, Zc, d, w, inv_eta, tau0, mx_a, mx_r, target)
    return math.asinh(B * sgn / abs(b)) - math.asinh(1.0), tm, ok


@njit(cache=True)
def _newton_resid(tm_, G_, Zc, w, inv_eta, tau0, mx_a, target, b, sw, swz, swz2, swr, swzi):
    """Residuals of the wall-speed condition and the pressure-driven flow of the Eyring-Maxwell
    film (3.3) at ``(tau_m, G)`` and their Jacobian (:func:`_slope_newton`; ``sw``.. are its
    fixed Maxwell sums)."""
    n = Zc.shape[0]
    s0 = min(max(tm_ / tau0, -700.0), 700.0)
    sh0, ch0 = _sinh_cosh(s0)
    e1 = 0.0
    e2 = 0.0
    e3 = 0.0
    e4 = 0.0
    e5 = 0.0
    for j in range(n):
        s = min(max((tm_ + G_ * Zc[j]) / tau0, -700.0), 700.0)
        sh, ch = _sinh_cosh(s)
        wi = w[j] * inv_eta[j]
        esh = wi * sh
        ech = wi * ch
        e1 += esh
        e2 += Zc[j] * esh
        e3 += ech
        e4 += Zc[j] * ech
        e5 += Zc[j] * Zc[j] * ech
    fa = tau0 * e1 + mx_a * (tm_ * sw + G_ * swz) + swr
    fr = tau0 * (e2 - sh0 * swzi) + mx_a * G_ * swz2
    return fa - target, fr - b, e3 + mx_a * sw, e4 + mx_a * swz, e4 - ch0 * swzi, e5 + mx_a * swz2


@njit(cache=True)
def _slope_newton(G, tm, Zc, w, inv_eta, tau0, mx_a, mx_r, target, b):
    """Newton on ``(tau_m, G)`` for the wall-speed condition and the pressure-driven flow ``b``
    (the fast path of :func:`solve_stress_slope` from a warm start). Returns
    ``(G, tau_m, ok)``; ``ok`` is False when it did not converge in a few damped steps."""
    n = Zc.shape[0]
    tolx = 1e-11 * tau0
    # the Maxwell terms are linear in (tau_m, G): their sums are fixed during the solve, and
    # only the Eyring terms need a pass over the nodes per evaluation (the per-node sums of
    # (3.3), regrouped: the root moves by rounding only, forces by < 1e-15)
    sw = 0.0
    swz = 0.0
    swz2 = 0.0
    swr = 0.0
    swzi = 0.0
    for j in range(n):
        sw += w[j]
        swz += w[j] * Zc[j]
        swz2 += w[j] * Zc[j] * Zc[j]
        swr += w[j] * mx_r[j]
        swzi += w[j] * Zc[j] * inv_eta[j]

    fa, fr, a11, a12, a21, a22 = _newton_resid(tm, G, Zc, w, inv_eta, tau0, mx_a, target, b, sw, swz, swz2, swr, swzi)
    for _ in range(30):
        det = a11 * a22 - a12 * a21
        if not (math.isfinite(det) and det > 0.0 and math.isfinite(fa) and math.isfinite(fr)):
            return G, tm, False
        dtm = -(a22 * fa - a12 * fr) / det
        dG = -(a11 * fr - a21 * fa) / det
        if abs(dtm) <= 1e-6 * tau0 and abs(dG) <= 1e-6 * tau0:
            # as in solve_tau_mid: the second derivatives are bounded by the first over tau0,
            # so a full step this small leaves an error of order 1e-12 tau0
            return G + dG, tm + dtm, True
        # residual norm in stress units (the diagonal of the Jacobian scales each equation)
        norm0 = abs(fa) / a11 + abs(fr) / a22
        lam = 1.0
        ok = False
        for _k in range(20):
            tn = tm + lam * dtm
            Gn = G + lam * dG
            fa_n, fr_n, b11, b12, b21, b22 = _newton_resid(tn, Gn, Zc, w, inv_eta, tau0, mx_a, target, b,
                                                           sw, swz, swz2, swr, swzi)
            if math.isfinite(fa_n) and math.isfinite(fr_n) and b11 > 0.0 and b22 > 0.0:
                if abs(fa_n) / b11 + abs(fr_n) / b22 < norm0 or lam * (abs(dtm) + abs(dG)) <= tolx:
                    ok = True
                    break
            lam *= 0.5
        if not ok:
            return G, tm, False
        tm, G = tn, Gn
        fa, fr, a11, a12, a21, a22 = fa_n, fr_n, b11, b12, b21, b22
        if (lam * abs(dtm) <= tolx + 1e-14 * abs(tm)) and (lam * abs(dG) <= tolx + 1e-12 * abs(G)):
            return G, tm, True
    return G, tm, False


@njit(cache=True)
def _newtonian_slope(b, Zc, w, inv_eta, tau0, mx_a):
    """``|b| / sum w Z^2 (1/eta + Maxwell)``: the slope of a Newtonian film with this flow
    (``tau0`` when that is not a positive number)."""
    s2 = 0.0
    for j in range(Zc.shape[0]):
        s2 += w[j] * Zc[j] * Zc[j] * (inv_eta[j] + mx_a)
    g = abs(b) / s2 if s2 > 0.0 else tau0
    if not (g > 0.0 and math.isfinite(g)):
        g = tau0
    return g


@njit(cache=True)
def solve_stress_slope(G_guess, tm_guess, Zc, d, w, inv_eta, tau0, mx_a, mx_r, target, b):
    """Stress slope ``G = dtau/dZ`` [Pa] whose pressure-driven flow is ``b`` [1/s].

    ``b = -q_p / h^2`` with ``q_p`` the pressure-driven volume flux per unit width [m^2/s] of
    the EHL solution, ``-h^3/(12 eta) dp/dx`` (Reynolds; :func:`sweep_line` scales it to the Z
    quadrature). For a Newtonian fluid at the EHL solver's viscosity this returns
    ``G = h dp/dx``; for an Eyring fluid
    whose viscosity falls with temperature it keeps the flux instead of the gradient, so shear
    thinning and heating cannot multiply the Poiseuille flow and its heat beyond what the film
    carries (mass conservation, the condition the EHL pressure was solved for).

    A damped Newton step on ``(tau_m, G)`` from the previous value (or the Newtonian slope
    ``|b| / sum w Z^2/eta``, an upper bound for a shear-thinning fluid) usually converges in a
    few steps. Otherwise the flow, increasing in G and zero at G = 0, is bracketed from that
    value and the bracket closed by Illinois steps with bisection when it stops shrinking. Returns
    ``(G, tau_m, ok)`` and leaves ``d = G (Z - 1/2)``.
    """
    if b == 0.0:
        B, tm, ok = _pressure_flow(0.0, tm_guess, Zc, d, w, inv_eta, tau0, mx_a, mx_r, target)
        return 0.0, tm, ok
    sgn = 1.0 if b > 0.0 else -1.0
    g = G_guess * sgn
    g_newton = math.nan  # the Newtonian slope, needed only without a warm guess
    if not (g > 0.0 and math.isfinite(g)):
        g_newton = _newtonian_slope(b, Zc, w, inv_eta, tau0, mx_a)
        g = g_newton
    Gn, tm, ok = _slope_newton(sgn * g, tm_guess, Zc, w, inv_eta, tau0, mx_a, mx_r, target, b)
    if ok and Gn * sgn > 0.0:
        for j in range(d.shape[0]):
            d[j] = Gn * Zc[j]
        return Gn, tm, True
    if not math.isfinite(g_newton):
        g_newton = _newtonian_slope(b, Zc, w, inv_eta, tau0, mx_a)
    tm = tm_guess
    f, tm, ok = _slope_residual(g, sgn, b, tm, Zc, d, w, inv_eta, tau0, mx_a, mx_r, target)
    if f == 0.0:
        return sgn * g, tm, ok
    lo = 0.0
    f_lo = -math.asinh(1.0)
    if f < 0.0:
        lo = g
        f_lo = f
        hi = max(2.0 * g, g_newton)
        f_hi, tm, ok = _slope_residual(hi, sgn, b, tm, Zc, d, w, inv_eta, tau0, mx_a, mx_r, target)
        k = 0
        while f_hi < 0.0 and k < 2000:
            lo = hi
            f_lo = f_hi
            hi *= 4.0
            f_hi, tm, ok = _slope_residual(hi, sgn, b, tm, Zc, d, w, inv_eta, tau0, mx_a, mx_r, target)
            k += 1
        if f_hi < 0.0:
            return sgn * hi, tm, False
    else:
        hi = g
        f_hi = f
    side = 0
    width = hi - lo
    x = hi
    for it in range(300):
        x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
        if it % 3 == 2 and hi - lo > 0.5 * width:
            # the Illinois steps stalled: bisect (geometrically across decades)
            x = math.sqrt(lo * hi) if lo > 0.0 and hi > 4.0 * lo else 0.5 * (lo + hi)
        if not (lo < x < hi):
            x = 0.5 * (lo + hi)
        if it % 3 == 2:
            width = hi - lo
        f, tm, ok = _slope_residual(x, sgn, b, tm, Zc, d, w, inv_eta, tau0, mx_a, mx_r, target)
        if abs(f) <= 1e-12 or hi - lo <= 1e-13 * hi:
            return sgn * x, tm, ok
        if f < 0.0:
            lo = x
            f_lo = f
            if side == -1:
                f_hi *= 0.5
            side = -1
        else:
            hi = x
            f_hi = f
            if side == 1:
                f_lo *= 0.5
            side = 1
    return sgn * x, tm, False


@njit(cache=True)
def _tridiag_solve(a, b, c, r, x):
    """Thomas algorithm: a_j x_{j-1} + b_j x_j + c_j x_{j+1} = r_j. Overwrites ``c`` and ``r``
    with the eliminated rows: the caller rebuilds them every iteration, and a station iteration
    is short enough (about 2 us) that two work arrays allocated per call showed in its cost."""
    n = b.shape[0]
    c[0] = c[0] / b[0]
    r[0] = r[0] / b[0]
    for j in range(1, n):
        m = b[j] - a[j] * c[j - 1]
        c[j] = c[j] / m
        r[j] = (r[j] - a[j] * r[j - 1]) / m
    x[n - 1] = r[n - 1]
    for j in range(n - 2, -1, -1):
        x[j] = r[j] - c[j] * x[j + 1]


@njit(cache=True)
def _wall_weight(WL, WR, i, j, n):
    m = i - j + n - 1
    if j == 0:
        return WR[m]
    if j == n - 1:
        return WL[m]
    return WL[m] + WR[m]


@njit(cache=True, nogil=True)
def _station(
    i, n, nzp, dx, dZ, p, h, dpdx, qp, flux, compress, dpdx_c, oil, log_ratio, tau0, inv_G, u1, u2, um, T_oil, Ts1, Ts2,
    WL1, WR1, WL2, WR2, thermal, first, q1_down, q2_down, T_down, T_start,
    tol_T, tol_tau, max_inner, relax, wz, Zc, flux_scale,
    d, inv_eta, mx_r, Ti, Tn, tau_old, aa, bb, cc, rr, gtot,
    T, tau, u, gv, q1, q2, heat, slope, inner_its, eq_rc, eq_src, eq_s,
):
    """Solve station ``i`` (see :func:`sweep_line`) with the values of the other stations in
    ``T``, ``tau``, ``q1``, ``q2`` (upstream) and ``T_down``, ``q1_down``, ``q2_down``
    (downstream, the lagged arrays); the iteration starts from ``T_start[i]`` unless ``first``.

    The energy rows of the last iteration are left in ``eq_rc[i]`` (rho Cp u per node),
    ``eq_src[i]`` (heat source per node) and ``eq_s[i, :6]`` (``A = k/(h dZ)^2``, the wall
    coefficients c1, c2, the wall influence C1, C2 of the other stations, ``k/(2 h dZ)``) for
    :func:`_zone_relax`.

    Returns ``(converged, failed shear-stress solves, reverse-flow nodes)``.
    """
    tau_fail = 0
    rev = 0
    # reverse flow is u below -1e-9 (u1 + u2): at a surface at rest the film velocity is zero
    # only to the shear-stress solve's tolerance (|u| ~ 1e-11 us); those nodes' convection is
    # negligible either way and must not be taken for recirculation
    u_eps = 1e-9 * (abs(u1) + abs(u2))
    hi_ = h[i]
    k_i = conductivity(p[i], oil)
    # pressure factors of viscosity and density, fixed along the station's film
    pr_i = roelands_pressure_term(p[i], oil)
    dh_i = density_pressure_term(p[i], oil)
    target = (u2 - u1) / hi_
    use_flux = flux and qp[i] != 0.0
    b_flux = -qp[i] * flux_scale / (hi_ * hi_) if use_flux else 0.0
    G = dpdx[i] * hi_
    if use_flux:
        G = math.nan if first else slope[i]
    else:
        for j in range(nzp):
            d[j] = G * Zc[j]
    # Maxwell term: dtau/dx by the same backward differences as the energy equation
    if i >= 2:
        mx_a = um * inv_G * 1.5 / dx
        for j in range(nzp):
            mx_r[j] = um * inv_G * (-2.0 * tau[i - 1, j] + 0.5 * tau[i - 2, j]) / dx
    elif i == 1:
        mx_a = um * inv_G / dx
        for j in range(nzp):
            mx_r[j] = -um * inv_G * tau[0, j] / dx
    else:
        mx_a = 0.0
        for j in range(nzp):
            mx_r[j] = 0.0
    # wall influence of all other stations (downstream ones from q_down)
    C1 = 0.0
    C2 = 0.0
    if thermal:
        for jj in range(n):
            if jj < i:
                C1 += _wall_weight(WL1, WR1, i, jj, n) * q1[jj]
                C2 += _wall_weight(WL2, WR2, i, jj, n) * q2[jj]
            elif jj > i:
                C1 += _wall_weight(WL1, WR1, i, jj, n) * q1_down[jj]
                C2 += _wall_weight(WL2, WR2, i, jj, n) * q2_down[jj]
    w1s = _wall_weight(WL1, WR1, i, i, n)
    w2s = _wall_weight(WL2, WR2, i, i, n)
    # starting values
    if not thermal:
        for j in range(nzp):
            Ti[j] = T_oil
    elif first:
        if i == 0:
            for j in range(nzp):
                Ti[j] = T_oil
            Ti[0] = Ts1
            Ti[nzp - 1] = Ts2
        else:
            for j in range(nzp):
                Ti[j] = T[i - 1, j]
    else:
        for j in range(nzp):
            Ti[j] = T_start[i, j]
    tm_guess = 0.0
    if first:
        if i > 0:
            for j in range(nzp):
                tm_guess += wz[j] * tau[i - 1, j]
        for j in range(nzp):
            tau_old[j] = 0.0
    else:
        # this station's mid-film stress of the previous sweep
        for j in range(nzp):
            tm_guess += wz[j] * tau[i, j]
            tau_old[j] = 0.0

    omega = relax
    last_dT = 1e300
    converged = False
    its = 0
    for it in range(max_inner):
        its = it + 1
        for j in range(nzp):
            inv_eta[j] = 1.0 / roelands_at(pr_i, log_ratio, Ti[j], oil)
        if use_flux:
            G, tm, ok = solve_stress_slope(G, tm_guess, Zc, d, wz, inv_eta, tau0, mx_a, mx_r, target, b_flux)
        else:
            tm, ok = solve_tau_mid(tm_guess, d, wz, inv_eta, tau0, mx_a, mx_r, target)
        if not ok:
            tau_fail += 1
        tm_guess = tm
        dtau = 0.0
        tmax = 1.0
        for j in range(nzp):
            t = tm + d[j]
            s = t / tau0
            if s > 700.0:
                s = 700.0
            elif s < -700.0:
                s = -700.0
            gv[i, j] = tau0 * inv_eta[j] * math.sinh(s)
            gtot[j] = gv[i, j] + mx_a * t + mx_r[j]
            heat[i, j] = t * gv[i, j]
            dtau = max(dtau, abs(t - tau_old[j]))
            tmax = max(tmax, abs(t))
            tau[i, j] = t
            tau_old[j] = t
        dtau /= tmax
        # velocity u(Z) = u1 + h int_0^Z gdot
        u[i, 0] = u1
        for j in range(1, nzp):
            u[i, j] = u[i, j - 1] + hi_ * 0.5 * dZ * (gtot[j - 1] + gtot[j])
        if not thermal:
            converged = True
            break
        # energy equation rows: -A T_{j-1} + (2A + conv) T_j - A T_{j+1} = heat + conv rhs
        A = k_i / (hi_ * hi_ * dZ * dZ)
        for j in range(1, nzp - 1):
            rc = density_at(dh_i, Ti[j], oil) * specific_heat(Ti[j], oil) * u[i, j]
            aa[j] = -A
            cc[j] = -A
            bb[j] = 2.0 * A
            rr[j] = heat[i, j]
            if compress:
                # compression work T alpha* u dp/dx (T absolute; alpha* the expansivity of (3.10)),
                # at the station iterate like the shear heat: heats where the oil is compressed
                rr[j] += (Ti[j] + T_KELVIN) * expansivity(Ti[j], oil) * u[i, j] * dpdx_c[i]
            eq_rc[i, j] = rc
            eq_src[i, j] = rr[j]
            if i == 0:
                pass  # inlet column fixed below
            elif u[i, j] >= -u_eps:
                if i >= 2:
                    bb[j] += 1.5 * rc / dx
                    rr[j] += rc * (2.0 * T[i - 1, j] - 0.5 * T[i - 2, j]) / dx
                else:
                    bb[j] += rc / dx
                    rr[j] += rc * T[i - 1, j] / dx
            elif i < n - 1:
                # reverse flow: first-order forward difference with the downstream values T_down
                bb[j] += -rc / dx
                rr[j] += -rc * T_down[i + 1, j] / dx
        c1 = w1s * k_i / (2.0 * hi_ * dZ)
        c2 = w2s * k_i / (2.0 * hi_ * dZ)
        jt = nzp - 1
        jm = nzp - 2
        eq_s[i, 0] = A
        eq_s[i, 1] = c1
        eq_s[i, 2] = c2
        eq_s[i, 3] = C1
        eq_s[i, 4] = C2
        eq_s[i, 5] = k_i / (hi_ * 2.0 * dZ)
        if i == 0:
            # inlet: oil at T_oil, walls respond to their own flux
            for j in range(1, nzp - 1):
                Tn[j] = T_oil
            Tn[0] = (Ts1 + C1 + 3.0 * c1 * T_oil) / (1.0 + 3.0 * c1)
            Tn[jt] = (Ts2 + C2 + 3.0 * c2 * T_oil) / (1.0 + 3.0 * c2)
        else:
            # wall rows (1 + 3c) T0 - 4c T1 + c T2 = Ts + C; T2 eliminated with row 1
            aa[0] = 0.0
            bb[0] = 1.0 + 3.0 * c1 - c1 * aa[1] / cc[1]
            cc[0] = -4.0 * c1 - c1 * bb[1] / cc[1]
            rr[0] = Ts1 + C1 - c1 * rr[1] / cc[1]
            aa[jt] = -4.0 * c2 - c2 * bb[jm] / aa[jm]
            bb[jt] = 1.0 + 3.0 * c2 - c2 * cc[jm] / aa[jm]
            cc[jt] = 0.0
            rr[jt] = Ts2 + C2 - c2 * rr[jm] / aa[jm]
            _tridiag_solve(aa, bb, cc, rr, Tn)
        dT = 0.0
        for j in range(nzp):
            dT = max(dT, abs(Tn[j] - Ti[j]) / (abs(Ti[j] + T_KELVIN)))
        if dT > last_dT and omega > 0.05:
            omega *= 0.5
        last_dT = dT
        for j in range(nzp):
            Ti[j] = Ti[j] + omega * (Tn[j] - Ti[j])
        if dT < tol_T and dtau < tol_tau:
            converged = True
            break
    inner_its[i] = its
    slope[i] = G
    for j in range(nzp):
        T[i, j] = Ti[j]
        if u[i, j] < -u_eps:
            rev += 1
    if thermal:
        q1[i] = k_i / (hi_ * 2.0 * dZ) * (-3.0 * Ti[0] + 4.0 * Ti[1] - Ti[2])
        q2[i] = -k_i / (hi_ * 2.0 * dZ) * (3.0 * Ti[nzp - 1] - 4.0 * Ti[nzp - 2] + Ti[nzp - 3])
    else:
        q1[i] = 0.0
        q2[i] = 0.0
    return converged, tau_fail, rev


@njit(cache=True, nogil=True)
def _zone_factor(i, n, nzp, dx, u_eps, u, eq_rc, eq_s, aa, bb, cc, fa, fcp, fim, f1, f2, fb):
    """Thomas factors of station ``i``'s energy rows with the coefficients of its last
    iteration, and the weights of its neighbours' temperatures in the right-hand side: the
    rows of :func:`_station` ((3.18)-(3.19), the wall rows with T2 eliminated). ``fim`` is
    the inverse pivot, ``fa`` and ``fcp`` the sub- and super-diagonal times it."""
    A = eq_s[i, 0]
    c1 = eq_s[i, 1]
    c2 = eq_s[i, 2]
    inv_dx = 1.0 / dx
    for j in range(1, nzp - 1):
        rc = eq_rc[i, j] * inv_dx
        aa[j] = -A
        cc[j] = -A
        bb[j] = 2.0 * A
        f1[i, j] = 0.0
        f2[i, j] = 0.0
        fb[i, j] = 0.0
        if u[i, j] >= -u_eps:
            if i >= 2:
                bb[j] += 1.5 * rc
                f1[i, j] = 2.0 * rc
                f2[i, j] = -0.5 * rc
            else:
                bb[j] += rc
                f1[i, j] = rc
        elif i < n - 1:
            bb[j] += -rc
            fb[i, j] = -rc
    jt = nzp - 1
    jm = nzp - 2
    aa[0] = 0.0
    bb[0] = 1.0 + 3.0 * c1 - c1 * aa[1] / cc[1]
    cc[0] = -4.0 * c1 - c1 * bb[1] / cc[1]
    aa[jt] = -4.0 * c2 - c2 * bb[jm] / aa[jm]
    bb[jt] = 1.0 + 3.0 * c2 - c2 * cc[jm] / aa[jm]
    cc[jt] = 0.0
    eq_s[i, 6] = c1 / A
    eq_s[i, 7] = c2 / A
    for j in range(nzp):
        im = 1.0 / (bb[j] - (aa[j] * fcp[i, j - 1] if j > 0 else 0.0))
        # the forward substitution's multiplier, premultiplied: one FMA per node on its chain
        fa[i, j] = aa[j] * im
        fcp[i, j] = cc[j] * im
        fim[i, j] = im


@njit(cache=True, nogil=True)
def _zone_solve(i, n, nzp, Ts1, Ts2, T, eq_src, eq_s, fa, fcp, fim, f1, f2, fb, rr, Tn, q1, q2):
    """Station ``i``'s energy rows (factored by :func:`_zone_factor`) with the current
    temperatures of its neighbours; updates ``T[i]``, ``q1[i]``, ``q2[i]`` and returns the
    largest relative change of the absolute temperature."""
    im2 = i - 2 if i >= 2 else 0
    ip1 = i + 1 if i < n - 1 else i
    for j in range(1, nzp - 1):
        rr[j] = eq_src[i, j] + f1[i, j] * T[i - 1, j] + f2[i, j] * T[im2, j] + fb[i, j] * T[ip1, j]
    jt = nzp - 1
    # wall rows with T2 eliminated (cc[1] = aa[jm] = -A): eq_s[i, 6:8] = c1/A, c2/A
    rr[0] = Ts1 + eq_s[i, 3] + eq_s[i, 6] * rr[1]
    rr[jt] = Ts2 + eq_s[i, 4] + eq_s[i, 7] * rr[jt - 1]
    Tn[0] = rr[0] * fim[i, 0]
    for j in range(1, nzp):
        Tn[j] = rr[j] * fim[i, j] - fa[i, j] * Tn[j - 1]
    for j in range(nzp - 2, -1, -1):
        Tn[j] = Tn[j] - fcp[i, j] * Tn[j + 1]
    # largest change over the smallest absolute temperature: a bound of the relative change
    # without a division per node
    dmax = 0.0
    tmin = math.inf
    for j in range(nzp):
        dmax = max(dmax, abs(Tn[j] - T[i, j]))
        tmin = min(tmin, abs(T[i, j] + T_KELVIN))
        T[i, j] = Tn[j]
    kq = eq_s[i, 5]
    q1[i] = kq * (-3.0 * Tn[0] + 4.0 * Tn[1] - Tn[2])
    q2[i] = -kq * (3.0 * Tn[nzp - 1] - 4.0 * Tn[nzp - 2] + Tn[nzp - 3])
    return dmax / tmin


@njit(cache=True, nogil=True)
def _zone_relax(lo, hi, last, n, nzp, dx, u_eps, Ts1, Ts2, T, u, eq_rc, eq_src, eq_s, aa, bb, cc, rr, Tn,
                fa, fcp, fim, f1, f2, fb, q1, q2, passes, tol):
    """Symmetric Gauss-Seidel passes of the energy equation (3.5) over a reverse-flow zone.

    Stations ``lo..hi`` carry reverse flow and ``last`` (hi + 1, or hi at the outlet) is the
    first one past it. Each pass solves the stations from ``hi`` back to ``lo`` and then from
    ``lo`` to ``last`` again, with the coefficients of their last nonlinear iteration frozen
    (rho Cp u, the heat sources and the wall influence of the other stations): the linear
    part of the recirculation, heat carried downstream near the walls and back upstream in
    the core, which the march would otherwise pass on by one station per sweep. Passes stop
    when the largest relative temperature change falls below ``tol``, stops shrinking, or
    after ``passes``. A converged field is left unchanged (to its station tolerance), so the
    fixed point of the sweeps is the same. Returns the number of passes.
    """
    for i in range(lo, last + 1):
        _zone_factor(i, n, nzp, dx, u_eps, u, eq_rc, eq_s, aa, bb, cc, fa, fcp, fim, f1, f2, fb)
    prev = math.inf
    k = 0
    while k < passes:
        k += 1
        ch = 0.0
        for i in range(hi, lo - 1, -1):
            ch = max(ch, _zone_solve(i, n, nzp, Ts1, Ts2, T, eq_src, eq_s, fa, fcp, fim, f1, f2, fb, rr, Tn, q1, q2))
        for i in range(lo, last + 1):
            ch = max(ch, _zone_solve(i, n, nzp, Ts1, Ts2, T, eq_src, eq_s, fa, fcp, fim, f1, f2, fb, rr, Tn, q1, q2))
        if not (ch >= tol and ch < prev):
            break
        prev = ch
    return k


@njit(cache=True, nogil=True)
def sweep_line(
    dx, p, h, dpdx, qp, flux, compress, dpdx_c, oil, u1, u2, um, T_oil, Ts1, Ts2,
    WL1, WR1, WL2, WR2, nz, thermal, first, q1_lag, q2_lag, T_lag,
    tol_T, tol_tau, max_inner, relax,
    T, tau, u, gv, q1, q2, heat, slope, inner_its, zone_passes=0, zone_tol=0.0,
):
    """One inlet-to-outlet sweep of the line-contact thermal model; fills the output arrays.

    Parameters (arrays have one row per station, ``nz + 1`` columns)
    ----------
    dx : station spacing [m]; p, h, dpdx : pressure [Pa], film [m], dp/dx [Pa/m] per station;
    qp : pressure-driven volume flux of the EHL solution per station [m^2/s];
    flux : True sets the stress slope from ``qp`` (:func:`solve_stress_slope`), False from
        ``dpdx`` (``G = h dp/dx``; zeros switch the pressure term off);
    compress : add the compressive heating ``-(T/rho)(d rho/d T)_p u dp/dx`` to the energy
        equation (Bruyere et al. 2012, Habchi 2008; (3.5) has none), with ``dpdx_c`` [Pa/m]
        the pressure gradient per station (read only when ``compress``);
    oil : properties.oil_params array; u1, u2 : wall speeds [m/s]; um : mean speed (Maxwell term);
    T_oil, Ts1, Ts2 : inlet oil and bulk wall temperatures [degC];
    WL1, WR1, WL2, WR2 : surface influence weights (surface.wall_weights);
    thermal : False holds T = T_oil everywhere (isothermal switch);
    first : first sweep (no lagged values yet: stations start from the upstream station);
    q1_lag, q2_lag : wall heat fluxes used for the influence of downstream stations [W/m^2];
    T_lag : temperatures used downstream of reverse-flow nodes and as starting values [degC];
    tol_T : relative change of absolute temperature ending the station iteration;
    tol_tau : relative shear-stress change; max_inner : station iteration limit;
    relax : initial under-relaxation of the temperature update (halved when the change grows).

    Outputs: T, tau [Pa], u [m/s], gv (viscous shear rate) [1/s], heat (tau*gv) [W/m^3],
    q1, q2 (heat flux into solid 1 and 2) [W/m^2], slope (stress slope G = h dp/dx across the
    film) [Pa], inner_its per station; ``slope`` also carries the previous sweep's values in.

    zone_passes, zone_tol : when the march has just passed a reverse-flow zone (a thick EHL
        inlet), relax the zone's energy equation by up to ``zone_passes`` symmetric passes
        (:func:`_zone_relax`, until the relative change is below ``zone_tol``) before going
        on downstream. Heat carried upstream by reverse flow then crosses the zone in one
        sweep instead of one station per sweep; the converged field is the same.

    Returns ``(n_station_fail, n_tau_fail, n_reverse, zone passes)``; the first three count
    the final state of each station.
    """
    n = p.shape[0]
    nzp = nz + 1
    dZ = 1.0 / nz
    tau0 = oil[I_TAU0]
    G = oil[I_G]
    inv_G = 0.0 if G >= G_ELASTICITY_OFF else 1.0 / G
    wz = np.full(nzp, dZ)
    wz[0] = 0.5 * dZ
    wz[nzp - 1] = 0.5 * dZ
    Zc = np.empty(nzp)
    for j in range(nzp):
        Zc[j] = j * dZ - 0.5
    # the flux target in the Z quadrature's terms: a Newtonian film at the EHL viscosity then
    # gets G = h dp/dx exactly (sum w Z^2 is 1/12 + dZ^2/6 for the trapezoid rule)
    flux_scale = 0.0
    for j in range(nzp):
        flux_scale += 12.0 * wz[j] * Zc[j] * Zc[j]

    d = np.empty(nzp)
    inv_eta = np.empty(nzp)
    mx_r = np.empty(nzp)
    Ti = np.empty(nzp)
    Tn = np.empty(nzp)
    tau_old = np.empty(nzp)
    aa = np.empty(nzp)
    bb = np.empty(nzp)
    cc = np.empty(nzp)
    rr = np.empty(nzp)
    gtot = np.empty(nzp)

    log_ratio = roelands_log_ratio(oil)
    st_fail = np.zeros(n, dtype=np.int64)
    st_tau = np.zeros(n, dtype=np.int64)
    st_rev = np.zeros(n, dtype=np.int64)
    # last energy rows of each station, and their factors for the zone passes
    eq_rc = np.empty((n, nzp))
    eq_src = np.empty((n, nzp))
    eq_s = np.empty((n, 8))
    fa = np.empty((n, nzp))
    fcp = np.empty((n, nzp))
    fim = np.empty((n, nzp))
    f1 = np.empty((n, nzp))
    f2 = np.empty((n, nzp))
    fb = np.empty((n, nzp))
    u_eps = 1e-9 * (abs(u1) + abs(u2))
    relax_zones = zone_passes > 0 and thermal
    n_pass = 0
    zlo = -1
    for i in range(n):
        ok, nt, nr = _station(
            i, n, nzp, dx, dZ, p, h, dpdx, qp, flux, compress, dpdx_c, oil, log_ratio, tau0, inv_G, u1, u2, um, T_oil, Ts1, Ts2,
            WL1, WR1, WL2, WR2, thermal, first, q1_lag, q2_lag, T_lag, T_lag,
            tol_T, tol_tau, max_inner, relax, wz, Zc, flux_scale,
            d, inv_eta, mx_r, Ti, Tn, tau_old, aa, bb, cc, rr, gtot,
            T, tau, u, gv, q1, q2, heat, slope, inner_its, eq_rc, eq_src, eq_s,
        )
        st_fail[i] = 0 if ok else 1
        st_tau[i] = nt
        st_rev[i] = nr
        if not relax_zones:
            continue
        # the inlet station is fixed: a zone starts at station 1 at the earliest
        if nr > 0 and zlo < 0:
            zlo = max(i, 1)
        if zlo >= 0 and (nr == 0 or i == n - 1):
            hi_z = i - 1 if nr == 0 else i
            if hi_z >= zlo:
                n_pass += _zone_relax(zlo, hi_z, i, n, nzp, dx, u_eps, Ts1, Ts2, T, u, eq_rc, eq_src, eq_s,
                                      aa, bb, cc, rr, Tn, fa, fcp, fim, f1, f2, fb, q1, q2, zone_passes, zone_tol)
            zlo = -1
    return np.sum(st_fail), np.sum(st_tau), np.sum(st_rev), n_pass


@njit(cache=True, nogil=True)
def _least_squares_gelsd(At, f):
    """``argmin |A gamma - f|`` for ``A`` given transposed (``At``, m x N, overwritten) by LAPACK's
    dgelsd with the inputs np.linalg.lstsq(A, f, rcond=1e-10) gives it; empty on failure."""
    m, N = At.shape
    ldb = max(N, m)
    b = np.zeros(ldb)  # in: f; out: gamma in b[:m]
    for r in range(N):
        b[r] = f[r]
    sv = np.empty(m)
    rank = np.empty(1, dtype=F_INT_nptype)
    if _gelsd(_KIND_D, N, m, 1, At.ctypes, N, b.ctypes, ldb, sv.ctypes, 1e-10, rank.ctypes) != 0:
        return np.empty(0)
    return b[:m].copy()


@njit(cache=True, nogil=True)
def _least_squares_numpy(At, f):
    """The same by np.linalg.lstsq (numba versions without the LAPACK helper)."""
    m, N = At.shape
    A = np.empty((N, m))
    for c in range(m):
        for r in range(N):
            A[r, c] = At[c, r]
    return np.linalg.lstsq(A, f, rcond=1e-10)[0]


_least_squares = _least_squares_gelsd if _gelsd is not None else _least_squares_numpy


@njit(cache=True, nogil=True)
def _anderson_step(X, F, count, x, g, depth):
    """One Anderson step (Walker & Ni 2011, type II, mixing 1) of the sweep map ``x -> g(x)``.

    ``X``, ``F`` hold the last ``count`` (at most ``depth + 1``) iterates and residuals
    ``g - x``, oldest first. Returns ``(x_new, count)``; on a degenerate or non-finite step
    (or a least-squares solve that fails) the history is cleared and ``g`` returned.
    """
    N = x.shape[0]
    f = g - x
    if count == depth + 1:
        for r in range(depth):
            for c in range(N):
                X[r, c] = X[r + 1, c]
                F[r, c] = F[r + 1, c]
        count -= 1
    for c in range(N):
        X[count, c] = x[c]
        F[count, c] = f[c]
    count += 1
    if count < 2:
        return g.copy(), count
    m = count - 1
    dF = np.empty((N, m))
    dX = np.empty((N, m))
    norms = np.empty(m)
    for c in range(m):
        s = 0.0
        for r in range(N):
            dF[r, c] = F[c + 1, r] - F[c, r]
            dX[r, c] = X[c + 1, r] - X[c, r]
            s += dF[r, c] * dF[r, c]
        norms[c] = math.sqrt(s)
        if not (math.isfinite(norms[c]) and norms[c] > 0.0):
            return g.copy(), 0
    # gamma = argmin |A gamma - f|, A = dF with unit columns (np.linalg.lstsq, rcond 1e-10)
    At = np.empty((m, N))  # row c of At is column c of A: A in column-major order
    for c in range(m):
        for r in range(N):
            At[c, r] = dF[r, c] / norms[c]
    b = _least_squares(At, f)
    if b.size == 0:
        return g.copy(), 0
    out = np.empty(N)
    for r in range(N):
        t = 0.0
        for c in range(m):
            t += (dX[r, c] + dF[r, c]) * (b[c] / norms[c])
        out[r] = g[r] - t
    for r in range(N):
        if not math.isfinite(out[r]):
            return g.copy(), 0
    return out, count


@njit(cache=True, nogil=True)
def march_line(
    dx, p, h, dpdx, qp, flux, compress, dpdx_c, oil, u1, u2, um, T_oil, Ts1, Ts2,
    WL1, WR1, WL2, WR2, nz, thermal, tol_T, tol_tau, max_inner, relax,
    max_sweeps, lagged, zone_passes, zone_tol, s1, s2, depth,
    T, tau, u, gv, q1, q2, heat, slope, inner_its, history, first_zone_passes=-1, warm=False,
):
    """Repeat :func:`sweep_line` until the field stops changing (thesis 3.2.2.2 with the
    upstream influences lagged; see ``thermal.line.solve_thermal_line``).

    The lagged quantities (downstream wall fluxes scaled to kelvin by ``s1``, ``s2``, and the
    temperatures) are updated by Anderson mixing of depth ``depth``. Sweeps stop after the
    first when nothing is lagged (isothermal, or no upstream reach and no reverse flow), when
    the largest relative temperature change falls below ``tol_T``, on non-finite temperatures
    or after ``max_sweeps``. ``history[k]`` receives the change of sweep k (1 for the first).
    ``zone_passes``, ``zone_tol``: relaxation of reverse-flow zones within each sweep
    (:func:`sweep_line`; 0 passes: none); ``first_zone_passes`` (>= 0) caps the passes of the
    first sweep, whose zone coefficients come from a field still far from its fixed point.
    ``warm``: ``T``, ``q1``, ``q2`` and ``slope`` hold a field near this one (the solution of
    the previous outer iteration): the first sweep starts from it as the later ones do, and
    its change counts.

    Returns ``(sweeps, settled, n_station_fail, n_tau_fail, n_reverse)`` of the last sweep and
    the number of zone passes of all sweeps.
    """
    n = p.shape[0]
    nzp = nz + 1
    q1_lag = q1.copy() if warm else np.zeros(n)
    q2_lag = q2.copy() if warm else np.zeros(n)
    T_lag = T.copy()
    N = 2 * n + n * nzp
    X = np.empty((depth + 1, N))
    F = np.empty((depth + 1, N))
    count = np.int64(0)  # not a literal 0: one signature of _anderson_step
    settled = False
    n_fail = 0
    n_tau_fail = 0
    n_rev = 0
    zone_total = 0
    sweeps = 0
    for k in range(max_sweeps):
        sweeps = k + 1
        first = k == 0 and not warm
        passes_k = min(zone_passes, first_zone_passes) if first and first_zone_passes >= 0 else zone_passes
        n_fail, n_tau_fail, n_rev, n_pass = sweep_line(
            dx, p, h, dpdx, qp, flux, compress, dpdx_c, oil, u1, u2, um, T_oil, Ts1, Ts2,
            WL1, WR1, WL2, WR2, nz, thermal, first, q1_lag, q2_lag, T_lag,
            tol_T, tol_tau, max_inner, relax, T, tau, u, gv, q1, q2, heat, slope, inner_its, passes_k, zone_tol,
        )
        zone_total += n_pass
        change = 1.0
        finite = True
        if not first:
            change = 0.0
            for i in range(n):
                for j in range(nzp):
                    c = abs(T[i, j] - T_lag[i, j]) / abs(T_lag[i, j] + T_KELVIN)
                    if not math.isfinite(c):
                        change = math.nan
                    elif c > change:
                        change = c
        history[k] = change
        if not (thermal and (lagged or n_rev > 0)):
            settled = True
            break
        if not first and change < tol_T:
            settled = True
            break
        for i in range(n):
            for j in range(nzp):
                if not math.isfinite(T[i, j]):
                    finite = False
        if not finite:
            break
        g = np.empty(N)
        x_old = np.empty(N)
        for i in range(n):
            g[i] = q1[i] * s1
            g[n + i] = q2[i] * s2
            x_old[i] = q1_lag[i] * s1
            x_old[n + i] = q2_lag[i] * s2
            for j in range(nzp):
                g[2 * n + i * nzp + j] = T[i, j]
                x_old[2 * n + i * nzp + j] = T_lag[i, j]
        if k == 0:
            x_new = g
        else:
            x_new, count = _anderson_step(X, F, count, x_old, g, depth)
        for i in range(n):
            q1_lag[i] = x_new[i] / s1
            q2_lag[i] = x_new[n + i] / s2
            for j in range(nzp):
                T_lag[i, j] = x_new[2 * n + i * nzp + j]
    return sweeps, settled, n_fail, n_tau_fail, n_rev, zone_total
