"""Banded LU with partial pivoting in numba: the collective line-relaxation systems.

LAPACK's ``gbsv`` (``gbtf2`` + ``gbtrs``: the unblocked factorisation LAPACK itself runs
for half band widths up to 64) transcribed operation for operation, so the row interchanges
are LAPACK's; the products may round differently (no fused multiply-add here). In numba the
steady line solver's system is solved in the kernel that builds it, without a call into
scipy and a copy into LAPACK's storage per sweep (docs/performance.md, "Line relaxation: banded
systems"). The starved and transient line solvers keep LAPACK (``line.level.solve_band``).

Storage: a matrix of ``m`` unknowns with ``q`` sub- and super-diagonals is held by columns,
``ab[j, 2 q + i - j] = A[i, j]`` (``ab`` of shape ``(m, 3 q + 1)``, LAPACK's ``gbtrf``
storage transposed so a column is contiguous); the first ``q`` entries of each column take the
fill-in of the interchanges and must be zero on entry.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def band_factor(ab, q, ipiv):
    """Factor ``P A = L U`` in place (LAPACK ``gbtf2``); ``ipiv[j]`` the row swapped with row
    ``j``. Returns 0, or ``j + 1`` for the first exactly zero pivot ``U[j, j]`` (the
    factorisation goes on, as LAPACK's)."""
    m = ab.shape[0]
    kv = 2 * q
    info = 0
    ju = 0
    mult = np.empty(q + 1)
    for j in range(m):
        km = min(q, m - 1 - j)
        # pivot: the first largest magnitude of column j on and below the diagonal
        jp = 0
        amax = abs(ab[j, kv])
        for t in range(1, km + 1):
            v = abs(ab[j, kv + t])
            if v > amax:
                amax = v
                jp = t
        ipiv[j] = j + jp
        if ab[j, kv + jp] != 0.0:
            ju = max(ju, min(j + q + jp, m - 1))
            if jp != 0:
                for c in range(j, ju + 1):  # rows j and j + jp of columns j .. ju
                    a = ab[c, kv + j + jp - c]
                    ab[c, kv + j + jp - c] = ab[c, kv + j - c]
                    ab[c, kv + j - c] = a
            if km > 0:
                rp = 1.0 / ab[j, kv]
                for t in range(1, km + 1):
                    ab[j, kv + t] *= rp
                    mult[t] = ab[j, kv + t]  # a copy the compiler need not reload
                for c in range(j + 1, ju + 1):
                    y = ab[c, kv + j - c]
                    if y != 0.0:
                        off = kv + j - c
                        for t in range(1, km + 1):
                            ab[c, off + t] -= mult[t] * y
        elif info == 0:
            info = j + 1
    return info


@njit(cache=True)
def band_substitute(ab, q, ipiv, b):
    """Solve ``A x = b`` in place from :func:`band_factor`'s factors (LAPACK ``gbtrs``)."""
    m = ab.shape[0]
    kv = 2 * q
    for j in range(m - 1):
        lm = min(q, m - 1 - j)
        p = ipiv[j]
        if p != j:
            t = b[p]
            b[p] = b[j]
            b[j] = t
        bj = b[j]
        if bj != 0.0:
            for t in range(1, lm + 1):
                b[j + t] -= ab[j, kv + t] * bj
    for j in range(m - 1, -1, -1):
        if b[j] != 0.0:
            b[j] /= ab[j, kv]
            bj = b[j]
            for i in range(j - 1, max(0, j - kv) - 1, -1):
                b[i] -= bj * ab[j, kv + i - j]


@njit(cache=True)
def solve_band_columns(ab, rhs, q):
    """Solution of the banded system ``ab`` (column storage, overwritten by its factors) for
    ``rhs`` (kept); a singular system (a film collapsed to zero) is relaxed by point Jacobi
    instead, as gbsv's callers do when it reports a zero pivot."""
    m = ab.shape[0]
    diag = ab[:, 2 * q].copy()
    ipiv = np.empty(m, dtype=np.int64)
    x = rhs.copy()
    if band_factor(ab, q, ipiv) == 0:
        band_substitute(ab, q, ipiv, x)
        return x
    for i in range(m):
        x[i] = rhs[i] / diag[i] if abs(diag[i]) > 0.0 else 0.0
    return x
