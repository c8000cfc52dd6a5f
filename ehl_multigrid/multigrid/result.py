"""The one result type of every EHL solve (line, point, FAS or Newton path).

In the spirit of scipy's ``OptimizeResult``: the fields and films, ``success``, a ``status``
code from :data:`STATUS`, a ``message``, the cycle count, work units, residual and load-error
histories and the wall time, so callers never parse printed text. The scalars of the contact
(``Hc``, ``Hm``, ``p_spike``, ...) read as attributes (``sol.Hc``); ``to_result()`` gives the
package's HDF5 :class:`~ehl_multigrid.model.results.Result`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..model.convergence import ConvergenceReport
from ..model.results import Result, ScalarAccess

#: status code -> name
STATUS = {
    0: "converged",     # residual and load error below their tolerances
    1: "max_cycles",    # the cycle budget ran out first
    2: "stalled",       # the residual stopped falling and the policy had nothing left to try
    3: "diverged",      # every retry of a cycle was rejected, or the iterate holds NaN/inf
    4: "stopped",       # the callback raised StopIteration
    5: "start_failed",  # no usable solution on the start grid
    6: "inaccurate",    # the iteration converged, but the estimated error exceeds the target
    7: "film_not_positive",  # the iteration converged to a discrete film <= 0 (grid too coarse)
    8: "residual_floor",  # the residual stopped falling below the policy's quiet level: tol too tight
    9: "mass_not_conserved",  # a starved result whose film carries more oil than supplied
    10: "time_budget",  # the time budget ran out during a solve, before it converged
}


@dataclass
class EHLResult(ScalarAccess):
    """Answer of an EHL solve.

    Attributes
    ----------
    success : bool -- the iteration met every tolerance and, when an accuracy was requested,
        the estimated errors of Hc and Hm meet it (``converged`` is an alias).
    status : int -- key of :data:`STATUS`; ``status_name`` its name.
    message : str -- why the solve stopped, and what to try when it failed.
    cycles : int -- accepted FAS cycles on all grids (Newton path: iterations).
    residual_history, load_error_history : finest-grid values after each cycle.
    work_units : float -- cost in finest-grid relaxation sweeps (NaN for the Newton path).
    wall_s : float -- wall time [s].
    actions : list of str -- robustness steps taken.
    history : per-cycle records (grid, cycle, residual, load error, Hc).
    contact : ``"line"`` or ``"point"``; solver : ``"fas"`` or ``"newton"``.
    problem, options : the dimensionless problem and the (immutable) options solved with.
    X, Y, P, H, H0 : grid (Y None for a line contact), pressure, film, film constant.
    scalars : contact observables (``Hc``, ``Hm``, ``Hc_error``, ``Hm_error`` ...), also
        readable as attributes.
    error : :class:`~ehl_multigrid.multigrid.accuracy.ErrorEstimate` (relative errors of Hc
        and Hm, budget {grid, domain, algebraic}); accuracy : the requested target or None.
    """

    status: int
    message: str
    cycles: int = 0
    residual_history: np.ndarray = field(default_factory=lambda: np.zeros(0))
    load_error_history: np.ndarray = field(default_factory=lambda: np.zeros(0))
    work_units: float = math.nan
    wall_s: float = math.nan
    actions: list[str] = field(default_factory=list)
    history: list[Any] = field(default_factory=list)
    fmg: list[dict[str, float]] = field(default_factory=list)
    tolerances: dict[str, float] = field(default_factory=dict)
    settings: Any = None
    start_level: int = 0
    status_name: str = ""
    success: bool = False
    contact: str = ""
    solver: str = "fas"
    problem: Any = None
    options: Any = None
    X: np.ndarray | None = None
    Y: np.ndarray | None = None
    P: np.ndarray | None = None
    H: np.ndarray | None = None
    H0: float = math.nan
    half: bool = False
    levels: int = 0
    scene: Any = None
    scalars: dict[str, Any] = field(default_factory=dict)
    extra: dict[str, Any] = field(default_factory=dict)
    builder: Callable[[EHLResult, Any], Result] | None = field(default=None, repr=False)
    error: Any = None
    accuracy: float | None = None

    def __post_init__(self) -> None:
        self.status_name = STATUS[self.status]
        self.success = self.status == 0

    def set_status(self, status: int, message: str) -> None:
        self.status, self.message = status, message
        self.status_name = STATUS[status]
        self.success = status == 0

    # -- aliases --------------------------------------------------------------------------
    @property
    def converged(self) -> bool:
        return self.success

    @property
    def H00(self) -> float:
        return self.H0

    @property
    def iterations(self) -> int:
        return self.cycles

    @property
    def output(self) -> EHLResult:
        """Deprecated: the result is its own output now."""
        return self

    # -- views ----------------------------------------------------------------------------
    @property
    def report(self) -> ConvergenceReport:
        """The convergence part as the package's :class:`ConvergenceReport` (HDF5 history)."""
        ex = dict(self.extra)
        per_level = [r.level_residuals for r in self.history]
        width = max((len(v) for v in per_level), default=0)
        lvl = np.full((len(per_level), max(width, 1)), np.nan)
        for i, v in enumerate(per_level):
            lvl[i, : len(v)] = v
        ex.update({
            "level_residuals": lvl,
            "status": self.status_name,
            "actions": list(self.actions),
            "cycle_level": np.array([r.level for r in self.history], dtype=int),
            "cycle_residual": np.array([r.residual for r in self.history], dtype=float),
            "cycle_load_error": np.array([r.load_error for r in self.history], dtype=float),
            "cycle_Hc_venner": np.array([r.Hc for r in self.history], dtype=float),
            "cycle_work_units": np.array([r.work_units for r in self.history], dtype=float),
            "fmg_points": np.array([d["points"] for d in self.fmg], dtype=int),
            "fmg_Hc_venner": np.array([d["Hc"] for d in self.fmg], dtype=float),
        })
        return ConvergenceReport(
            converged=self.success, message=self.message, iterations=self.cycles,
            residual_history=np.asarray(self.residual_history, dtype=float),
            load_error_history=np.asarray(self.load_error_history, dtype=float),
            tolerances=dict(self.tolerances), work_units=self.work_units, wall_s=self.wall_s,
            extra=ex)

    def to_result(self, scene: Any = None) -> Result:
        """The package :class:`Result` (kind ``"ehl_line"`` or ``"ehl_point"``)."""
        if self.builder is None:
            raise TypeError("this result has no field builder")
        return self.builder(self, self.scene if scene is None else scene)

    def payload(self) -> dict[str, Any]:
        """The JSON payload of ``ehl solve``: the contact's scalars plus the solve outcome."""
        keys = ["Hc", "Hm", "Hc_venner", "Hm_venner", "hc", "hm", "p_spike", "load_error",
                "levels", "points", "cycles", "wall_s", "converged", "X_Hm", "X_spike",
                "residual", "work_units", "M", "L", "theta", "pmax", "alpha_bar", "lambda_venner",
                "Hc_dpdx0", "X_dpdx0", "Y_Hm", "Hm_centerline", "P_max", "H00", "final_residual",
                "Hc_error", "Hm_error", "wall_total_s", "estimate_s"]
        out = {k: self.scalars[k] for k in keys if k in self.scalars}
        if self.error is not None:
            out["error_budget"] = self.error.budget
            out["accuracy"] = self.accuracy
        out.update(status=self.status_name, message=self.message, solver=self.solver,
                   actions=list(self.actions))
        return out


