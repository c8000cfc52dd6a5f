"""Scenes: one contact situation as a plain data object, loaded from TOML.

Every layer reads the same :class:`Scene`. Loading validates every value and raises
:class:`~ehl_multigrid.model.errors.InputError` naming the field, value, units and allowed range;
nothing is half-loaded. A value that is allowed but implausible for a real contact (a 10 m ball
radius: millimetres typed as metres), and a derived Hertz pressure, fitted film or Moes group far
beyond real contacts, warn with a :class:`~ehl_multigrid.model.errors.PlausibilityWarning` naming
the field, the value, the plausible range and the probable unit mistake
(:data:`~ehl_multigrid.model.plausibility.PLAUSIBLE`); strict mode refuses them. Built-in scenes live in
``ehl_multigrid/scenes/*.toml``.

TOML layout (plain numbers SI, temperatures in degC, angles in degrees; any value may instead
be a string with units, "7.94 mm", "1.5 GPa", "68 cSt", "70 degC", "1500 rpm"; a speed of rotation
in Hz or 1/s is revolutions per second, 2 pi rad each)::

    name = "my_contact"
    description = "..."
    [contact]     kind = "line" | "point" | "elliptic";  length = B [m] (line only)
    [geometry]    Rx, Ry [m] (reduced)  or  R1x, R2x, R1y, R2y [m] (inf = flat)
    [solids]      body1, body2 = preset name or table {preset, E, nu, rho, k, cp, hardness};
                  E_reduced [Pa] overrides the value computed from the bodies
    [element]     kind = "ball_bearing" | "roller_bearing" | "spur_gear" | "ball_on_disc" |
                  "ball_on_flat" plus its catalogue data (see model.elements); replaces
                  [geometry] and gives [contact], load, us and slip (which [operating] may override)
    [materials.NAME]  a solid {preset, E, nu, rho, k, cp, hardness, source} usable as body1/body2
    [lubricant]   preset = "T9" | "T9-point" | "HVI-160" plus overrides (eta0, alpha or z, tau0, ...);
                  or a data-sheet oil: oil = "mineral-VG68" ..., or iso_vg + vi, or nu40 + nu100,
                  with rho15, alpha40, tau0, k, cp40, T0 (Roelands reference, default T_oil)
    [operating]   load [N] or pmax [Pa]; us [m/s] (sum velocity u1 + u2) or entrainment_speed
                  [m/s] ((u1 + u2)/2); slip [-] (S = 2(u1-u2)/us); T_oil, T_surface1, T_surface2 [degC]
    [ranges]      us, slip, load: a list, or {min, max, n, log}
    [roughness]   Rq, Ra, sigma_s, dd [m]; n [1/m^2]; beta [m]; fc [-]; hardness [Pa]
    [supply]      hoil [m] (inf = flooded); hoil_over_sigma (list); delta [-] or "inlet"; or instead of hoil
                  hoil_profile = {y = [...], hoil = [...]} [m]: a layer across the track
                  (|y| from its centre; the starved point solver; hoil = its centre value)
    [feature]     a surface feature for 'ehl transient': kind = "waviness" | "bump" | "dent";
                  amplitude, width or wavelength [m]; x0 [b]; shape; body (1 or 2); or
                  kind = "map" with a height file (formats, units, levelling, filter: the
                  mixed layer's reader); validated there
    [solver.*]    free-form option tables per layer (ehl, thermal, mixed), validated there
"""

from __future__ import annotations

import copy
import math
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from functools import cached_property
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from . import fits, groups, hertz
from .constants import THETA_MAX, THETA_MIN
from .elements import ElementContact, element_contact
from .errors import (
    SLIP_DEFINITION,
    InputError,
    reject_unknown_keys,
    require_choice,
    require_positive,
    require_range,
    require_slip,
)
from .lubricant import T_MAX_C, T_MIN_C, Lubricant, lubricant_preset
from .materials import Material, material, materials_from_tables
from .oils import DATASHEET_T_MAX, DATASHEET_T_MIN, Oil, is_oil_table, oil_from_table
from .plausibility import check_plausible, unit_hint, warn_model_range
from .solids import Solid, reduced_modulus_of
from .units import convert_table, to_canonical

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

CONTACT_KINDS = ("line", "point", "elliptic")
#: Largest sum velocity u1 + u2 [m/s] a scene may give (high-speed bearings and gears stay well
#: below 200 m/s; a larger value is a unit mistake).
US_MAX = 1e3
TOP_KEYS = {
    "name", "description", "source", "contact", "geometry", "solids", "lubricant",
    "operating", "ranges", "roughness", "supply", "solver", "element", "materials", "feature",
}

#: Kind of quantity of each scalar key, per section, for values given with units.
UNIT_KINDS: dict[str, dict[str, str]] = {
    "contact": {"length": "length"},
    "geometry": {k: "length" for k in ("Rx", "Ry", "R1x", "R2x", "R1y", "R2y")},
    "solids": {"E_reduced": "pressure"},
    "lubricant": {
        "eta0": "dynamic_viscosity", "T0": "temperature", "rho0": "density",
        "T_rho": "temperature", "alpha_T": "inverse_temperature", "cp0": "specific_heat",
        "T_cp0": "temperature", "k0": "conductivity", "tau0": "pressure", "G": "pressure",
        "alpha": "inverse_pressure",
    },
    "operating": {
        "load": "force", "pmax": "pressure", "us": "speed", "entrainment_speed": "speed",
        "slip": "dimensionless", "srr": "dimensionless", "T_oil": "temperature",
        "T_surface1": "temperature", "T_surface2": "temperature",
    },
    "roughness": {
        "Rq": "length", "Ra": "length", "sigma_s": "length", "dd": "length",
        "n": "inverse_area", "beta": "length", "fc": "dimensionless", "hardness": "pressure",
    },
    "supply": {"hoil": "length"},
    "feature": {"amplitude": "length", "width": "length", "wavelength": "length", "dx": "length",
                "dy": "length"},
}
RANGE_KINDS = {"us": "speed", "slip": "dimensionless", "load": "force", "pmax": "pressure"}
#: Quantity of :data:`~ehl_multigrid.model.plausibility.PLAUSIBLE` of each [operating] value.
OPERATING_PLAUSIBLE = {"load": "load", "pmax": "pmax", "us": "us", "entrainment_speed": "entrainment_speed",
                       "T_oil": "temperature", "T_surface1": "temperature", "T_surface2": "temperature"}


