"""Greenwood-Williamson functions F_j (2.45), asperity pressure (4.18)-(4.19), plasticity (2.48)."""

import math

import numpy as np
import pytest
from scipy import integrate, special

from ehl_multigrid.model.errors import InputError
from mixed.gw import (
    asperity_pressure,
    gw_f,
    gw_f1,
    gw_f32,
    gw_f_inverse,
    gw_log_f,
    plasticity_index,
)


def f_quadrature(j, lam):
    """Independent reference: adaptive quadrature of (2.45), with phi(lam) factored out for
    lam > 0 so that the far tail keeps its relative accuracy."""
    if lam >= 0:
        val, _ = integrate.quad(lambda t: t**j * math.exp(-lam * t - 0.5 * t * t), 0, np.inf,
                                epsabs=0, epsrel=1e-13, limit=400)
        return val * math.exp(-0.5 * lam * lam) / math.sqrt(2 * math.pi)
    f = lambda s: (s - lam) ** j * math.exp(-0.5 * s * s) / math.sqrt(2 * math.pi)  # noqa: E731
    a, _ = integrate.quad(f, lam, 0.0, epsabs=0, epsrel=1e-13, limit=400)
    b, _ = integrate.quad(f, 0.0, np.inf, epsabs=0, epsrel=1e-13, limit=400)
    return a + b


LAMS = np.linspace(-10.0, 8.0, 37)


@pytest.mark.parametrize("j", [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.7])
def test_f_j_matches_quadrature_to_1e_10_from_minus_10_to_8(j):
    ref = np.array([f_quadrature(j, lam) for lam in LAMS])
    got = gw_f(j, LAMS)
    assert np.max(np.abs(got / ref - 1.0)) < 1e-10


def test_closed_form_f1_agrees_with_the_general_routine_and_quadrature():
    lam = np.linspace(-10.0, 8.0, 73)
    assert np.allclose(gw_f1(lam), gw_f(1.0, lam), rtol=1e-12, atol=0)
    assert gw_f1(6.5) == pytest.approx(f_quadrature(1.0, 6.5), rel=1e-11)


@pytest.mark.parametrize("j", [0.0, 1.0, 1.5, 3.0])
def test_f_j_value_at_zero_is_the_half_moment(j):
    # F_j(0) = E[s^j; s > 0] = 2^(j/2) Gamma((j+1)/2) / (2 sqrt(pi))
    exact = 2 ** (j / 2) * math.gamma((j + 1) / 2) / (2 * math.sqrt(math.pi))
    assert gw_f(j, 0.0) == pytest.approx(exact, rel=1e-14)


@pytest.mark.parametrize("j", [0.5, 1.5, 2.5])
def test_far_positive_tail_follows_the_asymptote_in_log_scale(j):
    # F_j ~ Gamma(j+1) phi(lam) lam^-(j+1) [1 - (j+1)(j+2)/(2 lam^2) + (j+1)(j+2)(j+3)(j+4)/(8 lam^4)]
    for lam in (30.0, 100.0, 1e4):
        a = (j + 1) * (j + 2) / (2 * lam**2)
        b = (j + 1) * (j + 2) * (j + 3) * (j + 4) / (8 * lam**4)
        log_asym = (math.lgamma(j + 1) - 0.5 * lam * lam - 0.5 * math.log(2 * math.pi)
                    - (j + 1) * math.log(lam) + math.log(1 - a + b))
        rel_err_bound = 5 * (j + 5) ** 3 / lam**6  # next term of the series
        assert gw_log_f(j, lam) == pytest.approx(log_asym, abs=rel_err_bound + 1e-14 * abs(log_asym))
    assert gw_f(j, 50.0) == 0.0  # exp(-1250) underflows; the log form does not
    assert np.isfinite(gw_log_f(j, 50.0))


@pytest.mark.parametrize("j", [0.5, 1.5, 2.5])
def test_far_negative_tail_follows_the_moment_expansion(j):
    # F_j(lam) ~ (-lam)^j [1 + C(j,2)/lam^2 + 3 C(j,4)/lam^4], exponentially small remainder
    for lam in (-8.0, -10.0, -20.0):
        c2 = j * (j - 1) / 2
        c4 = j * (j - 1) * (j - 2) * (j - 3) / 24
        c6 = j * (j - 1) * (j - 2) * (j - 3) * (j - 4) * (j - 5) / 720
        series = (-lam) ** j * (1 + c2 / lam**2 + 3 * c4 / lam**4 + 15 * c6 / lam**6)
        assert gw_f(j, lam) == pytest.approx(series, rel=200 * abs(c6) / lam**8 + 1e-13)


