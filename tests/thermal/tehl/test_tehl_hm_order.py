"""A thermal line answer's minimum film is estimated and refined at order 1.5 along X
(thermal.tehl.accuracy.HM_ORDER_X): its sequences are irregular under sliding (the spur gear at
S = 1: Hm ratios 6.1, 2.4, 3.5 on 257-2049 points; at second order its 513-point answer stated
1.66 % for a true 1.87 %)."""

import pytest

from thermal.tehl.accuracy import HM_ORDER_X, TEHLErrorEstimate, step_candidates


def _estimate(grid_hc: float, grid_hm: float) -> TEHLErrorEstimate:
    budget = {k: {"grid_x": g, "grid_z": 1e-5, "domain": 1e-5, "iteration": 1e-6}
              for k, g in (("Hc", grid_hc), ("Hm", grid_hm))}
    for b in budget.values():
        b["total"] = sum(b.values())
    return TEHLErrorEstimate(budget, (2.0, 2.0), None, 0.0)


def test_one_grid_finer_is_predicted_to_lower_hm_by_two_to_the_order_one_and_a_half():
    est = _estimate(1e-3, 8e-3)
    finer = next(c for c in step_candidates(est, 1025, 20, 1.0, 1.0, 16385) if c.what == "points")
    assert finer.predicted == pytest.approx(8e-3 * 2.0**-HM_ORDER_X + 2e-5 + 1e-6)
    # Hc keeps the second order of ORDERS: its part alone would be predicted at a quarter
    only_hc = _estimate(8e-3, 1e-5)
    finer = next(c for c in step_candidates(only_hc, 1025, 20, 1.0, 1.0, 16385) if c.what == "points")
    assert finer.predicted == pytest.approx(8e-3 / 4.0 + 2e-5 + 1e-6)
