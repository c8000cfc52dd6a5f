"""The box (domain) probes of an accuracy-driven point solve: a refinement sequence never
solves the same probe twice (the wide solve of one box is the narrow solve of the next)."""

import pytest

import ehl_multigrid.point.solve as point_solve
from ehl_multigrid.point.solve import solve_point


@pytest.mark.solver
def test_a_refinement_sequence_solves_each_probe_once(monkeypatch):
    seen = []
    original = point_solve.solve_fas

    def recording(problem, options, **kw):
        seen.append(options)
        return original(problem, options, **kw)

    monkeypatch.setattr(point_solve, "solve_fas", recording)
    res = solve_point(20, 10, accuracy=0.02, max_points=257)
    boxes = {o.xmin for o in seen}
    assert len(res.extra["refinements"]) >= 2 and len(boxes) >= 3  # two boxes probed
    assert len(seen) == len(set(seen))


def test_a_probe_that_needed_the_coarser_start_passes_it_on_to_the_wider_boxes():
    """A probe whose first attempt diverged and converged from half the rule's coarse intervals
    (retry_coarser_start) makes the later probes start from that share of the rule at once;
    without such a probe the rule stands."""
    from types import SimpleNamespace

    from ehl_multigrid.multigrid.options import PointOptions
    from ehl_multigrid.point.problem import coarse_intervals, problem_from_moes
    from ehl_multigrid.point.solve import learned_coarse

    pb = problem_from_moes(3000.0, 10.0, 1.0, "roelands", "dowson-higginson", None, None, None)
    wide = PointOptions(points=1025, xmin=-9.0, xmax=3.0, ymax=6.0)
    rule = coarse_intervals(pb.M, 12.0, 1025)
    assert rule == 128
    plain = SimpleNamespace(success=True, actions=[], levels=4)
    assert learned_coarse(pb, {wide: plain}, 2049, 24.0) is None
    retried = SimpleNamespace(success=True, levels=5,  # 1024 / 2^4 = 64 coarse intervals
                              actions=["ended diverged (...); solved again with 64 coarse intervals "
                                       "instead of 128 (retry_coarser_start): converged"])
    assert learned_coarse(pb, {wide: retried}, 2049, 24.0) == coarse_intervals(pb.M, 24.0, 2049) // 2 == 128
    failed = SimpleNamespace(success=False, levels=5, actions=retried.actions)
    assert learned_coarse(pb, {wide: failed}, 2049, 24.0) is None
