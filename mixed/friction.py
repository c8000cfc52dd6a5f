"""Friction in mixed lubrication (thesis 4.2.3, (4.30)-(4.39); chapter 5.4).

``f = (fc Pa + tau_H AH)/P`` (4.39): Coulomb friction on the asperities (4.31)-(4.32) plus the
shear force of the film.

* Isothermal (chapter 4): ``tau_H = tau0 asinh(eta gamma_dot/tau0)`` (4.33), Roelands viscosity
  (4.34) at the oil temperature and at ``pavehl = Ph/AH`` (4.35), ``AH = Anom (Ph/P)^(1/2)``
  (line, 4.36) or ``Anom (Ph/P)^(2/3)`` (point, 4.37) -- the Hertzian area of the load Ph --
  and ``gamma_dot = |u1 - u2|/hf,r = |S| us/(2 hf,r)``.
* Thermal (chapter 5.4): the film force comes from the thermal Roelands-Eyring solver
  (``thermal.film_friction``) run on the Hertz pressure of the load Ph (whose area and mean
  pressure are exactly AH and pavehl) with the uniform film hf,r; the temperature rises are
  reported. The asperity part and the load sharing are unchanged (the thesis's assumption).
  All speeds are solved as one batch (``thermal.film.film_frictions``: the line problems of
  every speed and slice on a thread pool), each with the answer of ``film_friction``.

Friction is returned as a magnitude: the sign of the slip only sets its direction.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ehl_multigrid.model.errors import ConvergenceError, InputError, require_range
from ehl_multigrid.model.lubricant import Lubricant
from ehl_multigrid.model.scene import Scene

from .sharing import LoadSharing


@dataclass
class MixedFriction:
    """Friction along a set of sum velocities (arrays over ``us``).

    ``coefficient = asperity + film``; ``asperity = fc Pa/P``; ``film = F_film/P``;
    ``film_force`` [N]; ``AH`` [m^2]; ``pavehl`` [Pa]; ``tau_film`` [Pa] mean film shear stress;
    ``eta_film`` [Pa s] (isothermal Roelands at pavehl, NaN on the thermal path);
    ``shear_rate`` [1/s]. Thermal path only: ``mean_temperature_rise``, ``max_temperature_rise``
    [K], ``thermal_converged``; ``thermal_used`` marks points solved by the thermal solver
    (points whose film carries less than ``min_film_fraction`` of the load use the isothermal
    film term, which is then negligible).
    """

    us: np.ndarray
    coefficient: np.ndarray
    asperity: np.ndarray
    film: np.ndarray
    film_force: np.ndarray
    AH: np.ndarray
    pavehl: np.ndarray
    tau_film: np.ndarray
    eta_film: np.ndarray
    shear_rate: np.ndarray
    fc: float
    slip: float
    thermal: bool
    mean_temperature_rise: np.ndarray | None = None
    max_temperature_rise: np.ndarray | None = None
    thermal_converged: np.ndarray | None = None
    thermal_used: np.ndarray | None = None
    thermal_messages: list[str] = field(default_factory=list)
    film_limited: np.ndarray | None = None
    wall_s: float = math.nan

    @property
    def converged(self) -> bool:
        return bool(self.thermal_converged is None or np.all(self.thermal_converged))


def film_area(kind: str, area_nom: float, film_fraction: np.ndarray) -> np.ndarray:
    """``AH = Anom (Ph/P)^(1/2)`` (line, 4.36) or ``Anom (Ph/P)^(2/3)`` (point, 4.37) [m^2]."""
    expo = 0.5 if kind == "line" else 2.0 / 3.0
    return area_nom * np.asarray(film_fraction, dtype=float) ** expo


def isothermal_film_stress(
    lubricant: Lubricant, pressure: np.ndarray, temperature: float, sliding_speed: np.ndarray, h: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Eyring stress (4.33) with Roelands viscosity (4.34): ``(tau [Pa], eta [Pa s], gamma_dot [1/s])``.

    ``gamma_dot = sliding_speed/h``; ``eta = eta(pressure, temperature)``.
    """
    eta = np.asarray(lubricant.viscosity(np.asarray(pressure, dtype=float), temperature), dtype=float)
    gdot = np.abs(np.asarray(sliding_speed, dtype=float)) / np.asarray(h, dtype=float)
    tau = np.asarray(lubricant.eyring_stress(eta, gdot), dtype=float)
    return tau, eta, gdot


