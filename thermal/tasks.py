"""Sweep tasks of the thermal layer (``ehl.tasks`` entry points)."""

from __future__ import annotations

from typing import Any


def traction_task(scene: Any, **options: Any) -> dict[str, Any]:
    """Friction at the scene's operating point (slip, us, load); options as ThermalOptions
    (``thermal=False`` for the isothermal model, ``nx``, ``nz``, ``slices`` ...)."""
    from .traction import solve_traction

    p = solve_traction(scene, **options)
    return {
        "friction_coefficient": p.coefficient, "friction_force": p.force,
        "mean_shear_stress": p.mean_shear_stress, "max_temperature_rise": p.max_temperature_rise,
        "mean_temperature_rise": p.mean_temperature_rise, "h": p.h, "converged": p.converged,
        "iterations": p.report.iterations, "solver_wall_s": p.report.wall_s,
    }
