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

A measured or synthetic surface: ``kind = "map"`` with ``file`` (heights, positive up; one
row for a line contact, rows along Y for a point contact), ``dx`` (and ``dy`` for a point
contact) the sample spacings [m], and optionally ``x0`` (position of the first sample, default:
the map just upstream of the contact, entering it) and ``y0`` (point: default centred). A
relative ``file`` is read from the working directory. The file is read by the height-map reader
a layer registers (entry-point group ``ehl.height_maps``; the mixed layer's
:func:`mixed.surface.feature.feature_heights` reads instrument formats, HDF5, text with unit
headers, levels, fills missing points and filters, with keys of its own); without one, a
``.npy`` array or a text table in metres.

Venner units: ``A = a R / b^2``, ``Lambda = lambda / b``, ``W = w / b`` with the reduced radius
``R`` and the Hertzian half-width ``b`` of the scene's operating point. The slide-to-roll ratio
is the scene's ``slip`` (``S = (u1 - u2)/u_m``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..line.problem import LineProblem
from ..model.errors import InputError, reject_unknown_keys, require_choice, require_range
from .features import (
    MAX_AMPLITUDE,
    MAX_DEPTH,
    SHAPES,
    Bump,
    Dent2D,
    Feature,
    HeightMap,
    PointFeature,
    Profile,
    Waviness,
    Waviness2D,
    require_in,
    waviness_span,
)

KEYS = {"kind", "amplitude", "width", "wavelength", "x0", "shape", "body", "phase"}
POINT_KEYS = KEYS | {"angle", "y0"}
MAP_KEYS = {"kind", "file", "dx", "dy", "x0", "y0", "body"}


def load_height_array(path: Any) -> np.ndarray:
    """The numbers of a ``.npy`` array or a text table (comma or white space separated), as
    floats, unchecked (``ndmin`` 2 for text)."""
    import os

    if not isinstance(path, str) or not os.path.isfile(path):
        raise InputError(f"feature.file = {path!r} is not a readable file (a .npy array or a text "
                         f"table of heights in metres)")
    try:
        if path.endswith(".npy"):
            return np.asarray(np.load(path, allow_pickle=False), dtype=float)
        with open(path, encoding="utf-8") as f:
            text = f.read().replace(",", " ")
        return np.asarray(np.loadtxt(text.splitlines(), ndmin=2), dtype=float)
    except (OSError, ValueError) as exc:
        raise InputError(f"feature.file = {path!r} could not be read as heights: "
                         f"{str(exc).splitlines()[0]}") from None


def check_heights(z: np.ndarray, ndim: int, path: Any) -> np.ndarray:
    """``z`` [m] squeezed to ``ndim`` dimensions (1: a line-contact profile; 2: a map, rows
    along Y), finite and at most 1 mm high, or an :class:`InputError` naming the file."""
    z = np.asarray(z, dtype=float)
    if ndim == 1:
        z = np.squeeze(z)
    if z.ndim != ndim:
        raise InputError(f"feature.file = {path!r} holds an array of shape {z.shape}: a "
                         f"{'line' if ndim == 1 else 'point'} contact needs {ndim} dimension(s)")
    if not np.all(np.isfinite(z)):
        raise InputError(f"feature.file = {path!r} has missing (NaN) or infinite heights: fill them first")
    require_range("feature.file (max |height|)", float(np.max(np.abs(z))), 0.0, 1e-3, "m")
    return z


def height_map_reader() -> Any:
    """The height-map reader a layer registers in the entry-point group ``ehl.height_maps``
    (the mixed layer's surface readers: instrument formats, units, levelling, filters), or
    None. The core never imports the layers above it; it finds them here."""
    from importlib.metadata import entry_points

    found = sorted(entry_points(group="ehl.height_maps"), key=lambda e: e.name)
    return found[0].load() if found else None


def _map_table(table: dict[str, Any], ndim: int) -> tuple[np.ndarray, float, float | None, int]:
    """Heights [m], spacings [m] and body of a ``kind = "map"`` table: read by the registered
    reader when a layer provides one (it checks its own keys), else as a plain array."""
    reader = height_map_reader()
    if reader is not None:
        z, dx, dy = reader(table, ndim, MAP_KEYS)
    else:
        reject_unknown_keys("feature", table, MAP_KEYS)
        z, dx, dy = load_height_array(table.get("file")), table.get("dx"), table.get("dy")
    z = check_heights(z, ndim, table.get("file"))
    dx = require_range("feature.dx", dx, 1e-9, 1e-2, "m")
    dy = require_range("feature.dy", dy, 1e-9, 1e-2, "m") if ndim == 2 else None
    return z, dx, dy, _body(table)


