"""Starved and mass-conserving EHL: Elrod-Adams cavitation with a film content ``theta`` and
an inlet oil supply, on the shared multilevel core.

Public API::

    from ehl_multigrid.line import LineProblem
    from ehl_multigrid.starved import solve_starved_line
    sol = solve_starved_line(LineProblem.from_moes(20, 10), hoil=0.05, points=513)
    sol.Hc, sol.Hc_flooded, sol.meniscus_x, sol.mass_balance_error, sol.extra["theta"]
"""

from .line import StarvedLineHierarchy, solve_starved_problem
from .meniscus import solve_starved_line, solve_starved_scene
from .supply import check_hoil, check_profile, hoil_venner

__all__ = ["StarvedLineHierarchy", "solve_starved_line", "solve_starved_scene", "solve_starved_problem", "check_hoil",
           "check_profile", "hoil_venner"]
