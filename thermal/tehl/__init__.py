"""Thermal elastohydrodynamic lubrication (TEHL): pressure, film and temperature solved
together with the generalised Reynolds equation (Yang & Wen 1990) and the Eyring law of the
thermal layer acting on the flow.

Main entry points: :func:`solve_tehl_line` (line contacts), :func:`tehl_traction_curve`,
:func:`solve_tehl_point` (point contacts).
"""

from .coefficients import film_factors, flux_integrals
from .hierarchy import FactorLevel, FactorLineHierarchy
from .line import (
    TEHLLineResult,
    TEHLOptions,
    estimate_error,
    isothermal_start,
    solve_tehl_line,
    tehl_traction_curve,
)
from .point import TEHLPointResult, solve_tehl_point

__all__ = [
    "film_factors", "flux_integrals", "FactorLevel", "FactorLineHierarchy", "TEHLLineResult",
    "TEHLOptions", "isothermal_start", "solve_tehl_line", "tehl_traction_curve", "TEHLPointResult",
    "solve_tehl_point", "estimate_error",
]
