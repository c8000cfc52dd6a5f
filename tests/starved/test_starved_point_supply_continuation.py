"""A starved point grid on which the FMG ladder and the exact zone solves all fail is solved by
continuation in the supply: a thinner layer first, then the layer from that film. The 6205
inner-race contact (M 3620, b/a 9.4) with a 100 nm layer (Hoil/Hc_flooded about 0.6) ended
`mass_not_conserved` on every grid; on 129 points it stops at a residual floor with a mass
imbalance of 7-9 from the FMG and at max_cycles from the exact zone solves, while 50 nm
converges there."""

from __future__ import annotations

import pytest

import ehl_multigrid.starved.point as sp
from ehl_multigrid.model.scene import load_scene
from ehl_multigrid.point.problem import problem_from_scene
from ehl_multigrid.starved.supply import hoil_venner

HOIL = 100e-9  # [m]; the flooded central film is about 160 nm


@pytest.mark.solver
def test_a_grid_no_ladder_solves_converges_by_continuation_in_the_supply():
    scene = load_scene("bearing_6205_inner_race")
    res = sp.solve_starved_point_scene(scene, hoil=HOIL, points=129, estimate=False, flooded=False,
                                       raise_on_failure=False)
    assert res.success, res.message
    assert any("continuation in the supply" in a for a in res.actions)
    assert res.extra["mass_balance_error"] <= 1e-3

    # the same discrete solution by another path: the layer from a 70 nm film, itself from 50 nm
    pb = problem_from_scene(scene)
    films = []
    for h in (50e-9, 70e-9, HOIL):
        prev = films[-1] if films else None
        kw = {} if prev is None else dict(coarse_theta=prev.extra["coarse_theta"],
                                          guess=(prev.X, prev.Y, prev.P, prev.H0))
        films.append(sp.solve_starved_point(pb, hoil_venner(h, pb.a, pb.Rx), points=129, half=True,
                                            raise_on_failure=False, **kw))
        assert films[-1].success, (h, films[-1].message)
    for key in ("Hc_venner", "Hm_venner"):
        assert res.scalars[key] == pytest.approx(films[-1].scalars[key], rel=1e-5)
    # more oil, thicker film: the 50 nm layer's central film lies well below
    assert films[0].scalars["Hc_venner"] < 0.6 * res.scalars["Hc_venner"]

def test_a_flooded_inlet_is_not_continued():
    failed = sp.EHLResult.__new__(sp.EHLResult)
    ctl = sp._StarvedPointControl.__new__(sp._StarvedPointControl)
    ctl.Hoil = float("inf")
    assert ctl._continued(129, failed) is failed
    assert sp._finite_layer(2.0) and sp._finite_layer(lambda Y: 1.0)
    assert sp._scaled_layer(2.0, 0.5) == 1.0
    assert sp._scaled_layer(lambda Y: 2.0 + Y, 0.5)(2.0) == 2.0
