"""Result of a transient run: time series, snapshots, per-step convergence, of the line
contact (:class:`TransientResult`) and the point contact (:class:`PointTransientResult`, the
same series with the point contact's geometry: its fields on ``(Y, X)``).

Definitions (line; Venner units: ``X = x/b``, ``H = h R/b^2``, ``P = p/pmax``, ``T = t u_m/b``):

* ``Hc(T)`` -- film at ``X = 0``; ``Hm(T)`` -- minimum film where ``P > 0`` or ``|X| <= 1.5``;
* ``dP(T)`` -- pressure fluctuation ``max_X |P(X, T) - P_s(X)|`` against the smooth steady
  pressure ``P_s`` (the core steady solution); ``Pmax(T)`` -- the largest pressure;
* ``xf(T)`` -- feature reference position (a bump's centre, a waviness crest at ``T = 0``
  phase 0) moving at ``speed``; ``dH(T)`` -- the film's deviation from the smooth steady film
  at ``xf``: ``H(xf, T) - H_s(xf)``;
* deformed amplitude: a bump's ``-dH`` when its centre passes ``X = 0``
  (:meth:`TransientResult.bump_amplitude_at_centre`); waviness: half the peak-to-peak of
  ``Hc(T)`` over the last full period (:meth:`TransientResult.waviness_amplitude`);
* ``stalled(T)`` -- 1 for a step accepted with a stalled residual (below ``accept_stall``);
* ``substeps(T)`` -- the solves a step took: 1, or more where a failed solve was halved (or,
  with a time tolerance, the adaptive steps and their rejected attempts);
* ``time_error(T)``, ``rejected(T)`` (adaptive runs) -- the largest accepted local film error
  of BDF2 in the output step (relative to the smallest film of the contact zone) and the steps
  solved again smaller;
* ``mass_balance(T)`` -- the discrete flux balance of the pressurised (wetted) zone of the
  converged step (discrete.flux_balance) over the total flux through it;
* ``mass_error(T)`` (line, mass-conserving cavitation) -- the oil the whole grid gained in the
  step beyond what flowed in and out, over the inflow (:func:`.cavitated.domain_mass_error`):
  zero to the step tolerance. NaN with the projection, which counts every gap behind a
  rupture as full of oil.

A run that ends early (a step fails, the film closes, the process is stopped) keeps every
completed step: ``complete`` is False and ``stop_reason`` says why. The last completed step is
always among the snapshots, and ``state`` holds what the next step needs (the unknowns of the
last two steps and their films), so that a checkpoint file can be continued
(:mod:`.checkpoint`).
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..line.problem import LineProblem
from ..model.results import COMPRESSION, _write_atomic, package_version
from ..multigrid.options import LineOptions
from ..multigrid.result import EHLResult
from .cavitated import CavitatedPointStepHierarchy, domain_mass_error, point_domain_mass_error
from .discrete import flux_balance
from .features import x_ref
from .hierarchy import TransientPointHierarchy

SERIES = ("step", "T", "Hc", "Hm", "H0", "Pmax", "dP", "xf", "dH", "residual", "load_error",
          "cycles", "work_units", "wall_s", "mass_balance", "stalled", "substeps")
#: arrays of :attr:`TransientResult.state` (the next step's inputs), besides its scalars
STATE_ARRAYS = ("P", "P_prev", "q", "q_prev", "theta", "q_prev2")
STATE_SCALARS = ("step", "T", "H0", "H0_prev")
#: scalars of an adaptive run's state (its last steps' sizes and the next step's)
STATE_STEP_SIZES = ("dt_prev", "dt_prev2", "h_next")


@dataclass
class TransientResult:
    """Answer of :func:`~.solve.solve_transient_line` (see module docstring for the series).

    Series are numpy arrays through attribute access (``res.Hc``, ``res.T`` ...); step 0 is
    the start. ``snapshots`` maps step -> dict of P, H, rho arrays on ``X``.
    """

    problem: LineProblem
    feature: Any
    body: int
    slide_roll: float
    speed: float
    dt: float
    scheme: str
    options: LineOptions
    steady: EHLResult
    X: np.ndarray
    series: dict[str, list[float]] = field(default_factory=lambda: {k: [] for k in SERIES})
    snapshots: dict[int, dict[str, np.ndarray]] = field(default_factory=dict)
    setup_s: float = 0.0
    wall_s: float = 0.0
    failed_step: int | None = None
    #: False when the run ended before its last planned step (see ``stop_reason``)
    complete: bool = True
    stop_reason: str = ""
    planned_steps: int = 0
    #: what produced the run (command-line arguments, scene), stored with the file
    run: dict[str, Any] = field(default_factory=dict)
    #: the inputs of the next step after the last completed one: ``step``, ``T``, the
    #: unknowns ``P``, ``H0`` and ``P_prev``, ``H0_prev`` of the step before, the films
    #: ``q = rho H`` of both (``q_prev`` None after the start; ``theta rho H`` and the film
    #: content ``theta`` with mass-conserving cavitation)
    state: dict[str, Any] | None = field(default=None, repr=False)
    #: the cavitation model of the steps: ``"projection"`` (``P >= 0``) or ``"mass-conserving"``
    cavitation: str = "projection"
    #: the supplied oil layer (Venner units; inf: flooded inlet)
    hoil: float = math.inf
    #: the oil a mass-conserving step may gain over the inflow (None: no criterion, or the
    #: projection)
    mass_tol: float | None = None
    _unkept: int | None = field(default=None, repr=False)

    def __getattr__(self, name: str) -> Any:
        series = self.__dict__.get("series")
        if series is not None and name in series:
            return np.asarray(series[name], dtype=float)
        raise AttributeError(name)

    # -- building -------------------------------------------------------------------------
    def record(self, n: int, T: float, hz: Any, res: EHLResult | None, wall: float, keep: bool) -> None:
        """Append step ``n`` (time ``T``) of the finest grid of ``hz`` to the series (``res``
        the step's solve, None for the start) and keep a snapshot when ``keep``."""
        lv, st = self._fields(hz)
        X, P, H = lv.X, lv.P, st.H
        zone = self.within(1.5) | (P > 0)
        xf = x_ref(self.feature) + self.speed * T
        s = self.series
        s["step"].append(n)
        s["T"].append(T)
        s["Hc"].append(self._central_film(hz, H))
        s["Hm"].append(float(np.min(H[zone])))
        s["H0"].append(float(self._film_constant(hz)))
        s["Pmax"].append(float(np.max(P)))
        s["dP"].append(float(np.max(np.abs(P - self.steady.P))))
        s["xf"].append(xf)
        s["dH"].append(float(np.interp(xf, X, self._row(H) - self._row(self.steady.H)))
                       if X[0] <= xf <= X[-1] else math.nan)
        if res is None:
            s["residual"].append(math.nan)
            s["load_error"].append(self._start_load_error(hz))
            s["cycles"].append(0)
            s["work_units"].append(0.0)
        else:
            s["residual"].append(float(res.residual_history[-1]))
            s["load_error"].append(float(res.load_error_history[-1]))
            s["cycles"].append(int(res.residual_history.size))
            s["work_units"].append(float(res.work_units))
        s["wall_s"].append(wall)
        self._record_mass_balance(hz, st, n)
        if n == 0:
            s["stalled"].append(0.0)
            s["substeps"].append(1.0)
        # the last completed step is always kept (a run that stops keeps its final state);
        # it is dropped again when the next step completes, unless it is a kept step
        if self._unkept is not None:
            self.snapshots.pop(self._unkept, None)
        self._unkept = None if keep else n
        self.snapshots[n] = {"P": P.copy(), "H": H.copy(), "rho": st.rho.copy()}
        if getattr(st, "theta", None) is not None:  # the mass-conserving model's film content
            self.snapshots[n]["theta"] = st.theta.copy()

    def mark_incomplete(self, reason: str) -> None:
        """Flag the run as ended before its last planned step, for ``reason`` (the first
        reason given is kept)."""
        self.complete = False
        if not self.stop_reason:
            self.stop_reason = reason

    # -- the contact's geometry (line here; the point result overrides) -------------------
    def _fields(self, hz: Any) -> tuple[Any, Any]:
        """The finest grid and its fluid state (``H``, ``rho``)."""
        return hz.fine, hz.fine.state()

    def within(self, r: float) -> np.ndarray:
        """Nodes inside ``r`` Hertzian half-widths of the centre."""
        return np.abs(self.X) <= r

    def _row(self, F: np.ndarray) -> np.ndarray:
        """The line of nodes through the feature's reference point."""
        return F

    def _central_film(self, hz: Any, H: np.ndarray) -> float:
        return float(np.interp(0.0, self.X, H))

    def _film_constant(self, hz: Any) -> float:
        return hz.fine.H0

    def _start_load_error(self, hz: Any) -> float:
        return hz.fine.load() / hz.fine.g - 1.0

    def steady_film(self, name: str) -> float:
        """The smooth steady film ``"Hc"`` or ``"Hm"``."""
        return getattr(self.steady, f"{name}_venner")

    def _summary_head(self) -> dict[str, Any]:
        return {"M": self.problem.M, "L": self.problem.L, "points": int(self.X.size),
                "xmin": self.problem.xmin, "xmax": self.problem.xmax}

    def _record_mass_balance(self, hz: Any, st: Any, n: int) -> None:
        self.series["mass_balance"].append(self._mass_balance(hz.fine, st) if n > 0 else math.nan)
        # a run continued from a file written before the series existed: NaN before it
        err = self.series.setdefault("mass_error", [math.nan] * (len(self.series["step"]) - 1))
        err.append(self._domain_mass_error(hz.fine, st) if n > 0 else math.nan)

    @staticmethod
    def _domain_mass_error(lv: Any, st: Any) -> float:
        """Oil gained by the whole grid in the step over the inflow
        (:func:`.cavitated.domain_mass_error`) with mass-conserving cavitation (its residual);
        NaN for the projection."""
        theta = getattr(st, "theta", None)
        if theta is None:
            # the projection counts every gap as full, so its balance over the grid measures
            # the gap behind each rupture, not the oil that changes the film: not recorded
            return math.nan
        return domain_mass_error(lv.P, theta, st.q, st.eps, lv.squeeze(st), lv.h, lv.order, lv.face)

    @staticmethod
    def _mass_balance(lv: Any, st: Any) -> float:
        """Relative flux balance of the wetted zone from node 2 to the last node before the
        first cavitated node downstream of the contact centre."""
        P = lv.P
        cav = np.flatnonzero((P <= 0.0) & (lv.X > 0.0))
        i1 = (int(cav[0]) if cav.size else lv.n - 1) - 2
        i0 = 2
        if i1 <= i0:
            return math.nan
        dq = lv.squeeze(st)
        bal = flux_balance(P, st.H, st.rho, st.eps, lv.h, dq, i0, i1, lv.face)
        q = st.rho * st.H
        return float(bal / max(abs(q[i0]), abs(q[i1]), 1e-300))

    def last_step(self) -> dict[str, Any]:
        return {k: v[-1] for k, v in self.series.items()}

    # -- observables ----------------------------------------------------------------------
    @property
    def steps(self) -> int:
        return len(self.series["step"]) - 1

    def bump_amplitude_at_centre(self) -> float:
        """``-dH`` interpolated to the time the feature centre passes ``X = 0`` (NaN when it
        does not pass). For a bump of amplitude A this is the deformed amplitude Ad."""
        xf, dH = self.xf, self.dH
        ok = np.isfinite(dH)
        xf, dH = xf[ok], dH[ok]
        if xf.size < 2 or not (xf.min() <= 0.0 <= xf.max()):
            return math.nan
        order = np.argsort(xf)
        return float(-np.interp(0.0, xf[order], dH[order]))

    def waviness_amplitude(self, periods: float = 1.0) -> float:
        """Half the peak-to-peak of ``Hc(T)`` over the last ``periods`` feature periods along X."""
        wl = getattr(self.feature, "wavelength_x", math.nan)
        if not math.isfinite(wl) or abs(self.speed) < 1e-12:
            return math.nan
        T, Hc = self.T, self.Hc
        per = periods * wl / abs(self.speed)
        if T[-1] - T[0] < per:
            return math.nan
        win = T >= T[-1] - per - 1e-12
        return 0.5 * float(Hc[win].max() - Hc[win].min())

    def fraction_below(self, threshold: float) -> list[float]:
        """Per kept step: the fraction of the Hertzian contact (line ``|X| <= 1``, point the
        Hertzian ellipse) where ``H < threshold`` (Venner units)."""
        inside = self.within(1.0)
        return [float(np.mean(self.snapshots[n]["H"][inside] < threshold)) for n in sorted(self.snapshots)]

    def summary(self) -> dict[str, Any]:
        """JSON-ready scalars of the run (``complete`` False and ``stop_reason`` for a run that
        ended early)."""
        cyc = self.cycles[1:]
        wall = np.asarray(self.series["wall_s"], dtype=float)[1:]  # (the field wall_s is the total)
        amp = getattr(self.feature, "amplitude", math.nan)
        out: dict[str, Any] = {
            **self._summary_head(),
            "feature": self.feature.describe(), "body": self.body, "slide_roll": self.slide_roll,
            "feature_speed": self.speed, "dt": self.dt, "scheme": self.scheme, "steps": self.steps,
            "T_end": float(self.T[-1]),
            "Hc_steady": float(self.steady_film("Hc")), "Hm_steady": float(self.steady_film("Hm")),
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
            "cavitation": self.cavitation, "hoil": self.hoil,
            "time_error_max": _nanmax_abs(self.series.get("time_error", [])[1:]),
            "rejected_steps": int(np.sum(self.series.get("rejected", [0.0]))),
            "mass_error_max": _nanmax_abs(self.series.get("mass_error", [])[1:]),
            "mass_tol": self.mass_tol,
            "mass_error_mean": _nanmean(self.series.get("mass_error", [])[1:]),
            "wall_per_step_s": float(np.mean(wall)) if wall.size else math.nan,
            "work_units_per_step": float(np.mean(self.work_units[1:])) if cyc.size else math.nan,
            "setup_s": self.setup_s, "wall_s": self.wall_s,
            "complete": self.complete, "stop_reason": self.stop_reason,
            "planned_steps": self.planned_steps,
        }
        kind = self.feature.kind
        ad = (self.bump_amplitude_at_centre() if kind == "bump" else
              self.waviness_amplitude() if kind == "waviness" else math.nan)
        out["Ad_over_Ai"] = ad / amp if amp else math.nan
        out["Ad"] = ad
        return out

    # -- output ---------------------------------------------------------------------------
    #: HDF5 ``kind`` attribute of the file
    file_kind = "ehl_transient_line"

    def _problem_dict(self) -> dict[str, Any]:
        return self.problem.describe()

    def to_hdf5(self, path: str | os.PathLike) -> str:
        """Write the series, snapshots and summary to HDF5 (temporary file, then rename).

        Root attributes: ``kind``, ``complete`` (False for a run that ended early or a
        checkpoint of a running one), ``stop_reason``, ``last_step``, ``last_T``,
        ``planned_steps``, ``summary``, ``problem``, ``options``, ``run`` (JSON). An incomplete
        file also holds the group ``state`` (the inputs of the next step) to continue from.
        """
        path = os.fspath(path)

        def write(f: Any) -> None:
            f.attrs["kind"] = self.file_kind
            f.attrs["package_version"] = package_version()
            f.attrs["complete"] = np.bool_(self.complete)
            f.attrs["stop_reason"] = self.stop_reason
            f.attrs["last_step"] = int(self.steps)
            f.attrs["last_T"] = float(self.series["T"][-1]) if self.series["T"] else math.nan
            f.attrs["planned_steps"] = int(self.planned_steps)
            f.attrs["summary"] = json.dumps(self.summary(), default=_jsonable)
            f.attrs["problem"] = json.dumps(self._problem_dict(), default=_jsonable)
            f.attrs["options"] = json.dumps(self.options.describe(), default=_jsonable)
            f.attrs["run"] = json.dumps(self.run, default=_jsonable)
            f.create_dataset("X", data=self.X)
            if getattr(self, "Y", None) is not None:  # point contact: snapshots are [T, Y, X]
                f.create_dataset("Y", data=self.Y)
            g = f.create_group("series")
            for k in (*SERIES, *sorted(set(self.series) - set(SERIES))):
                g.create_dataset(k, data=np.asarray(self.series[k], dtype=float))
            steps = sorted(self.snapshots)
            s = f.create_group("snapshots")
            s.create_dataset("step", data=np.asarray(steps, dtype=np.int64))
            s.create_dataset("T", data=np.asarray([self.series["T"][i] for i in steps]))
            for name in ("P", "H", "rho", "theta"):
                if name in self.snapshots[steps[-1]]:
                    s.create_dataset(name, data=np.array([self.snapshots[i][name] for i in steps]),
                                     **COMPRESSION)
            st = f.create_group("steady")
            st.create_dataset("P", data=self.steady.P)
            st.create_dataset("H", data=self.steady.H)
            if not self.complete and self.state is not None:
                g = f.create_group("state")
                for k in STATE_SCALARS:
                    g.attrs[k] = self.state[k]
                for k in STATE_STEP_SIZES:
                    if self.state.get(k) is not None:
                        g.attrs[k] = float(self.state[k])
                for k in STATE_ARRAYS:
                    if self.state.get(k) is not None:
                        g.create_dataset(k, data=self.state[k])

        return str(_write_atomic(path, write))



@dataclass
class PointTransientResult(TransientResult):
    """Answer of :func:`~.point_solve.solve_transient_point`: the series of :class:`TransientResult`
    (``Hc`` at X = Y = 0, ``Hm`` the minimum over the loaded zone, ``H0`` = H00, ``dH`` on the
    row through the feature's reference point) and snapshots of P, H ``[j, i]`` on ``(Y, X)``."""

    Y: np.ndarray | None = None
    yf: float = 0.0
    Hc_steady: float = math.nan
    Hm_steady: float = math.nan

    file_kind = "ehl_transient_point"

    def _problem_dict(self) -> dict[str, Any]:
        return self.problem.to_dict()

    def _zone(self, X: np.ndarray, Y: np.ndarray, r: float = 1.0) -> np.ndarray:
        """Nodes of ``(X, Y)`` inside ``r`` times the Hertzian ellipse."""
        boa = self.problem.b_over_a
        return X[None, :] ** 2 + (Y[:, None] / boa) ** 2 <= r**2

    def _fields(self, hz: Any) -> tuple[Any, Any]:
        return hz.fine, hz.fine

    def within(self, r: float) -> np.ndarray:
        """Nodes ``[j, i]`` inside ``r`` times the Hertzian ellipse."""
        return self._zone(self.X, self.Y, r)

    def _row(self, F: np.ndarray) -> np.ndarray:
        return F[int(np.argmin(np.abs(self.Y - self.yf)))]

    def _central_film(self, hz: Any, H: np.ndarray) -> float:
        return hz.central_film(hz.fine)

    def _film_constant(self, hz: Any) -> float:
        return hz.H00

    def _start_load_error(self, hz: Any) -> float:
        return hz.load(hz.fine) / hz.g_target - 1.0

    def steady_film(self, name: str) -> float:
        return getattr(self, f"{name}_steady")

    def _summary_head(self) -> dict[str, Any]:
        pb = self.problem
        return {"contact": "point", "M": pb.M, "L": pb.L, "theta": pb.theta,
                "points": int(self.X.size), "points_y": int(self.Y.size),
                "xmin": float(self.X[0]), "xmax": float(self.X[-1]), "ymax": float(self.Y[-1])}

    def _record_mass_balance(self, hz: Any, st: Any, n: int) -> None:
        bal = point_mass_balance(hz, terms=True) if n > 0 else {"balance": math.nan, "storage": math.nan}
        self.series["mass_balance"].append(bal["balance"])
        self.series.setdefault("storage", []).append(bal["storage"])
        # oil gained by the whole grid over the inflow (mass-conserving cavitation); NaN for
        # the projection, which counts every gap behind a rupture as full of oil. A run
        # continued from a file written before the series existed: NaN before it
        err = self.series.setdefault("mass_error", [math.nan] * (len(self.series["step"]) - 1))
        mc = n > 0 and isinstance(hz, CavitatedPointStepHierarchy)
        err.append(point_domain_mass_error(hz) if mc else math.nan)

    # -- observables ----------------------------------------------------------------------
    def load_fraction_below(self, threshold: float) -> list[float]:
        """Per kept step: the fraction of the load carried where ``H <= threshold``."""
        out = []
        for n in sorted(self.snapshots):
            P, H = self.snapshots[n]["P"], self.snapshots[n]["H"]
            out.append(float(P[H <= threshold].sum() / max(P.sum(), 1e-300)))
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


def _nanmax_abs(v: Any) -> float:
    a = np.abs(np.asarray(v, dtype=float))
    return float(np.nanmax(a)) if np.any(np.isfinite(a)) else math.nan


def _nanmean(v: Any) -> float:
    a = np.asarray(v, dtype=float)
    return float(np.nanmean(a)) if np.any(np.isfinite(a)) else math.nan


def _jsonable(v: Any) -> Any:
    if isinstance(v, (np.floating, np.integer)):
        return v.item()
    if isinstance(v, np.ndarray):
        return v.tolist()
    return str(v)


def load_series(path: str | os.PathLike) -> dict[str, Any]:
    """Read the series, snapshots and summary written by :meth:`TransientResult.to_hdf5`
    (with ``complete``, ``stop_reason``, ``run``, and ``state`` when the file holds one)."""
    import h5py

    with h5py.File(path, "r") as f:
        out: dict[str, Any] = {"summary": json.loads(f.attrs["summary"]), "X": f["X"][()],
                               "kind": str(f.attrs["kind"]),
                               # files written before the attribute existed were complete
                               "complete": bool(f.attrs.get("complete", True)),
                               "stop_reason": str(f.attrs.get("stop_reason", "")),
                               "run": json.loads(f.attrs.get("run", "{}"))}
        if "Y" in f:
            out["Y"] = f["Y"][()]
        out["series"] = {k: f["series"][k][()] for k in f["series"]}
        out["snapshots"] = {k: f["snapshots"][k][()] for k in f["snapshots"]}
        if "state" in f:
            g = f["state"]
            out["state"] = {**{k: g.attrs[k].item() for k in STATE_SCALARS},
                            **{k: g.attrs[k].item() for k in STATE_STEP_SIZES if k in g.attrs},
                            **{k: g[k][()] if k in g else None for k in STATE_ARRAYS}}
    return out
