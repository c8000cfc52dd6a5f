"""Hertzian dry contact: line, circular and elliptic (exact, with complete elliptic integrals).

These closed forms are the package's reference solutions: the EHL solvers tend to them at
high load and the tests use them as oracles.

Conventions: ``x`` is the rolling direction. For a line contact ``b`` is the half-width. For a
point contact ``a`` is the semi-axis along x and ``b`` the semi-axis along y
(circular: a = b).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from .errors import require_positive


@dataclass(frozen=True)
class HertzContact:
    """Dry-contact solution.

    Attributes
    ----------
    kind : ``line``, ``circular`` or ``elliptic``
    load : normal force P [N]
    pmax : maximum Hertzian pressure [Pa]
    a : semi-axis along x [m] (line: the half-width, equal to ``b``)
    b : semi-axis along y [m] (line: half-width)
    area : nominal area (line ``2 b B``, point ``pi a b``) [m^2]
    mean_pressure : load / area [Pa] (line ``pi/4 pmax``, point ``2/3 pmax``)
    length : line length B [m] (``nan`` for point contacts)
    """

    kind: str
    load: float
    pmax: float
    a: float
    b: float
    area: float
    mean_pressure: float
    length: float = math.nan

    def to_dict(self) -> dict:
        return asdict(self)


def hertz_line(load: float, length: float, R: float, E_reduced: float) -> HertzContact:
    """Line contact: ``b = sqrt(8 w R / (pi E'))``, ``pmax = 2 w / (pi b)``, ``w = P/B``.

    Examples
    --------
    >>> round(hertz_line(500.0, 0.01, 0.02, 231e9).pmax / 1e9, 3)   # thesis page 63
    0.297
    """
    P = require_positive("load", load, "N")
    B = require_positive("length", length, "m")
    R = require_positive("R", R, "m")
    E = require_positive("E_reduced", E_reduced, "Pa")
    w = P / B
    b = math.sqrt(8.0 * w * R / (math.pi * E))
    pmax = 2.0 * w / (math.pi * b)
    area = 2.0 * b * B
    return HertzContact("line", P, pmax, b, b, area, P / area, B)


def hertz_circular(load: float, R: float, E_reduced: float) -> HertzContact:
    """Circular contact: ``a = (3 P R / (2 E'))^(1/3)``, ``pmax = 3 P / (2 pi a^2)``."""
    P = require_positive("load", load, "N")
    R = require_positive("R", R, "m")
    E = require_positive("E_reduced", E_reduced, "Pa")
    a = (3.0 * P * R / (2.0 * E)) ** (1.0 / 3.0)
    pmax = 3.0 * P / (2.0 * math.pi * a * a)
    area = math.pi * a * a
    return HertzContact("circular", P, pmax, a, a, area, P / area)


def _axis_ratio_from_curvatures(q: float) -> float:
    """Minor/major semi-axis ratio k for curvature ratio ``q = C_big / C_small >= 1``.

    Hertz (Johnson 1985, 3.4): ``q = ((1/k^2) E(m) - K(m)) / (K(m) - E(m))`` with
    ``m = 1 - k^2``; monotone in k, equal to 1 at k = 1.
    """

    # here, not at import: scipy.optimize costs ~0.3 s of start-up
    from scipy import optimize, special

    def resid(logk: float) -> float:
        k = math.exp(logk)
        m = 1.0 - k * k
        K = special.ellipkm1(k * k)  # K(m) accurate as m -> 1
        E = special.ellipe(m)
        return math.log((E / (k * k) - K) / (K - E)) - math.log(q)

    # resid -> 0 as k -> 1, so bracket away from 1; k ~ q^(-0.636) (Hamrock-Brewe) is inside.
    hi = -1e-9
    lo = -1.0
    while resid(lo) < 0.0:
        lo *= 2.0
        if lo < -200:
            raise ValueError(f"curvature ratio {q} out of range")
    return math.exp(optimize.brentq(resid, lo, hi, xtol=1e-15, rtol=1e-14))


def hertz_elliptic(load: float, Rx: float, Ry: float, E_reduced: float) -> HertzContact:
    """Exact Hertz solution for an elliptic contact (complete elliptic integrals).

    Gap ``x^2/(2 Rx) + y^2/(2 Ry)``. The larger semi-axis lies along the larger radius;
    ``major^3 = 3 P (K - E) / (pi E' e^2 C_small)`` with ``C_small = 1/(2 R_large)``,
    ``e^2 = 1 - k^2``, ``pmax = 3 P / (2 pi a b)``. Reduces to :func:`hertz_circular` at Rx = Ry.
    """
    P = require_positive("load", load, "N")
    Rx = require_positive("Rx", Rx, "m")
    Ry = require_positive("Ry", Ry, "m")
    E = require_positive("E_reduced", E_reduced, "Pa")
    if abs(math.log(Rx / Ry)) < 1e-9:
        c = hertz_circular(P, Rx, E)
        return HertzContact("elliptic", P, c.pmax, c.a, c.b, c.area, c.mean_pressure)
    from scipy import special

    R_large, R_small = max(Rx, Ry), min(Rx, Ry)
    k = _axis_ratio_from_curvatures(R_large / R_small)
    m = 1.0 - k * k
    K = special.ellipkm1(k * k)
    Ee = special.ellipe(m)
    c_small = 1.0 / (2.0 * R_large)
    # E* of Johnson is E'/2: major^3 = 3P(K-E)/(2 pi E* m C_small).
    major = (3.0 * P * (K - Ee) / (math.pi * E * m * c_small)) ** (1.0 / 3.0)
    minor = k * major
    a, b = (major, minor) if Rx > Ry else (minor, major)
    pmax = 3.0 * P / (2.0 * math.pi * a * b)
    area = math.pi * a * b
    return HertzContact("elliptic", P, pmax, a, b, area, P / area)


def hertz_point(load: float, Rx: float, Ry: float, E_reduced: float) -> HertzContact:
    """Circular when Rx = Ry, otherwise elliptic."""
    if math.isclose(Rx, Ry, rel_tol=1e-12):
        return hertz_circular(load, Rx, E_reduced)
    return hertz_elliptic(load, Rx, Ry, E_reduced)


def load_for_pmax_line(pmax: float, length: float, R: float, E_reduced: float) -> float:
    """Load [N] of a line contact whose Hertzian pressure is ``pmax`` [Pa]:
    ``b = 4 R pmax / E'``, ``P = pi b pmax B / 2``."""
    pmax = require_positive("pmax", pmax, "Pa")
    b = 4.0 * R * pmax / E_reduced
    return math.pi * b * pmax * length / 2.0


def load_for_pmax_point(pmax: float, Rx: float, Ry: float, E_reduced: float) -> float:
    """Load [N] of a point contact whose Hertzian pressure is ``pmax`` [Pa] (pmax ~ P^(1/3))."""
    pmax = require_positive("pmax", pmax, "Pa")
    ref = hertz_point(1.0, Rx, Ry, E_reduced)
    return (pmax / ref.pmax) ** 3


def hertz_pressure_line(x: np.ndarray, b: float, pmax: float) -> np.ndarray:
    """``pmax sqrt(1 - (x/b)^2)`` inside the contact, 0 outside [Pa]."""
    s = 1.0 - (np.asarray(x, dtype=float) / b) ** 2
    return pmax * np.sqrt(np.clip(s, 0.0, None))


def hertz_pressure_point(x: np.ndarray, y: np.ndarray, a: float, b: float, pmax: float) -> np.ndarray:
    """``pmax sqrt(1 - (x/a)^2 - (y/b)^2)`` inside the ellipse, 0 outside [Pa]."""
    s = 1.0 - (np.asarray(x, dtype=float) / a) ** 2 - (np.asarray(y, dtype=float) / b) ** 2
    return pmax * np.sqrt(np.clip(s, 0.0, None))
