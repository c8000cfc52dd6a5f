"""Surface (flash) temperatures of the two solids: discrete influence weights.

The wall temperature of solid i is its bulk temperature plus the response of a half-space to
the heat flux ``q_i(x)`` the film sends into it (thesis (3.6)-(3.7), Carslaw & Jaeger moving heat source):

``T_i(x) = T_bulk,i + int q_i(x') K_i(x - x') dx'``.

Two kernels are offered.

``"carslaw-jaeger"``
    The thesis's (3.6)-(3.7) as printed (with the second equation's misprinted rho1 read as rho2):
    ``K(xi) = 1/sqrt(pi rho c k u) xi^(-1/2)`` for ``xi > 0`` and 0 upstream. This is the
    high-Peclet limit of a moving heat source; it diverges as ``u -> 0``, so it rejects a
    surface at rest.

``"moving-strip"`` (default)
    The exact steady temperature at the centre line of a heated strip of finite length ``B``
    (the line length, or the transverse contact width for point-contact slices) on a
    half-space moving at speed ``u`` (Carslaw & Jaeger's moving point source integrated over
    the strip length):

    ``K(xi) = 1/(pi k) int_0^Theta exp(-v |xi| (cosh t - sign xi)) dt``,
    ``v = u/(2 kappa)``, ``kappa = k/(rho c)``, ``Theta = asinh(B / (2 |xi|))``.

    For ``v B >> 1`` it tends to the 2-D moving line source ``exp(v xi) K0(v |xi|)/(pi k)`` and,
    downstream at ``v xi >> 1``, to the Carslaw-Jaeger kernel above. At ``u = 0`` it is the
    stationary strip ``asinh(B/(2|xi|))/(pi k)``: finite, with heat also reaching upstream
    points. That is how a surface at rest (pure sliding, |S| = 2) is handled; the 2-D kernel has no
    steady state at ``u = 0`` (it grows like ``ln(1/u)``), the finite strip length removes
    that divergence.

The heat flux is represented by hat functions on the uniform x grid, so the discrete
convolution is ``dT_i = sum_j W(i, j) q_j`` with weights split into the left and right halves
of each hat (``WL``, ``WR``, indexed by ``m = i - j + n - 1``); the first and last nodes carry
half hats.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numba import njit

from ehl_multigrid.model.errors import InputError, require_positive, require_range
from ehl_multigrid.model.solids import Solid

KERNELS = ("moving-strip", "carslaw-jaeger")

_GL_THETA = np.polynomial.legendre.leggauss(32)  # 1e-11 relative for v|xi| up to 1e7 (measured)
_GL_CELL = np.polynomial.legendre.leggauss(24)
_GL_FAR = np.polynomial.legendre.leggauss(8)
_GL_SING = np.polynomial.legendre.leggauss(48)


def diffusivity(solid: Solid) -> float:
    """Thermal diffusivity ``k/(rho c)`` [m^2/s]."""
    return solid.k / (solid.rho * solid.cp)


def peclet(u: float, half_width: float, solid: Solid) -> float:
    """Peclet number ``u b / (2 kappa)`` of a surface moving at ``u`` under a contact of half-width ``b``."""
    return abs(u) * half_width / (2.0 * diffusivity(solid))


def moving_strip_kernel(xi: np.ndarray, u: float, solid: Solid, length: float) -> np.ndarray:
    """Influence kernel ``K(xi)`` [K m/W] of the moving finite strip (see module docstring).

    ``xi = x - x'`` is the distance downstream of the source [m]; ``length`` the strip length
    B [m] (``inf`` for the 2-D line source, which needs ``u > 0``).
    """
    xi = np.atleast_1d(np.asarray(xi, dtype=float))
    v = abs(u) / (2.0 * diffusivity(solid))
    a = np.abs(xi)
    sgn = np.sign(xi)
    with np.errstate(divide="ignore", over="ignore"):
        theta_len = np.arcsinh(length / (2.0 * a)) if math.isfinite(length) else np.full_like(a, np.inf)
        va = v * a
        # beyond this angle exp(-va (cosh t - 1)) < e^-60
        cut = np.where(va > 0, np.arccosh(1.0 + 60.0 / np.maximum(va, 1e-300)), np.inf)
    tmax = np.minimum(theta_len, cut)
    if np.any(~np.isfinite(tmax)):
        raise InputError(
            "surface kernel: a surface at rest (u = 0) needs a finite kernel_length (strip length) [m]"
        )
    nodes, wts = _GL_THETA
    t = 0.5 * tmax[:, None] * (nodes[None, :] + 1.0)
    # cosh t - sign(xi) without cancellation near t = 0 downstream
    ch = np.where(sgn[:, None] > 0, 2.0 * np.sinh(0.5 * t) ** 2, np.cosh(t) + 1.0)
    ch = np.where(sgn[:, None] == 0, np.cosh(t), ch)
    integrand = np.exp(-va[:, None] * ch)
    out = 0.5 * tmax * (integrand @ wts) / (math.pi * solid.k)
    return out


@njit(cache=True)
def _strip_kernel_values(xi, v, length, k_solid, nodes, wts):
    """Compiled :func:`moving_strip_kernel` (``length <= 0`` means infinite)."""
    out = np.empty(xi.shape[0])
    for n in range(xi.shape[0]):
        a = abs(xi[n])
        va = v * a
        if xi[n] < 0.0 and 2.0 * va > 700.0:
            out[n] = 0.0
            continue
        tmax = math.asinh(length / (2.0 * a)) if length > 0.0 else 1e300
        if va > 0.0:
            cut = math.acosh(1.0 + 60.0 / va)
            if cut < tmax:
                tmax = cut
        s = 0.0
        for q in range(nodes.shape[0]):
            t = 0.5 * tmax * (nodes[q] + 1.0)
            if xi[n] > 0.0:
                sh = math.sinh(0.5 * t)
                ch = 2.0 * sh * sh
            else:
                ch = math.cosh(t) + 1.0
            s += wts[q] * math.exp(-va * ch)
        out[n] = 0.5 * tmax * s / (math.pi * k_solid)
    return out


def carslaw_jaeger_kernel(xi: np.ndarray, u: float, solid: Solid) -> np.ndarray:
    """Thesis kernel (3.6-3.7): ``xi^(-1/2) / sqrt(pi rho c k u)`` downstream, 0 upstream [K m/W]."""
    xi = np.atleast_1d(np.asarray(xi, dtype=float))
    c = 1.0 / math.sqrt(math.pi * solid.rho * solid.cp * solid.k * u)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(xi > 0, c / np.sqrt(np.where(xi > 0, xi, 1.0)), 0.0)


def _cj_linear_integral(a: np.ndarray, b: np.ndarray, alpha: np.ndarray, beta: np.ndarray) -> np.ndarray:
    """``int_a^b (alpha + beta xi) xi^(-1/2) dxi`` for ``0 <= a <= b``."""
    sa, sb = np.sqrt(a), np.sqrt(b)
    return 2.0 * alpha * (sb - sa) + (2.0 / 3.0) * beta * (sb**3 - sa**3)


@lru_cache(maxsize=64)
def wall_weights(
    n: int,
    dx: float,
    u: float,
    solid: Solid,
    kernel: str = "moving-strip",
    length: float = math.inf,
) -> tuple[np.ndarray, np.ndarray]:
    """Half-hat influence weights ``(WL, WR)`` [K m^2/W], each of size ``2n - 1`` (cached,
    read-only).

    ``WL[m + n - 1]`` is ``int_{-dx}^{0} (1 + t/dx) K(m dx - t) dt`` (left half of a hat centred on
    the source node, seen from a node m cells downstream); ``WR`` the right half
    ``int_0^{dx} (1 - t/dx) K(m dx - t) dt``.
    """
    out = _wall_weights(n, dx, u, solid, kernel, length)
    for arr in out:
        arr.setflags(write=False)
    return out


def _wall_weights(
    n: int,
    dx: float,
    u: float,
    solid: Solid,
    kernel: str = "moving-strip",
    length: float = math.inf,
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`wall_weights` without the cache."""
    require_range("surface kernel n", n, 2, 1e6)
    require_positive("surface kernel dx", dx, "m")
    require_range("surface velocity u", u, 0.0, 1e4, "m/s")
    if kernel not in KERNELS:
        raise InputError(f"surface_kernel = {kernel!r} is not one of the allowed values {list(KERNELS)}")
    m = np.arange(-(n - 1), n, dtype=float)
    if kernel == "carslaw-jaeger":
        if not u > 0:
            raise InputError(
                f"surface velocity u = {u:.6g} m/s: the Carslaw-Jaeger kernel (3.6-3.7) needs u > 0; "
                "use surface_kernel = 'moving-strip' for a surface at rest"
            )
        c = 1.0 / math.sqrt(math.pi * solid.rho * solid.cp * solid.k * u)
        # WR: xi in [(m-1)dx, m dx], weight (1 - m + xi/dx); nonzero for m >= 1
        lo = np.clip((m - 1.0) * dx, 0.0, None)
        hi = np.clip(m * dx, 0.0, None)
        WR = c * _cj_linear_integral(lo, hi, 1.0 - m, np.full_like(m, 1.0 / dx))
        # WL: xi in [m dx, (m+1) dx], weight (1 + m - xi/dx); nonzero for m >= 0
        lo = np.clip(m * dx, 0.0, None)
        hi = np.clip((m + 1.0) * dx, 0.0, None)
        WL = c * _cj_linear_integral(lo, hi, 1.0 + m, np.full_like(m, -1.0 / dx))
        return WL, WR

    if not (math.isfinite(length) or u > 0):
        raise InputError(
            "surface velocity u = 0 m/s: the moving-strip kernel needs a finite kernel_length [m] for a "
            "surface at rest"
        )
    if math.isfinite(length):
        require_positive("kernel_length", length, "m")

    v = u / (2.0 * diffusivity(solid))
    L = length if math.isfinite(length) else -1.0
    nodes, wts = _GL_THETA

    def k_of(xi: np.ndarray) -> np.ndarray:
        flat = np.ascontiguousarray(xi.ravel(), dtype=np.float64)
        return _strip_kernel_values(flat, v, L, solid.k, nodes, wts).reshape(xi.shape)

    WL = np.empty_like(m)
    WR = np.empty_like(m)
    # regular cells: xi in [m dx - dx, m dx] (WR) and [m dx, m dx + dx] (WL); 24 Gauss points
    # next to the singular cells, 8 further away where the kernel is smooth on the cell scale
    near = np.abs(m) <= 3
    for sel, (gx, gw) in ((near, _GL_CELL), (~near, _GL_FAR)):
        mm = m[sel]
        s = 0.5 * (gx + 1.0)  # in (0, 1)
        # WR: xi = (m - 1 + s) dx, weight (1 - m + xi/dx) = s
        WR[sel] = 0.5 * dx * (k_of((mm[:, None] - 1.0 + s[None, :]) * dx) * s[None, :]) @ gw
        # WL: xi = (m + s) dx, weight (1 + m - xi/dx) = 1 - s
        WL[sel] = 0.5 * dx * (k_of((mm[:, None] + s[None, :]) * dx) * (1.0 - s[None, :])) @ gw
    # cells touching xi = 0 (log singularity): graded nodes r = sigma^2 from the singular end
    sx, sw = _GL_SING
    g = 0.5 * (sx + 1.0)
    r = g**2
    jac = 0.5 * 2.0 * g * sw  # d r = 2 g dg, dg = dsig/2
    i0 = n - 1
    # WR, m = 1: xi = s dx in [0, dx], weight s; singular at s = 0
    WR[i0 + 1] = dx * np.sum(k_of(r * dx) * r * jac)
    # WR, m = 0: xi = (s - 1) dx in [-dx, 0], weight s; singular at s = 1 -> s = 1 - r
    WR[i0] = dx * np.sum(k_of(-r * dx) * (1.0 - r) * jac)
    # WL, m = 0: xi = s dx, weight 1 - s; singular at s = 0
    WL[i0] = dx * np.sum(k_of(r * dx) * (1.0 - r) * jac)
    # WL, m = -1: xi = (s - 1) dx, weight 1 - s; singular at s = 1 -> s = 1 - r
    WL[i0 - 1] = dx * np.sum(k_of(-r * dx) * r * jac)
    return WL, WR