def tightened(previous: EHLResult, tight: EHLResult, options: Any = None) -> EHLResult:
    """``tight``, a solve started on its finest grid from the converged ``previous`` of the same
    discrete problem (grid, box, cells) with tighter tolerances, as if ``previous`` had run its
    extra cycles: the FMG films, the histories and the work of both, and ``options`` (those the
    sequence asked for, without the relaxation settings the continuation was started with: the
    domain probes derive theirs from them and reuse their looser probes). The error estimate then
    takes the grid part from the FMG films and the iteration part from the last finest-grid
    cycles, as for one solve (a tolerance step of the accuracy loop costs its extra cycles,
    not a new FMG solve)."""
    tight.fmg = list(previous.fmg)
    if options is not None:
        tight.options = options
    tight.history = list(previous.history) + list(tight.history)
    tight.residual_history = np.concatenate([previous.residual_history, tight.residual_history])
    tight.load_error_history = np.concatenate([previous.load_error_history, tight.load_error_history])
    tight.cycles += previous.cycles
    tight.work_units += previous.work_units
    tight.actions[:0] = list(previous.actions)
    for key in ("cycles", "work_units"):
        if isinstance(tight.scalars.get(key), (int, float)):
            tight.scalars[key] = getattr(tight, key)
    tight.actions.append(f"tolerance step: cycles continued from the converged solve at the looser "
                         f"tolerance ({previous.cycles} cycles before, {len(tight.history) - len(previous.history)} after)")
    return tight


def ended_relaxation(previous: EHLResult) -> dict[str, Any]:
    """The relaxation settings ``previous`` ended with (the policy may have damped them), as
    option fields: a tolerance step continues with them."""
    st = previous.settings
    return dict(omega=st.omega, omega_jd=st.omega_jd, h00_gain=st.h00_gain, cycle=st.cycle)


def tightening(previous: EHLResult, options: Any, same: tuple[str, ...] = ("points", "xmin", "xmax", "ymax")) -> bool:
    """Whether ``options`` ask for the discrete problem ``previous`` was solved for (the option
    fields ``same`` equal) with tighter residual, load or film tolerances: a tolerance step that
    :func:`tightened` can continue."""
    before = previous.options
    if before is None or any(getattr(before, k, None) != getattr(options, k, None) for k in same):
        return False
    ft0, ft1 = getattr(before, "film_tol", None), getattr(options, "film_tol", None)
    return (options.tol < before.tol or options.tol_load < before.tol_load
            or (ft0 is not None and ft1 is not None and ft1 < ft0))
