"""Elastic deformation ``W_i = sum_j K_|i-j| P_j`` of a line contact, three ways behind one
interface (the film equation's elastic integral):

* :class:`DirectDeformation` -- the dense O(N^2) sum (reference, small grids);
* :class:`FFTDeformation` -- linear convolution by FFT with zero padding (DC-FFT), O(N log N),
  exact to round-off;
* :class:`MLMIDeformation` -- Brandt & Lubrecht multilevel multi-integration, O(N): the sum
  is evaluated on coarser grids with the kernel interpolated at order ``p`` in the source
  index (anterpolation of ``P``), the result interpolated at order ``p`` back to the fine
  grid, and both interpolations corrected exactly within ``m`` points of the diagonal.
  The error left is the interpolation error of the kernel beyond ``m`` points; it falls like
  ``m^-p`` (tests/line/test_deformation.py; docs/accuracy.md).

Use :func:`make_deformation` to build one; all have ``apply(P) -> W`` and ``kernel``.
Operators are cached per ``(n, h, method, options)`` because the multigrid solver calls them
thousands of times on the same grids.
"""

from __future__ import annotations

import functools
import threading

import numpy as np
from numba import njit

from ..model.errors import require_choice
from .kernel import log_kernel

METHODS = ("mlmi", "fft", "direct")


@njit(cache=True)
def _toeplitz_sum(K: np.ndarray, u: np.ndarray) -> np.ndarray:
    n = u.shape[0]
    out = np.zeros(n)
    for j in range(n):
        uj = u[j]
        if uj == 0.0:
            continue
        for i in range(n):
            d = i - j if i >= j else j - i
            out[i] += K[d] * uj
    return out


class DirectDeformation:
    """Dense sum, O(N^2). ``apply(P)[i] = sum_j K_|i-j| P_j``."""

    method = "direct"

    def __init__(self, n: int, h: float) -> None:
        self.n, self.h = n, h
        self.kernel = log_kernel(n, h)

    def apply(self, P: np.ndarray) -> np.ndarray:
        return _toeplitz_sum(self.kernel, np.ascontiguousarray(P, dtype=float))


def fast_real_length(n: int) -> int:
    """The smallest ``2^a 3^b 5^c >= n``: pocketfft's fast real transform lengths
    (``scipy.fft.next_fast_len(n, real=True)``)."""
    best = 1 << max(n - 1, 0).bit_length()
    p5 = 1
    while p5 < best:
        p35 = p5
        while p35 < best:
            m = p35
            while m < n:
                m *= 2
            best = min(best, m)
            p35 *= 3
        p5 *= 5
    return best


