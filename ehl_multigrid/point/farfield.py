"""Far-field pressure of a circular point contact whose film is thick against its deformation.

Far from the contact the film is the gap of the undeformed surfaces, ``H ~ r^2/2``, the pressure
is small (isoviscous, incompressible) and Reynolds' equation (Venner's form,
``div(eps grad P) = dH/dX``, ``eps = H^3/lambda``) becomes ``div(r^6 grad P) = 8 lambda X``. Its
solutions that fall as ``r^-3`` are ``P = r^-3 [B cos(phi) + C cosh(3 (phi - pi))]`` with
``B = -0.8 lambda`` (the particular solution; the periodic homogeneous ones fall as ``r^-6`` and
faster) and any ``C`` (``cosh(3 phi)``: ``m (m + 6) = k^2`` with ``m = -3``, ``k = 3i``). On the
free boundary, a ray at ``phi_c`` from the X axis, Reynolds' condition ``P = dP/dphi = 0`` gives
``tan(psi) = -3 tanh(3 psi)`` for ``psi = pi - phi_c`` and ``C = B cos(psi)/cosh(3 psi)``:
``phi_c = 71.56 deg``, ``C = 0.00173 lambda``; the pressure reaches past ``X = 0`` into the
outlet half-plane. The load it carries outside a box falls only as ``1/box``.

With it on the boundary and its load beyond the box counted, a rigid circular film no longer
depends on the box (docs/robustness.md, "Rigid surfaces": 0.1 % from half the rigid box to the
whole, against 15 % with ``P = 0``).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq

#: ``-B/lambda`` of the far-field pressure ``B cos(phi)/r^3``
FAR_AMPLITUDE = 0.8
#: angle from the -X axis of the far field's free boundary: ``tan(psi) = -3 tanh(3 psi)``
PSI = brentq(lambda p: math.tan(p) + 3.0 * math.tanh(3.0 * p), 1.6, 3.0)
#: ``C/B`` of the ``cosh(3 (phi - pi))`` term
COSH_RATIO = math.cos(PSI) / math.cosh(3.0 * PSI)


def _terms(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The ``cos(phi)`` and ``cosh(3 (phi - pi))`` terms of ``r^3 P / lambda`` inside the sector."""
    B = -FAR_AMPLITUDE
    inside = (phi > math.pi - PSI) & (phi < math.pi + PSI)
    return (np.where(inside, B * np.cos(phi), 0.0),
            np.where(inside, B * COSH_RATIO * np.cosh(3.0 * (phi - math.pi)), 0.0))


def far_pressure(lam: float, X: np.ndarray, Y: np.ndarray, c2: float = 0.0,
                 k: float = 0.0) -> np.ndarray:
    """The far-field pressure at ``(X, Y)`` (Venner units; zero at the origin). ``c2 = 2 H00``
    and ``k`` (the far deformation ``k/r`` of an elastic contact, ``k`` = the deformation
    constant times the load): the gap ``r^2/2 + c2/2 + k/r`` instead of ``r^2/2``, to first
    order in ``c2/r^2`` and ``k/r^3``, which turns the radial factors into
    ``r^-3 (1 - 2 c2/r^2 - 16 k/r^3)`` (cos) and ``r^-3 (1 - 4.5 c2/r^2 - 6 k/r^3)`` (cosh)."""
    X, Y = np.broadcast_arrays(np.asarray(X, float), np.asarray(Y, float))
    r = np.hypot(X, Y)
    phi = np.mod(np.arctan2(Y, X), 2.0 * math.pi)
    t1, t3 = _terms(phi)
    with np.errstate(divide="ignore", invalid="ignore"):
        q, e = c2 / (r * r), k / r**3
        out = lam * np.maximum(t1 * (1.0 - 2.0 * q - 16.0 * e) + t3 * (1.0 - 4.5 * q - 6.0 * e),
                               0.0) / r**3
    return np.where(r > 0.0, out, 0.0)


def load_outside(lam: float, xmin: float, xmax: float, ymax: float, c2: float = 0.0,
                 k: float = 0.0) -> float:
    """``∫∫ far_pressure`` outside the box ``xmin <= X <= xmax, |Y| <= ymax`` (``xmin < 0 <
    xmax``): along each ray ``∫_R^inf r^-3 (1 - a c2/r^2 - b k/r^3) r dr = 1/R - a c2/(3 R^3)
    - b k/(4 R^4)``, ``R`` where the ray leaves the box."""
    def ray(phi: float) -> float:
        c, s = math.cos(phi), math.sin(phi)
        R = min([xmin / c] if c < 0 else [xmax / c] if c > 0 else [math.inf])
        if s != 0.0:
            R = min(R, ymax / abs(s))
        t1, t3 = (float(t) for t in _terms(np.array(phi)))
        return (t1 * (1.0 / R - 2.0 * c2 / (3.0 * R**3) - 4.0 * k / R**4)
                + t3 * (1.0 / R - 1.5 * c2 / R**3 - 1.5 * k / R**4))

    lo, hi = math.pi - PSI, math.pi + PSI
    corners = sorted(p % (2 * math.pi) for p in (math.atan2(ymax, xmin), math.atan2(-ymax, xmin),
                                                  math.atan2(ymax, xmax), math.atan2(-ymax, xmax)))
    breaks = [p for p in corners if lo < p < hi] + [math.pi]
    return lam * quad(ray, lo, hi, points=breaks, limit=400)[0]


def boundary_excess(P: np.ndarray, hx: float, hy: float, half: bool) -> float:
    """How much the plain node sum of :func:`~.fas.load_integral` counts boundary values above
    the trapezoid rule (edge nodes weigh 1/2, corners 1/4; a half domain's row 0 is the
    symmetry line, inside the full domain)."""
    w = np.zeros(P.shape)
    w[:, 0] += 0.5
    w[:, -1] += 0.5
    w[-1, :] += 0.5
    if not half:
        w[0, :] += 0.5
    w[-1, 0] = w[-1, -1] = 0.75
    if not half:
        w[0, 0] = w[0, -1] = 0.75
    rows = np.ones(P.shape[0]) if not half else np.r_[1.0, np.full(P.shape[0] - 1, 2.0)]
    return float(hx * hy * np.sum(rows[:, None] * w * P))


class ClosedFormFarField:
    """The circular contact's far field (this module's closed form) behind the interface of
    :class:`~.farfield_angular.AngularFarField` (``pressure``, ``load_outside``)."""

    theta = 1.0

    @staticmethod
    def pressure(lam: float, X: np.ndarray, Y: np.ndarray, c2: float = 0.0, k: float = 0.0) -> np.ndarray:
        return far_pressure(lam, X, Y, c2, k)

    @staticmethod
    def load_outside(lam: float, xmin: float, xmax: float, ymax: float, c2: float = 0.0,
                     k: float = 0.0) -> float:
        return load_outside(lam, xmin, xmax, ymax, c2, k)


def far_field_for(theta: float):
    """The far field of ellipticity ``theta``: the closed form for a round gap (on it the film
    comes closer to the wide box than with the angular solution: docs/accuracy.md), else
    :func:`~.farfield_angular.angular_far_field`."""
    if abs(theta - 1.0) <= 1e-12:
        return ClosedFormFarField()
    from .farfield_angular import angular_far_field

    return angular_far_field(float(theta))


def far_field_on(far_field: bool | None) -> bool:
    """Whether a point solve takes the far-field boundary: as asked, else always (circular
    contacts by this module's closed form, elliptic ones by ``point.farfield_angular``)."""
    return True if far_field is None else bool(far_field)
