"""The whole chain for one map: missing points -> levelling -> filter -> statistics.

Order matters and is fixed: missing points are filled (or marked excluded) first, the plane or
form is removed from the raw heights (the thesis's Wyko "Terms removed: Tilt"), then the
optional filter, then the statistics about the mean plane of the result.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ehl_multigrid.model.errors import InputError, require_choice, require_positive

from .filters import FilterStudy, filter_until_psi, gaussian_lowpass, lowpass_3x3
from .heightmap import HeightMap, parse_length
from .levelling import handle_missing, level
from .statistics import Summits, SurfaceStats, find_summits, surface_statistics

FILTER_KINDS = ("none", "lowpass", "gaussian", "until-psi")


@dataclass(frozen=True)
class FilterSpec:
    """Which filter to apply.

    kind: ``none``; ``lowpass`` (``passes`` of the 3 x 3 kernel ``weights``); ``gaussian``
    (ISO cut-off ``cutoff`` [m]); ``until-psi`` (filter progressively with ``method`` until
    psi <= ``target``).
    """

    kind: str = "none"
    passes: int = 0
    cutoff: float = math.nan
    weights: str = "binomial"
    method: str = "lowpass"
    target: float = 1.0
    max_passes: int = 64

    def describe(self) -> str:
        if self.kind == "lowpass":
            return f"lowpass {self.weights} x {self.passes}"
        if self.kind == "gaussian":
            return f"gaussian lambda_c = {self.cutoff:.4g} m"
        if self.kind == "until-psi":
            return f"until psi <= {self.target:g} ({self.method})"
        return "none"


_FILTER_RE = re.compile(r"^\s*([a-z-]+)\s*(?::\s*(.+))?$")


def parse_filter(text: str | None, method: str = "lowpass", target: float = 1.0,
                 weights: str = "binomial") -> FilterSpec:
    """``none`` | ``lowpass:K`` | ``gauss:LAMBDA`` (e.g. ``gauss:20um``) | ``until-psi[:TARGET]``."""
    if text is None:
        return FilterSpec()
    m = _FILTER_RE.match(text.lower())
    if not m:
        raise InputError(f"filter = {text!r}; expected none, lowpass:K, gauss:LAMBDA (e.g. gauss:20um) or until-psi[:TARGET]")
    kind, arg = m.group(1), m.group(2)
    kind = {"gauss": "gaussian", "low-pass": "lowpass", "until_psi": "until-psi"}.get(kind, kind)
    require_choice("filter", kind, FILTER_KINDS)
    if kind == "lowpass":
        try:
            k = int(arg) if arg is not None else 1
        except ValueError:
            raise InputError(f"filter = {text!r}: the number of passes must be an integer") from None
        if not 0 <= k <= 10000:
            raise InputError(f"filter passes = {k} must be in [0, 10000]")
        return FilterSpec("lowpass", passes=k, weights=weights)
    if kind == "gaussian":
        if arg is None:
            raise InputError("filter gauss needs a cut-off wavelength, e.g. gauss:20um")
        return FilterSpec("gaussian", cutoff=parse_length(arg, "filter cut-off lambda_c", "m"))
    if kind == "until-psi":
        tgt = require_positive("target psi", float(arg), "-") if arg else target
        require_choice("filter method", method, ("lowpass", "gaussian"))
        return FilterSpec("until-psi", method=method, target=tgt, weights=weights)
    return FilterSpec()


@dataclass
class Analysis:
    """Result of :func:`analyse_surface`."""

    raw: HeightMap
    surface: HeightMap  # levelled (and filtered) map the statistics describe
    summits: Summits
    stats: SurfaceStats
    filter: FilterSpec
    study: FilterStudy | None = None
    unfiltered: SurfaceStats | None = None
    nan_policy: str = "exclude"

    def payload(self) -> dict[str, Any]:
        """JSON-ready dictionary: the main keys first (Ra, Rq, n, beta, sigma_s, dd, psi)."""
        d = self.stats.to_dict()
        main = {k: d.pop(k) for k in ("Ra", "Rq", "n", "beta", "sigma_s", "dd", "psi")}
        out: dict[str, Any] = {**main, **d}
        out["units"] = dict(SurfaceStats.UNITS)
        out["source"] = self.raw.source
        out["nan_policy"] = self.nan_policy
        out["n_missing_raw"] = self.raw.n_missing
        out["filter"] = self.filter.describe()
        if self.unfiltered is not None:
            out["unfiltered"] = {k: getattr(self.unfiltered, k) for k in
                                 ("Ra", "Rq", "n", "beta", "sigma_s", "dd", "psi", "n_summits")}
        if self.study is not None:
            out["filter_study"] = self.study.to_dict()
        notes = list(self.raw.meta.get("notes", []))
        if notes:
            out["read_notes"] = notes
        return out


def analyse_surface(
    hmap: HeightMap,
    levelling: str = "plane",
    form_order: int = 2,
    nan: str = "exclude",
    filter: FilterSpec | None = None,
    E_reduced: float | None = None,
    hardness: float | None = None,
) -> Analysis:
    """Missing points, levelling, filter, statistics (module docstring).

    Parameters
    ----------
    hmap : the raw map [m].
    levelling : ``plane`` (default, thesis), ``form`` (polynomial of ``form_order``), ``mean``, ``none``.
    nan : ``exclude`` (default) or ``fill`` (harmonic interpolation); see :mod:`.levelling`.
    filter : :class:`FilterSpec` (default none).
    E_reduced, hardness : E' and H' [Pa] for psi (defaults steel on steel, 5 GPa).
    """
    spec = filter or FilterSpec()
    hm = handle_missing(hmap, nan)
    hm = level(hm, levelling, form_order)
    _require_roughness(hmap, hm, levelling)
    study = None
    unfiltered = None
    if spec.kind != "none":
        unfiltered = surface_statistics(hm, E_reduced, hardness)
    if spec.kind == "lowpass":
        hm = lowpass_3x3(hm, spec.passes, spec.weights)
    elif spec.kind == "gaussian":
        hm = gaussian_lowpass(hm, spec.cutoff)
    elif spec.kind == "until-psi":
        study = filter_until_psi(hm, spec.target, spec.method, max_passes=spec.max_passes,
                                 weights=spec.weights, E_reduced=E_reduced, hardness=hardness, keep_maps=True)
        hm = study.maps[study.chosen]
        study.maps = []
    summits = find_summits(hm)
    stats = surface_statistics(hm, E_reduced, hardness, summits=summits)
    if study is not None and not study.reached:
        stats = _with_note(stats, f"psi did not fall to {spec.target:g} within the filter settings tried")
    return Analysis(hmap, hm, summits, stats, spec, study, unfiltered, nan)


#: Rq below this fraction of the largest raw height is round-off of the levelling, not
#: roughness (double precision keeps about 1e-16 of the heights; 1e-9 leaves a wide margin and
#: stays far below any measured surface: Rq 1 nm under 10 um of tilt is 1e-4).
FLAT_FRACTION = 1e-9


def _require_roughness(raw: HeightMap, levelled: HeightMap, levelling: str) -> None:
    """Refuse a map that is flat after levelling: its Rq is round-off and it has no summits,
    so every Greenwood-Williamson parameter would be meaningless."""
    z = levelled.z[np.isfinite(levelled.z)]
    rq = float(np.sqrt(np.mean((z - z.mean()) ** 2))) if z.size else 0.0
    top = float(np.nanmax(np.abs(raw.z))) if np.isfinite(raw.z).any() else 0.0
    if not rq > FLAT_FRACTION * top or rq == 0.0:
        raise InputError(
            f"height map {raw.source or ''} is flat after {levelling} levelling (Rq = {rq:.3g} m against heights "
            f"up to {top:.3g} m): it holds no roughness to analyse".replace("map  is", "map is")
        )


def _with_note(stats: SurfaceStats, note: str) -> SurfaceStats:
    return replace(stats, notes=stats.notes + (note,))
