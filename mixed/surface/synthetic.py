"""Synthetic height maps for tests, validation and users.

* :func:`gaussian_random_surface` - an isotropic Gaussian random surface with a chosen spectrum:
  a Gaussian autocorrelation ``R(r) = Rq^2 exp(-(r/l)^2)`` (correlation length ``l``; spectral
  moments ``m0 = Rq^2``, ``m2 = 2 Rq^2/l^2``, ``m4 = 12 Rq^2/l^4``, Nayak bandwidth 3), generated
  by circulant embedding so the sampled field has exactly the covariance ``R(k dx)`` at every
  sampling interval; or a self-affine power-law spectrum ``C(q) ~ q^(-2(1+H))`` between a
  roll-off and a short-wavelength cut-off (Hurst exponent ``H``, PSD slope ``-2(1+H)``).
* :func:`planted_asperities` - spherical caps of one radius with normally distributed apex
  heights on a flat base at random non-overlapping positions, with the planted values returned.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numba import njit

from ehl_multigrid.model.errors import InputError, require_positive, require_range

from .heightmap import HeightMap


def _shape(shape: Any) -> tuple[int, int]:
    if isinstance(shape, (int, np.integer)):
        shape = (int(shape), int(shape))
    try:
        ny, nx = (int(s) for s in shape)
    except (TypeError, ValueError):
        raise InputError(f"shape = {shape!r} must be an integer or a pair (ny, nx)") from None
    if ny < 3 or nx < 3 or ny * nx > 2**28:
        raise InputError(f"shape = {(ny, nx)} must be at least 3 x 3 and at most 2^28 points")
    return ny, nx


def gaussian_acf_moments(Rq: float, corr_length: float) -> dict[str, float]:
    """Profile spectral moments of the Gaussian autocorrelation ``Rq^2 exp(-(r/l)^2)``:
    ``m0 = R(0)``, ``m2 = -R''(0)``, ``m4 = R''''(0)`` [m^2, -, 1/m^2] and Nayak's ``alpha``."""
    m0 = Rq**2
    m2 = 2.0 * Rq**2 / corr_length**2
    m4 = 12.0 * Rq**2 / corr_length**4
    return {"m0": m0, "m2": m2, "m4": m4, "alpha": m0 * m4 / m2**2}


def gaussian_random_surface(
    shape: Any,
    dx: float,
    Rq: float,
    corr_length: float | None = None,
    hurst: float | None = None,
    rolloff: float | None = None,
    short_cutoff: float | None = None,
    dy: float | None = None,
    seed: int | None = None,
    normalise: bool = True,
) -> HeightMap:
    """Isotropic Gaussian random surface (periodic) [m].

    Give ``corr_length`` [m] for the Gaussian autocorrelation, or ``hurst`` (0 < H < 1) for a
    self-affine spectrum flat below the roll-off wavenumber ``2 pi/rolloff`` (default: the map
    side / 4) and zero above ``2 pi/short_cutoff`` (default: none, up to the Nyquist wavenumber).
    ``normalise`` rescales the realisation to exactly ``Rq`` (the ensemble Rq otherwise).
    ``meta["moments"]`` holds the continuous-surface spectral moments for the Gaussian ACF.
    """
    ny, nx = _shape(shape)
    dxm = require_positive("dx", dx, "m")
    dym = dxm if dy is None else require_positive("dy", dy, "m")
    rq = require_positive("Rq", Rq, "m")
    if (corr_length is None) == (hurst is None):
        raise InputError("give exactly one of corr_length (Gaussian autocorrelation) or hurst (power-law PSD)")
    rng = np.random.default_rng(seed)
    meta: dict[str, Any] = {"generator": "gaussian_random_surface", "Rq": rq, "seed": seed}
    if corr_length is not None:
        ell = require_positive("corr_length", corr_length, "m")
        if ell * 4 > min(nx * dxm, ny * dym):
            raise InputError(
                f"corr_length = {ell:.4g} m is too long for a {nx * dxm:.4g} x {ny * dym:.4g} m map "
                "(it must be below a quarter of the shorter side)"
            )
        # circulant embedding: covariance at periodic lags; its FFT is the (non-negative) spectrum
        lx = np.minimum(np.arange(nx), nx - np.arange(nx)) * dxm
        ly = np.minimum(np.arange(ny), ny - np.arange(ny)) * dym
        cov = np.exp(-(ly[:, None] ** 2 + lx[None, :] ** 2) / ell**2)
        lam = np.clip(np.fft.fft2(cov).real, 0.0, None)
        meta.update({"spectrum": "gaussian_acf", "corr_length": ell, "moments": gaussian_acf_moments(rq, ell)})
    else:
        H = require_range("hurst", hurst, 0.0, 1.0, "-", lo_open=True, hi_open=True)
        lr = require_positive("rolloff", rolloff, "m") if rolloff is not None else 0.25 * min(nx * dxm, ny * dym)
        qr = 2.0 * math.pi / lr
        qs = 2.0 * math.pi / require_positive("short_cutoff", short_cutoff, "m") if short_cutoff else math.inf
        qx = 2.0 * math.pi * np.fft.fftfreq(nx, dxm)
        qy = 2.0 * math.pi * np.fft.fftfreq(ny, dym)
        q = np.hypot(qy[:, None], qx[None, :])
        lam = np.where(q < qr, 1.0, (np.maximum(q, qr) / qr) ** (-2.0 * (1.0 + H)))
        lam[q > qs] = 0.0
        lam[0, 0] = 0.0
        meta.update({"spectrum": "power_law", "hurst": H, "psd_slope": -2.0 * (1.0 + H), "rolloff": lr,
                     "short_cutoff": short_cutoff})
    noise = rng.standard_normal((ny, nx)) + 1j * rng.standard_normal((ny, nx))
    field = np.fft.fft2(np.sqrt(lam / (nx * ny)) * noise).real
    field -= field.mean()
    if normalise:
        field *= rq / np.sqrt(np.mean(field**2))
    else:
        field *= rq / math.sqrt(lam.sum() / (nx * ny))
    return HeightMap(field, dxm, dym, source="synthetic gaussian_random_surface", meta=meta)


def spectral_moments(hmap: HeightMap) -> dict[str, float]:
    """Profile spectral moments of a (periodic, gap-free) map from its periodogram, averaged
    over the x and y directions: ``m0 = <z^2>``, ``m2 = <z_x^2>``, ``m4 = <z_xx^2>`` with
    spectral (exact) derivatives, and Nayak's bandwidth ``alpha = m0 m4 / m2^2``."""
    if hmap.n_missing:
        raise InputError("spectral_moments needs a map without missing points (fill them first)")
    z = hmap.z - hmap.z.mean()
    P = np.abs(np.fft.fft2(z)) ** 2 / z.size**2
    kx = 2.0 * math.pi * np.fft.fftfreq(hmap.nx, hmap.dx)[None, :]
    ky = 2.0 * math.pi * np.fft.fftfreq(hmap.ny, hmap.dy)[:, None]
    m0 = float(P.sum())
    m2 = 0.5 * float((P * kx**2).sum() + (P * ky**2).sum())
    m4 = 0.5 * float((P * kx**4).sum() + (P * ky**4).sum())
    return {"m0": m0, "m2": m2, "m4": m4, "alpha": m0 * m4 / m2**2 if m2 > 0 else math.nan}


# -- planted spherical asperities ----------------------------------------------------------------
@dataclass(frozen=True)
class PlantedTruth:
    """What was planted: cap centres [m], apex heights above the base [m], radius [m]."""

    x: np.ndarray
    y: np.ndarray
    apex: np.ndarray
    radius: float
    area: float

    @property
    def density(self) -> float:
        return self.x.size / self.area

    @property
    def sigma_s(self) -> float:
        return float(np.std(self.apex, ddof=1))


@njit(cache=True)
def _place(n: int, lx: float, ly: float, dmin: float, ux: np.ndarray, uy: np.ndarray) -> tuple:
    """Random sequential placement with minimum centre distance (cell list); returns the
    accepted centres among the candidate points (ux, uy) in [0,1)^2, in order, up to n."""
    ncx = max(1, int(lx / dmin))
    ncy = max(1, int(ly / dmin))
    cw = lx / ncx
    ch = ly / ncy
    head = -np.ones(ncx * ncy, dtype=np.int64)
    nxt = -np.ones(n, dtype=np.int64)
    xs = np.empty(n)
    ys = np.empty(n)
    count = 0
    d2 = dmin * dmin
    for t in range(ux.size):
        if count == n:
            break
        x = ux[t] * lx
        y = uy[t] * ly
        cx = min(int(x / cw), ncx - 1)
        cy = min(int(y / ch), ncy - 1)
        ok = True
        for oy in range(-1, 2):
            for ox in range(-1, 2):
                jx = cx + ox
                jy = cy + oy
                if jx < 0 or jy < 0 or jx >= ncx or jy >= ncy:
                    continue
                k = head[jy * ncx + jx]
                while k >= 0:
                    if (xs[k] - x) ** 2 + (ys[k] - y) ** 2 < d2:
                        ok = False
                        break
                    k = nxt[k]
                if not ok:
                    break
            if not ok:
                break
        if ok:
            xs[count] = x
            ys[count] = y
            c = cy * ncx + cx
            nxt[count] = head[c]
            head[c] = count
            count += 1
    return xs[:count], ys[:count]


@njit(cache=True)
def _raster_caps(z: np.ndarray, dx: float, dy: float, xs: np.ndarray, ys: np.ndarray,
                 apex: np.ndarray, R: float) -> None:
    ny, nx = z.shape
    for i in range(xs.size):
        h = apex[i]
        a = math.sqrt(max(2.0 * R * h - h * h, 0.0))
        j0 = max(0, int(math.floor((xs[i] - a) / dx)))
        j1 = min(nx - 1, int(math.ceil((xs[i] + a) / dx)))
        k0 = max(0, int(math.floor((ys[i] - a) / dy)))
        k1 = min(ny - 1, int(math.ceil((ys[i] + a) / dy)))
        for k in range(k0, k1 + 1):
            ry = k * dy - ys[i]
            for j in range(j0, j1 + 1):
                rx = j * dx - xs[i]
                r2 = rx * rx + ry * ry
                if r2 < a * a:
                    zc = h - R + math.sqrt(R * R - r2)
                    if zc > z[k, j]:
                        z[k, j] = zc


def planted_asperities(
    shape: Any,
    dx: float,
    density: float,
    radius: float,
    height_mean: float,
    height_std: float,
    dy: float | None = None,
    noise_rq: float = 0.0,
    seed: int | None = None,
) -> tuple[HeightMap, PlantedTruth]:
    """Spherical caps (radius ``radius`` [m]) at ``density`` [1/m^2] on a flat base at z = 0.

    Apex heights above the base are normal (``height_mean``, ``height_std`` [m]); values below
    ``0.2 height_mean`` are redrawn so every cap stands clear of the base. Centres are placed by
    random sequential adsorption with a minimum distance of two footprint radii of the tallest
    cap plus two grid steps, so caps never touch; an :class:`InputError` says when the density
    is too high for that. ``noise_rq`` adds uncorrelated Gaussian noise (instrument noise).
    """
    ny, nx = _shape(shape)
    dxm = require_positive("dx", dx, "m")
    dym = dxm if dy is None else require_positive("dy", dy, "m")
    dens = require_positive("density", density, "1/m^2")
    R = require_positive("radius", radius, "m")
    mu = require_positive("height_mean", height_mean, "m")
    sd = require_range("height_std", height_std, 0.0, mu / 2.0, "m")
    require_range("noise_rq", noise_rq, 0.0, math.inf, "m")
    lx, ly = nx * dxm, ny * dym
    n = int(round(dens * lx * ly))
    if n < 1:
        raise InputError(f"density = {dens:.4g} 1/m^2 gives no asperity on a {lx:.4g} x {ly:.4g} m map")
    rng = np.random.default_rng(seed)
    apex = rng.normal(mu, sd, n)
    low = apex < 0.2 * mu
    while low.any():
        apex[low] = rng.normal(mu, sd, int(low.sum()))
        low = apex < 0.2 * mu
    hmax = float(apex.max())
    if hmax >= R:
        raise InputError(f"apex heights up to {hmax:.4g} m must stay below the radius {R:.4g} m (caps, not spheres)")
    a_max = math.sqrt(2.0 * R * hmax - hmax**2)
    dmin = 2.0 * a_max + 2.0 * max(dxm, dym)
    cand = rng.random((2, 200 * n + 1000))
    xs, ys = _place(n, lx, ly, dmin, cand[0], cand[1])
    # grid point j represents [j - 1/2, j + 1/2) dx: centres cover exactly the sampled area
    xs = xs - 0.5 * dxm
    ys = ys - 0.5 * dym
    if xs.size < n:
        raise InputError(
            f"density = {dens:.4g} 1/m^2 is too high for non-overlapping caps of footprint radius "
            f"{a_max:.3g} m; at most about {0.5 / dmin**2:.3g} 1/m^2 fit (lower the density, radius or height)"
        )
    z = np.zeros((ny, nx))
    _raster_caps(z, dxm, dym, xs, ys, apex, R)
    if noise_rq > 0:
        z = z + rng.normal(0.0, noise_rq, z.shape)
    truth = PlantedTruth(x=xs, y=ys, apex=apex, radius=R, area=lx * ly)
    meta = {"generator": "planted_asperities", "density": dens, "radius": R, "height_mean": mu,
            "height_std": sd, "noise_rq": noise_rq, "seed": seed, "n_planted": n}
    return HeightMap(z, dxm, dym, source="synthetic planted_asperities", meta=meta), truth
