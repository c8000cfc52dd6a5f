"""Deformation paths against the direct O(N^2) sum (the film equation's elastic integral)."""

import numpy as np
import pytest

from ehl_multigrid.point.deformation import (
    MLMIDeformation,
    cell_kernel,
    make_deformation,
)


def _pressure(nx, ny, hx, hy, half, seed=0):
    rng = np.random.default_rng(seed)
    X = -4.5 + hx * np.arange(nx)
    Y = hy * np.arange(ny) if half else (np.arange(ny) - (ny - 1) / 2) * hy
    P = np.sqrt(np.clip(1 - X[None, :] ** 2 - (Y[:, None] / 1.3) ** 2, 0, None))
    P = P + 0.05 * rng.random((ny, nx))
    P[:, 0] = P[:, -1] = 0.0
    P[-1] = 0.0
    if not half:
        P[0] = 0.0
    return P


def test_cell_kernel_self_term_is_exact_square_integral():
    # integral of 1/r over a unit square centred on the origin = 4 asinh(1)
    K = cell_kernel(2, 2, 1.0, 1.0)
    assert K[0, 0] == pytest.approx(4.0 * np.arcsinh(1.0), rel=1e-14)
    # far cell: close to area / distance
    K = cell_kernel(200, 1, 1.0, 1.0)
    assert K[0, 199] == pytest.approx(1.0 / 199.0, rel=1e-5)


def test_hertz_deformation_at_centre_is_one():
    # (2/pi^2) ∫∫ sqrt(1 - r^2)/r = 1 at the centre (circular Hertz)
    n = 129
    X = np.linspace(-4.5, 1.5, n)
    Y = np.linspace(-3, 3, n)
    h = X[1] - X[0]
    P = np.sqrt(np.clip(1 - X[None, :] ** 2 - Y[:, None] ** 2, 0, None))
    W = make_deformation("fft", n, n, h, h)(P)
    assert 2 / np.pi**2 * W[64, 96] == pytest.approx(1.0, abs=2e-3)


@pytest.mark.parametrize("nx,ny,half", [(33, 33, False), (65, 33, False), (33, 17, True)])
def test_fft_matches_direct_sum_to_1e10(nx, ny, half):
    hx, hy = 6.0 / (nx - 1), 0.3
    P = _pressure(nx, ny, hx, hy, half)
    a = make_deformation("direct", nx, ny, hx, hy, half)(P)
    b = make_deformation("fft", nx, ny, hx, hy, half)(P)
    assert np.abs(a - b).max() / np.abs(a).max() < 1e-10


def test_half_domain_deformation_equals_full_domain():
    n = 33
    h = 6.0 / (n - 1)
    Pf = _pressure(n, n, h, h, False)
    Pf = 0.5 * (Pf + Pf[::-1])  # symmetric in Y
    Ph = Pf[(n - 1) // 2:].copy()
    Wf = make_deformation("fft", n, n, h, h)(Pf)
    Wh = make_deformation("fft", n, (n + 1) // 2, h, h, True)(Ph)
    assert np.abs(Wf[(n - 1) // 2:] - Wh).max() < 1e-12 * np.abs(Wf).max()


def test_mlmi_default_accuracy_and_convergence_with_order():
    """Default MLMI (q=3, mc=8) is an approximation (~1e-5 relative); the error falls with
    the interpolation order and correction box; q=7, mc=28 reaches 1e-10 at N = 65^2."""
    n = 65
    h = 6.0 / (n - 1)
    P = _pressure(n, n, h, h, False)
    ref = make_deformation("direct", n, n, h, h)(P)
    errs = []
    for q, mc in ((3, 8), (5, 16), (7, 28)):
        m = MLMIDeformation(n, n, h, h, q=q, mc=mc, n_direct=17)
        assert len(m.ranges) >= 2  # genuinely multilevel
        errs.append(np.abs(m(P) - ref).max() / np.abs(ref).max())
    assert errs[0] < 1e-4
    assert errs[1] < errs[0] / 100
    assert errs[2] < 1e-10


def test_mlmi_half_domain_matches_direct():
    nx, ny = 65, 33
    h = 6.0 / (nx - 1)
    P = _pressure(nx, ny, h, h, True)
    ref = make_deformation("direct", nx, ny, h, h, True)(P)
    got = MLMIDeformation(nx, ny, h, h, True, q=5, mc=16, n_direct=17)(P)
    assert np.abs(got - ref).max() / np.abs(ref).max() < 1e-7
