"""The accuracy sequence of a point contact starts on twice the box when the domain probes of the
default box already say that box cannot meet the target: the solve on the default box, which
the controller would only have replaced, is not made, and the answer is the same."""

import pytest

import ehl_multigrid.point.solve as solve_mod
from ehl_multigrid.point.solve import solve_point

pytestmark = pytest.mark.solver


def _solves(res):
    return [(r["points"], r["box"]) for r in res.extra["refinements"] if r["purpose"] == "solve"]


#: the target: 2 % (the sequence 129 points on the default box, 257 on twice it) costs half as
#: much as 1 % (257, then 513 on twice the box) and skips the same default box
TARGET = 0.02


@pytest.fixture(scope="module")
def plain():
    """(20, 10) at 2 % as the sequence ran without the start-box choice."""
    mp = pytest.MonkeyPatch()
    mp.setattr(solve_mod, "start_box", lambda *a, **k: None)
    try:
        return solve_point(20.0, 10.0, accuracy=TARGET, half=True, far_field=False, raise_on_failure=False)
    finally:
        mp.undo()


def test_a_default_box_too_small_for_the_target_is_skipped_with_the_same_answer(plain):
    lines = []
    res = solve_point(20.0, 10.0, accuracy=TARGET, half=True, far_field=False, raise_on_failure=False, progress=lines.append)
    assert res.success and plain.success
    # the plain sequence solved the default box first and then refined to twice it
    assert _solves(plain)[0][1] == 1.0 and _solves(plain)[-1][1] == 2.0
    assert _solves(res) == _solves(plain)[1:]
    assert any("starting on box x2" in s for s in lines)
    for key in ("Hc", "Hm"):
        assert res.scalars[key] == pytest.approx(plain.scalars[key], rel=1e-9)
        assert getattr(res.error, key) == pytest.approx(getattr(plain.error, key), rel=1e-6)


def test_a_failed_start_on_twice_the_box_falls_back_to_the_default_box(monkeypatch, probing):
    real = solve_mod.solve_fas
    failed = []

    def solve_fas(problem, options=None, callback=None, scene=None, guess=None, **kw):
        res = real(problem, options, callback=callback, scene=scene, guess=guess, **kw)
        # the start on twice the box, not the domain probe on the same grid and box before it
        if options.points == 257 and options.xmin == -9.0 and not probing[0] and not failed:
            failed.append(options)
            res.set_status(3, "diverged on grid 4 (made to fail by the test)")
        return res

    monkeypatch.setattr(solve_mod, "solve_fas", solve_fas)
    res = solve_point(20.0, 10.0, accuracy=TARGET, half=True, far_field=False, raise_on_failure=False)
    assert failed  # the wide start was tried
    steps = _solves(res)
    assert steps[:2] == [(257, 2.0), (129, 1.0)]
    assert res.status_name in ("converged", "inaccurate")