def feature_from_scene_table(table: dict[str, Any] | None, problem: LineProblem) -> tuple[Feature, int]:
    """``(feature, body)`` from a ``[feature]`` table in metres (see module docstring).

    Every value is checked in the units the table gives it (lengths and heights in metres,
    ``x0`` in b, ``phase`` in rad) against the range the solver takes on the problem's domain,
    before it is made dimensionless: an :class:`InputError` names the key, the value and the
    allowed range in those units."""
    unit = _FilmUnit(problem.b, problem.R, "b", "b^2/R", (problem.xmin, problem.xmax, None))
    if table and table.get("kind") == "map" and problem.physical:
        z, dx, _, body = _map_table(table, 1)
        unit.check_map_heights(z)
        X = np.arange(z.size) * (dx / problem.b)
        x0 = require_in("feature.x0", table.get("x0", problem.xmin), problem.xmin, problem.xmax,
                        "- (x/b)", f"the profile must start inside the domain X in [{problem.xmin:g}, "
                                   f"{problem.xmax:g}]")
        return Profile(x0 + X, z * problem.R / problem.b**2), body
    return _shape_from_table(table, KEYS, problem, unit, "R, b", -3.0)


def point_feature_from_scene_table(table: dict[str, Any] | None, problem: Any,
                                   domain: tuple[float, float, float] | None = None,
                                   warnings: list[str] | None = None) -> tuple[PointFeature, int]:
    """``(feature, body)`` of a point or elliptic scene from a ``[feature]`` table in metres
    (``problem`` a physical :class:`~ehl_multigrid.point.problem.PointProblem`).

    ``domain``: the solver's box ``(xmin, xmax, ymax)`` in units of a (default: the point
    solver's default box); every value is checked against it in the units the table gives
    (as :func:`feature_from_scene_table`). A height map wider than the box across the rolling
    direction appends a warning to ``warnings`` (its rows outside the box are not seen)."""
    from ..point.problem import resolve_domain

    xmin, xmax, ymax = resolve_domain(problem, None, None, None) if domain is None else domain
    unit = _FilmUnit(problem.a, problem.Rx, "a", "a^2/Rx", (xmin, xmax, ymax))
    if table and table.get("kind") == "map" and problem.physical:
        z, dx, dy, body = _map_table(table, 2)
        unit.check_map_heights(z)
        dxa, dya = dx / problem.a, dy / problem.a
        ny, nx = z.shape
        lx, ly = (nx - 1) * dxa, (ny - 1) * dya
        x0 = require_in("feature.x0", table.get("x0", -1.5 - lx), xmin - lx, xmax - lx, "- (x/a)",
                        f"the map's downstream edge x0 + {lx:.4g} a must start inside the domain "
                        f"X in [{xmin:g}, {xmax:g}]")
        y0 = require_in("feature.y0", table.get("y0", -0.5 * ly), -ymax - ly, ymax, "- (y/a)",
                        f"the map's rows, y0 .. y0 + {ly:.4g} a, must overlap the domain "
                        f"|Y| <= {ymax:g}")
        if warnings is not None and (y0 < -ymax or y0 + ly > ymax):
            a = problem.a
            warnings.append(
                f"the height map spans y = {y0 * a:.4g} .. {(y0 + ly) * a:.4g} m across the rolling "
                f"direction ({ny} rows of dy = {dy:.4g} m), wider than the solver's box |y| <= "
                f"{ymax * a:.4g} m (|Y| <= {ymax:g} a): the rows outside it are clipped and do not "
                f"pass through the contact")
        return HeightMap(z * problem.Rx / problem.a**2, dxa, dya, x0, y0), body
    return _shape_from_table(table, POINT_KEYS, problem, unit, "Rx, a", -2.5)


