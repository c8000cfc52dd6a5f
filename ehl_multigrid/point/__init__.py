"""Multilevel EHL solver for steady isothermal circular and elliptic contacts: the point
discretisation (:class:`PointHierarchy`) on the shared multilevel driver, the Newton/pyamg
cross-check path (:class:`NewtonOptions`), the problem (:class:`PointProblem`,
:func:`problem_from_moes`, :func:`problem_from_scene`) and the post-processing
(:func:`build_result`, :func:`film_metrics`).

A film is solved through the front door :func:`ehl_multigrid.solve` (``options={"solver":
"newton"}`` for the cross-check path; docs/api.md). The solver functions behind it,
:func:`~.solve.solve_point`, :func:`~.solve.solve_fas`, :func:`~.newton.solve_newton_amg` and
:func:`~.fas.point_solver`, are internal: importable from here for the package itself, its
tests and validation scripts, but not part of the public API (``__all__``).
"""

from ..multigrid.options import PointOptions
from .fas import PointHierarchy
from .fas import point_solver as point_solver
from .newton import NewtonOptions
from .newton import solve_newton_amg as solve_newton_amg
from .postprocess import build_result, film_metrics
from .problem import PointProblem, default_domain, problem_from_moes, problem_from_scene
from .solve import PointSolution
from .solve import solve_fas as solve_fas
from .solve import solve_point as solve_point

__all__ = ["NewtonOptions", "PointHierarchy", "PointOptions", "PointProblem", "PointSolution",
           "build_result", "default_domain", "film_metrics", "problem_from_moes", "problem_from_scene"]

