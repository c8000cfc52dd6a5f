"""Dimensionless groups (Moes, Dowson-Higginson, Venner) and the film-thickness fits (2.17-2.34, 4.23-4.26)."""

import math

import numpy as np
import pytest

from ehl_multigrid.model import fits, groups
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.hertz import hertz_circular, hertz_line


def test_moes_line_groups_from_dowson_higginson():
    G, U, W = groups.dowson_higginson_line(1e5, 2.0, 0.04, 2.2e-8, 2.3e11, 0.02)
    M, L = groups.moes_line(1e5, 2.0, 0.04, 2.2e-8, 2.3e11, 0.02)
    assert M == pytest.approx(W * U**-0.5, rel=1e-14)
    assert L == pytest.approx(G * U**0.25, rel=1e-14)


def test_venner_line_lambda_and_alpha_bar_match_physical_definitions():
    # lambda = 6 eta0 us R^2 / (b^3 pmax), alpha_bar = alpha pmax (Venner's dimensionless form)
    w, us, eta0, alpha, E, R = 2e5, 3.0, 0.05, 2e-8, 2.3e11, 0.015
    hz = hertz_line(w * 0.01, 0.01, R, E)
    M, L = groups.moes_line(w, us, eta0, alpha, E, R)
    lam, abar = groups.venner_line(M, L)
    assert lam == pytest.approx(6 * eta0 * us * R**2 / (hz.b**3 * hz.pmax), rel=1e-12)
    assert abar == pytest.approx(alpha * hz.pmax, rel=1e-12)


def test_venner_point_lambda_and_alpha_bar_match_physical_definitions():
    P, us, eta0, alpha, E, R = 40.0, 5.0, 0.01, 2e-8, 2.3e11, 0.01
    hz = hertz_circular(P, R, E)
    M, L = groups.moes_point(P, us, eta0, alpha, E, R)
    lam, abar = groups.venner_point(M, L)
    assert lam == pytest.approx(6 * eta0 * us * R**2 / (hz.a**3 * hz.pmax), rel=1e-12)
    assert abar == pytest.approx(alpha * hz.pmax, rel=1e-12)


def test_film_conversions_agree_with_physical_scalings():
    # line: H_venner = h R / b^2 ; H_moes = h / (R sqrt(U))
    w, us, eta0, alpha, E, R = 2e5, 3.0, 0.05, 2e-8, 2.3e11, 0.015
    hz = hertz_line(w * 0.01, 0.01, R, E)
    M, _ = groups.moes_line(w, us, eta0, alpha, E, R)
    h = 1e-7
    Hv = h * R / hz.b**2
    Hm = h / groups.moes_film_scale(us, eta0, E, R)
    assert groups.moes_from_venner_line(Hv, M) == pytest.approx(Hm, rel=1e-12)
    assert groups.venner_from_moes_line(Hm, M) == pytest.approx(Hv, rel=1e-12)
    # circular
    P, us, eta0 = 40.0, 5.0, 0.01
    hz = hertz_circular(P, R, E)
    M, _ = groups.moes_point(P, us, eta0, alpha, E, R)
    Hv = h * R / hz.a**2
    Hm = h / groups.moes_film_scale(us, eta0, E, R)
    assert groups.venner_from_moes_point(Hm, M) == pytest.approx(Hv, rel=1e-12)


def test_nijenbanning_circular_coefficients_2_30_to_2_34():
    M, L = 37.0, 7.0
    t = fits.nijenbanning_terms(M, L, 1.0)
    # the thesis prints the theta = 1 coefficients rounded to the digits shown: 41.3, 2.4, 0.9, 1.25
    assert round(t["HRI"] * M**2, 1) == 41.3
    assert round(t["HEI"] * M ** (2 / 15), 1) == 2.4
    assert round(t["HRP"] / L ** (2 / 3), 1) == 0.9
    assert round(t["HEP"] / (M ** (-1 / 12) * L**0.75), 2) == 1.25
    assert t["H00"] == 1.8


@pytest.mark.parametrize("M, L", [(5.0, 0.0), (20.0, 10.0), (300.0, 15.0), (2000.0, 2.0)])
def test_gamma1_equal_one_returns_the_smooth_fits(M, L):
    assert fits.moes_line_central(M, L, 1.0) == fits.moes_line_central(M, L)
    for th in (0.25, 1.0, 4.0):
        assert fits.nijenbanning_central(M, L, th, 1.0) == fits.nijenbanning_central(M, L, th)


@pytest.mark.parametrize("g1", [1.0, 1.3, 3.0, 12.0, 80.0])
@pytest.mark.parametrize("M, L", [(2.0, 1.0), (50.0, 10.0), (1000.0, 20.0)])
def test_gamma1_line_form_equals_smooth_fit_with_substituted_groups(M, L, g1):
    # P -> P/g1, E' -> E'/g1 gives M -> M g1^-1/2, L -> L g1^-3/4, H -> H g1^-1/2 (4.9-4.10)
    expect = math.sqrt(g1) * fits.moes_line_central(M * g1**-0.5, L * g1**-0.75)
    assert fits.moes_line_central(M, L, g1) == pytest.approx(expect, rel=1e-12)


@pytest.mark.parametrize("g1", [1.0, 1.3, 3.0, 12.0, 80.0])
@pytest.mark.parametrize("M, L, th", [(5.0, 2.5, 1.0), (100.0, 10.0, 0.25), (800.0, 20.0, 4.0)])
def test_gamma1_point_form_equals_smooth_fit_with_substituted_groups(M, L, th, g1):
    # point: M -> M g1^-3/4, L -> L g1^-3/4, H -> H g1^-1/2
    expect = math.sqrt(g1) * fits.nijenbanning_central(M * g1**-0.75, L * g1**-0.75, th)
    assert fits.nijenbanning_central(M, L, th, g1) == pytest.approx(expect, rel=1e-12)


def test_moes_line_fit_asymptotes():
    # rigid-isoviscous: Hc -> HRI = 3/M at small M, L = 0 ; elastic-isoviscous HEI at large M, L = 0
    assert fits.moes_line_central(1e-4, 0.0) == pytest.approx(3e4, rel=1e-6)
    assert fits.moes_line_central(1e6, 0.0) == pytest.approx(2.621 * 1e6**-0.2, rel=1e-3)
    # elastic-piezoviscous dominates at large M and L
    M, L = 1e5, 25.0
    assert fits.moes_line_central(M, L) == pytest.approx(1.311 * M**-0.125 * L**0.75, rel=0.05)


def test_fits_are_vectorised():
    M = np.array([10.0, 100.0, 1000.0])
    out = fits.moes_line_central(M, 10.0)
    assert out.shape == (3,)
    assert out[0] == pytest.approx(fits.moes_line_central(10.0, 10.0))
    grid = fits.nijenbanning_central(M[:, None], np.array([0.0, 5.0])[None, :])
    assert grid.shape == (3, 2)


@pytest.mark.parametrize(
    "kwargs, match",
    [({"M": -1.0, "L": 1.0}, "M ="), ({"M": 1.0, "L": -1.0}, "L ="), ({"M": 1.0, "L": 1.0, "gamma1": 0.5}, "gamma1")],
)
def test_fit_bad_input_names_the_parameter(kwargs, match):
    with pytest.raises(InputError, match=match):
        fits.moes_line_central(**kwargs)
