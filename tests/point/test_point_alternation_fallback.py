
"""A wider contact whose X-line relaxation fails is relaxed along X and Y lines instead: the
policy's ``"alternate"`` step within a solve and, when the solve still fails, one solve
again with alternation on every grid (``point.solve.RETRY_ALTERNATING``)."""

import pytest

from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.multigrid.policy import RobustnessPolicy
from ehl_multigrid.point import solve_point
from ehl_multigrid.point.fas import POINT_POLICY, PointHierarchy
from ehl_multigrid.point.problem import problem_from_moes

pytestmark = pytest.mark.solver


def _barus(M, L, points=129, **kw):
    return solve_point(M, L, viscosity="barus", density="incompressible", points=points,
                       estimate=False, raise_on_failure=False, **kw)


def test_a_barus_contact_at_L_20_converges_only_with_alternating_relaxation():
    # the fit-check map's Barus L = 20 row failed at every M with X lines alone (P = 0 on the
    # boundary, as measured; the far field lets X lines converge here)
    assert not _barus(5.0, 20.0, alternating=False, far_field=False).success
    sol = _barus(5.0, 20.0, far_field=False)
    assert sol.success, sol.message
    assert any("alternate" in a for a in sol.actions)
    # the same answer as alternating from the start (to the iteration's tolerance)
    ref = _barus(5.0, 20.0, alternating=True, far_field=False)
    assert ref.success
    assert abs(sol.Hc / ref.Hc - 1.0) < 1e-3 and abs(sol.Hm / ref.Hm - 1.0) < 2e-3


@pytest.mark.slow  # the retry decision: test_point_retry_chain.py (no solves)
def test_a_solve_that_fails_with_x_lines_is_solved_again_and_charged_for_both_attempts():
    # (5, 20) at 257^2 with W cycles: the mid-solve switch does not save it, the second solve
    # (alternating, W cycles) does. (The default F cycles converge it with X lines.)
    # far_field off: the scenario of the retry, on the P = 0 boundary it was measured with
    sol = _barus(5.0, 20.0, points=257, cycle="W", far_field=False)
    ref = _barus(5.0, 20.0, points=257, alternating=True, cycle="W", far_field=False)
    assert sol.success and ref.success
    assert any("solved again" in a for a in sol.actions)
    assert sol.Hc == ref.Hc and sol.Hm == ref.Hm
    assert sol.work_units > ref.work_units


def test_the_alternate_step_switches_every_grid_once_and_respects_the_options():
    hz = PointHierarchy(problem_from_moes(20.0, 10.0), PointOptions(points=129))
    assert not any(lev.alternate for lev in hz.levels)
    msg = RobustnessPolicy(POINT_POLICY).on_reject(None, hz)  # the ladder's first step
    assert "alternate" in msg
    assert all(lev.alternate for lev in hz.levels) and hz.sweep_cost(len(hz.levels) - 1) == 2.0
    assert hz.alternate_all(None) == ""
    off = PointHierarchy(problem_from_moes(20.0, 10.0), PointOptions(points=129, alternating=False))
    assert off.alternate_all(None) == "" and not any(lev.alternate for lev in off.levels)
