"""The line relaxation's banded systems go straight to LAPACK's gbsv (``line.level.solve_band``):
the answers of ``scipy.linalg.solve_banded`` bit for bit, and a singular system relaxed by point
Jacobi instead; the steady sweep kernel's banded LU (``line.band``, LAPACK's interchanges) to
rounding."""

import numpy as np
import pytest
import scipy.linalg as sl

from ehl_multigrid.line.band import solve_band_columns
from ehl_multigrid.line.level import solve_band


@pytest.mark.parametrize("band", [1, 2, 4])
def test_a_banded_system_is_solved_as_scipy_solve_banded_solves_it_bit_for_bit(band):
    rng = np.random.default_rng(band)
    for n in (1, 2, 7, 129):
        ab = rng.standard_normal((2 * band + 1, n))  # no diagonal dominance: row interchanges
        b = rng.standard_normal(n)
        assert np.array_equal(solve_band(ab, b, band), sl.solve_banded((band, band), ab, b))


@pytest.mark.parametrize("band", [1, 4])
def test_a_singular_system_falls_back_to_point_jacobi(band):
    ab = np.zeros((2 * band + 1, 4))
    ab[band] = [2.0, 0.0, 4.0, 1.0]  # a zero on the diagonal of a diagonal matrix
    assert solve_band(ab, np.array([2.0, 3.0, 4.0, 5.0]), band).tolist() == [1.0, 0.0, 1.0, 5.0]


def _dense(ab: np.ndarray, band: int) -> np.ndarray:
    n = ab.shape[1]
    A = np.zeros((n, n))
    for i in range(n):
        for j in range(max(0, i - band), min(n, i + band + 1)):
            A[i, j] = ab[band + i - j, j]
    return A


def _columns(ab: np.ndarray, band: int) -> np.ndarray:
    """LAPACK band storage into line.band's column storage (fill-in rows zero)."""
    cols = np.zeros((ab.shape[1], 3 * band + 1))
    cols[:, band:] = ab.T
    return cols


@pytest.mark.parametrize("band", [1, 2, 4, 8])
def test_the_sweep_kernels_banded_lu_solves_as_gbsv_to_rounding(band):
    rng = np.random.default_rng(band)
    for n in (1, 2, 7, 129):
        ab = rng.standard_normal((2 * band + 1, n))  # no diagonal dominance: row interchanges
        b = rng.standard_normal(n)
        x = solve_band_columns(_columns(ab, band), b.copy(), band)
        ref = sl.solve_banded((band, band), ab, b)
        # both backward stable with the same interchanges: apart by rounding times the condition
        cond = np.linalg.cond(_dense(ab, band))
        assert np.max(np.abs(x - ref)) <= 100 * cond * np.finfo(float).eps * np.max(np.abs(ref))


@pytest.mark.parametrize("band", [1, 4])
def test_the_sweep_kernel_relaxes_a_singular_system_by_point_jacobi(band):
    ab = np.zeros((2 * band + 1, 4))
    ab[band] = [2.0, 0.0, 4.0, 1.0]
    x = solve_band_columns(_columns(ab, band), np.array([2.0, 3.0, 4.0, 5.0]), band)
    assert x.tolist() == [1.0, 0.0, 1.0, 5.0]
