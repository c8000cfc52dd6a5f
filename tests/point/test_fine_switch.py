"""The GS/JD switch on the finest point grids (point.fas.sweep_switch): raised only on grids of
2049 points and more, where the Jacobi-distributive zone has shrunk (measured at 4097^2: the
default (20, 10) converges in FMG alone instead of stalling for eight cycles)."""

from ehl_multigrid.point import fas


def test_switch_is_raised_only_on_grids_of_2049_points_and_more():
    assert fas.sweep_switch(1.0, 1025) == 1.0
    assert fas.sweep_switch(1.0, 2049) == fas.FINE_SWITCH_FACTOR * 1.0
    assert fas.sweep_switch(1.0, 4097) == fas.FINE_SWITCH_FACTOR * 1.0
    assert fas.sweep_switch(10.0, 8193) == fas.FINE_SWITCH_FACTOR * 10.0
    # the coarse grids of a fine solve keep theirs: raised there, the switch stalled the
    # load balance of (20, 10, theta 0.25)
    assert fas.sweep_switch(1.0, 17) == 1.0
