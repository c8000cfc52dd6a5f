"""Far-field pressure of an elliptic point contact (any ``theta = Rx/Ry``), by its angular
functions.

Far upstream the gap is ``H = X^2/2 + theta Y^2/2 + H00 + k/r`` (``r`` the distance from the
centre, ``k/r`` the far deformation of the load) and the pressure is small, so Reynolds'
equation is ``div(H^3 grad P) = lambda dH/dX``. In ``Y' = sqrt(theta) Y``, polar ``(rho, phi)``,
the undeformed gap is ``rho^2/2`` and the operator ``d_X(G d_X) + theta d_Y'(G d_Y')``; the
pressure is ``lambda [rho^-3 f(phi) + c2 rho^-5 g_c(phi) + k rho^-6 g_k(phi)]`` (``c2 = 2 H00``),
the first term exact for the undeformed gap, the others its first-order corrections in
``c2/rho^2`` and ``k/rho^3``. Each angular function solves a linear ODE

    (sin^2 + theta cos^2) u'' + (theta - 1)(2 s + 4) sin cos u' + s [(s + 5 + theta) cos^2
        + (1 + theta (s + 5)) sin^2] u = S(phi),    s = -3, -5, -6,

on the pressurised sector ``|phi - pi| < psi``, symmetric about the -X axis (``u'(pi) = 0``).
Reynolds' free-boundary condition ``P = dP/dphi = 0`` on the ray ``phi_c = pi - psi`` fixes
``psi`` (``f(phi_c) = f'(phi_c) = 0``), and to first order the corrections vanish there
(``g(phi_c) = 0``: the ray's own shift is then second order). For ``theta = 1`` ``f`` is
``-0.8 cos(phi) + C cosh(3 (phi - pi))``, ``psi`` = 108.44 deg (``point.farfield``). For
``theta < 1`` the ``k`` problem is near resonance with that condition (``g_k`` reaches 300 times
``f`` at theta 0.25, 1100 at 0.15, and does not reduce the residual of the far-field equation):
:class:`AngularFarField` leaves that term out there (``with_deformation``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.integrate import quad, solve_ivp
from scipy.interpolate import CubicHermiteSpline
from scipy.optimize import brentq

_TOL = dict(rtol=1e-11, atol=1e-13, method="DOP853")


def _coefficients(s: float, kappa: float, phi: float) -> tuple[float, float, float]:
    c, sn = math.cos(phi), math.sin(phi)
    return (sn * sn + kappa * c * c, (kappa - 1.0) * (2.0 * s + 4.0) * sn * c,
            s * ((s + 5.0 + kappa) * c * c + (1.0 + kappa * (s + 5.0)) * sn * sn))


def _integrate(s: float, kappa: float, source, phi0: float, u0: float, du0: float):
    def rhs(phi, y):
        a2, a1, a0 = _coefficients(s, kappa, phi)
        return [y[1], (source(phi) - a1 * y[1] - a0 * y[0]) / a2]
    return solve_ivp(rhs, (phi0, math.pi), [u0, du0], dense_output=True, **_TOL)


@dataclass(frozen=True)
class AngularFarField:
    """The angular functions of one ellipticity ``theta`` (:func:`angular_far_field`): the
    free-boundary ray ``phi_c`` and splines of ``f``, ``g_c``, ``g_k`` on ``[phi_c, pi]``."""

    theta: float
    phi_c: float
    f: CubicHermiteSpline
    g_c: CubicHermiteSpline
    g_k: CubicHermiteSpline

    @property
    def with_deformation(self) -> bool:
        """Whether the ``k`` term is used: not below theta 1 (near resonance: module note)."""
        return self.theta >= 1.0

    def terms(self, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``f, g_c, g_k`` at ``phi`` in ``[0, 2 pi)`` (zero outside the sector)."""
        a = math.pi - np.abs(math.pi - np.asarray(phi, float))  # symmetric about phi = pi
        inside = a > self.phi_c
        a = np.clip(a, self.phi_c, math.pi)
        return tuple(np.where(inside, sp(a), 0.0) for sp in (self.f, self.g_c, self.g_k))

    def pressure(self, lam: float, X: np.ndarray, Y: np.ndarray, c2: float = 0.0,
                 k: float = 0.0) -> np.ndarray:
        """The far-field pressure at ``(X, Y)`` (Venner units, Y in units of a), >= 0."""
        X, Y = np.broadcast_arrays(np.asarray(X, float), np.asarray(Y, float))
        Yp = math.sqrt(self.theta) * Y
        rho = np.hypot(X, Yp)
        phi = np.mod(np.arctan2(Yp, X), 2.0 * math.pi)
        f, gc, gk = self.terms(phi)
        k = k if self.with_deformation else 0.0
        with np.errstate(divide="ignore", invalid="ignore"):
            out = lam * np.maximum(f + c2 * gc / rho**2 + k * gk / rho**3, 0.0) / rho**3
        return np.where(rho > 0.0, out, 0.0)

    def load_outside(self, lam: float, xmin: float, xmax: float, ymax: float, c2: float = 0.0,
                     k: float = 0.0) -> float:
        """``∫∫`` of :meth:`pressure` outside the box ``xmin <= X <= xmax, |Y| <= ymax``
        (``xmin < 0 < xmax``): along each ray of the ``(X, Y')`` plane ``∫_R^inf`` of the
        pressure, ``R`` where the ray leaves the box: with ``u = 1/rho`` the integral over
        ``[0, 1/R]`` of the positive part of ``f + c2 g_c u^2 + k g_k u^3`` (the pressure is
        clipped at 0 where the corrections outweigh ``f`` next to the free boundary), times
        ``1/sqrt(theta)`` (``dY = dY'/sqrt(theta)``)."""
        yb = math.sqrt(self.theta) * ymax
        k = k if self.with_deformation else 0.0

        def ray(phi: float) -> float:
            c, s = math.cos(phi), math.sin(phi)
            R = xmin / c if c < 0 else (xmax / c if c > 0 else math.inf)
            if s != 0.0:
                R = min(R, yb / abs(s))
            f, gc, gk = (float(t) for t in self.terms(np.array(phi)))
            return _positive_part_integral((f, 0.0, c2 * gc, k * gk), 1.0 / R)

        lo = self.phi_c
        corners = sorted(p % (2 * math.pi) for p in (math.atan2(yb, xmin), math.atan2(yb, xmax)))
        breaks = [p for p in corners if lo < p < math.pi]
        # symmetric in Y: twice the upper half
        return 2.0 * lam / math.sqrt(self.theta) * quad(ray, lo, math.pi, points=breaks or None, limit=400)[0]


