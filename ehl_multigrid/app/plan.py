"""The planner: which physics a scene needs, with the numbers behind each decision.

For a scene and a target accuracy (``tolerance``, relative, on film thickness and friction) or a
fidelity level, each decision compares an estimate computed from the scene with a threshold:

* film from the fit or from the multigrid solver (fit deviation against tolerance);
* asperity contact (Lambda = h / sigma over the scene's speed range against 3, thesis 4.3.1);
* thermal model (estimated temperature rise times the friction's sensitivity to it) at the
  operating slip(s) (the scene's slip, or its ``[ranges] slip``), where the film and the
  Stribeck curve are computed; the traction curve of ``ehl run`` sweeps its own slips and
  chooses its thermal model there (the thermal layer's stage says which and why);
* starvation (inlet oil film against 6 sigma, thesis chapter 6);
* non-Newtonian Eyring (Newtonian shear stress against tau0);
* Maxwell elasticity (Deborah number against 1).

The estimates are deliberately simple and cheap; ``validation/plan`` compares them with the
full models. The plan is stored in every result the main job writes (``meta['plan']``).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from ..model import fits
from ..model.constants import ETA_INF, P_R
from ..model.errors import InputError, require_range
from ..model.fidelity import FIDELITIES
from ..model.lubricant import G_ELASTICITY_OFF, density_ratio_dh
from ..model.scene import Scene
from ..multigrid.gridchoice import GridChoice, solver_grid
from .stages import TEHL_STAGED, TEHL_UNAVAILABLE

#: Lambda = hc / Rq above which the film carries the whole load (thesis 4.3.1: "roughly more than
#: three times as large as Rq").
LAMBDA_FULL_FILM = 3.0
#: Composite roughness Rq of the smoothest machined steel pairs [m]: superfinished bearing
#: raceways and rollers, Ra 0.02-0.05 um each (ISO 492 practice), so about 0.05 um together. A
#: scene without ``[roughness]`` whose film lies below ``LAMBDA_FULL_FILM`` times this is told
#: that real surfaces would touch there.
SMOOTHEST_STEEL_RQ = 0.05e-6
#: Inlet film above which starvation does not change the film (thesis chapter 6: hoil >= 6 sigma
#: gives the flooded curve).
HOIL_FLOODED_OVER_SIGMA = 6.0


@dataclass
class Decision:
    """One modelling choice: what was estimated, against which threshold, and the verdict."""

    model: str
    include: bool
    setting: str
    estimate: float
    threshold: float
    units: str
    reason: str

    def __post_init__(self) -> None:
        self.include = bool(self.include)  # numpy comparisons give np.bool_
        self.estimate = float(self.estimate)
        self.threshold = float(self.threshold)


@dataclass
class Plan:
    scene: str
    tolerance: float
    fidelity: str
    decisions: list[Decision] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    def get(self, model: str) -> Decision:
        for d in self.decisions:
            if d.model == model:
                return d
        raise KeyError(model)

    def includes(self, model: str) -> bool:
        return self.get(model).include

    def to_dict(self) -> dict[str, Any]:
        return {
            "scene": self.scene, "tolerance": self.tolerance, "fidelity": self.fidelity,
            "decisions": [asdict(d) for d in self.decisions], "notes": list(self.notes),
        }


def resolve_tolerance(fidelity: str | None, tolerance: float | None) -> tuple[str, float]:
    if tolerance is not None:
        tol = require_range("tolerance", tolerance, 1e-6, 1.0, "-", lo_open=True)
        fid = min(FIDELITIES, key=lambda k: abs(math.log(FIDELITIES[k].tolerance / tol)))
        return fid, tol
    fid = fidelity or "standard"
    if fid not in FIDELITIES:
        raise InputError(f"fidelity = {fid!r} is not one of {sorted(FIDELITIES)}")
    return fid, FIDELITIES[fid].tolerance


def speed_range(scene: Scene) -> np.ndarray:
    if "us" in scene.ranges:
        return scene.ranges["us"].values()
    return np.array([scene.us])


def slip_range(scene: Scene) -> np.ndarray:
    if "slip" in scene.ranges:
        return scene.ranges["slip"].values()
    return np.array([scene.slip])


def fit_deviation_estimate(scene: Scene) -> tuple[float, str]:
    """Expected relative deviation of the fitted central film from a Roelands + Dowson-Higginson
    solution at the scene's (M, L), and where the number comes from.

    Uses the table measured by the fit-check studies (:func:`~ehl_multigrid.model.fits.deviation_table`,
    nearest tabulated point), else the 10-25 % range the literature states for Barus-type fits
    against Roelands + Dowson-Higginson solutions. A point contact long in the rolling direction
    (theta > 1, where the table measured at theta = 1 does not hold) adds
    :func:`~ehl_multigrid.model.fits.theta_deviation`.
    """
    M, L = scene.moes()
    kind = "line" if scene.kind == "line" else "point"
    tab = fits.deviation_table(kind)
    Ms, Ls, dev = np.array(tab["M"]), np.array(tab["L"]), np.abs(tab["deviation"])
    # nearest tabulated point in log M and L (the fit error varies slowly)
    i = int(np.argmin(np.abs(np.log(Ms) - math.log(M))))
    j = int(np.argmin(np.abs(Ls - L)))
    val = float(dev[i, j])
    if np.isfinite(val):
        why = f"measured fit check ({tab['source'] or 'fit_deviation table'}) at M={Ms[i]:g}, L={Ls[j]:g}"
    else:
        val, why = 0.25, ("Barus-type, incompressible fits exceed Roelands + Dowson-Higginson solutions by "
                          "10-25 % (not yet measured here)")
    extra = fits.theta_deviation(kind, scene.theta)
    if extra > 0.0:
        val += extra
        why += (f"; plus {extra:.2g} for theta = {scene.theta:.3g} > 1 (the solver's film above Nijenbanning's by "
                f"{fits.THETA_DEVIATION_PER_DOUBLING:g} per doubling of theta, measured at theta 2-4)")
    return val, why


#: The thermal decision includes the model when ``THERMAL_DECISION_MARGIN * friction_sensitivity``
#: exceeds the tolerance; the estimate is at least 0.936 of the thermal solver's change over 616
#: cases, leaving about 17 % (docs/thermal.md, "The planner's thermal decision").
THERMAL_DECISION_MARGIN = 1.25
#: what the thermal decision covers: the traction stage sweeps slips beyond the operating ones
#: and decides its own model there
TRACTION_SCOPE = ("this decision holds at the operating slip (film, Stribeck curve); the traction "
                  "curve chooses its model at the largest of its slips and the operating one")
#: the coupled solver found a third to a half of Gupta's thermal film reduction on the built-in
#: line scenes in rolling (docs/thermal.md): a point contact's coupled solve runs in the main job
#: where this fraction of the reduction still exceeds the tolerance
TEHL_POINT_FRACTION = 1.0 / 3.0
#: film reduction per unit ``beta dT`` of the contact's estimated temperature rise
#: (:func:`temperature_rise_estimate`, operating point): the largest measured Hm reduction over
#: it on 15 line contacts at slip 0.5-2 is 0.26; line contacts only (docs/thermal.md, "Contact heating and the film")
CONTACT_HEATING_FILM = 0.3
#: the same for point and elliptic contacts, of either film and either sign: the largest measured
#: change over ``beta dT`` is 0.142 on 14 point contacts (docs/thermal.md, "Contact heating and the film")
CONTACT_HEATING_FILM_POINT = 0.15
#: the friction models (traction and Stribeck curves) are Eyring models whatever this decision
EYRING_SCOPE = "the friction curves always use the Eyring law (3.3), which is Newtonian at low stress"


@dataclass(frozen=True)
class ThermalFilmChange:
    """The heat's expected change of a scene's film at its operating point (fractions of the
    isothermal central film): ``gupta`` (inlet shear heating, Gupta et al. 1992, from the thermal
    loading ``loading`` and ``ph_E`` = pmax/E'), ``heating`` (the contact's own heat, conducted
    into the inlet: ``per_beta_dT`` x beta dT for the estimated rise ``dT`` [K], 0 in rolling)
    and ``expected``, what the coupled solver is expected to find: the larger of
    ``TEHL_POINT_FRACTION`` x ``gupta`` and ``heating``."""

    loading: float
    ph_E: float
    gupta: float
    heating: float
    dT: float
    per_beta_dT: float

    @property
    def expected(self) -> float:
        return max(TEHL_POINT_FRACTION * self.gupta, self.heating)


def thermal_film_change(scene: Any) -> ThermalFilmChange:
    """:class:`ThermalFilmChange` of ``scene`` at its operating point."""
    L_scene = scene.thermal_properties()["thermal_loading"]  # beta eta0 um^2/k: ~ us^2
    ph_E = scene.hertz.pmax / scene.E_reduced
    gupta = 1.0 - float(fits.gupta_thermal_factor(L_scene, scene.slip, ph_E))
    # Gupta's inlet heating grows with us^2 and misses the heat of sliding that a slow or resting
    # surface conducts into the inlet (pure sliding at 0.06 m/s, 1.7 GPa line: Hc 0.83 of
    # isothermal; a 1.6 GPa ball at 0.2 m/s: 0.75) and the hot outlet (1.93 GPa ball at S = 1: Hm 1.10)
    per_beta_dT = CONTACT_HEATING_FILM if scene.kind == "line" else CONTACT_HEATING_FILM_POINT
    dT = heating = 0.0
    if scene.slip != 0.0:
        dT = temperature_rise_estimate(scene, scene.us, scene.slip, float(scene.central_film_fit()[1]))["dT"]
        heating = per_beta_dT * scene.lubricant.beta(scene.T_oil) * dT
    return ThermalFilmChange(L_scene, ph_E, gupta, heating, dT, per_beta_dT)


def temperature_rise_estimate(scene: Scene, us: float, slip: float, h: float) -> dict[str, float]:
    """Cheap estimate of the contact temperature rise [K] and of the friction's relative change.

    One decoupled pass of the thermal model (thesis chapter 3) on the Hertz pressure with a uniform
    film ``h`` [m]: the isothermal Eyring shear stress (3.3) at each point of the contact
    (``tau = tau0 asinh(eta(p) |u1-u2| / (h tau0))``, Roelands eta at T_oil) gives the heat flux
    ``q = tau |u1 - u2|``; the Carslaw-Jaeger moving-source integral (3.6-3.7),
    ``Theta_i(x) = 1/sqrt(pi rho_i Cp_i k_i u_i) int_{-a}^{x} q dx'/sqrt(x - x')``, is the surface
    temperature rise of body i if it took all the heat. The heat splits between the bodies
    through the film (conductance ``G = k_oil/h``, uniform heating across it):
    ``T_1 = Theta_1/2 (q + 2 G Theta_2) / (q + G (Theta_1 + Theta_2))`` and symmetrically
    (equal surface temperatures for a thin film, half the heat each for a thick one). The film
    adds ``q h/(8 k_oil)`` at mid-film (reported ``dT``, the maximum over the contact) and
    ``q h/(12 k_oil)`` on its mean across the film.

    The linearised friction change is the shear-weighted mean of
    ``|d ln eta/dT| * damping * dT_film_mean`` (Eyring damping ``x / (sqrt(1 + x^2) asinh x)``,
    ``x = eta gamma_dot / tau0``; the film-mean temperature is what sets the shear stress of a
    film sheared between two walls). Less heat is generated once friction drops, so the
    reported ``friction_sensitivity`` is ``s / (1 + s)`` of the linear value ``s`` (used by the
    decision: never below 0.936 x the solver's change in validation/plan), and the reported
    temperatures are scaled by the friction ratio ``phi = W(s)/s`` of ``phi = exp(-s phi)``
    (heat proportional to friction; W = Lambert W), which keeps them realistic at high heating;
    ``dT_isothermal_heat`` is the unscaled maximum.

    Point and elliptic contacts use 8 slices across y (each a Hertz line of half-width
    ``a sqrt(1 - Y^2)``), line contacts one line; 64 points along x.
    The high-Peclet source overestimates at Peclet ``u a / (2 kappa) < 1`` (up to 3.6x measured),
    which errs towards including the thermal model.
    """
    lub = scene.lubricant
    hz = scene.hertz
    du = abs(slip) * us / 2.0
    T = scene.T_oil
    if not du > 0.0:
        return {"tau": 0.0, "q": 0.0, "dT": 0.0, "dT_mean": 0.0, "dT_surface": 0.0, "dT_isothermal_heat": 0.0,
                "eyring_x": 0.0, "friction_sensitivity": 0.0, "friction_sensitivity_linear": 0.0}
    nx, ny = 64, 8
    X = -1.0 + (np.arange(nx) + 0.5) * (2.0 / nx)
    Y = np.zeros(1) if scene.kind == "line" else (np.arange(ny) + 0.5) / ny
    half = np.sqrt(1.0 - Y**2)  # slice half-width / a (and pmax of the slice / pmax)
    p = hz.pmax * half[:, None] * np.sqrt(1.0 - X[None, :] ** 2)
    eta = np.asarray(lub.viscosity(p, T), dtype=float)
    x = eta * (du / h) / lub.tau0
    tau = lub.tau0 * np.arcsinh(x)
    q = tau * du
    # moving-source weights on cell centres: int_cell (x_j - x')^(-1/2) dx' in units of sqrt(dx)
    d = np.arange(nx)[:, None] - np.arange(nx)[None, :]
    w = 2.0 * (np.sqrt(np.clip(d + 0.5, 0.0, None)) - np.sqrt(np.clip(d - 0.5, 0.0, None)))
    w[d == 0] = 2.0 * math.sqrt(0.5)
    dx = hz.a * half * (2.0 / nx)
    source = (q @ w.T) * np.sqrt(dx)[:, None] / math.sqrt(math.pi)
    u1 = abs(0.5 * us * (1 + 0.5 * slip))
    u2 = abs(0.5 * us * (1 - 0.5 * slip))
    # a surface at rest keeps a small conductance so the partition formula stays finite
    theta = [source / math.sqrt(b.k * b.rho * b.cp * max(u, 1e-6 * us)) for b, u in ((scene.body1, u1), (scene.body2, u2))]
    k_oil = np.asarray(lub.conductivity(p), dtype=float)
    G = k_oil / h
    den = q + G * (theta[0] + theta[1])
    T1 = 0.5 * theta[0] * (q + 2.0 * G * theta[1]) / den
    T2 = 0.5 * theta[1] * (q + 2.0 * G * theta[0]) / den
    surface = 0.5 * (T1 + T2)
    film_mid = surface + q * h / (8.0 * k_oil)
    film_mean = surface + q * h / (12.0 * k_oil)
    # |d ln(eta)/dT| of Roelands at p, T_oil
    expo = (1.0 + p / P_R) ** lub.z * ((lub.T0 + 135.0) / (T + 135.0)) ** lub.S0
    dlneta_dT = math.log(lub.eta0 / ETA_INF) * expo * lub.S0 / (T + 135.0)
    damping = np.where(x > 1e-12, x / (np.sqrt(1.0 + x * x) * np.arcsinh(np.maximum(x, 1e-300))), 1.0)
    area = np.broadcast_to(half[:, None], p.shape)  # cell areas are proportional to the slice width
    force = float(np.sum(tau * area))
    s_lin = float(np.sum(tau * dlneta_dT * damping * film_mean * area) / force)
    w = math.log1p(s_lin)  # Lambert W(s_lin) by Newton: w exp(w) = s_lin
    for _ in range(30):
        step = (w * math.exp(w) - s_lin) / (math.exp(w) * (1.0 + w))
        w -= step
        if abs(step) < 1e-12 * (1.0 + w):
            break
    phi = w / s_lin if s_lin > 1e-12 else 1.0
    return {
        "tau": force / float(np.sum(area)), "q": force / float(np.sum(area)) * du,
        "dT": phi * float(film_mid.max()), "dT_mean": phi * float(np.sum(film_mean * area) / np.sum(area)),
        "dT_surface": phi * float(surface.max()), "dT_isothermal_heat": float(film_mid.max()),
        "eyring_x": float(x.max()),
        "friction_sensitivity": s_lin / (1.0 + s_lin), "friction_sensitivity_linear": s_lin,
    }


def film_grid(scene: Scene, tol: float) -> GridChoice:
    """Finest grid of the film solver for the scene at tolerance ``tol`` (measured grid-error
    constants, :mod:`ehl_multigrid.multigrid.gridchoice`; the point solver's own minimum grid as floor)."""
    M, _ = scene.moes()
    if scene.kind == "line":
        return solver_grid("line", M, tol)
    from ..point.problem import min_points

    return solver_grid("point", M, tol, floor=min_points(M, scene.hertz.b / scene.hertz.a))


def make_plan(scene: Scene, fidelity: str | None = None, tolerance: float | None = None) -> Plan:
    """Decide what the scene needs. See the module docstring for the criteria."""
    fid, tol = resolve_tolerance(fidelity, tolerance)
    plan = Plan(scene.name, tol, fid)
    speeds = speed_range(scene)
    slips = slip_range(scene)

    # 1. film: fit or solver
    dev, src = fit_deviation_estimate(scene)
    use_solver = dev > tol
    why = f"expected fit deviation {dev:.3g} {'>' if use_solver else '<='} tolerance {tol:g} ({src})"
    if use_solver:
        why += f"; {film_grid(scene, tol).first_grid_reason(tol)}"
    plan.decisions.append(Decision("film", True, "multigrid solver" if use_solver else "fit", dev, tol, "-", why))

    # 2. asperity contact
    hcs = np.array([scene.central_film_fit(us=u)[1] for u in speeds])
    if scene.roughness is None:
        why = "scene has no [roughness]: smooth surfaces"
        hc_op = float(scene.central_film_fit()[1])
        if hc_op < LAMBDA_FULL_FILM * SMOOTHEST_STEEL_RQ:
            why += (f"; the fitted central film at the operating point, {hc_op * 1e9:.3g} nm, is below "
                    f"{LAMBDA_FULL_FILM:g} x {SMOOTHEST_STEEL_RQ * 1e6:g} um, the composite roughness of "
                    f"superfinished steel: real surfaces would touch (mixed lubrication); give [roughness] "
                    f"to compute the load the asperities carry")
        plan.decisions.append(Decision("asperities", False, "smooth", math.inf, LAMBDA_FULL_FILM, "-", why))
    else:
        lam_min = float(hcs.min() / scene.roughness.Rq)
        need = lam_min < LAMBDA_FULL_FILM
        plan.decisions.append(Decision(
            "asperities", need, "Greenwood-Williamson load sharing" if need else "full film",
            lam_min, LAMBDA_FULL_FILM, "-",
            f"smallest Lambda = hc/Rq over us in [{speeds.min():.3g}, {speeds.max():.3g}] m/s is {lam_min:.3g}",
        ))

    # 3. thermal and 5. non-Newtonian, at the worst (largest) slip and speed
    s_worst = float(np.max(np.abs(slips)))
    u_worst = float(speeds.max())
    h_worst = float(scene.central_film_fit(us=u_worst)[1])
    if s_worst > 0:
        # the largest estimate over the speed range at the largest slip
        ests = [(temperature_rise_estimate(scene, float(u), s_worst, float(hu)), float(u)) for u, hu in zip(speeds, hcs, strict=True)]
        est, u_est = max(ests, key=lambda e: e[0]["friction_sensitivity"])
        threshold = tol / THERMAL_DECISION_MARGIN
        need = est["friction_sensitivity"] > threshold
        plan.decisions.append(Decision(
            "thermal", need, "thermal Roelands-Eyring (chapter 3)" if need else "isothermal",
            est["friction_sensitivity"], threshold, "-",
            f"estimated temperature rise {est['dT']:.3g} K at slip {s_worst:g}, us {u_est:.3g} m/s changes friction by "
            f"about {est['friction_sensitivity']:.2g} (relative; threshold = tolerance / {THERMAL_DECISION_MARGIN:g} "
            f"safety margin, validation/plan/REPORT.md); {TRACTION_SCOPE}",
        ))
        tau_newton = float(scene.lubricant.viscosity(scene.hertz.mean_pressure, scene.T_oil)) * s_worst * u_worst / 2 / h_worst
        plan.decisions.append(Decision(
            "eyring", tau_newton > scene.lubricant.tau0 * tol, "Eyring (non-Newtonian)" if tau_newton > scene.lubricant.tau0 * tol else "Newtonian",
            tau_newton / scene.lubricant.tau0, tol, "-",
            f"Newtonian shear stress {tau_newton:.3g} Pa against tau0 = {scene.lubricant.tau0:.3g} Pa at the "
            f"operating slip; {EYRING_SCOPE}",
        ))
    else:
        plan.decisions.append(Decision("thermal", False, "isothermal", 0.0, tol, "-",
                                       f"no slip at the operating point: no shear heating; {TRACTION_SCOPE}"))
        plan.decisions.append(Decision("eyring", False, "Newtonian", 0.0, tol, "-",
                                       f"no slip at the operating point: no shear stress; {EYRING_SCOPE}"))

    # 3b. thermal EHL: heat in the inlet thins the film (the decoupled method keeps its friction
    # within 0.6 % on the thesis's line conditions, validation/tehl/REPORT.md, but not its film).
    # Decided at the operating point, where the film is solved; the scene's ranges only noted
    change = thermal_film_change(scene)
    L_scene, ph_E, gupta, heating = change.loading, change.ph_E, change.gupta, change.heating
    red = max(gupta, heating)
    need = red > tol
    # a line contact's coupled solve costs seconds and runs as a stage of the thermal layer; a
    # point contact's costs 10-150 s: it runs where the contact's heat or TEHL_POINT_FRACTION of
    # Gupta's reduction exceeds the tolerance (a flooded inlet only), else it is advised
    expected = change.expected > tol
    staged = scene.kind == "line" or (math.isinf(scene.supply.hoil) and expected)
    if staged:
        solved = TEHL_STAGED
    elif expected:
        # a starved point inlet: the coupled solvers are flooded ones (point) or line ones
        solved = TEHL_UNAVAILABLE
    else:
        solved = "thermal EHL advised (ehl solve SCENE --thermal)"
    why = (f"thermal film reduction {gupta:.2g} by Gupta et al. (1992) at the operating point (thermal "
           f"loading {L_scene:.3g}, us {scene.us:.3g} m/s, slip {scene.slip:g})")
    if heating > gupta:
        why += (f"; up to {heating:.2g} from the contact's heat (estimated temperature rise {change.dT:.3g} K: "
                f"{change.per_beta_dT:g} x beta dT)")
    if len(speeds) > 1 or s_worst != abs(scene.slip):
        worst = max((1.0 - float(fits.gupta_thermal_factor(L_scene * (float(u) / scene.us) ** 2, s_worst, ph_E)),
                     float(u)) for u in speeds)
        why += (f"; up to {worst[0]:.2g} over the scene's ranges (us {worst[1]:.3g} m/s, slip {s_worst:g}), "
                f"where the curves keep the isothermal film")
    plan.decisions.append(Decision(
        "tehl", need, solved if need else "isothermal film", red, tol, "-",
        f"{why}; the coupled solver measured 35-70 % of it on the central film but more on the "
        f"minimum film at high load and slip (Hm 0.75 of isothermal at 1.6 GPa, S = 1)",
    ))

    # 4. starvation
    if scene.roughness is not None and scene.supply.hoil_over_sigma:
        hmin = min(scene.supply.hoil_over_sigma)
        plan.decisions.append(Decision("starvation", hmin < HOIL_FLOODED_OVER_SIGMA, "Chevalier (chapter 6)", hmin,
                                       HOIL_FLOODED_OVER_SIGMA, "sigma", f"smallest hoil/sigma = {hmin:g}"))
    elif math.isfinite(scene.supply.hoil):
        hs = scene.supply.hoil / (scene.roughness.Rq if scene.roughness else hcs.max())
        ref = HOIL_FLOODED_OVER_SIGMA if scene.roughness else 1.0 / float(density_ratio_dh(scene.hertz.pmax))
        # the mass-conserving solvers (ehl_multigrid.starved) replace the fit for smooth contacts
        method = f"Elrod-Adams solver (starved {'line' if scene.kind == 'line' else 'point'})"
        why = (f"inlet oil film {scene.supply.hoil:.3g} m = {hs:.3g} Rq; starved below {ref:g} Rq"
               if scene.roughness else
               f"inlet oil film {scene.supply.hoil:.3g} m = {hs:.3g} x the fitted flooded central film; "
               f"starved below {ref:.3g} (the flooded film's flux at ambient density, 1/rho(pmax))")
        plan.decisions.append(Decision("starvation", hs < ref, method, hs, ref, "-", why))
    else:
        plan.decisions.append(Decision("starvation", False, "flooded", math.inf, HOIL_FLOODED_OVER_SIGMA, "sigma",
                                       "supply.hoil = inf: fully flooded"))

    # 6. Maxwell elasticity
    G = scene.lubricant.G
    eta_mean = float(scene.lubricant.viscosity(scene.hertz.mean_pressure, scene.T_oil))
    De = eta_mean * (u_worst / 2.0) / (G * scene.hertz.a)
    why = (f"Deborah number eta um/(G a) = {De:.3g} with G = {G:.3g} Pa" if G < G_ELASTICITY_OFF else
           "the lubricant gives no shear modulus (G = 1e30 Pa: elasticity off)")
    plan.decisions.append(Decision("maxwell", De > 1.0, "visco-elastic" if De > 1.0 else "off", De, 1.0, "-", why))
    return plan


def print_plan(plan: Plan) -> None:
    print(f"plan for {plan.scene}: fidelity {plan.fidelity}, tolerance {plan.tolerance:g}")
    for d in plan.decisions:
        flag = "yes" if d.include else "no "
        print(f"  {d.model:<11} {flag}  {d.setting:<38} {d.reason}")
    for n in plan.notes:
        print(f"  note: {n}")
