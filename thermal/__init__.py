"""Thermal non-linear Roelands-Eyring friction in EHL line and point contacts (thesis chapter 3:
the Eyring law with Maxwell term (3.3), the energy equation (3.5) and the moving-heat-source
surface temperatures (3.6)-(3.7)).

Main entry points: :func:`solve_traction` (one slip), :func:`traction_curve` (friction against
slip), :func:`film_friction` (uniform film under Hertz pressure; the contract used by the mixed
lubrication layer), :func:`film_frictions` (many such points at once) and
:func:`solve_thermal_line` (one line profile; :func:`solve_thermal_lines` for a batch of them on
a thread pool).
"""

from ehl_multigrid.lazy import lazy_exports

#: public name -> submodule; loaded on first use so that the command line (which registers the
#: thermal subcommands at every start of ``ehl``) does not import the kernels
_LAZY = {
    "FilmFriction": "film", "film_friction": "film", "film_frictions": "film",
    "Surroundings": "line", "ThermalLineSolution": "line", "solve_thermal_line": "line",
    "ThermalOptions": "options", "LineJob": "parallel", "solve_thermal_lines": "parallel",
    "LineProfile": "profiles", "hertz_profile": "profiles", "hertz_slices": "profiles",
    "profile_from_arrays": "profiles", "profiles_from_result": "profiles",
    "TractionPoint": "traction", "solve_traction": "traction", "traction_curve": "traction",
    "traction_result": "traction",
}

__all__ = list(_LAZY)


__getattr__, __dir__ = lazy_exports(__name__, _LAZY, globals())