@dataclass(frozen=True)
class Range:
    """A list of values or a ``{min, max, n, log}`` span, resolved to an array by :meth:`values`."""

    field: str
    explicit: tuple[float, ...] | None = None
    min: float = math.nan
    max: float = math.nan
    n: int = 0
    log: bool = False

    def values(self) -> np.ndarray:
        if self.explicit is not None:
            return np.array(self.explicit, dtype=float)
        if self.log:
            return np.geomspace(self.min, self.max, self.n)
        return np.linspace(self.min, self.max, self.n)

    def to_toml_value(self) -> Any:
        if self.explicit is not None:
            return list(self.explicit)
        return {"min": self.min, "max": self.max, "n": self.n, "log": self.log}


@dataclass(frozen=True)
class Roughness:
    """Equivalent rough surface (Greenwood-Williamson, thesis 2.4.1 and 4.4). Lengths in metres.

    Rq (= sigma) and the summit parameters; Whitehouse-Archard defaults (sigma_s = 0.7 sigma,
    dd = 0.82 sigma) fill in what is missing when only Rq is given.
    """

    Rq: float
    sigma_s: float
    dd: float
    n: float = math.nan
    beta: float = math.nan
    Ra: float = math.nan
    fc: float = 0.13
    hardness: float = 5e9


@dataclass(frozen=True)
class Supply:
    """Oil supply: ``hoil`` inlet oil film [m] (inf = fully flooded), optional list of
    ``hoil/sigma`` values for starvation studies, and Chevalier's exponent ``delta``."""

    hoil: float = math.inf
    hoil_over_sigma: tuple[float, ...] = ()
    #: Chevalier's exponent of (6.1), or "inlet": from the flooded inlet at each speed
    delta: float | str = 3.5
    #: Layer across the track: ``(y [m], hoil [m])`` points, piecewise linear in ``|y|`` (the
    #: distance from the track centre), constant beyond the last point; ``hoil`` is then its
    #: value at the centre. Empty: a uniform layer.
    hoil_profile: tuple[tuple[float, ...], tuple[float, ...]] = ()

    def layer_at(self, y: Any) -> Any:
        """The supplied layer [m] at lateral position(s) ``y`` [m] (uniform ``hoil`` without a
        profile)."""
        if not self.hoil_profile:
            return np.full(np.shape(y), self.hoil) if np.ndim(y) else self.hoil
        ys, hs = self.hoil_profile
        return np.interp(np.abs(y), ys, hs)


