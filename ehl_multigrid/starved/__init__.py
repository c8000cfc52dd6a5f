"""Starved and mass-conserving EHL line contact: Elrod-Adams cavitation with a film content
``theta`` and an inlet oil supply, on the shared multilevel core.

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

Example::

    from ehl_multigrid.line import LineProblem
    from ehl_multigrid.starved import solve_starved_line
    sol = solve_starved_line(LineProblem.from_moes(20, 10), 0.05, points=513)
    sol.Hc, sol.Hc_flooded, sol.meniscus_x, sol.mass_balance_error, sol.extra["theta"]
"""

from .line import StarvedLineHierarchy, solve_starved_problem
from .meniscus import solve_starved_line, solve_starved_scene
from .point import StarvedPointHierarchy, solve_starved_point, solve_starved_point_scene
from .supply import check_hoil, check_profile, hoil_venner

__all__ = ["StarvedLineHierarchy", "solve_starved_line", "solve_starved_scene", "solve_starved_problem",
           "StarvedPointHierarchy", "solve_starved_point", "solve_starved_point_scene",
           "check_hoil", "check_profile", "hoil_venner"]
