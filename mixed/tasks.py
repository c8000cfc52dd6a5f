"""Sweep tasks of the mixed layer (``ehl.tasks`` entry points)."""

from __future__ import annotations

from typing import Any

import numpy as np


def stribeck_point_task(scene: Any, thermal: bool = False, hoil: float | None = None, *,
                        thermal_options: dict[str, Any] | None = None, film_factor: float = 1.0,
                        **options: Any) -> dict[str, Any]:
    """Mixed-lubrication state at the scene's operating point: friction and its parts, load
    shares, film and separation, regime. ``hoil`` [m] limits the oil supply (chapter 6);
    ``thermal_options`` and ``film_factor`` as in :func:`~mixed.stribeck.stribeck_curve`."""
    from .stribeck import stribeck_curve, stribeck_options

    c = stribeck_curve(scene, np.array([scene.us]), hoil=hoil, thermal=thermal,
                       thermal_options=thermal_options, film_factor=film_factor,
                       options=stribeck_options(scene, **options) if options else None, transitions=False)
    s, f = c.sharing, c.friction
    return {
        "us": float(scene.us),
        "friction_coefficient": float(f.coefficient[0]), "asperity_friction": float(f.asperity[0]),
        "film_friction": float(f.film[0]), "Pa": float(s.Pa[0]), "Ph": float(s.Ph[0]),
        "asperity_fraction": float(s.asperity_fraction[0]),
        "gamma1": float(s.gamma1[0]), "hfr": float(s.hfr[0]), "hs": float(s.hs[0]), "hss": float(s.hss[0]),
        "Lambda": float(s.Lambda[0]), "regime": c.regime_names()[0], "converged": c.converged,
    }