@dataclass(frozen=True)
class Scene:
    """One contact situation. Build with :func:`load_scene` or :meth:`Scene.from_dict`.

    Derived quantities (Hertz, inlet viscosity, Moes groups, fitted film) are properties.
    """

    name: str
    description: str
    source: str
    kind: str
    length: float  # B [m], line only (nan otherwise)
    Rx: float
    Ry: float
    body1: Solid
    body2: Solid
    E_reduced: float
    lubricant: Lubricant
    load: float
    us: float
    slip: float
    T_oil: float
    T_surface1: float
    T_surface2: float
    ranges: dict[str, Range] = field(default_factory=dict)
    roughness: Roughness | None = None
    supply: Supply = field(default_factory=Supply)
    solver: dict[str, dict[str, Any]] = field(default_factory=dict)
    #: A surface feature ([feature] table, lengths in metres), read by the transient solver.
    feature: dict[str, Any] = field(default_factory=dict)
    raw: dict[str, Any] = field(default_factory=dict, compare=False, repr=False)
    #: The machine element the contact came from ([element] table), if any.
    element: ElementContact | None = field(default=None, compare=False)
    #: The data-sheet oil the lubricant was built from, if any.
    oil: Oil | None = field(default=None, compare=False, repr=False)

    # -- derived ------------------------------------------------------------------------------
    @property
    def R(self) -> float:
        """Reduced radius in the rolling direction [m] (``Rx``)."""
        return self.Rx

    @property
    def theta(self) -> float:
        """Ellipticity parameter ``Rx/Ry`` (0 for a line contact)."""
        return self.Rx / self.Ry

    @property
    def u1(self) -> float:
        """Velocity of surface 1 [m/s]: ``us (1 + S/2) / 2``."""
        return 0.5 * self.us * (1.0 + 0.5 * self.slip)

    @property
    def u2(self) -> float:
        return 0.5 * self.us * (1.0 - 0.5 * self.slip)

    @cached_property
    def hertz(self) -> hertz.HertzContact:
        return self.hertz_at(self.load)

    def hertz_at(self, load: float) -> hertz.HertzContact:
        """The Hertzian contact of this geometry under ``load`` [N]."""
        if self.kind == "line":
            return hertz.hertz_line(load, self.length, self.Rx, self.E_reduced)
        return hertz.hertz_point(load, self.Rx, self.Ry, self.E_reduced)

    @property
    def eta0(self) -> float:
        """Ambient-pressure viscosity at the oil inlet temperature [Pa s] (Roelands T term)."""
        return float(self.lubricant.eta_at(self.T_oil))

    @property
    def alpha(self) -> float:
        """Roelands-equivalent pressure-viscosity coefficient at the inlet temperature [1/Pa]."""
        return float(self.lubricant.alpha(self.T_oil))

    def moes(self, us: float | None = None, load: float | None = None) -> tuple[float, float]:
        """Moes (M, L) at the scene's operating point (or the given ``us``/``load``)."""
        us = self.us if us is None else us
        load = self.load if load is None else load
        if self.kind == "line":
            return groups.moes_line(load / self.length, us, self.eta0, self.alpha, self.E_reduced, self.Rx)
        return groups.moes_point(load, us, self.eta0, self.alpha, self.E_reduced, self.Rx)

    @contextmanager
    def naming_moes_inputs(self) -> Iterator[None]:
        """Re-raise a solver's refusal of the Moes M or L (an :class:`InputError` starting
        ``"M ="`` or ``"L ="``) with the scene values that make them, so that a load given in kN
        as N is named, not only "M = 0.0875 is outside [0.1, 20000]"."""
        try:
            yield
        except InputError as exc:
            if not str(exc).startswith(("M =", "L =")):
                raise
            per = f" on {self.length:g} m" if self.kind == "line" else ""
            raise InputError(f"{exc}; scene {self.name}: load {self.load:g} N{per}, us {self.us:g} m/s, eta0 "
                             f"{self.eta0:.4g} Pa s, alpha {self.alpha:.4g} 1/Pa, E' {self.E_reduced:.4g} Pa, "
                             f"Rx {self.Rx:.4g} m (M grows with the load and falls with speed and viscosity; "
                             f"L grows with alpha and speed): check these values and their units") from None

    def film_scale(self, us: float | None = None) -> float:
        """Metres per unit Moes film H at sum velocity ``us`` [m]."""
        return groups.moes_film_scale(self.us if us is None else us, self.eta0, self.E_reduced, self.Rx)

    def central_film_fit(self, us: float | None = None, load: float | None = None, gamma1: float = 1.0) -> tuple[float, float]:
        """``(Hc, hc)``: fitted Moes central film and its value in metres (Moes line or
        Nijenbanning)."""
        M, L = self.moes(us, load)
        Hc = float(fits.central_film_fit(self.kind, M, L, 1.0 if self.kind == "line" else self.theta, gamma1))
        return Hc, Hc * self.film_scale(us)

    def supplied_film_fit(self, us: float | None = None, load: float | None = None) -> tuple[float, float]:
        """``(Hc, hc)``: the fitted central film for the scene's supply: the flooded fit
        (:meth:`central_film_fit`) reduced by Chevalier's (6.1)-(6.4) for a finite
        ``[supply] hoil`` (exponent ``supply.delta``; ``"inlet"`` from the flooded inlet), so
        that a starved scene's estimate never carries more oil than supplied."""
        Hc, hc = self.central_film_fit(us, load)
        hoil = self.supply.hoil
        if math.isinf(hoil):
            return Hc, hc
        from .starvation import INLET, chevalier_reduction, density_ratio_at, inlet_delta

        hz = self.hertz if load is None else self.hertz_at(load)
        delta = self.supply.delta
        if delta == INLET:
            delta = float(inlet_delta(self.kind, hc * self.Rx / hz.a**2, self.theta))
        k = float(chevalier_reduction(hoil / (hc * density_ratio_at(hz.pmax)), delta))
        return Hc * k, hc * k

    def thermal_properties(self) -> dict[str, float]:
        """The oil's thermal properties at the oil temperature and the thermal loading:
        ``beta`` = -d ln(eta)/dT [1/K] (Roelands (2.6)), ``k_oil`` [W/(m K)] (3.12) and
        ``cp_oil`` [J/(kg K)] (3.13) at ambient pressure, and ``thermal_loading`` =
        ``beta eta0 um^2 / k_oil`` with the entrainment speed ``um = us/2`` (the parameter of the
        thermal film-reduction correlations: Murch & Wilson 1975, Gupta et al. 1992)."""
        lub = self.lubricant
        beta = lub.beta(self.T_oil)
        k_oil = float(lub.conductivity(0.0))
        return {"beta": beta, "k_oil": k_oil, "cp_oil": float(lub.specific_heat(self.T_oil)),
                "thermal_loading": beta * self.eta0 * (0.5 * self.us) ** 2 / k_oil}

    def summary(self) -> dict[str, Any]:
        """Main scalars as a flat dict (what ``ehl show --json`` prints).

        Next to the fitted film: whether (M, L, theta) lie inside the range where the package
        checked the fit against its solver (``hc_fit_in_range``, ``hc_fit_range``), the fit's
        measured bias there (``hc_fit_deviation`` = (Hc_fit - Hc_solver)/Hc_solver interpolated,
        ``hc_fit_deviation_min``/``_max`` around it; nan outside) and a sentence saying so
        (``hc_fit_note``), from :func:`~ehl_multigrid.model.fits.fit_validity`; for a finite
        ``[supply] hoil`` also ``hc_fit_starved`` (:meth:`supplied_film_fit`).
        """
        hz = self.hertz
        M, L = self.moes()
        Hc, hc = self.central_film_fit()
        fit = fits.fit_validity(self.kind, M, L, 1.0 if self.kind == "line" else self.theta)
        out: dict[str, Any] = {
            "name": self.name,
            "contact": self.kind,
            "load": self.load,
            "us": self.us,
            "slip": self.slip,
            "T_oil": self.T_oil,
            "E_reduced": self.E_reduced,
            "Rx": self.Rx,
            "Ry": self.Ry,
            "u1": self.u1,
            "u2": self.u2,
            "entrainment_speed": 0.5 * self.us,
            "eta0": self.eta0,
            "alpha": self.alpha,
            "pmax": hz.pmax,
            "mean_pressure": hz.mean_pressure,
            "area": hz.area,
            "M": M,
            "L": L,
            "Hc_fit": Hc,
            "hc_fit": hc,
            "hc_fit_in_range": fit["in_range"],
            "hc_fit_range": fit["range"],
            "hc_fit_deviation": fit["deviation"],
            "hc_fit_deviation_min": fit["deviation_min"],
            "hc_fit_deviation_max": fit["deviation_max"],
            "hc_fit_note": fit["note"],
        }
        if math.isfinite(self.supply.hoil):
            # the flooded fit above is not this scene's film: the supply bounds it ((6.1)-(6.4))
            out["hoil"] = self.supply.hoil
            out["Hc_fit_starved"], out["hc_fit_starved"] = self.supplied_film_fit()
        if self.kind == "line":
            out["b"] = hz.b
            out["length"] = self.length
            lam, abar = groups.venner_line(M, L)
        else:
            out["a"] = hz.a
            out["b"] = hz.b
            out["theta"] = self.theta
            lam, abar = groups.venner_point(M, L)
        out["lambda_venner"] = lam
        out["alpha_bar"] = abar
        out.update(self.thermal_properties())
        if self.roughness is not None:
            out["Lambda_fit"] = hc / self.roughness.Rq
        if self.element is not None:
            el = self.element.describe()
            out["element"] = el.pop("element")
            for k in ("contact", "Rx", "Ry", "theta", "us", "slip", "entrainment_speed",
                      "length", "load_per_length"):
                el.pop(k, None)
            out.update({f"element_{k}": v for k, v in el.items()})
        if self.oil is not None:
            out.update({
                "oil": self.oil.name, "oil_nu40": self.oil.nu40, "oil_nu100": self.oil.nu100,
                "oil_viscosity_index": self.oil.viscosity_index, "oil_rho15": self.oil.rho15,
                "oil_nu_T_oil": self.oil.kinematic_viscosity(self.T_oil),
                "oil_source": self.oil.source,
            })
        return out

    # -- (de)serialisation -----------------------------------------------------------------
    @classmethod
    def from_dict(cls, data: dict[str, Any], origin: str = "<dict>") -> Scene:
        """Validate and resolve a scene dictionary (the parsed TOML).

        Every physical value is also checked for plausibility (:func:`check_plausible`: a
        :class:`~ehl_multigrid.model.errors.PlausibilityWarning` naming field, value, plausible
        range and the probable unit mistake, an :class:`InputError` in strict mode), and so are
        the derived Hertz pressure, fitted film and Moes groups.
        """
        return _build_scene(copy.deepcopy(data), origin)

    def to_dict(self) -> dict[str, Any]:
        """The resolved scene as a TOML-ready dictionary (round-trips through :meth:`from_dict`)."""
        d: dict[str, Any] = {
            "name": self.name,
            "description": self.description,
            "source": self.source,
            "contact": {"kind": self.kind},
            "geometry": {"Rx": self.Rx, "Ry": self.Ry},
            "solids": {
                "body1": self.body1.to_dict(),
                "body2": self.body2.to_dict(),
                "E_reduced": self.E_reduced,
            },
            "lubricant": self.lubricant.to_dict(),
            "operating": {
                "load": self.load, "us": self.us, "slip": self.slip, "T_oil": self.T_oil,
                "T_surface1": self.T_surface1, "T_surface2": self.T_surface2,
            },
            "supply": {
                "hoil": self.supply.hoil,
                "hoil_over_sigma": list(self.supply.hoil_over_sigma),
                "delta": self.supply.delta,
            },
        }
        if self.supply.hoil_profile:
            del d["supply"]["hoil"]
            d["supply"]["hoil_profile"] = {"y": list(self.supply.hoil_profile[0]),
                                           "hoil": list(self.supply.hoil_profile[1])}
        if self.kind == "line":
            d["contact"]["length"] = self.length
        if self.ranges:
            d["ranges"] = {k: r.to_toml_value() for k, r in self.ranges.items()}
        if self.roughness is not None:
            d["roughness"] = {k: v for k, v in vars(self.roughness).items() if not _isnan(v)}
        if self.solver:
            d["solver"] = copy.deepcopy(self.solver)
        if self.feature:
            d["feature"] = copy.deepcopy(self.feature)
        return d

    def to_toml(self) -> str:
        import tomli_w

        return tomli_w.dumps(self.to_dict())

    def with_operating(self, **changes: float) -> Scene:
        """A copy at another operating point (load, us, slip, temperatures); re-validated."""
        d = self.to_dict()
        reject_unknown_keys("operating", changes, {"load", "us", "slip", "T_oil", "T_surface1", "T_surface2", "pmax"})
        if "pmax" in changes:
            d["operating"].pop("load", None)
        d["operating"].update(changes)
        # the scene itself was checked when it was loaded: check only what changes (a Stribeck
        # curve's speeds must not repeat the scene's warnings at every point)
        scene = _build_scene(d, f"{self.name} (modified)", check=False)
        resolved = {"load": scene.load, "us": scene.us, "T_oil": scene.T_oil,
                    "T_surface1": scene.T_surface1, "T_surface2": scene.T_surface2}
        for key in changes:
            if key in resolved:
                check_plausible(f"operating.{key}", resolved[key], OPERATING_PLAUSIBLE[key])
            elif key == "pmax":
                check_plausible("operating.pmax", scene.hertz.pmax, "pmax")
        return scene

    def with_supply(self, **changes: Any) -> Scene:
        """A copy with another oil supply (``hoil``, ``hoil_over_sigma``, ``delta``); re-validated."""
        d = self.to_dict()
        reject_unknown_keys("supply", changes, {"hoil", "hoil_over_sigma", "delta"})
        d.setdefault("supply", {}).update(changes)
        scene = _build_scene(d, f"{self.name} (modified)", check=False)
        if "hoil" in changes:
            check_plausible("supply.hoil", scene.supply.hoil, "hoil")
        return scene


