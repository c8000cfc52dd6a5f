"""Levelling (tilt and form removal) and missing-point handling.

The thesis's Wyko settings remove the tilt only ("Terms removed: Tilt", section 4.4.1);
:func:`remove_form` removes a least-squares polynomial of the given total degree for curved
specimens (a ball). Both fit on the valid (non-NaN) points only.

Missing points (NaN), two policies, stated in every statistics output:

* ``"exclude"`` (default): NaN points stay NaN; amplitude statistics use the valid points,
  a summit needs a complete valid 3 x 3 neighbourhood, and filters use normalised convolution.
* ``"fill"``: NaN points are replaced by the harmonic (Laplace) interpolation of their valid
  neighbours. A harmonic fill has no interior maximum, so it creates no summit inside a hole.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ehl_multigrid.model.errors import InputError, require_choice

from .heightmap import HeightMap

NAN_POLICIES = ("exclude", "fill")


def _poly_terms(order: int) -> list[tuple[int, int]]:
    return [(i, j) for k in range(order + 1) for i in range(k + 1) for j in [k - i]]


def fit_polynomial(hmap: HeightMap, order: int) -> np.ndarray:
    """Least-squares polynomial ``sum c_ij x^i y^j`` (``i + j <= order``) over the valid points,
    evaluated on the whole grid [m]. Coordinates are scaled to [-1, 1] for conditioning."""
    if not isinstance(order, (int, np.integer)) or isinstance(order, bool) or not 0 <= order <= 6:
        raise InputError(f"polynomial order = {order!r} must be an integer in [0, 6]")
    ny, nx = hmap.shape
    xs = np.linspace(-1.0, 1.0, nx)
    ys = np.linspace(-1.0, 1.0, ny)
    valid = ~hmap.missing
    terms = _poly_terms(int(order))
    # x^i y^j separable: build the design matrix on valid points only
    iy, ix = np.nonzero(valid)
    A = np.empty((iy.size, len(terms)))
    for c, (i, j) in enumerate(terms):
        A[:, c] = xs[ix] ** i * ys[iy] ** j
    coef, *_ = np.linalg.lstsq(A, hmap.z[valid], rcond=None)
    out = np.zeros(hmap.shape)
    for c, (i, j) in enumerate(terms):
        out += coef[c] * np.outer(ys**j, xs**i)
    return out


def remove_plane(hmap: HeightMap) -> HeightMap:
    """Subtract the least-squares plane (tilt and mean), as the thesis's "Terms removed: Tilt"."""
    return hmap.with_z(hmap.z - fit_polynomial(hmap, 1), "plane (tilt) removed")


def remove_form(hmap: HeightMap, order: int) -> HeightMap:
    """Subtract a least-squares polynomial form of total degree ``order`` (2 = quadric)."""
    return hmap.with_z(hmap.z - fit_polynomial(hmap, order), f"form removed (polynomial order {order})")


def level(hmap: HeightMap, method: str = "plane", order: int = 2) -> HeightMap:
    """``method``: ``"plane"`` (tilt), ``"form"`` (polynomial of ``order``), ``"mean"`` or ``"none"``."""
    require_choice("levelling", method, ("plane", "form", "mean", "none"))
    if method == "plane":
        return remove_plane(hmap)
    if method == "form":
        return remove_form(hmap, order)
    if method == "mean":
        return hmap.with_z(hmap.z - np.nanmean(hmap.z), "mean removed")
    return hmap


def fill_harmonic(z: np.ndarray) -> np.ndarray:
    """Replace NaN points by the solution of Laplace's equation with the valid points as
    Dirichlet data (4-neighbour stencil; grid edges are natural boundaries)."""
    miss = np.isnan(z)
    if not miss.any():
        return z.copy()
    if miss.all():
        raise InputError("height map has no valid point to fill from")
    ny, nx = z.shape
    idx = -np.ones(z.shape, dtype=np.int64)
    iy, ix = np.nonzero(miss)
    nunk = iy.size
    idx[iy, ix] = np.arange(nunk)
    diag = np.zeros(nunk)
    rhs = np.zeros(nunk)
    rows: list[np.ndarray] = []
    cols: list[np.ndarray] = []
    zfill = np.where(miss, 0.0, z)
    for sy, sx in ((0, 1), (0, -1), (1, 0), (-1, 0)):
        jy, jx = iy + sy, ix + sx
        inside = (jy >= 0) & (jy < ny) & (jx >= 0) & (jx < nx)
        diag[inside] += 1.0
        k = np.nonzero(inside)[0]
        nb_unknown = miss[jy[k], jx[k]]
        rhs[k[~nb_unknown]] += zfill[jy[k[~nb_unknown]], jx[k[~nb_unknown]]]
        rows.append(k[nb_unknown])
        cols.append(idx[jy[k[nb_unknown]], jx[k[nb_unknown]]])
    r = np.concatenate(rows)
    c = np.concatenate(cols)
    A = sp.csr_matrix((np.concatenate([diag, -np.ones(r.size)]), (np.concatenate([np.arange(nunk), r]),
                                                                  np.concatenate([np.arange(nunk), c]))),
                      shape=(nunk, nunk))
    sol = spla.spsolve(A.tocsc(), rhs)
    out = z.copy()
    out[iy, ix] = sol
    return out


def handle_missing(hmap: HeightMap, policy: str = "exclude") -> HeightMap:
    """Apply the missing-point policy (module docstring); records what was done in the history."""
    require_choice("nan policy", policy, NAN_POLICIES)
    n = hmap.n_missing
    if n == 0:
        return hmap
    if policy == "fill":
        return hmap.with_z(fill_harmonic(hmap.z), f"{n} missing points filled (harmonic interpolation)")
    return hmap.with_z(hmap.z, f"{n} missing points excluded")
