"""The line relaxation's banded systems (``line.level.solve_band``, banded LU of ``line.band``
with LAPACK's partial pivoting): the answers of ``scipy.linalg.solve_banded`` to rounding, and a
singular system relaxed by point Jacobi instead."""

import numpy as np
import pytest
import scipy.linalg as sl

from ehl_multigrid.line.level import solve_band


def _dense(ab: np.ndarray, band: int) -> np.ndarray:
    n = ab.shape[1]
    A = np.zeros((n, n))
    for i in range(n):
        for j in range(max(0, i - band), min(n, i + band + 1)):
            A[i, j] = ab[band + i - j, j]
    return A


@pytest.mark.parametrize("band", [1, 2, 4, 8])
def test_a_banded_system_is_solved_as_scipy_solve_banded_solves_it_to_rounding(band):
    rng = np.random.default_rng(band)
    for n in (1, 2, 7, 129):
        ab = rng.standard_normal((2 * band + 1, n))  # no diagonal dominance: row interchanges
        b = rng.standard_normal(n)
        x = solve_band(ab, b, band)
        ref = sl.solve_banded((band, band), ab, b)
        # backward stable: the difference is bounded by the condition number times rounding
        cond = np.linalg.cond(_dense(ab, band))
        assert np.max(np.abs(x - ref)) <= 100 * cond * np.finfo(float).eps * np.max(np.abs(ref))


def test_the_banded_solve_leaves_its_inputs_unchanged():
    rng = np.random.default_rng(3)
    ab, b = rng.standard_normal((9, 50)), rng.standard_normal(50)
    ab0, b0 = ab.copy(), b.copy()
    solve_band(ab, b, 4)
    assert np.array_equal(ab, ab0) and np.array_equal(b, b0)


@pytest.mark.parametrize("band", [1, 4])
def test_a_singular_system_falls_back_to_point_jacobi(band):
    ab = np.zeros((2 * band + 1, 4))
    ab[band] = [2.0, 0.0, 4.0, 1.0]  # a zero on the diagonal of a diagonal matrix
    assert solve_band(ab, np.array([2.0, 3.0, 4.0, 5.0]), band).tolist() == [1.0, 0.0, 1.0, 5.0]
