"""Rough-surface analysis: from a measured height map to the mixed-lubrication roughness
parameters n, beta, sigma_s, dd, sigma and the plasticity index (thesis 4.4.1-4.4.2, 5.2-5.3;
plasticity index (2.48)).

Typical use::

    from mixed.surface import read_height_map, analyse_surface, parse_filter
    hm = read_height_map("disc.csv", dx="0.781um", units="um")
    a = analyse_surface(hm, filter=parse_filter("until-psi"))
    a.stats.n, a.stats.beta, a.stats.sigma_s, a.stats.psi

This subpackage imports only ``ehl_multigrid`` (never the rest of ``mixed``).
"""

from __future__ import annotations

import importlib
from typing import Any

# Submodules load on first use, so `ehl` (which registers `ehl surface` at start-up) stays fast.
_LAZY = {
    "Analysis": "analysis", "FilterSpec": "analysis", "analyse_surface": "analysis", "parse_filter": "analysis",
    "FilterStudy": "filters", "filter_until_psi": "filters", "gaussian_lowpass": "filters",
    "gaussian_sigma": "filters", "gaussian_transmission": "filters", "lowpass_3x3": "filters",
    "lowpass_transmission": "filters",
    "HeightMap": "heightmap", "make_height_map": "heightmap", "parse_length": "heightmap",
    "unit_factor": "heightmap",
    "fill_harmonic": "levelling", "handle_missing": "levelling", "level": "levelling",
    "remove_form": "levelling", "remove_plane": "levelling",
    "gaussian_acf": "nayak", "nayak_continuous": "nayak", "nine_point_prediction": "nayak",
    "read_height_map": "readers", "read_instrument": "readers", "xyz_to_grid": "readers",
    "Summits": "statistics", "SurfaceStats": "statistics", "combine_statistics": "statistics",
    "counter_surface": "statistics", "find_summits": "statistics", "height_histograms": "statistics",
    "plasticity_index": "statistics", "sum_surface": "statistics", "surface_statistics": "statistics",
    "PlantedTruth": "synthetic", "gaussian_acf_moments": "synthetic",
    "gaussian_random_surface": "synthetic", "planted_asperities": "synthetic",
    "spectral_moments": "synthetic",
}

__all__ = sorted(_LAZY)


def __getattr__(name: str) -> Any:
    mod = _LAZY.get(name)
    if mod is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f".{mod}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
