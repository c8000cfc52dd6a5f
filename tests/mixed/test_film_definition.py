"""Johnson's film definition (4.20) and its inverse; planes (4.28); Whitehouse-Archard; two surfaces."""

import math

import numpy as np
import pytest
from scipy import integrate

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import Roughness
from mixed.film import (
    equivalent_surface,
    johnson_film,
    separation_from_film,
)

SIGMA = 7e-8


def film_by_quadrature(hs, sigma):
    """(4.20) integrated directly: int_-inf^hs (hs - z) phi(z) dz."""
    f = lambda z: (hs - z) * math.exp(-0.5 * (z / sigma) ** 2) / (sigma * math.sqrt(2 * math.pi))  # noqa: E731
    val, _ = integrate.quad(f, hs - 40 * sigma, hs, epsabs=0, epsrel=1e-12, limit=200)
    return val


@pytest.mark.parametrize("t", [-5.0, -2.0, -0.5, 0.0, 0.7, 2.0, 6.0])
def test_film_matches_direct_integration_of_4_20(t):
    hs = t * SIGMA
    assert johnson_film(hs, SIGMA) == pytest.approx(film_by_quadrature(hs, SIGMA), rel=1e-10)


def test_film_limits_thick_zero_and_negative_separation():
    assert johnson_film(0.0, SIGMA) == pytest.approx(SIGMA / math.sqrt(2 * math.pi), rel=1e-14)
    hs = 10 * SIGMA
    assert johnson_film(hs, SIGMA) == pytest.approx(hs, rel=1e-20 + 1e-15)
    neg = johnson_film(np.array([-3, -8, -20]) * SIGMA, SIGMA)
    assert np.all(neg > 0)  # the film never vanishes, however negative hs is
    assert np.all(np.diff(johnson_film(np.linspace(-6, 6, 50) * SIGMA, SIGMA)) > 0)


def test_inverse_round_trips_from_deep_contact_to_thick_films():
    hs = np.concatenate([np.linspace(-9, 9, 37), [25.0, 300.0]]) * SIGMA
    back = separation_from_film(johnson_film(hs, SIGMA), SIGMA)
    assert np.allclose(back, hs, rtol=1e-12, atol=1e-13 * SIGMA)


def test_inverse_handles_extremely_thin_films_without_underflow():
    hs = separation_from_film(1e-250 * SIGMA, SIGMA)
    assert np.isfinite(hs) and hs < -30 * SIGMA
    assert math.log(johnson_film(hs, SIGMA) / SIGMA) == pytest.approx(math.log(1e-250), rel=1e-10)


def test_inverse_rejects_non_positive_films():
    with pytest.raises(InputError, match="hf,r"):
        separation_from_film(0.0, SIGMA)
    with pytest.raises(InputError, match="sigma"):
        johnson_film(1e-8, -1.0)


def test_equivalent_surface_combines_in_quadrature_and_keeps_the_rougher_summits():
    # Table 4.3 footnote: disc 1 combined sigma_s = 0.034 um with a ball of 0.0225 um
    disc = 0.034e-6 * math.sqrt(1 - (0.0225 / 0.034) ** 2)
    ball = Roughness(Rq=0.03e-6, sigma_s=0.0225e-6, dd=0.82 * 0.03e-6, n=1e12, beta=1e-6, fc=0.1, hardness=7e9)
    d1 = Roughness(Rq=0.035e-6, sigma_s=disc, dd=0.82 * 0.035e-6, n=6.7e10, beta=27e-6, fc=0.14, hardness=5e9)
    eq = equivalent_surface(ball, d1)
    assert eq.sigma_s == pytest.approx(0.034e-6, rel=1e-12)
    assert eq.Rq == pytest.approx(math.hypot(0.03e-6, 0.035e-6))
    assert eq.dd == pytest.approx(0.82 * eq.Rq)  # Whitehouse-Archard proportions survive
    assert (eq.n, eq.beta, eq.fc, eq.hardness) == (6.7e10, 27e-6, 0.14, 5e9)
    with pytest.raises(InputError, match="Roughness"):
        equivalent_surface(ball, 1e-7)
