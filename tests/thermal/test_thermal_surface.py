"""Surface-temperature kernels (thesis (3.6)-(3.7)) and their discrete weights."""

import math

import numpy as np
import pytest
from scipy.special import k0

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.solids import STEEL
from thermal.surface import (
    carslaw_jaeger_kernel,
    diffusivity,
    moving_strip_kernel,
    wall_weights,
)


def _response(WL, WR, n):
    """Wall temperature rise at every node for a uniform unit flux on all nodes."""
    out = np.zeros(n)
    for i in range(n):
        for j in range(n):
            m = i - j + n - 1
            out[i] += WR[m] if j == 0 else (WL[m] if j == n - 1 else WL[m] + WR[m])
    return out


def test_long_moving_strip_equals_2d_moving_line_source():
    u = 4.0
    v = u / (2 * diffusivity(STEEL))
    xi = np.array([-1e-4, -1e-5, 1e-7, 1e-5, 3e-4])
    exact = np.exp(v * xi) * k0(v * np.abs(xi)) / (math.pi * STEEL.k)
    assert moving_strip_kernel(xi, u, STEEL, 1e3) == pytest.approx(exact, rel=1e-9)


def test_moving_strip_tends_to_carslaw_jaeger_downstream_at_high_peclet():
    u = 4.0
    xi = np.array([1e-4, 3e-4, 1e-3])
    ratio = moving_strip_kernel(xi, u, STEEL, 1.0) / carslaw_jaeger_kernel(xi, u, STEEL)
    # 2-D line source: exp(z) K0(z) sqrt(2 z / pi) = 1 - 1/(8z) + ...
    z = u / (2 * diffusivity(STEEL)) * xi
    assert ratio == pytest.approx(np.exp(z) * k0(z) * np.sqrt(2 * z / np.pi), rel=1e-9)
    assert np.all(np.abs(ratio - 1) < 1.5 / (8 * z))


def test_stationary_strip_kernel_is_finite_and_symmetric():
    xi = np.array([1e-5, 1e-4])
    Kp = moving_strip_kernel(xi, 0.0, STEEL, 0.032)
    Km = moving_strip_kernel(-xi, 0.0, STEEL, 0.032)
    assert Kp == pytest.approx(np.arcsinh(0.032 / (2 * xi)) / (math.pi * STEEL.k), rel=1e-12)
    assert Km == pytest.approx(Kp, rel=1e-12)


def test_carslaw_jaeger_weights_reproduce_uniform_flux_response():
    # uniform flux q = 1 from x = 0: dT = 2 sqrt(x) / sqrt(pi rho c k u), exact for hat functions
    n, dx, u = 60, 1e-5, 3.0
    WL, WR = wall_weights(n, dx, u, STEEL, "carslaw-jaeger")
    c = 1 / math.sqrt(math.pi * STEEL.rho * STEEL.cp * STEEL.k * u)
    x = dx * np.arange(n)
    r = _response(WL, WR, n)
    assert r[1:] == pytest.approx(2 * c * np.sqrt(x[1:]), rel=1e-12)


def test_moving_strip_weights_match_quadrature_of_the_kernel():
    from scipy.integrate import quad

    n, dx, u, B = 12, 2e-5, 0.5, 0.01
    WL, WR = wall_weights(n, dx, u, STEEL, "moving-strip", B)
    for m in (-2, -1, 0, 1, 3):
        def f(t, m=m):
            return (1 - t / dx) * moving_strip_kernel(np.array([m * dx - t]), u, STEEL, B)[0]

        ref = quad(f, 0, dx, limit=400, epsabs=0.0, epsrel=1e-12)[0]
        assert WR[m + n - 1] == pytest.approx(ref, rel=1e-6)


def test_carslaw_jaeger_kernel_rejects_surface_at_rest():
    with pytest.raises(InputError, match="u > 0"):
        wall_weights(10, 1e-5, 0.0, STEEL, "carslaw-jaeger")
    with pytest.raises(InputError, match="kernel_length"):
        wall_weights(10, 1e-5, 0.0, STEEL, "moving-strip", math.inf)
