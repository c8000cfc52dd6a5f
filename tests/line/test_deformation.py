"""Elastic deformation paths (the film equation's elastic integral): FFT and MLMI against the direct sum."""

import numpy as np
import pytest

from ehl_multigrid.line import DirectDeformation, FFTDeformation, MLMIDeformation, log_kernel


def pressure(n):
    X = np.linspace(-4.5, 1.5, n)
    P = np.sqrt(np.clip(1.0 - X**2, 0.0, None)) + 0.3 * np.exp(-(((X - 0.9) / 0.02) ** 2))
    P[0] = P[-1] = 0.0
    return X[1] - X[0], P


def rel_err(a, b):
    return np.max(np.abs(a - b)) / np.max(np.abs(b))


def test_log_kernel_is_the_cell_integral_of_ln():
    h = 0.03
    K = log_kernel(50, h)
    F = lambda x: x * (np.log(np.abs(x)) - 1.0)  # noqa: E731
    d = np.arange(1, 50)
    assert K[0] == pytest.approx(2 * F(h / 2), rel=1e-14)
    assert np.allclose(K[1:], F((d + 0.5) * h) - F((d - 0.5) * h), rtol=1e-9, atol=0)


@pytest.mark.parametrize("n", [129, 257, 1025])
def test_fft_matches_direct_sum(n):
    h, P = pressure(n)
    op = FFTDeformation(n, h)
    assert op.size == 2 * (n - 1)  # a power of two: no wrap-around with P = 0 at the ends
    assert rel_err(op.apply(P), DirectDeformation(n, h).apply(P)) < 1e-13


@pytest.mark.parametrize("n", [1, 2, 3, 4, 9, 100, 257])
def test_fft_matches_direct_sum_with_pressure_at_the_ends(n):
    P = np.random.default_rng(n).random(n)  # P_0 and P_(n-1) not zero: added directly
    h = 3.0 / max(n - 1, 1)
    assert rel_err(FFTDeformation(n, h).apply(P), DirectDeformation(n, h).apply(P)) < 1e-13


@pytest.mark.parametrize("n", [257, 1025, 4097])
def test_mlmi_default_matches_direct_sum_to_1e10(n):
    # default order 12, correction radius 48: measured 1e-11 at every n (REPORT.md)
    h, P = pressure(n)
    op = MLMIDeformation(n, h)
    assert len(op.levels) >= 2
    assert rel_err(op.apply(P), DirectDeformation(n, h).apply(P)) < 1e-10


def test_mlmi_error_falls_with_the_correction_radius():
    n = 1025
    h, P = pressure(n)
    ref = DirectDeformation(n, h).apply(P)
    errs = [rel_err(MLMIDeformation(n, h, order=8, radius=m).apply(P), ref) for m in (8, 16, 32)]
    assert errs[0] > errs[1] > errs[2]
    assert errs[2] < 1e-7 and errs[0] > 1e-6


def test_mlmi_is_exact_when_the_correction_covers_the_grid():
    n = 129
    h, P = pressure(n)
    op = MLMIDeformation(n, h, order=4, radius=200, n_direct=33)
    assert rel_err(op.apply(P), DirectDeformation(n, h).apply(P)) < 1e-13
