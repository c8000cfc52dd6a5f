"""Roughness statistics of a height map (thesis 4.4.1-4.4.2; 9-point summits, plasticity
index (2.48)).

Definitions used here (all heights relative to the mean plane of the valid points):

* ``Ra = mean|z|``, ``Rq = sigma = sqrt(mean z^2)``, skewness ``Rsk = mean z^3 / Rq^3``,
  kurtosis ``Rku = mean z^4 / Rq^4`` (3 for a Gaussian surface).
* Summits, 9-point rule (thesis 4.4.1, de Rooij): a point strictly higher than all 8
  neighbours; points on the map edge cannot be tested and are excluded, as are points whose
  3 x 3 neighbourhood has a missing value. ``n = N_summits / (N_tested dx dy)`` [1/m^2], with
  ``N_tested`` the number of points that could be tested (interior, complete neighbourhood).
* Summit curvature: ``kappa = -(z_xx + z_yy)/2`` with 3-point central second differences
  ``z_xx = (z[i,j+1] - 2 z[i,j] + z[i,j-1]) / dx^2`` (same in y). It is exact for a
  paraboloid, and strictly positive at every 9-point summit.
* Summit radius ``beta = 1 / mean(kappa)``. The mean curvature is what the random-process
  theory predicts (Nayak: ``(8/3) sqrt(m4/pi)``), and it is a robust average: ``mean(1/kappa)``
  is dominated by the few nearly flat summits (it is reported too, as ``beta_mean_radius``).
  The thesis does not say which average de Rooij's program used.
* ``sigma_s`` = standard deviation of the summit heights, ``dd`` = mean summit height above the
  mean plane (Figs 4.16-4.17).
* Plasticity index (2.48): ``psi = (E'_GW / H') sqrt(sigma_s / beta)``, ``E'_GW = E'/2`` (2.49).
  Checked against thesis Table 4.3: disc 3 (sigma_s = 0.018 um, beta = 61.2 um, E' = 2.3e11 Pa,
  H' = 5 GPa) gives psi = 0.39, as printed.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np
from numba import njit

from ehl_multigrid.model.errors import InputError, require_positive
from ehl_multigrid.model.solids import STEEL, gw_modulus, reduced_modulus_of

from .heightmap import HeightMap

#: Defaults for the plasticity index: steel on steel (E' = 2.308e11 Pa) and H' = 5 GPa (thesis).
DEFAULT_E_REDUCED = reduced_modulus_of(STEEL, STEEL)
DEFAULT_HARDNESS = STEEL.hardness

SUMMIT_RULE = "9-point: strictly higher than all 8 neighbours; edge points and incomplete neighbourhoods excluded"
CURVATURE_STENCIL = "kappa = -(z_xx + z_yy)/2, 3-point central second differences"
BETA_DEFINITION = "beta = 1/mean(kappa) over the summits"


@dataclass(frozen=True)
class Summits:
    """9-point summits of a map: indices, heights above the mean plane [m], curvatures [1/m]."""

    iy: np.ndarray
    ix: np.ndarray
    height: np.ndarray
    kappa: np.ndarray
    n_tested: int
    dx: float
    dy: float

    @property
    def count(self) -> int:
        return int(self.iy.size)

    @property
    def density(self) -> float:
        """Summit density ``n`` [1/m^2]."""
        return self.count / (self.n_tested * self.dx * self.dy) if self.n_tested else math.nan


def mean_plane_heights(hmap: HeightMap) -> np.ndarray:
    """Heights relative to the mean of the valid points [m] (NaN kept)."""
    return hmap.z - np.nanmean(hmap.z)


@njit(cache=True)
def _summit_scan(z: np.ndarray, has_nan: bool) -> tuple[np.ndarray, np.ndarray, int]:
    """One pass over the interior: 9-point summits (strict) and the number of testable points
    (interior points with a complete, finite 3 x 3 neighbourhood)."""
    ny, nx = z.shape
    # two summits are never neighbours, so at most one per 2 x 2 block
    cap = ((ny - 1) // 2 + 1) * ((nx - 1) // 2 + 1)
    iy = np.empty(cap, dtype=np.int64)
    ix = np.empty(cap, dtype=np.int64)
    count = 0
    tested = 0
    for i in range(1, ny - 1):
        for j in range(1, nx - 1):
            c = z[i, j]
            if has_nan:
                complete = True
                for a in range(-1, 2):
                    for b in range(-1, 2):
                        if not np.isfinite(z[i + a, j + b]):
                            complete = False
                if not complete:
                    continue
            tested += 1
            higher = True
            for a in range(-1, 2):
                for b in range(-1, 2):
                    if (a != 0 or b != 0) and not c > z[i + a, j + b]:
                        higher = False
                        break
                if not higher:
                    break
            if higher:
                iy[count] = i
                ix[count] = j
                count += 1
    return iy[:count], ix[:count], tested


def find_summits(hmap: HeightMap) -> Summits:
    """Summits by the 9-point rule and their curvature (module docstring)."""
    z = mean_plane_heights(hmap)
    iy, ix, tested = _summit_scan(z, bool(np.isnan(z).any()))
    h = z[iy, ix]
    zxx = (z[iy, ix + 1] - 2.0 * h + z[iy, ix - 1]) / hmap.dx**2
    zyy = (z[iy + 1, ix] - 2.0 * h + z[iy - 1, ix]) / hmap.dy**2
    kappa = -0.5 * (zxx + zyy)
    return Summits(iy, ix, h, kappa, int(tested), hmap.dx, hmap.dy)


def plasticity_index(sigma_s: float, beta: float, E_reduced: float = DEFAULT_E_REDUCED,
                     hardness: float = DEFAULT_HARDNESS) -> float:
    """Greenwood-Williamson plasticity index (2.48): ``(E'_GW/H') sqrt(sigma_s/beta)``.

    ``E_reduced`` is Hertz's E' [Pa]; E'_GW = E'/2 (2.49). ``hardness`` H' [Pa].
    """
    if not (math.isfinite(sigma_s) and math.isfinite(beta)) or beta <= 0:
        return math.nan
    return gw_modulus(E_reduced) / require_positive("hardness", hardness, "Pa") * math.sqrt(sigma_s / beta)


@dataclass(frozen=True)
class SurfaceStats:
    """Roughness parameters of one (equivalent) surface. Lengths in metres.

    ``n`` [1/m^2], ``beta`` [m], ``sigma_s`` [m], ``dd`` [m], ``psi`` [-]; the method strings
    and ``processing`` (levelling, missing points, filter) say how they were obtained.
    """

    Ra: float
    Rq: float
    Rsk: float
    Rku: float
    Rt: float
    n: float
    beta: float
    sigma_s: float
    dd: float
    psi: float
    n_summits: int
    kappa_mean: float
    kappa_std: float
    beta_mean_radius: float
    E_reduced: float
    hardness: float
    dx: float
    dy: float
    shape: tuple[int, int]
    n_missing: int
    n_tested: int
    processing: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()
    method: dict[str, str] = field(default_factory=lambda: {
        "summit_rule": SUMMIT_RULE, "curvature": CURVATURE_STENCIL, "beta": BETA_DEFINITION,
        "psi": "(E'/2 / H') sqrt(sigma_s/beta) (2.48-2.49)",
    })

    @property
    def sigma(self) -> float:
        return self.Rq

    @property
    def n_beta_sigma_s(self) -> float:
        """Whitehouse-Archard product ``n beta sigma_s`` (thesis 4.3.2 keeps it at 0.05)."""
        return self.n * self.beta * self.sigma_s

    UNITS = {
        "Ra": "m", "Rq": "m", "Rsk": "-", "Rku": "-", "Rt": "m", "n": "1/m^2", "beta": "m",
        "sigma_s": "m", "dd": "m", "psi": "-", "n_summits": "-", "kappa_mean": "1/m",
        "kappa_std": "1/m", "beta_mean_radius": "m", "E_reduced": "Pa", "hardness": "Pa",
        "dx": "m", "dy": "m", "n_beta_sigma_s": "-", "dd_over_sigma": "-", "sigma_s_over_sigma": "-",
    }

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["shape"] = list(self.shape)
        d["processing"] = list(self.processing)
        d["notes"] = list(self.notes)
        d["n_beta_sigma_s"] = self.n_beta_sigma_s
        d["dd_over_sigma"] = self.dd / self.Rq if self.Rq > 0 else math.nan
        d["sigma_s_over_sigma"] = self.sigma_s / self.Rq if self.Rq > 0 else math.nan
        return d

    def roughness_block(self, fc: float | None = None) -> dict[str, float]:
        """The scene ``[roughness]`` table (ehl_multigrid.model.scene): Rq, Ra, sigma_s, dd, n, beta, hardness."""
        out: dict[str, float] = {}
        for k in ("Rq", "Ra", "sigma_s", "dd", "n", "beta"):
            v = float(getattr(self, k))
            if not math.isfinite(v):
                raise InputError(f"roughness.{k} is not available ({v}); the map gave {self.n_summits} summits")
            out[k] = v
        out["hardness"] = float(self.hardness)
        if fc is not None:
            out["fc"] = float(fc)
        return out


def amplitude_statistics(hmap: HeightMap) -> dict[str, float]:
    """Ra, Rq, Rsk, Rku, Rt of the valid heights about their mean plane [m, -]."""
    z = mean_plane_heights(hmap)
    v = z[np.isfinite(z)] if hmap.n_missing else z.ravel()
    v2 = v * v
    rq = float(np.sqrt(v2.mean()))
    out = {"Ra": float(np.abs(v).mean()), "Rq": rq, "Rt": float(v.max() - v.min())}
    if rq > 0:
        out["Rsk"] = float(np.dot(v2, v) / v.size / rq**3)
        out["Rku"] = float(np.dot(v2, v2) / v.size / rq**4)
    else:
        out["Rsk"] = out["Rku"] = math.nan
    return out


def surface_statistics(
    hmap: HeightMap,
    E_reduced: float | None = None,
    hardness: float | None = None,
    summits: Summits | None = None,
) -> SurfaceStats:
    """All roughness parameters of ``hmap`` as it is (level and filter it first).

    Parameters
    ----------
    hmap : the height map [m].
    E_reduced : E' [Pa] for the plasticity index (default steel on steel, 2.308e11 Pa).
    hardness : H' [Pa] (default 5 GPa, the thesis's value).
    summits : precomputed :func:`find_summits` result (to avoid recomputing).
    """
    E = DEFAULT_E_REDUCED if E_reduced is None else require_positive("E_reduced", E_reduced, "Pa")
    H = DEFAULT_HARDNESS if hardness is None else require_positive("hardness", hardness, "Pa")
    amp = amplitude_statistics(hmap)
    s = find_summits(hmap) if summits is None else summits
    notes: list[str] = []
    if s.count >= 2:
        kmean = float(np.mean(s.kappa))
        beta = 1.0 / kmean
        sigma_s = float(np.std(s.height, ddof=1))
        dd = float(np.mean(s.height))
        kstd = float(np.std(s.kappa, ddof=1))
        beta_r = float(np.mean(1.0 / s.kappa))
    else:
        kmean = beta = sigma_s = kstd = beta_r = math.nan
        dd = float(s.height.mean()) if s.count else math.nan
        notes.append(f"only {s.count} summit(s) found: summit statistics undefined")
    if 0 < s.count < 100:
        notes.append(f"only {s.count} summits: summit statistics carry a sampling error of order 1/sqrt(N)")
    return SurfaceStats(
        Ra=amp["Ra"], Rq=amp["Rq"], Rsk=amp["Rsk"], Rku=amp["Rku"], Rt=amp["Rt"],
        n=s.density, beta=beta, sigma_s=sigma_s, dd=dd, psi=plasticity_index(sigma_s, beta, E, H),
        n_summits=s.count, kappa_mean=kmean, kappa_std=kstd, beta_mean_radius=beta_r,
        E_reduced=E, hardness=H, dx=hmap.dx, dy=hmap.dy, shape=hmap.shape,
        n_missing=hmap.n_missing, n_tested=s.n_tested, processing=hmap.history, notes=tuple(notes),
    )


# -- two surfaces ---------------------------------------------------------------------------
def counter_surface(sigma_s: float, Rq: float | None = None, dd: float | None = None) -> SurfaceStats:
    """Statistics of a counter surface known only by its summit std (and optionally Rq, dd),
    e.g. the thesis's smooth ball with sigma_s = 0.0225 um (Table 4.3 footnote)."""
    ss = require_positive("counter sigma_s", sigma_s, "m")
    rq = ss / 0.7 if Rq is None else require_positive("counter Rq", Rq, "m")
    d = 0.0 if dd is None else float(dd)
    nan = math.nan
    return SurfaceStats(
        Ra=nan, Rq=rq, Rsk=nan, Rku=nan, Rt=nan, n=nan, beta=nan, sigma_s=ss, dd=d, psi=nan,
        n_summits=0, kappa_mean=nan, kappa_std=nan, beta_mean_radius=nan,
        E_reduced=DEFAULT_E_REDUCED, hardness=DEFAULT_HARDNESS, dx=nan, dy=nan, shape=(0, 0),
        n_missing=0, n_tested=0, processing=("counter surface given by sigma_s" + ("" if Rq else ", Rq = sigma_s/0.7"),),
    )