def _isnan(v: Any) -> bool:
    return isinstance(v, float) and math.isnan(v)


# -- building and validation ----------------------------------------------------------------
def _section(data: dict, key: str, required: bool = True) -> dict:
    sec = data.get(key)
    if sec is None:
        if required:
            raise InputError(f"scene is missing the [{key}] table")
        return {}
    if not isinstance(sec, dict):
        raise InputError(f"[{key}] must be a table, got {type(sec).__name__}")
    return sec


def _text(field_name: str, value: Any) -> str:
    if not isinstance(value, str):
        raise InputError(f"{field_name} = {value!r} must be a string")
    return value


def _temperature(field_name: str, value: Any) -> float:
    return _require(field_name, value, T_MIN_C, T_MAX_C, "degC", "temperature")


def _require(field_name: str, value: Any, lo: float, hi: float, units: str, key: str, **kw: bool) -> float:
    """:func:`require_range`; a refusal also names the probable unit mistake (``key`` of
    :data:`~ehl_multigrid.model.plausibility.PLAUSIBLE`), e.g. a roughness of 0.2 m given in um."""
    try:
        return require_range(field_name, value, lo, hi, units, **kw)
    except InputError as exc:
        hint = unit_hint(key, value) if isinstance(value, (int, float)) and not isinstance(value, bool) else ""
        raise InputError(f"{exc}: {hint}" if hint else str(exc)) from None


def _solid(field_name: str, spec: Any, extra: dict[str, Material] | None = None) -> Solid:
    if isinstance(spec, str):
        try:
            return material(spec, extra)
        except InputError as exc:
            raise InputError(f"solids.{field_name}: {exc}") from None
    if isinstance(spec, dict):
        try:
            base = material(str(spec.get("preset", "steel")), extra)
            from .materials import MATERIAL_KEYS

            return base.with_changes(**convert_table(f"solids.{field_name}", spec, MATERIAL_KEYS))
        except InputError as exc:
            raise InputError(f"solids.{field_name}: {exc}") from None
    raise InputError(f"solids.{field_name} = {spec!r} must be a material name or a table")


def _with_units(data: dict, key: str, required: bool = True) -> dict:
    """The section ``key`` with its scalar values converted from strings with units."""
    return convert_table(key, _section(data, key, required), UNIT_KINDS[key])


def _range(field_name: str, spec: Any, lo: float, hi: float, units: str, lo_open: bool) -> Range:
    try:
        return _range_unchecked(field_name, spec, lo, hi, units, lo_open)
    except InputError as exc:
        if field_name == "slip" and "outside the allowed range" in str(exc):
            raise InputError(f"{exc} ({SLIP_DEFINITION})") from None
        raise


def _range_ends(rng: Range) -> list[tuple[str, float]]:
    """``(label, value)`` of a range's given values: its list, or its min and max."""
    name = f"ranges.{rng.field}"
    if rng.explicit is not None:
        return [(f"{name}[{i}]", v) for i, v in enumerate(rng.explicit)]
    return [(f"{name}.min", rng.min), (f"{name}.max", rng.max)]


