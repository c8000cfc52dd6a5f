"""Plausible ranges of physical inputs and derived results for real contacts.

Plausibility (:data:`PLAUSIBLE`): the range of each physical input (and of a few derived results)
that real contacts have -- ball and roller bearings, gears, cams, tribometers -- and the unit
mistakes that would explain a value outside it. :func:`check_plausible` warns
(:class:`~ehl_multigrid.model.errors.PlausibilityWarning`) naming the field, the value, the range
and the probable mistake ("did you give millimetres? 10.32 mm = 0.01032 m").
Strict mode turns the warnings into errors (:mod:`ehl_multigrid.model.errors`).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

from ehl_multigrid.model.errors import ModelRangeWarning, warn_implausible


@dataclass(frozen=True)
class UnitMistake:
    """A unit a value may have been typed in by mistake: ``canonical = given * scale + offset``."""

    name: str  # what the message calls it ("millimetres")
    unit: str  # how to write it in a scene (pint spelling, "mm")
    scale: float
    offset: float = 0.0


MM = UnitMistake("millimetres", "mm", 1e-3)
UM = UnitMistake("micrometres", "um", 1e-6)
INCH = UnitMistake("inches", "inch", 0.0254)
KELVIN = UnitMistake("kelvin", "K", 1.0, -273.15)
FAHRENHEIT = UnitMistake("degrees Fahrenheit", "degF", 5.0 / 9.0, -32.0 * 5.0 / 9.0)
RPM = UnitMistake("revolutions per minute", "rpm", 2.0 * math.pi / 60.0)
RPM_AS_HZ = UnitMistake("revolutions per minute", "rpm", 1.0 / 60.0)
MPA = UnitMistake("MPa", "MPa", 1e6)
GPA = UnitMistake("GPa", "GPa", 1e9)
KN = UnitMistake("kN", "kN", 1e3)
MPAS = UnitMistake("mPa s (centipoise)", "mPa*s", 1e-3)
CENTISTOKES = UnitMistake("mm^2/s (centistokes)", "cSt", 1e-6)
G_CM3 = UnitMistake("g/cm^3", "g/cm^3", 1e3)
PER_MM2 = UnitMistake("summits per mm^2", "1/mm^2", 1e6)
PER_GPA = UnitMistake("1/GPa", "1/GPa", 1e-9)
KJ = UnitMistake("kJ/(kg K)", "kJ/(kg*K)", 1e3)
MM_S = UnitMistake("mm/s", "mm/s", 1e-3)


@dataclass(frozen=True)
class Plausible:
    """The range ``[lo, hi]`` (in ``unit``, the canonical unit) real contacts have, the unit
    mistakes that would explain a value outside it, and what to say when none does."""

    lo: float
    hi: float
    unit: str
    mistakes: tuple[UnitMistake, ...] = ()
    note: str = "check the value and its unit"
    #: compare ``|value|`` (signed quantities: concave radii, surface speeds)
    magnitude: bool = False
    #: the value also shown in another unit: (unit, factor)
    also: tuple[str, float] | None = None


_LEN = (MM, INCH)

#: Plausible ranges of scene inputs and derived results for real contacts (bearings, gears,
#: cams, tribometers; docs/inputs.md): outside is possible but more often a unit mistake. Hard
#: limits (negative, NaN, beyond the models) are checked where the values are read.
PLAUSIBLE: dict[str, Plausible] = {
    # operating point
    "load": Plausible(1e-3, 1e7, "N", (KN,), "no bearing, gear or tribometer contact carries that"),
    "pmax": Plausible(1e6, 1e10, "Pa", (MPA, GPA)),
    "us": Plausible(1e-6, 200.0, "m/s", (MM_S,)),
    "entrainment_speed": Plausible(5e-7, 100.0, "m/s", (MM_S,)),
    "surface_speed": Plausible(0.0, 100.0, "m/s", (MM_S,), magnitude=True),
    "temperature": Plausible(-40.0, 250.0, "degC", (KELVIN, FAHRENHEIT),
                             "lubricated contacts run between about -40 and 250 degC"),
    # geometry
    "Rx": Plausible(1e-4, 1.0, "m", _LEN),
    "Ry": Plausible(1e-4, 10.0, "m", _LEN),
    "body_radius": Plausible(1e-4, 3.0, "m", _LEN, magnitude=True),
    "line_length": Plausible(1e-4, 1.0, "m", _LEN),
    # solids
    "E": Plausible(1e6, 1.2e12, "Pa", (GPA, MPA), "solids range from rubber (1 MPa) to diamond (1.05e12 Pa)"),
    "E_reduced": Plausible(1e6, 1.5e12, "Pa", (GPA, MPA)),
    "poisson": Plausible(0.05, 0.5, "-", (), "solids have 0.07 (diamond) to 0.5 (rubber)"),
    "solid_density": Plausible(500.0, 2.5e4, "kg/m^3", (G_CM3,)),
    "solid_conductivity": Plausible(0.05, 2500.0, "W/(m K)"),
    "solid_specific_heat": Plausible(100.0, 3000.0, "J/(kg K)", (KJ,)),
    "hardness": Plausible(1e7, 1.5e11, "Pa", (GPA, MPA)),
    # lubricant
    "eta0": Plausible(1e-4, 20.0, "Pa s", (MPAS,),
                      "lubricants at their inlet temperature have 1e-4 Pa s (hot light oil) to about "
                      "20 Pa s (a heavy gear oil near 0 degC)"),
    "kinematic_viscosity": Plausible(1e-6, 1e-2, "m^2/s", (CENTISTOKES,)),
    "alpha": Plausible(3e-9, 6e-8, "1/Pa", (PER_GPA,),
                       "lubricants have about 5e-9 (water-glycol) to 4e-8 1/Pa (traction fluids, PFPE)"),
    "roelands_z": Plausible(0.25, 1.3, "-", (), "Roelands z of lubricants lies between about 0.3 and 1.1"),
    "roelands_S0": Plausible(0.5, 3.0, "-", (), "Roelands S0 of lubricants lies between about 0.8 and 2"),
    "oil_density": Plausible(700.0, 2000.0, "kg/m^3", (G_CM3,)),
    "thermal_expansion": Plausible(1e-4, 2e-3, "1/K"),
    "oil_specific_heat": Plausible(1000.0, 4500.0, "J/(kg K)", (KJ,)),
    "oil_conductivity": Plausible(0.05, 0.7, "W/(m K)"),
    "tau0": Plausible(1e5, 1e8, "Pa", (MPA,)),
    # roughness and supply
    "roughness": Plausible(1e-9, 1e-5, "m", (UM,), magnitude=True),
    "summit_density": Plausible(1e8, 1e14, "1/m^2", (PER_MM2,)),
    "summit_radius": Plausible(1e-7, 1e-3, "m", (MM, UM)),
    "boundary_friction": Plausible(0.01, 0.5, "-"),
    "hoil": Plausible(1e-9, 1e-3, "m", (UM, MM)),
    # machine elements
    "angular_speed": Plausible(1e-3, 2000.0, "rad/s", (RPM,),
                               "only spindle and turbine bearings run above about 19000 rpm",
                               also=("rpm", 60.0 / (2.0 * math.pi))),
    "frequency": Plausible(1e-2, 1e3, "Hz", (RPM_AS_HZ,)),
    "teeth": Plausible(12.0, 500.0, "teeth", (),
                       "a standard (unshifted) 20 deg gear undercuts below 17 teeth, and pinions of "
                       "fewer than about 12 teeth need a profile shift, which this gear model leaves out"),
    "rolling_elements": Plausible(5.0, 150.0, "elements"),
    "rolling_element_diameter": Plausible(5e-4, 0.2, "m", _LEN),
    "pitch_diameter": Plausible(2e-3, 6.0, "m", _LEN),
    "roller_length": Plausible(5e-4, 0.5, "m", _LEN),
    "module": Plausible(2e-4, 0.05, "m", (MM,)),
    "face_width": Plausible(1e-3, 1.0, "m", _LEN),
    "ball_radius": Plausible(5e-4, 0.1, "m", _LEN),
    "track_radius": Plausible(1e-3, 0.5, "m", _LEN),
    "stroke": Plausible(1e-5, 0.1, "m", (MM, UM)),
    "torque": Plausible(1e-3, 1e7, "N m"),
    "power": Plausible(0.1, 1e8, "W"),
    # derived results
    "hertz_pmax": Plausible(1e6, 1e10, "Pa", (),
                            "no steel or ceramic carries that (rolling contacts stay below about 4 GPa); "
                            "check the load and the radii and their units"),
    "film": Plausible(1e-10, 1e-3, "m", (),
                      "an EHL film is between about a nanometre and a few micrometres; check the "
                      "viscosity, the speed, the load and the radii and their units"),
    "moes_M": Plausible(1e-2, 1e6, "-", (),
                        "far outside the published Moes and Nijenbanning fits; check the load, speed "
                        "and viscosity and their units"),
    "moes_L": Plausible(0.0, 100.0, "-", (),
                        "far outside the published Moes and Nijenbanning fits (L up to about 25); "
                        "check the viscosity, pressure-viscosity coefficient and speed and their units"),
}

REAL_CONTACTS = "real contacts (bearings, gears, cams, tribometers)"

#: thinnest film [m] the continuum Reynolds equation describes: below a few molecular layers the
#: oil's structure and the surfaces' forces set the film (Johnston, Wayte & Spikes 1991 measured
#: EHL behaviour down to a few nanometres)
CONTINUUM_FILM = 2e-9
#: largest Hertz pressure [Pa] below which the viscosity laws (Roelands, Barus) rest on
#: measurements; above it they are extrapolated and bearing steel approaches its yield
MEASURED_VISCOSITY_PRESSURE = 3e9


def model_range_warning(what: str, value: float, field: str) -> str | None:
    """Why ``value`` of ``field``, a ``what`` (``"film"`` [m], ``"pmax"`` [Pa]), lies where the
    models are an extrapolation, or None. The caller warns with a
    :class:`~ehl_multigrid.model.errors.ModelRangeWarning`."""
    v = float(value)
    if not math.isfinite(v):
        return None
    if what == "film" and 0.0 < v < CONTINUUM_FILM:
        return (f"{field} = {v * 1e9:.3g} nm is below about {CONTINUUM_FILM * 1e9:g} nm, a few molecular "
                f"layers, where the continuum Reynolds equation of this package no longer describes "
                f"the oil: the film is the model's, the contact's may differ (and is likely mixed "
                f"or boundary lubricated)")
    if what == "pmax" and v > MEASURED_VISCOSITY_PRESSURE:
        return (f"{field} = {v / 1e9:.3g} GPa is above about {MEASURED_VISCOSITY_PRESSURE / 1e9:g} GPa: "
                f"the viscosity laws are extrapolated beyond the pressures they were measured at and "
                f"bearing steel approaches its yield, so the film and friction are the model's "
                f"extrapolation")
    return None


def unit_hint(key: str, value: float) -> str:
    """The probable unit mistake behind ``value`` for the quantity ``key`` of :data:`PLAUSIBLE`
    (the first listed unit in which the number is plausible), as a sentence; ``""`` if none."""
    spec = PLAUSIBLE[key]
    try:
        v = float(value)
    except (TypeError, ValueError):
        return ""
    if not math.isfinite(v):
        return ""
    for mk in spec.mistakes:
        si = v * mk.scale + mk.offset
        if spec.lo <= (abs(si) if spec.magnitude else si) <= spec.hi:
            return (f"did you give {mk.name}? {v:.6g} {mk.unit} = {si:.4g} {spec.unit} "
                    f"(plain numbers are {spec.unit}; write '{v:.6g} {mk.unit}')")
    return ""


def implausibility(field: str, value: float, key: str, units_given: bool = False) -> str | None:
    """Why ``value`` of ``field`` is implausible for a real contact (field, value, plausible
    range and the probable unit mistake or what to check), or ``None`` when it is plausible.
    ``units_given``: the input named its unit, so no unit mistake is suggested.

    Non-finite values pass: NaN is refused where values are read, ``inf`` means flat or flooded.
    """
    spec = PLAUSIBLE[key]
    v = float(value)
    if not math.isfinite(v) or spec.lo <= (abs(v) if spec.magnitude else v) <= spec.hi:
        return None
    unit = "" if spec.unit == "-" else f" {spec.unit}"
    shown = f"{field} = {v:.6g}{unit}"
    if spec.also is not None:
        shown += f" ({v * spec.also[1]:.6g} {spec.also[0]})"
    span = f"[{spec.lo:g}, {spec.hi:g}]{unit}"
    if spec.magnitude:
        span = f"|value| in {span}"
    hint = "" if units_given else unit_hint(key, v)
    return f"{shown} is outside the plausible range {span} of {REAL_CONTACTS}: {hint or spec.note}"


def check_plausible(field: str, value: float, key: str, units_given: bool = False) -> bool:
    """Warn (:class:`~ehl_multigrid.model.errors.PlausibilityWarning`; an :class:`InputError` in
    strict mode) when ``value`` of ``field`` lies outside the plausible range of ``key``
    (``units_given``: see :func:`implausibility`).

    Returns whether the value is plausible.
    """
    message = implausibility(field, value, key, units_given)
    if message is None:
        return True
    warn_implausible(message, stacklevel=2)
    return False


def warn_model_range(what: str, value: float, field: str) -> bool:
    """Warn (:class:`~ehl_multigrid.model.errors.ModelRangeWarning`) when ``value`` lies where
    the models are an extrapolation (:func:`model_range_warning`); returns whether it does not."""
    message = model_range_warning(what, value, field)
    if message is None:
        return True
    warnings.warn(message, ModelRangeWarning, stacklevel=2)
    return False
