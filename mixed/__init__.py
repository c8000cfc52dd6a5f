"""Mixed lubrication and Stribeck curves (thesis chapters 4-6: Greenwood-Williamson
asperity pressure (4.18), load sharing (4.21)-(4.22), friction (4.30)-(4.39), starvation).

Modules: :mod:`mixed.gw` (Greenwood-Williamson F_j, asperity pressure, plasticity index),
:mod:`mixed.film` (Johnson's film definition and its inverse, planes, equivalent surface),
:mod:`mixed.sharing` (load sharing, gamma1 by bracketing), :mod:`mixed.friction` (isothermal
and thermal friction), :mod:`mixed.stribeck` (curves, regimes, transitions, result),
:mod:`mixed.starvation` (Chevalier, hs_min, varsigma), :mod:`mixed.critical` (critical load),
:mod:`mixed.cli` (``ehl stribeck``). ``mixed.surface`` (rough-surface analysis) is separate.

The main functions are importable from here; submodules load on first use so that
``import mixed`` stays cheap.
"""

from __future__ import annotations

import importlib
from typing import Any

_LAZY = {
    "gw_f": "gw", "gw_f32": "gw", "gw_log_f": "gw", "gw_f_inverse": "gw", "asperity_pressure": "gw",
    "plasticity_index": "gw",
    "johnson_film": "film", "separation_from_film": "film", "equivalent_surface": "film",
    "load_sharing": "sharing", "LoadSharing": "sharing",
    "mixed_friction": "friction", "MixedFriction": "friction",
    "stribeck_curve": "stribeck", "stribeck_cases": "stribeck", "stribeck_result": "stribeck",
    "transition_speed": "stribeck", "StribeckCurve": "stribeck",
    "chevalier_reduction": "starvation", "limiting_inlet_film": "starvation",
    "limiting_inlet_film_for_roughness": "starvation",
    "critical_load": "critical",
}

__all__ = sorted(_LAZY)


def __getattr__(name: str) -> Any:
    mod = _LAZY.get(name)
    if mod is None:
        raise AttributeError(f"module 'mixed' has no attribute {name!r}")
    return getattr(importlib.import_module(f"mixed.{mod}"), name)
