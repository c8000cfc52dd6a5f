"""Hertz reference solutions (line, circular, exact elliptic) against the thesis and analytic identities."""

import math

import numpy as np
import pytest
from scipy import integrate

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.hertz import (
    hertz_circular,
    hertz_elliptic,
    hertz_line,
    hertz_point,
    load_for_pmax_line,
    load_for_pmax_point,
)
from ehl_multigrid.model.solids import STEEL, gw_modulus, reduced_modulus, reduced_modulus_of


def test_line_contact_page_63_gives_0_30_gpa():
    # thesis page 63: P = 500 N, B = 0.01 m, R = 0.02 m, E' = 231 GPa -> pmax ~ 0.3 GPa
    hz = hertz_line(500.0, 0.01, 0.02, 231e9)
    assert hz.pmax == pytest.approx(0.30e9, rel=0.02)
    assert hz.pmax == pytest.approx(hz.b * 231e9 / (4 * 0.02), rel=1e-12)  # pmax = E' b / (4R)
    assert hz.mean_pressure == pytest.approx(math.pi / 4 * hz.pmax, rel=1e-12)


def test_point_contact_appendix_d_gives_1_gpa():
    hz = hertz_circular(42.8, 0.01032, 2.3e11)
    assert hz.pmax == pytest.approx(1.0e9, rel=0.02)
    assert hz.pmax == pytest.approx(2.3e11 * hz.a / (math.pi * 0.01032), rel=1e-12)
    assert hz.mean_pressure == pytest.approx(2 / 3 * hz.pmax, rel=1e-12)


def test_line_contact_fig_3_8_gives_1_58_gpa():
    # appendix C, 42400 N: R = 0.0381/2, B = 0.032 m
    hz = hertz_line(42400.0, 0.032, 0.0381 / 2, 2.3e11)
    assert hz.pmax == pytest.approx(1.58e9, rel=0.01)


def test_elliptic_reduces_to_circular():
    c = hertz_circular(100.0, 0.01, 2.3e11)
    e = hertz_elliptic(100.0, 0.01, 0.01 * (1 + 1e-7), 2.3e11)
    assert e.a == pytest.approx(c.a, rel=1e-6)
    assert e.pmax == pytest.approx(c.pmax, rel=1e-6)


@pytest.mark.parametrize("theta", [0.05, 0.25, 0.5, 2.0, 4.0, 20.0])
def test_elliptic_pressure_integrates_to_load_and_is_symmetric_in_theta(theta):
    Rx = 0.01
    e = hertz_elliptic(50.0, Rx, Rx / theta, 2.3e11)
    assert 2 * math.pi / 3 * e.pmax * e.a * e.b == pytest.approx(50.0, rel=1e-12)
    # swapping Rx and Ry swaps the semi-axes
    s = hertz_elliptic(50.0, Rx / theta, Rx, 2.3e11)
    assert (s.a, s.b) == pytest.approx((e.b, e.a), rel=1e-9)


@pytest.mark.parametrize("theta", [0.1, 0.3, 3.0])
def test_elliptic_displacement_matches_the_gap_inside_the_contact(theta):
    """Independent check: the Boussinesq displacement of the Hertz pressure,
    u(x, y) = (2/(pi E')) int p / r dA, must equal delta - x^2/(2Rx) - y^2/(2Ry) inside."""
    Rx, E = 0.01, 2.3e11
    Ry = Rx / theta
    e = hertz_elliptic(80.0, Rx, Ry, E)

    def u(x0, y0):
        # polar coordinates around (x0, y0) remove the 1/r singularity
        def radial(phi):
            c, s = math.cos(phi), math.sin(phi)
            # distance to the ellipse boundary along the ray: solve quadratic
            A = (c / e.a) ** 2 + (s / e.b) ** 2
            B = 2 * (x0 * c / e.a**2 + y0 * s / e.b**2)
            C = (x0 / e.a) ** 2 + (y0 / e.b) ** 2 - 1
            rmax = (-B + math.sqrt(B * B - 4 * A * C)) / (2 * A)

            def f(r):
                x, y = x0 + r * c, y0 + r * s
                return e.pmax * math.sqrt(max(0.0, 1 - (x / e.a) ** 2 - (y / e.b) ** 2))

            return integrate.quad(f, 0, rmax, epsabs=0, epsrel=1e-10)[0]

        return 2 / (math.pi * E) * integrate.quad(radial, 0, 2 * math.pi, epsabs=0, epsrel=1e-9, limit=200)[0]

    u0 = u(0.0, 0.0)
    for fx, fy in [(0.5, 0.0), (0.0, 0.5), (0.4, 0.4)]:
        x, y = fx * e.a, fy * e.b
        gap_change = x * x / (2 * Rx) + y * y / (2 * Ry)
        assert u0 - u(x, y) == pytest.approx(gap_change, rel=1e-6)


def test_elliptic_axis_ratio_close_to_hamrock_brewe_approximation():
    # k = a_y/a_x ~ 1.0339 (Ry/Rx)^0.636 within a few per cent (approximation, not an oracle)
    for ratio in (2.0, 5.0, 10.0):
        e = hertz_elliptic(10.0, 0.01, 0.01 * ratio, 2.3e11)
        assert e.b / e.a == pytest.approx(1.0339 * ratio**0.636, rel=0.03)


def test_load_for_pmax_inverts_hertz():
    P = load_for_pmax_line(1.2e9, 0.01, 0.02, 231e9)
    assert hertz_line(P, 0.01, 0.02, 231e9).pmax == pytest.approx(1.2e9, rel=1e-12)
    P = load_for_pmax_point(1.93e9, 0.01, 0.03, 2.3e11)
    assert hertz_point(P, 0.01, 0.03, 2.3e11).pmax == pytest.approx(1.93e9, rel=1e-10)


def test_reduced_modulus_and_gw_convention():
    E = reduced_modulus_of(STEEL, STEEL)
    assert E == pytest.approx(2.1e11 / (1 - 0.09), rel=1e-12)
    assert reduced_modulus(2e11, 0.3, 1e30, 0.0) == pytest.approx(2 * 2e11 / 0.91, rel=1e-9)  # rigid partner
    assert gw_modulus(E) == pytest.approx(E / 2)


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda: hertz_line(0.0, 0.01, 0.02, 2.3e11), "load"),
        (lambda: hertz_line(-5.0, 0.01, 0.02, 2.3e11), "load"),
        (lambda: hertz_circular(10.0, -0.01, 2.3e11), "R"),
        (lambda: reduced_modulus(2e11, 0.5, 2e11, 0.3), "nu1"),
    ],
)
def test_bad_hertz_input_names_the_field(call, field):
    with pytest.raises(InputError, match=field):
        call()


def test_hertz_pressure_profiles_integrate_to_load():
    from ehl_multigrid.model.hertz import hertz_pressure_line

    hz = hertz_line(1000.0, 0.01, 0.02, 2.3e11)
    x = np.linspace(-hz.b, hz.b, 20001)
    assert integrate.trapezoid(hertz_pressure_line(x, hz.b, hz.pmax), x) * 0.01 == pytest.approx(1000.0, rel=1e-4)
