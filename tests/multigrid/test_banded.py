"""The line relaxation's banded systems are solved in one compiled kernel
(``multigrid.banded.solve_banded``) with LAPACK's elimination: partial pivoting, the same
answers as ``scipy.linalg.solve_banded`` to round-off, and a singular system reported."""

import numpy as np
import pytest
import scipy.linalg as sl

from ehl_multigrid.line.level import solve_band
from ehl_multigrid.multigrid.banded import solve_banded


def _dense(ab, q):
    n = ab.shape[1]
    A = np.zeros((n, n))
    for j in range(n):
        for i in range(max(0, j - q), min(n, j + q + 1)):
            A[i, j] = ab[q + i - j, j]
    return A


@pytest.mark.parametrize("q", [1, 2, 4])
def test_a_banded_system_needing_row_interchanges_is_solved_as_lapack_solves_it(q):
    rng = np.random.default_rng(q)
    for n in (1, 2, 7, 40):
        ab = rng.standard_normal((2 * q + 1, n))  # no diagonal dominance: pivoting needed
        b = rng.standard_normal(n)
        x, ok = solve_banded(ab, b, q)
        assert ok
        ref = sl.solve_banded((q, q), ab, b)
        assert np.allclose(x, ref, rtol=1e-11, atol=1e-11 * np.abs(ref).max())
        assert np.allclose(_dense(ab, q) @ x, b, atol=1e-9)


def test_a_singular_system_is_reported_and_the_sweep_falls_back_to_point_jacobi():
    ab = np.zeros((3, 4))
    ab[1] = [2.0, 0.0, 4.0, 1.0]  # a zero on the diagonal of a diagonal matrix
    assert not solve_banded(ab, np.ones(4), 1)[1]
    assert solve_band(ab, np.array([2.0, 3.0, 4.0, 5.0]), 1).tolist() == [1.0, 0.0, 1.0, 5.0]