def combine_statistics(s1: SurfaceStats, s2: SurfaceStats, beta_rule: str = "rougher") -> SurfaceStats:
    """Equivalent single rough surface of two rough surfaces (Greenwood & Tripp; thesis 4.4.1
    footnote): ``sigma_s = sqrt(s1^2 + s2^2)``, ``Rq = sqrt(Rq1^2 + Rq2^2)``, ``dd = sqrt(dd1^2 +
    dd2^2)`` (dd scales with sigma, Whitehouse-Archard).

    ``beta_rule="rougher"`` keeps n and beta of the surface with the larger sigma_s (how the thesis
    combined disc 1 with its ball: only sigma_s is combined); ``"harmonic"`` adds the curvatures,
    ``1/beta = 1/beta1 + 1/beta2`` (summit on summit), with n of the rougher surface. E' and H'
    come from ``s1``. When both maps share a grid, :func:`sum_surface` is the exact alternative.
    """
    if beta_rule not in ("rougher", "harmonic"):
        raise InputError(f"beta_rule = {beta_rule!r} is not one of ['rougher', 'harmonic']")
    rough, smooth = (s1, s2) if s1.sigma_s >= s2.sigma_s else (s2, s1)
    if not math.isfinite(rough.n):
        rough, smooth = smooth, rough
    if not (math.isfinite(rough.n) and math.isfinite(rough.beta)):
        raise InputError("combine_statistics: neither surface has summit density and radius (n, beta)")
    beta = rough.beta
    if beta_rule == "harmonic":
        if not math.isfinite(smooth.beta):
            raise InputError("beta_rule='harmonic' needs beta of both surfaces")
        beta = 1.0 / (1.0 / rough.beta + 1.0 / smooth.beta)
    sigma_s = math.hypot(s1.sigma_s, s2.sigma_s)
    nan = math.nan
    return SurfaceStats(
        Ra=nan, Rq=math.hypot(s1.Rq, s2.Rq), Rsk=nan, Rku=nan, Rt=nan, n=rough.n, beta=beta,
        sigma_s=sigma_s, dd=math.hypot(s1.dd, s2.dd),
        psi=plasticity_index(sigma_s, beta, s1.E_reduced, s1.hardness),
        n_summits=rough.n_summits, kappa_mean=1.0 / beta, kappa_std=nan, beta_mean_radius=nan,
        E_reduced=s1.E_reduced, hardness=s1.hardness, dx=rough.dx, dy=rough.dy, shape=rough.shape,
        n_missing=rough.n_missing, n_tested=rough.n_tested,
        processing=(f"combined two surfaces (Greenwood-Tripp, beta_rule={beta_rule})",
                    *[f"surface 1: {p}" for p in s1.processing], *[f"surface 2: {p}" for p in s2.processing]),
    )


