"""The line relaxation's banded systems go straight to LAPACK's gbsv (``line.level.solve_band``):
the answers of ``scipy.linalg.solve_banded`` bit for bit, and a singular system relaxed by point
Jacobi instead."""

import numpy as np
import pytest
import scipy.linalg as sl

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
