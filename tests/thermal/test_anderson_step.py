"""The Anderson step of the thermal sweeps (thermal.kernels._anderson_step) solves its least-squares
problem with LAPACK's dgelsd called directly: it must give exactly the step of the same formula
with a library least-squares solve (scipy's gelsd driver, rcond 1e-10)."""

import numpy as np
import pytest
import scipy.linalg

from thermal.kernels import _anderson_step


def reference_step(X, F, count, x, g, depth):
    """Walker & Ni type II step with the kernel's summation order and scipy's dgelsd."""
    N = x.shape[0]
    f = g - x
    if count == depth + 1:
        X[:-1] = X[1:].copy()
        F[:-1] = F[1:].copy()
        count -= 1
    X[count] = x
    F[count] = f
    count += 1
    if count < 2:
        return g.copy(), count
    m = count - 1
    dF = (F[1:count] - F[:m]).T
    dX = (X[1:count] - X[:m]).T
    norms = np.empty(m)
    for c in range(m):
        s = 0.0
        for r in range(N):
            s += dF[r, c] * dF[r, c]
        norms[c] = np.sqrt(s)
    gamma = scipy.linalg.lstsq(dF / norms, f, cond=1e-10, lapack_driver="gelsd")[0]
    out = np.empty(N)
    for r in range(N):
        t = 0.0
        for c in range(m):
            t += (dX[r, c] + dF[r, c]) * (gamma[c] / norms[c])
        out[r] = g[r] - t
    return out, count


@pytest.mark.parametrize("case", ["full_rank", "rank_deficient"])
def test_anderson_step_equals_the_step_with_a_library_least_squares_solve(case):
    rng = np.random.default_rng(7)
    N, depth = 120, 3
    X, F = np.zeros((depth + 1, N)), np.zeros((depth + 1, N))
    Xr, Fr = X.copy(), F.copy()
    count = count_ref = 0
    x = rng.random(N)
    direction = rng.random(N)
    for k in range(9):
        if case == "full_rank":
            g = 0.4 * x + rng.random(N)
        else:
            # residuals that change along one direction only: parallel difference columns, a
            # rank-one least-squares problem that rcond truncates
            g = x + (k + 1.0) * direction
        new, count = _anderson_step(X, F, count, x, g, depth)
        ref, count_ref = reference_step(Xr, Fr, count_ref, x, g, depth)
        assert count == count_ref, f"step {k}: history length {count} against {count_ref}"
        np.testing.assert_array_equal(new, ref, err_msg=f"{case} step {k}: the Anderson iterate differs")
        np.testing.assert_array_equal(X, Xr, err_msg=f"{case} step {k}: the iterate history differs")
        x = new
    assert count == depth + 1


def test_anderson_step_without_a_change_of_residual_restarts_from_the_sweep_result():
    N, depth = 50, 2
    X, F = np.zeros((depth + 1, N)), np.zeros((depth + 1, N))
    x = np.linspace(0.0, 1.0, N)
    g = x + 0.5
    _, count = _anderson_step(X, F, 0, x, g, depth)
    new, count = _anderson_step(X, F, count, x, g, depth)  # same residual: zero difference column
    assert count == 0, f"history kept ({count} entries) after a zero residual difference"
    np.testing.assert_array_equal(new, g)
