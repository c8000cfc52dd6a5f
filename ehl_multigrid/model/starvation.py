"""Chevalier's starved central film (thesis chapter 6, (6.1)-(6.4)) from the flooded film.

``Hcs/Hc = r/(1 + r^delta)^(1/delta)``, ``r = hoil/(hc rho_bar(pmax))`` (Chevalier et al. 1998):
the supplied layer ``hoil`` (both surfaces together, ambient density), compressed to the
density at pmax (isothermal Dowson-Higginson (2.7)), bounds the film as the speed grows.
``delta`` lies between 2 and 5 (3.5 by default); ``delta = "inlet"`` takes it from the flooded
inlet: circular contacts ``2.37 - 0.95 log10(Hc_ff)`` (``Hc_ff = hc Rx/a^2``), fitted to the
package's mass-conserving starved point solver within 0.1 over nine contacts (L = 2-20); line
contacts ``Hc/Hc_ff = min(r, 1)``, which (6.1) approaches at its largest admitted ``delta`` (20);
elliptic contacts (``0.25 <= theta <= 4``) the circular rule with terms in ``t = log10(theta)``,
``+ t (-0.202 + 2.152 log10(Hc_ff)) + 1.574 t^2``, fitted to the same solver over 20 contacts
(rms 0.11); outside that ellipticity they are refused. The rules are in the spirit of Damiens et
al. (2004), whose inlet parameter collapses circular contacts.
"""

from __future__ import annotations

import math

import numpy as np

from .errors import InputError, require_positive, require_range
from .lubricant import density_ratio_dh

ArrayLike = float | np.ndarray

#: ``delta = a + b log10(Hc_ff)`` (Venner units) of circular contacts, fitted to the starved point
#: solver (docs/fits.md, "Starved films")
INLET_DELTA_FIT = (2.37, -0.95)
#: Hc_ff (Venner) over which that fit was made; outside it ``delta`` is held at the end values,
#: since the fitted line does not hold beyond them (docs/fits.md)
INLET_HC_RANGE = (0.063, 0.447)
#: elliptic contacts: ``delta`` = the circular rule ``+ t (c1 + c2 log10(Hc_ff)) + c3 t^2``,
#: ``t = log10(theta)``, fitted to the starved point solver at theta 0.25-4 (docs/fits.md)
INLET_DELTA_THETA = (-0.202, 2.152, 1.574)
#: the ellipticities ``theta = Rx/Ry`` over which that fit was made (refused outside)
INLET_THETA_RANGE = (0.25, 4.0)
#: elliptic Hc_ff (Venner) range at theta: these values times ``theta^INLET_HC_THETA_POWER``;
#: ``delta`` is held at its ends, as the circular one at INLET_HC_RANGE
INLET_HC_RANGE_ELLIPTIC = (0.0445, 0.245)
INLET_HC_THETA_POWER = -0.53
#: line contacts: (6.1) at its largest admitted exponent stands for the solver's min(r, 1)
LINE_INLET_DELTA = 20.0
#: the admitted constant exponents
DELTA_RANGE = (0.5, 20.0)
#: the one named exponent rule besides a number
INLET = "inlet"


def require_delta(name: str, delta: float | str) -> float | str:
    """A Chevalier exponent: a number in :data:`DELTA_RANGE` or ``"inlet"`` (from the flooded inlet)."""
    if isinstance(delta, str):
        if delta != INLET:
            raise InputError(f"{name} = {delta!r} must be a number in [{DELTA_RANGE[0]}, {DELTA_RANGE[1]}] "
                             f"or {INLET!r} (the exponent from the flooded inlet length)")
        return delta
    return require_range(name, delta, DELTA_RANGE[0], DELTA_RANGE[1], "-")


def inlet_delta(kind: str, hc_venner: ArrayLike, theta: float = 1.0) -> ArrayLike:
    """Chevalier's exponent from the flooded inlet: ``kind`` ``"line"`` gives
    :data:`LINE_INLET_DELTA`; a circular contact ``2.37 - 0.95 log10(Hc_ff)``, ``Hc_ff = hc Rx/a^2``
    (flooded central film in Venner units, ``a`` the Hertzian semi-axis in the rolling
    direction), with ``Hc_ff`` held inside :data:`INLET_HC_RANGE`, where it was measured; an
    elliptic contact of ellipticity ``theta = Rx/Ry`` in :data:`INLET_THETA_RANGE` adds
    :data:`INLET_DELTA_THETA`'s terms (``Hc_ff`` held inside the range measured at that theta)."""
    h = np.asarray(hc_venner, dtype=float)
    if np.any(~(h > 0)):
        raise InputError(f"hc_venner = {h[~(h > 0)].ravel()[:3]} must be > 0 (flooded film, h Rx/a^2)")
    a, b = INLET_DELTA_FIT
    if kind == "line":
        out = np.full(h.shape, LINE_INLET_DELTA)
    elif kind == "elliptic":
        lo, hi = INLET_THETA_RANGE
        if not lo <= theta <= hi:
            raise InputError(
                f"supply.delta = 'inlet' is measured for elliptic contacts with theta = Rx/Ry in "
                f"[{lo:g}, {hi:g}] (here {theta:.4g}): the starved point solver's exponent depends on the "
                "ellipticity (validation/starved/study_collapse_elliptic.py); give supply.delta a number "
                "(0.5-20) for this elliptic contact")
        t = math.log10(theta)
        c1, c2, c3 = INLET_DELTA_THETA
        scale = theta ** INLET_HC_THETA_POWER
        x = np.log10(np.clip(h, INLET_HC_RANGE_ELLIPTIC[0] * scale, INLET_HC_RANGE_ELLIPTIC[1] * scale))
        out = a + b * x + t * (c1 + c2 * x) + c3 * t * t
    else:
        out = a + b * np.log10(np.clip(h, *INLET_HC_RANGE))
    return float(out) if out.ndim == 0 else out


def chevalier_reduction(r: ArrayLike, delta: float = 3.5) -> ArrayLike:
    """Film reduction (6.1) ``Hcs/Hc = r/(1 + r^delta)^(1/delta)``; 1 for ``r = inf``."""
    delta = require_range("delta", delta, 0.5, 20.0, "-")
    r = np.asarray(r, dtype=float)
    if np.any(~(r >= 0)):
        raise InputError(f"r = {r[~(r >= 0)].ravel()[:3]} must be >= 0 (r = Hoil/(Hc rho_bar))")
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        lr = np.log(r)
        out = np.exp(lr - np.logaddexp(0.0, delta * lr) / delta)
    out = np.where(np.isinf(r), 1.0, out)
    return float(out) if out.ndim == 0 else out


def log_starved_film(log_hc: np.ndarray, hoil: float, rho_bar: float, delta: float) -> np.ndarray:
    """``ln hcs`` from ``ln hc`` (metres) by (6.3)-(6.4); ``hoil = inf`` returns ``ln hc``."""
    if math.isinf(hoil):
        return np.asarray(log_hc, dtype=float)
    log_cap = math.log(hoil / rho_bar)  # limit of hcs for hc -> inf
    log_r = log_cap - np.asarray(log_hc, dtype=float)
    return log_cap - np.logaddexp(0.0, delta * log_r) / delta


def density_ratio_at(pmax: float) -> float:
    """``rho_bar(pmax)`` of (6.3): isothermal Dowson-Higginson density ratio (2.7)."""
    return float(density_ratio_dh(require_positive("pmax", pmax, "Pa")))
