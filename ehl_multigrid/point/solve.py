"""One entry point for point and elliptic contacts, shaped like :func:`~ehl_multigrid.line.solve_line`.

>>> sol = solve_point(20, 10, points=129)                     # doctest: +SKIP
>>> round(sol.Hc, 2), sol.success, sol.status_name            # doctest: +SKIP
>>> res = sol.to_result()                                     # kind "ehl_point"
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..model.errors import InputError, require_choice
from ..multigrid.options import PointOptions, build_scene_options, scene_solver_table
from ..multigrid.result import EHLResult
from ..multigrid.threads import preserved_threads
from .fas import point_solver
from .postprocess import build_result
from .problem import PointProblem, min_points, problem_from_moes, problem_from_scene

SOLVERS = ("fas", "newton")

#: The answer of a point-contact solve is the package's one EHL result type.
PointSolution = EHLResult


def _finish(sol: EHLResult, scene: Any) -> EHLResult:
    sol.scene = scene
    sol.builder = build_result
    sol.scalars = dict(build_result(sol, scene).scalars)
    return sol


def solve_fas(problem: PointProblem, options: PointOptions | None = None,
              callback: Callable[[dict[str, Any]], None] | None = None, scene: Any = None,
              **kw: Any) -> EHLResult:
    """FAS/FMG solve of one :class:`PointProblem`; keyword arguments override ``options``."""
    opt = PointOptions.build(options, **kw)
    with preserved_threads():
        solver = point_solver(problem, opt)
        sol = solver.solve(callback=callback)
    hz = solver.hierarchy
    fine = hz.levels[-1]
    sol.contact, sol.solver, sol.problem, sol.options = "point", "fas", problem, opt
    sol.X, sol.Y, sol.P, sol.H = fine.X, fine.Y, fine.P.copy(), fine.H.copy()
    sol.H0, sol.half, sol.levels = hz.H00, opt.half, len(hz.levels)
    sol.extra.update(final_omega=sol.settings.omega, final_omega_jd=sol.settings.omega_jd,
                     final_h00_gain=sol.settings.h00_gain, final_cycle=sol.settings.cycle,
                     final_switch=sol.settings.switch)
    if not sol.success:
        if opt.points < min_points(problem.M, problem.b_over_a):
            sol.message += (f"; at M = {problem.M:.4g} a grid of {opt.points} points is too coarse "
                            f"for this solver: use points >= {min_points(problem.M, problem.b_over_a)}")
        if sol.load_error_history.size and sol.load_error_history[-1] > 1e-2:
            sol.message += ("; the load cannot be balanced: at low M the inlet of this domain is too "
                            "short (extend xmin/ymax), at high M the grid is too coarse (more points)")
    return _finish(sol, scene)


def solve_point(
    M: float | None = None, L: float | None = None, *, theta: float = 1.0, scene: Any = None,
    viscosity: str | None = None, density: str | None = None,
    alpha: float | None = None, eta0: float | None = None, p0: float | None = None,
    solver: str = "fas", rigid: bool = False,
    callback: Callable[[dict[str, Any]], None] | None = None,
    options: PointOptions | None = None, **kw: Any,
) -> EHLResult:
    """Solve the steady isothermal EHL point or elliptic contact (Venner's dimensionless
    Reynolds, film and load equations; Roelands (2.6) and Dowson-Higginson (2.7) by default).

    Give either Moes ``M, L`` and ``theta = Rx/Ry`` (oil data ``alpha``, ``eta0``, ``p0``
    default to :data:`~ehl_multigrid.model.constants.MOES_ONLY_DEFAULTS`) or a point/elliptic
    ``scene``, whose ``[solver.ehl]`` table (viscosity, density and any option) applies below
    the explicit arguments (defaults: Roelands, Dowson-Higginson). ``solver`` is ``"fas"`` (FAS/FMG multigrid,
    :class:`~ehl_multigrid.multigrid.options.PointOptions`) or ``"newton"`` (the Newton
    semi-system path with pyamg, :class:`~ehl_multigrid.point.newton.NewtonOptions`);
    ``rigid=True`` switches the elastic deformation off (FAS only). Remaining keyword
    arguments are options of the chosen solver.

    Returns an :class:`~ehl_multigrid.multigrid.result.EHLResult`.
    """
    require_choice("solver", solver, SOLVERS)
    model, table = scene_solver_table(scene, "point") if scene is not None else ({}, {})
    viscosity = viscosity or model.get("viscosity", "roelands")
    density = density or model.get("density", "dowson-higginson")
    if scene is not None:
        if M is not None or L is not None:
            raise InputError("give either a scene or M and L, not both")
        pb = problem_from_scene(scene, viscosity, density)
    else:
        if M is None or L is None:
            raise InputError("solve_point needs M and L (Moes groups) or a scene")
        pb = problem_from_moes(M, L, theta, viscosity, density, alpha, eta0, p0)
    if solver == "fas":
        if rigid:
            kw["elastic"] = False
        opts = build_scene_options(PointOptions, options, table, kw)
        return solve_fas(pb, opts, callback=callback, scene=scene)
    if rigid:
        raise InputError("rigid = True is available with solver = 'fas' only")
    from .newton import solve_newton_amg

    sol = solve_newton_amg(pb, options, **kw)
    if scene is not None:
        sol = _finish(sol, scene)
    return sol
