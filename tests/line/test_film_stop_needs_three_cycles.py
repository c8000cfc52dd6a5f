"""The film rule of accuracy-driven line solves stops only after three finest-grid cycles, so
the iteration error is estimated from a measured contraction (``LineHierarchy.film_stop_films``;
Barus (1000, 10) at 32769 points stopped after two cycles 4.5x its stated algebraic error from
its discrete solution)."""

from ehl_multigrid.line.solver import LineHierarchy, solve_line


def _finest_cycles(sol):
    top = sol.levels - 1
    return [h for h in sol.history if h.level == top and h.cycle >= 0]


def test_film_stop_waits_for_three_finest_grid_cycles(monkeypatch):
    kw = dict(points=1025, film_tol=5e-3, tol=1e-12, tol_load=1e-12, estimate=False)
    sol = solve_line(20.0, 10.0, **kw)
    assert sol.success and sol.residual_history[-1] > 1e-12  # stopped by the film rule
    monkeypatch.setattr(LineHierarchy, "film_stop_films", 2)
    two = solve_line(20.0, 10.0, **kw)
    # (each followed by the confirming W cycle of an early stop)
    assert two.success and len(_finest_cycles(two)) == 3
    assert len(_finest_cycles(sol)) == 4
