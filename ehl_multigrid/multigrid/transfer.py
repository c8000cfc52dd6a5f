"""Grid transfers of the FAS cycles on uniform 1-D grids ``X_i = X_0 + i h`` with ``2^k n0 + 1``
points: injection and full weighting to the coarse grid, linear interpolation of corrections
and cubic (four-point) FMG interpolation to the fine grid. Two-dimensional grids apply them
per axis or use the numba versions of their contact module.
"""

from __future__ import annotations

import numpy as np


def inject(u: np.ndarray) -> np.ndarray:
    return u[::2].copy()


def full_weighting(r: np.ndarray) -> np.ndarray:
    out = np.zeros((r.shape[0] - 1) // 2 + 1)
    out[1:-1] = 0.25 * r[1:-3:2] + 0.5 * r[2:-2:2] + 0.25 * r[3:-1:2]
    return out


def interpolate_linear(u: np.ndarray) -> np.ndarray:
    out = np.empty(2 * (u.shape[0] - 1) + 1)
    out[::2] = u
    out[1::2] = 0.5 * (u[:-1] + u[1:])
    return out


def interpolate_cubic(u: np.ndarray) -> np.ndarray:
    """Four-point (cubic) interpolation, one-sided quadratic at the ends (FMG interpolation)."""
    nc = u.shape[0]
    out = np.empty(2 * (nc - 1) + 1)
    out[::2] = u
    mid = np.empty(nc - 1)
    if nc >= 4:
        mid[1:-1] = (-u[:-3] + 9.0 * u[1:-2] + 9.0 * u[2:-1] - u[3:]) / 16.0
        mid[0] = (3.0 * u[0] + 6.0 * u[1] - u[2]) / 8.0
        mid[-1] = (3.0 * u[-1] + 6.0 * u[-2] - u[-3]) / 8.0
    else:
        mid[:] = 0.5 * (u[:-1] + u[1:])
    out[1::2] = mid
    return out
