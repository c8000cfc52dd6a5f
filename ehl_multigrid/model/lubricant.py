"""Lubricant properties: Roelands and Barus viscosity, Dowson-Higginson density with the
temperature term, conductivity, specific heat and the Eyring law: Roelands (2.6), Barus (2.4),
Dowson-Higginson (2.7) with temperature (3.10), conductivity (3.12), specific heat (3.13),
Eyring (2.36).

All functions take SI units and temperatures in degrees Celsius, as the thesis does, and are
vectorised over numpy arrays.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, fields, replace

import numpy as np

# the Roelands and Dowson-Higginson constants live in .constants; importing them from here
# keeps working
from .constants import DH_A, DH_B, ETA_INF, P_R
from .errors import InputError, reject_unknown_keys, require_positive, require_range

T_MIN_C = -50.0
T_MAX_C = 400.0


#: shear modulus [Pa] from which the Maxwell term is off (the default G = 1e30 means no
#: elasticity)
G_ELASTICITY_OFF = 1e29


@dataclass(frozen=True)
class Lubricant:
    """A lubricant as the thesis describes it (appendices A and B).

    Parameters
    ----------
    name : str
    eta0 : float
        Viscosity at ``T0`` and ambient pressure [Pa s].
    T0 : float
        Reference temperature of ``eta0`` [degC].
    z : float
        Roelands pressure-viscosity index [-].
    S0 : float
        Roelands temperature-viscosity index [-].
    rho0 : float
        Density at ambient pressure and ``T_rho`` [kg/m^3].
    T_rho : float
        Reference temperature of ``rho0`` [degC].
    alpha_T : float
        Thermal expansion coefficient of the density (3.10) [1/degC].
    cp0 : float
        Specific heat at ``T_cp0`` [J/(kg degC)].
    T_cp0 : float
        Reference temperature of ``cp0`` [degC].
    c_cp : float
        Temperature slope of the specific heat, ``Cp = cp0 + c_cp (T - T_cp0)`` [J/(kg degC^2)].
    k0 : float
        Thermal conductivity at ambient pressure [W/(m degC)].
    tau0 : float
        Eyring stress [Pa].
    G : float
        Shear modulus of the Maxwell term (3.3) [Pa]; 1e30 (any value from
        :data:`G_ELASTICITY_OFF` on) switches elasticity off.
    """

    name: str
    eta0: float
    T0: float
    z: float
    S0: float
    rho0: float
    T_rho: float
    alpha_T: float
    cp0: float
    T_cp0: float
    c_cp: float
    k0: float
    tau0: float
    G: float = 1e30

    def __post_init__(self) -> None:
        p = f"lubricant {self.name!r}"
        require_range(f"{p}.eta0", self.eta0, ETA_INF, 1e6, "Pa s", lo_open=True)
        require_range(f"{p}.T0", self.T0, T_MIN_C, T_MAX_C, "degC")
        require_range(f"{p}.z", self.z, 0.0, 3.0, "-", lo_open=True)
        require_range(f"{p}.S0", self.S0, 0.0, 10.0, "-")
        require_range(f"{p}.rho0", self.rho0, 100.0, 5000.0, "kg/m^3")
        require_range(f"{p}.T_rho", self.T_rho, T_MIN_C, T_MAX_C, "degC")
        require_range(f"{p}.alpha_T", self.alpha_T, 0.0, 1e-2, "1/degC")
        require_positive(f"{p}.cp0", self.cp0, "J/(kg degC)")
        require_range(f"{p}.T_cp0", self.T_cp0, T_MIN_C, T_MAX_C, "degC")
        require_range(f"{p}.c_cp", self.c_cp, -100.0, 100.0, "J/(kg degC^2)")
        require_positive(f"{p}.k0", self.k0, "W/(m degC)")
        require_positive(f"{p}.tau0", self.tau0, "Pa")
        require_positive(f"{p}.G", self.G, "Pa")

    # -- viscosity --------------------------------------------------------------------------
    def beta(self, T: float) -> float:
        """Temperature-viscosity coefficient ``-d ln(eta)/dT`` at ambient pressure [1/K], from
        the temperature term of Roelands (2.6):
        ``ln(eta0/eta_inf) S0 (T0 + 135)^S0 / (T + 135)^(S0 + 1)``."""
        return float(np.log(self.eta0 / ETA_INF) * self.S0 * (self.T0 + 135.0) ** self.S0
                     / (float(T) + 135.0) ** (self.S0 + 1.0))

    def eta_at(self, T: float | np.ndarray) -> np.ndarray | float:
        """Ambient-pressure viscosity at temperature ``T`` [degC] (Roelands temperature term) [Pa s]."""
        return self.viscosity(0.0, T)

    def alpha(self, T: float | np.ndarray | None = None) -> np.ndarray | float:
        """Pressure-viscosity coefficient equivalent to Roelands at p = 0 [1/Pa] (from (2.6)):
        ``alpha = z (ln eta0(T) - ln eta_inf) / p_r``."""
        eta = self.eta0 if T is None else self.eta_at(T)
        return self.z * (np.log(eta) - np.log(ETA_INF)) / P_R

    def viscosity(
        self, p: float | np.ndarray, T: float | np.ndarray | None = None
    ) -> np.ndarray | float:
        """Roelands viscosity (2.6, 3.2.1.7) [Pa s] at pressure ``p`` [Pa] and ``T`` [degC].

        ``eta = eta_inf (eta0/eta_inf) ** [(1 + p/p_r)**z ((T0+135)/(T+135))**S0]``.
        Negative pressures (cavitated zones) are treated as zero.
        """
        p = np.maximum(np.asarray(p, dtype=float), 0.0)
        expo = (1.0 + p / P_R) ** self.z
        if T is not None:
            expo = expo * ((self.T0 + 135.0) / (np.asarray(T, dtype=float) + 135.0)) ** self.S0
        out = ETA_INF * np.exp(np.log(self.eta0 / ETA_INF) * expo)
        return out if out.ndim else float(out)

    # -- density, conductivity, heat capacity ------------------------------------------------
    def density(self, p: float | np.ndarray, T: float | np.ndarray | None = None) -> np.ndarray | float:
        """Dowson-Higginson density with the temperature term (3.10) [kg/m^3]:
        ``rho0 (1 - alpha_T (T - T_rho)) (1 + 0.34615 p / (0.59263e9 + p))``; ``T=None`` means ``T_rho``."""
        out = self.rho0 * density_ratio_dh(p)
        if T is not None:
            out = out * (1.0 - self.alpha_T * (np.asarray(T, dtype=float) - self.T_rho))
        return out if np.ndim(out) else float(out)

    def conductivity(self, p: float | np.ndarray) -> np.ndarray | float:
        """Mineral-oil conductivity (3.12) ``k0 (0.56 + 0.44 sqrt(1 + 2e-8 p))`` [W/(m degC)]."""
        p = np.maximum(np.asarray(p, dtype=float), 0.0)
        out = self.k0 * (0.56 + 0.44 * np.sqrt(1.0 + 2e-8 * p))
        return out if out.ndim else float(out)

    def specific_heat(self, T: float | np.ndarray) -> np.ndarray | float:
        """Specific heat (3.13) ``cp0 + c_cp (T - T_cp0)`` [J/(kg degC)]."""
        out = self.cp0 + self.c_cp * (np.asarray(T, dtype=float) - self.T_cp0)
        return out if np.ndim(out) else float(out)

    # -- Eyring -----------------------------------------------------------------------------
    def eyring_stress(self, eta: float | np.ndarray, shear_rate: float | np.ndarray) -> np.ndarray | float:
        """Eyring shear stress (2.36, 4.33) ``tau0 asinh(eta gamma_dot / tau0)`` [Pa]."""
        out = self.tau0 * np.arcsinh(np.asarray(eta) * np.asarray(shear_rate) / self.tau0)
        return out if np.ndim(out) else float(out)

    # -- construction -----------------------------------------------------------------------
    def with_changes(self, **changes: float | str) -> Lubricant:
        """A copy with some properties replaced; ``alpha`` [1/Pa] may be given instead of ``z``."""
        changes = dict(changes)
        allowed = {f.name for f in fields(self)} | {"alpha", "preset"}
        reject_unknown_keys("lubricant", changes, allowed)
        changes.pop("preset", None)
        alpha = changes.pop("alpha", None)
        base = replace(self, **changes)
        if alpha is not None:
            require_range("lubricant.alpha", alpha, 1e-10, 1e-7, "1/Pa")
            base = replace(base, z=z_from_alpha(float(alpha), base.eta0))
        return base

    def to_dict(self) -> dict:
        return asdict(self)


def density_ratio_dh(p: float | np.ndarray) -> np.ndarray | float:
    """Isothermal Dowson-Higginson ratio rho/rho0 (2.7) ``1 + 0.34615 p / (0.59263e9 + p)``."""
    p = np.maximum(np.asarray(p, dtype=float), 0.0)
    out = 1.0 + DH_B * p / (DH_A + p)
    return out if out.ndim else float(out)


def z_from_alpha(alpha: float, eta0: float) -> float:
    """Roelands index giving pressure-viscosity coefficient ``alpha`` [1/Pa] at p = 0."""
    if eta0 <= ETA_INF:
        raise InputError(f"lubricant.eta0 = {eta0:.6g} Pa s must exceed eta_inf = {ETA_INF} Pa s")
    return alpha * P_R / (np.log(eta0) - np.log(ETA_INF))


#: Appendix A (T9). The thesis uses tau0 = 3.7e6 Pa for its line-contact fits and 8e6 Pa for
#: point contacts; the preset carries the line value, ``T9-point`` the point value.
T9 = Lubricant(
    name="T9", eta0=88e-4, T0=40.0, z=0.87, S0=1.2, rho0=869.0, T_rho=15.0, alpha_T=7.9e-4,
    cp0=2020.0, T_cp0=45.0, c_cp=4.1, k0=0.135, tau0=3.7e6, G=1e30,
)
#: Appendix B (HVI-160).
HVI160 = Lubricant(
    name="HVI-160", eta0=90e-3, T0=40.0, z=0.63, S0=1.27, rho0=878.0, T_rho=25.0, alpha_T=7.6e-4,
    cp0=2110.0, T_cp0=60.0, c_cp=5.0, k0=0.14, tau0=1.3e7, G=1e30,
)

PRESETS: dict[str, Lubricant] = {
    "T9": T9,
    "T9-point": replace(T9, name="T9-point", tau0=8e6),
    "HVI-160": HVI160,
}


def lubricant_preset(name: str) -> Lubricant:
    """Look up a preset by name (``T9``, ``T9-point``, ``HVI-160``)."""
    try:
        return PRESETS[name]
    except KeyError:
        raise InputError(
            f"lubricant.preset = {name!r} is not a known oil; known presets are {sorted(PRESETS)}"
        ) from None
