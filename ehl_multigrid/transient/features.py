"""Surface features that move through a line or a point (circular, elliptic) contact with the
surface that carries them.

Heights are in the contact's film units (line ``A = a R / b^2``, point ``A = a Rx / a_H^2`` for a
physical height ``a``, ``a_H`` the Hertz semi-axis along the rolling direction X), positions in
``X = x/b`` (point: ``X = x/a_H``, ``Y = y/a_H``). A positive height is a bump (it narrows the
gap), a negative one a dent. The film with a feature on either body reads (Venner & Lubrecht
2000, ch. 12 and 13)

``H(X, T) = H0(T) + X^2/2 - R(X - c T) - (1/pi) int ln|X - X'| P(X', T) dX'``,
``H(X, Y, T) = H00(T) + X^2/2 + theta Y^2/2 - R(X - c T, Y) + cd int int P/r dX'dY'``

where ``R`` is the feature's height in its own frame at ``T = 0`` and ``c`` its speed in
units of the mean rolling speed ``u_m = (u1 + u2)/2`` (:func:`feature_speed`); features move
along X only.

Shapes of the line contact:

* :class:`Waviness` -- ``R(X) = A cos(2 pi X / Lambda + phase)``;
* :class:`Profile` -- a sampled profile (measured or synthetic roughness), interpolated;
* :class:`Bump` -- a single feature of width ``W`` centred at ``x0``:
  ``"cosine-gaussian"``: ``R = A 10^(-10 (s/W)^2) cos(2 pi s / W)`` (the dent/bump shape of
  Venner & Lubrecht's transient studies, ``s = X - x0``), or
  ``"gaussian"``: ``R = A exp(-(s/W)^2)``.

Shapes of the point contact:

* :class:`Waviness2D` -- ``R = A cos(2 pi (X cos phi + Y sin phi)/Lambda + phase)``:
  ``phi = 0`` transverse waviness (crests across the rolling direction, the film sees it move),
  ``phi = 90`` longitudinal (crests along the rolling direction: steady), anything between;
* :class:`Dent2D` -- a single dent or bump, circular in plan, of width ``W`` centred at
  ``(x0, y0)``, of the line bump's shapes in ``r``, the distance from its centre;
* :class:`HeightMap` -- a sampled height map ``z[j, i]`` (Y row, X column) with spacings
  ``(dx, dy)``, bilinear and zero outside (measured or synthetic roughness: a plain array, so
  any reader can supply it).

:class:`Smooth` (alias :data:`Smooth2D`): no feature, on either contact.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from ..model.errors import InputError, require_choice, require_range

SHAPES = ("cosine-gaussian", "gaussian")
#: Largest feature height accepted [Venner film units]: far above the central film of any
#: line contact the solver covers (Hc ~ 0.01-0.5); a larger one cuts through both surfaces.
MAX_AMPLITUDE = 1.0
#: Deepest dent or valley accepted [film units]: a pocket touches nothing, so real
#: micrometre dents on nanometre films are taken; how deep ones run: docs/transient.md.
MAX_DEPTH = 10.0


def require_relief(field: str, z: np.ndarray, units: str) -> None:
    """Heights of a feature or map: peaks up to :data:`MAX_AMPLITUDE`, depths (``-z``) up
    to :data:`MAX_DEPTH`."""
    require_range(f"{field} (highest)", max(float(np.max(z)), 0.0), 0.0, MAX_AMPLITUDE, units)
    require_range(f"{field} (deepest)", max(-float(np.min(z)), 0.0), 0.0, MAX_DEPTH, units)


def require_in(field: str, value: float, lo: float, hi: float, units: str, why: str,
               lo_open: bool = False) -> float:
    """:func:`require_range` with the reason for the range appended to the message."""
    try:
        return require_range(field, value, lo, hi, units, lo_open=lo_open)
    except InputError as exc:
        raise InputError(f"{exc} ({why})") from None


def feature_speed(body: int, slide_roll: float) -> float:
    """Speed of a feature on ``body`` (1 or 2) over the mean speed ``u_m``.

    With the slide-to-roll ratio ``S = (u1 - u2)/u_m``: ``u1/u_m = 1 + S/2``,
    ``u2/u_m = 1 - S/2``.
    """
    require_choice("body", body, (1, 2))
    s = require_range("slide_roll", slide_roll, -2.0, 2.0, "- ((u1 - u2)/u_m)")
    return 1.0 + 0.5 * s if body == 1 else 1.0 - 0.5 * s


class Described:
    """``describe()`` of a dataclass feature: its kind and fields."""

    kind: str

    def describe(self) -> dict[str, Any]:
        return {"kind": self.kind, **asdict(self)}


@dataclass(frozen=True)
class Waviness(Described):
    """Sinusoidal waviness ``A cos(2 pi X / wavelength + phase)`` (transverse ridges of a
    line contact: crests parallel to the contact line).

    Attributes
    ----------
    amplitude : ``A`` [Venner film units, a R/b^2], >= 0.
    wavelength : ``Lambda = lambda / b`` [-].
    phase : phase at ``X = 0``, ``T = 0`` [rad].
    """

    amplitude: float
    wavelength: float
    phase: float = 0.0

    kind = "waviness"

    def __post_init__(self) -> None:
        require_range("feature.amplitude", self.amplitude, 0.0, MAX_AMPLITUDE, "- (a R/b^2)")
        require_range("feature.wavelength", self.wavelength, 1e-3, 1e3, "- (lambda/b)")
        require_range("feature.phase", self.phase, -1e3, 1e3, "rad")

    @property
    def length_scale(self) -> float:
        """The length a time step must resolve: the wavelength."""
        return self.wavelength

    @property
    def wavelength_x(self) -> float:
        """The wavelength along the rolling direction."""
        return self.wavelength

    def height(self, X: np.ndarray) -> np.ndarray:
        return self.amplitude * np.cos(2.0 * math.pi * np.asarray(X) / self.wavelength + self.phase)

    def check_domain(self, xmin: float, xmax: float) -> None:
        """At least one wavelength must fit in the domain."""
        require_in("feature.wavelength", self.wavelength, 1e-3, xmax - xmin, "-",
                   f"the domain [{xmin:g}, {xmax:g}] must hold one wavelength")


class ShapedFeature(Described):
    """The width rules of the single-feature shapes (``width``, ``shape``, centre ``x0``),
    shared by the line contact's :class:`Bump` and the point contact's dent."""

    width: float
    shape: str
    x0: float

    @property
    def x_entry(self) -> float:
        """The position whose arrival at the outlet ends a default run: the centre."""
        return self.x0

    def check_domain(self, xmin: float, xmax: float, ymax: float | None = None) -> None:
        """The whole feature (``reach`` around its centre) must start inside the domain
        ``[xmin, xmax]`` (a point contact's dent also inside ``|Y| <= ymax``)."""
        f, reach, line = self.reach / self.width, self.reach, ymax is None
        along = f"[{xmin:g}, {xmax:g}]" if line else f"X in [{xmin:g}, {xmax:g}]"
        require_in("feature.width", self.width, 1e-3,
                   (0.5 * (xmax - xmin) if line else min(0.5 * (xmax - xmin), ymax)) / f, "-",
                   f"the feature must fit in the domain {along}" + ("" if line else f", |Y| <= {ymax:g}"))
        require_in("feature.x0", self.x0, xmin + reach, xmax - reach, "-",
                   f"the whole feature must start inside the domain {along}")
        if not line:
            require_in("feature.y0", self.y0, -ymax + reach, ymax - reach, "-",
                       f"the whole feature must lie inside |Y| <= {ymax:g}")

    @property
    def reach(self) -> float:
        """Distance from the centre beyond which the height is negligible: ``W`` for the
        cosine-Gaussian (below 1e-3 A), ``2.6 W`` for the Gaussian (1e-3 A)."""
        return self.width if self.shape == "cosine-gaussian" else 2.6 * self.width

    @property
    def length_scale(self) -> float:
        """The length a time step must resolve: the width (Gaussian) or the half wavelength
        of the cosine-Gaussian's oscillation."""
        return self.width if self.shape == "gaussian" else 0.5 * self.width


@dataclass(frozen=True)
class Bump(ShapedFeature):
    """A single bump (``amplitude > 0``) or dent (``amplitude < 0``) centred at ``x0`` at
    ``T = 0``.

    Attributes
    ----------
    amplitude : ``A`` [Venner film units, a R/b^2].
    width : ``W`` [-, x/b]: the cosine-Gaussian's wavelength, or the Gaussian's 1/e
        half-width.
    x0 : centre at ``T = 0`` [-, x/b] (usually upstream of the contact, e.g. -3).
    shape : ``"cosine-gaussian"`` or ``"gaussian"``.
    """

    amplitude: float
    width: float
    x0: float = -3.0
    shape: str = "cosine-gaussian"

    kind = "bump"

    def __post_init__(self) -> None:
        require_range("feature.amplitude", self.amplitude, -MAX_DEPTH, MAX_AMPLITUDE, "- (a R/b^2)")
        require_range("feature.width", self.width, 1e-3, 1e3, "- (x/b)")
        require_range("feature.x0", self.x0, -1e3, 1e3, "- (x/b)")
        require_choice("feature.shape", self.shape, SHAPES)

    def height(self, X: np.ndarray) -> np.ndarray:
        s = np.asarray(X) - self.x0
        if self.shape == "gaussian":
            return self.amplitude * np.exp(-((s / self.width) ** 2))
        return self.amplitude * 10.0 ** (-10.0 * (s / self.width) ** 2) * np.cos(2.0 * math.pi * s / self.width)


@dataclass(frozen=True, eq=False)
class Profile:
    """A sampled height profile (measured or synthetic roughness, e.g. one row of a
    ``mixed.surface`` height map), linearly interpolated and zero outside its samples.

    Attributes
    ----------
    x : sample positions in the body's frame at ``T = 0`` [-, x/b], increasing, uniform.
    z : heights [Venner film units, a R/b^2] (positive = up, narrowing the gap).
    """

    x: np.ndarray
    z: np.ndarray

    kind = "profile"

    def __post_init__(self) -> None:
        x = np.asarray(self.x, dtype=float)
        z = np.asarray(self.z, dtype=float)
        if x.ndim != 1 or x.shape != z.shape or x.size < 4:
            raise InputError(f"feature.x and feature.z must be 1-D of one length >= 4 "
                             f"(got shapes {x.shape} and {z.shape})")
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(z))):
            raise InputError("feature.x and feature.z must be finite (fill missing points first)")
        dx = np.diff(x)
        if np.any(dx <= 0.0) or np.ptp(dx) > 1e-6 * dx.mean():
            raise InputError("feature.x must be uniformly spaced and increasing")
        require_relief("feature.z", z, "- (a R/b^2)")
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "z", z)

    @property
    def amplitude(self) -> float:
        """RMS height [Venner units]."""
        return float(np.sqrt(np.mean(self.z**2)))

    @property
    def length_scale(self) -> float:
        """Four sample spacings: the shortest wavelength the samples describe well."""
        return 4.0 * float(self.x[1] - self.x[0])

    @property
    def x_entry(self) -> float:
        """The position whose arrival at the outlet ends a default run: the tail."""
        return float(self.x[0])

    @property
    def x_ref(self) -> float:
        """The reference position at ``T = 0``: the centre."""
        return 0.5 * (float(self.x[0]) + float(self.x[-1]))

    def height(self, X: np.ndarray) -> np.ndarray:
        return np.interp(np.asarray(X, dtype=float), self.x, self.z, left=0.0, right=0.0)

    def check_domain(self, xmin: float, xmax: float) -> None:
        require_in("feature.x[0]", float(self.x[0]), xmin, xmax, "-",
                   f"the profile must start inside the domain [{xmin:g}, {xmax:g}]")

    def describe(self) -> dict[str, Any]:
        return {"kind": self.kind, "points": int(self.x.size), "x_start": float(self.x[0]),
                "x_end": float(self.x[-1]), "rms": self.amplitude,
                "max": float(np.max(self.z)), "min": float(np.min(self.z))}


