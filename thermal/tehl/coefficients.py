"""Across-film coefficients of the generalised Reynolds equation (Yang & Wen 1990; Najji et
al. 1989) for viscosity and density that vary across the film, with the Eyring law of the
thermal layer acting on the flow through the effective viscosity ``eta* = tau / gdot``.

At one station, with ``Z = z/h``, the shear stress ``tau = tau_a + h (dp/dx) Z`` (momentum
(3.4)) and ``du/dz = tau/eta*``::

    A(Z) = int_0^Z dZ'/eta*,   B(Z) = int_0^Z Z' dZ'/eta*
    u(Z) = u1 + h tau_a A(Z) + h^2 (dp/dx) B(Z),   tau_a from u(1) = u2
    q_m  = int_0^h rho u dz = h [u1 R0 + (u2 - u1) RA/A(1)] + h^3 (dp/dx) [RB - B(1) RA/A(1)]

with ``R0 = int rho dZ``, ``RA = int rho A dZ``, ``RB = int rho B dZ``. In Yang & Wen's
notation ``eta_e = 1/A(1)``, ``eta_e' = 1/B(1)``, ``rho_e = R0``, ``rho_e' = eta_e RA``,
``rho_e'' = eta_e' RB``: the Poiseuille coefficient is ``(rho/eta)_e/12 = eta_e rho_e'/eta_e'
- rho_e''`` (here ``RB - B(1) RA/A(1)``, negated) and the Couette mass flux
``rho* u_m = u1 rho_e + (u2 - u1) rho_e'``.

The multilevel operator takes these as two ratios to the isothermal Newtonian values at the
same pressure and the inlet temperature (``rho_iso = rho(p, T_oil)``, ``eta_iso =
eta(p, T_oil)``): the flow factor ``a = (rho/eta)_e / (rho_iso/eta_iso)`` multiplies Venner's
``eps = rho H^3/(eta lambda)`` and the Couette factor ``c = rho*/rho_iso`` multiplies the
wedge density. Both integrals use the cumulative trapezoid rule on the thermal grid's Z nodes
and are divided by the same quadrature of the isothermal Newtonian profile, so a uniform film
at the inlet temperature with no shear thinning gives ``a = c = 1`` exactly.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ehl_multigrid.model.lubricant import Lubricant


def _cumtrapz(f: np.ndarray, dZ: float) -> np.ndarray:
    """Cumulative trapezoid along the last axis, starting at 0."""
    out = np.zeros_like(f)
    out[..., 1:] = np.cumsum(0.5 * dZ * (f[..., 1:] + f[..., :-1]), axis=-1)
    return out


def _trapz(f: np.ndarray, dZ: float) -> np.ndarray:
    return np.trapezoid(f, dx=dZ, axis=-1)


def flux_integrals(inv_eta: np.ndarray, rho: np.ndarray, u1: float, u2: float) -> tuple[np.ndarray, np.ndarray]:
    """Poiseuille and Couette mass-flux coefficients per station.

    ``inv_eta``, ``rho`` : (station, Z node) ``1/eta*`` [1/(Pa s)] and density [kg/m^3].
    Returns ``(K, C)``: ``q_m = h C - h^3 K dp/dx`` with ``K = B(1) RA/A(1) - RB`` [kg/(m^3 Pa s)]
    and ``C = u1 R0 + (u2 - u1) RA/A(1)`` [kg/(m^2 s)].
    """
    nzp = inv_eta.shape[-1]
    dZ = 1.0 / (nzp - 1)
    Z = np.linspace(0.0, 1.0, nzp)
    A = _cumtrapz(inv_eta, dZ)
    B = _cumtrapz(Z * inv_eta, dZ)
    R0 = _trapz(rho, dZ)
    RA = _trapz(rho * A, dZ)
    RB = _trapz(rho * B, dZ)
    ratio = RA / A[..., -1]
    K = B[..., -1] * ratio - RB
    C = u1 * R0 + (u2 - u1) * ratio
    return K, C


def effective_inverse_viscosity(eta: np.ndarray, tau: np.ndarray, tau0: float) -> np.ndarray:
    """``1/eta* = gdot/tau = sinh(tau/tau0) / (eta tau/tau0)`` [1/(Pa s)] (Eyring (2.36)); the
    Newtonian ``1/eta`` where ``tau = 0``."""
    s = np.asarray(tau, dtype=float) / tau0
    small = np.abs(s) < 1e-4
    ss = np.where(small, 1.0, s)
    ratio = np.where(small, 1.0 + s * s / 6.0, np.sinh(np.clip(ss, -700.0, 700.0)) / ss)
    return ratio / eta


def film_factors(p: np.ndarray, T: np.ndarray, tau: np.ndarray, lubricant: Lubricant, T_oil: float,
                 u1: float, u2: float, shear_thinning: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Flow factor ``a`` and Couette factor ``c`` per station (see module docstring).

    ``p`` [Pa] per station; ``T`` [degC] and ``tau`` [Pa] on (station, Z node).
    ``shear_thinning=False`` uses the Newtonian ``eta(p, T)`` (Eyring off in the flow).
    """
    a, c, _ = _factors_and_fluidity(p, T, tau, lubricant, T_oil, u1, u2, shear_thinning)
    return a, c