def _positive_part_integral(coef: tuple[float, float, float, float], U: float) -> float:
    """``∫_0^U max(p(u), 0) du`` for the cubic ``p = c0 + c1 u + c2 u^2 + c3 u^3``."""
    c = np.asarray(coef, float)
    P = np.polynomial.Polynomial(c)
    cuts = [0.0] + sorted(float(r.real) for r in P.roots() if abs(r.imag) < 1e-12 and 0.0 < r.real < U) + [U]
    antider = P.integ()
    return float(sum(antider(b) - antider(a) for a, b in zip(cuts, cuts[1:], strict=False)
                     if P(0.5 * (a + b)) > 0.0))


@lru_cache(maxsize=32)
def angular_far_field(theta: float) -> AngularFarField:
    """The far field's angular functions for ``theta`` (cached per ellipticity)."""
    kappa = float(theta)
    cos_src = lambda phi: 8.0 * math.cos(phi)  # noqa: E731 -- lambda = 1: P scales with it

    def miss(psi: float) -> float:
        sol = _integrate(-3.0, kappa, cos_src, math.pi - psi, 0.0, 0.0)
        return float(sol.y[1, -1])

    # the sector's half-angle: the root of f'(pi) = 0 next to the circular 108.4 deg, bracketed
    # on a scan (it moves with theta)
    grid = np.linspace(0.52 * math.pi, 0.98 * math.pi, 47)
    vals = [miss(p) for p in grid]
    roots = [(a, b) for a, b, fa, fb in zip(grid, grid[1:], vals, vals[1:], strict=False) if fa * fb < 0.0]
    if not roots:
        raise ValueError(f"no far-field free boundary found for theta = {theta:g}")
    psi = brentq(miss, *roots[0], xtol=1e-13)
    phi_c = math.pi - psi
    f_sol = _integrate(-3.0, kappa, cos_src, phi_c, 0.0, 0.0)

    def f_terms(phi: float) -> tuple[float, float, float]:
        f, df = f_sol.sol(phi)
        a2, a1, a0 = _coefficients(-3.0, kappa, phi)
        d2f = (8.0 * math.cos(phi) - a1 * df - a0 * f) / a2
        return f, df, d2f

    def ab(phi: float) -> tuple[float, float, float, float]:
        # A = s f c - f' sn, B = s f sn + f' c (s = -3) and their phi derivatives
        f, df, d2f = f_terms(phi)
        c, sn = math.cos(phi), math.sin(phi)
        A = -3.0 * f * c - df * sn
        B = -3.0 * f * sn + df * c
        dA = -4.0 * df * c + 3.0 * f * sn - d2f * sn
        dB = -4.0 * df * sn - 3.0 * f * c + d2f * c
        return A, B, dA, dB

    def src_c(phi: float) -> float:
        _, _, dA, dB = ab(phi)
        return -3.0 * (-dA * math.sin(phi) + kappa * dB * math.cos(phi))

    def W(phi: float) -> tuple[float, float]:
        c, sn = math.cos(phi), math.sin(phi)
        w = math.sqrt(c * c + sn * sn / kappa)
        dw = sn * c * (1.0 / kappa - 1.0) / w
        return 1.0 / w, -dw / (w * w)

    def src_k(phi: float) -> float:
        A, B, dA, dB = ab(phi)
        w, dw = W(phi)
        c, sn = math.cos(phi), math.sin(phi)
        m = -1.0
        t = (m * w * A * c - (dw * A + w * dA) * sn
             + kappa * (m * w * B * sn + (dw * B + w * dB) * c))
        return 8.0 * (-w * c - dw * sn) - 6.0 * t

    def corrected(s: float, source) -> object:
        part = _integrate(s, kappa, source, phi_c, 0.0, 0.0)
        hom = _integrate(s, kappa, lambda phi: 0.0, phi_c, 0.0, 1.0)
        alpha = -part.y[1, -1] / hom.y[1, -1]  # u'(pi) = 0
        return lambda phi: part.sol(phi) + alpha * hom.sol(phi)

    nodes = phi_c + (math.pi - phi_c) * (1.0 - np.cos(np.linspace(0.0, math.pi, 801))) / 2.0
    fv = f_sol.sol(nodes)
    gc_fun, gk_fun = corrected(-5.0, src_c), corrected(-6.0, src_k)
    gc, gk = gc_fun(nodes), gk_fun(nodes)
    return AngularFarField(theta, phi_c, CubicHermiteSpline(nodes, fv[0], fv[1]),
                           CubicHermiteSpline(nodes, gc[0], gc[1]), CubicHermiteSpline(nodes, gk[0], gk[1]))


def hertz_central_deformation(b_over_a: float) -> float:
    """``∫∫ P / r`` of the Hertzian pressure ``sqrt(1 - X^2 - (Y/beta)^2)`` (``beta = b/a``):
    ``(pi/4) ∫ dphi / sqrt(cos^2 + sin^2/beta^2)`` (the radial integral of the ellipsoid is
    ``pi/(4 sqrt(e))``); ``pi^2/2`` for a circle, so that times ``2/pi^2`` it is 1."""
    beta2 = b_over_a * b_over_a
    return 0.25 * math.pi * quad(lambda p: 1.0 / math.sqrt(math.cos(p) ** 2 + math.sin(p) ** 2 / beta2),
                                 0.0, 2.0 * math.pi, limit=200)[0]
