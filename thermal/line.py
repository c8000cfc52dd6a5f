"""Thermal non-linear Roelands-Eyring model on one line profile (thesis 3.2: constitutive law
(3.3), momentum (3.4), energy (3.5), surface temperatures (3.6)-(3.7), mapping (3.14)-(3.17)).

:func:`solve_thermal_line` runs the compiled march (kernels.py) for a :class:`LineProfile` and returns
the fields, the friction per unit length, the heat budget and a convergence report.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ehl_multigrid.model.convergence import ConvergenceReport
from ehl_multigrid.model.errors import ConvergenceError, InputError, require_range
from ehl_multigrid.model.lubricant import T_MAX_C, T_MIN_C, Lubricant
from ehl_multigrid.model.solids import Solid

from . import kernels
from .kernels import T_KELVIN
from .options import ThermalOptions
from .profiles import LineProfile
from .properties import T_ROELANDS_MIN, oil_params
from .surface import wall_weights

#: Anderson mixing depth of the sweep iteration (Walker & Ni 2011): for a slow or stationary
#: surface the plain sweep iteration is barely contractive; mixing makes it converge in a few sweeps
ANDERSON_DEPTH = 6

#: at most this many symmetric passes over a reverse-flow zone per sweep (kernels._zone_relax),
#: and FIRST_ZONE_PASSES in the first sweep, whose zone coefficients the second sweep still
#: changes, so relaxing them further would be redone there (docs/thermal.md)
ZONE_PASSES = 30
FIRST_ZONE_PASSES = 2
#: the zone passes stop when they change the temperature by less than ZONE_TOL * tol_T
#: (the sweep tolerance: the zone is an inner solve of the sweep)
ZONE_TOL = 1.0


@dataclass(frozen=True)
class Surroundings:
    """What the film sees besides its own profile: oil, solids, speeds and temperatures.

    u1, u2 : speeds of surface 1 (Z = 0) and surface 2 (Z = 1) [m/s], both >= 0;
    T_oil : inlet oil temperature [degC]; T_surface1, T_surface2 : bulk temperatures [degC].
    """

    lubricant: Lubricant
    body1: Solid
    body2: Solid
    u1: float
    u2: float
    T_oil: float
    T_surface1: float
    T_surface2: float

    def __post_init__(self) -> None:
        require_range("u1", self.u1, 0.0, 1e3, "m/s")
        require_range("u2", self.u2, 0.0, 1e3, "m/s")
        if not self.u1 + self.u2 > 0:
            raise InputError("u1 + u2 = 0 m/s: the thermal model needs a positive sum velocity")
        for name in ("T_oil", "T_surface1", "T_surface2"):
            require_range(name, getattr(self, name), T_MIN_C, T_MAX_C, "degC")


@dataclass
class ThermalLineSolution:
    """Fields of one line profile; arrays are (station, Z node).

    force_per_length : friction force per unit length of line [N/m], ``-int tau_mean dx``,
        positive when surface 1 is faster (it opposes surface 1's motion);
    traction1/2_per_length : shear force of the film on surface 1 / 2 along +x [N/m];
    stress_slope : ``G = dtau/dZ = h dp/dx`` per station [Pa] (zero without the pressure term;
        with ``momentum='flux'`` the slope that carries the EHL solution's pressure-driven flux);
    heat : dict of the heat budget per unit length [W/m]: shear, compression (the compressive
        heating integrated; 0 when it is off), conduction1, conduction2, convection (the (3.5)
        convection term integrated), enthalpy_flux (outlet minus inlet of rho Cp u T h, for
        reference), balance (relative residual of shear + compression - conduction -
        convection, over the shear heat).
    """

    profile: LineProfile
    Z: np.ndarray
    T: np.ndarray
    tau: np.ndarray
    u: np.ndarray
    gdot: np.ndarray
    heat_rate: np.ndarray
    q1: np.ndarray
    q2: np.ndarray
    force_per_length: float
    traction1_per_length: float
    traction2_per_length: float
    report: ConvergenceReport
    T_oil: float
    stress_slope: np.ndarray | None = None
    extra: dict = field(default_factory=dict)
    #: oil of the heat budget (None: isothermal solution, empty budget)
    lubricant: Lubricant | None = field(default=None, repr=False)
    #: the energy equation carried the compressive heating (ThermalOptions.compressive_heating)
    compressive_heating: bool = False
    _heat: dict[str, float] | None = field(default=None, repr=False)

    @property
    def heat(self) -> dict[str, float]:
        """Heat budget per unit length [W/m] (:func:`heat_budget`; computed on first use,
        empty for an isothermal solution)."""
        if self._heat is None:
            self._heat = ({} if self.lubricant is None else
                          heat_budget(self.profile, self.T, self.u, self.heat_rate, self.q1, self.q2, self.lubricant,
                                      compression=self.compressive_heating))
        return self._heat

    @property
    def T_surface1(self) -> np.ndarray:
        return self.T[:, 0]

    @property
    def T_surface2(self) -> np.ndarray:
        return self.T[:, -1]

    @property
    def tau_mean(self) -> np.ndarray:
        """Film-mean (= mid-film, tau is linear in Z) shear stress per station [Pa]."""
        return _zmean(self.tau)

    def max_temperature_rise(self) -> float:
        return float(np.max(self.T) - self.T_oil)

    def mean_temperature_rise(self) -> float:
        """Film-mean temperature rise averaged over the Hertz contact of this line [K]."""
        m = self.profile.contact_mask
        if m.sum() < 2:
            return 0.0
        X = self.profile.X[m]
        Tm = _zmean(self.T)[m]
        return float(np.trapezoid(Tm, X) / (X[-1] - X[0]) - self.T_oil)


def _zmean(a: np.ndarray) -> np.ndarray:
    return np.trapezoid(a, dx=1.0 / (a.shape[1] - 1), axis=1)


def solve_thermal_line(profile: LineProfile, env: Surroundings, options: ThermalOptions,
                       kernel_length: float = math.inf, symmetric: bool = True,
                       start: ThermalLineSolution | None = None) -> ThermalLineSolution:
    """Solve the thermal Eyring model on one line profile.

    Each sweep marches from inlet to outlet (thesis 3.2.2.2); influences pointing upstream
    (reverse flow, the upstream reach of the surface kernel) are lagged and the sweeps repeat
    until the field stops changing. With ``symmetric`` (default), once the march has passed a
    recirculation zone it relaxes the zone's energy equation by symmetric (backward, then
    forward) passes with the coefficients of the last station iteration
    (:func:`thermal.kernels.sweep_line`), which carries the upstream convection across the zone
    at once: the thick inlet of an EHL field then settles in as few sweeps as the rest of the
    contact (3-4 on appendix C, against 20-30 without), to the same field within the sweep
    tolerance ``tol_T``.

    ``start``: a solution of a nearby profile on the same stations and nz (the previous outer
    iteration of a TEHL solve), from whose temperatures, wall fluxes and stress slopes the
    sweeps start; the field they settle to is the same within ``tol_T``.

    Raises :class:`ConvergenceError` on non-finite values or temperatures outside the property
    model (T < -135 degC); an unconverged but finite solution is returned with
    ``report.converged = False`` and the reason in ``report.message``.
    """
    t0 = time.perf_counter()
    nx = profile.X.size
    nz = options.nz
    nzp = nz + 1
    dx = profile.dx
    p = np.ascontiguousarray(profile.p, dtype=np.float64)
    h = np.ascontiguousarray(profile.h, dtype=np.float64)
    if np.any(~(h > 0)):
        raise InputError("film thickness h must be > 0 m at every station (zero film)")
    mode = momentum_mode(profile, options)
    dpdx = np.ascontiguousarray(profile.dpdx if mode == "gradient" else np.zeros(nx), dtype=np.float64)
    compress = bool(options.compressive_heating and options.thermal)
    dpdx_c = np.ascontiguousarray(profile.dpdx if compress else np.zeros(nx), dtype=np.float64)
    qp = np.ascontiguousarray(profile.poiseuille_flux if mode == "flux" else np.zeros(nx), dtype=np.float64)
    oil = oil_params(env.lubricant, options.G)
    um = 0.5 * (env.u1 + env.u2)
    if options.thermal:
        WL1, WR1 = wall_weights(nx, dx, env.u1, env.body1, options.surface_kernel, kernel_length)
        WL2, WR2 = wall_weights(nx, dx, env.u2, env.body2, options.surface_kernel, kernel_length)
        lagged = _reaches_upstream(WL1, WR1) or _reaches_upstream(WL2, WR2)
    else:
        WL1 = WR1 = WL2 = WR2 = np.zeros(2 * nx - 1)
        # read-only like the cached weights of the thermal path: one compiled specialisation
        WL1.setflags(write=False)
        lagged = False
    T = np.full((nx, nzp), float(env.T_oil))
    tau = np.zeros((nx, nzp))
    u = np.zeros((nx, nzp))
    gv = np.zeros((nx, nzp))
    heat = np.zeros((nx, nzp))
    slope = np.zeros(nx)
    q1 = np.zeros(nx)
    q2 = np.zeros(nx)
    inner = np.zeros(nx, dtype=np.int64)
    if start is not None and start.T.shape != T.shape:
        raise InputError(f"start has {start.T.shape[0]} stations x {start.T.shape[1] - 1} intervals across "
                         f"the film; this solve has {nx} x {nz}")
    warm = start is not None and bool(options.thermal)
    if warm:
        T[:], tau[:], q1[:], q2[:], slope[:] = start.T, start.tau, start.q1, start.q2, start.stress_slope
    # lagged fluxes enter through sum W q: scale them to kelvin by the self weights
    s1 = max(abs(WL1[nx - 1] + WR1[nx - 1]), 1e-300)
    s2 = max(abs(WL2[nx - 1] + WR2[nx - 1]), 1e-300)
    history = np.zeros(options.max_sweeps)
    sweeps, sweeps_ok, n_fail, n_tau_fail, n_rev, n_zone = kernels.march_line(
        dx, p, h, dpdx, qp, mode == "flux", compress, dpdx_c, oil, float(env.u1), float(env.u2), um, float(env.T_oil),
        float(env.T_surface1), float(env.T_surface2), WL1, WR1, WL2, WR2, nz, bool(options.thermal),
        float(options.tol_T), float(options.tol_tau), int(options.max_inner), float(options.relax),
        int(options.max_sweeps), bool(lagged), ZONE_PASSES if symmetric else 0, ZONE_TOL * float(options.tol_T),
        float(s1), float(s2), ANDERSON_DEPTH, T, tau, u, gv, q1, q2, heat, slope, inner, history, FIRST_ZONE_PASSES,
        warm,
    )
    sweep_change = history[:sweeps].copy()
    wall = time.perf_counter() - t0
    converged = bool(sweeps_ok and n_fail == 0 and n_tau_fail == 0)
    parts = []
    if n_fail:
        parts.append(f"{n_fail} station(s) did not reach tol_T/tol_tau in {options.max_inner} iterations")
    if n_tau_fail:
        parts.append(f"{n_tau_fail} shear-stress solve(s) failed")
    if not sweeps_ok:
        parts.append(f"sweeps did not settle in {options.max_sweeps}")
    message = "converged" if converged else "; ".join(parts)
    report = ConvergenceReport(
        converged=converged,
        message=message,
        iterations=int(sweeps),
        residual_history=sweep_change,
        tolerances={"T": options.tol_T, "tau": options.tol_tau},
        wall_s=wall,
        extra={
            "inner_iterations": inner.copy(),
            "reverse_flow_nodes": int(n_rev),
            "zone_passes": int(n_zone),
            "lagged_kernel": bool(lagged),
            "momentum": mode,
        },
    )
    hint = "raise max_inner, lower relax, or check the film/pressure input"
    kernels_check(T, tau, report, hint)
    if np.max(T) > T_MAX_C:
        warning = (f"temperature reaches {np.max(T):.4g} degC, above the {T_MAX_C:g} degC limit of the "
                   "lubricant property model: the oil would degrade; treat the result as qualitative")
        report.extra["warnings"] = [warning]
        report.message = f"{report.message}; warning: {warning}"
    Z = np.linspace(0.0, 1.0, nzp)
    x = profile.x
    tau_m = _zmean(tau)
    F = -float(np.trapezoid(tau_m, x))
    F1 = float(np.trapezoid(tau[:, 0], x))
    F2 = -float(np.trapezoid(tau[:, -1], x))
    return ThermalLineSolution(
        profile=profile, Z=Z, T=T, tau=tau, u=u, gdot=gv, heat_rate=heat, q1=q1, q2=q2,
        force_per_length=F, traction1_per_length=F1, traction2_per_length=F2,
        report=report, T_oil=float(env.T_oil), stress_slope=slope,
        lubricant=env.lubricant if options.thermal else None, compressive_heating=compress,
    )


def momentum_mode(profile: LineProfile, options: ThermalOptions) -> str:
    """How the pressure term of (3.4) enters (see ThermalOptions.momentum): ``off``,
    ``gradient`` (the given dp/dx) or ``flux`` (the EHL solution's pressure-driven flux)."""
    m = options.momentum
    if m == "auto":
        if profile.source in ("hertz", "thesis-slice"):
            return "off"
        return "flux" if profile.poiseuille_flux is not None else "gradient"
    if m == "flux":
        if profile.poiseuille_flux is None:
            raise InputError("momentum = 'flux' needs an EHL field (its pressure-driven flux); "
                             f"the {profile.source!r} input has none: use 'on', 'off' or 'auto'")
        return "flux"
    return "gradient" if m == "on" else "off"


def _reaches_upstream(WL: np.ndarray, WR: np.ndarray) -> bool:
    """True when a surface kernel carries heat upstream (index m = i - j < 0 in WL, m <= 0 in WR)."""
    i0 = (WL.size - 1) // 2
    up = np.sum(np.abs(WL[:i0])) + np.sum(np.abs(WR[: i0 + 1]))
    return bool(up > 1e-12 * (np.sum(np.abs(WL)) + np.sum(np.abs(WR))))


def kernels_check(T: np.ndarray, tau: np.ndarray, report: ConvergenceReport, hint: str) -> None:
    from ehl_multigrid.model.convergence import check_finite

    check_finite("temperature T", T, report, hint)
    check_finite("shear stress tau", tau, report, hint)
    if np.min(T) <= T_ROELANDS_MIN:
        raise ConvergenceError(
            f"temperature fell to {np.min(T):.4g} degC, below the Roelands limit {T_ROELANDS_MIN} degC", report, hint
        )


def heat_budget(
    profile: LineProfile, T: np.ndarray, u: np.ndarray, heat: np.ndarray, q1: np.ndarray, q2: np.ndarray,
    lub: Lubricant, compression: bool = False,
) -> dict[str, float]:
    """Heat budget per unit length of line [W/m] from the converged fields.

    Computed with quadratures independent of the solver's stencils: trapezoid in Z and x,
    second-order central differences for dT/dx. Rho and Cp from the core Lubricant. With
    ``compression`` the work of compression ``int h int T alpha* u dp/dx dZ dx`` is a source,
    with ``alpha* = -(1/rho) d rho/dT`` from a central difference (0.01 K) of the core
    Lubricant's density (not the kernels' closed form) and ``dp/dx`` the profile's.
    """
    x = profile.x
    h = profile.h
    nzp = T.shape[1]
    dZ = 1.0 / (nzp - 1)
    P = np.repeat(profile.p[:, None], nzp, axis=1)
    rho = lub.density(P, T)
    cp = lub.specific_heat(T)
    shear = float(np.trapezoid(h * np.trapezoid(heat, dx=dZ, axis=1), x))
    cond1 = float(np.trapezoid(q1, x))
    cond2 = float(np.trapezoid(q2, x))
    dTdx = np.gradient(T, profile.dx, axis=0, edge_order=2)
    conv = float(np.trapezoid(h * np.trapezoid(rho * cp * u * dTdx, dx=dZ, axis=1), x))
    flux = h * np.trapezoid(rho * cp * u * T, dx=dZ, axis=1)
    enth = float(flux[-1] - flux[0])
    comp = 0.0
    if compression:
        dT = 0.01
        alpha = -(lub.density(P, T + dT) - lub.density(P, T - dT)) / (2.0 * dT * rho)
        work = (T + T_KELVIN) * alpha * u * profile.dpdx[:, None]
        comp = float(np.trapezoid(h * np.trapezoid(work, dx=dZ, axis=1), x))
    bal = (shear + comp - cond1 - cond2 - conv) / shear if shear > 0 else 0.0
    return {
        "shear": shear, "compression": comp, "conduction1": cond1, "conduction2": cond2, "convection": conv,
        "enthalpy_flux": enth, "balance": bal,
    }

