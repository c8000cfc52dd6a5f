"""Lubricants from data-sheet values: ISO VG grade and viscosity index, or two viscosities.

What a lubricant data sheet gives (kinematic viscosity at 40 and 100 degC, or the ISO VG grade
and the viscosity index, and the density at 15 degC) becomes a
:class:`~ehl_multigrid.model.lubricant.Lubricant` (Roelands eta0 at T0, z, S0 ...):

* ISO 3448: the grade VG is the kinematic viscosity at 40 degC in mm^2/s (cSt).
* ASTM D2270 (ISO 2909): the viscosity index from the viscosities at 40 and 100 degC, with the
  standard's Table 1 of L and H (``data/astm_d2270_table1.json``, linear interpolation as the
  standard prescribes) and its equations above 70 cSt; inverted here for nu100 from VG and VI.
* ASTM D341 (Walther): ``log10 log10(nu + 0.7) = A - B log10 T`` with nu in cSt and T in
  kelvin, a straight line through the two data points (valid above 2 cSt).
* Density ``rho(T) = rho15 (1 - alpha_T (T - 15))``, the temperature term of (3.10), so
  ``eta = nu rho``.
* Pressure-viscosity coefficient: given, or from the So and Klaus correlation (P. So and
  E. E. Klaus, ASLE Trans. 23 (1980) 409-421), which uses the atmospheric viscosity, the ASTM
  D341 slope B and the density at the temperature.
* Roelands parameters: ``eta0`` is the Walther viscosity at T0; ``z`` follows from alpha by the
  lubricant module's ``alpha = z (ln eta0 - ln eta_inf)/p_r`` (:func:`z_from_alpha`); ``S0`` is
  chosen so that Roelands' temperature term (2.6) reproduces the Walther viscosity at a second
  temperature exactly: ``S0 = ln[ln(eta1/eta_inf)/ln(eta0/eta_inf)] / ln[(T0+135)/(T1+135)]``.
  Between and beyond the two temperatures Roelands and Walther differ slightly (measured in the
  tests).
* Thermal properties of mineral oils, when not given: Cragoe's correlations (C. S. Cragoe,
  *Thermal properties of petroleum products*, US Bureau of Standards Misc. Publ. 97, 1929):
  ``k = 0.1172 (1 - 0.00054 T)/s15`` W/(m K) and ``cp = (1684 + 3.39 T)/sqrt(s15)`` J/(kg K),
  T in degC, s15 the specific gravity at 15 degC.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, replace
from functools import lru_cache
from importlib import resources
from typing import Any

import numpy as np

from ehl_multigrid.model.constants import ETA_INF, P_R
from ehl_multigrid.model.errors import (
    InputError,
    reject_unknown_keys,
    require_positive,
    require_range,
)
from ehl_multigrid.model.lubricant import Lubricant, z_from_alpha
from ehl_multigrid.model.units import convert_table

#: the temperatures [degC] at which :meth:`Oil.lubricant` builds a data-sheet oil (its ``T0``,
#: ``T_fit``; a scene's ``operating.T_oil`` when no ``T0`` is given)
DATASHEET_T_MIN, DATASHEET_T_MAX = -30.0, 300.0

CST = 1e-6  # m^2/s per mm^2/s (cSt)
KELVIN = 273.15


# -- ASTM D341 (Walther) ----------------------------------------------------------------------
@dataclass(frozen=True)
class WaltherLine:
    """``log10 log10(nu + 0.7) = A - B log10 T`` (ASTM D341), nu in cSt, T in kelvin."""

    A: float
    B: float

    @classmethod
    def through(cls, T1: float, nu1: float, T2: float, nu2: float) -> WaltherLine:
        """The line through two points ``(T [degC], nu [m^2/s])``.

        Raises
        ------
        InputError
            If the temperatures coincide, a viscosity is not positive, or the viscosity does
            not fall with temperature.
        """
        require_range("oil T1", T1, -60.0, 400.0, "degC")
        require_range("oil T2", T2, -60.0, 400.0, "degC")
        require_positive("oil nu1", nu1, "m^2/s")
        require_positive("oil nu2", nu2, "m^2/s")
        if T1 == T2:
            raise InputError(f"the two viscosity points need different temperatures (both {T1:g} degC)")
        (Ta, nua), (Tb, nub) = sorted([(T1, nu1), (T2, nu2)])
        if not nub < nua:
            raise InputError(
                f"viscosity must fall with temperature: nu({Ta:g} degC) = {nua / CST:.6g} cSt, "
                f"nu({Tb:g} degC) = {nub / CST:.6g} cSt"
            )
        ya, yb = _walther_y(nua), _walther_y(nub)
        xa, xb = math.log10(Ta + KELVIN), math.log10(Tb + KELVIN)
        B = (ya - yb) / (xb - xa)
        return cls(A=ya + B * xa, B=B)

    def nu(self, T: float | np.ndarray) -> float | np.ndarray:
        """Kinematic viscosity at ``T`` [degC] [m^2/s]."""
        y = self.A - self.B * np.log10(np.asarray(T, dtype=float) + KELVIN)
        out = (10.0 ** (10.0**y) - 0.7) * CST
        return out if np.ndim(out) else float(out)

    def temperature(self, nu: float) -> float:
        """Temperature [degC] at which the viscosity is ``nu`` [m^2/s]."""
        return 10.0 ** ((self.A - _walther_y(nu)) / self.B) - KELVIN


def _walther_y(nu: float) -> float:
    return math.log10(math.log10(nu / CST + 0.7))


# -- ASTM D2270 (viscosity index) -------------------------------------------------------------
@lru_cache(maxsize=1)
def _d2270_table() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    text = (resources.files("ehl_multigrid") / "data" / "astm_d2270_table1.json").read_text()
    rows = np.array(json.loads(text)["rows"], dtype=float)
    return rows[:, 0], rows[:, 1], rows[:, 2]


def d2270_L_H(nu100: float) -> tuple[float, float]:
    """ASTM D2270 basic values L and H [cSt] for ``nu100`` [cSt] (>= 2 cSt).

    L and H are the 40 degC viscosities of the VI 0 and VI 100 reference oils with the same
    100 degC viscosity: Table 1 interpolated linearly up to 70 cSt, the standard's equations
    ``L = 0.8353 Y^2 + 14.67 Y - 216``, ``H = 0.1684 Y^2 + 11.85 Y - 97`` above.
    """
    Y = require_range("nu100", nu100, 2.0, math.inf, "cSt", hi_open=True)
    if Y <= 70.0:
        nus, Ls, Hs = _d2270_table()
        return float(np.interp(Y, nus, Ls)), float(np.interp(Y, nus, Hs))
    return 0.8353 * Y**2 + 14.67 * Y - 216.0, 0.1684 * Y**2 + 11.85 * Y - 97.0


def viscosity_index(nu40: float, nu100: float) -> float:
    """Viscosity index by ASTM D2270 from kinematic viscosities at 40 and 100 degC [m^2/s].

    Procedure A (VI <= 100): ``VI = 100 (L - U)/(L - H)``; procedure B (U < H, VI > 100):
    ``N = (log H - log U)/log Y``, ``VI = (10^N - 1)/0.00715 + 100``; U = nu40, Y = nu100 in cSt.
    Not rounded.
    """
    U = require_positive("nu40", nu40, "m^2/s") / CST
    Y = require_positive("nu100", nu100, "m^2/s") / CST
    if Y < 2.0:
        raise InputError(f"nu100 = {Y:.6g} cSt: the viscosity index is not defined below 2 cSt (ASTM D2270)")
    if not Y < U:
        raise InputError(f"nu100 = {Y:.6g} cSt must be below nu40 = {U:.6g} cSt")
    L, H = d2270_L_H(Y)
    if U >= H:
        return 100.0 * (L - U) / (L - H)
    N = (math.log10(H) - math.log10(U)) / math.log10(Y)
    return (10.0**N - 1.0) / 0.00715 + 100.0


def nu100_from_vi(nu40: float, vi: float) -> float:
    """The 100 degC viscosity [m^2/s] of an oil with ``nu40`` [m^2/s] and viscosity index ``vi``.

    Inverts :func:`viscosity_index` (monotonic in nu100 at fixed nu40) with Brent's method.
    """
    from scipy.optimize import brentq

    U = require_range("nu40", nu40 / CST, 2.5, 1e5, "cSt")
    vi = require_range("vi", vi, -100.0, 400.0, "-")

    def f(Y: float) -> float:
        return viscosity_index(U * CST, Y * CST) - vi

    lo, hi = 2.0, U * (1.0 - 1e-9)
    if f(lo) > 0.0:
        raise InputError(
            f"vi = {vi:g} with nu40 = {U:.6g} cSt needs nu100 below 2 cSt, where the viscosity "
            "index is not defined (ASTM D2270)"
        )
    if f(hi) < 0.0:
        raise InputError(f"vi = {vi:g} is not reachable with nu40 = {U:.6g} cSt")
    return brentq(f, lo, hi, xtol=1e-12, rtol=1e-12) * CST


# -- pressure-viscosity coefficient, thermal properties --------------------------------------
def alpha_so_klaus(nu: float, B: float, rho: float) -> float:
    """Pressure-viscosity coefficient by So and Klaus (1980) [1/Pa].

    ``alpha [1e-8 m^2/N] = 1.216 + 4.143 x^3.0627 + 2.848e-4 B^5.1903 x^1.5976
    - 3.999 x^3.0975 s^0.1162`` with ``x = log10(nu [cSt])`` at the temperature, B the ASTM D341
    slope and s the density [g/cm^3] at the temperature. The tests compare it with the measured
    coefficients of 13 mineral oils at 30, 60 and 100 degC.
    """
    x = math.log10(require_range("nu", nu / CST, 1.0, 1e6, "cSt"))
    s = require_range("rho", rho, 500.0, 2000.0, "kg/m^3") / 1000.0
    B = require_range("Walther slope B", B, 1.0, 6.0, "-")
    a = (1.216 + 4.143 * x**3.0627 + 2.848e-4 * B**5.1903 * x**1.5976
         - 3.999 * x**3.0975 * s**0.1162)
    return a * 1e-8


def conductivity_cragoe(s15: float, T: float) -> float:
    """Mineral-oil thermal conductivity (Cragoe 1929) ``0.1172 (1 - 0.00054 T)/s15`` [W/(m K)]."""
    return 0.1172 * (1.0 - 0.00054 * T) / s15


def specific_heat_cragoe(s15: float, T: float) -> float:
    """Mineral-oil specific heat (Cragoe 1929) ``(1684 + 3.39 T)/sqrt(s15)`` [J/(kg K)]."""
    return (1684.0 + 3.39 * T) / math.sqrt(s15)


# -- the oil --------------------------------------------------------------------------------
@dataclass(frozen=True)
class Oil:
    """A lubricant as its data sheet gives it.

    Parameters
    ----------
    name : str
    nu40, nu100 : float
        Kinematic viscosity at 40 and 100 degC [m^2/s].
    rho15 : float
        Density at 15 degC [kg/m^3].
    alpha_T : float
        Thermal expansion coefficient of the density [1/degC].
    tau0 : float
        Eyring stress [Pa].
    alpha40 : float, optional
        Pressure-viscosity coefficient at 40 degC [1/Pa]; None: So and Klaus.
    k : float, optional
        Thermal conductivity [W/(m K)]; None: Cragoe at T0.
    cp40, c_cp : float, optional
        Specific heat at 40 degC [J/(kg K)] and its slope [J/(kg K^2)]; None: Cragoe.
    source : str
        Where the numbers come from.
    """

    name: str
    nu40: float
    nu100: float
    rho15: float
    alpha_T: float = 7.6e-4
    tau0: float = 5e6
    alpha40: float | None = None
    k: float | None = None
    cp40: float | None = None
    c_cp: float | None = None
    source: str = ""

    def __post_init__(self) -> None:
        p = f"oil {self.name!r}"
        require_range(f"{p}.nu40", self.nu40 / CST, 2.5, 1e5, "cSt")
        require_range(f"{p}.nu100", self.nu100 / CST, 1.0, self.nu40 / CST, "cSt", hi_open=True)
        require_range(f"{p}.rho15", self.rho15, 500.0, 2000.0, "kg/m^3")
        require_range(f"{p}.alpha_T", self.alpha_T, 0.0, 2e-3, "1/degC")
        require_positive(f"{p}.tau0", self.tau0, "Pa")
        if self.alpha40 is not None:
            require_range(f"{p}.alpha40", self.alpha40, 1e-9, 1e-7, "1/Pa")
        if self.k is not None:
            require_range(f"{p}.k", self.k, 0.01, 1.0, "W/(m K)")
        if self.cp40 is not None:
            require_range(f"{p}.cp40", self.cp40, 500.0, 5000.0, "J/(kg K)")

    @property
    def walther(self) -> WaltherLine:
        return WaltherLine.through(40.0, self.nu40, 100.0, self.nu100)

    @property
    def viscosity_index(self) -> float:
        return viscosity_index(self.nu40, self.nu100)

    def kinematic_viscosity(self, T: float) -> float:
        """Walther kinematic viscosity at ``T`` [degC] [m^2/s]."""
        return float(self.walther.nu(T))

    def density(self, T: float) -> float:
        """``rho15 (1 - alpha_T (T - 15))`` [kg/m^3]."""
        return self.rho15 * (1.0 - self.alpha_T * (T - 15.0))

    def dynamic_viscosity(self, T: float) -> float:
        """``nu(T) rho(T)`` [Pa s]."""
        return self.kinematic_viscosity(T) * self.density(T)

    def pressure_viscosity(self, T: float = 40.0) -> float:
        """alpha at ``T`` [1/Pa]: So and Klaus, or the given alpha40 carried to T by Roelands
        with constant z (the package's viscosity law)."""
        if self.alpha40 is None:
            return alpha_so_klaus(self.kinematic_viscosity(T), self.walther.B, self.density(T))
        z = z_from_alpha(self.alpha40, self.dynamic_viscosity(40.0))
        return z * (math.log(self.dynamic_viscosity(T)) - math.log(ETA_INF)) / P_R

    def lubricant(self, T0: float = 40.0, T_fit: float | None = None) -> Lubricant:
        """The Roelands lubricant of the package, exact at ``T0`` and ``T_fit`` [degC].

        ``eta0 = eta(T0)`` from the Walther line and the density; ``z`` from alpha at T0;
        ``S0`` so that the Roelands temperature term gives the Walther viscosity at ``T_fit``
        (default 100 degC, or 40 degC when T0 is 100 degC).
        """
        T0 = require_range("lubricant.T0", T0, DATASHEET_T_MIN, DATASHEET_T_MAX, "degC")
        if T_fit is None:
            T_fit = 100.0 if abs(T0 - 100.0) > 5.0 else 40.0
        T_fit = require_range("lubricant.T_fit", T_fit, DATASHEET_T_MIN, DATASHEET_T_MAX, "degC")
        if abs(T_fit - T0) < 1.0:
            raise InputError(f"lubricant.T_fit = {T_fit:g} degC must differ from T0 = {T0:g} degC")
        eta0 = self.dynamic_viscosity(T0)
        eta1 = self.dynamic_viscosity(T_fit)
        S0 = roelands_S0(eta0, T0, eta1, T_fit)
        z = z_from_alpha(self.pressure_viscosity(T0), eta0)
        s15 = self.rho15 / 1000.0
        k = self.k if self.k is not None else conductivity_cragoe(s15, T0)
        if self.cp40 is not None:
            cp0 = self.cp40 + (self.c_cp or 0.0) * (T0 - 40.0)
            c_cp = self.c_cp or 0.0
        else:
            cp0, c_cp = specific_heat_cragoe(s15, T0), 3.39 / math.sqrt(s15)
        return Lubricant(
            name=self.name, eta0=eta0, T0=T0, z=z, S0=S0, rho0=self.rho15, T_rho=15.0,
            alpha_T=self.alpha_T, cp0=cp0, T_cp0=T0, c_cp=c_cp, k0=k, tau0=self.tau0,
        )

    def describe(self, T: float | None = None) -> dict[str, Any]:
        """Data-sheet numbers and derived values (at ``T`` [degC] when given), SI."""
        w = self.walther
        out: dict[str, Any] = {
            "oil": self.name, "nu40": self.nu40, "nu100": self.nu100,
            "viscosity_index": self.viscosity_index, "rho15": self.rho15,
            "walther_A": w.A, "walther_B": w.B, "alpha40": self.pressure_viscosity(40.0),
            "tau0": self.tau0, "oil_source": self.source,
        }
        if T is not None:
            out.update({
                "T": T, "nu_T": self.kinematic_viscosity(T), "rho_T": self.density(T),
                "eta_T": self.dynamic_viscosity(T), "alpha_T": self.pressure_viscosity(T),
            })
        return out


def roelands_S0(eta0: float, T0: float, eta1: float, T1: float) -> float:
    """Roelands temperature index reproducing ``eta1`` at ``T1`` from ``eta0`` at ``T0`` (2.6).

    From ``ln(eta/eta_inf) = ln(eta0/eta_inf) ((T0 + 135)/(T + 135))^S0`` at p = 0 (T in degC).
    """
    for f, v in (("eta0", eta0), ("eta1", eta1)):
        if not v > ETA_INF:
            raise InputError(f"{f} = {v:.6g} Pa s must exceed eta_inf = {ETA_INF} Pa s for Roelands")
    return math.log(math.log(eta1 / ETA_INF) / math.log(eta0 / ETA_INF)) / math.log(
        (T0 + 135.0) / (T1 + 135.0)
    )


def iso_vg_oil(grade: float, vi: float, rho15: float, name: str | None = None, **kw: Any) -> Oil:
    """An oil of ISO 3448 grade ``grade`` (nu40 in cSt) and viscosity index ``vi``."""
    grade = require_range("lubricant.iso_vg", grade, 2.5, 3200.0, "cSt")
    nu40 = grade * CST
    return Oil(name=name or f"ISO VG {grade:g} VI {vi:g}", nu40=nu40,
               nu100=nu100_from_vi(nu40, vi), rho15=rho15, **kw)


# -- presets --------------------------------------------------------------------------------
_MINERAL_NOTE = (
    "solvent-refined paraffinic mineral oil (API group I), representative: nu40 = ISO VG "
    "(ISO 3448), VI 95, rho15 from typical product data sheets (0.86-0.89 g/cm^3 rising with "
    "grade), alpha_T 7.6e-4/degC as the thesis's mineral oil HVI-160 (appendix B); alpha by "
    "So and Klaus (1980); k and cp by Cragoe (1929); tau0 = 5 MPa is an order of magnitude "
    "only (the thesis fits 3.7-13 MPa for its mineral oils): measure it for friction work"
)
_MINERAL_RHO15 = {32: 862.0, 46: 866.0, 68: 872.0, 100: 876.0, 150: 882.0, 220: 887.0, 320: 891.0}


def _presets() -> dict[str, Oil]:
    out = {
        f"mineral-VG{g}": iso_vg_oil(g, 95.0, rho, name=f"mineral-VG{g}", source=_MINERAL_NOTE)
        for g, rho in _MINERAL_RHO15.items()
    }
    out["PAO-VG68"] = iso_vg_oil(
        68, 140.0, 835.0, name="PAO-VG68", alpha_T=7.0e-4, tau0=4e6, alpha40=1.6e-8, k=0.145,
        cp40=2100.0, c_cp=3.9,
        source="polyalphaolefin, representative of PAO-based ISO VG 68 oils (VI 135-150, "
        "0.83-0.84 g/cm^3); alpha40 = 1.6e-8 1/Pa, below the 1.8-2.0e-8 at 38 degC that Jones "
        "et al. (1975, NASA TN D-8024) measured for heavier synthetic paraffinic oils (So and "
        "Klaus gives 2.5e-8, too high for PAO); k, cp typical of PAO (0.14-0.15 W/(m K), about "
        "2.1 kJ/(kg K) at 40 degC); tau0 order of magnitude",
    )
    out["ester-VG46"] = iso_vg_oil(
        46, 140.0, 960.0, name="ester-VG46", alpha_T=7.5e-4, tau0=4e6, alpha40=1.2e-8, k=0.15,
        cp40=1950.0, c_cp=3.5,
        source="synthetic polyol ester, representative (ISO VG 46, VI 140, 0.95-0.97 g/cm^3); "
        "alpha40 = 1.2e-8 1/Pa in the range Jones et al. (1975, NASA TN D-8024) measured for "
        "ester fluids (1.28-1.37e-8 at 38 degC), So and Klaus overestimates esters; k, cp "
        "typical of esters; tau0 order of magnitude",
    )
    out["traction-fluid"] = Oil(
        name="traction-fluid", nu40=30.0 * CST, nu100=5.0 * CST, rho15=900.0, alpha_T=7.0e-4,
        tau0=12e6, alpha40=3.1e-8, k=0.11, cp40=2000.0, c_cp=4.0,
        source="cycloaliphatic hydrocarbon traction fluid, representative (Santotrac-50 type: "
        "about 30 cSt at 40 degC, 5 cSt at 100 degC, 0.90 g/cm^3); alpha40 = 3.1e-8 1/Pa as "
        "Jones et al. (1975, NASA TN D-8024) measured for a synthetic traction fluid at 38 degC; "
        "tau0 high, as traction fluids have (order of magnitude)",
    )
    return out


@lru_cache(maxsize=1)
def preset_oils() -> dict[str, Oil]:
    """The preset oils by name, built on first use (their VI inversion needs scipy.optimize,
    which would otherwise cost every start-up about 0.3 s)."""
    return _presets()


def __getattr__(name: str) -> Any:
    # ``OILS`` stays importable, built when first asked for
    if name == "OILS":
        return preset_oils()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def oil_preset(name: str) -> Oil:
    """A preset oil by name (``mineral-VG68``, ``PAO-VG68``, ``ester-VG46``, ``traction-fluid`` ...)."""
    oils = preset_oils()
    try:
        return oils[name]
    except KeyError:
        raise InputError(f"lubricant.oil = {name!r} is not a known oil; known oils are {sorted(oils)}") from None


#: Keys of a ``[lubricant]`` table read by :func:`oil_from_table`, with their kinds of quantity.
OIL_KEYS: dict[str, str] = {
    "iso_vg": "kinematic_viscosity", "vi": "dimensionless", "nu40": "kinematic_viscosity",
    "nu100": "kinematic_viscosity", "rho15": "density", "alpha_T": "inverse_temperature",
    "tau0": "pressure", "alpha40": "inverse_pressure", "k": "conductivity",
    "cp40": "specific_heat", "c_cp": "", "T0": "temperature",
    "T_fit": "temperature",
}
OIL_TABLE_KEYS = set(OIL_KEYS) | {"oil", "name", "source"}


def is_oil_table(table: dict[str, Any]) -> bool:
    """Whether a ``[lubricant]`` table describes an oil by data-sheet values."""
    return any(k in table for k in ("oil", "iso_vg", "nu40"))


def oil_from_table(table: dict[str, Any], section: str = "lubricant") -> tuple[Oil, dict[str, float]]:
    """An :class:`Oil` from a scene table, and the Roelands options (``T0``, ``T_fit``) it sets.

    Either ``oil = PRESET`` (other keys override it), or ``iso_vg`` with ``vi`` (grade in cSt,
    or "68 cSt"), or ``nu40`` with ``nu100``; ``rho15`` is required without a preset.
    """
    reject_unknown_keys(section, table, OIL_TABLE_KEYS)
    v = convert_table(section, table, {k: q for k, q in OIL_KEYS.items() if q and k != "iso_vg"})
    if "iso_vg" in v:  # a grade is a number in cSt; "68 cSt" is accepted too
        g = v["iso_vg"]
        v["iso_vg"] = g if isinstance(g, (int, float)) and not isinstance(g, bool) else convert_table(
            section, {"iso_vg": g}, {"iso_vg": "kinematic_viscosity"})["iso_vg"] / CST
    options = {k: v.pop(k) for k in ("T0", "T_fit") if k in v}
    base = oil_preset(str(v.pop("oil"))) if "oil" in v else None
    has_vg, has_nu = "iso_vg" in v, "nu40" in v
    if has_vg and has_nu:
        raise InputError(f"[{section}] give iso_vg (with vi) or nu40 (with nu100), not both")
    if has_vg != ("vi" in v) and has_vg:
        raise InputError(f"[{section}] iso_vg needs vi (the viscosity index, ASTM D2270)")
    if "vi" in v and not has_vg:
        raise InputError(f"[{section}] vi needs iso_vg (the grade, nu40 in cSt)")
    if has_nu != ("nu100" in v):
        raise InputError(f"[{section}] nu40 and nu100 go together (m^2/s, or '68 cSt')")
    if base is None and "rho15" not in v:
        raise InputError(f"[{section}] needs rho15 (density at 15 degC, kg/m^3) or an oil preset")
    fields_ = {k: v[k] for k in ("rho15", "alpha_T", "tau0", "alpha40", "k", "cp40", "c_cp",
                                  "source") if k in v}
    try:
        if has_vg:
            nu40 = v["iso_vg"] * CST
            nu100 = nu100_from_vi(nu40, v["vi"])
        elif has_nu:
            nu40, nu100 = v["nu40"], v["nu100"]
        else:
            nu40 = nu100 = None
        if base is not None:
            changes = dict(fields_)
            if nu40 is not None:
                changes.update(nu40=nu40, nu100=nu100)
            name = str(v.get("name", base.name if not changes else f"{base.name} (modified)"))
            oil = replace(base, name=name, **changes)
        else:
            if nu40 is None:
                raise InputError(f"[{section}] needs oil, iso_vg with vi, or nu40 with nu100")
            name = str(v.get("name", f"ISO VG {nu40 / CST:g}" if has_vg else "oil"))
            oil = Oil(name=name, nu40=nu40, nu100=nu100, **fields_)
    except InputError as exc:
        raise InputError(f"[{section}]: {exc}") from None
    return oil, options
