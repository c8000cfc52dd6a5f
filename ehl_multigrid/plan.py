"""The planner: which physics a scene needs, with the numbers behind each decision.

For a scene and a target accuracy (``tolerance``, relative, on film thickness and friction) or a
fidelity level, each decision compares an estimate computed from the scene with a threshold:

* film from the fit or from the multigrid solver (fit deviation against tolerance);
* asperity contact (Lambda = h / sigma over the scene's speed range against 3, thesis 4.3.1);
* thermal model (estimated temperature rise times the friction's sensitivity to it);
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

from .errors import InputError, require_range
from .lubricant import ETA_INF, P_R, density_ratio_dh
from .scene import Scene

#: Relative accuracy targeted by each fidelity level.
FIDELITY_TOLERANCE = {"fast": 0.1, "standard": 0.02, "reference": 0.002}

#: Lambda = hc / Rq above which the film carries the whole load (thesis 4.3.1: "roughly more than
#: three times as large as Rq").
LAMBDA_FULL_FILM = 3.0
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
        fid = min(FIDELITY_TOLERANCE, key=lambda k: abs(math.log(FIDELITY_TOLERANCE[k] / tol)))
        return fid, tol
    fid = fidelity or "standard"
    if fid not in FIDELITY_TOLERANCE:
        raise InputError(f"fidelity = {fid!r} is not one of {sorted(FIDELITY_TOLERANCE)}")
    return fid, FIDELITY_TOLERANCE[fid]


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

    Uses the table measured by the fit-check studies when one is installed
    (``ehl_multigrid/data/fit_deviation_<contact>.json``), else MODEL.md's stated range.
    """
    from importlib import resources

    M, L = scene.moes()
    contact = "line" if scene.kind == "line" else "point"
    res = resources.files("ehl_multigrid") / "data" / f"fit_deviation_{contact}.json"
    if res.is_file():
        import json

        tab = json.loads(res.read_text())
        Ms, Ls, dev = np.array(tab["M"]), np.array(tab["L"]), np.abs(np.array(tab["deviation"], dtype=float))
        # nearest tabulated point in log M and L (the fit error varies slowly)
        i = int(np.argmin(np.abs(np.log(Ms) - math.log(M))))
        j = int(np.argmin(np.abs(Ls - L)))
        val = dev[i, j]
        if np.isfinite(val):
            return float(val), f"measured fit check ({tab.get('source', res.name)}) at M={Ms[i]:g}, L={Ls[j]:g}"
    return 0.25, "MODEL.md 6: fits exceed Roelands + Dowson-Higginson solutions by 10-25 % (not yet measured here)"


def temperature_rise_estimate(scene: Scene, us: float, slip: float, h: float) -> dict[str, float]:
    """Cheap estimate of the contact temperature rise [K] and of the friction's sensitivity.

    Shear stress: isothermal Eyring at the Hertz mean pressure, shear rate ``|u1-u2|/h``.
    Heat flux ``q = tau |u1 - u2|`` split between the surfaces; each surface's flash
    temperature for a band of length ``2a`` passing at its speed u (high Peclet, 1-D transient
    conduction): ``dT = 2 (q/2)/k sqrt(kappa t/pi)``, ``t = 2a/u``; a surface at rest gets the
    steady band-source value with t = (2a)^2/kappa capped. The film adds ``q h / (8 k_oil)``.
    The friction's relative change is ``|d ln eta/dT| dT`` times the Eyring damping
    ``x / (sqrt(1 + x^2) asinh x)``, ``x = eta gamma_dot / tau0``.
    """
    lub = scene.lubricant
    hz = scene.hertz
    p = hz.mean_pressure
    du = abs(slip) * us / 2.0
    eta = float(lub.viscosity(p, scene.T_oil))
    rate = du / h
    x = eta * rate / lub.tau0
    tau = lub.tau0 * math.asinh(x)
    q = tau * du
    u1 = 0.5 * us * (1 + 0.5 * slip)
    u2 = 0.5 * us * (1 - 0.5 * slip)
    length = 2.0 * hz.a
    rises = []
    for body, u in ((scene.body1, abs(u1)), (scene.body2, abs(u2))):
        kappa = body.k / (body.rho * body.cp)
        t = length / u if u > 0 else math.inf
        t = min(t, length**2 / kappa)  # a slow or resting surface tends to steady conduction
        rises.append(2.0 * (q / 2.0) / body.k * math.sqrt(kappa * t / math.pi))
    dT_surface = min(rises)  # heat goes preferentially into the cooler path
    k_oil = float(lub.conductivity(p))
    dT = dT_surface + q * h / (8.0 * k_oil)
    # d ln(eta)/dT of Roelands at p, T_oil
    T = scene.T_oil
    expo = (1.0 + p / P_R) ** lub.z * ((lub.T0 + 135.0) / (T + 135.0)) ** lub.S0
    dlneta_dT = -math.log(lub.eta0 / ETA_INF) * expo * lub.S0 / (T + 135.0)
    damping = x / (math.sqrt(1 + x * x) * math.asinh(x)) if x > 1e-12 else 1.0
    return {
        "tau": tau, "q": q, "dT": dT, "dT_surface": dT_surface, "eyring_x": x,
        "friction_sensitivity": abs(dlneta_dT) * dT * damping,
    }


