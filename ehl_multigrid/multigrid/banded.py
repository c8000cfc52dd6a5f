"""Banded linear systems of the collective line relaxation, solved in one compiled kernel.

LAPACK's ``gbsv`` (behind ``scipy.linalg.solve_banded``) factorises column by column with a
BLAS call per step (pivot search, swap, scale, rank-one update); with 4 sub- and
super-diagonals each call moves a few numbers, and the calls, not the arithmetic, take the
time. :func:`solve_banded` runs the same elimination (partial pivoting, the multipliers of
each column scaled by the reciprocal of its pivot) in one kernel.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def solve_banded(ab: np.ndarray, rhs: np.ndarray, q: int) -> tuple[np.ndarray, bool]:
    """Solve ``A x = rhs`` for ``A`` in LAPACK band storage with ``q`` sub- and
    super-diagonals (``ab[q + i - j, j] = A[i, j]``, shape ``(2 q + 1, n)``), by Gaussian
    elimination with partial pivoting as LAPACK's ``gbsv``. Returns ``(x, ok)``; ``ok`` is
    False when a pivot is exactly zero (a singular system), and ``x`` is then not a solution.

    Examples
    --------
    >>> import numpy as np
    >>> ab = np.array([[0.0, 1.0, 1.0], [4.0, 4.0, 4.0], [1.0, 1.0, 0.0]])
    >>> x, ok = solve_banded(ab, np.array([5.0, 6.0, 5.0]), 1)
    >>> bool(ok), np.round(x, 12).tolist()
    (True, [1.0, 1.0, 1.0])
    """
    n = ab.shape[1]
    kv = 2 * q  # the upper bandwidth of U after the row interchanges
    # column-major band as LAPACK's (W[c, r] is its AB(r, c)): a column's band is contiguous
    W = np.zeros((n, 3 * q + 1))
    for j in range(n):
        for r in range(2 * q + 1):
            W[j, q + r] = ab[r, j]
    x = rhs.copy()
    piv = np.empty(n, np.int64)
    ju = 0  # last column the interchanges so far reach
    for j in range(n):
        km = min(q, n - 1 - j)
        jp = 0
        amax = abs(W[j, kv])
        for p in range(1, km + 1):
            v = abs(W[j, kv + p])
            if v > amax:
                amax = v
                jp = p
        piv[j] = j + jp
        if W[j, kv + jp] == 0.0:
            return x, False
        ju = max(ju, min(j + q + jp, n - 1))
        if jp != 0:
            for c in range(j, ju + 1):
                t = W[c, kv + j - c]
                W[c, kv + j - c] = W[c, kv + j + jp - c]
                W[c, kv + j + jp - c] = t
        if km > 0:
            rp = 1.0 / W[j, kv]
            for p in range(1, km + 1):
                W[j, kv + p] *= rp
            for c in range(j + 1, ju + 1):
                u = W[c, kv + j - c]
                if u != 0.0:
                    for p in range(1, km + 1):
                        W[c, kv + j + p - c] -= W[j, kv + p] * u
    for j in range(n):  # L y = P b
        l_row = piv[j]
        if l_row != j:
            t = x[l_row]
            x[l_row] = x[j]
            x[j] = t
        for p in range(1, min(q, n - 1 - j) + 1):
            x[j + p] -= W[j, kv + p] * x[j]
    for j in range(n - 1, -1, -1):  # U x = y, by columns as LAPACK's tbsv
        if x[j] != 0.0:
            x[j] /= W[j, kv]
            t = x[j]
            for i in range(max(0, j - kv), j):
                x[i] -= t * W[j, kv + i - j]
    return x, True
