"""Time-dependent isothermal EHL point (circular or elliptic) contact: surface features
passing through the contact.

Venner's dimensionless transient Reynolds equation of a point contact (Venner & Lubrecht
2000, ch. 13; ``X = x/a``, ``Y = y/a``, ``H = h Rx/a^2``, ``T = t u_m/a``)

``d/dX(eps dP/dX) + d/dY(eps dP/dY) - d(rho H)/dX - d(rho H)/dT = 0``

(wedge and squeeze terms carry the same factor, so neither has a coefficient), with the film
of :mod:`.point_features` and the load ``int int P dX dY = 2 pi b/(3a)`` at every step
(constant load, H00(T) free). The design is the line contact's (:mod:`.solve`): BDF2 steps
(the first backward Euler), one FAS solve per step by the shared driver on
:class:`~.point_hierarchy.TransientPointHierarchy` started from the previous solution
extrapolated in time, the deformation (FFT) recomputed after every relaxation sweep. The
start is the core steady solution, then the steady equations with the feature frozen at its
``T = 0`` position.

Limits: as the line contact (projection cavitation ``P >= 0``, no mixed lubrication: a film
that closes raises :class:`ConvergenceError`). The full domain is solved (features need not
be symmetric in Y).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..model.errors import ConvergenceError, InputError, require_choice, require_range
from ..multigrid.driver import MultilevelSolver
from ..multigrid.options import PointOptions
from ..multigrid.policy import RobustnessPolicy
from ..multigrid.result import EHLResult
from ..multigrid.threads import preserved_threads
from ..point.fas import HINT, POINT_POLICY, point_settings
from ..point.problem import PointProblem
from ..point.solve import solve_fas
from .features import feature_speed, require_in
from .point_features import PointFeature, Smooth2D
from .point_hierarchy import TransientPointHierarchy
from .result import TransientResult
from .solve import MAX_STEP_FRACTION, MAX_STEPS, SCHEMES, _step_coefficients

#: Default numerics of a point time step: FFT deformation, a residual below the time error of
#: the default step (measured: 4-6 cycles per step at Courant 1).
POINT_TRANSIENT_DEFAULTS = {"points": 129, "deformation": "fft", "tol": 1e-5, "tol_load": 1e-6,
                            "max_cycles": 40, "raise_on_failure": False, "half": False}


def point_transient_options(options: PointOptions | None = None, **kw: Any) -> PointOptions:
    """Point options of the time steps: :data:`POINT_TRANSIENT_DEFAULTS` below ``options``
    and keywords (always the full domain)."""
    base = PointOptions.build(None, **POINT_TRANSIENT_DEFAULTS) if options is None else options
    if kw.get("half") or (options is not None and options.half and "half" not in kw):
        raise InputError("half = True: the transient point solver needs the full domain "
                         "(features are not symmetric in Y)")
    return PointOptions.build(base, **{**kw, "raise_on_failure": False, "half": False})


def max_point_time_step(feature: PointFeature, speed: float) -> float:
    """Largest ``dT`` accepted: the feature and the free film waves (the mean speed) move at
    most :data:`~.solve.MAX_STEP_FRACTION` of the feature's length scale along X."""
    return MAX_STEP_FRACTION * feature.length_scale / max(abs(speed), 1.0)