def _range_unchecked(field_name: str, spec: Any, lo: float, hi: float, units: str, lo_open: bool) -> Range:
    name = f"ranges.{field_name}"
    kind = RANGE_KINDS[field_name]
    if isinstance(spec, list):
        spec = [to_canonical(f"{name}[{i}]", v, kind) if isinstance(v, str) else v
                for i, v in enumerate(spec)]
    elif isinstance(spec, dict):
        spec = {k: to_canonical(f"{name}.{k}", v, kind) if k in ("min", "max") and isinstance(v, str)
                else v for k, v in spec.items()}
    if isinstance(spec, list):
        if not spec:
            raise InputError(f"{name} is an empty list")
        vals = tuple(require_range(f"{name}[{i}]", v, lo, hi, units, lo_open=lo_open) for i, v in enumerate(spec))
        return Range(field_name, explicit=vals)
    if isinstance(spec, dict):
        reject_unknown_keys(name, spec, {"min", "max", "n", "log"})
        for k in ("min", "max", "n"):
            if k not in spec:
                raise InputError(f"{name} needs '{k}' (a table {{min, max, n, log}} or a list)")
        vmin = require_range(f"{name}.min", spec["min"], lo, hi, units, lo_open=lo_open)
        vmax = require_range(f"{name}.max", spec["max"], vmin, hi, units)
        n = spec["n"]
        if not isinstance(n, int) or isinstance(n, bool) or n < 1 or n > 100000:
            raise InputError(f"{name}.n = {n!r} must be an integer in [1, 100000]")
        log = spec.get("log", False)
        if not isinstance(log, bool):
            # TOML has true/false; a string such as "no" must not switch log spacing on
            raise InputError(f"{name}.log = {log!r} must be true or false")
        if log and vmin <= 0:
            raise InputError(f"{name}.min = {vmin:.6g} {units} must be > 0 for a log range")
        return Range(field_name, None, vmin, vmax, n, log)
    raise InputError(f"{name} = {spec!r} must be a list or a table {{min, max, n, log}}")


