"""Multilevel EHL solver for steady isothermal circular and elliptic contacts (issue 4).

Public API (same shape as :func:`ehl_multigrid.line.solve_line`)::

    from ehl_multigrid.point import solve_point
    sol = solve_point(20, 10, points=257)          # Moes groups, circular, FAS/FMG
    sol = solve_point(20, 10, theta=0.25)          # elliptic, theta = Rx/Ry
    sol = solve_point(scene=load_scene("appendix_d_point"), solver="newton")
    sol.Hc, sol.Hm, sol.converged, sol.report      # Moes-scaled films, convergence
    res = sol.to_result()                          # core Result, kind "ehl_point"

Lower level: :func:`solve_fas` (FAS/FMG on a :class:`PointProblem`), :func:`solve_newton_amg`
(second path), :func:`problem_from_moes`, :func:`problem_from_scene`, :func:`build_result`.
"""

from .fas import FASOutput, SolverOptions, solve_fas
from .newton import NewtonOptions, solve_newton_amg
from .postprocess import build_result, film_metrics
from .problem import PointProblem, default_domain, problem_from_moes, problem_from_scene
from .solve import PointSolution, solve_point

__all__ = ["FASOutput", "NewtonOptions", "PointProblem", "PointSolution", "SolverOptions",
           "build_result", "default_domain", "film_metrics", "problem_from_moes",
           "problem_from_scene", "solve_fas", "solve_newton_amg", "solve_point"]