@dataclass
class PointTransientResult(TransientResult):
    """Answer of :func:`solve_transient_point`: the series of :class:`TransientResult`
    (``Hc`` at X = Y = 0, ``Hm`` the minimum over the loaded zone, ``H0`` = H00, ``dH`` on the
    row through the feature's reference point) and snapshots of P, H ``[j, i]`` on ``(Y, X)``."""

    Y: np.ndarray | None = None
    yf: float = 0.0
    Hc_steady: float = math.nan
    Hm_steady: float = math.nan
    stop_reason: str = ""

    file_kind = "ehl_transient_point"

    def _problem_dict(self) -> dict[str, Any]:
        return self.problem.to_dict()

    def _x_feature(self, T: float) -> float:
        f = self.feature
        if f.kind == "height_map":
            x_start, x_end, _, _ = f.extent
            return 0.5 * (x_start + x_end) + self.speed * T
        return getattr(f, "x0", 0.0) + self.speed * T

    def _zone(self, X: np.ndarray, Y: np.ndarray) -> np.ndarray:
        boa = self.problem.b_over_a
        return X[None, :] ** 2 + (Y[:, None] / boa) ** 2 <= 1.0

    def record(self, n: int, T: float, hz: Any, res: EHLResult | None, wall: float, keep: bool) -> None:
        lv = hz.fine
        X, Y, P, H = lv.X, lv.Y, lv.P, lv.H
        boa = self.problem.b_over_a
        zone = (X[None, :] ** 2 + (Y[:, None] / boa) ** 2 <= 1.5**2) | (P > 0)
        xf = self._x_feature(T)
        j = int(np.argmin(np.abs(Y - self.yf)))
        s = self.series
        s["step"].append(n)
        s["T"].append(T)
        s["Hc"].append(hz.central_film(lv))
        s["Hm"].append(float(np.min(H[zone])))
        s["H0"].append(float(hz.H00))
        s["Pmax"].append(float(np.max(P)))
        s["dP"].append(float(np.max(np.abs(P - self.steady.P))))
        s["xf"].append(xf)
        s["dH"].append(float(np.interp(xf, X, H[j] - self.steady.H[j])) if X[0] <= xf <= X[-1] else math.nan)
        if res is None:
            s["residual"].append(math.nan)
            s["load_error"].append(hz.load(lv) / hz.g_target - 1.0)
            s["cycles"].append(0)
            s["work_units"].append(0.0)
        else:
            s["residual"].append(float(res.residual_history[-1]))
            s["load_error"].append(float(res.load_error_history[-1]))
            s["cycles"].append(int(res.residual_history.size))
            s["work_units"].append(float(res.work_units))
        s["wall_s"].append(wall)
        bal = point_mass_balance(hz, terms=True) if n > 0 else {"balance": math.nan, "storage": math.nan}
        s["mass_balance"].append(bal["balance"])
        s.setdefault("storage", []).append(bal["storage"])
        if n == 0:
            s["stalled"].append(0.0)
        if keep:
            self.snapshots[n] = {"P": P.copy(), "H": H.copy(), "rho": lv.rho.copy()}

    # -- observables ----------------------------------------------------------------------
    def fraction_below(self, threshold: float) -> list[float]:
        """Per kept step: the fraction of the Hertzian contact ellipse where ``H < threshold``."""
        inside = self._zone(self.X, self.Y)
        return [float(np.mean(self.snapshots[n]["H"][inside] < threshold)) for n in sorted(self.snapshots)]

    def load_fraction_below(self, threshold: float) -> list[float]:
        """Per kept step: the fraction of the load carried where ``H <= threshold``."""
        out = []
        for n in sorted(self.snapshots):
            P, H = self.snapshots[n]["P"], self.snapshots[n]["H"]
            out.append(float(P[H <= threshold].sum() / max(P.sum(), 1e-300)))
        return out

    def film_distribution(self, bins: int = 40) -> tuple[np.ndarray, np.ndarray]:
        """Histogram (counts, edges) of H over the Hertzian ellipse and all kept steps."""
        inside = self._zone(self.X, self.Y)
        H = np.concatenate([self.snapshots[n]["H"][inside] for n in sorted(self.snapshots)])
        return np.histogram(H, bins=bins)

    def waviness_amplitude(self, periods: float = 1.0) -> float:
        """Half the peak-to-peak of ``Hc(T)`` over the last ``periods`` periods along X."""
        wl = getattr(self.feature, "wavelength_x", math.nan)
        if not math.isfinite(wl) or abs(self.speed) < 1e-12:
            return math.nan
        T, Hc = self.T, self.Hc
        per = periods * wl / abs(self.speed)
        if T[-1] - T[0] < per:
            return math.nan
        win = T >= T[-1] - per - 1e-12
        return 0.5 * float(Hc[win].max() - Hc[win].min())

    def summary(self) -> dict[str, Any]:
        cyc = self.cycles[1:]
        wall = self.wall_s_series()[1:]
        amp = getattr(self.feature, "amplitude", math.nan)
        pb = self.problem
        out: dict[str, Any] = {
            "contact": "point", "M": pb.M, "L": pb.L, "theta": pb.theta,
            "points": int(self.X.size), "points_y": int(self.Y.size),
            "xmin": float(self.X[0]), "xmax": float(self.X[-1]), "ymax": float(self.Y[-1]),
            "feature": self.feature.describe(), "body": self.body, "slide_roll": self.slide_roll,
            "feature_speed": self.speed, "dt": self.dt, "scheme": self.scheme, "steps": self.steps,
            "T_end": float(self.T[-1]),
            "Hc_steady": float(self.Hc_steady), "Hm_steady": float(self.Hm_steady),
            "Hc_min": float(np.min(self.Hc)), "Hc_max": float(np.max(self.Hc)),
            "Hm_min": float(np.min(self.Hm)), "dP_max": float(np.max(self.dP)),
            "Pmax_max": float(np.max(self.Pmax)),
            "cycles_mean": float(np.mean(cyc)) if cyc.size else math.nan,
            "cycles_max": int(np.max(cyc)) if cyc.size else 0,
            "stalled_steps": int(np.sum(self.stalled)),
            "residual_max": float(np.nanmax(self.residual[1:])) if cyc.size else math.nan,
            "load_error_max": float(np.max(np.abs(self.load_error[1:]))) if cyc.size else math.nan,
            "mass_balance_max": float(np.nanmax(np.abs(self.mass_balance[1:])))
            if cyc.size and np.any(np.isfinite(self.mass_balance[1:])) else math.nan,
            "wall_per_step_s": float(np.mean(wall)) if wall.size else math.nan,
            "work_units_per_step": float(np.mean(self.work_units[1:])) if cyc.size else math.nan,
            "setup_s": self.setup_s, "wall_s": self.wall_s,
        }
        kind = self.feature.kind
        ad = (self.bump_amplitude_at_centre() if kind == "bump" else
              self.waviness_amplitude() if kind == "waviness" else math.nan)
        out["Ad_over_Ai"] = ad / amp if amp else math.nan
        out["Ad"] = ad
        return out


