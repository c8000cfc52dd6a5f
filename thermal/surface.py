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


@njit(cache=True, nogil=True)
def _strip_kernel(xi, v, length, k_solid, nodes, wts):
    """Compiled :func:`moving_strip_kernel` at one ``xi`` [m] (``length <= 0`` means infinite)."""
    a = abs(xi)
    va = v * a
    if xi < 0.0 and 2.0 * va > 700.0:
        return 0.0
    tmax = math.asinh(length / (2.0 * a)) if length > 0.0 else 1e300
    if va > 0.0:
        cut = math.acosh(1.0 + 60.0 / va)
        if cut < tmax:
            tmax = cut
    s = 0.0
    for q in range(nodes.shape[0]):
        t = 0.5 * tmax * (nodes[q] + 1.0)
        if xi > 0.0:
            sh = math.sinh(0.5 * t)
            ch = 2.0 * sh * sh
        else:
            ch = math.cosh(t) + 1.0
        s += wts[q] * math.exp(-va * ch)
    return 0.5 * tmax * s / (math.pi * k_solid)


@njit(cache=True, nogil=True)
def _mirror_cell_moments(k, dx, v, length, k_solid, tn, tw, gx, gw):
    """Hat moments of the downstream cell ``[k dx, (k + 1) dx]`` and of its upstream mirror
    ``[-(k + 1) dx, -k dx]`` by Gauss-Legendre (nodes ``gx``, weights ``gw`` on [-1, 1]).

    Upstream of a source the moving-strip kernel is the downstream one times ``exp(-2 v |xi|)``
    (the integrands ``exp(-v|xi| (cosh t -+ 1))`` differ by that factor over the same range of
    t), and the Gauss nodes of the mirror cell are the mirror images of the downstream ones, so
    one set of kernel values serves both cells. Returns ``(down_s, down_1s, up_s, up_1s)``:
    ``int_0^1 s K((c + s) dx) ds`` and ``int_0^1 (1 - s) K((c + s) dx) ds`` for ``c = k`` and
    ``c = -k - 1``.
    """
    nq = gx.shape[0]
    kd = np.empty(nq)
    ke = np.empty(nq)
    down_s = 0.0
    down_1s = 0.0
    for q in range(nq):
        s = 0.5 * (gx[q] + 1.0)
        a = (k + s) * dx
        kd[q] = _strip_kernel(a, v, length, k_solid, tn, tw)
        two_va = 2.0 * v * a
        ke[q] = kd[q] * math.exp(-two_va) if two_va <= 700.0 else 0.0
        down_s += kd[q] * s * gw[q]
        down_1s += kd[q] * (1.0 - s) * gw[q]
    up_s = 0.0
    up_1s = 0.0
    for q in range(nq):
        s = 0.5 * (gx[q] + 1.0)
        # node q of the mirror cell sits at |xi| = (k + 1 - s) dx, the downstream node nq - 1 - q
        kq = ke[nq - 1 - q]
        up_s += kq * s * gw[q]
        up_1s += kq * (1.0 - s) * gw[q]
    return 0.5 * down_s, 0.5 * down_1s, 0.5 * up_s, 0.5 * up_1s


@njit(cache=True, nogil=True)
def _strip_hat_weights(n, dx, v, length, k_solid, tn, tw, cx, cw, fx, fw, sx, sw):
    """Half-hat weights ``(WL, WR)`` of the moving-strip kernel (see :func:`wall_weights`).

    Cell ``c`` (``xi`` in ``[c dx, (c + 1) dx]``) carries ``WL[m = c]`` (weight ``1 - s``) and
    ``WR[m = c + 1]`` (weight ``s``); downstream cell ``k`` and its upstream mirror ``-k - 1``
    share their kernel values (:func:`_mirror_cell_moments`). ``WL[k]`` and ``WR[-k]`` use the
    24-point rule ``(cx, cw)`` when ``k <= 3``, ``WR[k + 1]`` and ``WL[-k - 1]`` when
    ``k + 1 <= 3``, the others the 8-point rule ``(fx, fw)``; the two cells touching ``xi = 0``
    (log singularity) use graded nodes ``r = sigma^2`` of the 48-point rule ``(sx, sw)`` from
    the singular end.
    """
    i0 = n - 1
    WL = np.zeros(2 * n - 1)
    WR = np.zeros(2 * n - 1)
    for k in range(1, n):
        near_a = k <= 3      # WL[k], WR[-k]
        near_b = k + 1 <= 3  # WR[k + 1], WL[-k - 1] (exist for k + 1 <= n - 1)
        gx, gw = (cx, cw) if near_a else (fx, fw)
        d_s, d_1s, u_s, u_1s = _mirror_cell_moments(k, dx, v, length, k_solid, tn, tw, gx, gw)
        WL[i0 + k] = dx * d_1s
        WR[i0 - k] = dx * u_s
        if k + 1 <= n - 1:
            if near_b != near_a:
                gx, gw = (cx, cw) if near_b else (fx, fw)
                d_s, d_1s, u_s, u_1s = _mirror_cell_moments(k, dx, v, length, k_solid, tn, tw, gx, gw)
            WR[i0 + k + 1] = dx * d_s
            WL[i0 - k - 1] = dx * u_1s
    # the cells touching xi = 0: d r = 2 g dg, g = (sigma + 1)/2
    down_s = 0.0
    down_1s = 0.0
    up_s = 0.0
    up_1s = 0.0
    for q in range(sx.shape[0]):
        g = 0.5 * (sx[q] + 1.0)
        r = g * g
        jac = g * sw[q]
        kd = _strip_kernel(r * dx, v, length, k_solid, tn, tw)
        two_va = 2.0 * v * r * dx
        ku = kd * math.exp(-two_va) if two_va <= 700.0 else 0.0
        down_s += kd * r * jac
        down_1s += kd * (1.0 - r) * jac
        up_s += ku * r * jac
        up_1s += ku * (1.0 - r) * jac
    WR[i0 + 1] = dx * down_s   # m = 1: xi = s dx, weight s
    WL[i0] = dx * down_1s      # m = 0: xi = s dx, weight 1 - s
    WR[i0] = dx * up_1s        # m = 0: xi = (s - 1) dx, weight s = 1 - r
    WL[i0 - 1] = dx * up_s     # m = -1: xi = (s - 1) dx, weight 1 - s = r
    return WL, WR


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


# 512 tables hold a repeated 21-slip curve's 41 (line), 410 (Hertz point, 10 slices) or about
# 50 (EHL input), 0.7 ms each to build (a third of a Hertz point curve's CPU); a table is
# 2 (2n - 1) floats, 2.5 kB at the default n = 80
@lru_cache(maxsize=512)
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
    return _strip_hat_weights(n, dx, v, L, solid.k, *_GL_THETA, *_GL_CELL, *_GL_FAR, *_GL_SING)