def _build_scene(data: dict[str, Any], origin: str, check: bool = True) -> Scene:
    """The validated scene of ``data``; with ``check``, then the plausibility of its inputs and
    derived results (:func:`_check_plausibility`)."""
    if not isinstance(data, dict):
        raise InputError(f"scene {origin} must be a table")
    reject_unknown_keys("scene top level", data, TOP_KEYS)
    # (field, value, quantity of plausibility.PLAUSIBLE) of every input to check for plausibility
    plaus: list[tuple[str, float, str]] = []
    name = _text("name", data.get("name", Path(origin).stem))
    description = _text("description", data.get("description", ""))
    source = _text("source", data.get("source", ""))

    extra_materials = materials_from_tables(data["materials"]) if "materials" in data else {}
    element = element_contact(data["element"], check=check) if "element" in data else None

    contact = _with_units(data, "contact", required=element is None)
    reject_unknown_keys("contact", contact, {"kind", "length"})
    if element is not None:
        kind = require_choice("contact.kind", contact.get("kind", element.kind), CONTACT_KINDS)
        if kind != element.kind:
            raise InputError(
                f"contact.kind = {kind!r} contradicts [element] kind = {element.element!r}, "
                f"which gives a {element.kind!r} contact; leave contact.kind out"
            )
        if "length" in contact:
            raise InputError("contact.length is given by the [element] table; leave it out")
        if element.kind == "line":
            contact = {**contact, "length": element.length}
    kind = require_choice("contact.kind", contact.get("kind", element.kind if element else None), CONTACT_KINDS)
    if kind == "line":
        if "length" not in contact:
            raise InputError("contact.length (B, m) is required for a line contact")
        length = require_positive("contact.length", contact["length"], "m")
        plaus.append(("contact.length", length, "line_length"))
    else:
        if "length" in contact:
            raise InputError(f"contact.length is only meaningful for a line contact, not {kind!r}")
        length = math.nan

    if element is not None:
        if "geometry" in data:
            raise InputError("give [geometry] or [element], not both (the element gives Rx and Ry)")
        Rx, Ry = _reduced_radii({"Rx": element.Rx, "Ry": element.Ry}, kind)
    else:
        geo = _with_units(data, "geometry")
        reject_unknown_keys("geometry", geo, {"Rx", "Ry", "R1x", "R2x", "R1y", "R2y"})
        Rx, Ry = _reduced_radii(geo, kind)
        # the radii as given (body radii or the reduced ones); the [element] checks its own
        plaus += [(f"geometry.{k}", geo[k], "body_radius" if k[1] in "12" else k)
                  for k in ("Rx", "Ry", "R1x", "R2x", "R1y", "R2y") if k in geo]

    solids = _with_units(data, "solids", required=False)
    reject_unknown_keys("solids", solids, {"body1", "body2", "E_reduced"})
    body1 = _solid("body1", solids.get("body1", "steel"), extra_materials)
    body2 = _solid("body2", solids.get("body2", "steel"), extra_materials)
    for label, body in (("body1", body1), ("body2", body2)):
        plaus += [(f"solids.{label} ({body.name}).{k}", getattr(body, k), q) for k, q in SOLID_PLAUSIBLE.items()]
    if "E_reduced" in solids:
        E_red = _require("solids.E_reduced", solids["E_reduced"], 1e6, 4e12, "Pa", "E_reduced")
        plaus.append(("solids.E_reduced", E_red, "E_reduced"))
    else:
        E_red = reduced_modulus_of(body1, body2)

    op = _with_units(data, "operating", required=element is None)
    reject_unknown_keys("operating", op, set(UNIT_KINDS["operating"]))
    lub_spec = _section(data, "lubricant")
    oil = None
    if is_oil_table(lub_spec):
        oil, oil_options = oil_from_table(lub_spec)
        if "T0" in oil_options:
            T_ref = oil_options["T0"]
        elif "T_oil" in op:
            T_ref = _temperature("operating.T_oil", op["T_oil"])
            if not DATASHEET_T_MIN <= T_ref <= DATASHEET_T_MAX:
                # the data-sheet oil is built at the inlet temperature: name the field given
                hint = unit_hint("temperature", T_ref)
                raise InputError(f"operating.T_oil = {T_ref:g} degC is outside the range [{DATASHEET_T_MIN:g}, "
                                 f"{DATASHEET_T_MAX:g}] degC of the data-sheet oil model{f': {hint}' if hint else ''}")
        else:
            T_ref = 40.0
        lub = oil.lubricant(T_ref, oil_options.get("T_fit"))
    else:
        lub = _preset_lubricant(convert_table("lubricant", lub_spec, UNIT_KINDS["lubricant"]))

    if "load" in op and "pmax" in op:
        raise InputError("[operating] needs exactly one of load (N) or pmax (Pa)")
    if "load" not in op and "pmax" not in op:
        if element is None:
            raise InputError("[operating] needs exactly one of load (N) or pmax (Pa)")
        load = require_positive("element load", element.load, "N")
    elif "load" in op:
        load = require_positive("operating.load", op["load"], "N")
        plaus.append(("operating.load", load, "load"))
    else:
        pmax = _require("operating.pmax", op["pmax"], 1e5, 2e10, "Pa", "pmax")
        plaus.append(("operating.pmax", pmax, "pmax"))
        if kind == "line":
            load = hertz.load_for_pmax_line(pmax, length, Rx, E_red)
        else:
            load = hertz.load_for_pmax_point(pmax, Rx, Ry, E_red)
    if "us" in op and "entrainment_speed" in op:
        raise InputError("[operating] give us (sum velocity u1 + u2) or entrainment_speed ((u1 + u2)/2), not both")
    if "us" in op:
        us = _require("operating.us", op["us"], 0.0, US_MAX, "m/s", "us", lo_open=True)
        plaus.append(("operating.us", us, "us"))
    elif "entrainment_speed" in op:
        us = 2.0 * _require("operating.entrainment_speed", op["entrainment_speed"], 0.0, US_MAX / 2.0, "m/s",
                            "entrainment_speed", lo_open=True)
        plaus.append(("operating.entrainment_speed", us / 2.0, "entrainment_speed"))
    elif element is not None:
        us = require_range("element sum velocity u1 + u2", element.us, 0.0, US_MAX, "m/s", lo_open=True)
        plaus.append(("element sum velocity u1 + u2", us, "us"))
    else:
        raise InputError("operating.us (sum velocity u1 + u2, m/s) or operating.entrainment_speed is required")
    if "slip" in op and "srr" in op:
        raise InputError(f"operating.slip = {op['slip']!r} and operating.srr = {op['srr']!r}: give one "
                         f"(slip S = 2(u1-u2)/(u1+u2) = 2 SRR)")
    if "srr" in op:
        # the literature's slide-to-roll ratio on the sum speed, half the package's slip
        try:
            srr = require_range("operating.srr", op["srr"], -1.0, 1.0, "-")
        except InputError as exc:
            raise InputError(f"{exc} (SRR = (u1-u2)/(u1+u2); the package's slip S = 2 SRR)") from None
        slip = 2.0 * srr
    elif "slip" in op:
        slip = require_slip("operating.slip", op["slip"])
    else:
        slip = require_slip("element slip", element.slip) if element else 0.0
    T_oil = _temperature("operating.T_oil", op.get("T_oil", lub.T0))
    T_s1 = _temperature("operating.T_surface1", op.get("T_surface1", T_oil))
    T_s2 = _temperature("operating.T_surface2", op.get("T_surface2", T_oil))
    # the surfaces default to the oil temperature: one warning for one mistake
    plaus += [(f, T, "temperature") for f, T in (("operating.T_oil", T_oil), ("operating.T_surface1", T_s1),
                                                  ("operating.T_surface2", T_s2)) if f.endswith("oil") or T != T_oil]

    rng = _section(data, "ranges", required=False)
    reject_unknown_keys("ranges", rng, {"us", "slip", "load", "pmax"})
    ranges: dict[str, Range] = {}
    if "us" in rng:
        ranges["us"] = _range("us", rng["us"], 0.0, US_MAX, "m/s", lo_open=True)
    if "slip" in rng:
        ranges["slip"] = _range("slip", rng["slip"], -2.0, 2.0, "-", lo_open=False)
    if "load" in rng:
        ranges["load"] = _range("load", rng["load"], 0.0, 1e9, "N", lo_open=True)
    if "pmax" in rng:
        ranges["pmax"] = _range("pmax", rng["pmax"], 1e5, 2e10, "Pa", lo_open=False)
    for key in ("us", "load", "pmax"):
        if key in ranges:
            plaus += [(label, v, key) for label, v in _range_ends(ranges[key])]

    rough = _roughness(_with_units(data, "roughness", required=False))
    if rough is not None:
        plaus += [(f"roughness.{k}", getattr(rough, k), q) for k, q in ROUGHNESS_PLAUSIBLE.items()
                  # sigma_s and dd default to fractions of Rq: one warning for one mistake
                  if not (k == "sigma_s" and rough.sigma_s == 0.7 * rough.Rq)
                  and not (k == "dd" and rough.dd == 0.82 * rough.Rq)]

    sup = _with_units(data, "supply", required=False)
    reject_unknown_keys("supply", sup, {"hoil", "hoil_over_sigma", "delta", "hoil_profile"})
    profile = _hoil_profile(sup.get("hoil_profile"))
    if profile and kind == "line":
        raise InputError("supply.hoil_profile is a layer across the track of a point or elliptic "
                         "contact; a line contact takes a uniform supply.hoil")
    if profile and "hoil" in sup:
        raise InputError("give either supply.hoil (a uniform layer) or supply.hoil_profile (a layer "
                         "across the track, whose centre value is the hoil), not both")
    hoil = (float(np.interp(0.0, *profile)) if profile else
            _require("supply.hoil", sup.get("hoil", math.inf), 0.0, math.inf, "m", "hoil", lo_open=True))
    plaus.append(("supply.hoil", hoil, "hoil"))
    hos = sup.get("hoil_over_sigma", [])
    if not isinstance(hos, list):
        raise InputError(f"supply.hoil_over_sigma = {hos!r} must be a list")
    hos_t = tuple(require_range(f"supply.hoil_over_sigma[{i}]", v, 0.0, math.inf, "-", lo_open=True) for i, v in enumerate(hos))
    delta = sup.get("delta", 3.5)
    if isinstance(delta, str):  # the exponent from the flooded inlet (the mixed layer computes it)
        if delta != "inlet":
            raise InputError(f"supply.delta = {delta!r} must be a number in [0.5, 20] or 'inlet' "
                             "(Chevalier's exponent from the flooded inlet length)")
    else:
        delta = require_range("supply.delta", delta, 0.5, 20.0, "-")
    if hos_t and rough is None:
        raise InputError("supply.hoil_over_sigma needs a [roughness] table (sigma = Rq)")

    feature = _with_units(data, "feature", required=False)
    for key, value in feature.items():
        # positions and sizes: the transient layer validates the table, but a NaN must not
        # travel that far (it would end as a solve that does not converge)
        if isinstance(value, float) and not math.isfinite(value):
            raise InputError(f"feature.{key} = {value} is not a finite number")

    solver = _section(data, "solver", required=False)
    reject_unknown_keys("solver", solver, {"ehl", "thermal", "mixed"})
    for k, v in solver.items():
        if not isinstance(v, dict):
            raise InputError(f"[solver.{k}] must be a table of options")

    scene = Scene(
        name=name, description=description, source=source, kind=kind, length=length,
        Rx=Rx, Ry=Ry, body1=body1, body2=body2, E_reduced=E_red, lubricant=lub,
        load=load, us=us, slip=slip, T_oil=T_oil, T_surface1=T_s1, T_surface2=T_s2,
        ranges=ranges, roughness=rough, supply=Supply(hoil, hos_t, delta, profile), solver=solver,
        feature=feature,
        raw=data, element=element, oil=oil,
    )
    if check:
        _check_plausibility(scene, plaus)
    return scene


