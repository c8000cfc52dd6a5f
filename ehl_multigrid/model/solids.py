"""Solid materials and the reduced modulus E' (Hertz's ``2/E' = (1-nu1^2)/E1 + (1-nu2^2)/E2``).

Two moduli appear in the thesis and must not be mixed:

* ``E_reduced`` (E'): ``2/E' = (1 - nu1^2)/E1 + (1 - nu2^2)/E2``, used by Hertz, the EHL
  equations and the dimensionless groups (steel on steel about 2.3e11 Pa);
* ``E_gw`` (E'_GW = E'/2): the Greenwood-Williamson effective modulus of the plasticity
  index (2.48-2.49).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, fields, replace

from .errors import reject_unknown_keys, require_positive, require_range


@dataclass(frozen=True)
class Solid:
    """An elastic body with the thermal properties the Carslaw-Jaeger term needs.

    Parameters
    ----------
    E : Young's modulus [Pa]; nu : Poisson ratio [-]; rho : density [kg/m^3];
    k : conductivity [W/(m degC)]; cp : specific heat [J/(kg degC)]; hardness : H' [Pa].
    """

    name: str
    E: float
    nu: float
    rho: float
    k: float
    cp: float
    hardness: float

    def __post_init__(self) -> None:
        p = f"solid {self.name!r}"
        require_range(f"{p}.E", self.E, 1e6, 2e12, "Pa")
        require_range(f"{p}.nu", self.nu, 0.0, 0.5, "-", hi_open=True)
        require_positive(f"{p}.rho", self.rho, "kg/m^3")
        require_positive(f"{p}.k", self.k, "W/(m degC)")
        require_positive(f"{p}.cp", self.cp, "J/(kg degC)")
        require_positive(f"{p}.hardness", self.hardness, "Pa")

    def with_changes(self, **changes: float | str) -> Solid:
        reject_unknown_keys("solid", changes, {f.name for f in fields(self)} | {"preset"})
        changes.pop("preset", None)
        return replace(self, **changes)

    def to_dict(self) -> dict:
        return asdict(self)


#: Bearing steel (appendices C and D: E' = 2.3e11 Pa, rho = 7875, k = 67, Cp = 400; H' = 5 GPa).
#: E = 2.1e11 Pa with nu = 0.3 gives E' = 2.308e11 Pa for steel on steel.
STEEL = Solid(name="steel", E=2.1e11, nu=0.3, rho=7875.0, k=67.0, cp=400.0, hardness=5e9)
PRESETS: dict[str, Solid] = {"steel": STEEL}


def reduced_modulus(E1: float, nu1: float, E2: float, nu2: float) -> float:
    """E' from ``2/E' = (1 - nu1^2)/E1 + (1 - nu2^2)/E2`` [Pa] (Hertz; the thesis's E')."""
    for f, v in (("E1", E1), ("E2", E2)):
        require_positive(f, v, "Pa")
    for f, v in (("nu1", nu1), ("nu2", nu2)):
        require_range(f, v, 0.0, 0.5, "-", hi_open=True)
    return 2.0 / ((1.0 - nu1**2) / E1 + (1.0 - nu2**2) / E2)


def reduced_modulus_of(body1: Solid, body2: Solid) -> float:
    return reduced_modulus(body1.E, body1.nu, body2.E, body2.nu)


def gw_modulus(E_reduced: float) -> float:
    """Greenwood-Williamson effective modulus ``E'_GW = E'/2`` (2.49) [Pa]."""
    return 0.5 * require_positive("E_reduced", E_reduced, "Pa")
