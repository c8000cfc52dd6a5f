"""The accuracy loop's repair (the coarser grids solved to convergence when the FMG films look
irregular) leaves out the grids the sequence found without a positive discrete film
(``solve_to_accuracy(no_film=...)``): a line contact at M >= 3000 and low L fails its dense
start there, and a repair solve there only returned ``film_not_positive`` ((5000, 0): 0.6 s on
2049 points)."""

from types import SimpleNamespace

from ehl_multigrid.multigrid.accuracy import _SteadyControl
from ehl_multigrid.multigrid.controller import Resolution


def _result(n: int, hc: float, hm: float, fmg: list[tuple[int, float, float]]) -> SimpleNamespace:
    top = len(fmg)
    hist = [SimpleNamespace(level=top, cycle=c, Hc=hc * (1 + 1e-7 * c), Hm=hm * (1 + 1e-7 * c), Hm_sub=hm)
            for c in range(3)]
    return SimpleNamespace(
        scalars={"Hc_venner": hc, "Hm_venner": hm}, levels=top + 1, contact="line",
        fmg=[{"level": k, "points": p, "Hc": c, "Hm": m} for k, (p, c, m) in enumerate(fmg)],
        history=hist, load_error_history=[1e-9], extra={}, success=True, status_name="converged",
        wall_s=0.01, message="converged", X=list(range(n)), set_status=lambda code, message: None)


def test_the_repair_does_not_solve_a_grid_known_to_hold_no_film():
    # irregular FMG films (non-monotone Hm): the estimate misses 0.5 % and asks for the repair
    res = _result(16385, 1.0, 0.9, [(2049, 0.95, 0.80), (4097, 0.99, 0.91), (8193, 0.998, 0.88)])
    solved = []

    def solve(n, box, tol):
        solved.append(n)
        return _result(n, 1.0, 0.9, [])

    for no_film, expected in ((None, [8193, 4097]), (lambda n, box: n == 4097, [8193])):
        solved.clear()
        control = _SteadyControl(solve, lambda r, box: (1e-6, 1e-6), None, 0.005, True, 131073, 4.0,
                                 1, extrapolate=True, no_film=no_film)
        control.estimate(res, Resolution(16385), lambda step: None)
        assert solved == expected
