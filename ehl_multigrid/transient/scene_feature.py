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
    if not table:
        raise InputError("the scene has no [feature] table; add one (kind, amplitude, width or "
                         "wavelength [m], x0 [b], body) to run 'ehl transient'")
    reject_unknown_keys("feature", table, KEYS)
    if not problem.physical:
        raise InputError("a [feature] in metres needs a scene with known geometry (R, b)")
    kind = require_choice("feature.kind", table.get("kind"), ("waviness", "bump", "dent"))
    body = int(require_range("feature.body", table.get("body", 1), 1, 2, "-"))
    a = require_range("feature.amplitude", table.get("amplitude"), 0.0, 1e-3, "m")
    scale = problem.R / problem.b**2
    if kind == "waviness":
        lam = require_range("feature.wavelength", table.get("wavelength"), 1e-9, 1.0, "m")
        return Waviness(a * scale, lam / problem.b, float(table.get("phase", 0.0))), body
    w = require_range("feature.width", table.get("width"), 1e-9, 1.0, "m")
    sign = -1.0 if kind == "dent" else 1.0
    return Bump(sign * a * scale, w / problem.b, float(table.get("x0", -3.0)),
                str(table.get("shape", "cosine-gaussian"))), body


def point_feature_from_scene_table(table: dict[str, Any] | None, problem: Any) -> tuple[PointFeature, int]:
    """``(feature, body)`` of a point or elliptic scene from a ``[feature]`` table in metres
    (``problem`` a physical :class:`~ehl_multigrid.point.problem.PointProblem`)."""
    if not table:
        raise InputError("the scene has no [feature] table; add one (kind, amplitude, width or "
                         "wavelength [m], x0 [a], body) to run 'ehl transient'")
    reject_unknown_keys("feature", table, POINT_KEYS)
    if not problem.physical:
        raise InputError("a [feature] in metres needs a scene with known geometry (Rx, a)")
    kind = require_choice("feature.kind", table.get("kind"), ("waviness", "bump", "dent"))
    body = int(require_range("feature.body", table.get("body", 1), 1, 2, "-"))
    amp = require_range("feature.amplitude", table.get("amplitude"), 0.0, 1e-3, "m")
    scale = problem.Rx / problem.a**2
    if kind == "waviness":
        lam = require_range("feature.wavelength", table.get("wavelength"), 1e-9, 1.0, "m")
        return Waviness2D(amp * scale, lam / problem.a, float(table.get("angle", 0.0)),
                          float(table.get("phase", 0.0))), body
    w = require_range("feature.width", table.get("width"), 1e-9, 1.0, "m")
    sign = -1.0 if kind == "dent" else 1.0
    return Dent2D(sign * amp * scale, w / problem.a, float(table.get("x0", -2.5)),
                  float(table.get("y0", 0.0)), str(table.get("shape", "cosine-gaussian"))), body
