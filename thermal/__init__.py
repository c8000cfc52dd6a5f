"""Thermal non-linear Roelands-Eyring friction in EHL line and point contacts (thesis chapter 3:
the Eyring law with Maxwell term (3.3), the energy equation (3.5) and the moving-heat-source
surface temperatures (3.6)-(3.7)).

Main entry points: :func:`solve_traction` (one slip), :func:`traction_curve` (friction against
slip), :func:`film_friction` (uniform film under Hertz pressure; the contract used by the mixed
lubrication layer), :func:`film_frictions` (many such points at once) and
:func:`solve_thermal_line` (one line profile; :func:`solve_thermal_lines` for a batch of them on
a thread pool).
"""

import warnings

from .film import FilmFriction, film_friction, film_frictions
from .line import _RENAMED, Surroundings, ThermalLineSolution, solve_thermal_line
from .options import ThermalOptions
from .parallel import LineJob, solve_thermal_lines
from .profiles import (
    LineProfile,
    hertz_profile,
    hertz_slices,
    profile_from_arrays,
    profiles_from_result,
)
from .traction import TractionPoint, solve_traction, traction_curve, traction_result

__all__ = [
    "FilmFriction", "film_friction", "film_frictions", "ThermalLineSolution", "Surroundings", "solve_thermal_line",
    "LineJob", "solve_thermal_lines", "ThermalOptions",
    "LineProfile", "hertz_profile", "hertz_slices", "profile_from_arrays", "profiles_from_result",
    "TractionPoint", "solve_traction", "traction_curve", "traction_result",
]


def __getattr__(name: str):
    # thermal.solve_line / thermal.LineSolution of the previous release
    if name in _RENAMED:
        new = _RENAMED[name]
        warnings.warn(f"thermal.{name} is deprecated: use thermal.{new} (the old name will be "
                      "removed in the next release)", DeprecationWarning, stacklevel=2)
        return globals()[new]
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
