"""ehl_multigrid: lubricant and solid properties, Hertz, dimensionless groups, film-thickness
fits, scenes, results, and the multigrid EHL solvers for line and point contacts.

The package follows Q. Liu's thesis (Twente, 2002) and the dimensionless EHL formulation of
Venner and Moes; docstrings cite the thesis's equation numbers, e.g. (2.6).

Layers: :mod:`ehl_multigrid.model` (the physics foundation), the numerical packages
:mod:`ehl_multigrid.line` and :mod:`ehl_multigrid.point`, and the ``ehl`` application in
:mod:`ehl_multigrid.app`.

The front door of every film solve is :func:`solve` (steady, starved, thermal, transient; a
scene or a :class:`MoesProblem`), which returns a :class:`Solution` (docs/api.md); it loads
the solvers only when called.
"""

from .front import solve
from .model.errors import ConvergenceError, InputError
from .model.fits import moes_line_central, nijenbanning_central
from .model.hertz import HertzContact, hertz_circular, hertz_elliptic, hertz_line, hertz_point
from .model.lubricant import Lubricant, lubricant_preset
from .model.results import Result
from .model.scene import Scene, builtin_scene_names, load_scene
from .model.solids import Solid, gw_modulus, reduced_modulus
from .solution import MoesProblem, Solution, Status

__all__ = [
    "ConvergenceError", "InputError", "moes_line_central", "nijenbanning_central",
    "HertzContact", "hertz_circular", "hertz_elliptic", "hertz_line", "hertz_point",
    "Lubricant", "lubricant_preset", "Result", "Scene", "builtin_scene_names", "load_scene",
    "Solid", "gw_modulus", "reduced_modulus", "MoesProblem", "Solution", "Status", "solve",
]