def test_recurrence_f_next_equals_j_f_previous_minus_lam_f():
    # integration by parts of (2.45): F_(j+1) = j F_(j-1) - lam F_j
    lam = np.linspace(-10.0, 8.0, 91)
    for j in (0.5, 1.5, 2.0):
        lhs = gw_f(j + 1, lam)
        rhs = j * gw_f(j - 1, lam) - lam * gw_f(j, lam)
        ok = lam < 3  # for lam >> 0 the right side cancels; compare there in absolute terms
        assert np.allclose(lhs[ok], rhs[ok], rtol=1e-11, atol=0)
        assert np.allclose(lhs[~ok], rhs[~ok], rtol=0, atol=1e-13 * np.max(np.abs(lam * gw_f(j, lam))))


def test_inverse_round_trips_over_the_whole_range():
    lam = np.array([-10.0, -3.3, -0.2, 0.0, 1.7, 4.0, 8.0, 20.0])
    back = gw_f_inverse(1.5, gw_f32(lam))
    assert np.allclose(back, lam, rtol=1e-12, atol=1e-12)
    assert gw_f_inverse(0.0, 0.5) == pytest.approx(0.0, abs=1e-13)


def test_vectorised_and_scalar_calls_agree():
    lam = np.linspace(-5, 5, 11).reshape(11, 1)
    arr = gw_f32(lam)
    assert arr.shape == (11, 1)
    assert all(gw_f32(float(x)) == pytest.approx(float(y), rel=1e-15) for x, y in zip(lam.ravel(), arr.ravel(), strict=True))


def test_bad_orders_and_values_raise_input_error():
    with pytest.raises(InputError, match="j"):
        gw_f(-1.5, 0.0)
    with pytest.raises(InputError, match="j"):
        gw_f(25.0, 0.0)
    with pytest.raises(InputError, match="> 0"):
        gw_f_inverse(1.5, -1.0)
    with pytest.raises(InputError, match="< 1"):
        gw_f_inverse(0.0, 1.5)


def test_asperity_pressure_equals_the_direct_gw_integral():
    # (2.44): (2/3) n sqrt(beta) E' int (z - hss)^(3/2) phi_s(z) dz, integrated directly
    n, beta, ss, E = 1e11, 1e-5, 5e-8, 231e9
    hss = 0.4 * ss
    integrand = lambda z: (z - hss) ** 1.5 * math.exp(-0.5 * (z / ss) ** 2) / (ss * math.sqrt(2 * math.pi))  # noqa: E731
    val, _ = integrate.quad(integrand, hss, 12 * ss, epsabs=0, epsrel=1e-12)
    assert asperity_pressure(hss, n, beta, ss, E) == pytest.approx(2 / 3 * n * math.sqrt(beta) * E * val, rel=1e-9)


def test_plasticity_index_reproduces_table_4_3():
    # E' = 230 GPa, E'_GW = E'/2, H' = 5 GPa; thesis values 0.816, 0.58, 0.39, 5.12
    rows = [(0.034e-6, 27e-6, 0.816), (0.029e-6, 46.2e-6, 0.58), (0.018e-6, 61.2e-6, 0.39), (0.27e-6, 5.441e-6, 5.12)]
    for ss, beta, psi in rows:
        assert plasticity_index(230e9, 5e9, ss, beta) == pytest.approx(psi, abs=0.006)


def test_pbdv_representation_agrees_where_scipy_is_accurate():
    # F_j = Gamma(j+1) exp(-lam^2/4) D_(-j-1)(lam) / sqrt(2 pi); scipy's pbdv is good to ~1e-12 for |lam| < 4
    lam = np.linspace(-4, 4, 17)
    d, _ = special.pbdv(-2.5, lam)
    ref = math.gamma(2.5) * np.exp(-lam * lam / 4) * d / math.sqrt(2 * math.pi)
    assert np.allclose(gw_f32(lam), ref, rtol=1e-11)
