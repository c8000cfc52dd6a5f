"""Physical constants of the property laws and the oil defaults of Moes-only problems.

One place for every constant that more than one module uses; the property functions
(:mod:`ehl_multigrid.model.lubricant`), the EHL solvers and the thermal kernels import them
from here.
"""

from __future__ import annotations

#: Roelands viscosity law (2.6): viscosity at infinite temperature [Pa s].
ETA_INF = 6.31e-5
#: Roelands reference pressure pr (2.6) [Pa].
P_R = 1.962e8
#: Dowson-Higginson density (2.7, 3.10): ``rho/rho0 = 1 + DH_B p/(DH_A + p)``; DH_A [Pa], DH_B [-].
DH_A = 0.59263e9
DH_B = 0.34615

#: Oil of a problem given only by the Moes groups (M, L): alpha [1/Pa], eta0 [Pa s] and the
#: Roelands reference pressure p0 [Pa], rounded from P_R; stored regression values depend on p0,
#: so unifying it with P_R is a change of numbers of its own (docs/conventions.md)
MOES_ONLY_DEFAULTS = {"p0": 1.96e8, "alpha": 2.2e-8, "eta0": 0.04}

#: Ellipticity ``theta = Rx/Ry`` an elliptic contact may have: the range of the point solver
#: (:class:`ehl_multigrid.point.problem.PointProblem`), so a scene the solver would refuse is
#: refused on load. Slenderer contacts are line contacts of finite length.
THETA_MIN = 0.01
THETA_MAX = 100.0
