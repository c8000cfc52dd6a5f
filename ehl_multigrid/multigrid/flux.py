"""Face coefficient of the Poiseuille flux of the Reynolds discretisation.

The flux ``eps dP/dX`` between two nodes takes its coefficient at the face between them from
the nodes' ``eps = rho H^3/(eta lambda)``:

* ``"arithmetic"`` (the default, Venner's): ``(a + b)/2``, the mean over the cell of ``eps``
  interpolated linearly between the nodes;
* ``"logarithmic"``: ``(a - b)/(ln a - ln b)``, the mean over the cell of ``eps`` interpolated
  exponentially between the nodes -- as the viscosity ``e^(alpha_bar P)`` varies across the
  outlet's pressure fall, where ``eps`` changes by orders of magnitude within a few cells and
  the linear interpolant overstates it.

Both are second-order central discretisations (they differ by ``O(h^2)`` where ``eps`` is smooth
on the grid's scale) and converge to the same film. Which coarse-grid film is closer is an
empirical matter (docs/accuracy.md, "Face coefficient of the Poiseuille flux"): on line
contacts the logarithmic mean puts the minimum film of (1500, 8) within 0.1 % of its limit on
8193-16385 points, where the arithmetic mean leaves 1.6-0.6 %; coefficients smaller still (the
geometric mean, or the harmonic average ``ab/L`` of the exponential, which carries a pure
Poiseuille flux exactly) bring Hc closer but overshoot Hm by 1-5 %. Its grid sequence of Hm is
not monotone on coarse grids, so the accuracy loop states it with more caution
(``accuracy.richardson(earlier_half=...)``, converged coarser solves); ``LineOptions.face`` takes
it on request (``"auto"``: where ``alpha_bar >= 1``), the default stays arithmetic.

Where a node has no film (``eps = 0``, a collapsed iterate) both use the arithmetic mean, so a
point next to it keeps its Poiseuille coupling.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

#: names of the face coefficients and the codes the kernels take
FACE_MODES = {"arithmetic": 0, "logarithmic": 1}
#: below this relative difference of the two coefficients the logarithmic mean is their
#: arithmetic mean to rounding (its series starts with ``(a - b)^2/(6 (a + b))``)
EQUAL_REL = 1e-6


@njit(cache=True, inline="always")
def eps_face(a: float, b: float, mode: int) -> float:
    """Face coefficient of two nodes' ``eps``: ``mode`` 0 arithmetic, 1 logarithmic mean
    (arithmetic where either is not positive)."""
    if mode == 0 or a <= 0.0 or b <= 0.0 or abs(a - b) <= EQUAL_REL * (a + b):
        return 0.5 * (a + b)
    return (a - b) / (math.log(a) - math.log(b))


@njit(cache=True, inline="always")
def eps_face_d(a: float, b: float, mode: int) -> tuple[float, float, float]:
    """:func:`eps_face` and its derivatives with respect to ``a`` and ``b``."""
    if mode == 0 or a <= 0.0 or b <= 0.0 or abs(a - b) <= EQUAL_REL * (a + b):
        return 0.5 * (a + b), 0.5, 0.5
    d = math.log(a) - math.log(b)
    m = (a - b) / d
    return m, (1.0 - m / a) / d, (m / b - 1.0) / d


@njit(cache=True)
def eps_faces(a: np.ndarray, b: np.ndarray, mode: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`eps_face_d` on arrays (the dense Newton Jacobians assembled with numpy)."""
    n = a.shape[0]
    m, da, db = np.empty(n), np.empty(n), np.empty(n)
    for k in range(n):
        m[k], da[k], db[k] = eps_face_d(a[k], b[k], mode)
    return m, da, db


@njit(cache=True)
def face_coefficients(eps: np.ndarray, mode: int) -> np.ndarray:
    """:func:`eps_face` of every face of a line of nodes, ``out[i]`` between ``eps[i]`` and
    ``eps[i + 1]``, with one logarithm per node instead of two per face and stencil. The mean
    is symmetric to the bit (``(b - a)/(ln b - ln a)`` is ``(a - b)/(ln a - ln b)`` exactly), so
    a stencil takes both its faces from here."""
    n = eps.shape[0]
    out = np.empty(max(n - 1, 0))
    if mode == 0:
        for i in range(n - 1):
            out[i] = 0.5 * (eps[i] + eps[i + 1])
        return out
    ln = np.zeros(n)
    for i in range(n):
        if eps[i] > 0.0:
            ln[i] = math.log(eps[i])
    for i in range(n - 1):
        a, b = eps[i], eps[i + 1]
        if a <= 0.0 or b <= 0.0 or abs(a - b) <= EQUAL_REL * (a + b):
            out[i] = 0.5 * (a + b)
        else:
            out[i] = (a - b) / (ln[i] - ln[i + 1])
    return out
