"""Load sharing between the asperities and the film (thesis 4.2.3-4.2.4, (4.21)-(4.29); ch. 6).

For each sum velocity the unknown is the fluid load-sharing factor ``gamma1 = P/Ph``
(``1/gamma1 + 1/gamma2 = 1``, ``gamma2 = P/Pa``). Given ``gamma1``:

1. the film ``hf,r`` is the mixed form of the Moes (line, (4.23)-(4.24)) or Nijenbanning
   (point/elliptic, (4.25)-(4.26)) fit, ``hf,r = Hc(M, L, gamma1) R sqrt(eta0 us/(E' R))``,
   times a ``film_factor`` (1, or ``hc_solved/hc_fit`` when an EHL solution of the smooth
   contact replaces the fit), reduced by Chevalier's starvation formula (6.4) when an inlet
   film ``hoil`` is given;
2. the separation follows from Johnson's film definition (4.27) inverted, ``hss = hs - dd`` (4.28);
3. Greenwood-Williamson gives the asperity load ``Anom pa(hss)`` (4.18, 4.29).

The residual ``ln(Anom pa(hss)/P) - ln(1/gamma2)`` decreases monotonically in ``gamma1`` (a
larger gamma1 thickens the fitted film and lowers the asperity pressure, while it raises the
share the asperities must carry), so it is bracketed and solved in ``x = ln(gamma1 - 1)``.
``gamma1 - 1 = e^x`` and ``gamma2 - 1 = e^-x`` keep both limits exact in floating point:
``x -> -inf`` is full-film EHL, ``x -> +inf`` boundary lubrication. With starvation the residual
can stay positive as ``gamma1 -> inf``: the supplied oil cannot hold the surfaces apart beyond
``hs_min`` (all load on the asperities, Fig. 6.1), and the point is returned as boundary
lubrication with ``hs = hs_min``.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ehl_multigrid.model import fits, hertz
from ehl_multigrid.model.convergence import ConvergenceReport, check_finite
from ehl_multigrid.model.errors import ConvergenceError, InputError, require_positive, require_range
from ehl_multigrid.model.scene import Roughness, Scene

from .film import johnson_film, separation_from_log_film
from .gw import asperity_pressure_coefficient, gw_log_f
from .roots import bracketed_root
from .starvation import (
    INLET,
    density_ratio_at,
    hss_min,
    inlet_delta,
    log_starved_film,
    require_delta,
)

X_LO = -60.0  # gamma1 - 1 = 1e-26: the film carries everything to double precision
X_HI = 80.0   # gamma1 = 5.5e34: the film carries nothing to double precision


@dataclass
class LoadSharing:
    """Solution of (4.21)-(4.29) at a set of sum velocities (SI units, arrays over ``us``).

    ``hfr`` [m] film (4.20/4.27), ``hs``/``hss`` [m] separations (4.28), ``Lambda = hfr/Rq``;
    ``Pa``/``Ph`` [N] asperity and film loads; ``gamma1 = P/Ph``, ``gamma2 = P/Pa``;
    ``hc_fit`` [m] the flooded fit at the solved gamma1 (before starvation);
    ``boundary`` marks points where the starved film is below ``hs_min`` (all load on the
    asperities, gamma1 = inf); ``film_factor`` multiplies the fitted film (``hc_fit`` includes it).
    """

    kind: str
    load: float
    us: np.ndarray
    Pa: np.ndarray
    Ph: np.ndarray
    gamma1: np.ndarray
    gamma2: np.ndarray
    hfr: np.ndarray
    hs: np.ndarray
    hss: np.ndarray
    Lambda: np.ndarray
    hc_fit: np.ndarray
    boundary: np.ndarray
    pmax: float
    area: float
    hs_min: float
    hoil: float
    delta: float | str
    roughness: Roughness
    report: ConvergenceReport = field(repr=False, default=None)  # type: ignore[assignment]
    film_factor: float = 1.0
    #: Chevalier's exponent at each point (NaN where the asperities carry all the load, and
    #: everywhere for a flooded inlet)
    delta_used: np.ndarray = field(repr=False, default=None)  # type: ignore[assignment]

    @property
    def asperity_fraction(self) -> np.ndarray:
        """``Pa/P = 1/gamma2``."""
        return self.Pa / self.load

    @property
    def film_fraction(self) -> np.ndarray:
        """``Ph/P = 1/gamma1``."""
        return self.Ph / self.load


def require_film_factor(film_factor: float) -> float:
    """The film calibration factor, checked: finite, in (0.01, 100]."""
    return require_range("film_factor", film_factor, 0.01, 100.0, "-", lo_open=True)


def require_gw_roughness(rough: Roughness | None, where: str = "scene") -> Roughness:
    """The roughness, checked to have the summit parameters GW needs."""
    if rough is None:
        raise InputError(f"{where} has no [roughness] table; mixed lubrication needs Rq, n, beta (sigma_s, dd default to 0.7 Rq, 0.82 Rq)")
    for name, units in (("n", "1/m^2"), ("beta", "m")):
        v = getattr(rough, name)
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise InputError(f"roughness.{name} = {v!r} {units} is required (> 0) for the Greenwood-Williamson model")
    return rough


def contact_at_load(scene: Scene, load: float) -> hertz.HertzContact:
    """Hertz contact of the scene's geometry at another load."""
    return scene.hertz if load == scene.load else scene.hertz_at(load)