@dataclass(frozen=True)
class Smooth:
    """No feature: smooth surfaces (start-up and steady-limit runs)."""

    amplitude: float = 0.0
    kind = "smooth"

    @property
    def length_scale(self) -> float:
        """The Hertzian half-width (``X = 1``; point contacts: the semi-axis ``a``): the scale
        of the film's own transients."""
        return 1.0

    def height(self, X: np.ndarray, Y: np.ndarray | None = None) -> np.ndarray:
        X = np.asarray(X, dtype=float)
        return np.zeros_like(X) if Y is None else np.zeros(np.broadcast_shapes(X.shape, np.shape(Y)))

    def check_domain(self, *box: float) -> None:
        return None

    def describe(self) -> dict[str, Any]:
        return {"kind": self.kind}


Feature = Waviness | Bump | Profile | Smooth


def x_ref(feature: Any) -> float:
    """A feature's reference position at ``T = 0`` (series ``xf``): a single feature's or a
    sampled surface's centre, else (waviness: its crest of phase 0; smooth) 0."""
    return getattr(feature, "x_ref", getattr(feature, "x0", 0.0))


def default_end_time(xmin: float, xmax: float, feature: Any, speed: float) -> float:
    """A single feature or a sampled surface: until its :attr:`x_entry` (centre, tail) reaches
    ``xmax`` (when it does not move: one transit of the domain); waviness: one transit plus
    three periods along X; smooth: two transits."""
    span = xmax - xmin
    if feature.kind == "smooth":
        return 2.0 * span
    if feature.kind != "waviness":
        return (xmax - feature.x_entry) / speed if speed > 1e-9 else span
    wl = feature.wavelength_x
    period = wl / abs(speed) if math.isfinite(wl) and abs(speed) > 1e-9 else 0.0
    return span + 3.0 * period


