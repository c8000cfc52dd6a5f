"""The inlet oil supply of a starved contact: validation and scaling.

The supplied layer ``hoil`` is the total oil layer on the surfaces ahead of the contact (both
surfaces together, at ambient pressure and density), the film that a flooded inlet would not
notice when it is thicker than the gap. In Venner's line-contact units (``X = x/b``,
``H = h R/b^2``) it is ``Hoil = hoil R/b^2``; in Moes units ``Hoil_Moes = Hoil 8 M/pi``
(like every film). ``Hoil = inf`` is the flooded inlet.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..model.errors import InputError, require_range

#: allowed range of the supplied layer in Venner units (``inf``: flooded)
HOIL_RANGE = (0.0, math.inf)


def check_hoil(hoil: Any, field: str = "hoil", units: str = "- (Venner: hoil R/b^2)") -> float:
    """The supplied layer as a float in ``(0, inf]`` or :class:`InputError` naming the field,
    the value and the allowed range (negative, zero and NaN layers are rejected)."""
    return require_range(field, hoil, *HOIL_RANGE, units, lo_open=True)


def check_profile(profile: Any, points: int, field: str = "hoil_profile",
                  units: str = "- (Venner: hoil R/b^2)") -> np.ndarray:
    """A supply profile across the track (one layer per grid line) as an array of ``points``
    values in ``(0, inf]``; a profile longer or shorter than the grid, or holding a bad
    value, raises :class:`InputError` naming the field, the value and the allowed range."""
    arr = np.asarray(profile, dtype=float)
    if arr.ndim != 1:
        raise InputError(f"{field} must be a 1-D list of layers, got shape {arr.shape}")
    if arr.shape[0] != points:
        raise InputError(f"{field} has {arr.shape[0]} values; the grid has {points} lines across "
                         f"the track, so the allowed length is exactly {points}")
    for i, v in enumerate(arr):
        check_hoil(v, f"{field}[{i}]", units)
    return arr


def hoil_venner(hoil_m: float, b: float, R: float) -> float:
    """``Hoil = hoil R/b^2`` from a layer ``hoil_m`` [m] (``inf`` stays ``inf``)."""
    hoil_m = require_range("supply.hoil", hoil_m, 0.0, math.inf, "m", lo_open=True)
    return math.inf if math.isinf(hoil_m) else hoil_m * R / b**2


def layer_across_track(supply: Any, a: float, Rx: float) -> Callable[[float], float]:
    """A scene's ``[supply] hoil_profile`` as the point solvers take it: the layer in Venner
    units (``hoil Rx/a^2``) at a row ``Y = y/a``."""
    def Hoil(Y: float) -> float:
        return hoil_venner(float(supply.layer_at(Y * a)), a, Rx)

    return Hoil