def point_mass_balance(hz: TransientPointHierarchy, box: float = 0.6, terms: bool = False) -> Any:
    """Discrete mass balance of the control volume ``|X| <= box``, ``|Y| <= box b/a`` (inside the
    pressurised zone) of the finest grid: storage ``hx hy sum d(rho H)/dT`` minus the net
    inflow through its faces (Poiseuille ``-eps_face dP/dn``, second-order upwind Couette
    ``1.5 q_i - 0.5 q_{i-1}`` along X), over the Couette flux through its inlet face. Zero (to the
    residual) when the discrete equations are in conservation form; NaN when the box holds a
    cavitated node. ``terms``: a dict with the balance and the storage term (same scaling)."""
    nan = {"balance": math.nan, "storage": math.nan} if terms else math.nan
    lv = hz.fine
    X, Y, P, q, eps = lv.X, lv.Y, lv.P, lv.rho * lv.H, lv.eps
    hx, hy = lv.hx, lv.hy
    ii = np.flatnonzero(np.abs(X) <= box)
    jj = np.flatnonzero(np.abs(Y) <= box * hz.boa)
    if ii.size < 2 or jj.size < 2 or ii[0] < 3:
        return nan
    i0, i1, j0, j1 = ii[0], ii[-1], jj[0], jj[-1]
    if np.any(P[j0 - 1:j1 + 2, i0 - 1:i1 + 2] <= 0.0):
        return nan
    rows = slice(j0, j1 + 1)
    cols = slice(i0, i1 + 1)
    storage = hx * hy * float(np.sum(hz.squeeze()[rows, cols]))
    # X faces (flux q_x = -eps dP/dX + Couette): inlet face i0 - 1/2, outlet face i1 + 1/2
    c_in = 1.5 * q[rows, i0 - 1] - 0.5 * q[rows, i0 - 2]
    c_out = 1.5 * q[rows, i1] - 0.5 * q[rows, i1 - 1]
    p_in = 0.5 * (eps[rows, i0 - 1] + eps[rows, i0]) * (P[rows, i0] - P[rows, i0 - 1]) / hx
    p_out = 0.5 * (eps[rows, i1] + eps[rows, i1 + 1]) * (P[rows, i1 + 1] - P[rows, i1]) / hx
    flow_x = hy * float(np.sum((c_in - p_in) - (c_out - p_out)))
    # Y faces (flux q_y = -eps dP/dY)
    p_lo = 0.5 * (eps[j0 - 1, cols] + eps[j0, cols]) * (P[j0, cols] - P[j0 - 1, cols]) / hy
    p_hi = 0.5 * (eps[j1, cols] + eps[j1 + 1, cols]) * (P[j1 + 1, cols] - P[j1, cols]) / hy
    flow_y = hx * float(np.sum(-p_lo + p_hi))
    scale = max(hy * float(np.sum(np.abs(c_in))), 1e-300)
    bal = (storage - (flow_x + flow_y)) / scale
    return {"balance": bal, "storage": storage / scale} if terms else bal