def _us_array(us: float | np.ndarray | None, scene: Scene) -> np.ndarray:
    arr = np.atleast_1d(np.asarray(scene.us if us is None else us, dtype=float)).ravel()
    if arr.size == 0:
        raise InputError("us: empty list of sum velocities")
    bad = ~np.isfinite(arr) | ~(arr > 0)
    if bad.any():
        raise InputError(f"us = {arr[bad][:3]} m/s must be finite and > 0 (sum velocity)")
    return arr


class _Problem:
    """The load-sharing residual for a set of sum velocities (arrays indexed by point)."""

    def __init__(self, scene: Scene, us: np.ndarray, load: float, rough: Roughness, hoil: float, delta: float,
                 film_factor: float = 1.0) -> None:
        self.kind = scene.kind
        self.load = load
        self.rough = rough
        self.hoil = hoil
        self.delta = delta
        self.contact = contact_at_load(scene, load)
        # ln(hc) [m] -> ln(Hc_ff) in Venner units (h Rx/a^2) for delta = "inlet"
        self.log_venner = math.log(scene.Rx / self.contact.a**2)
        self.theta = 1.0 if scene.kind == "line" else scene.theta
        ML = np.array([scene.moes(float(u), load) for u in us])
        self.M, self.L = ML[:, 0], ML[:, 1]
        self.log_scale = np.log([scene.film_scale(float(u)) for u in us]) + math.log(film_factor)
        self.rho_bar = density_ratio_at(self.contact.pmax)
        c = asperity_pressure_coefficient(rough.n, rough.beta, rough.sigma_s, scene.E_reduced)
        self.log_a0 = math.log(c) + math.log(self.contact.area / load)
        self.coef = c

    def state(self, x: np.ndarray, idx: np.ndarray) -> dict[str, np.ndarray]:
        g1 = 1.0 + np.exp(x)
        Hc = np.asarray(fits.central_film_fit(self.kind, self.M[idx], self.L[idx], self.theta, g1), dtype=float)
        log_hc = np.log(Hc) + self.log_scale[idx]
        log_h = log_starved_film(log_hc, self.hoil, self.rho_bar, self.delta_at(log_hc))
        r = self.rough
        hs = np.asarray(separation_from_log_film(log_h - math.log(r.Rq), r.Rq), dtype=float)
        hss = hs - r.dd
        log_a = self.log_a0 + np.asarray(gw_log_f(1.5, hss / r.sigma_s), dtype=float)
        # ln(1/gamma2) = ln(expit(x)) = -ln(1 + e^-x)
        resid = log_a + np.logaddexp(0.0, -x)
        return {"x": x, "Hc": Hc, "log_hc": log_hc, "log_h": log_h, "hs": hs, "hss": hss, "resid": resid}

    def residual(self, x: np.ndarray, idx: np.ndarray) -> np.ndarray:
        return self.state(x, idx)["resid"]

    def delta_at(self, log_hc: np.ndarray) -> float | np.ndarray:
        """Chevalier's exponent at flooded films ``exp(log_hc)`` [m] (a number, or per point)."""
        return exponent_at(self.kind, self.delta, log_hc, self.log_venner, self.hoil, self.theta)


