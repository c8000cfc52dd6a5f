"""Low-pass filters and the thesis's "filter until psi ~ 1" procedure (section 5.3).

Two filters, each recorded in the map's history so the statistics say which filter produced
them (thesis 5.3):

* :func:`lowpass_3x3` - the thesis's filter: "a standard WYKO filter which reduces the height at
  a point by the weighted average of its neighbours" (5.3, footnote 2), applied k times. The
  thesis does not print the weights; the default is the 3 x 3 binomial kernel
  ``[[1,2,1],[2,4,2],[1,2,1]]/16`` (transmission ``cos^2(pi dx/lambda_x) cos^2(pi dy/lambda_y)``
  per pass, never negative); ``weights="box"`` is the plain 3 x 3 mean.
* :func:`gaussian_lowpass` - areal Gaussian low-pass of ISO 16610-21/-61 with cut-off wavelength
  ``lambda_c``: weighting ``s(x) = exp(-pi (x/(alpha lambda_c))^2)/(alpha lambda_c)``,
  ``alpha = sqrt(ln 2 / pi)``, i.e. a Gaussian of standard deviation
  ``lambda_c sqrt(ln 2 / 2) / pi``; amplitude transmission ``exp(-pi (alpha lambda_c / lambda)^2)``,
  50 % at ``lambda = lambda_c``. Applied in Fourier space with the exact transmission.

Missing points (NaN) are handled by normalised convolution: ``F(z m) / F(m)`` with ``m`` the
valid mask, so a hole neither spreads nor drags its neighbours to zero; NaN points stay NaN.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import ndimage

from ehl_multigrid.model.errors import InputError, require_choice, require_positive

from .heightmap import HeightMap
from .statistics import SurfaceStats, surface_statistics

ISO_ALPHA = math.sqrt(math.log(2.0) / math.pi)
LOWPASS_KERNELS = {
    "binomial": np.outer([1.0, 2.0, 1.0], [1.0, 2.0, 1.0]) / 16.0,
    "box": np.ones((3, 3)) / 9.0,
}
EDGE_MODES = ("reflect", "wrap")


def gaussian_sigma(cutoff: float) -> float:
    """Standard deviation [m] of the ISO 16610-21 Gaussian weighting for cut-off ``cutoff`` [m]."""
    return cutoff * math.sqrt(math.log(2.0) / 2.0) / math.pi


def gaussian_transmission(wavelength: np.ndarray | float, cutoff: float) -> np.ndarray | float:
    """Amplitude transmission of the ISO Gaussian low-pass for a sinusoid of ``wavelength``."""
    return np.exp(-math.pi * (ISO_ALPHA * cutoff / np.asarray(wavelength, dtype=float)) ** 2)


def lowpass_transmission(wavelength_x: float, dx: float, passes: int = 1, weights: str = "binomial",
                         wavelength_y: float = math.inf, dy: float | None = None) -> float:
    """Transmission of ``passes`` applications of the 3 x 3 kernel for a sinusoid with the given
    wavelengths along x and y (``inf`` = constant along that axis)."""
    dy = dx if dy is None else dy

    def one_axis(lam: float, h: float) -> float:
        c = math.cos(2.0 * math.pi * h / lam) if math.isfinite(lam) else 1.0
        return (1.0 + c) / 2.0 if weights == "binomial" else (1.0 + 2.0 * c) / 3.0

    require_choice("lowpass weights", weights, tuple(LOWPASS_KERNELS))
    return (one_axis(wavelength_x, dx) * one_axis(wavelength_y, dy)) ** passes


def _normalised(apply: Any, z: np.ndarray) -> np.ndarray:
    miss = np.isnan(z)
    if not miss.any():
        return apply(z)
    m = (~miss).astype(float)
    num = apply(np.where(miss, 0.0, z))
    den = apply(m)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = num / den
    out[miss] = np.nan
    return out


def lowpass_3x3(hmap: HeightMap, passes: int = 1, weights: str = "binomial", mode: str = "reflect") -> HeightMap:
    """The thesis's low-pass filter: each point replaced by the weighted mean of itself and its 8
    neighbours, ``passes`` times (module docstring). ``mode``: map edges mirrored or periodic."""
    if isinstance(passes, bool) or not isinstance(passes, (int, np.integer)) or passes < 0 or passes > 10000:
        raise InputError(f"passes = {passes!r} must be an integer in [0, 10000]")
    require_choice("lowpass weights", weights, tuple(LOWPASS_KERNELS))
    require_choice("edge mode", mode, EDGE_MODES)
    k = LOWPASS_KERNELS[weights]
    z = hmap.z
    for _ in range(int(passes)):
        z = _normalised(lambda a: ndimage.convolve(a, k, mode=mode), z)
    # consecutive calls add up to one history entry ("... x 4"), as the thesis counts passes
    prefix = f"low-pass 3x3 {weights} x "
    total = int(passes)
    hist = hmap.history
    if hist and hist[-1].startswith(prefix):
        total += int(hist[-1][len(prefix):])
        hmap = HeightMap(hmap.z, hmap.dx, hmap.dy, hmap.source, hist[:-1], dict(hmap.meta))
    return hmap.with_z(z, f"{prefix}{total}")


def _gaussian_fft(a: np.ndarray, sx: float, sy: float, mode: str) -> np.ndarray:
    """Gaussian smoothing with standard deviations (sx, sy) in grid points, exact transmission."""
    ny, nx = a.shape
    if mode == "reflect":
        px = min(nx - 1, int(math.ceil(4.0 * sx)) + 1)
        py = min(ny - 1, int(math.ceil(4.0 * sy)) + 1)
        a = np.pad(a, ((py, py), (px, px)), mode="symmetric")
    else:
        px = py = 0
    fy = np.fft.fftfreq(a.shape[0])
    fx = np.fft.rfftfreq(a.shape[1])
    # Fourier transform of a unit-area Gaussian: exp(-2 pi^2 s^2 f^2)
    H = np.exp(-2.0 * math.pi**2 * ((sy * fy[:, None]) ** 2 + (sx * fx[None, :]) ** 2))
    out = np.fft.irfft2(np.fft.rfft2(a) * H, s=a.shape)
    return out[py : py + ny, px : px + nx]


def gaussian_lowpass(hmap: HeightMap, cutoff: float, mode: str = "reflect") -> HeightMap:
    """ISO 16610-21/-61 Gaussian low-pass with cut-off wavelength ``cutoff`` [m] (module docstring).

    ``mode="reflect"`` mirrors the map at its edges (statistics within about one ``cutoff`` of
    an edge are still influenced by the mirror); ``"wrap"`` treats the map as periodic.
    """
    lc = require_positive("cutoff wavelength lambda_c", cutoff, "m")
    require_choice("edge mode", mode, EDGE_MODES)
    s = gaussian_sigma(lc)
    z = _normalised(lambda a: _gaussian_fft(a, s / hmap.dx, s / hmap.dy, mode), hmap.z)
    return hmap.with_z(z, f"Gaussian low-pass lambda_c = {lc:.4g} m (ISO 16610-21)")


# -- filter until psi ------------------------------------------------------------------------
@dataclass
class FilterStep:
    """One step of :func:`filter_until_psi`: the filter setting and the statistics it gave."""

    method: str
    setting: float  # passes (lowpass) or lambda_c [m] (gaussian)
    stats: SurfaceStats

    def to_dict(self) -> dict[str, Any]:
        d = {"method": self.method, "setting": self.setting,
             "setting_units": "passes" if self.method == "lowpass" else "m"}
        d.update({k: getattr(self.stats, k) for k in ("Ra", "Rq", "n", "beta", "sigma_s", "dd", "psi", "n_summits")})
        return d


@dataclass
class FilterStudy:
    """Statistics after each filter step; ``chosen`` indexes the first step with psi <= target."""

    target: float
    steps: list[FilterStep] = field(default_factory=list)
    chosen: int = -1
    reached: bool = False
    maps: list[HeightMap] = field(default_factory=list, repr=False)

    @property
    def result(self) -> FilterStep:
        return self.steps[self.chosen]

    def to_dict(self) -> dict[str, Any]:
        return {"target_psi": self.target, "reached": self.reached, "chosen": self.chosen,
                "steps": [s.to_dict() for s in self.steps]}


def default_cutoffs(hmap: HeightMap, factor: float = math.sqrt(2.0), n: int = 16) -> np.ndarray:
    """Cut-offs from ``2 max(dx, dy)`` (50 % at the Nyquist wavelength) growing by ``factor``,
    up to a quarter of the shorter map side."""
    start = 2.0 * max(hmap.dx, hmap.dy)
    stop = 0.25 * min(hmap.nx * hmap.dx, hmap.ny * hmap.dy)
    vals = start * factor ** np.arange(n)
    return vals[vals <= stop] if np.any(vals <= stop) else vals[:1]


def filter_until_psi(
    hmap: HeightMap,
    target: float = 1.0,
    method: str = "lowpass",
    max_passes: int = 64,
    cutoffs: np.ndarray | list[float] | None = None,
    weights: str = "binomial",
    mode: str = "reflect",
    E_reduced: float | None = None,
    hardness: float | None = None,
    keep_maps: bool = False,
) -> FilterStudy:
    """Filter progressively until the plasticity index falls to ``target`` (thesis 5.3).

    ``method="lowpass"``: 0, 1, 2, ... passes of :func:`lowpass_3x3` (up to ``max_passes``);
    ``method="gaussian"``: :func:`gaussian_lowpass` at increasing ``cutoffs`` (default
    :func:`default_cutoffs`), each applied to the unfiltered map. Step 0 of the low-pass is the
    unfiltered map. Statistics are reported after every step; the study stops at the first step
    with ``psi <= target`` (``reached``) or when the settings are exhausted (``chosen`` is then
    the last step, ``reached`` False).
    """
    tgt = require_positive("target psi", target, "-")
    require_choice("filter method", method, ("lowpass", "gaussian"))
    study = FilterStudy(target=tgt)

    def record(m: str, setting: float, hm: HeightMap) -> bool:
        st = surface_statistics(hm, E_reduced, hardness)
        study.steps.append(FilterStep(m, setting, st))
        if keep_maps:
            study.maps.append(hm)
        return math.isfinite(st.psi) and st.psi <= tgt

    if method == "lowpass":
        if isinstance(max_passes, bool) or not isinstance(max_passes, (int, np.integer)) or not 0 <= max_passes <= 10000:
            raise InputError(f"max_passes = {max_passes!r} must be an integer in [0, 10000]")
        hm = hmap
        done = record("lowpass", 0, hm)
        k = 0
        while not done and k < max_passes:
            hm = lowpass_3x3(hm, 1, weights, mode)
            k += 1
            done = record("lowpass", k, hm)
    else:
        lcs = default_cutoffs(hmap) if cutoffs is None else np.asarray(cutoffs, dtype=float)
        if lcs.ndim != 1 or lcs.size == 0:
            raise InputError("cutoffs must be a non-empty list of wavelengths [m]")
        done = False
        for lc in lcs:
            done = record("gaussian", float(lc), gaussian_lowpass(hmap, float(lc), mode))
            if done:
                break
    study.reached = bool(done)
    study.chosen = len(study.steps) - 1
    return study