def solve_transient_point(
    problem: PointProblem, feature: PointFeature | None, *, body: int = 1, slide_roll: float = 0.0,
    dt: float | None = None, steps: int | None = None, t_end: float | None = None,
    options: PointOptions | None = None, scheme: str = "bdf2", snapshot_every: int = 10,
    initial: tuple[np.ndarray, float] | None = None, accept_stall: float = 1e-3,
    on_film_collapse: str = "raise",
    callback: Callable[[dict[str, Any]], None] | None = None, **kw: Any,
) -> PointTransientResult:
    """Run a surface feature through an EHL point contact at constant load.

    Parameters
    ----------
    problem : the steady :class:`PointProblem` (M, L, theta, lubricant).
    feature : :class:`~.point_features.Waviness2D`, :class:`~.point_features.Dent2D`,
        :class:`~.point_features.HeightMap` (film units ``a_phys Rx/a^2``, lengths in a);
        None for smooth surfaces.
    body : the surface carrying the feature (1 or 2); it moves at ``u_body/u_m`` along X.
    slide_roll : ``S = (u1 - u2)/u_m`` in [-2, 2].
    dt : time step ``dT`` (``T = t u_m/a``); default: one mesh size per step at the faster of
        the feature and the mean flow (Courant 1). Allowed: ``(0, max_point_time_step]``.
    steps, t_end : number of steps, or the end time (default: until a dent's centre or a
        map's upstream edge has reached ``xmax``; waviness: one transit plus three periods).
    options : :class:`PointOptions` of every step (defaults :data:`POINT_TRANSIENT_DEFAULTS`);
        keywords override fields.
    scheme, snapshot_every, initial, callback : as :func:`~.solve.solve_transient_line`
        (``initial`` is ``(P[j, i], H00)``).
    accept_stall : a step whose cycles end above the tolerances (stalled, cycle limit, or
        rejected cycles: seen as a limit cycle of the cavitation boundary when a dent or rough
        patch leaves the contact) is accepted when the relative residual and load error of
        the iterate it leaves are below this; it is flagged in the ``stalled`` series and
        counted in the summary. 0 accepts no such step.
    on_film_collapse : ``"raise"`` (:class:`ConvergenceError`) or ``"stop"``: end the run at
        the step whose film closes (a feature or rough patch cutting through it: mixed
        lubrication, not modelled) and return the steps before it, with ``failed_step`` and
        ``stop_reason`` set (rough-surface studies: the time of first contact).

    Returns
    -------
    PointTransientResult

    Raises
    ------
    InputError : bad feature (too large for the domain), time step, step count or options.
    ConvergenceError : a step's multilevel solve failed, or the film closed, naming the step.
    """
    require_choice("scheme", scheme, SCHEMES)
    require_choice("on_film_collapse", on_film_collapse, ("raise", "stop"))
    feature = Smooth2D() if feature is None else feature
    speed = feature_speed(body, slide_roll)
    opts = point_transient_options(options, **kw)
    if not opts.elastic:
        raise InputError("elastic = False: the transient point solver needs elastic surfaces")
    with preserved_threads():
        hz = TransientPointHierarchy(problem, opts, feature.height)
    fine = hz.fine
    feature.check_domain(hz.xmin, hz.xmax, hz.ymax)
    dt_max = max_point_time_step(feature, speed)
    if dt is None:
        dt = min(fine.hx / max(abs(speed), 1.0), dt_max)
    require_in("dt", dt, 0.0, dt_max, "-",
               f"T = t u_m/a; a step moves at most {MAX_STEP_FRACTION:g} of the feature's length scale "
               f"{feature.length_scale:g} at speed {max(abs(speed), 1.0):g}", lo_open=True)
    if steps is None:
        if t_end is None:
            t_end = default_point_end_time(hz.xmin, hz.xmax, feature, speed)
        require_range("t_end", t_end, dt, dt * MAX_STEPS, "- (T = t u_m/a)")
        steps = int(math.ceil(t_end / dt - 1e-9))
    if isinstance(steps, bool) or int(steps) != steps:
        raise InputError(f"steps = {steps!r} must be an integer in [1, {MAX_STEPS}]")
    require_range("steps", steps, 1, MAX_STEPS, "time steps")
    require_range("snapshot_every", snapshot_every, 1, MAX_STEPS, "steps")
    require_range("accept_stall", accept_stall, 0.0, 0.01, "- (relative residual)")
    steps, snapshot_every = int(steps), int(snapshot_every)

    t0 = time.perf_counter()
    with preserved_threads():
        steady = solve_fas(problem, opts)
        if not steady.success and initial is None:
            raise ConvergenceError(f"transient point solver: the steady start failed: {steady.message}",
                                   steady.report, HINT)
        out = PointTransientResult(problem=problem, feature=feature, body=body, slide_roll=slide_roll,
                                   speed=speed, dt=float(dt), scheme=scheme, options=opts, steady=steady,
                                   X=fine.X.copy(), Y=fine.Y.copy(), yf=float(getattr(feature, "y0", 0.0)))
        ic = int(np.argmin(np.abs(fine.X)))
        jc = int(np.argmin(np.abs(fine.Y)))
        boa = problem.b_over_a
        zone = (fine.X[None, :] ** 2 + (fine.Y[:, None] / boa) ** 2 <= 1.5**2) | (steady.P > 0)
        out.Hc_steady = float(steady.H[jc, ic])
        out.Hm_steady = float(np.min(steady.H[zone]))
        hz.h00_step_max = 0.1 * max(out.Hc_steady, 1e-6)
        if initial is not None:
            P0, H00 = initial
            P0 = np.asarray(P0, dtype=float)
            if P0.shape != fine.P.shape:
                raise InputError(f"initial P has shape {P0.shape}; the finest grid has {fine.P.shape}")
            fine.P, hz.H00 = np.ascontiguousarray(np.maximum(P0, 0.0)), float(H00)
            hz.set_step(0.0, 0.0, np.zeros_like(fine.P))
        else:
            fine.P, hz.H00 = np.ascontiguousarray(steady.P), float(steady.H0)
            hz.set_step(0.0, 0.0, np.zeros_like(fine.P))
            if feature.kind != "smooth":
                res = _solve_point_step(hz, problem, opts)
                if not res.success:
                    raise ConvergenceError(f"transient point solver: the steady start with the feature "
                                           f"at T = 0 failed: {res.message}", res.report, HINT)
        out.record(0, 0.0, hz, None, 0.0, keep=True)
        out.setup_s = time.perf_counter() - t0

        q_prev: np.ndarray | None = None
        q_now = fine.rho * fine.H
        P_prev, H00_prev = fine.P.copy(), hz.H00
        for n in range(1, steps + 1):
            T = n * dt
            ct, hist = _step_coefficients(scheme, n, dt, q_now, q_prev)
            P_now, H00_now = fine.P.copy(), hz.H00
            if n > 1:  # linear extrapolation in time: the start iterate of the step
                Pn = np.maximum(2.0 * P_now - P_prev, 0.0)
                Pn[0, :] = Pn[-1, :] = Pn[:, 0] = Pn[:, -1] = 0.0
                fine.P = np.ascontiguousarray(Pn)
                hz.H00 = 2.0 * H00_now - H00_prev
            hz.set_step(speed * T, ct, hist)
            ts = time.perf_counter()
            res = _solve_point_step(hz, problem, opts)
            wall = time.perf_counter() - ts
            finite = bool(np.all(np.isfinite(fine.P)) and math.isfinite(hz.H00))
            stalled_ok = False
            if not res.success and finite and res.status in (1, 2, 3):
                # cycles that stall, hit the cycle limit or are rejected (a limit cycle of the
                # free boundary) leave the best accepted iterate: accept it when its own
                # residual and load error are below accept_stall
                m = hz.measure(len(hz.levels) - 1)
                stalled_ok = m.ok and m.residual < accept_stall and m.load_error < accept_stall
            wet = fine.P > 0.0
            closed = res.status == 7 or (finite and wet.any() and float(fine.H[wet].min()) <= 0.0)
            if closed and on_film_collapse == "stop":
                out.failed_step = n
                out.stop_reason = (f"the film closed at step {n} (T = {T:.5g}): min H = "
                                   f"{float(fine.H[wet].min()) if wet.any() else math.nan:.3g}")
                break
            if not (res.success or stalled_ok) or not finite:
                out.failed_step = n
                raise ConvergenceError(
                    f"transient point solver: time step {n} (T = {T:.5g}, dT = {dt:.4g}) failed: "
                    f"{res.message}", res.report,
                    "a smaller time step (dt), more points, or a smaller feature amplitude")
            if closed:
                out.failed_step = n
                raise ConvergenceError(
                    f"transient point solver: time step {n} (T = {T:.5g}): the film collapsed "
                    f"(min H = {float(fine.H[wet].min()):.3g} where P > 0); the feature cuts through "
                    f"the film, which needs a mixed-lubrication model", None, "a smaller feature amplitude")
            P_prev, H00_prev = P_now, H00_now
            q_prev, q_now = q_now, fine.rho * fine.H
            out.record(n, T, hz, res, wall, keep=(n % snapshot_every == 0 or n == steps))
            out.series["stalled"].append(0.0 if res.success else 1.0)
            if callback is not None:
                callback(out.last_step())
    out.wall_s = time.perf_counter() - t0
    hz.solver = None
    return out


def default_point_end_time(xmin: float, xmax: float, feature: PointFeature, speed: float) -> float:
    """A dent: until its centre reaches ``xmax``; a height map: until its upstream edge does;
    waviness: one transit of the domain plus three X periods; smooth: two transits."""
    span = xmax - xmin
    moving = speed > 1e-9
    if feature.kind == "smooth":
        return 2.0 * span
    if feature.kind == "bump":
        return (xmax - feature.x0) / speed if moving else span
    if feature.kind == "height_map":
        return (xmax - feature.extent[0]) / speed if moving else span
    wl = feature.wavelength_x
    period = wl / abs(speed) if math.isfinite(wl) and abs(speed) > 1e-9 else 0.0
    return span + 3.0 * period


def _solve_point_step(hz: TransientPointHierarchy, problem: PointProblem, opts: PointOptions) -> EHLResult:
    solver = MultilevelSolver(hz, opts, point_settings(problem, opts),
                              RobustnessPolicy(POINT_POLICY, opts.adapt), HINT)
    return solver.solve()


