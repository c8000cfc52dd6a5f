"""Multilevel EHL solver for steady isothermal circular and elliptic contacts (issue 4).

Main entry points: :func:`solve_point` (FAS/FMG), :func:`solve_newton_amg` (second path,
Newton semi-system with pyamg), :func:`problem_from_moes`, :func:`problem_from_scene`,
:func:`build_result`.
"""

from .fas import FASOutput, SolverOptions, solve_fas
from .postprocess import build_result, film_metrics
from .problem import PointProblem, problem_from_moes, problem_from_scene

solve_point = solve_fas

__all__ = ["FASOutput", "PointProblem", "SolverOptions", "build_result", "film_metrics",
           "problem_from_moes", "problem_from_scene", "solve_fas", "solve_point"]
