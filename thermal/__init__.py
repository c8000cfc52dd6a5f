"""Thermal non-linear Roelands-Eyring friction in EHL line and point contacts (thesis chapter 3,
MODEL.md section 9).

Main entry points: :func:`solve_traction` (one slip), :func:`traction_curve` (friction against
slip), :func:`film_friction` (uniform film under Hertz pressure; the contract used by the mixed
lubrication layer) and :func:`solve_line` (one line profile).
"""

from .film import FilmFriction, film_friction
from .line import LineSolution, Surroundings, solve_line
from .options import ThermalOptions
from .profiles import (
    LineProfile,
    hertz_profile,
    hertz_slices,
    profile_from_arrays,
    profiles_from_result,
)
from .traction import TractionPoint, solve_traction, traction_curve, traction_result

__all__ = [
    "FilmFriction", "film_friction", "LineSolution", "Surroundings", "solve_line", "ThermalOptions",
    "LineProfile", "hertz_profile", "hertz_slices", "profile_from_arrays", "profiles_from_result",
    "TractionPoint", "solve_traction", "traction_curve", "traction_result",
]
