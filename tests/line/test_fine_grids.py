"""Fine-grid line solves that stalled in a limit cycle (validation/line_fine/REPORT.md)."""

from ehl_multigrid.line import solve_line


def test_isoviscous_m100_converges_at_4097_points_and_continues_the_second_order_sequence():
    # before: "stalled" at 4097 points (Hc oscillating by +-5 % from cycle to cycle, residual
    # ~1e-3): Jacobi-distributive changes next to the outlet's cavitation point and cycles
    # through the 129-point grid, which cannot hold a positive film at M = 100
    # grid_stop=None: converged on the residual itself, not on the films' grid rule
    films = {n: solve_line(100.0, 0.0, points=n, estimate=False, raise_on_failure=False, grid_stop=None)
             for n in (1025, 2049, 4097)}
    fine = films[4097]
    assert fine.status_name == "converged", fine.message
    assert fine.residual_history[-1] < 1e-5 and abs(fine.load_error) < 1e-6
    assert all(s.success for s in films.values())
    # second order: the change 2049 -> 4097 is about a quarter of 1025 -> 2049
    d1 = films[2049].Hc - films[1025].Hc
    d2 = fine.Hc - films[2049].Hc
    assert d1 * d2 > 0.0
    assert 3.0 < d1 / d2 < 5.5