def make_plan(scene: Scene, fidelity: str | None = None, tolerance: float | None = None) -> Plan:
    """Decide what the scene needs. See the module docstring for the criteria."""
    fid, tol = resolve_tolerance(fidelity, tolerance)
    plan = Plan(scene.name, tol, fid)
    speeds = speed_range(scene)
    slips = slip_range(scene)

    # 1. film: fit or solver
    dev, src = fit_deviation_estimate(scene)
    use_solver = dev > tol
    plan.decisions.append(Decision(
        "film", True, "multigrid solver" if use_solver else "fit",
        dev, tol, "-",
        f"expected fit deviation {dev:.3g} {'>' if use_solver else '<='} tolerance {tol:g} ({src})",
    ))

    # 2. asperity contact
    hcs = np.array([scene.central_film_fit(us=u)[1] for u in speeds])
    if scene.roughness is None:
        plan.decisions.append(Decision("asperities", False, "smooth", math.inf, LAMBDA_FULL_FILM, "-",
                                       "scene has no [roughness]: smooth surfaces"))
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
        est = temperature_rise_estimate(scene, u_worst, s_worst, h_worst)
        need = est["friction_sensitivity"] > tol
        plan.decisions.append(Decision(
            "thermal", need, "thermal Roelands-Eyring (chapter 3)" if need else "isothermal",
            est["friction_sensitivity"], tol, "-",
            f"estimated temperature rise {est['dT']:.3g} K at slip {s_worst:g}, us {u_worst:.3g} m/s changes friction by "
            f"about {est['friction_sensitivity']:.2g} (relative)",
        ))
        tau_newton = float(scene.lubricant.viscosity(scene.hertz.mean_pressure, scene.T_oil)) * s_worst * u_worst / 2 / h_worst
        plan.decisions.append(Decision(
            "eyring", tau_newton > scene.lubricant.tau0 * tol, "Eyring (non-Newtonian)" if tau_newton > scene.lubricant.tau0 * tol else "Newtonian",
            tau_newton / scene.lubricant.tau0, tol, "-",
            f"Newtonian shear stress {tau_newton:.3g} Pa against tau0 = {scene.lubricant.tau0:.3g} Pa",
        ))
    else:
        plan.decisions.append(Decision("thermal", False, "isothermal", 0.0, tol, "-", "no slip: no shear heating"))
        plan.decisions.append(Decision("eyring", False, "Newtonian", 0.0, tol, "-", "no slip: no shear stress"))

    # 4. starvation
    if scene.roughness is not None and scene.supply.hoil_over_sigma:
        hmin = min(scene.supply.hoil_over_sigma)
        plan.decisions.append(Decision("starvation", hmin < HOIL_FLOODED_OVER_SIGMA, "Chevalier (chapter 6)", hmin,
                                       HOIL_FLOODED_OVER_SIGMA, "sigma", f"smallest hoil/sigma = {hmin:g}"))
    elif math.isfinite(scene.supply.hoil):
        hs = scene.supply.hoil / (scene.roughness.Rq if scene.roughness else hcs.max())
        ref = HOIL_FLOODED_OVER_SIGMA if scene.roughness else 1.0 / float(density_ratio_dh(scene.hertz.pmax))
        plan.decisions.append(Decision("starvation", hs < ref, "Chevalier (chapter 6)", hs, ref, "-",
                                       f"inlet oil film {scene.supply.hoil:.3g} m"))
    else:
        plan.decisions.append(Decision("starvation", False, "flooded", math.inf, HOIL_FLOODED_OVER_SIGMA, "sigma",
                                       "supply.hoil = inf: fully flooded"))

    # 6. Maxwell elasticity
    G = scene.lubricant.G
    eta_mean = float(scene.lubricant.viscosity(scene.hertz.mean_pressure, scene.T_oil))
    De = eta_mean * (u_worst / 2.0) / (G * scene.hertz.a)
    plan.decisions.append(Decision("maxwell", De > 1.0, "visco-elastic" if De > 1.0 else "off", De, 1.0, "-",
                                   f"Deborah number eta um/(G a) = {De:.3g} with G = {G:.3g} Pa"))
    return plan


def print_plan(plan: Plan) -> None:
    print(f"plan for {plan.scene}: fidelity {plan.fidelity}, tolerance {plan.tolerance:g}")
    for d in plan.decisions:
        flag = "yes" if d.include else "no "
        print(f"  {d.model:<11} {flag}  {d.setting:<38} {d.reason}")
    for n in plan.notes:
        print(f"  note: {n}")