def sum_surface(h1: HeightMap, h2: HeightMap) -> HeightMap:
    """The composite surface ``z1 + z2`` of two maps on the same grid (Greenwood-Tripp equivalent
    surface against a smooth plane); analyse it with :func:`surface_statistics`."""
    if h1.shape != h2.shape or not (np.isclose(h1.dx, h2.dx) and np.isclose(h1.dy, h2.dy)):
        raise InputError(
            f"sum_surface needs maps on the same grid: shapes {h1.shape} vs {h2.shape}, "
            f"dx {h1.dx:.4g} vs {h2.dx:.4g} m, dy {h1.dy:.4g} vs {h2.dy:.4g} m"
        )
    return HeightMap(h1.z + h2.z, h1.dx, h1.dy, source=f"{h1.source} + {h2.source}",
                     history=("sum of two surfaces",))


# -- histograms (Figs 4.16-4.17) --------------------------------------------------------------
def height_histograms(hmap: HeightMap, stats: SurfaceStats, summits: Summits | None = None,
                      bins: int = 60) -> dict[str, np.ndarray]:
    """Surface-height and summit-height densities [1/m] with their Gaussian equivalents
    (surface: N(0, sigma); summits: N(dd, sigma_s)), as thesis Figs 4.16-4.17.

    Surface densities are on ``bins`` bins ("height" centres [m]); summit densities on their own
    coarser bins ("summit_height" centres, about sqrt(N_summits) of them, at most ``bins``).
    """
    z = mean_plane_heights(hmap)
    v = z[np.isfinite(z)]
    s = find_summits(hmap) if summits is None else summits
    edges = np.linspace(float(v.min()), float(v.max()), bins + 1)
    centres = 0.5 * (edges[1:] + edges[:-1])
    surf, _ = np.histogram(v, edges, density=True)
    if s.count >= 2:
        nb = int(min(bins, max(5, math.sqrt(s.count))))
        sedges = np.linspace(float(s.height.min()), float(s.height.max()), nb + 1)
        summ, _ = np.histogram(s.height, sedges, density=True)
    else:
        sedges = edges[[0, -1]]
        summ = np.zeros(1)
    scentres = 0.5 * (sedges[1:] + sedges[:-1])

    def gauss(x: np.ndarray, mu: float, sd: float) -> np.ndarray:
        if not (math.isfinite(sd) and sd > 0):
            return np.full_like(x, np.nan)
        return np.exp(-0.5 * ((x - mu) / sd) ** 2) / (sd * math.sqrt(2 * math.pi))

    return {
        "height": centres,
        "surface_density": surf,
        "surface_gaussian": gauss(centres, 0.0, stats.Rq),
        "summit_height": scentres,
        "summit_density": summ,
        "summit_gaussian": gauss(centres, stats.dd, stats.sigma_s),
    }
