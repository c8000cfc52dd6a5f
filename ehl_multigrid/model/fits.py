"""Central film-thickness fits of Moes (line) and Nijenbanning (elliptic).

* Moes line fit (2.17-2.22) and its mixed-lubrication form (4.23-4.24);
* Nijenbanning elliptic fit (2.23-2.29) and its mixed-lubrication form (4.25-4.26).

All take Moes groups (M, L) built on the sum velocity and return the Moes-scaled central film
``Hc`` (``h = Hc R sqrt(eta0 us/(E' R))``, see :func:`ehl_multigrid.model.groups.moes_film_scale`).
``gamma1 >= 1`` is the fluid load-sharing factor ``P/Ph``; ``gamma1 = 1`` is the smooth fit.
Vectorised: arguments broadcast against each other.

The fits were built on Barus-type, incompressible solutions: a solver with Roelands viscosity
and Dowson-Higginson compressibility gives markedly thinner central films, which is physics,
not an error of either (how much thinner, and where the fits were checked: docs/fits.md).
"""

from __future__ import annotations

import json
import math
from functools import lru_cache
from importlib import resources
from typing import Any

import numpy as np

from .errors import InputError

ArrayLike = float | np.ndarray


def _prep(M: ArrayLike, L: ArrayLike, gamma1: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    M, L, g = np.broadcast_arrays(
        np.asarray(M, dtype=float), np.asarray(L, dtype=float), np.asarray(gamma1, dtype=float)
    )
    if np.any(~(M > 0)) or not np.all(np.isfinite(M)):
        raise InputError(f"M = {M[~(M > 0) | ~np.isfinite(M)].ravel()[:3]} must be finite and > 0")
    if np.any(~(L >= 0)) or not np.all(np.isfinite(L)):
        raise InputError(f"L = {L[~(L >= 0) | ~np.isfinite(L)].ravel()[:3]} must be finite and >= 0")
    if np.any(~(g >= 1)):
        raise InputError(f"gamma1 = {g[~(g >= 1)].ravel()[:3]} must be >= 1 (gamma1 = P/Ph)")
    return M, L, g


def _out(x: np.ndarray) -> ArrayLike:
    return float(x) if x.ndim == 0 else x


def moes_line_terms(M: ArrayLike, L: ArrayLike) -> dict[str, np.ndarray]:
    """Asymptotes of the Moes line fit (2.18-2.21): HRI, HEI, HRP, HEP."""
    M = np.asarray(M, dtype=float)
    L = np.asarray(L, dtype=float)
    return {
        "HRI": 3.0 / M,
        "HEI": 2.621 * M ** (-1.0 / 5.0),
        "HRP": 1.287 * L ** (2.0 / 3.0),
        "HEP": 1.311 * M ** (-1.0 / 8.0) * L ** (3.0 / 4.0),
    }


def moes_line_central(M: ArrayLike, L: ArrayLike, gamma1: ArrayLike = 1.0) -> ArrayLike:
    """Moes line central film (2.17, 2.22); with ``gamma1`` the mixed form (4.23-4.24).

    ``Hc = [gamma1^s (HRI^(7/3) + gamma1^(-14/15) HEI^(7/3))^(3s/7)
    + (HRP^(-7/2) + HEP^(-7/2))^(-2s/7)]^(1/s)``,
    ``s = (7 + 8 exp(-2 (HEI/HRI) gamma1^(-2/5)))/5``.

    At ``L = 0`` the piezoviscous term vanishes (limit of ``HRP, HEP -> 0``).

    Examples
    --------
    >>> round(moes_line_central(1e-3, 0.0) * 1e-3, 3)   # rigid-isoviscous asymptote 3/M
    3.0
    """
    M, L, g = _prep(M, L, gamma1)
    t = moes_line_terms(M, L)
    s = (7.0 + 8.0 * np.exp(-2.0 * (t["HEI"] / t["HRI"]) * g ** (-2.0 / 5.0))) / 5.0
    iso = g**s * (t["HRI"] ** (7.0 / 3.0) + g ** (-14.0 / 15.0) * t["HEI"] ** (7.0 / 3.0)) ** (3.0 * s / 7.0)
    with np.errstate(divide="ignore"):
        inner = t["HRP"] ** (-3.5) + t["HEP"] ** (-3.5)
        piezo = np.where(L > 0, inner ** (-2.0 * s / 7.0), 0.0)
    return _out((iso + piezo) ** (1.0 / s))


def nijenbanning_terms(M: ArrayLike, L: ArrayLike, theta: ArrayLike = 1.0) -> dict[str, np.ndarray]:
    """Asymptotes of the Nijenbanning fit (2.24-2.29) for ellipticity ``theta = Rx/Ry``."""
    M = np.asarray(M, dtype=float)
    L = np.asarray(L, dtype=float)
    th = np.asarray(theta, dtype=float)
    c = 1.0 + 0.006 * np.log(th) + 0.63 * th ** (4.0 / 7.0)
    return {
        "HRI": 145.0 * (1.0 + 0.796 * th ** (14.0 / 15.0)) ** (-15.0 / 7.0) / th * M**-2.0,
        "HEI": 3.18 * c ** (-14.0 / 25.0) * th ** (-1.0 / 15.0) * M ** (-2.0 / 15.0),
        "HRP": 1.29 * (1.0 + 0.691 * th) ** (-2.0 / 3.0) * L ** (2.0 / 3.0),
        "HEP": 1.48 * c ** (-7.0 / 20.0) * th ** (-1.0 / 24.0) * M ** (-1.0 / 12.0) * L ** 0.75,
        "H00": 1.8 / th,
    }


def nijenbanning_central(
    M: ArrayLike, L: ArrayLike, theta: ArrayLike = 1.0, gamma1: ArrayLike = 1.0
) -> ArrayLike:
    """Nijenbanning central film (2.23); with ``gamma1`` the mixed form (4.25-4.26).

    ``Hc = gamma1^(1/2) [(gamma1^(9/4) HRI^(3/2) + (gamma1^(-2/5) HEI^(-4) + H00^(-4))^(-3/8))^(2s/3)
    + (gamma1^4 HRP^(-8) + gamma1^4 HEP^(-8))^(-s/8)]^(1/s)``,
    ``s = 1.5 (1 + exp(-1.2 (HEI/HRI) gamma1^(-7/5)))``.
    """
    M, L, g = _prep(M, L, gamma1)
    th = np.broadcast_to(np.asarray(theta, dtype=float), M.shape)
    if np.any(~(th > 0)):
        raise InputError(f"theta = {th[~(th > 0)].ravel()[:3]} must be > 0 (theta = Rx/Ry)")
    t = nijenbanning_terms(M, L, th)
    s = 1.5 * (1.0 + np.exp(-1.2 * (t["HEI"] / t["HRI"]) * g ** (-7.0 / 5.0)))
    ei = (g ** (-2.0 / 5.0) * t["HEI"] ** -4.0 + t["H00"] ** -4.0) ** (-3.0 / 8.0)
    iso = (g ** (9.0 / 4.0) * t["HRI"] ** 1.5 + ei) ** (2.0 * s / 3.0)
    with np.errstate(divide="ignore"):
        inner = g**4 * t["HRP"] ** -8.0 + g**4 * t["HEP"] ** -8.0
        piezo = np.where(L > 0, inner ** (-s / 8.0), 0.0)
    return _out(np.sqrt(g) * (iso + piezo) ** (1.0 / s))


#: Ellipticity range over which the Nijenbanning fit was checked against the point solver
#: (theta = 0.25, 1 and 4; docs/fits.md).
CHECKED_THETA = (0.25, 4.0)


@lru_cache(maxsize=2)
def deviation_table(contact: str) -> dict[str, Any]:
    """The package's fit-check table of ``contact`` (``ehl_multigrid/data/fit_deviation_*.json``):
    ``M`` and ``L`` grids, ``deviation[i, j]`` = (Hc_fit - Hc_solver)/Hc_solver at (M_i, L_j)
    against converged Roelands + Dowson-Higginson solutions (nan where no solve converged; point
    contacts at theta = 1), ``definition``, ``source`` and ``provenance`` (package version, date,
    command and solver fingerprint of the run that wrote it; docs/fits.md). Read once."""
    kind = "line" if contact == "line" else "point"
    tab = json.loads((resources.files("ehl_multigrid") / "data" / f"fit_deviation_{kind}.json").read_text())
    dev = np.array([[np.nan if v is None else v for v in row] for row in tab["deviation"]], dtype=float)
    dev.setflags(write=False)
    return {"M": tuple(float(m) for m in tab["M"]), "L": tuple(float(x) for x in tab["L"]), "deviation": dev,
            "definition": tab.get("definition", ""), "source": tab.get("source", ""),
            "provenance": tab.get("provenance", {})}


def checked_range(contact: str) -> dict[str, tuple[float, float]]:
    """The (M, L) box (and theta for point contacts) over which the package's fit-check studies
    compared the fit with converged solver solutions (``ehl_multigrid/data/fit_deviation_*.json``).
    Outside it a fitted film is an extrapolation of the fit's asymptotes, unchecked here."""
    tab = deviation_table(contact)
    out = {"M": (min(tab["M"]), max(tab["M"])), "L": (min(tab["L"]), max(tab["L"]))}
    if contact != "line":
        out["theta"] = CHECKED_THETA
    return out


def fit_deviation(contact: str, M: float, L: float) -> tuple[float, float, float] | None:
    """The measured bias of the fit at (M, L): ``(dev, lo, hi)`` with ``dev`` the deviation
    (Hc_fit - Hc_solver)/Hc_solver of :func:`deviation_table` interpolated bilinearly in
    (log M, L), and ``lo``, ``hi`` the smallest and largest of the table cell's corners; corners
    without a converged solve are left out. ``None`` outside the table or without any corner."""
    tab = deviation_table(contact)
    Ms, Ls, dev = np.log(tab["M"]), np.asarray(tab["L"]), tab["deviation"]
    if not (M > 0 and math.isfinite(M) and math.isfinite(L)):
        return None
    x, y = math.log(M), float(L)
    if not (Ms[0] <= x <= Ms[-1] and Ls[0] <= y <= Ls[-1]):
        return None
    i = min(int(np.searchsorted(Ms, x, side="right")) - 1, len(Ms) - 2)
    j = min(int(np.searchsorted(Ls, y, side="right")) - 1, len(Ls) - 2)
    tx = (x - Ms[i]) / (Ms[i + 1] - Ms[i])
    ty = (y - Ls[j]) / (Ls[j + 1] - Ls[j])
    corners = dev[i:i + 2, j:j + 2]
    weights = np.outer([1.0 - tx, tx], [1.0 - ty, ty])
    have = np.isfinite(corners)
    if not have.any():
        return None
    w = np.where(have, weights, 0.0)
    # on a grid line the far corners have no weight: then their mean stands in
    value = float(np.sum(w * np.nan_to_num(corners)) / np.sum(w)) if np.sum(w) > 0 else float(np.mean(corners[have]))
    return value, float(np.min(corners[have])), float(np.max(corners[have]))


def _bias_words(lo: float, hi: float) -> str:
    """``lo``-``hi`` (relative deviations of the fit from the solver) in words."""
    if round(100 * lo) == round(100 * hi):
        return f"about {abs(100 * lo):.0f} % {'above' if lo >= 0.0 else 'below'}"
    if lo >= 0.0:
        return f"{100 * lo:.0f}-{100 * hi:.0f} % above"
    if hi <= 0.0:
        return f"{-100 * hi:.0f}-{-100 * lo:.0f} % below"
    return f"{-100 * lo:.0f} % below to {100 * hi:.0f} % above"


def fit_validity(contact: str, M: float, L: float, theta: float = 1.0) -> dict[str, Any]:
    """Where the central-film fit stands at (M, L, theta): inside the range where the package
    checked it against its solver (:func:`checked_range`, :func:`extrapolation_note`) and, inside
    it, its measured bias (:func:`fit_deviation`; point contacts measured at theta = 1, so given
    for theta <= 1 only); for theta > 1 :func:`deviation_note` instead.

    Returns
    -------
    dict
        ``in_range`` (bool); ``range`` (the checked box as text); ``deviation``, ``deviation_min``,
        ``deviation_max`` ((Hc_fit - Hc_solver)/Hc_solver interpolated and over the table cell;
        nan outside the range); ``extrapolation`` and ``theta_note`` (sentences or None);
        ``note`` (one sentence for the reader: the extrapolation, or the bias).
    """
    box = checked_range(contact)
    extrapolation = extrapolation_note(contact, M, L, theta)
    theta_note = deviation_note(contact, theta)
    found = fit_deviation(contact, M, L) if extrapolation is None and theta_note is None else None
    dev, lo, hi = found if found is not None else (math.nan, math.nan, math.nan)
    name = "Moes line" if contact == "line" else "Nijenbanning"
    if extrapolation is not None:
        note = extrapolation
    elif theta_note is not None:
        note = theta_note
    elif found is None:
        note = f"inside the checked range, but no converged solve of the {name} fit check lies near here"
    else:
        at_one = "" if contact == "line" or theta == 1.0 else ", measured at theta = 1"
        note = (f"the {name} fit is typically {_bias_words(lo, hi)} the converged Roelands + "
                f"Dowson-Higginson solver here ({100 * dev:+.0f} % interpolated{at_one}; the package's fit check)")
    if theta_note is not None and note != theta_note:
        note = f"{note}; {theta_note}"
    return {
        "in_range": extrapolation is None,
        "range": ", ".join(f"{k} in [{a:g}, {b:g}]" for k, (a, b) in box.items()),
        "deviation": dev, "deviation_min": lo, "deviation_max": hi,
        "extrapolation": extrapolation, "theta_note": theta_note, "note": note,
    }


def extrapolation_note(contact: str, M: float, L: float, theta: float = 1.0) -> str | None:
    """A sentence saying which of ``M``, ``L``, ``theta`` lie outside :func:`checked_range`, or
    ``None`` when the fit is used where it was checked."""
    box = checked_range(contact)
    values = {"M": M, "L": L, "theta": theta}
    outside = [f"{k} = {values[k]:.4g} outside [{lo:g}, {hi:g}]" for k, (lo, hi) in box.items()
               if not lo <= values[k] <= hi]
    if not outside:
        return None
    name = "Moes line" if contact == "line" else "Nijenbanning"
    return (f"the {name} fit is extrapolated here ({'; '.join(outside)}, the range where it was checked "
            "against the solver); treat Hc as an estimate")


#: range of (solver Hc)/(Nijenbanning Hc) - 1 at theta = 4 (Barus, incompressible, M 5-100,
#: L 0-10): the fit, demonstrated by Nijenbanning et al. (1994) for theta < 1, under-predicts
#: contacts long in the rolling direction (docs/fits.md)
THETA_ABOVE_ONE_DEVIATION = (0.10, 0.54)
#: the solver's central film above Nijenbanning's per doubling of theta > 1: 0.11 at theta = 2,
#: 0.23-0.28 at theta = 4 (Barus, L = 5-10; more at L = 0) (docs/fits.md)
THETA_DEVIATION_PER_DOUBLING = 0.12


def theta_deviation(contact: str, theta: float = 1.0) -> float:
    """Expected extra deviation of the Nijenbanning central film at ``theta > 1`` (a contact
    long in the rolling direction), beyond the one measured at theta = 1:
    :data:`THETA_DEVIATION_PER_DOUBLING` times ``log2(theta)``; 0 for line contacts and
    theta <= 1."""
    if contact == "line" or not theta > 1.0:
        return 0.0
    return THETA_DEVIATION_PER_DOUBLING * math.log2(theta)


def deviation_note(contact: str, theta: float = 1.0) -> str | None:
    """A sentence when the fit is used where the package's solver measured it far off even
    inside the checked range (point contacts with ``theta > 1``), else ``None``."""
    if contact == "line" or not theta > 1.0:
        return None
    lo, hi = THETA_ABOVE_ONE_DEVIATION
    # the range is where it was measured: crossed cylinders at theta = 4, M 389, L 8.7 (Roelands)
    # had the solver 1 % below the fit
    return (f"theta = {theta:.4g} > 1 (contact long in the rolling direction): at theta = 4 the point "
            f"solver's central film was {lo:.0%}-{hi:.0%} above the Nijenbanning fit over M 5-100, L 0-10 "
            f"(Barus) and 1% below it at M 389, L 8.7; Nijenbanning et al. (1994) demonstrate the fit for "
            f"theta < 1: solve the contact (ehl solve) instead of trusting the fit")


def central_film_fit(contact: str, M: ArrayLike, L: ArrayLike, theta: ArrayLike = 1.0, gamma1: ArrayLike = 1.0) -> ArrayLike:
    """Moes fit for ``contact == 'line'``, Nijenbanning otherwise."""
    if contact == "line":
        return moes_line_central(M, L, gamma1)
    if contact in ("point", "circular", "elliptic"):
        return nijenbanning_central(M, L, theta, gamma1)
    raise InputError(f"contact = {contact!r} is not one of ['line', 'point', 'elliptic']")


def gupta_thermal_factor(L: ArrayLike, S: ArrayLike, ph_over_E: float) -> ArrayLike:
    """Thermal reduction of the central film ``hc,thermal/hc,isothermal`` of Gupta et al. (1992),
    in the form commonly quoted (not checked against the paper here):
    ``(1 - 13.2 (ph/E') L^0.42) / (1 + 0.213 (1 + 2.23 |S|^0.83) L^0.64)`` with the thermal
    loading ``L = beta eta0 um^2/k`` (:meth:`Scene.thermal_properties`), the slide-to-roll ratio
    ``S`` and ``ph/E'``. A flag for the central film, not a bound on the minimum film: the
    coupled thermal EHL solver reduces the minimum film more than this at high load and slip
    (docs/fits.md)."""
    L = np.asarray(L, dtype=float)
    S = np.abs(np.asarray(S, dtype=float))
    if np.any(L < 0.0):
        raise InputError(f"thermal loading L = {L} must be >= 0")
    return _out((1.0 - 13.2 * ph_over_E * L**0.42) / (1.0 + 0.213 * (1.0 + 2.23 * S**0.83) * L**0.64))
