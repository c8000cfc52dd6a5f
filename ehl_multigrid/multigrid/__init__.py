"""The multilevel core shared by every EHL solve.

* :mod:`.options` -- immutable options (:class:`MultigridOptions`, :class:`LineOptions`,
  :class:`PointOptions`);
* :mod:`.driver` -- :class:`MultilevelSolver`: recursive FAS V/W/F cycles, FMG, the extra
  finest-grid cycles, callback and histories, over a contact's grid hierarchy;
* :mod:`.policy` -- the adaptive robustness policy and the per-solve settings it adapts;
* :mod:`.result` -- :class:`EHLResult`, the one result type of every EHL solve, and the
  :data:`STATUS` table;
* :mod:`.transfer` -- 1-D grid transfers; :mod:`.threads` -- thread use of one solve.

Line and point contacts provide the hierarchies (:mod:`ehl_multigrid.line`,
:mod:`ehl_multigrid.point`); their numba kernels stay specialised per dimension.
"""

from .driver import CycleRecord, Measurement, MultilevelSolver
from .options import LineOptions, MultigridOptions, PointOptions
from .policy import PolicyParameters, RobustnessPolicy, Settings
from .result import STATUS, EHLResult

__all__ = ["CycleRecord", "EHLResult", "LineOptions", "Measurement", "MultigridOptions",
           "MultilevelSolver", "PointOptions", "PolicyParameters", "RobustnessPolicy", "STATUS",
           "Settings"]
