"""Surface features that move through a point (circular or elliptic) contact.

Heights are in the point contact's film units (``A = a_phys Rx / a^2`` for a physical height
``a_phys``), positions in ``X = x/a``, ``Y = y/a`` (``a`` the Hertz semi-axis along the rolling
direction X). A positive height is a bump (it narrows the gap), a negative one a dent. The
film with a feature on either body reads (Venner & Lubrecht 2000, ch. 13)

``H(X, Y, T) = H00(T) + X^2/2 + theta Y^2/2 - R(X - c T, Y) + cd int int P/r dX'dY'``

where ``R`` is the feature's height in its own frame at ``T = 0`` and ``c`` its speed over the
mean rolling speed (:func:`~.features.feature_speed`); features move along X only.

Shapes:

* :class:`Waviness2D` -- ``R = A cos(2 pi (X cos phi + Y sin phi)/Lambda + phase)``:
  ``phi = 0`` transverse waviness (crests across the rolling direction, the film sees it move),
  ``phi = 90`` longitudinal (crests along the rolling direction: steady), anything between;
* :class:`Dent2D` -- a single dent or bump, circular in plan, of width ``W`` centred at
  ``(x0, y0)``: ``"cosine-gaussian"``: ``R = A 10^(-10 (r/W)^2) cos(2 pi r/W)`` (Venner &
  Lubrecht's dent shape), or ``"gaussian"``: ``R = A exp(-(r/W)^2)``;
* :class:`HeightMap` -- a sampled height map ``z[j, i]`` (Y row, X column) with spacings
  ``(dx, dy)``, bilinear and zero outside (measured or synthetic roughness: a plain array, so
  any reader can supply it);
* :class:`Smooth2D` -- no feature.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.ndimage import map_coordinates

from ..model.errors import InputError, require_choice, require_range
from .features import (
    MAX_AMPLITUDE,
    MAX_DEPTH,
    SHAPES,
    Described,
    ShapedFeature,
    Smooth,
    require_in,
    require_relief,
)

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

    def check_domain(self, xmin: float, xmax: float, ymax: float) -> None:
        """The whole feature (``reach`` around its centre) must start inside the domain."""
        f = self.reach / self.width
        require_in("feature.width", self.width, 1e-3, min(0.5 * (xmax - xmin), ymax) / f, "-",
                   f"the feature must fit in the domain X in [{xmin:g}, {xmax:g}], |Y| <= {ymax:g}")
        require_in("feature.x0", self.x0, xmin + self.reach, xmax - self.reach, "-",
                   f"the whole feature must start inside the domain X in [{xmin:g}, {xmax:g}]")
        require_in("feature.y0", self.y0, -ymax + self.reach, ymax - self.reach, "-",
                   f"the whole feature must lie inside |Y| <= {ymax:g}")


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
    def length_scale(self) -> float:
        """Four sample spacings along X: the shortest wavelength the samples describe well."""
        return 4.0 * float(self.dx)

    def height(self, X: np.ndarray, Y: np.ndarray) -> np.ndarray:
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
