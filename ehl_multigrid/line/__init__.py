"""Multilevel (FAS/FMG) solver for the steady isothermal EHL line contact: the line
discretisation (:class:`LineHierarchy`) on the shared cycles, FMG and robustness policy of
:mod:`ehl_multigrid.multigrid`, and the deformation (``W = sum_j K_|i-j| P_j``,
:func:`make_deformation`: mlmi, fft, direct).

A film is solved through the front door :func:`ehl_multigrid.solve` (docs/api.md). The solver
functions behind it, :func:`~.solver.solve_line`, :func:`~.solver.solve_line_problem` and
:func:`~.solver.line_solver`, are internal: importable from here for the package itself, its
tests and validation scripts, but not part of the public API (``__all__``).
"""

from ..multigrid.options import LineOptions
from .deformation import DirectDeformation, FFTDeformation, MLMIDeformation, make_deformation
from .kernel import log_kernel
from .problem import LineProblem
from .solution import LineSolution
from .solver import LineHierarchy
from .solver import line_solver as line_solver
from .solver import solve_line as solve_line
from .solver import solve_line_problem as solve_line_problem

__all__ = [
    "DirectDeformation", "FFTDeformation", "MLMIDeformation", "make_deformation", "log_kernel",
    "LineHierarchy", "LineOptions", "LineProblem", "LineSolution",
]