def _shape_from_table(table: dict[str, Any] | None, keys: set[str], problem: Any, unit: _FilmUnit,
                      geometry: str, x0_default: float) -> tuple[Any, int]:
    """``(feature, body)`` of a waviness, bump or dent table in metres, checked against the
    box of ``unit``: a line contact's :class:`Waviness` or :class:`Bump` when the box has no
    ``ymax``, else a point contact's :class:`Waviness2D` (with ``angle``) or :class:`Dent2D`
    (with ``y0``). ``geometry`` names the scene's lengths the table needs, ``x0_default``
    is the default start of a bump's or dent's centre."""
    kind, body, amp, length = _read_table(table, keys, problem, unit.name, geometry)
    unit.check_amplitude(kind, amp)
    xmin, xmax, ymax = unit.box
    line = ymax is None
    scale = unit.radius / unit.length**2
    where = f"X in [{xmin:g}, {xmax:g}]" + ("" if line else f", |Y| <= {ymax:g}")
    if kind == "waviness":
        angle = 0.0 if line else require_range("feature.angle", table.get("angle", 0.0), -90.0, 90.0,
                                                "degrees")
        unit.check_length("wavelength", length, xmax - xmin if line else waviness_span(angle, xmin, xmax, ymax),
                          f"the domain {where} must hold one wavelength"
                          + ("" if line else f" at angle {angle:g} deg"))
        phase = require_range("feature.phase", table.get("phase", 0.0), -1e3, 1e3, "rad")
        if line:
            return Waviness(amp * scale, length / unit.length, phase), body
        return Waviness2D(amp * scale, length / unit.length, angle, phase), body
    shape = require_choice("feature.shape", table.get("shape", "cosine-gaussian"), SHAPES)
    f = _reach_factor(shape)
    unit.check_length("width", length, (0.5 * (xmax - xmin) if line else min(0.5 * (xmax - xmin), ymax)) / f,
                      f"the {kind} must fit in the domain {where}")
    n = unit.name
    reach = f * length / unit.length
    x0 = require_in("feature.x0", table.get("x0", x0_default), xmin + reach, xmax - reach, f"- (x/{n})",
                    f"the whole {kind} (its centre +- {reach:.3g} {n}) must start inside the domain "
                    f"X in [{xmin:g}, {xmax:g}]")
    sign = -1.0 if kind == "dent" else 1.0
    if line:
        return Bump(sign * amp * scale, length / unit.length, x0, shape), body
    y0 = require_in("feature.y0", table.get("y0", 0.0), -ymax + reach, ymax - reach, f"- (y/{n})",
                    f"the whole {kind} (its centre +- {reach:.3g} {n}) must lie inside |Y| <= {ymax:g}")
    return Dent2D(sign * amp * scale, length / unit.length, x0, y0, shape), body


def _reach_factor(shape: str) -> float:
    """A single feature's reach over its width (:attr:`~.features.ShapedFeature.reach`)."""
    return 1.0 if shape == "cosine-gaussian" else 2.6


class _FilmUnit:
    """The contact's units and box: the checks of a feature's heights and lengths in metres
    against the solver's limits in its own units: lengths in ``length`` (b or a) [m], heights
    in the film unit ``length^2/radius`` [m]; ``name`` and ``film`` spell them in messages;
    ``box`` is the solver's ``(xmin, xmax, ymax)`` in units of ``length`` (``ymax`` None: a
    line contact)."""

    def __init__(self, length: float, radius: float, name: str, film: str,
                 box: tuple[float, float, float | None]) -> None:
        self.length, self.radius, self.name, self.film, self.box = length, radius, name, film, box
        self.height = length**2 / radius

    def _limit(self) -> str:
        return (f"the transient solver takes features up to {MAX_AMPLITUDE:g} film unit "
                f"{self.film} = {MAX_AMPLITUDE * self.height:.4g} m high and {MAX_DEPTH:g} film "
                f"units = {MAX_DEPTH * self.height:.4g} m deep for this contact")

    def check_amplitude(self, kind: str, amp: float) -> float:
        what = {"dent": "the dent's depth", "bump": "the bump's height",
                "waviness": "the waviness amplitude"}[kind]
        most = MAX_DEPTH if kind == "dent" else MAX_AMPLITUDE
        return require_in("feature.amplitude", amp, 0.0, min(1e-3, most * self.height),
                          "m", f"{what}; {self._limit()}")

    def check_map_heights(self, z: np.ndarray) -> None:
        require_in("feature.file (highest)", max(float(np.max(z)), 0.0), 0.0,
                   MAX_AMPLITUDE * self.height, "m", self._limit())
        require_in("feature.file (deepest)", max(-float(np.min(z)), 0.0), 0.0,
                   MAX_DEPTH * self.height, "m", self._limit())

    def check_length(self, key: str, value: float, most: float, why: str) -> float:
        """``value`` [m] within ``[1e-3, most]`` of the length unit, in metres."""
        L = self.length
        return require_in(f"feature.{key}", value, 1e-3 * L, min(1e3, most) * L, "m",
                          f"{1e-3:g} .. {min(1e3, most):.4g} {self.name} with {self.name} = {L:.4g} m: "
                          f"{why}")


def _body(table: dict[str, Any]) -> int:
    """``feature.body``: exactly 1 or 2."""
    v = table.get("body", 1)
    if isinstance(v, bool) or not isinstance(v, (int, float)) or v not in (1, 2):
        raise InputError(f"feature.body = {v!r} is not one of the allowed values [1, 2] (the "
                         f"surface that carries the feature)")
    return int(v)


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
    kind = require_choice("feature.kind", table.get("kind"), ("waviness", "bump", "dent", "map"))
    if kind == "map":
        raise InputError("feature.kind = 'map' needs a scene with known geometry and the keys file, dx (and dy for a point contact)")
    body = _body(table)
    amp = require_range("feature.amplitude", table.get("amplitude"), 0.0, 1e-3, "m")
    key = "wavelength" if kind == "waviness" else "width"
    return kind, body, amp, require_range(f"feature.{key}", table.get(key), 1e-9, 1.0, "m")
