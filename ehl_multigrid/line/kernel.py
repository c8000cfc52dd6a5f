"""Elastic log kernel of the line-contact film equation.

The film equation ``H = H0 + X^2/2 - (1/pi) int ln|X - X'| P(X') dX'`` is discretised with
``P`` piecewise constant on cells of width ``h`` centred on the nodes, so the deformation
``W_i = sum_j K_|i-j| P_j`` uses the exact cell integral

``K_d = int_{(d-1/2)h}^{(d+1/2)h} ln|x| dx``,

which depends only on ``d = |i - j|``: the matrix is Toeplitz on a uniform grid.
"""

from __future__ import annotations

import numpy as np


def log_kernel(n: int, h: float) -> np.ndarray:
    """Toeplitz coefficients ``K_d``, ``d = 0 .. n-1``, of the cell-integrated log kernel.

    Written in a form without cancellation (``K_d = h (ln h - 1 + 2 d atanh(1/(2d))
    + ln(d^2 - 1/4)/2)`` for ``d >= 1``) so the coefficients are accurate to round-off
    at any distance.

    Parameters
    ----------
    n : int
        Number of coefficients (grid points).
    h : float
        Mesh size (dimensionless, ``X = x/b``).
    """
    d = np.arange(n, dtype=float)
    K = np.empty(n)
    K[0] = h * (np.log(0.5 * h) - 1.0)
    if n > 1:
        dd = d[1:]
        K[1:] = h * (np.log(h) - 1.0 + 2.0 * dd * np.arctanh(0.5 / dd) + 0.5 * np.log(dd * dd - 0.25))
    return K
