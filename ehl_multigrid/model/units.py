"""Values with units in scene files: ``"7.94 mm"``, ``"1.5 GPa"``, ``"68 cSt"``, ``"70 degC"``.

A scene value is either a plain number, taken as given in the field's canonical unit (SI, with
temperatures in degC and angles in degrees as everywhere at the package's interface), or a
string with units, converted to the canonical unit by the units library pint. A value of the
wrong dimension ("7 GPa" for a length) raises :class:`InputError` naming the field, the value
and the expected dimension.

Rotational speeds: an angular speed written with a frequency unit (``"10 Hz"``, ``"50 1/s"``,
``"3000 1/min"``) is revolutions per unit time, ``omega = 2 pi f``; ``"1500 rpm"``, ``"5 turn/s"``
and ``"10 rad/s"`` carry their angle. (pint alone reads ``"10 Hz"`` as 10 rad/s, since the radian
is dimensionless.) A frequency written with an angle (``"3000 rpm"`` for a stroke frequency) is
``f = omega/(2 pi)``.

pint is imported and its registry built only when a string is first converted (about 0.15 s),
so scenes of plain numbers, and the ``ehl`` start-up, never pay for it.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any

from ehl_multigrid.model.errors import InputError

#: Canonical unit of each kind of quantity the scenes and machine-element helpers use.
#: Temperatures are degC (the thesis's convention); angles degrees (catalogue convention);
#: everything else SI.
CANONICAL: dict[str, str] = {
    "length": "m",
    "area": "m^2",
    "force": "N",
    "force_per_length": "N/m",
    "pressure": "Pa",
    "speed": "m/s",
    "angular_speed": "rad/s",
    "frequency": "Hz",
    "time": "s",
    "kinematic_viscosity": "m^2/s",
    "dynamic_viscosity": "Pa*s",
    "density": "kg/m^3",
    "temperature": "degC",
    "angle": "degree",
    "torque": "N*m",
    "power": "W",
    "conductivity": "W/(m*K)",
    "specific_heat": "J/(kg*K)",
    "inverse_area": "1/m^2",
    "inverse_pressure": "1/Pa",
    "inverse_temperature": "1/K",
    "dimensionless": "",
}


@lru_cache(maxsize=1)
def registry() -> Any:
    """The package's pint ``UnitRegistry``, created once on first use.

    Offset units (degC, degF) are converted to kelvin when multiplied, so ``"70 degC"``
    parses as a temperature rather than raising pint's offset-unit error.
    """
    import pint

    return pint.UnitRegistry(autoconvert_offset_to_baseunit=True)


def to_canonical(field: str, value: Any, kind: str) -> float:
    """Convert a scene value to the canonical unit of ``kind`` (see :data:`CANONICAL`).

    Parameters
    ----------
    field : str
        Dotted name of the scene field, used in error messages (``"element.ball_diameter"``).
    value : float, int or str
        A plain number (returned unchanged, as float) or a string with units.
    kind : str
        Kind of quantity, a key of :data:`CANONICAL`.

    Returns
    -------
    float
        The value in the canonical unit: SI, temperatures in degC, angles in degrees.

    Raises
    ------
    InputError
        If the string cannot be parsed or has the wrong dimension.
    """
    if kind not in CANONICAL:
        raise InputError(f"unknown quantity kind {kind!r}; known kinds are {sorted(CANONICAL)}")
    if isinstance(value, bool):
        raise InputError(f"{field} = {value!r} is not a number or a value with units")
    if isinstance(value, (int, float)):
        return float(value)
    if not isinstance(value, str):
        raise InputError(
            f"{field} = {value!r} must be a number or a string with units, e.g. '7.94 mm'"
        )
    unit = CANONICAL[kind]
    shown = unit or "dimensionless"
    ureg = registry()
    try:
        q = ureg.Quantity(value.strip())
    except Exception as exc:  # pint raises several unrelated types for unparsable text
        raise InputError(
            f"{field} = {value!r} is not a number or a value with units ({exc}); "
            f"expected a {kind.replace('_', ' ')} such as '1.0 {shown}'"
        ) from None
    if not hasattr(q, "units") or str(q.units) == "dimensionless":
        # "7.5" in quotes is a plain number in the canonical unit, like an unquoted 7.5.
        return float(getattr(q, "magnitude", q))
    target = ureg.Unit(unit) if unit else ureg.dimensionless
    if q.dimensionality != target.dimensionality:
        raise InputError(
            f"{field} = {value!r} has dimension {q.dimensionality}, but a "
            f"{kind.replace('_', ' ')} ({target.dimensionality}, in {shown}) is expected"
        )
    if kind in ("angular_speed", "frequency"):
        # the radian is dimensionless in pint: "10 Hz" would become 10 rad/s and "3000 rpm"
        # 314 Hz; a rotation count per time is 2 pi rad per revolution
        root = q.to_root_units()
        has_angle = "radian" in dict(root.unit_items())
        per_second = float(root.magnitude)
        if kind == "angular_speed":
            return per_second if has_angle else 2.0 * math.pi * per_second
        return per_second / (2.0 * math.pi) if has_angle else per_second
    return float(q.to(target).magnitude)


def convert_table(section: str, table: dict[str, Any], kinds: dict[str, str]) -> dict[str, Any]:
    """A copy of ``table`` with every key listed in ``kinds`` converted by :func:`to_canonical`.

    Keys not in ``kinds`` are copied unchanged (the caller validates them); so are values that
    are not strings or numbers (lists, tables), which the caller handles.
    """
    out = dict(table)
    for key, kind in kinds.items():
        v = out.get(key)
        if isinstance(v, (str, int, float)) and not isinstance(v, bool):
            out[key] = to_canonical(f"{section}.{key}", v, kind)
    return out
