"""The deformation's transforms call pocketfft directly, with scipy.fft's results bit for bit
(``multigrid.transforms``), and fall back to scipy.fft when the direct path is not available;
the line deformation's numpy FFTs give scipy.fft's results bit for bit."""

import numpy as np
import pytest
import scipy.fft as sfft

from ehl_multigrid.line.deformation import FFTDeformation as LineFFT
from ehl_multigrid.line.deformation import fast_real_length
from ehl_multigrid.multigrid import transforms
from ehl_multigrid.point.deformation import FFTDeformation as PointFFT


def test_the_direct_transforms_equal_scipy_fft_bit_for_bit():
    assert transforms.direct()  # the installed scipy exposes pocketfft's routines
    rng = np.random.default_rng(11)
    x = rng.random((9, 33))
    F = transforms.rfft(x, 64)
    assert np.array_equal(F, sfft.rfft(x, n=64, axis=-1))
    assert np.array_equal(transforms.irfft(F, 64), sfft.irfft(F, n=64, axis=-1))
    V = rng.random((17, 6))
    for inverse, ref in ((False, sfft.dct), (True, sfft.idct)):
        W = np.zeros((17, 9))
        W[:, 2:8] = V
        transforms.dct1(W[:, 2:8], inverse)  # a view, in place
        assert np.array_equal(W[:, 2:8], ref(V, type=1, axis=0))
        assert not W[:, :2].any() and not W[:, 8:].any()
    c = rng.random((16, 5)) + 1j * rng.random((16, 5))
    for inverse, ref in ((False, sfft.fft), (True, sfft.ifft)):
        a = c.copy()
        transforms.fft_inplace(a, inverse)
        assert np.array_equal(a, ref(c, axis=0))


@pytest.mark.parametrize("half", [True, False])
def test_the_point_deformation_is_the_same_through_scipy_fft(monkeypatch, half):
    n = 65
    ny = (n + 1) // 2 if half else n
    P = np.random.default_rng(5).random((ny, n))
    op = PointFFT(n, ny, 6.0 / (n - 1), 3.0 / (n - 1), half=half)
    direct = op(P).copy()
    monkeypatch.setattr(transforms, "_DIRECT", False)
    assert np.array_equal(op(P), direct)


@pytest.mark.parametrize("n", [257, 1025, 4097])
def test_the_line_deformation_on_numpy_fft_equals_scipy_fft_bit_for_bit(n):
    op = LineFFT(n, 6.0 / (n - 1))
    c = np.zeros(op.size)
    c[: n - 1] = op.kernel[: n - 1]
    c[op.size - n + 2:] = op.kernel[1: n - 1][::-1]
    P = np.random.default_rng(6).random(n)
    P[0] = P[-1] = 0.0
    ref = sfft.irfft(sfft.rfft(P, n=op.size) * sfft.rfft(c), n=op.size)[:n]
    assert np.array_equal(op.apply(P), ref)


def test_the_fast_real_lengths_are_scipys():
    lengths = [fast_real_length(n) for n in range(1, 5000)]
    assert lengths == [sfft.next_fast_len(n, real=True) for n in range(1, 5000)]


def test_the_line_deformation_is_the_same_through_numpy_fft(monkeypatch):
    from ehl_multigrid.line import deformation

    op = LineFFT(1025, 6.0 / 1024)
    P = np.random.default_rng(6).random(1025)
    direct = op.apply(P)
    assert deformation._numpy_pocketfft() is not None  # the installed numpy's ufuncs
    monkeypatch.setattr(deformation, "_PFU", False)
    assert np.array_equal(op.apply(P), direct)
