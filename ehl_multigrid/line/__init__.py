"""Multilevel (FAS/FMG) solver for the steady isothermal EHL line contact.

Public API::

    from ehl_multigrid.line import solve_line, LineProblem
    sol = solve_line(20, 10, points=1025)            # Moes groups, default oil
    sol.Hc, sol.Hm, sol.success, sol.status_name     # Moes-scaled films, outcome
    res = sol.to_result()                            # package Result, kind "ehl_line"

    from ehl_multigrid.line import make_deformation  # W = sum_j K_|i-j| P_j (mlmi/fft/direct)

The cycles, FMG and robustness policy are the shared ones of :mod:`ehl_multigrid.multigrid`;
this package holds the line discretisation (:class:`LineHierarchy`).
"""

from ..multigrid.options import LineOptions
from .deformation import DirectDeformation, FFTDeformation, MLMIDeformation, make_deformation
from .kernel import log_kernel
from .problem import LineProblem
from .solution import LineSolution
from .solver import LineHierarchy, line_solver, solve_line, solve_line_problem

__all__ = [
    "DirectDeformation", "FFTDeformation", "MLMIDeformation", "make_deformation", "log_kernel",
    "LineHierarchy", "LineOptions", "LineProblem", "LineSolution", "line_solver", "solve_line",
    "solve_line_problem",
]

