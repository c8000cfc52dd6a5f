"""Surface features that move through a line contact with the surface that carries them.

Heights are in Venner's film units (``A = a R / b^2`` for a physical height ``a``) and
positions in ``X = x/b``. A positive height is a bump (it narrows the gap), a negative one a
dent. The film equation with a feature on either body reads (Venner & Lubrecht 2000, ch. 12)

``H(X, T) = H0(T) + X^2/2 - R(X - c T) - (1/pi) int ln|X - X'| P(X', T) dX'``

where ``R`` is the feature's height in its own frame at ``T = 0`` and ``c`` its speed in
units of the mean rolling speed ``u_m = (u1 + u2)/2`` (:func:`feature_speed`).

Shapes:

* :class:`Waviness` -- ``R(X) = A cos(2 pi X / Lambda + phase)``;
* :class:`Profile` -- a sampled profile (measured or synthetic roughness), interpolated;
* :class:`Bump` -- a single feature of width ``W`` centred at ``x0``:
  ``"cosine-gaussian"``: ``R = A 10^(-10 (s/W)^2) cos(2 pi s / W)`` (the dent/bump shape of
  Venner & Lubrecht's transient studies, ``s = X - x0``), or
  ``"gaussian"``: ``R = A exp(-(s/W)^2)``.
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

    def check_domain(self, xmin: float, xmax: float) -> None:
        """The feature (``x0 +- reach``) must fit in the domain at the start."""
        reach = self.reach
        require_in("feature.width", self.width, 1e-3, 0.5 * (xmax - xmin) / (reach / self.width),
                   "-", f"the feature must fit in the domain [{xmin:g}, {xmax:g}]")
        require_in("feature.x0", self.x0, xmin + reach, xmax - reach, "-",
                   f"the whole feature must start inside the domain [{xmin:g}, {xmax:g}]")


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
