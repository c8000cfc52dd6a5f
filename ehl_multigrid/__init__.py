"""ehl_multigrid: lubricant and solid properties, Hertz, dimensionless groups, film-thickness
fits, scenes, results, and the multigrid EHL solvers for line and point contacts.

The package follows Q. Liu's thesis (Twente, 2002) and the dimensionless EHL formulation of
Venner and Moes; see MODEL.md for the equations cited in docstrings.
"""

from .errors import ConvergenceError, InputError
from .fits import moes_line_central, nijenbanning_central
from .hertz import HertzContact, hertz_circular, hertz_elliptic, hertz_line, hertz_point
from .lubricant import Lubricant, lubricant_preset
from .results import Result
from .scene import Scene, builtin_scene_names, load_scene
from .solids import Solid, gw_modulus, reduced_modulus

__all__ = [
    "ConvergenceError", "InputError", "moes_line_central", "nijenbanning_central",
    "HertzContact", "hertz_circular", "hertz_elliptic", "hertz_line", "hertz_point",
    "Lubricant", "lubricant_preset", "Result", "Scene", "builtin_scene_names", "load_scene",
    "Solid", "gw_modulus", "reduced_modulus",
]