#: a waviness closer than this to longitudinal (degrees) does not move through the contact
LONGITUDINAL_TOL = 1e-9


def waviness_span(angle: float, xmin: float, xmax: float, ymax: float) -> float:
    """The length of the domain X in ``[xmin, xmax]``, ``|Y| <= ymax`` along a waviness's wave
    vector at ``angle`` degrees to X (the shorter side between the axes)."""
    return min(xmax - xmin, 2.0 * ymax) if 0.0 < abs(angle) < 90.0 else \
        (xmax - xmin if angle == 0.0 else 2.0 * ymax)


@dataclass(frozen=True)
class Waviness2D(Described):
    """Sinusoidal waviness at an angle to the rolling direction.

    Attributes
    ----------
    amplitude : ``A`` [film units, a_phys Rx/a^2], >= 0.
    wavelength : ``Lambda = lambda/a`` [-] (along the wave vector).
    angle : ``phi`` [degrees] between the wave vector and the rolling direction X: 0 transverse
        (ridges across the rolling direction), 90 longitudinal (ridges along it).
    phase : phase at the origin at ``T = 0`` [rad].
    """

    amplitude: float
    wavelength: float
    angle: float = 0.0
    phase: float = 0.0

    kind = "waviness"

    def __post_init__(self) -> None:
        require_range("feature.amplitude", self.amplitude, 0.0, MAX_AMPLITUDE, "- (a Rx/a^2)")
        require_range("feature.wavelength", self.wavelength, 1e-3, 1e3, "- (lambda/a)")
        require_range("feature.angle", self.angle, -90.0, 90.0, "degrees")
        require_range("feature.phase", self.phase, -1e3, 1e3, "rad")

    @property
    def wavelength_x(self) -> float:
        """Wavelength seen along the rolling direction, ``Lambda/|cos phi|`` (inf for
        longitudinal waviness)."""
        c = abs(math.cos(math.radians(self.angle)))
        return self.wavelength / c if c > LONGITUDINAL_TOL else math.inf

    @property
    def length_scale(self) -> float:
        """The length along X a time step must resolve (the X wavelength; the Hertz
        semi-axis for longitudinal waviness, which does not move)."""
        return min(self.wavelength_x, 1e3) if math.isfinite(self.wavelength_x) else 1.0

    def height(self, X: np.ndarray, Y: np.ndarray) -> np.ndarray:
        phi = math.radians(self.angle)
        k = 2.0 * math.pi / self.wavelength
        return self.amplitude * np.cos(k * (np.asarray(X) * math.cos(phi) + np.asarray(Y) * math.sin(phi))
                                       + self.phase)

    def check_domain(self, xmin: float, xmax: float, ymax: float) -> None:
        """One wavelength must fit in the domain along the wave vector."""
        require_in("feature.wavelength", self.wavelength, 1e-3,
                   waviness_span(self.angle, xmin, xmax, ymax), "-",
                   f"the domain X in [{xmin:g}, {xmax:g}], |Y| <= {ymax:g} must hold one wavelength "
                   f"at angle {self.angle:g} deg")


