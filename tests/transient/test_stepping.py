"""The time loop shared by the line and point contacts: the BDF coefficients of the squeeze
term and the extrapolated start iterate of a step (no solves)."""

from __future__ import annotations

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.transient import Bump, Dent2D, max_point_time_step, max_time_step
from ehl_multigrid.transient.stepping import _extrapolate, step_coefficients, time_steps


@pytest.mark.parametrize("scheme, n, exact_for", [("bdf2", 2, 2), ("bdf2", 1, 1), ("euler", 5, 1)])
def test_bdf_coefficients_differentiate_polynomials_of_their_order_exactly(scheme, n, exact_for):
    dt = 0.05
    T = np.array([-1.0, 0.0, 1.0]) * dt  # levels n-1, n, n+1
    for degree in range(exact_for + 1):
        q = T**degree  # (rho H)(T) at one node
        ct, s = step_coefficients(scheme, n, dt, np.array([q[1]]), np.array([q[0]]))
        exact = degree * T[2] ** (degree - 1) if degree else 0.0
        assert ct * q[2] - s[0] == pytest.approx(exact, abs=1e-12)
    # one order higher is not exact
    q = T ** (exact_for + 1)
    ct, s = step_coefficients(scheme, n, dt, np.array([q[1]]), np.array([q[0]]))
    assert abs(ct * q[2] - s[0] - (exact_for + 1) * T[2] ** exact_for) > 1e-6


def test_extrapolated_start_is_nonnegative_and_zero_on_the_boundary():
    rng = np.random.default_rng(1)
    for shape in ((9,), (7, 9)):
        now, prev = rng.random(shape), rng.random(shape)
        P = _extrapolate(now, prev)
        inner = (slice(1, -1),) * len(shape)
        assert np.array_equal(P[inner], np.maximum(2.0 * now - prev, 0.0)[inner])
        edge = np.ones(shape, dtype=bool)
        edge[inner] = False
        assert np.all(P[edge] == 0.0) and np.all(P >= 0.0)


def test_line_and_point_share_the_time_step_limit():
    bump, dent = Bump(0.01, 0.5), Dent2D(-0.01, 0.5)
    assert max_time_step(bump, 1.5) == max_point_time_step(dent, 1.5) == 0.25 * 0.25 / 1.5
    dt, steps, every = time_steps(bump, 1.0, 0.01, None, None, 1.0, 10, 1e-3, "b", lambda: 0.0)
    assert (dt, steps, every) == (0.01, 100, 10)
    with pytest.raises(InputError, match=r"t_end = 5e\+06 .*\(T = t u_m/a\)"):
        time_steps(dent, 1.0, 0.01, None, None, 5e6, 10, 1e-3, "a", lambda: 0.0)


@pytest.mark.parametrize("ratio", [0.5, 2.0, 0.125])
def test_variable_step_bdf2_differentiates_quadratics_exactly(ratio):
    """BDF2 with the step ``dt`` after an interval ``dt_prev = dt/ratio`` (the halved steps of a
    failed solve) is exact for polynomials up to degree 2 and not for degree 3."""
    dt = 0.05
    T = np.array([-dt / ratio, 0.0, dt])
    for degree, exact in ((0, True), (1, True), (2, True), (3, False)):
        q = T**degree
        ct, s = step_coefficients("bdf2", 3, dt, np.array([q[1]]), np.array([q[0]]), dt / ratio)
        dq = degree * T[2] ** (degree - 1) if degree else 0.0
        assert bool(abs(ct * q[2] - s[0] - dq) < 1e-10) is exact


def test_a_step_whose_solve_fails_is_solved_again_in_halves_on_the_same_output_times(monkeypatch):
    """A step whose solve diverges is repeated as two half steps: the run goes on, its output
    times stay n dT, the step records two solves, and the films agree with the undisturbed run
    to well within the step's time error."""
    from ehl_multigrid.line.problem import LineProblem
    from ehl_multigrid.transient import solve_transient_line, stepping

    problem = LineProblem.from_moes(20, 10, xmin=-4.5)
    kw = dict(dt=0.05, steps=8, points=129, snapshot_every=100)
    plain = solve_transient_line(problem, Bump(-0.05, 0.5, x0=-2.0), **kw)
    real = stepping.Stepper.solve_step
    calls = {"n": 0}

    def flaky(self):
        calls["n"] += 1
        res = real(self)
        if calls["n"] == 5:  # the first attempt of a step in the middle of the run
            res.success, res.status = False, 3
        return res

    monkeypatch.setattr(stepping.Stepper, "solve_step", flaky)
    res = solve_transient_line(problem, Bump(-0.05, 0.5, x0=-2.0), **kw)
    assert res.complete and res.steps == 8
    np.testing.assert_allclose(res.series["T"], np.arange(9) * 0.05)
    assert sorted(res.series["substeps"]) == [1.0] * 8 + [2.0]
    assert np.max(np.abs(res.Hc / plain.Hc - 1.0)) < 2e-3


@pytest.mark.parametrize("depth, blamed", [(-0.005, False), (-0.5, True)])
def test_a_step_that_diverges_to_a_closed_film_blames_the_feature_only_when_it_is_deep(monkeypatch, depth,
                                                                                        blamed):
    """A step whose iteration diverges to a film that is not positive: a dent far shallower than
    the film (5e-3 against a film of about 0.1) cannot have closed it, so the failure says the
    iteration diverged and names no mixed lubrication; a dent five times the film may have."""
    from ehl_multigrid.line.problem import LineProblem
    from ehl_multigrid.model.errors import ConvergenceError
    from ehl_multigrid.transient import solve_transient_line, stepping

    real = stepping.Stepper.solve_step
    calls = {"n": 0}

    def diverging(self):
        calls["n"] += 1
        res = real(self)
        if calls["n"] > 2:  # after the start and step 1: every solve ends on a closed film
            self.hz.fine.H0 -= 1.0
            res.success, res.status, res.message = False, 3, "diverged on grid 2: cycle 5 rejected"
        return res

    monkeypatch.setattr(stepping.Stepper, "solve_step", diverging)
    problem = LineProblem.from_moes(20, 10, xmin=-4.5)
    with pytest.raises(ConvergenceError) as err:
        solve_transient_line(problem, Bump(depth, 0.5, x0=-2.0), dt=0.05, steps=4, points=129)
    msg = str(err.value)
    assert "time step 2" in msg
    assert ("mixed-lubrication" in msg and "cuts through the film" in msg) is blamed
    assert ("did not converge" in msg and "diverged" in msg and "deep" in msg) is not blamed
    assert err.value.partial.steps == 1 and not err.value.partial.complete
