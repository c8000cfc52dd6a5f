"""Lubricant property functions compiled for the thermal kernels (thesis 3.2.1.7-3.2.1.10:
Roelands (2.6), Dowson-Higginson with temperature (3.10) and its thermal expansivity, conductivity (3.12),
specific heat (3.13)).

The reference implementations live in :class:`ehl_multigrid.model.lubricant.Lubricant`; these are the
same formulas as scalar numba functions so the inner loops can call them. The tests check both
paths agree at known points. Temperatures in degC, pressures in Pa.

The oil is passed to the kernels as a float array, :func:`oil_params`, with the layout
``OIL_FIELDS``.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ehl_multigrid.model.constants import DH_A, DH_B, ETA_INF, P_R
from ehl_multigrid.model.lubricant import Lubricant

#: Layout of the float array handed to the kernels.
OIL_FIELDS = (
    "eta0", "T0", "z", "S0", "rho0", "T_rho", "alpha_T", "cp0", "T_cp0", "c_cp", "k0", "tau0", "G",
)
I_ETA0, I_T0, I_Z, I_S0, I_RHO0, I_TRHO, I_ALPHAT, I_CP0, I_TCP0, I_CCP, I_K0, I_TAU0, I_G = range(13)

#: Roelands' temperature term ((T0 + 135)/(T + 135))^S0 needs T > -135 degC.
T_ROELANDS_MIN = -135.0


def oil_params(lub: Lubricant, G: float | None = None) -> np.ndarray:
    """Pack a :class:`Lubricant` into the kernels' float array (``G`` overrides the shear modulus)."""
    vals = [float(getattr(lub, f)) for f in OIL_FIELDS]
    if G is not None:
        vals[I_G] = float(G)
    return np.array(vals, dtype=np.float64)


@njit(cache=True)
def roelands(p: float, T: float, oil: np.ndarray) -> float:
    """Roelands viscosity (2.6) [Pa s]: ``eta_inf (eta0/eta_inf)^[(1+p/pr)^z ((T0+135)/(T+135))^S0]``."""
    return roelands_at(roelands_pressure_term(p, oil), roelands_log_ratio(oil), T, oil)


@njit(cache=True)
def roelands_pressure_term(p: float, oil: np.ndarray) -> float:
    """The pressure factor ``(1 + p/pr)^z`` of (2.6) (p < 0 read as 0); constant along a
    station's film, so the marching kernels evaluate it once per station."""
    pp = p if p > 0.0 else 0.0
    return (1.0 + pp / P_R) ** oil[I_Z]


@njit(cache=True)
def roelands_log_ratio(oil: np.ndarray) -> float:
    """``ln(eta0/eta_inf)`` of (2.6)."""
    return math.log(oil[I_ETA0] / ETA_INF)


@njit(cache=True)
def roelands_at(pressure_term: float, log_ratio: float, T: float, oil: np.ndarray) -> float:
    """Roelands viscosity (2.6) [Pa s] from :func:`roelands_pressure_term` and
    :func:`roelands_log_ratio` (the same floating-point operations as :func:`roelands`)."""
    expo = pressure_term * ((oil[I_T0] + 135.0) / (T + 135.0)) ** oil[I_S0]
    return ETA_INF * math.exp(log_ratio * expo)


@njit(cache=True)
def density(p: float, T: float, oil: np.ndarray) -> float:
    """Density with temperature (3.10) [kg/m^3]."""
    return density_at(density_pressure_term(p, oil), T, oil)


@njit(cache=True)
def density_pressure_term(p: float, oil: np.ndarray) -> float:
    """The Dowson-Higginson factor ``1 + B p/(A + p)`` of (3.10) (p < 0 read as 0)."""
    pp = p if p > 0.0 else 0.0
    return 1.0 + DH_B * pp / (DH_A + pp)


@njit(cache=True)
def density_at(pressure_term: float, T: float, oil: np.ndarray) -> float:
    """Density (3.10) [kg/m^3] from :func:`density_pressure_term` (same operations as
    :func:`density`)."""
    return oil[I_RHO0] * (1.0 - oil[I_ALPHAT] * (T - oil[I_TRHO])) * pressure_term


@njit(cache=True)
def expansivity(T: float, oil: np.ndarray) -> float:
    """Volumetric thermal expansivity ``-(1/rho) (d rho/d T)_p`` [1/K] of the density (3.10),
    ``alpha_T / (1 - alpha_T (T - T_rho))`` (the Dowson-Higginson pressure factor (2.7) cancels)."""
    return oil[I_ALPHAT] / (1.0 - oil[I_ALPHAT] * (T - oil[I_TRHO]))


@njit(cache=True)
def specific_heat(T: float, oil: np.ndarray) -> float:
    """Specific heat (3.13) ``cp0 + c_cp (T - T_cp0)`` [J/(kg degC)]."""
    return oil[I_CP0] + oil[I_CCP] * (T - oil[I_TCP0])


@njit(cache=True)
def conductivity(p: float, oil: np.ndarray) -> float:
    """Mineral-oil conductivity (3.12) ``k0 (0.56 + 0.44 sqrt(1 + 2e-8 p))`` [W/(m degC)]."""
    pp = p if p > 0.0 else 0.0
    return oil[I_K0] * (0.56 + 0.44 * math.sqrt(1.0 + 2e-8 * pp))