def mixed_friction(
    scene: Scene,
    sharing: LoadSharing,
    *,
    slip: float | None = None,
    fc: float | None = None,
    thermal: bool = False,
    thermal_options: dict[str, Any] | None = None,
    min_film_fraction: float = 1e-6,
    limit_film_to_boundary: bool = True,
    progress: Callable[[int], None] | None = None,
) -> MixedFriction:
    """Coefficient of friction (4.39) and its asperity and film parts for a solved load sharing.

    Parameters
    ----------
    scene : lubricant, oil temperature, contact kind.
    sharing : result of :func:`mixed.sharing.load_sharing`.
    slip : S = 2(u1 - u2)/(u1 + u2) (default ``scene.slip``); the sliding speed is ``|S| us/2``.
    fc : boundary friction coefficient (default ``roughness.fc``).
    thermal : film force from ``thermal.film_friction`` (chapter 5.4) instead of (4.33)-(4.37).
    thermal_options : extra keyword options passed to ``thermal.film_friction``.
    min_film_fraction : below this ``Ph/P`` the thermal solve is skipped (isothermal film term).
    limit_film_to_boundary : cap the film's shear stress at ``fc pavehl`` (its force at
        ``fc Ph``). A film sheared harder than the boundary layers would slip at them instead;
        without the cap a starved film of molecular thickness (hf,r << 1 nm) gives Eyring
        stresses above the boundary friction. Where the cap acts, ``film_limited`` is True.
    progress : called with 1 after each thermal point (for a progress bar).
    """
    t0 = time.perf_counter()
    slip = scene.slip if slip is None else require_range("slip", slip, -2.0, 2.0, "-")
    fc = sharing.roughness.fc if fc is None else require_range("fc", fc, 0.0, 1.0, "-")
    require_range("min_film_fraction", min_film_fraction, 0.0, 1.0, "-")
    P = sharing.load
    us = sharing.us
    frac = sharing.Ph / P
    AH = film_area(sharing.kind, sharing.area, frac)
    with np.errstate(divide="ignore", invalid="ignore"):
        pavehl = np.where(AH > 0, sharing.Ph / AH, 0.0)
    sliding = abs(slip) * us / 2.0
    tau, eta, gdot = isothermal_film_stress(scene.lubricant, pavehl, scene.T_oil, sliding, sharing.hfr)
    film_force = tau * AH
    out = MixedFriction(
        us=us, coefficient=np.empty_like(us), asperity=fc * sharing.Pa / P, film=np.empty_like(us),
        film_force=film_force, AH=AH, pavehl=pavehl, tau_film=tau, eta_film=eta, shear_rate=gdot,
        fc=fc, slip=slip, thermal=thermal,
    )
    if thermal:
        _thermal_film(scene, sharing, out, slip, thermal_options or {}, min_film_fraction, progress)
    out.film_limited = np.zeros(us.size, dtype=bool)
    if limit_film_to_boundary:
        cap = fc * sharing.Ph
        out.film_limited = out.film_force > cap
        out.film_force = np.where(out.film_limited, cap, out.film_force)
    out.film = out.film_force / P
    out.coefficient = out.asperity + out.film
    out.wall_s = time.perf_counter() - t0
    return out


def _thermal_film(
    scene: Scene,
    sharing: LoadSharing,
    out: MixedFriction,
    slip: float,
    options: dict[str, Any],
    min_film_fraction: float,
    progress: Callable[[int], None] | None,
) -> None:
    try:
        from thermal.film import film_frictions
    except (ImportError, AttributeError) as exc:
        raise InputError(
            f"thermal friction needs thermal.film.film_frictions, which is not available ({type(exc).__name__}: {exc})"
        ) from None
    n = out.us.size
    out.mean_temperature_rise = np.zeros(n)
    out.max_temperature_rise = np.zeros(n)
    out.thermal_converged = np.ones(n, dtype=bool)
    out.thermal_used = np.zeros(n, dtype=bool)
    out.eta_film = np.full(n, np.nan)
    P = sharing.load
    solve = (sharing.Ph > min_film_fraction * P) & (slip != 0.0)
    idx = np.flatnonzero(solve)
    if progress is not None:
        for _ in range(n - idx.size):
            progress(1)
    # all points' thermal film solves at once (threads over the line problems); each result is
    # the one of thermal.film_friction at that point
    results = film_frictions(
        scene, loads=[float(sharing.Ph[i]) for i in idx], hs=[float(sharing.hfr[i]) for i in idx],
        us=[float(out.us[i]) for i in idx], slip=abs(slip), thermal=True, pressure="hertz", **options,
    )
    for i, ff in zip(idx, results, strict=True):
        if isinstance(ff, ConvergenceError):
            out.thermal_converged[i] = False
            out.film_force[i] = math.nan
            out.tau_film[i] = math.nan
            out.mean_temperature_rise[i] = math.nan
            out.max_temperature_rise[i] = math.nan
            out.thermal_messages.append(f"us = {out.us[i]:.4g} m/s: {ff}")
        else:
            out.thermal_used[i] = True
            out.film_force[i] = abs(float(ff.force))
            out.tau_film[i] = abs(float(ff.mean_shear_stress))
            out.mean_temperature_rise[i] = float(ff.mean_temperature_rise)
            out.max_temperature_rise[i] = float(ff.max_temperature_rise)
            out.thermal_converged[i] = bool(ff.converged)
            if not ff.converged:
                out.thermal_messages.append(f"us = {out.us[i]:.4g} m/s: thermal solve not converged")
        if progress is not None:
            progress(1)
