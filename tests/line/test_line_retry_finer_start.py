"""A line solve whose FMG diverges below its finest grid is solved again from a coarsest grid
twice as fine (``LineOptions.retry_finer_start``): Roelands (300, 10) on 2049 points diverges on
its 513-point grid after the 257-point coarsest grid's correction."""

from ehl_multigrid.line import solve_line

CASE = dict(M=300.0, L=10.0, points=2049, estimate=False, raise_on_failure=False)


def test_a_coarse_grid_divergence_is_solved_again_from_a_finer_coarsest_grid():
    plain = solve_line(**CASE, retry_finer_start=False)
    assert plain.status_name == "diverged"
    assert plain.history[-1].level < plain.levels - 1  # below the finest grid

    res = solve_line(**CASE)
    assert res.success
    assert res.levels == plain.levels - 1
    assert any("retry_finer_start" in a for a in res.actions)
    # the answer is the one of that hierarchy asked for directly; both attempts are charged
    direct = solve_line(**CASE, levels=plain.levels - 1)
    assert res.scalars["Hc"] == direct.scalars["Hc"]
    assert res.work_units == direct.work_units + plain.work_units


def test_explicit_levels_are_not_changed():
    res = solve_line(**CASE, levels=4)
    assert res.status_name == "diverged"
    assert not any("retry_finer_start" in a for a in res.actions)
