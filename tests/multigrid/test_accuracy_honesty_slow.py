"""Honest error estimates beyond the moderate-load circular case: high-load line, elliptic
point, the algebraic part against a tight solve of the same grid, and the low-load point
contact whose domain error falls only 1.3-1.6x per doubling of the box (it needs the domain
safety factor of 3; 1.5 missed it). References are independent solves on finer grids and
wider boxes (the study: validation/accuracy/REPORT.md)."""

import pytest

from ehl_multigrid.line import solve_line
from ehl_multigrid.point import solve_point

pytestmark = pytest.mark.slow

TIGHT_LINE = {"tol": 1e-8, "tol_load": 1e-9, "estimate": False}
TIGHT_POINT = {"tol": 1e-5, "tol_load": 1e-6, "half": True, "estimate": False}


def richardson2(coarse: float, fine: float) -> float:
    """Second-order Richardson limit of two films on grids refined by 2."""
    return fine + (fine - coarse) / 3.0


def box_limit_change(g1: float, g2: float, g4: float) -> float:
    """Relative change from the default box to an unbounded one, from boxes 1x, 2x, 4x at equal
    mesh: the change after 4x continued geometrically with the measured decay per doubling."""
    d2, d4 = g2 / g1 - 1.0, g4 / g1 - 1.0
    r = d2 / (d4 - d2)
    assert r > 1.0, "the box change must shrink with each doubling for this reference"
    return d4 + (d4 - d2) / (r - 1.0)


def test_line_estimate_covers_the_error_at_high_load():
    # M = 1000: the default box's domain error is 1e-5 (measured), so the reference is the
    # grid limit of tight solves 4 and 8 times finer than the tested 4097 points
    sol = solve_line(1000.0, 10.0, points=4097)
    a = solve_line(1000.0, 10.0, points=16385, **TIGHT_LINE)
    b = solve_line(1000.0, 10.0, points=32769, **TIGHT_LINE)
    assert a.success and b.success
    for k, est in (("Hc_venner", sol.Hc_error), ("Hm_venner", sol.Hm_error)):
        true = abs(sol.scalars[k] / richardson2(a.scalars[k], b.scalars[k]) - 1.0)
        assert true <= est <= 5.0 * true


def test_line_algebraic_estimate_covers_the_distance_to_the_tight_solution():
    for M, L, n in ((100.0, 10.0, 1025), (5.0, 0.0, 513), (1000.0, 20.0, 2049)):
        sol = solve_line(M, L, points=n)
        tight = solve_line(M, L, points=n, **TIGHT_LINE)
        for k in ("Hc", "Hm"):
            true = abs(sol.scalars[f"{k}_venner"] / tight.scalars[f"{k}_venner"] - 1.0)
            assert true <= sol.error.budget["algebraic"][k]


def _elliptic_true_and_stated() -> list[tuple[float, float]]:
    """(true, stated) relative errors of Hc and Hm of elliptic (20, 10, theta 0.25) on 129 points,
    against tight solves on 257 and 513 points and on 1, 2 and 4 times the box."""
    M, L, theta, n = 20.0, 10.0, 0.25, 129
    sol = solve_point(M, L, theta=theta, points=n)
    d, yr = sol.extra["domain"], sol.extra["y_ratio"]
    grid = [solve_point(M, L, theta=theta, points=p, **TIGHT_POINT) for p in (257, 513)]
    box = [solve_point(M, L, theta=theta, points=f * (n - 1) + 1, xmin=f * d[0], xmax=f * d[1],
                       ymax=f * d[2], y_ratio=yr, **TIGHT_POINT) for f in (1, 2, 4)]
    out = []
    for k, est in (("Hc_venner", sol.Hc_error), ("Hm_venner", sol.Hm_error)):
        change = box_limit_change(*(b.scalars[k] for b in box))
        ref = richardson2(grid[0].scalars[k], grid[1].scalars[k]) * (1.0 + change)
        out.append((abs(sol.scalars[k] / ref - 1.0), est))
    return out


def test_elliptic_point_estimate_covers_the_error_against_finer_grids_and_wider_boxes():
    for true, est in _elliptic_true_and_stated():
        assert true <= est


@pytest.mark.xfail(strict=True, reason="with the far-field boundary this film has almost no domain "
                   "error left and the estimate states 7.6 times the true Hm error (0.88 % for "
                   "0.12 %: grid part 0.66 %, domain part 0.22 %)")
def test_elliptic_point_estimate_is_within_five_times_the_true_error():
    for true, est in _elliptic_true_and_stated():
        assert est <= 5.0 * true


def test_low_load_point_estimate_covers_the_domain_error_of_the_default_box():
    M, L, n = 5.0, 0.0, 129
    sol = solve_point(M, L, points=n)
    d = sol.extra["domain"]
    wide = solve_point(M, L, points=8 * (n - 1) + 1, xmin=8 * d[0], xmax=8 * d[1], ymax=8 * d[2],
                       **TIGHT_POINT)
    # a lower bound of the true error: the films grow with every doubling of the box (by 6.1,
    # 4.5, 2.9 % of Hc from 1x to 8x) and still grow beyond the 8x box
    for k, est in (("Hc_venner", sol.Hc_error), ("Hm_venner", sol.Hm_error)):
        assert abs(sol.scalars[k] / wide.scalars[k] - 1.0) <= est
