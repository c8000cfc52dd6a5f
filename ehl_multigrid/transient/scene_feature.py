"""A scene's ``[feature]`` table (physical units) as a dimensionless line-contact feature.

::

    [feature]
    kind = "dent"              # "waviness", "bump" or "dent"
    amplitude = 0.1e-6         # m: waviness amplitude, bump height or dent depth
    width = 50e-6              # m: bump/dent width W (cosine-Gaussian wavelength, Gaussian 1/e half-width)
    # wavelength = 100e-6      # m: waviness wavelength (instead of width)
    x0 = -3.0                  # start position of a bump/dent centre in Hertzian half-widths b
    shape = "cosine-gaussian"  # or "gaussian"
    body = 1                   # the surface that carries it (1 or 2)

Point (circular, elliptic) scenes also take ``angle`` (waviness: degrees between the wave
vector and the rolling direction; 0 transverse, 90 longitudinal) and ``y0`` (a dent's lateral
position in units of a); there ``x0`` is in units of the Hertz semi-axis ``a`` along the rolling
direction and the film unit is ``a^2/Rx``.

Venner units: ``A = a R / b^2``, ``Lambda = lambda / b``, ``W = w / b`` with the reduced radius
``R`` and the Hertzian half-width ``b`` of the scene's operating point. The slide-to-roll ratio
is the scene's ``slip`` (``S = (u1 - u2)/u_m``).
"""

from __future__ import annotations

from typing import Any

from ..line.problem import LineProblem
from ..model.errors import InputError, reject_unknown_keys, require_choice, require_range
from .features import Bump, Feature, Waviness
from .point_features import Dent2D, PointFeature, Waviness2D

KEYS = {"kind", "amplitude", "width", "wavelength", "x0", "shape", "body", "phase"}
POINT_KEYS = KEYS | {"angle", "y0"}


def feature_from_scene_table(table: dict[str, Any] | None, problem: LineProblem) -> tuple[Feature, int]:
    """``(feature, body)`` from a ``[feature]`` table in metres (see module docstring)."""
    kind, body, amp, length = _read_table(table, KEYS, problem, "b", "R, b")
    scale = problem.R / problem.b**2
    if kind == "waviness":
        return Waviness(amp * scale, length / problem.b, float(table.get("phase", 0.0))), body
    sign = -1.0 if kind == "dent" else 1.0
    return Bump(sign * amp * scale, length / problem.b, float(table.get("x0", -3.0)),
                str(table.get("shape", "cosine-gaussian"))), body


def point_feature_from_scene_table(table: dict[str, Any] | None, problem: Any) -> tuple[PointFeature, int]:
    """``(feature, body)`` of a point or elliptic scene from a ``[feature]`` table in metres
    (``problem`` a physical :class:`~ehl_multigrid.point.problem.PointProblem`)."""
    kind, body, amp, length = _read_table(table, POINT_KEYS, problem, "a", "Rx, a")
    scale = problem.Rx / problem.a**2
    if kind == "waviness":
        return Waviness2D(amp * scale, length / problem.a, float(table.get("angle", 0.0)),
                          float(table.get("phase", 0.0))), body
    sign = -1.0 if kind == "dent" else 1.0
    return Dent2D(sign * amp * scale, length / problem.a, float(table.get("x0", -2.5)),
                  float(table.get("y0", 0.0)), str(table.get("shape", "cosine-gaussian"))), body


def _read_table(table: dict[str, Any] | None, keys: set[str], problem: Any, unit: str,
                geometry: str) -> tuple[str, int, float, float]:
    """``(kind, body, amplitude [m], wavelength or width [m])`` of a checked ``[feature]``
    table; ``unit`` names the length unit of ``x0`` and ``geometry`` the scene's lengths it
    needs, in messages."""
    if not table:
        raise InputError(f"the scene has no [feature] table; add one (kind, amplitude, width or "
                         f"wavelength [m], x0 [{unit}], body) to run 'ehl transient'")
    reject_unknown_keys("feature", table, keys)
    if not problem.physical:
        raise InputError(f"a [feature] in metres needs a scene with known geometry ({geometry})")
    kind = require_choice("feature.kind", table.get("kind"), ("waviness", "bump", "dent"))
    body = int(require_range("feature.body", table.get("body", 1), 1, 2, "-"))
    amp = require_range("feature.amplitude", table.get("amplitude"), 0.0, 1e-3, "m")
    key = "wavelength" if kind == "waviness" else "width"
    return kind, body, amp, require_range(f"feature.{key}", table.get(key), 1e-9, 1.0, "m")
