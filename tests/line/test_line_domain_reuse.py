"""A box change measured far below the target is not measured again on finer grids of the
same box (``multigrid.accuracy.DOMAIN_REUSE_BELOW``)."""

from ehl_multigrid.line import solve_line
from ehl_multigrid.line.solver import line_domain_change
from ehl_multigrid.multigrid.accuracy import DOMAIN_REUSE_BELOW, DOMAIN_SAFETY


def test_a_negligible_box_change_is_reused_and_agrees_with_the_finer_grids_own_probes():
    # line (100, 10) at 0.5 %: 4097 points, then 8193 on the same box; the box change (about
    # 1.3e-4) is measured once
    res = solve_line(100.0, 10.0, accuracy=0.005)
    assert res.success
    assert len(res.X) == 8193
    assert "4097-point" in res.extra["domain_note"]
    dom = res.error.budget["domain"]
    assert max(dom.values()) < DOMAIN_REUSE_BELOW * 0.005  # the domain part: 3x the change
    # the 8193-point solve's own probes: the reused change within a factor 1.5 of theirs,
    # so the stated domain part (3x the change) still bounds what they would measure
    own = line_domain_change(res.problem, res.options, res)
    for k, d in zip(("Hc", "Hm"), own, strict=True):
        assert abs(d) <= dom[k]
        assert abs(dom[k] / DOMAIN_SAFETY) <= 1.5 * abs(d) + 1e-7
