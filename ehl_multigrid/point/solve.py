"""One entry point for point and elliptic contacts, shaped like :func:`~ehl_multigrid.line.solve_line`.

>>> sol = solve_point(20, 10, points=129)                     # doctest: +SKIP
>>> round(sol.Hc, 2), sol.converged                           # doctest: +SKIP
>>> res = sol.to_result()                                     # kind "ehl_point"
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from ..model.convergence import ConvergenceReport
from ..model.errors import InputError, require_choice
from ..model.results import Result, ScalarAccess
from .postprocess import build_result, summary_payload
from .problem import PointProblem, problem_from_moes, problem_from_scene

SOLVERS = ("fas", "newton")


@dataclass
class PointSolution(ScalarAccess):
    """Answer of :func:`solve_point`: the raw solver output, its problem and the scalars of the
    ``ehl_point`` result (``Hc``, ``Hm``, ``hc``, ``p_spike``, ``load_error``, ...) as attributes."""

    problem: PointProblem
    output: Any  # FASOutput or NewtonOutput
    solver: str
    scene: Any = None
    scalars: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self._result = build_result(self.output, self.scene)
        self.scalars = dict(self._result.scalars)

    @property
    def report(self) -> ConvergenceReport:
        return self.output.report

    @property
    def X(self):
        return self.output.X

    @property
    def Y(self):
        return self.output.Y

    @property
    def P(self):
        return self.output.P

    @property
    def H(self):
        return self.output.H

    def to_result(self, scene: Any = None) -> Result:
        """Core :class:`Result` of kind ``"ehl_point"`` (full domain, also for half solves)."""
        if scene is None or scene is self.scene:
            return self._result
        return build_result(self.output, scene)

    def payload(self) -> dict[str, Any]:
        """The JSON payload of ``ehl solve`` (same keys as the line solver first)."""
        out = summary_payload(self._result)
        out["solver"] = self.solver
        return out


def solve_point(
    M: float | None = None, L: float | None = None, *, theta: float = 1.0, scene: Any = None,
    viscosity: str = "roelands", density: str = "dowson-higginson",
    alpha: float | None = None, eta0: float | None = None, p0: float | None = None,
    solver: str = "fas", rigid: bool = False, **options: Any,
) -> PointSolution:
    """Solve the steady isothermal EHL point or elliptic contact (MODEL.md 5).

    Give either Moes ``M, L`` and ``theta = Rx/Ry`` (oil data ``alpha``, ``eta0``, ``p0``
    default to ``MOES_ONLY_DEFAULTS``) or a point/elliptic ``scene``. ``solver`` is ``"fas"``
    (FAS/FMG multigrid, :class:`~ehl_multigrid.point.fas.SolverOptions`) or ``"newton"`` (the
    Newton semi-system path with pyamg, :class:`~ehl_multigrid.point.newton.NewtonOptions`);
    ``rigid=True`` switches the elastic deformation off (FAS only). Remaining keyword
    arguments are options of the chosen solver.
    """
    require_choice("solver", solver, SOLVERS)
    if scene is not None:
        if M is not None or L is not None:
            raise InputError("give either a scene or M and L, not both")
        pb = problem_from_scene(scene, viscosity, density)
    else:
        if M is None or L is None:
            raise InputError("solve_point needs M and L (Moes groups) or a scene")
        pb = problem_from_moes(M, L, theta, viscosity, density, alpha, eta0, p0)
    if solver == "fas":
        from .fas import solve_fas

        out = solve_fas(pb, elastic=not rigid, **options)
    else:
        if rigid:
            raise InputError("rigid = True is available with solver = 'fas' only")
        from .newton import solve_newton_amg

        out = solve_newton_amg(pb, **options)
    return PointSolution(pb, out, solver, scene)
