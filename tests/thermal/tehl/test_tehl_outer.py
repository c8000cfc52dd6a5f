"""The TEHL outer iteration after an Anderson step that overshoots: it restarts the history
and takes plain damped steps at the same under-relaxation before extrapolating again. An
extrapolation from a restarted history (one secant made of inner solves with algebraic noise)
overshoots again: halving the damping each time, the page 63 contact at 20 m/s in rolling
(thermal loading 0.59) reaches the smallest damping and stops as diverged on 1025 points with
its films settled to 1e-7."""

import pytest

from ehl_multigrid.model.scene import load_scene
from thermal.tehl.line import solve_tehl_line

pytestmark = pytest.mark.solver


def test_an_overshooting_anderson_step_is_followed_by_plain_steps_and_the_solve_converges():
    sc = load_scene("page63_line_2000N").with_operating(us=20.0)
    r = solve_tehl_line(sc, 0.0, points=1025)
    assert r.report.converged
    assert any("after an Anderson step" in a for a in r.report.extra["actions"])
    # the plain-damped iteration (no Anderson at all) reaches the same fixed point
    plain = solve_tehl_line(sc, 0.0, points=1025, anderson=0)
    assert r.Hc == pytest.approx(plain.Hc, rel=2 * r.options.tol_H)
    assert r.Hm == pytest.approx(plain.Hm, rel=2 * r.options.tol_H)