#: Quantity of :data:`~ehl_multigrid.model.plausibility.PLAUSIBLE` of each property of a solid.
SOLID_PLAUSIBLE = {"E": "E", "nu": "poisson", "rho": "solid_density", "k": "solid_conductivity",
                   "cp": "solid_specific_heat", "hardness": "hardness"}
#: ... of each roughness parameter (Ra and the summit parameters only when given: nan passes).
ROUGHNESS_PLAUSIBLE = {"Rq": "roughness", "Ra": "roughness", "sigma_s": "roughness", "dd": "roughness",
                       "n": "summit_density", "beta": "summit_radius", "fc": "boundary_friction",
                       "hardness": "hardness"}
#: ... of each property of a lubricant (the viscosity is checked at the inlet, see below).
LUBRICANT_PLAUSIBLE = {"z": "roelands_z", "S0": "roelands_S0", "rho0": "oil_density",
                       "alpha_T": "thermal_expansion", "cp0": "oil_specific_heat",
                       "k0": "oil_conductivity", "tau0": "tau0"}


def _check_plausibility(scene: Scene, inputs: list[tuple[str, float, str]]) -> None:
    """Warn about every implausible input (``(field, value, quantity)``), then about the
    lubricant and the derived results: the Hertz pressure, the fitted central film and the
    Moes groups: a :class:`~ehl_multigrid.model.errors.PlausibilityWarning` each, or in strict
    mode an :class:`InputError` for the first."""
    for field_name, value, key in inputs:
        check_plausible(field_name, value, key)
    lub = scene.lubricant
    for k, q in LUBRICANT_PLAUSIBLE.items():
        check_plausible(f"lubricant ({lub.name}).{k}", getattr(lub, k), q)
    # the viscosity the contact sees: at T0 as given, then (if that is plausible) at the inlet
    # temperature, then the pressure-viscosity coefficient there (one warning for one mistake)
    ok = check_plausible(f"lubricant ({lub.name}).eta0 (at T0 = {lub.T0:g} degC)", lub.eta0, "eta0")
    ok = ok and (scene.T_oil == lub.T0 or check_plausible(
        f"inlet viscosity eta(T_oil = {scene.T_oil:g} degC)", scene.eta0, "eta0"))
    if ok:
        check_plausible(f"pressure-viscosity coefficient alpha(T_oil = {scene.T_oil:g} degC)", scene.alpha, "alpha")
    try:
        pmax = scene.hertz.pmax
        M, L = scene.moes()
        _, hc = scene.central_film_fit()
    except (InputError, ValueError, ArithmeticError):
        return  # a result the model cannot form: the solver refuses the inputs itself
    if check_plausible("Hertz pmax", pmax, "hertz_pmax"):
        warn_model_range("pmax", pmax, "Hertz pmax")
    check_plausible("fitted central film hc_fit", hc, "film")
    check_plausible("Moes M", M, "moes_M")
    check_plausible("Moes L", L, "moes_L")


def _preset_lubricant(lub_spec: dict[str, Any]) -> Lubricant:
    """A lubricant from a preset with overrides, or from a full table of Roelands properties."""
    if "preset" in lub_spec:
        base = lubricant_preset(lub_spec["preset"])
        overrides = {k: v for k, v in lub_spec.items() if k != "preset"}
    else:
        missing = {"name", "eta0", "T0", "S0", "rho0", "T_rho", "alpha_T", "cp0", "T_cp0", "c_cp", "k0", "tau0"} - set(lub_spec)
        if "z" not in lub_spec and "alpha" not in lub_spec:
            missing.add("z (or alpha)")
        if missing:
            raise InputError(
                f"[lubricant] without a preset must give {sorted(missing)} "
                "(or describe the oil by oil = PRESET, iso_vg + vi, or nu40 + nu100)"
            )
        base = None
        overrides = lub_spec
    try:
        if base is None:
            z = lub_spec.get("z", 1.0)
            fields_ = {k: v for k, v in overrides.items() if k != "alpha"}
            fields_["z"] = z
            lub = Lubricant(**fields_)
            if "alpha" in overrides:
                lub = lub.with_changes(alpha=overrides["alpha"])
        else:
            if "alpha" in overrides and "z" in overrides:
                raise InputError("[lubricant] give alpha or z, not both")
            lub = base.with_changes(**overrides)
    except TypeError as exc:
        raise InputError(f"[lubricant]: {exc}") from None
    return lub


def _reduced_radii(geo: dict, kind: str) -> tuple[float, float]:
    has_reduced = "Rx" in geo or "Ry" in geo
    has_bodies = any(k in geo for k in ("R1x", "R2x", "R1y", "R2y"))
    if has_reduced and has_bodies:
        raise InputError("[geometry] give either Rx, Ry (reduced) or R1x, R2x, R1y, R2y, not both")
    if has_bodies:
        def inv(key: str) -> float:
            v = geo.get(key, math.inf)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or v == 0 or math.isnan(v):
                raise InputError(f"geometry.{key} = {v!r} m must be a non-zero radius (inf = flat, negative = concave)")
            return 1.0 / float(v)

        cx = inv("R1x") + inv("R2x")
        cy = inv("R1y") + inv("R2y")
        if not cx > 0:
            raise InputError(f"geometry: reduced curvature 1/Rx = {cx:.6g} 1/m must be > 0 (R1x, R2x)")
        Rx = 1.0 / cx
        Ry = 1.0 / cy if cy > 0 else math.inf
    else:
        if "Rx" not in geo:
            raise InputError("[geometry] needs Rx (m) or the body radii R1x, R2x, R1y, R2y")
        Rx = require_positive("geometry.Rx", geo["Rx"], "m")
        default_Ry = math.inf if kind == "line" else Rx
        Ry = require_positive("geometry.Ry", geo.get("Ry", default_Ry), "m", allow_inf=True)
    _require("geometry.Rx", Rx, 1e-6, 100.0, "m", "Rx")
    if kind == "line":
        if math.isfinite(Ry):
            raise InputError(f"geometry.Ry = {Ry:.6g} m must be inf for a line contact")
    else:
        _require("geometry.Ry", Ry, 1e-6, 100.0, "m", "Ry")
        if kind == "point" and not math.isclose(Rx, Ry, rel_tol=1e-9):
            raise InputError(
                f"contact.kind = 'point' needs Rx = Ry (got Rx = {Rx:.6g} m, Ry = {Ry:.6g} m); use 'elliptic'"
            )
        require_range("theta = Rx/Ry", Rx / Ry, THETA_MIN, THETA_MAX, "-")
    return Rx, Ry