def _numpy_pocketfft():
    """numpy's pocketfft ufuncs ``(rfft_n_even, rfft_n_odd, irfft)``, called straight into
    per-thread output arrays (``numpy.fft.rfft`` allocates its output each call: at 131073
    points the fresh 2 MB arrays cost a fifth of the transform), when they give
    ``numpy.fft``'s results bit for bit on a probe; None otherwise (another numpy whose private
    module moved or changed: ``numpy.fft`` then)."""
    global _PFU
    if _PFU is None:
        _PFU = False
        try:
            from numpy.fft import _pocketfft_umath as pfu

            x = np.random.default_rng(3).random(7)
            ok = True
            for size in (12, 15):
                F = np.empty(size // 2 + 1, dtype=complex)
                (pfu.rfft_n_even if size % 2 == 0 else pfu.rfft_n_odd)(x, 1.0, out=F)
                y = np.empty(size)
                pfu.irfft(F, np.reciprocal(size, dtype=float), out=y)
                ok = ok and np.array_equal(F, np.fft.rfft(x, size)) and \
                    np.array_equal(y, np.fft.irfft(np.fft.rfft(x, size), size))
            if ok:
                _PFU = (pfu.rfft_n_even, pfu.rfft_n_odd, pfu.irfft)
        except Exception:  # noqa: BLE001 - any change of the private API: numpy.fft
            _PFU = False
    return _PFU or None


_PFU: tuple | bool | None = None


class FFTDeformation:
    """Linear (not circular) convolution by FFT: the Toeplitz kernel is embedded in a
    circulant and ``P`` is zero padded to its length.

    The two end points carry no pressure on a line grid, so the sources ``j = 1 .. N-2`` reach
    the targets ``i = 0 .. N-1`` over distances up to ``N - 2`` and a circulant of length
    ``2 N - 3`` or more holds them without wrap-around: ``2 (N - 1)``, a power of two on the
    solver's grids, where pocketfft's transform pair is twice as fast as on the ``2 N - 1`` of
    a general convolution (7.6 -> 3.6 ms at 131073 points; docs/performance.md). End pressures
    that are not zero are added by the direct sum.

    numpy's FFTs (pocketfft, as scipy.fft's: the same results bit for bit,
    tests/multigrid/test_transforms.py), so a line solve imports neither ``scipy.fft`` nor the
    ``scipy.special`` it loads; the transforms write into arrays kept per thread
    (:func:`_numpy_pocketfft`)."""

    method = "fft"

    def __init__(self, n: int, h: float) -> None:
        self.n, self.h = n, h
        self.kernel = log_kernel(n, h)
        self.size = fast_real_length(max(2 * n - 3, n))
        c = np.zeros(self.size)
        c[: n - 1] = self.kernel[: n - 1]
        if n > 2:
            c[self.size - n + 2:] = self.kernel[1: n - 1][::-1]
        self._kf = np.fft.rfft(c)
        self._local = threading.local()

    def apply(self, P: np.ndarray) -> np.ndarray:
        P = np.asarray(P, dtype=float)
        n = self.n
        if n == 1:
            return P * self.kernel
        ends = P[0] != 0.0 or P[-1] != 0.0
        if ends:
            P0, P1 = P[0], P[-1]
            P = P.copy()
            P[0] = P[-1] = 0.0
        ufuncs = _numpy_pocketfft()
        if ufuncs is None:
            W = np.fft.irfft(np.fft.rfft(P, self.size) * self._kf, self.size)[:n]
        else:
            bufs = getattr(self._local, "bufs", None)
            if bufs is None:
                bufs = self._local.bufs = (np.empty(self.size // 2 + 1, dtype=complex), np.empty(self.size))
            F, out = bufs
            ufuncs[self.size % 2](P, 1.0, out=F)
            F *= self._kf
            ufuncs[2](F, np.reciprocal(self.size, dtype=float), out=out)
            W = out[:n].copy()
        if ends:
            W += P0 * self.kernel + P1 * self.kernel[::-1]
        return W


# -- multilevel multi-integration -----------------------------------------------------------
def _stencils(nc: int, p: int) -> tuple[np.ndarray, np.ndarray]:
    """Order-``p`` Lagrange interpolation from a coarse grid (``nc + 1`` points) to the odd
    points of the fine grid: start index ``s`` (clamped inside the grid) and weights."""
    I = np.arange(nc)
    starts = np.clip(I - p // 2 + 1, 0, nc + 1 - p).astype(np.int64)
    t = (I + 0.5 - starts)[:, None]  # position inside the stencil
    nodes = np.arange(p, dtype=float)
    weights = np.ones((nc, p))
    for k in range(p):
        for q in range(p):
            if q != k:
                weights[:, k] *= (t[:, 0] - nodes[q]) / (nodes[k] - nodes[q])
    return starts, weights


@njit(cache=True)
def _anterpolate(u: np.ndarray, starts: np.ndarray, weights: np.ndarray) -> np.ndarray:
    nc = (u.shape[0] - 1) // 2
    p = weights.shape[1]
    ub = np.empty(nc + 1)
    for J in range(nc + 1):
        ub[J] = u[2 * J]
    for I in range(nc):
        uj = u[2 * I + 1]
        if uj == 0.0:
            continue
        s = starts[I]
        for k in range(p):
            ub[s + k] += weights[I, k] * uj
    return ub


@njit(cache=True)
def _interpolate_and_correct(
    Wc: np.ndarray, u: np.ndarray, ub: np.ndarray, starts: np.ndarray, weights: np.ndarray,
    cj: np.ndarray, m: int, ci: np.ndarray, ci_first: np.ndarray,
) -> np.ndarray:
    nc = Wc.shape[0] - 1
    n = 2 * nc
    p = weights.shape[1]
    W = np.empty(n + 1)
    for I in range(nc + 1):
        W[2 * I] = Wc[I]
    for I in range(nc):
        s = starts[I]
        acc = 0.0
        for k in range(p):
            acc += weights[I, k] * Wc[s + k]
        # result-interpolation correction near the diagonal (coarse sources)
        J0 = ci_first[I]
        for t in range(ci.shape[1]):
            J = J0 + t
            if J > nc:
                break
            acc += ci[I, t] * ub[J]
        W[2 * I + 1] = acc
    # source-anterpolation correction near the diagonal (odd sources)
    for I in range(nc):
        uj = u[2 * I + 1]
        if uj == 0.0:
            continue
        j = 2 * I + 1
        for t in range(2 * m + 1):
            i = j - m + t
            if i < 0 or i > n:
                continue
            W[i] += cj[I, t] * uj
    return W


@njit(cache=True)
def _corrections(K: np.ndarray, starts: np.ndarray, weights: np.ndarray, m: int):
    """Exact-minus-interpolated kernel within ``m`` points of the diagonal.

    ``cj[I, t]``: source correction for odd source ``j = 2I+1`` at target ``i = j - m + t``;
    ``ci[I, t]``: result correction for odd target ``i = 2I+1`` from coarse source
    ``J = first[I] + t``.
    """
    n = K.shape[0] - 1
    nc = n // 2
    p = weights.shape[1]
    cj = np.zeros((nc, 2 * m + 1))
    ci = np.zeros((nc, m + 2))
    first = np.empty(nc, dtype=np.int64)
    for I in range(nc):
        j = 2 * I + 1
        s = starts[I]
        for t in range(2 * m + 1):
            i = j - m + t
            if i < 0 or i > n:
                continue
            approx = 0.0
            for k in range(p):
                approx += weights[I, k] * K[abs(i - 2 * (s + k))]
            cj[I, t] = K[abs(i - j)] - approx
        J0 = max((j - m + 1) // 2, 0)
        first[I] = J0
        for t in range(m + 2):
            J = J0 + t
            if J > nc or abs(j - 2 * J) > m:
                continue
            approx = 0.0
            for k in range(p):
                approx += weights[I, k] * K[2 * abs(s + k - J)]
            ci[I, t] = K[abs(j - 2 * J)] - approx
    return cj, ci, first


class _MLMILevel:
    def __init__(self, K: np.ndarray, p: int, m: int) -> None:
        nc = (K.shape[0] - 1) // 2
        self.starts, self.weights = _stencils(nc, p)
        self.cj, self.ci, self.ci_first = _corrections(K, self.starts, self.weights, m)
        self.m = m


class MLMIDeformation:
    """Multilevel multi-integration (Brandt & Lubrecht 1990) on a uniform grid.

    Parameters
    ----------
    n, h : grid points (``n - 1`` divisible by 2 for each coarsening) and mesh size.
    order : interpolation order ``p`` (even, number of points of the Lagrange stencils).
    radius : correction radius ``m`` [points] around the diagonal.
    n_direct : the sum is done directly once a grid has at most this many points.
    """

    method = "mlmi"

    def __init__(self, n: int, h: float, order: int = 12, radius: int = 48, n_direct: int = 65) -> None:
        if order % 2 or order < 2:
            raise ValueError("MLMI order must be even and >= 2")
        self.n, self.h, self.order, self.radius, self.n_direct = n, h, order, radius, n_direct
        self.kernel = log_kernel(n, h)
        self.levels: list[_MLMILevel] = []
        K = self.kernel
        while K.shape[0] > n_direct and (K.shape[0] - 1) % 2 == 0 and (K.shape[0] - 1) // 2 >= order:
            self.levels.append(_MLMILevel(K, order, radius))
            K = K[::2].copy()
        self.coarse_kernel = K

    def apply(self, P: np.ndarray) -> np.ndarray:
        us = [np.ascontiguousarray(P, dtype=float)]
        for lev in self.levels:
            us.append(_anterpolate(us[-1], lev.starts, lev.weights))
        W = _toeplitz_sum(self.coarse_kernel, us[-1])
        for k in range(len(self.levels) - 1, -1, -1):
            lev = self.levels[k]
            W = _interpolate_and_correct(
                W, us[k], us[k + 1], lev.starts, lev.weights, lev.cj, lev.m, lev.ci, lev.ci_first
            )
        return W


Deformation = DirectDeformation | FFTDeformation | MLMIDeformation


@functools.lru_cache(maxsize=64)
def make_deformation(n: int, h: float, method: str = "fft", order: int = 12, radius: int = 48) -> Deformation:
    """The deformation operator for ``n`` points at mesh size ``h`` (cached).

    ``method`` is ``"mlmi"``, ``"fft"`` or ``"direct"``; ``order``/``radius`` apply to MLMI.
    """
    require_choice("deformation", method, METHODS)
    if method == "direct":
        return DirectDeformation(n, h)
    if method == "fft":
        return FFTDeformation(n, h)
    return MLMIDeformation(n, h, order=order, radius=radius)