def exponent_at(kind: str, delta: float | str, log_hc: np.ndarray, log_venner: float,
                hoil: float, theta: float = 1.0) -> float | np.ndarray:
    """``delta`` itself, or for ``"inlet"`` :func:`~mixed.starvation.inlet_delta` of the flooded
    film ``exp(log_hc)`` [m] in Venner units (``log_venner = ln(Rx/a^2)``); NaN for a flooded
    inlet (``hoil = inf``), where no exponent applies."""
    if math.isinf(hoil):
        return math.nan
    if delta == INLET:
        return inlet_delta(kind, np.exp(np.asarray(log_hc, dtype=float) + log_venner), theta)
    return delta


def fitted_film(
    scene: Scene,
    us: float,
    gamma1: float,
    *,
    load: float | None = None,
    hoil: float | None = None,
    delta: float | None = None,
    film_factor: float = 1.0,
) -> float:
    """Film ``hf,r`` [m] of the mixed fit (4.23)/(4.25) at a given ``gamma1``, times
    ``film_factor``, starved by (6.4) when ``hoil`` is finite (defaults from the scene's supply)."""
    P = scene.load if load is None else load
    hoil = scene.supply.hoil if hoil is None else hoil
    delta = scene.supply.delta if delta is None else require_delta("delta", delta)
    M, L = scene.moes(us, P)
    theta = 1.0 if scene.kind == "line" else scene.theta
    Hc = float(fits.central_film_fit(scene.kind, M, L, theta, gamma1))
    log_hc = np.array([math.log(Hc * scene.film_scale(us) * require_film_factor(film_factor))])
    contact = contact_at_load(scene, P)
    d = exponent_at(scene.kind, delta, log_hc, math.log(scene.Rx / contact.a**2), hoil,
                    1.0 if scene.kind == "line" else scene.theta)
    rho_bar = density_ratio_at(contact.pmax)
    return float(np.exp(log_starved_film(log_hc, hoil, rho_bar, d))[0])


