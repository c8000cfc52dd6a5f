"""Starved and mass-conserving EHL line and point contacts: Elrod-Adams cavitation with a film
content ``theta`` and an inlet oil supply, on the shared multilevel core
(:class:`StarvedLineHierarchy`, :class:`StarvedPointHierarchy`; the supply's units and checks:
:func:`hoil_venner`, :func:`check_hoil`, :func:`check_profile`).

A starved film is solved through the front door :func:`ehl_multigrid.solve` (``physics=
"starved"``, chosen for a scene with a finite ``[supply] hoil``; docs/api.md). The solver
functions behind it are internal -- importable from here for the package itself, its tests and
validation scripts, but not part of the public API (``__all__``):

* :func:`solve_starved_line` -- a :class:`~ehl_multigrid.line.problem.LineProblem` and the
  supplied layer ``Hoil = hoil R/b^2`` (Venner units): the meniscus is found by a root search
  over mass-conserving flooded-inlet solves (meniscus.py); the result carries ``theta``,
  ``meniscus_x``, ``Hc_flooded``, ``mass_balance_error``, the outlet layer and the error
  estimate at fixed supply.
* :func:`solve_starved_scene` -- the same for a line-contact scene and its ``[supply] hoil`` [m].
* :func:`solve_starved_problem` -- one multilevel solve of the hierarchy as given (flooded
  inlet with ``hoil = inf``; with a finite supply the meniscus inside the multilevel iteration,
  the coupled path, robust only at moderate starvation).
* :func:`solve_starved_point` -- the point (circular) contact: a
  :class:`~ehl_multigrid.point.problem.PointProblem` and ``Hoil = hoil Rx/a^2`` (a number or
  a profile across the track); the meniscus is found inside the multilevel iteration
  (point.py); :func:`solve_starved_point_scene` for a point scene and its ``[supply] hoil``
  [m], with the flooded film of the same discretisation and an error estimate.
"""

from .line import StarvedLineHierarchy
from .line import solve_starved_problem as solve_starved_problem
from .meniscus import solve_starved_line as solve_starved_line
from .meniscus import solve_starved_scene as solve_starved_scene
from .point import StarvedPointHierarchy
from .point import solve_starved_point as solve_starved_point
from .point import solve_starved_point_scene as solve_starved_point_scene
from .supply import check_hoil, check_profile, hoil_venner

__all__ = ["StarvedLineHierarchy", "StarvedPointHierarchy", "check_hoil", "check_profile", "hoil_venner"]
