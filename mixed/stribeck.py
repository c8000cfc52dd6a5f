"""Stribeck curves: friction, its parts, load shares, film and separation against sum velocity
(thesis 4.3-4.4, Figs 4.4-4.23; thermal 5.4, Figs 5.9-5.10; starved chapter 6, Figs 6.2-6.7).

The regime of each point follows from the share of the load carried by the asperities,
``Pa/P``: boundary (BL) when it is at least ``bl_fraction``, full film (EHL) when it is at most
``ehl_fraction``, mixed (ML) between. Both thresholds are options (scene ``[solver.mixed]`` or
keyword arguments); the transition speeds are solved for exactly, not read off the grid.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from scipy import optimize

from ehl_multigrid.model.convergence import ConvergenceReport
from ehl_multigrid.model.errors import InputError, reject_unknown_keys, require_range
from ehl_multigrid.model.results import Result
from ehl_multigrid.model.scene import Scene

from .film import johnson_film
from .friction import MixedFriction, mixed_friction
from .gw import plasticity_index
from .sharing import LoadSharing, contact_at_load, fitted_film, load_sharing, require_gw_roughness
from .starvation import hss_min

REGIME_NAMES = ("BL", "ML", "EHL")
DEFAULT_OPTIONS: dict[str, float] = {
    "bl_fraction": 0.95,       # Pa/P at or above: boundary lubrication
    "ehl_fraction": 0.05,      # Pa/P at or below: full-film EHL
    "min_film_fraction": 1e-6,  # Ph/P below which the thermal film solve is skipped
    "xtol": 1e-12,             # tolerance on ln(gamma1 - 1)
}
DEFAULT_US = (1e-3, 1e2, 60)


def stribeck_options(scene: Scene | None = None, **overrides: float | None) -> dict[str, float]:
    """Options from the defaults, then ``scene.solver['mixed']``, then keyword overrides."""
    opts = dict(DEFAULT_OPTIONS)
    if scene is not None:
        table = scene.solver.get("mixed", {})
        reject_unknown_keys("solver.mixed", table, set(DEFAULT_OPTIONS))
        opts.update(table)
    opts.update({k: v for k, v in overrides.items() if v is not None})
    reject_unknown_keys("stribeck options", opts, set(DEFAULT_OPTIONS))
    bl = require_range("bl_fraction", opts["bl_fraction"], 0.0, 1.0, "-", lo_open=True, hi_open=False)
    require_range("ehl_fraction", opts["ehl_fraction"], 0.0, bl, "-", lo_open=True, hi_open=True)
    require_range("min_film_fraction", opts["min_film_fraction"], 0.0, 1.0, "-")
    require_range("xtol", opts["xtol"], 1e-15, 1e-3, "-")
    return {k: float(v) for k, v in opts.items()}


def classify_regime(asperity_fraction: np.ndarray, bl_fraction: float, ehl_fraction: float) -> np.ndarray:
    """0 = BL (``Pa/P >= bl_fraction``), 2 = EHL (``Pa/P <= ehl_fraction``), 1 = ML otherwise."""
    f = np.asarray(asperity_fraction, dtype=float)
    return np.where(f >= bl_fraction, 0, np.where(f <= ehl_fraction, 2, 1)).astype(np.int8)


def default_us(scene: Scene, n: int | None = None, us_min: float | None = None, us_max: float | None = None) -> np.ndarray:
    """Sum velocities: ``scene.ranges['us']`` (or 1e-3..1e2 m/s, 60 points), log-spaced; ``n``,
    ``us_min``, ``us_max`` override the range's ends and count (``n = 1`` with equal ends: that
    one speed)."""
    rng = scene.ranges.get("us")
    if rng is not None and rng.explicit is None:
        lo, hi, cnt = rng.min, rng.max, rng.n
    elif rng is not None:
        vals = rng.values()
        lo, hi, cnt = float(vals.min()), float(vals.max()), vals.size
        if n is None and us_min is None and us_max is None:
            return np.sort(vals)
    else:
        lo, hi, cnt = DEFAULT_US
    lo = lo if us_min is None else require_range("us_min", us_min, 0.0, 1e3, "m/s", lo_open=True)
    hi = hi if us_max is None else require_range("us_max", us_max, 0.0, 1e3, "m/s", lo_open=True)
    cnt = cnt if n is None else n
    if not isinstance(cnt, (int, np.integer)) or isinstance(cnt, bool) or not 1 <= cnt <= 100000:
        raise InputError(f"n = {cnt!r} must be an integer in [1, 100000] (number of sum velocities)")
    if cnt == 1 and hi == lo:
        return np.array([lo])  # one speed: us_min = us_max
    if not hi > lo:
        raise InputError(f"us_max = {hi:.6g} m/s must exceed us_min = {lo:.6g} m/s (or equal it with n = 1)")
    return np.geomspace(lo, hi, int(cnt))


@dataclass
class StribeckCurve:
    """One Stribeck curve: load sharing, friction and regimes at the sum velocities ``us``.

    ``hoil`` [m] is the inlet film (inf = flooded); ``transitions`` holds the sum velocities
    [m/s] where ``Pa/P`` crosses ``bl_fraction`` (``us_bl_ml``) and ``ehl_fraction``
    (``us_ml_ehl``), NaN when not crossed in 1e-9..1e5 m/s.
    """

    scene: Scene
    sharing: LoadSharing
    friction: MixedFriction
    regime: np.ndarray
    hoil: float
    options: dict[str, float]
    transitions: dict[str, float] = field(default_factory=dict)
    wall_s: float = math.nan

    @property
    def us(self) -> np.ndarray:
        return self.sharing.us

    @property
    def converged(self) -> bool:
        return bool(self.sharing.report.converged and self.friction.converged)

    def regime_names(self) -> list[str]:
        return [REGIME_NAMES[int(r)] for r in self.regime]


def transition_speed(
    scene: Scene,
    fraction: float,
    *,
    load: float | None = None,
    hoil: float | None = None,
    us_bounds: tuple[float, float] = (1e-9, 1e5),
    film_factor: float = 1.0,
) -> float:
    """Sum velocity [m/s] at which the asperities carry ``fraction`` of the load.

    At the transition the load sharing is known (``gamma2 = 1/fraction``), so GW (4.29) gives
    ``hss``, Johnson's definition (4.27) the film it needs, and the speed is the root in
    ``ln us`` of "fitted (starved) film at that gamma1 = required film"; the fitted film grows
    monotonically with speed. NaN if the root is outside ``us_bounds`` (e.g. a starved
    contact whose film is capped below the required one by its inlet supply). ``film_factor``
    as in :func:`~mixed.sharing.load_sharing`.
    """
    require_range("fraction", fraction, 0.0, 1.0, "-", lo_open=True, hi_open=True)
    rough = require_gw_roughness(scene.roughness)
    P = scene.load if load is None else require_range("load", load, 0.0, math.inf, "N", lo_open=True)
    contact = contact_at_load(scene, P)
    hss = hss_min(fraction * P, contact.area, rough.n, rough.beta, rough.sigma_s, scene.E_reduced)
    target = math.log(johnson_film(hss + rough.dd, rough.Rq))
    gamma1 = 1.0 / (1.0 - fraction)

    def g(lnu: float) -> float:
        return math.log(fitted_film(scene, math.exp(lnu), gamma1, load=P, hoil=hoil, film_factor=film_factor)) - target

    a, b = math.log(us_bounds[0]), math.log(us_bounds[1])
    if not (g(a) < 0.0 < g(b)):
        return math.nan
    return math.exp(optimize.brentq(g, a, b, xtol=1e-13, rtol=1e-13))


def stribeck_curve(
    scene: Scene,
    us: np.ndarray | None = None,
    *,
    load: float | None = None,
    slip: float | None = None,
    hoil: float | None = None,
    thermal: bool = False,
    thermal_options: dict[str, Any] | None = None,
    options: dict[str, float] | None = None,
    transitions: bool = True,
    progress: Callable[[int], None] | None = None,
    film_factor: float = 1.0,
) -> StribeckCurve:
    """Stribeck curve of ``scene`` at sum velocities ``us`` (default :func:`default_us`).

    ``hoil`` [m] starves the inlet (chapter 6; default ``scene.supply.hoil``); ``thermal`` takes
    the film stress from the thermal solver (chapter 5.4). ``options`` as
    :func:`stribeck_options` returns them. ``film_factor`` multiplies the fitted film at every
    speed (``hc_solved/hc_fit``: the fit calibrated on an EHL solution; default 1).
    """
    t0 = time.perf_counter()
    require_gw_roughness(scene.roughness)
    opts = options if options is not None else stribeck_options(scene)
    us_arr = default_us(scene) if us is None else np.asarray(us, dtype=float)
    ls = load_sharing(scene, us_arr, load=load, hoil=hoil, xtol=opts["xtol"], film_factor=film_factor)
    fr = mixed_friction(scene, ls, slip=slip, thermal=thermal, thermal_options=thermal_options,
                        min_film_fraction=opts["min_film_fraction"], progress=progress)
    reg = classify_regime(ls.asperity_fraction, opts["bl_fraction"], opts["ehl_fraction"])
    curve = StribeckCurve(scene, ls, fr, reg, ls.hoil, opts)
    if transitions:
        curve.transitions = {
            "us_bl_ml": transition_speed(scene, opts["bl_fraction"], load=load, hoil=hoil, film_factor=film_factor),
            "us_ml_ehl": transition_speed(scene, opts["ehl_fraction"], load=load, hoil=hoil, film_factor=film_factor),
        }
    curve.wall_s = time.perf_counter() - t0
    return curve


# -- result ------------------------------------------------------------------------------------
_FIELDS: tuple[tuple[str, str, str, str], ...] = (
    # name, source attribute path, units, long name
    ("friction_coefficient", "friction.coefficient", "-", "coefficient of friction (4.39)"),
    ("friction_asperity", "friction.asperity", "-", "asperity part fc Pa/P"),
    ("friction_film", "friction.film", "-", "film part tau_H AH/P"),
    ("film_force", "friction.film_force", "N", "film shear force"),
    ("Pa", "sharing.Pa", "N", "load on the asperities"),
    ("Ph", "sharing.Ph", "N", "load on the film"),
    ("gamma1", "sharing.gamma1", "-", "P/Ph"),
    ("gamma2", "sharing.gamma2", "-", "P/Pa"),
    ("hfr", "sharing.hfr", "m", "film thickness hf,r (4.20)"),
    ("hs", "sharing.hs", "m", "separation of the mean height plane"),
    ("hss", "sharing.hss", "m", "separation of the mean summit plane (4.28)"),
    ("Lambda", "sharing.Lambda", "-", "hf,r / Rq"),
    ("hc_fit", "sharing.hc_fit", "m", "flooded fitted film at gamma1 times film_factor (before starvation)"),
    ("delta_used", "sharing.delta_used", "-", "Chevalier's exponent of (6.1) at each point (NaN: boundary)"),
    ("AH", "friction.AH", "m^2", "film area (4.36)/(4.37)"),
    ("pavehl", "friction.pavehl", "Pa", "mean film pressure Ph/AH (4.35)"),
    ("tau_film", "friction.tau_film", "Pa", "mean film shear stress"),
    ("shear_rate", "friction.shear_rate", "1/s", "|u1 - u2| / hf,r"),
    ("eta_film", "friction.eta_film", "Pa s", "Roelands viscosity at pavehl (isothermal)"),
)


def _get(curve: StribeckCurve, path: str) -> np.ndarray:
    obj: Any = curve
    for part in path.split("."):
        obj = getattr(obj, part)
    return np.asarray(obj, dtype=float)


def stribeck_result(scene: Scene, curves: list[StribeckCurve], *, thermal: bool, wall_s: float | None = None) -> Result:
    """A core :class:`Result` of kind ``stribeck``: fields on ``(case, us)``, one case per inlet
    film (case 0 is the first curve given, normally the flooded one)."""
    if not curves:
        raise InputError("stribeck_result needs at least one curve")
    us = curves[0].us
    for c in curves[1:]:
        if c.us.shape != us.shape or not np.allclose(c.us, us):
            raise InputError("all curves of one stribeck result must share the same sum velocities")
    r = Result("stribeck", scene)
    r.add_coord("us", us, "m/s", "sum velocity u1 + u2")
    r.add_coord("case", np.arange(len(curves)), "-", "curve index (inlet film case)")
    dims = ("case", "us")
    for name, path, units, long in _FIELDS:
        r.add_field(name, np.stack([_get(c, path) for c in curves]), units, dims, long)
    r.add_field("asperity_fraction", np.stack([c.sharing.asperity_fraction for c in curves]), "-", dims, "Pa/P")
    r.add_field("regime", np.stack([c.regime for c in curves]).astype(np.int8), "-", dims, "0 BL, 1 ML, 2 EHL")
    r.add_field("boundary_guard", np.stack([c.sharing.boundary for c in curves]).astype(np.int8), "-", dims,
                "1 where the starved film is below hs_min (all load on the asperities)")
    r.add_field("film_limited", np.stack([c.friction.film_limited for c in curves]).astype(np.int8), "-", dims,
                "1 where the film shear stress was capped at fc pavehl (molecularly thin film)")
    sigma = curves[0].sharing.roughness.Rq
    hoil = np.array([c.hoil for c in curves])
    r.add_field("hoil", hoil, "m", ("case",), "inlet oil film (inf = flooded)")
    r.add_field("hoil_over_sigma", hoil / sigma, "-", ("case",), "hoil / Rq")
    for key in ("us_bl_ml", "us_ml_ehl"):
        r.add_field(key, np.array([c.transitions.get(key, math.nan) for c in curves]), "m/s", ("case",),
                    f"transition speed ({key})")
    if thermal:
        for name in ("mean_temperature_rise", "max_temperature_rise"):
            r.add_field(name, np.stack([_get(c, f"friction.{name}") for c in curves]), "K", dims, name.replace("_", " "))
        r.add_field("thermal_converged", np.stack([c.friction.thermal_converged for c in curves]).astype(np.int8), "-", dims,
                    "1 where the thermal film solve converged")
    c0 = curves[0]
    rough = c0.sharing.roughness
    r.set_scalar("load", c0.sharing.load, "N")
    r.set_scalar("pmax", c0.sharing.pmax, "Pa")
    r.set_scalar("area", c0.sharing.area, "m^2")
    r.set_scalar("hs_min", c0.sharing.hs_min, "m")
    r.set_scalar("slip", c0.friction.slip, "-")
    r.set_scalar("fc", c0.friction.fc, "-")
    r.set_scalar("Rq", rough.Rq, "m")
    r.set_scalar("sigma_s", rough.sigma_s, "m")
    r.set_scalar("dd", rough.dd, "m")
    r.set_scalar("plasticity_index", plasticity_index(scene.E_reduced, rough.hardness, rough.sigma_s, rough.beta), "-")
    r.set_scalar("thermal", bool(thermal), "-")
    r.set_scalar("film_factor", float(c0.sharing.film_factor), "-")
    for k, v in c0.options.items():
        r.set_scalar(k, v, "-")
    converged = all(c.converged for c in curves)
    msgs = [m for c in curves for m in c.friction.thermal_messages]
    report = ConvergenceReport(
        converged=converged,
        message="all load-sharing points bracketed and solved" + ("; thermal film solves converged" if thermal and converged else "")
        + ("" if converged else f"; {len(msgs)} thermal point(s) not converged: " + " | ".join(msgs[:5])),
        iterations=max(c.sharing.report.iterations for c in curves),
        residual_history=c0.sharing.report.residual_history,
        tolerances={"xtol": c0.options["xtol"]},
        wall_s=float(sum(c.wall_s for c in curves) if wall_s is None else wall_s),
    )
    r.add_report(report)
    r.meta["regime_codes"] = {"0": "BL", "1": "ML", "2": "EHL"}
    r.meta["model"] = "Liu (2002) ch. 4 (GW + Moes/Nijenbanning mixed fits), 5.4 (thermal film), 6 (Chevalier starvation)"
    return r


def save_partial(path: Path, scene: Scene, curves: list[StribeckCurve], thermal: bool) -> None:
    """Write the finished curves so far (interrupted runs keep their work)."""
    stribeck_result(scene, curves, thermal=thermal).save(path)


def stribeck_cases(
    scene: Scene,
    us: np.ndarray | None = None,
    *,
    hoil_over_sigma: Any = (),
    thermal: bool = False,
    thermal_options: dict[str, Any] | None = None,
    options: dict[str, float] | None = None,
    load: float | None = None,
    slip: float | None = None,
    save_path: Path | None = None,
    progress: Callable[[int], None] | None = None,
    film_factor: float = 1.0,
) -> list[StribeckCurve]:
    """The scene's own supply (flooded unless ``scene.supply.hoil`` is finite) followed by one
    starved curve per ``hoil/Rq`` value (chapter 6). With ``save_path`` the HDF5 result is
    rewritten after every finished curve, so an interrupted run keeps its finished curves.
    ``film_factor`` as in :func:`stribeck_curve`."""
    rough = require_gw_roughness(scene.roughness)
    opts = options if options is not None else stribeck_options(scene)
    us_arr = default_us(scene) if us is None else np.asarray(us, dtype=float)
    hoils = [scene.supply.hoil]
    for i, v in enumerate(hoil_over_sigma):
        hoils.append(require_range(f"hoil_over_sigma[{i}]", v, 0.0, math.inf, "-", lo_open=True) * rough.Rq)
    curves: list[StribeckCurve] = []
    for h in hoils:
        curves.append(stribeck_curve(scene, us_arr, load=load, slip=slip, hoil=h, thermal=thermal,
                                     thermal_options=thermal_options, options=opts, progress=progress,
                                     film_factor=film_factor))
        if save_path is not None:
            save_partial(Path(save_path), scene, curves, thermal)
        if progress is not None and not thermal:
            progress(1)  # thermal runs report per point instead
    return curves
