"""Property functions of the thermal kernels (thesis 2.6, 3.10, 3.12, 3.13)."""

import math

import numpy as np
import pytest

from ehl_multigrid.model.lubricant import HVI160, T9
from thermal.properties import conductivity, density, oil_params, roelands, specific_heat


@pytest.mark.parametrize("lub", [T9, HVI160], ids=["T9", "HVI-160"])
def test_kernel_properties_equal_core_lubricant(lub):
    oil = oil_params(lub)
    for p in (0.0, 1e8, 5e8, 1.6e9, 3e9):
        for T in (20.0, 60.0, 150.0):
            assert roelands(p, T, oil) == pytest.approx(lub.viscosity(p, T), rel=1e-12)
            assert density(p, T, oil) == pytest.approx(lub.density(p, T), rel=1e-12)
            assert specific_heat(T, oil) == pytest.approx(lub.specific_heat(T), rel=1e-12)
        assert conductivity(p, oil) == pytest.approx(lub.conductivity(p), rel=1e-12)


def test_properties_at_reference_points_of_appendix_a():
    oil = oil_params(T9)
    # viscosity at T0 = 40 degC, p = 0 is eta0 = 88e-4 Pa s (2.6)
    assert roelands(0.0, 40.0, oil) == pytest.approx(88e-4, rel=1e-12)
    # Roelands by hand at p = pr = 1.962e8 Pa, 40 degC: eta_inf (eta0/eta_inf)^(2^z)
    assert roelands(1.962e8, 40.0, oil) == pytest.approx(6.31e-5 * (88e-4 / 6.31e-5) ** (2.0**0.87), rel=1e-12)
    # density (3.10): rho0 at T_rho = 15 degC and p = 0; DH factor 1.34615 as p -> inf
    assert density(0.0, 15.0, oil) == pytest.approx(869.0, rel=1e-12)
    assert density(1e15, 15.0, oil) == pytest.approx(869.0 * 1.34615, rel=1e-5)
    assert density(0.0, 115.0, oil) == pytest.approx(869.0 * (1 - 7.9e-4 * 100.0), rel=1e-12)
    # specific heat (3.13): 2020 at 45 degC, slope 4.1 J/kg/degC^2
    assert specific_heat(45.0, oil) == pytest.approx(2020.0)
    assert specific_heat(145.0, oil) == pytest.approx(2020.0 + 410.0)
    # conductivity (3.12): k0 at p = 0; k0 (0.56 + 0.44 sqrt(21)) at 1 GPa
    assert conductivity(0.0, oil) == pytest.approx(0.135)
    assert conductivity(1e9, oil) == pytest.approx(0.135 * (0.56 + 0.44 * math.sqrt(21.0)))


def test_viscosity_falls_with_temperature_and_rises_with_pressure():
    oil = oil_params(T9)
    T = np.linspace(20, 200, 10)
    eta = [roelands(1e9, t, oil) for t in T]
    assert np.all(np.diff(eta) < 0)
    assert roelands(2e9, 60.0, oil) > roelands(1e9, 60.0, oil) > roelands(0.0, 60.0, oil)
