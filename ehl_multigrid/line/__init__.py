"""Multilevel (FAS/FMG) solver for the steady isothermal EHL line contact (MODEL.md 5).

Public API::

    from ehl_multigrid.line import solve_line, LineProblem, MultilevelLineSolver
    sol = solve_line(20, 10, points=1025)            # Moes groups, default oil
    sol.Hc, sol.Hm, sol.converged                    # Moes-scaled films
    res = sol.to_result()                            # core Result, kind "ehl_line"

    from ehl_multigrid.line import make_deformation  # W = sum_j K_|i-j| P_j (mlmi/fft/direct)
"""

from .deformation import DirectDeformation, FFTDeformation, MLMIDeformation, make_deformation
from .kernel import log_kernel
from .problem import LineProblem
from .solution import LineSolution
from .solver import LineSolverOptions, MultilevelLineSolver, solve_line

__all__ = [
    "DirectDeformation", "FFTDeformation", "MLMIDeformation", "make_deformation", "log_kernel",
    "LineProblem", "LineSolution", "LineSolverOptions", "MultilevelLineSolver", "solve_line",
]
