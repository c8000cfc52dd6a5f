"""Critical load (thesis 4.3.1): where the EHL-ML transition stops moving to higher speeds.

The thesis observes that the EHL-ML transition shifts to higher sum velocities with increasing
load below a critical load (about 8800 N for the page-63 conditions) and to lower velocities
above it, and explains it by the relative stiffness of film and asperities: below the critical
load the film is stiffer than the asperities, above it the asperities are stiffer.

Here the critical load is computed from that defining behaviour: the load that maximises the
EHL-ML transition speed ``us_t(P)``, the sum velocity at which the asperities carry a given
small ``fraction`` of the load (solved exactly with the load-sharing model). At that load the
two stiffnesses balance: a small load increase thins the film (film compliance) exactly as much
as the asperities need to take up their share of the extra load (asperity stiffness), so the
asperity share at fixed speed does not change: ``d ln(Pa/P)/d ln P = 0`` at ``us_t``.
The result depends on the fraction that defines the transition; it is reported with it.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np
from scipy import optimize

from ehl_multigrid.model import hertz
from ehl_multigrid.model.errors import InputError, require_range
from ehl_multigrid.model.scene import Scene

from .gw import gw_f
from .sharing import load_sharing, require_gw_roughness
from .stribeck import transition_speed


@dataclass(frozen=True)
class CriticalLoad:
    """``load`` [N] maximising the EHL-ML transition speed ``us_transition`` [m/s] for the
    transition ``fraction``; ``pmax`` [Pa] there; ``hss_over_sigma_s`` and ``Lambda`` at the
    transition; ``asperity_log_stiffness = -d ln pa/d hss * sigma_s`` there;
    ``loads``/``speeds`` the scan (NaN where the fraction was not crossed); ``interior`` False
    when the maximum sits at a scan end (no critical load inside the scanned range)."""

    fraction: float
    load: float
    pmax: float
    us_transition: float
    hss_over_sigma_s: float
    Lambda: float
    asperity_log_stiffness: float
    interior: bool
    loads: tuple[float, ...]
    speeds: tuple[float, ...]

    def to_dict(self) -> dict:
        return asdict(self)


def _load_for_pmax(scene: Scene, pmax: float) -> float:
    if scene.kind == "line":
        return hertz.load_for_pmax_line(pmax, scene.length, scene.Rx, scene.E_reduced)
    return hertz.load_for_pmax_point(pmax, scene.Rx, scene.Ry, scene.E_reduced)


def critical_load(
    scene: Scene,
    *,
    fraction: float = 0.05,
    pmax_range: tuple[float, float] = (0.1e9, 4.0e9),
    n_scan: int = 25,
    rtol: float = 1e-4,
) -> CriticalLoad:
    """The critical load of ``scene``'s geometry, lubricant and roughness (see module text).

    Parameters
    ----------
    fraction : asperity load share ``Pa/P`` that defines the EHL-ML transition.
    pmax_range : scanned Hertzian pressures [Pa] (turned into loads).
    n_scan : log-spaced loads in the coarse scan, refined by bounded Brent around the maximum.
    rtol : relative tolerance on the load.
    """
    require_gw_roughness(scene.roughness)
    require_range("fraction", fraction, 0.0, 1.0, "-", lo_open=True, hi_open=True)
    lo_p = require_range("pmax_range[0]", pmax_range[0], 1e6, 2e10, "Pa")
    hi_p = require_range("pmax_range[1]", pmax_range[1], lo_p, 2e10, "Pa", lo_open=True)
    if not isinstance(n_scan, int) or n_scan < 5:
        raise InputError(f"n_scan = {n_scan!r} must be an integer >= 5")
    loads = np.geomspace(_load_for_pmax(scene, lo_p), _load_for_pmax(scene, hi_p), n_scan)
    speeds = np.array([transition_speed(scene, fraction, load=float(P)) for P in loads])
    if not np.any(np.isfinite(speeds)):
        raise InputError(f"the asperity share {fraction} is never crossed for loads {loads[0]:.4g}..{loads[-1]:.4g} N")
    k = int(np.nanargmax(speeds))
    interior = 0 < k < n_scan - 1
    best = float(loads[k])
    if interior:
        res = optimize.minimize_scalar(
            lambda lnP: -math.log(transition_speed(scene, fraction, load=math.exp(lnP))),
            bounds=(math.log(loads[k - 1]), math.log(loads[k + 1])), method="bounded",
            options={"xatol": rtol},
        )
        best = math.exp(float(res.x))
    us_t = transition_speed(scene, fraction, load=best)
    ls = load_sharing(scene, us_t, load=best)
    rough = ls.roughness
    lam = float(ls.hss[0] / rough.sigma_s)
    stiff = float(1.5 * gw_f(0.5, lam) / gw_f(1.5, lam))
    return CriticalLoad(
        fraction=fraction, load=best, pmax=ls.pmax, us_transition=us_t, hss_over_sigma_s=lam,
        Lambda=float(ls.Lambda[0]), asperity_log_stiffness=stiff, interior=interior,
        loads=tuple(float(x) for x in loads), speeds=tuple(float(x) for x in speeds),
    )
