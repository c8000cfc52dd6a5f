"""Independent reference for the rigid-isoviscous, incompressible point contact.

With rigid surfaces, ``eta = rho = 1``, the film ``H = H00 + X^2/2 + theta Y^2/2`` does not
depend on P, so for a given H00 the discrete Reynolds equation (same 5-point / upwind
discretisation as :mod:`.numerics`) is LINEAR in P. This module solves it with a sparse direct
factorisation and an active-set loop for cavitation (points with P < 0 are fixed to 0 and the
system re-solved until the set is stable; a point re-enters when its residual asks for a
positive pressure), and finds H00 from the load balance by Brent's method. It shares no code
with the multigrid solver apart from the problem parameters, so it is an independent check of
the FAS solver's rigid limit (``SolverOptions(elastic=False)``).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.optimize import brentq

from .problem import PointProblem


def _assemble(X, Y, H, lam, order, active):
    """Sparse matrix and right-hand side of ``Poiseuille(P) = wedge`` with rows of the
    boundary and of the active (cavitated) set replaced by ``P = 0``."""
    ny, nx = H.shape
    hx, hy = X[1] - X[0], Y[1] - Y[0]
    eps = H**3 / lam
    idx = np.arange(nx * ny).reshape(ny, nx)
    free = np.zeros((ny, nx), bool)
    free[1:-1, 1:-1] = True
    free &= ~active
    jj, ii = np.nonzero(free)
    e = eps[jj, ii]
    cw = 0.5 * (eps[jj, ii - 1] + e) / hx**2
    ce = 0.5 * (eps[jj, ii + 1] + e) / hx**2
    cs = 0.5 * (eps[jj - 1, ii] + e) / hy**2
    cn = 0.5 * (eps[jj + 1, ii] + e) / hy**2
    rows, cols, vals = [], [], []
    for dj, di, v in ((0, 0, -(cw + ce + cs + cn)), (0, -1, cw), (0, 1, ce), (-1, 0, cs), (1, 0, cn)):
        ok = free[jj + dj, ii + di]
        rows.append(idx[jj, ii][ok])
        cols.append(idx[jj + dj, ii + di][ok])
        vals.append(v[ok])
    fixed = idx[~free]
    rows.append(fixed)
    cols.append(fixed)
    vals.append(np.ones(fixed.size))
    b = np.zeros((ny, nx))
    w1 = (H[:, 1:] - H[:, :-1]) / hx
    wed = np.zeros((ny, nx))
    wed[:, 1:] = w1
    if order == 2:
        wed[:, 2:] = (1.5 * H[:, 2:] - 2.0 * H[:, 1:-1] + 0.5 * H[:, :-2]) / hx
    b[free] = wed[free]
    A = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(nx * ny, nx * ny))
    return A, b.ravel()


def rigid_pressure(X, Y, H, lam, order=2, max_active_iter=100):
    """Cavitated solution of the linear rigid Reynolds problem for a fixed film H: primal
    active set for the complementarity problem (negative pressures are fixed to 0 and the
    system re-solved; when none is negative, fixed points whose residual ``b - A P`` is
    negative, i.e. that ask for a positive pressure, are released)."""
    ny, nx = H.shape
    active = np.zeros((ny, nx), bool)
    P = np.zeros((ny, nx))
    A0, b0 = _assemble(X, Y, H, lam, order, active)
    inner = np.zeros((ny, nx), bool)
    inner[1:-1, 1:-1] = True
    for _ in range(max_active_iter):
        A, b = _assemble(X, Y, H, lam, order, active)
        P = spla.spsolve(A.tocsc(), b).reshape(ny, nx)
        neg = (P < 0.0) & ~active
        if neg.any():
            active |= neg
            continue
        r = (b0 - A0 @ P.ravel()).reshape(ny, nx)
        back = active & inner & (r < -1e-12 * np.abs(b0).max())
        if not back.any():
            break
        active &= ~back
    return np.maximum(P, 0.0)


def solve_rigid_direct(problem: PointProblem, n: int = 65, xmin: float = -4.5, xmax: float = 1.5,
                       ymax: float | None = None, order: int = 2) -> dict:
    """Rigid-isoviscous reference: returns ``{"H00", "Hc_venner", "Hc", "P", "X", "Y"}``."""
    ymax = 3.0 * problem.b_over_a if ymax is None else ymax
    X = np.linspace(xmin, xmax, n)
    Y = np.linspace(-ymax, ymax, n)
    hx, hy = X[1] - X[0], Y[1] - Y[0]
    G = 0.5 * X[None, :] ** 2 + 0.5 * problem.theta * Y[:, None] ** 2
    lam = problem.lam

    def load_err(H00):
        P = rigid_pressure(X, Y, H00 + G, lam, order)
        return hx * hy * P.sum() - problem.load

    lo, hi = 1e-3, 1.0
    for _ in range(20):
        if load_err(lo) > 0:
            break
        lo *= 0.1
    for _ in range(20):
        if load_err(hi) < 0:
            break
        hi *= 4.0
    H00 = brentq(load_err, lo, hi, xtol=1e-14, rtol=1e-12)
    P = rigid_pressure(X, Y, H00 + G, lam, order)
    return {"H00": H00, "Hc_venner": H00, "Hc": H00 * problem.moes_factor, "P": P, "X": X, "Y": Y}