@dataclass(frozen=True)
class Dent2D(ShapedFeature):
    """A single dent (``amplitude < 0``) or bump (``> 0``), circular in plan.

    Attributes
    ----------
    amplitude : ``A`` [film units].
    width : ``W`` [-, x/a]: the cosine-Gaussian's wavelength, or the Gaussian's 1/e radius.
    x0, y0 : centre at ``T = 0`` [-, x/a] (usually upstream, e.g. x0 = -2.5).
    shape : ``"cosine-gaussian"`` or ``"gaussian"``.
    """

    amplitude: float
    width: float
    x0: float = -2.5
    y0: float = 0.0
    shape: str = "cosine-gaussian"

    kind = "bump"

    def __post_init__(self) -> None:
        require_range("feature.amplitude", self.amplitude, -MAX_DEPTH, MAX_AMPLITUDE, "- (a Rx/a^2)")
        require_range("feature.width", self.width, 1e-3, 1e3, "- (x/a)")
        require_range("feature.x0", self.x0, -1e3, 1e3, "- (x/a)")
        require_range("feature.y0", self.y0, -1e3, 1e3, "- (y/a)")
        require_choice("feature.shape", self.shape, SHAPES)

    def height(self, X: np.ndarray, Y: np.ndarray) -> np.ndarray:
        r2 = ((np.asarray(X) - self.x0) ** 2 + (np.asarray(Y) - self.y0) ** 2) / self.width**2
        if self.shape == "gaussian":
            return self.amplitude * np.exp(-r2)
        return self.amplitude * 10.0 ** (-10.0 * r2) * np.cos(2.0 * math.pi * np.sqrt(r2))


