"""Lubricant properties against hand calculations (thesis 2.4, 2.6, 2.7, 3.10-3.13)."""

import math

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.lubricant import (
    ETA_INF,
    HVI160,
    P_R,
    T9,
    density_ratio_dh,
    lubricant_preset,
)


def test_roelands_returns_eta0_at_reference_temperature_and_zero_pressure():
    assert T9.viscosity(0.0, T9.T0) == pytest.approx(88e-4, rel=1e-14)
    assert HVI160.viscosity(0.0) == pytest.approx(90e-3, rel=1e-14)


def test_roelands_pressure_term_matches_hand_calculation():
    # (2.6) at p = 1 GPa, T = T0: eta_inf (eta0/eta_inf)^((1 + p/pr)^z)
    p = 1e9
    expo = (1 + p / 1.962e8) ** 0.87
    hand = 6.31e-5 * (88e-4 / 6.31e-5) ** expo
    assert T9.viscosity(p, 40.0) == pytest.approx(hand, rel=1e-12)


def test_roelands_temperature_term_matches_hand_calculation():
    # ((T0 + 135)/(T + 135))^S0 multiplies the exponent: at 60 degC, p = 0
    expo = ((40 + 135) / (60 + 135)) ** 1.2
    hand = 6.31e-5 * (88e-4 / 6.31e-5) ** expo
    assert T9.eta_at(60.0) == pytest.approx(hand, rel=1e-12)
    assert T9.eta_at(60.0) < T9.eta0


def test_alpha_from_z_is_the_roelands_slope_at_zero_pressure():
    alpha = T9.alpha()
    assert alpha == pytest.approx(0.87 * (math.log(88e-4) - math.log(ETA_INF)) / P_R, rel=1e-14)
    # d ln(eta)/dp at p = 0 by finite difference equals alpha
    dp = 1e3
    slope = (math.log(T9.viscosity(dp)) - math.log(T9.viscosity(0.0))) / dp
    assert slope == pytest.approx(alpha, rel=1e-4)


def test_alpha_override_sets_z_so_alpha_is_reproduced():
    oil = T9.with_changes(eta0=20.2e-3, alpha=2e-8)
    assert oil.alpha() == pytest.approx(2e-8, rel=1e-12)


def test_dowson_higginson_density_limits_and_rounded_form():
    assert density_ratio_dh(0.0) == 1.0
    # large-pressure limit 1.34615; the rounded form (0.59e9 + 1.34p)/(0.59e9 + p) differs at most
    # by the ratio of the two limits, 1.34615/1.34 - 1 = 0.46 %
    assert density_ratio_dh(1e15) == pytest.approx(1.34615, rel=1e-5)
    p = np.array([0.5e9, 1e9, 2e9])
    rounded = (0.59e9 + 1.34 * p) / (0.59e9 + p)
    np.testing.assert_allclose(density_ratio_dh(p), rounded, rtol=1.34615 / 1.34 - 1)


def test_density_temperature_term_3_10():
    # rho0 (1 - alpha_T (T - T_rho)) at ambient pressure
    assert T9.density(0.0, 15.0) == pytest.approx(869.0)
    assert T9.density(0.0, 115.0) == pytest.approx(869.0 * (1 - 7.9e-4 * 100))


def test_conductivity_and_specific_heat_at_known_points():
    assert T9.conductivity(0.0) == pytest.approx(0.135)
    # (3.12) at 1 GPa: k0 (0.56 + 0.44 sqrt(21))
    assert T9.conductivity(1e9) == pytest.approx(0.135 * (0.56 + 0.44 * math.sqrt(21.0)))
    assert T9.specific_heat(45.0) == pytest.approx(2020.0)
    assert T9.specific_heat(145.0) == pytest.approx(2020.0 + 4.1 * 100)


def test_eyring_stress_and_shear_rate_are_inverse():
    eta, rate = 0.1, 1e7
    tau = T9.eyring_stress(eta, rate)
    assert T9.tau0 / eta * math.sinh(tau / T9.tau0) == pytest.approx(rate, rel=1e-12)
    # Newtonian at low stress
    assert T9.eyring_stress(eta, 1.0) == pytest.approx(eta * 1.0, rel=1e-9)


def test_unknown_oil_names_the_known_presets():
    with pytest.raises(InputError, match="HVI-160"):
        lubricant_preset("SAE-30")


def test_invalid_lubricant_value_names_field_and_range():
    with pytest.raises(InputError, match=r"tau0 = -1 Pa .*\(0, inf\)"):
        T9.with_changes(tau0=-1.0)
