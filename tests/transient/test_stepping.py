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