@dataclass(frozen=True, eq=False)
class HeightMap:
    """A sampled height map (measured or synthetic roughness), bilinear, zero outside.

    Attributes
    ----------
    z : heights ``[j, i]`` (Y row, X column) [film units] (positive = up, narrowing the gap).
    dx, dy : sample spacings [-, x/a].
    x0, y0 : position of sample ``z[0, 0]`` at ``T = 0`` [-, x/a].
    """

    z: np.ndarray
    dx: float
    dy: float
    x0: float
    y0: float

    kind = "height_map"

    def __post_init__(self) -> None:
        z = np.ascontiguousarray(self.z, dtype=float)
        if z.ndim != 2 or min(z.shape) < 4:
            raise InputError(f"feature.z must be a 2-D height map with >= 4 samples each way "
                             f"(got shape {z.shape})")
        if not np.all(np.isfinite(z)):
            raise InputError("feature.z must be finite (fill missing points first)")
        require_range("feature.dx", self.dx, 1e-6, 1e3, "- (x/a)", lo_open=True)
        require_range("feature.dy", self.dy, 1e-6, 1e3, "- (y/a)", lo_open=True)
        require_relief("feature.z", z, "- (a Rx/a^2)")
        object.__setattr__(self, "z", z)

    @property
    def extent(self) -> tuple[float, float, float, float]:
        """``(x_start, x_end, y_start, y_end)`` at ``T = 0``."""
        ny, nx = self.z.shape
        return (self.x0, self.x0 + (nx - 1) * self.dx, self.y0, self.y0 + (ny - 1) * self.dy)

    @property
    def amplitude(self) -> float:
        """RMS height [film units]."""
        return float(np.sqrt(np.mean(self.z**2)))

    @property
    def x_entry(self) -> float:
        """The position whose arrival at the outlet ends a default run: the upstream edge."""
        return self.extent[0]

    @property
    def x_ref(self) -> float:
        """The reference position at ``T = 0``: the centre."""
        x_start, x_end, _, _ = self.extent
        return 0.5 * (x_start + x_end)

    @property
    def y_ref(self) -> float:
        """The row the film change is followed on: the map's centre row."""
        _, _, y_start, y_end = self.extent
        return 0.5 * (y_start + y_end)

    @property
    def length_scale(self) -> float:
        """Four sample spacings along X: the shortest wavelength the samples describe well."""
        return 4.0 * float(self.dx)

    def height(self, X: np.ndarray, Y: np.ndarray) -> np.ndarray:
        # imported here: scipy.ndimage costs every ehl process 0.15 s at start-up
        from scipy.ndimage import map_coordinates

        X, Y = np.broadcast_arrays(np.asarray(X, dtype=float), np.asarray(Y, dtype=float))
        coords = np.array([(Y - self.y0) / self.dy, (X - self.x0) / self.dx])
        return map_coordinates(self.z, coords, order=1, mode="constant", cval=0.0)

    def check_domain(self, xmin: float, xmax: float, ymax: float) -> None:
        """The map's downstream edge must start inside the domain (it then enters the contact)
        and its rows must overlap the domain."""
        x_start, x_end, y_start, y_end = self.extent
        require_in("feature.x_end", x_end, xmin, xmax, "-",
                   f"the map's downstream edge must start inside the domain X in [{xmin:g}, {xmax:g}]")
        if y_end < -ymax or y_start > ymax:
            raise InputError(f"feature rows Y in [{y_start:g}, {y_end:g}] miss the domain |Y| <= {ymax:g}")

    def describe(self) -> dict[str, Any]:
        x_start, x_end, y_start, y_end = self.extent
        return {"kind": self.kind, "shape": list(self.z.shape), "dx": self.dx, "dy": self.dy,
                "x_start": x_start, "x_end": x_end, "y_start": y_start, "y_end": y_end,
                "rms": self.amplitude, "max": float(self.z.max()), "min": float(self.z.min())}


#: no feature: the line contact's smooth surfaces take ``(X, Y)`` too
Smooth2D = Smooth
PointFeature = Waviness2D | Dent2D | HeightMap | Smooth
