"""Dimensionless viscosity and density of every EHL solver (line, point, Newton path).

``eta_bar = eta/eta0`` and ``rho_bar = rho/rho0`` as functions of ``P = p/pmax``:

* Roelands (2.6) at the inlet temperature:
  ``ln eta_bar = ln(eta0/eta_inf) [(1 + P pmax/p0)^z - 1]``;
* Barus (2.4): ``ln eta_bar = alpha_bar P`` with ``alpha_bar = alpha pmax``;
* Dowson-Higginson (2.7): ``rho_bar = 1 + 0.34615 p/(0.59263e9 + p)``;
* incompressible: ``rho_bar = 1``.

The parameters are packed in a small float array (:func:`pack`) read by numba kernels; the
scalar functions are inlined into the contacts' kernels, :func:`log_derivatives` serves
whole arrays.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..model.constants import DH_A, DH_B

VISCOSITY = ("roelands", "barus")
DENSITY = ("dowson-higginson", "incompressible")

# indices into the packed parameter array
_VISC, _LNR, _Z, _PM_P0, _ABAR, _DENS, _PM_A, _B = range(8)


def pack(viscosity: str, density: str, lnr: float, z: float, pmax_over_p0: float,
         alpha_bar: float, pmax: float) -> np.ndarray:
    """Parameter array for :func:`log_viscosity` and :func:`density`.

    ``lnr = ln(eta0/eta_inf)``, ``z`` the Roelands index, ``pmax_over_p0 = pmax/p0``,
    ``alpha_bar = alpha pmax``, ``pmax`` [Pa] (for Dowson-Higginson).
    """
    par = np.zeros(8)
    par[_VISC] = 0.0 if viscosity == "roelands" else 1.0
    par[_LNR], par[_Z], par[_PM_P0], par[_ABAR] = lnr, z, pmax_over_p0, alpha_bar
    par[_DENS] = 0.0 if density == "dowson-higginson" else 1.0
    par[_PM_A], par[_B] = pmax / DH_A, DH_B
    return par


@njit(cache=True)
def log_viscosity(P: float, par: np.ndarray) -> tuple[float, float]:
    """``(ln eta_bar, d ln eta_bar / dP)`` at dimensionless pressure ``P`` (negative -> 0)."""
    Pp = P if P > 0.0 else 0.0
    if par[0] == 0.0:
        c = par[3]
        base = 1.0 + Pp * c
        z = par[2]
        bz = base**z
        return par[1] * (bz - 1.0), par[1] * z * c * bz / base
    return par[4] * Pp, par[4]


@njit(cache=True)
def density(P: float, par: np.ndarray) -> tuple[float, float]:
    """``(rho_bar, d rho_bar / dP)`` at dimensionless pressure ``P`` (negative -> 0)."""
    if par[5] != 0.0:
        return 1.0, 0.0
    Pp = P if P > 0.0 else 0.0
    c = par[6]
    d = 1.0 + Pp * c
    return 1.0 + par[7] * Pp * c / d, par[7] * c / (d * d)


@njit(cache=True)
def log_derivatives(P: np.ndarray, par: np.ndarray, dlr: np.ndarray, dle: np.ndarray) -> None:
    """Fill ``d ln(rho_bar)/dP`` and ``d ln(eta_bar)/dP`` for every entry of ``P`` (any shape)."""
    Pf, a, b = P.ravel(), dlr.ravel(), dle.ravel()
    for k in range(Pf.shape[0]):
        r, dr = density(Pf[k], par)
        a[k] = dr / r
        b[k] = log_viscosity(Pf[k], par)[1]
