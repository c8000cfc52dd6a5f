"""The point solver's cycle type: F cycles for steady solves that start with X lines, W cycles
where every grid alternates from the start, the options' own when given, and the policy's
``"W"`` step turning F cycles into W cycles."""

from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.multigrid.policy import PolicyParameters, RobustnessPolicy, Settings
from ehl_multigrid.point import fas, solve_point
from ehl_multigrid.point.problem import problem_from_moes


def _cycle(theta, **kw):
    return fas.point_solver(problem_from_moes(20.0, 10.0, theta), PointOptions(points=65, **kw)).settings.cycle


def test_circular_contacts_take_f_cycles_and_narrow_or_alternating_ones_w_cycles():
    assert _cycle(1.0) == "F"
    assert _cycle(4.0) == "W"  # b/a < 0.5: every grid alternates from the start
    assert _cycle(1.0, alternating=True) == "W"
    assert _cycle(1.0, cycle="V") == "V" and _cycle(4.0, cycle="F") == "F"


def test_solvers_built_on_the_point_hierarchy_keep_w_cycles_by_default():
    s = fas.point_settings(problem_from_moes(20.0, 10.0), PointOptions(points=65))
    assert s.cycle == "W"


def test_the_policy_w_step_turns_f_cycles_into_w_cycles():
    pol = RobustnessPolicy(PolicyParameters(reject_ladder=(("W",),)))
    s = Settings.start(PointOptions(points=65, cycle="F"), 0.05, 1.0)
    assert "F -> W" in pol.on_reject(s, None) and s.cycle == "W"


def test_f_and_w_cycles_converge_to_the_same_films():
    f = solve_point(20.0, 10.0, points=129, half=True, estimate=False)
    w = solve_point(20.0, 10.0, points=129, half=True, estimate=False, cycle="W")
    assert f.success and w.success and f.extra["final_cycle"] == "F"
    # both within the residual tolerance 1e-4 of the same discrete solution
    assert abs(f.Hc / w.Hc - 1.0) < 1e-4 and abs(f.Hm / w.Hm - 1.0) < 3e-4
