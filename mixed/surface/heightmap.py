"""The height map: heights on a regular grid, in metres, with its spacings and history.

Every function of :mod:`mixed.surface` takes and returns a :class:`HeightMap`. Heights ``z`` are
stored in metres on a ``(ny, nx)`` array (first axis y, second axis x); missing points are NaN.
``history`` records every processing step (levelling, filling, filters) so the statistics say
which filter produced them (thesis 5.3 filters until psi ~ 1).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ehl_multigrid.model.errors import InputError, require_positive

#: Length units accepted for heights and spacings, in metres.
LENGTH_UNITS: dict[str, float] = {
    "m": 1.0,
    "mm": 1e-3,
    "um": 1e-6,
    "µm": 1e-6,
    "micron": 1e-6,
    "nm": 1e-9,
    "A": 1e-10,
    "angstrom": 1e-10,
}


def unit_factor(units: str | None, field_name: str = "units") -> float:
    """Metres per unit of ``units`` (``None`` means metres)."""
    if units is None:
        return 1.0
    key = str(units).strip()
    if key in LENGTH_UNITS:
        return LENGTH_UNITS[key]
    if key.lower() in LENGTH_UNITS:
        return LENGTH_UNITS[key.lower()]
    raise InputError(f"{field_name} = {units!r} is not a known length unit; allowed: {sorted(LENGTH_UNITS)}")


_LENGTH_RE = re.compile(r"^\s*([-+0-9.eE]+)\s*([A-Za-zµ]*)\s*$")


def parse_length(value: Any, field_name: str, default_units: str | None = None) -> float:
    """A length in metres from a number (in ``default_units``) or a string such as ``"0.781um"``."""
    if isinstance(value, str):
        m = _LENGTH_RE.match(value)
        if not m:
            raise InputError(f"{field_name} = {value!r} is not a length (e.g. 7.81e-7 or 0.781um)")
        try:
            num = float(m.group(1))
        except ValueError:
            raise InputError(f"{field_name} = {value!r} is not a length (e.g. 7.81e-7 or 0.781um)") from None
        units = m.group(2) or default_units
    else:
        num, units = value, default_units
    v = require_positive(field_name, num, units or "m") * unit_factor(units, f"{field_name} units")
    return v


@dataclass(frozen=True)
class HeightMap:
    """Heights ``z`` [m] on a regular grid with spacings ``dx`` (along axis 1) and ``dy`` (axis 0) [m].

    Attributes
    ----------
    z : (ny, nx) float array, NaN where the instrument gave no value.
    dx, dy : grid spacings [m].
    source : where the map came from (file name, generator).
    history : processing steps applied, in order (plain strings, e.g. ``"plane removed"``).
    meta : free metadata (units read from the file, generator parameters ...).
    """

    z: np.ndarray
    dx: float
    dy: float
    source: str = ""
    history: tuple[str, ...] = ()
    meta: dict[str, Any] = field(default_factory=dict, compare=False)

    def __post_init__(self) -> None:
        z = np.asarray(self.z, dtype=float)
        if z.ndim != 2:
            raise InputError(f"height map must be a 2-D array (ny, nx), got shape {z.shape}")
        if z.shape[0] < 3 or z.shape[1] < 3:
            raise InputError(
                f"height map shape {z.shape} is too small: the 9-point summit rule needs at least 3 x 3 points"
            )
        if np.isinf(z).any():
            raise InputError("height map contains infinite values; use NaN for missing points")
        if np.isnan(z).all():
            raise InputError("height map contains no valid (non-NaN) point")
        object.__setattr__(self, "z", z)
        object.__setattr__(self, "dx", require_positive("dx", self.dx, "m"))
        object.__setattr__(self, "dy", require_positive("dy", self.dy, "m"))

    @property
    def shape(self) -> tuple[int, int]:
        return self.z.shape  # type: ignore[return-value]

    @property
    def nx(self) -> int:
        return self.z.shape[1]

    @property
    def ny(self) -> int:
        return self.z.shape[0]

    @property
    def missing(self) -> np.ndarray:
        """Boolean mask of missing (NaN) points."""
        return np.isnan(self.z)

    @property
    def n_missing(self) -> int:
        return int(self.missing.sum())

    @property
    def x(self) -> np.ndarray:
        """x coordinates of the columns [m], starting at 0."""
        return np.arange(self.nx) * self.dx

    @property
    def y(self) -> np.ndarray:
        return np.arange(self.ny) * self.dy

    @property
    def area(self) -> float:
        """Sampled area ``nx dx * ny dy`` [m^2]."""
        return self.nx * self.dx * self.ny * self.dy

    def with_z(self, z: np.ndarray, step: str | None = None) -> HeightMap:
        """A copy with new heights and ``step`` appended to the history."""
        hist = self.history + ((step,) if step else ())
        return replace(self, z=np.asarray(z, dtype=float), history=hist, meta=dict(self.meta))

    def describe(self) -> str:
        return (
            f"{self.ny} x {self.nx} points, dx = {self.dx:.4g} m, dy = {self.dy:.4g} m"
            + (f", {self.n_missing} missing" if self.n_missing else "")
        )


def make_height_map(
    z: np.ndarray,
    dx: Any,
    dy: Any = None,
    units: str | None = None,
    xy_units: str | None = None,
    source: str = "<array>",
) -> HeightMap:
    """Build a :class:`HeightMap` from an array in ``units`` and spacings in ``xy_units``.

    ``dy`` defaults to ``dx``; spacings may be strings with a unit (``"0.781um"``).
    """
    if dx is None:
        raise InputError("dx (grid spacing along x, m) is required: the array carries no spacing")
    zf = unit_factor(units, "units")
    dxm = parse_length(dx, "dx", xy_units)
    dym = dxm if dy is None else parse_length(dy, "dy", xy_units)
    arr = np.asarray(z, dtype=float)
    if arr.ndim != 2:
        raise InputError(f"height map must be a 2-D array (ny, nx), got shape {arr.shape}")
    return HeightMap(arr * zf, dxm, dym, source=source, meta={"units": units or "m"})