def _roughness(sec: dict) -> Roughness | None:
    if not sec:
        return None
    allowed = {"Rq", "Ra", "sigma_s", "dd", "n", "beta", "fc", "hardness"}
    reject_unknown_keys("roughness", sec, allowed)
    if "Rq" not in sec:
        raise InputError("roughness.Rq (m) is required when a [roughness] table is given")
    Rq = _require("roughness.Rq", sec["Rq"], 1e-10, 1e-4, "m", "roughness")
    sigma_s = _require("roughness.sigma_s", sec.get("sigma_s", 0.7 * Rq), 1e-10, 1e-4, "m", "roughness")
    dd = _require("roughness.dd", sec.get("dd", 0.82 * Rq), -1e-4, 1e-4, "m", "roughness")
    n = _require("roughness.n", sec["n"], 1e4, 1e16, "1/m^2", "summit_density") if "n" in sec else math.nan
    beta = _require("roughness.beta", sec["beta"], 1e-8, 1e-1, "m", "summit_radius") if "beta" in sec else math.nan
    Ra = _require("roughness.Ra", sec["Ra"], 1e-10, 1e-4, "m", "roughness") if "Ra" in sec else math.nan
    fc = require_range("roughness.fc", sec.get("fc", 0.13), 0.0, 1.0, "-")
    hard = require_positive("roughness.hardness", sec.get("hardness", 5e9), "Pa")
    for key, what in (("n", "summit density, 1/m^2"), ("beta", "summit radius, m")):
        if key not in sec:
            # the Greenwood-Williamson asperity model (2.43-2.45) needs both; refusing here
            # saves a main job from failing at its Stribeck stage after the film solve
            raise InputError(
                f"roughness.{key} ({what}) is required: the Greenwood-Williamson asperity model needs "
                "n and beta besides Rq (measure them from a height map with `ehl surface FILE --write-scene`)"
            )
    return Roughness(Rq=Rq, sigma_s=sigma_s, dd=dd, n=n, beta=beta, Ra=Ra, fc=fc, hardness=hard)


# -- loading ----------------------------------------------------------------------------------
#: Largest scene file read [bytes]; a scene is a few kB of TOML.
MAX_SCENE_BYTES = 1_000_000


def _read_scene_text(path: Path) -> str:
    try:
        size = path.stat().st_size
        if size > MAX_SCENE_BYTES:
            raise InputError(f"scene file {str(path)!r} is {size} bytes; a scene is a TOML file of at most "
                             f"{MAX_SCENE_BYTES} bytes")
        raw = path.read_bytes()
    except OSError as exc:
        raise InputError(f"scene file {str(path)!r} cannot be read ({exc.strerror or exc})") from None
    if b"\x00" in raw:
        raise InputError(f"scene file {str(path)!r} is not a TOML text file (it holds binary data)")
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"scene file {str(path)!r} is not UTF-8 text as TOML requires "
                         f"(byte {exc.start}: {raw[exc.start:exc.start + 1]!r})") from None


def builtin_scene_names() -> list[str]:
    """Names of the scenes shipped in ``ehl_multigrid/scenes``."""
    files = resources.files("ehl_multigrid") / "scenes"
    return sorted(p.name[:-5] for p in files.iterdir() if p.name.endswith(".toml"))


DEFAULT_SCENE = "default"


def load_scene(name_or_path: str | Path | None = None) -> Scene:
    """Load a built-in scene by name or a TOML file by path (``None``: the default scene)."""
    if name_or_path is None:
        name_or_path = DEFAULT_SCENE
    path = Path(name_or_path)
    if path.suffix == ".toml" or path.exists():
        if path.exists() and not path.is_file():
            raise InputError(f"scene file {str(path)!r} is not a regular file")
        if not path.is_file():
            raise InputError(f"scene file {str(path)!r} does not exist")
        text = _read_scene_text(path)
        origin = str(path)
    else:
        res = resources.files("ehl_multigrid") / "scenes" / f"{name_or_path}.toml"
        if not res.is_file():
            raise InputError(
                f"scene {str(name_or_path)!r} is neither a file nor a built-in scene; "
                f"built-in scenes: {builtin_scene_names()}"
            )
        text = res.read_text()
        origin = f"builtin:{name_or_path}"
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"scene {origin} is not valid TOML: {exc}") from None
    data.setdefault("name", Path(str(name_or_path)).stem)
    return Scene.from_dict(data, origin)


def _hoil_profile(table: Any) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """``[supply] hoil_profile = {y = [...], hoil = [...]}`` (metres; ``y`` from the track
    centre, increasing, >= 0; layers finite and > 0) as ``(y, hoil)`` tuples; () when absent."""
    if table is None:
        return ()
    if not isinstance(table, dict) or set(table) != {"y", "hoil"}:
        raise InputError(f"supply.hoil_profile = {table!r} must be a table with the lists y [m] "
                         f"(distance from the track centre) and hoil [m]")
    ys, hs = table["y"], table["hoil"]
    if not (isinstance(ys, list) and isinstance(hs, list)) or len(ys) != len(hs) or len(ys) < 2:
        raise InputError(f"supply.hoil_profile: y and hoil must be lists of equal length >= 2 "
                         f"(got {len(ys) if isinstance(ys, list) else ys!r} and "
                         f"{len(hs) if isinstance(hs, list) else hs!r})")
    y = tuple(require_range(f"supply.hoil_profile.y[{i}]", v, 0.0, 1.0, "m") for i, v in enumerate(ys))
    h = tuple(require_range(f"supply.hoil_profile.hoil[{i}]", v, 0.0, 1e-2, "m", lo_open=True)
              for i, v in enumerate(hs))
    if any(b <= a for a, b in zip(y, y[1:], strict=False)):
        raise InputError(f"supply.hoil_profile.y = {list(y)} must increase")
    return (y, h)