def load_sharing(
    scene: Scene,
    us: float | np.ndarray | None = None,
    *,
    load: float | None = None,
    roughness: Roughness | None = None,
    hoil: float | None = None,
    delta: float | None = None,
    xtol: float = 1e-12,
    film_factor: float = 1.0,
) -> LoadSharing:
    """Solve the mixed-lubrication load sharing (4.21)-(4.29) at the sum velocities ``us``.

    Parameters
    ----------
    scene : contact, lubricant (``eta0``, ``alpha`` at ``T_oil`` enter the fits) and roughness.
    us : sum velocities [m/s] (default ``scene.us``).
    load : normal load [N] (default ``scene.load``).
    roughness : overrides ``scene.roughness`` (needs Rq, sigma_s, dd, n, beta).
    hoil : inlet oil film [m] for Chevalier's starvation (6.4); ``inf`` is flooded
        (default ``scene.supply.hoil``).
    delta : Chevalier exponent (default ``scene.supply.delta``, 3.5), or ``"inlet"``: at each speed
        from the flooded inlet (:func:`~mixed.starvation.inlet_delta`); ``LoadSharing.delta_used``
        holds the exponent of every point.
    xtol : absolute tolerance on ``ln(gamma1 - 1)``.
    film_factor : multiplies the fitted film at every speed: ``hc_solved/hc_fit`` of an EHL
        solution of the smooth contact at the operating point calibrates the fit on it
        (default 1, the fit itself).

    Returns
    -------
    LoadSharing, with a :class:`ConvergenceReport` (every point bracketed and converged).

    Raises
    ------
    InputError for bad input; ConvergenceError if a point cannot be bracketed or solved.
    """
    t0 = time.perf_counter()
    rough = require_gw_roughness(roughness if roughness is not None else scene.roughness)
    us_arr = _us_array(us, scene)
    P = require_positive("load", scene.load if load is None else load, "N")
    hoil = scene.supply.hoil if hoil is None else require_range("hoil", hoil, 0.0, math.inf, "m", lo_open=True)
    delta = scene.supply.delta if delta is None else require_delta("delta", delta)
    require_range("xtol", xtol, 1e-15, 1e-3, "-")
    prob = _Problem(scene, us_arr, P, rough, hoil, delta, require_film_factor(film_factor))
    n = us_arr.size
    idx = np.arange(n)

    hi = np.full(n, X_HI)
    f_hi = prob.residual(hi, idx)
    boundary = f_hi > 0.0
    lo = np.full(n, X_LO)
    f_lo = prob.residual(lo, idx)
    # full film to double precision: the root lies near ln(asperity share at gamma1 = 1)
    deep = f_lo < 0.0
    if deep.any():
        lo = np.where(deep, f_lo + X_LO - 5.0, lo)  # f_lo + X_LO ~ ln a0 (x-independent there)
        f_lo = np.where(deep, prob.residual(lo, idx), f_lo)
    if np.any(f_lo < 0.0):
        bad = np.flatnonzero(f_lo < 0.0)
        raise ConvergenceError(
            f"load sharing: no bracket at us = {us_arr[bad][:3]} m/s (residual {f_lo[bad][:3]} at the full-film end)",
            None, "report this case: the asperity load should vanish as gamma1 -> 1",
        )
    solve = np.flatnonzero(~boundary)
    x = np.full(n, np.inf)
    iterations = 0
    res_hist: list[float] = []
    width_hist: list[float] = []
    if solve.size:
        def func(xx: np.ndarray, sub: np.ndarray) -> np.ndarray:
            return prob.residual(xx, solve[sub])

        br = bracketed_root(func, lo[solve], hi[solve], f_lo[solve], f_hi[solve], xtol=xtol, maxiter=300)
        if not np.all(br.converged):
            report = ConvergenceReport(False, "load sharing: bracket did not close", br.iterations,
                                       np.asarray(br.residual_history), tolerances={"xtol": xtol})
            raise ConvergenceError(
                f"load sharing did not converge at us = {us_arr[solve][~br.converged][:3]} m/s",
                report, "loosen xtol or report the case",
            )
        x[solve] = br.x
        iterations = br.iterations
        res_hist = br.residual_history
        width_hist = br.width_history

    Pa = np.empty(n)
    Ph = np.empty(n)
    g1 = np.empty(n)
    g2 = np.empty(n)
    hs = np.empty(n)
    hc_fit = np.full(n, np.nan)
    hfr = np.empty(n)
    delta_used = np.full(n, np.nan)
    hs_lim = hss_min(P, prob.contact.area, rough.n, rough.beta, rough.sigma_s, scene.E_reduced) + rough.dd
    if solve.size:
        st = prob.state(x[solve], solve)
        xs = x[solve]
        # exp(-x) overflows to inf at deep full-film points: gamma2 = inf, Pa = 0 are exact
        with np.errstate(over="ignore"):
            Pa[solve] = P / (1.0 + np.exp(-xs))
            Ph[solve] = P / (1.0 + np.exp(xs))
            g1[solve] = 1.0 + np.exp(xs)
            g2[solve] = 1.0 + np.exp(-xs)
        hs[solve] = st["hs"]
        hfr[solve] = np.exp(st["log_h"])
        hc_fit[solve] = np.exp(st["log_hc"])
        delta_used[solve] = prob.delta_at(st["log_hc"])
        final_resid = float(np.max(np.abs(st["resid"])))
    else:
        final_resid = 0.0
    b = np.flatnonzero(boundary)
    if b.size:
        Pa[b], Ph[b], g1[b], g2[b] = P, 0.0, np.inf, 1.0
        hs[b] = hs_lim
        hfr[b] = johnson_film(hs_lim, rough.Rq)
    hss = hs - rough.dd
    for name, arr in (("Pa", Pa), ("hfr", hfr), ("hs", hs)):
        check_finite(f"load sharing {name}", arr, None, "report this case")
    report = ConvergenceReport(
        converged=True,
        message=f"{solve.size} point(s) bracketed and solved in ln(gamma1 - 1); {b.size} in boundary lubrication (starved, hs < hs_min)",
        iterations=iterations,
        residual_history=np.asarray(res_hist + [final_resid], dtype=float),
        tolerances={"xtol": xtol},
        wall_s=time.perf_counter() - t0,
        extra={"bracket_width": np.asarray(width_hist, dtype=float)},
    )
    return LoadSharing(
        kind=scene.kind, load=P, us=us_arr, Pa=Pa, Ph=Ph, gamma1=g1, gamma2=g2, hfr=hfr, hs=hs,
        hss=hss, Lambda=hfr / rough.Rq, hc_fit=hc_fit, boundary=boundary, pmax=prob.contact.pmax,
        area=prob.contact.area, hs_min=hs_lim, hoil=hoil, delta=delta, roughness=rough, report=report,
        film_factor=float(film_factor), delta_used=delta_used,
    )