def _factors_and_fluidity(p: np.ndarray, T: np.ndarray, tau: np.ndarray, lubricant: Lubricant, T_oil: float,
                          u1: float, u2: float, shear_thinning: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`film_factors` and the fluidity ``1/eta*`` on (station, Z node) they integrate."""
    P2 = np.repeat(np.asarray(p, dtype=float)[:, None], T.shape[1], axis=1)
    eta = lubricant.viscosity(P2, T)
    rho = lubricant.density(P2, T)
    inv = effective_inverse_viscosity(eta, tau, lubricant.tau0) if shear_thinning else 1.0 / eta
    K, C = flux_integrals(inv, rho, u1, u2)
    eta_i = lubricant.viscosity(P2, np.full_like(T, T_oil))
    rho_i = lubricant.density(P2, np.full_like(T, T_oil))
    K0, C0 = flux_integrals(1.0 / eta_i, rho_i, u1, u2)
    return K / K0, C / C0, inv


def solution_factors_and_response(sol: Any, env: Any, shear_thinning: bool = True
                                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`film_factors` of a thermal solution ``sol`` (:class:`~thermal.line.ThermalLineSolution`)
    in the surroundings ``env`` (:class:`~thermal.line.Surroundings`: oil, inlet temperature,
    speeds), and the :func:`flow_response` a multilevel solve takes with them, from one
    evaluation of the film's viscosity."""
    a, c, inv = _factors_and_fluidity(sol.profile.p, sol.T, sol.tau, env.lubricant, env.T_oil, env.u1,
                                      env.u2, shear_thinning)
    w = _response(inv, sol.tau, env.lubricant.tau0) if shear_thinning else np.zeros(a.shape)
    return a, c, flow_response(a, w)


def viscosity_response(sol: Any, env: Any, shear_thinning: bool = True) -> np.ndarray:
    """Per station, ``w = 1 - d ln eta_e / d ln eta`` at the station's shear: how much less
    the flow's effective viscosity follows a change of the Newtonian viscosity (of the
    pressure) than the isothermal operator assumes. 0 where the film is Newtonian; towards 1
    where the Eyring stress ``|tau| >> tau0``: the secant viscosity ``eta* = tau/gdot`` at a
    given shear rate responds as ``d ln eta*/d ln eta = tanh(t)/t`` (``t = |tau|/tau0``,
    from (2.36)), 1/58 at the 2.5 GPa of a traction fluid at 5 % slip. Averaged over the film
    with the fluidity ``1/eta*`` that weights the flux integrals.

    The multilevel solve of one outer iteration keeps the flow factor ``a`` frozen; with
    ``w`` it keeps ``a`` times ``(eta(p)/eta(p_ref))^w`` instead, so that where the effective
    viscosity hardly depends on the pressure, a pressure change inside the solve does not
    scale the flow by ``exp(alpha dp)`` (thermal.tehl.point.FactorPointHierarchy). The
    outer iteration's fixed point is the same: there ``p = p_ref``. The solve takes it in full
    where ``a`` reaches :data:`RESPONSE_FROM` and not at all at ``a = 1`` (:func:`flow_response`;
    why, measured: docs/thermal.md, "The flow's viscosity response")."""
    if not shear_thinning:
        return np.zeros(sol.T.shape[0])
    p = np.repeat(np.asarray(sol.profile.p, dtype=float)[:, None], sol.T.shape[1], axis=1)
    lub = env.lubricant
    return _response(effective_inverse_viscosity(lub.viscosity(p, sol.T), sol.tau, lub.tau0), sol.tau, lub.tau0)


def _response(inv: np.ndarray, tau: np.ndarray, tau0: float) -> np.ndarray:
    """:func:`viscosity_response` from the fluidity ``inv`` and the stress ``tau`` on (station,
    Z node)."""
    t = np.abs(np.asarray(tau, dtype=float)) / tau0
    resp = np.where(t < 1e-4, 1.0, np.tanh(t) / np.maximum(t, 1e-300))
    dZ = 1.0 / (inv.shape[-1] - 1)
    return np.clip(1.0 - _trapz(resp * inv, dZ) / _trapz(inv, dZ), 0.0, 1.0)


#: the flow factor from which a multilevel solve takes the flow's viscosity response in full
#: (:func:`viscosity_response`); the Eyring films where the frozen factor failed reach 1e12-1e24
RESPONSE_FROM = 1e3


def flow_response(a: np.ndarray, w: np.ndarray) -> np.ndarray:
    """The viscosity response a multilevel solve takes: ``w`` times ``ln a / ln RESPONSE_FROM``
    clipped to [0, 1] (:func:`viscosity_response`, :data:`RESPONSE_FROM`)."""
    return w * np.clip(np.log(np.maximum(a, 1.0)) / math.log(RESPONSE_FROM), 0.0, 1.0)


#: largest change of ``ln eps`` the viscosity response makes (a factor e^5 = 148): the response
#: is the flow's slope at the pressure of the start, which far from it no longer holds
RESPONSE_SHIFT_MAX = 5.0


def response_multiplier(w: np.ndarray, log_ratio: np.ndarray) -> np.ndarray:
    """``exp(w ln(k_ref/k))``, the factor on ``eps`` of the viscosity response (``k = rho/eta``
    at the current and the start pressure), its exponent clipped to :data:`RESPONSE_SHIFT_MAX`."""
    with np.errstate(invalid="ignore"):
        x = np.where(w > 0.0, w * log_ratio, 0.0)  # (no response where w = 0, even at ln ratio = inf)
    x = np.nan_to_num(x, nan=0.0, posinf=RESPONSE_SHIFT_MAX, neginf=-RESPONSE_SHIFT_MAX)
    return np.exp(np.clip(x, -RESPONSE_SHIFT_MAX, RESPONSE_SHIFT_MAX))

