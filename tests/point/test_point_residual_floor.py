"""Point solves that cannot reach their tolerance say why: a residual asked below the
relaxation's floor ends ``residual_floor`` with settled films, not ``diverged``
(``POINT_POLICY.quiet_below``); a steep Barus solve that diverges names the cause."""

from ehl_multigrid.point import solve_point


def test_a_tolerance_below_the_floor_ends_at_the_floor_with_settled_films():
    common = dict(points=513, half=True, estimate=False, raise_on_failure=False, threads=1)
    deep = solve_point(20, 10, tol=1e-9, tol_load=1e-6, max_cycles=60, grid_stop=None, **common)
    # before: a cycle at 4.9e-9 after 1.5e-9 was rejected as growth, the stall steps stirred
    # the iterate and the solve ended "diverged"
    assert deep.status_name == "residual_floor", deep.message
    assert "not a divergence" in deep.message
    assert deep.residual_history[-1] < 1e-5
    assert not any("rejected" in a for a in deep.actions)
    ref = solve_point(20, 10, tol=1e-7, tol_load=1e-6, grid_stop=None, **common)
    assert ref.success
    for h in ("Hc", "Hm"):
        assert abs(deep.scalars[h] / ref.scalars[h] - 1.0) < 1e-6


def test_a_diverged_steep_barus_solve_says_why_and_names_roelands():
    # circular-ish theta 4, alpha_bar 33: the refinement of the fit-check map that diverges
    sol = solve_point(20, 20, theta=4, viscosity="barus", density="incompressible", points=1025,
                      estimate=False, raise_on_failure=False)
    assert sol.status_name == "diverged"
    assert "alpha_bar = 33" in sol.message and "Roelands" in sol.message
