"""Greenwood-Williamson asperity contact (thesis 2.4.1, 4.2.2; GW functions (2.45),
asperity pressure (4.18)-(4.19)).

``F_j(lam) = int_lam^inf (s - lam)^j phi*(s) ds`` (2.45) with ``phi*`` the standard normal
density, evaluated to near machine precision for every ``lam`` (tested for -10..8 against
quadrature and both asymptotes) and in log form for the far tail, where ``F_j`` underflows.

Method (all three pieces are exact representations, not fits):

* ``lam > 1``: ``F_j = phi(lam) lam^-(j+1) int_0^inf x^j e^-x exp(-x^2/(2 lam^2)) dx``
  by generalised Gauss-Laguerre quadrature (weight ``x^j e^-x``, 100 nodes; 150 for j > 10). The remaining
  integrand is smooth and flattens as ``lam`` grows, so the rule is exact to rounding for
  ``lam > 1``; the log form never underflows.
* ``-12 <= lam <= 1``: the parabolic-cylinder representation
  ``F_j = Gamma(j+1) exp(-lam^2/4) D_{-j-1}(lam)/sqrt(2 pi)`` written with Kummer's series
  (DLMF 12.7.12-13); for ``lam <= 0`` every term is positive, for ``0 < lam <= 1`` the
  cancellation costs less than a factor 10. (``scipy.special.pbdv`` itself is only good to
  about 1e-9 near ``lam = 6``, which is why it is not used.)
* ``lam < -12``: the asymptotic series ``sum_k C(j, 2k) (2k-1)!! (-lam)^(j-2k)``; the
  neglected part is of order ``phi(lam)`` (below 1e-31 relative).

The asperity pressure is (4.18) ``pa = (2/3) n beta^(1/2) E' sigma_s^(3/2) F_3/2(hss/sigma_s)``
with the reduced modulus E' (Hertz of a sphere on a flat, ``(4/3) E* = (2/3) E'``); the
plasticity index (2.48) uses ``E'_GW = E'/2``.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numba import njit
from scipy import special

from ehl_multigrid.model.errors import InputError, require_positive, require_range
from ehl_multigrid.model.solids import gw_modulus

ArrayLike = float | np.ndarray

_LAM_KUMMER_HI = 1.0
_LAM_ASYM_LO = -12.0
_HALF_LOG_2PI = 0.5 * math.log(2.0 * math.pi)
J_MIN, J_MAX = -1.0, 20.0


@lru_cache(maxsize=32)
def _constants(j: float) -> tuple[np.ndarray, np.ndarray, float, float, float]:
    # 100 nodes reach rounding level for lam > 1 up to j = 10; larger orders need more
    x, w = special.roots_genlaguerre(100 if j <= 10.0 else 150, j)
    c0 = math.exp(math.lgamma(j + 1.0) - _HALF_LOG_2PI - 0.5 * (j + 1.0) * math.log(2.0))
    c1 = math.sqrt(math.pi) / math.gamma(0.5 * (j + 2.0))
    c2 = math.sqrt(2.0 * math.pi) / math.gamma(0.5 * (j + 1.0))
    return np.ascontiguousarray(x), np.ascontiguousarray(w), c0, c1, c2


@njit(cache=True)
def _kummer_m(a: float, b: float, x: float) -> float:
    # Kummer M(a, b, x) for a, b, x >= 0: positive terms, summed until negligible.
    s = 1.0
    t = 1.0
    k = 0
    while True:
        t *= (a + k) / (b + k) * x / (k + 1.0)
        s += t
        k += 1
        if t < 1e-17 * s or k > 5000:
            break
    return s


@njit(cache=True)
def _log_f_scalar(j: float, lam: float, xs: np.ndarray, ws: np.ndarray, c0: float, c1: float, c2: float) -> float:
    if lam > 1.0:
        acc = 0.0
        inv = 1.0 / (2.0 * lam * lam)
        for k in range(xs.shape[0]):
            acc += ws[k] * math.exp(-xs[k] * xs[k] * inv)
        return math.log(acc) - (j + 1.0) * math.log(lam) - 0.5 * lam * lam - 0.9189385332046728
    if lam >= -12.0:
        x = 0.5 * lam * lam
        m1 = _kummer_m(0.5 * (j + 1.0), 0.5, x)
        m2 = _kummer_m(0.5 * (j + 2.0), 1.5, x)
        val = c0 * math.exp(-x) * (c1 * m1 - c2 * lam * m2)
        return math.log(val)
    # asymptotic series in 1/lam^2 for lam -> -inf
    z = -lam
    inv2 = 1.0 / (z * z)
    term = 1.0
    s = 1.0
    k = 0
    while k < 200:
        # ratio of consecutive terms: C(j,2k+2)(2k+1)!!/(C(j,2k)(2k-1)!!) / z^2
        term *= (j - 2.0 * k) * (j - 2.0 * k - 1.0) / (2.0 * k + 2.0) * inv2
        s += term
        k += 1
        if abs(term) < 1e-17 * abs(s):
            break
    return j * math.log(z) + math.log(s)


@njit(cache=True)
def _log_f_array(j: float, lam: np.ndarray, xs: np.ndarray, ws: np.ndarray, c0: float, c1: float, c2: float) -> np.ndarray:
    out = np.empty(lam.shape[0])
    for i in range(lam.shape[0]):
        li = lam[i]
        if math.isnan(li):
            out[i] = math.nan
        elif li == math.inf:
            out[i] = -math.inf
        elif li == -math.inf:
            out[i] = math.inf
        else:
            out[i] = _log_f_scalar(j, li, xs, ws, c0, c1, c2)
    return out


def _check_j(j: float) -> float:
    return require_range("j (GW function order)", j, J_MIN, J_MAX, "-", lo_open=True)


def _as_array(lam: ArrayLike) -> tuple[np.ndarray, tuple[int, ...]]:
    arr = np.asarray(lam, dtype=float)
    return np.ascontiguousarray(arr.ravel()), arr.shape


def _out(arr: np.ndarray, shape: tuple[int, ...]) -> ArrayLike:
    return float(arr[0]) if shape == () else arr.reshape(shape)


def gw_log_f(j: float, lam: ArrayLike) -> ArrayLike:
    """``ln F_j(lam)`` (2.45), accurate where ``F_j`` itself underflows (``lam`` up to 1e150).

    Parameters
    ----------
    j : order, ``-1 < j <= 20``.
    lam : standardised separation ``hss/sigma_s`` [-], any shape.
    """
    j = _check_j(j)
    flat, shape = _as_array(lam)
    xs, ws, c0, c1, c2 = _constants(float(j))
    return _out(_log_f_array(float(j), flat, xs, ws, c0, c1, c2), shape)


def gw_f(j: float, lam: ArrayLike) -> ArrayLike:
    """Greenwood-Williamson function ``F_j(lam) = int_lam^inf (s - lam)^j phi*(s) ds`` (2.45).

    Relative error below 1e-12 for ``lam`` in [-10, 8] (tests check 1e-10 against
    quadrature); vectorised over ``lam``. ``F_1`` has a closed form (:func:`gw_f1`); this
    general routine agrees with it to rounding.

    Examples
    --------
    >>> round(gw_f(1.5, 0.0), 12)   # F_j(0) = 2^(j/2) Gamma((j+1)/2) / (2 sqrt(pi))
    0.430019993662
    """
    lf = gw_log_f(j, lam)
    return float(math.exp(lf)) if np.ndim(lf) == 0 else np.exp(lf)


def gw_f1(lam: ArrayLike) -> ArrayLike:
    """``F_1(lam) = phi(lam) - lam Q(lam)``; for ``lam > 0`` written with ``erfcx`` to avoid
    the cancellation (relative error about ``lam^2`` ulp)."""
    lam = np.asarray(lam, dtype=float)
    phi = np.exp(-0.5 * lam * lam - _HALF_LOG_2PI)
    with np.errstate(over="ignore", invalid="ignore"):
        pos = phi * (1.0 - lam * math.sqrt(math.pi / 2.0) * special.erfcx(lam / math.sqrt(2.0)))
        neg = phi - lam * 0.5 * special.erfc(lam / math.sqrt(2.0))
    out = np.where(lam > 0.0, pos, neg)
    if np.any(lam > 30.0):  # beyond this the erfcx form loses digits; use the general one
        big = lam > 30.0
        out = np.where(big, np.exp(np.asarray(gw_log_f(1.0, np.where(big, lam, 31.0)))), out)
    return float(out) if out.ndim == 0 else out


def gw_f32(lam: ArrayLike) -> ArrayLike:
    """``F_3/2(lam)``, the asperity-pressure function of (4.18)."""
    return gw_f(1.5, lam)


def gw_f_inverse(j: float, value: ArrayLike) -> ArrayLike:
    """``lam`` such that ``F_j(lam) = value`` (``F_j`` decreases monotonically).

    Solved by bracketing and bisection on ``ln F_j`` (vectorised; 0.5e-13 absolute in lam).
    For ``j = 0`` the value must lie in (0, 1).
    """
    j = require_range("j (GW function order)", j, 0.0, J_MAX, "-")
    v = np.asarray(value, dtype=float)
    if np.any(~(v > 0)) or np.any(~np.isfinite(v)):
        raise InputError(f"F_{j:g} value = {v[~(v > 0) | ~np.isfinite(v)].ravel()[:3]} must be finite and > 0")
    if j == 0.0 and np.any(v >= 1.0):
        raise InputError(f"F_0 value = {v[v >= 1].ravel()[:3]} must be < 1 (F_0 is a probability)")
    target = np.log(v).ravel()
    lo = np.full(target.shape, -1.0)
    hi = np.full(target.shape, 1.0)
    for _ in range(80):  # expand until F(lo) >= v >= F(hi)
        bad_lo = np.asarray(gw_log_f(j, lo)) < target
        bad_hi = np.asarray(gw_log_f(j, hi)) > target
        if not (bad_lo.any() or bad_hi.any()):
            break
        lo = np.where(bad_lo, 2.0 * lo, lo)
        hi = np.where(bad_hi, 2.0 * hi, hi)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        above = np.asarray(gw_log_f(j, mid)) > target
        lo = np.where(above, mid, lo)
        hi = np.where(above, hi, mid)
        if np.all(hi - lo < 5e-14 * np.maximum(1.0, np.abs(mid))):
            break
    out = 0.5 * (lo + hi)
    return float(out[0]) if v.ndim == 0 else out.reshape(v.shape)


# -- asperity pressure and plasticity --------------------------------------------------------
def asperity_pressure_coefficient(n: float, beta: float, sigma_s: float, E_reduced: float) -> float:
    """``(2/3) n beta^(1/2) E' sigma_s^(3/2)`` [Pa], the prefactor of (4.18)."""
    n = require_positive("roughness.n", n, "1/m^2")
    beta = require_positive("roughness.beta", beta, "m")
    sigma_s = require_positive("roughness.sigma_s", sigma_s, "m")
    E = require_positive("E_reduced", E_reduced, "Pa")
    return 2.0 / 3.0 * n * math.sqrt(beta) * E * sigma_s**1.5


