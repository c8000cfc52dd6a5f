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
