"""The GS/JD switch on the finest point meshes (point.fas.sweep_switch): raised only where the
mesh is as fine as 2049 points on the classic X box [-4.5, 1.5] or finer, where the
Jacobi-distributive zone has shrunk (measured at 4097^2: the default (20, 10) converges in FMG
alone instead of stalling for eight cycles)."""

import pytest

from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.point import fas
from ehl_multigrid.point.problem import problem_from_moes


def test_switch_is_raised_only_on_meshes_as_fine_as_2049_points_on_the_classic_box():
    assert fas.sweep_switch(1.0, 6.0 / 1024) == 1.0
    assert fas.sweep_switch(1.0, 6.0 / 2048) == fas.FINE_SWITCH_FACTOR
    assert fas.sweep_switch(10.0, 6.0 / 8192) == fas.FINE_SWITCH_FACTOR * 10.0
    # the coarse grids of a fine solve keep theirs: raised there, the switch stalled the load
    # balance of (20, 10, theta 0.25) at 4097^2
    assert fas.sweep_switch(1.0, 6.0 / 16) == 1.0


@pytest.mark.solver
def test_default_box_grids_get_it_from_2049_points_and_a_widened_box_does_not():
    pb = problem_from_moes(20.0, 10.0)
    # without the far-field boundary values, which take most of a 2049-point hierarchy's set-up
    # (0.4-0.9 s of it) and leave its grids as they are (the same hx on every level)
    fine = fas.PointHierarchy(pb, PointOptions(points=2049, half=True, far_field=False))
    raised = [fas.sweep_switch(1.0, lev.hx) > 1.0 for lev in fine.levels]
    assert raised[-1] and not any(raised[:-1])
    wide = fas.PointHierarchy(pb, PointOptions(points=2049, half=True, xmin=-18.0, xmax=6.0, ymax=12.0,
                                               far_field=False))
    assert not any(fas.sweep_switch(1.0, lev.hx) > 1.0 for lev in wide.levels)