def asperity_pressure(hss: ArrayLike, n: float, beta: float, sigma_s: float, E_reduced: float) -> ArrayLike:
    """Mean asperity pressure (4.18) ``pa = (2/3) n beta^(1/2) E' sigma_s^(3/2) F_3/2(hss/sigma_s)`` [Pa].

    Parameters
    ----------
    hss : separation of the smooth surface from the mean plane of the summits [m] (any sign).
    n : summit density [1/m^2]; beta : mean summit radius [m]; sigma_s : summit height std [m].
    E_reduced : reduced modulus E' [Pa] (2/E' = sum (1 - nu^2)/E).
    """
    c = asperity_pressure_coefficient(n, beta, sigma_s, E_reduced)
    return c * gw_f32(np.asarray(hss, dtype=float) / sigma_s) if np.ndim(hss) else c * gw_f32(float(hss) / sigma_s)


def plasticity_index(E_reduced: float, hardness: float, sigma_s: float, beta: float) -> float:
    """Greenwood-Williamson plasticity index (2.48) ``psi = (E'_GW/H') sqrt(sigma_s/beta)``,
    with ``E'_GW = E'/2`` (2.49). Elastic below about 0.6, plastic above 1."""
    H = require_positive("hardness", hardness, "Pa")
    s = require_positive("sigma_s", sigma_s, "m")
    b = require_positive("beta", beta, "m")
    return gw_modulus(E_reduced) / H * math.sqrt(s / b)
