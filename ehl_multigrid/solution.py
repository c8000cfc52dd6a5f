"""The result contract of the front door :func:`ehl_multigrid.solve`: one frozen, typed answer
for every physics (steady, starved, thermal, transient).

* :class:`Status` -- the status codes of every solve (the table of
  :data:`ehl_multigrid.multigrid.result.STATUS`, same numbers and names);
* :class:`Outcome` -- how the solve ended: ``success``, ``status``, ``message``, wall time,
  work units, iterations and the robustness actions taken;
* :class:`ErrorEstimate` -- the estimated relative errors of Hc and Hm, split into named parts
  (:class:`PartError`: ``grid``, ``domain``, ``iteration``, ``time``, ``nz`` ...), the part
  that dominates and the verdict against the accuracy asked for;
* :class:`Grid` -- the finest grid and the box it covers;
* :class:`Solution` -- the films (Moes ``Hc``, ``Hm``; metres ``hc``, ``hm``), read-only
  ``fields``, ``grid``, ``error``, ``outcome`` and the physics' own quantities in ``details``
  (:class:`StarvedDetails`, :class:`ThermalDetails`, :class:`TransientDetails`; None for a
  steady solve), composed, never as string keys;
* :class:`MoesProblem` -- a problem given by the Moes groups alone (no scene).

``raw`` of a :class:`Solution` is the underlying solver's own result object; it is there for
the transition from the older entry points and its type is not part of the contract.

This module imports no solver (``import ehl_multigrid`` stays free of numba).
"""

from __future__ import annotations

import enum
import math
import numbers
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, fields, is_dataclass
from types import MappingProxyType
from typing import Any

import numpy as np

from .model.constants import MOES_ONLY_DEFAULTS, THETA_MAX, THETA_MIN
from .model.errors import InputError, require_choice, require_range

PHYSICS = ("steady", "starved", "thermal", "transient")
CONTACTS = ("line", "point", "elliptic")


class Status(enum.IntEnum):
    """Status of a solve: the codes of :data:`ehl_multigrid.multigrid.result.STATUS`.

    Only ``CONVERGED`` is a success. ``label`` is the lower-case name the older results and
    the command line use (``status_name``, ``"max_cycles"`` ...)."""

    CONVERGED = 0  # every tolerance met and, with an accuracy target, the estimate meets it
    MAX_CYCLES = 1  # the cycle (or outer-iteration) budget ran out first
    STALLED = 2  # the residual stopped falling and the policy had nothing left to try
    DIVERGED = 3  # every retry was rejected, or the iterate holds NaN/inf
    STOPPED = 4  # the callback raised StopIteration
    START_FAILED = 5  # no usable solution on the start grid (or no start at all)
    INACCURATE = 6  # the iteration converged, but the estimated error exceeds the target
    FILM_NOT_POSITIVE = 7  # a film <= 0 (grid too coarse, or a feature cutting through it)
    RESIDUAL_FLOOR = 8  # the residual stopped falling at the policy's quiet level: tol too tight
    MASS_NOT_CONSERVED = 9  # a starved result whose film carries more oil than supplied
    TIME_BUDGET = 10  # the time budget ran out during a solve, before it converged

    @property
    def label(self) -> str:
        """The lower-case name (``"converged"``, ``"max_cycles"`` ...)."""
        return self.name.lower()

    @classmethod
    def from_label(cls, label: str) -> Status:
        """The member of a lower-case name (``Status.from_label("stalled")``)."""
        try:
            return cls[str(label).upper()]
        except KeyError:
            raise InputError(f"status = {label!r} is not one of {[s.label for s in cls]}") from None


def as_float(value: Any) -> float:
    """A float, NaN for None or anything that is not a number."""
    if value is None or isinstance(value, bool):
        return math.nan
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan


def frozen_array(values: Any) -> np.ndarray:
    """A read-only copy of ``values`` (the solver's own array stays writable and unshared)."""
    out = np.array(values, copy=True)
    out.setflags(write=False)
    return out


def frozen_fields(arrays: Mapping[str, Any]) -> Mapping[str, np.ndarray]:
    """A read-only mapping of read-only copies (entries that are None are left out)."""
    return MappingProxyType({k: frozen_array(v) for k, v in arrays.items() if v is not None})


@dataclass(frozen=True)
class PartError:
    """One part of an error estimate: the relative errors of Hc and Hm it contributes (NaN
    when that part could not be measured)."""

    Hc: float
    Hm: float

    @property
    def worst(self) -> float:
        """``max(Hc, Hm)``; NaN when either is NaN."""
        return max(self.Hc, self.Hm) if not (math.isnan(self.Hc) or math.isnan(self.Hm)) else math.nan


@dataclass(frozen=True)
class ErrorEstimate:
    """Estimated relative errors of the central and minimum film.

    Attributes
    ----------
    Hc, Hm : float -- estimated relative errors (the sum of the parts); NaN when not estimated
        or when a part could not be measured (such a result cannot be called accurate).
    parts : mapping of part name -> :class:`PartError`, read-only. Names: ``grid`` (mesh along
        X, Richardson), ``domain`` (box truncation), ``iteration`` (algebraic: what the
        iteration and the load error leave; for starved solves also the supply mismatch),
        ``nz`` (thermal: intervals across the film), ``isothermal`` (thermal point films anchored
        on the core's isothermal films: that reference's error), ``time`` (transient: the time step).
    target : float or None -- the accuracy asked for.
    notes : tuple of str -- how the parts were measured.
    """

    Hc: float = math.nan
    Hm: float = math.nan
    parts: Mapping[str, PartError] = field(default_factory=lambda: MappingProxyType({}))
    target: float | None = None
    notes: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if not isinstance(self.parts, MappingProxyType):
            object.__setattr__(self, "parts", MappingProxyType(dict(self.parts)))
        object.__setattr__(self, "notes", tuple(self.notes))

    @property
    def dominant(self) -> str | None:
        """The part with the largest ``max(Hc, Hm)`` among those measured; None when none was."""
        known = {k: p.worst for k, p in self.parts.items() if math.isfinite(p.worst)}
        return max(known, key=known.__getitem__) if known else None

    @property
    def meets_target(self) -> bool:
        """True when a target was given and both estimated errors are known and within it;
        False without a target (nothing was judged) or with an unknown error."""
        if self.target is None:
            return False
        # (max() would pass over a NaN: each error is checked)
        return all(math.isfinite(e) and e <= self.target for e in (self.Hc, self.Hm))


@dataclass(frozen=True)
class Outcome:
    """How a solve ended.

    Attributes
    ----------
    success : bool -- the iteration converged and, with an accuracy target, the estimated
        errors of Hc and Hm meet it (``status`` is then ``Status.CONVERGED``).
    status : :class:`Status`; message : why it stopped, and what to try when it failed.
    wall_s : seconds of the whole solve (refinements, estimates and probes included).
    work_units : cost in finest-grid relaxation sweeps of the returned solve (NaN when the
        solver does not count them).
    iterations : multilevel cycles of the returned solve (thermal: outer iterations;
        transient: the cycles of all time steps).
    actions : robustness steps taken (retries, continuation, fallbacks), in order.
    """

    success: bool
    status: Status
    message: str
    wall_s: float = math.nan
    work_units: float = math.nan
    iterations: int = 0
    actions: tuple[str, ...] = ()


@dataclass(frozen=True)
class Grid:
    """The finest grid of a solution.

    ``points`` along X, ``points_y`` along Y (None for a line contact), ``levels`` of the
    multilevel hierarchy (None when the solver does not report them), ``box`` the contact's
    domain in units of the Hertzian half-width: ``(xmin, xmax)`` for a line contact (a starved
    line contact's box starts at the meniscus), ``(xmin, xmax, ymin, ymax)`` for point and
    elliptic ones; ``half`` -- only ``Y >= 0`` of it was solved (the symmetric half of a smooth
    contact; the fields then cover that half)."""

    points: int
    points_y: int | None = None
    levels: int | None = None
    box: tuple[float, ...] = ()
    half: bool = False


@dataclass(frozen=True)
class StarvedDetails:
    """What a starved (mass-conserving, Elrod-Adams) solve adds: the meniscus position
    ``meniscus_x`` (X = x/b or x/a; -inf when the supply floods the inlet), the flooded films of
    the same discretisation (Moes ``Hc_flooded``, ``Hm_flooded``) and the ratios to them, the
    relative ``mass_balance_error``, the supplied layer ``hoil`` [m] and ``rho_c_Hc_over_hoil``
    (1 in the severe-starvation limit of rolling)."""

    meniscus_x: float = math.nan
    Hc_flooded: float = math.nan
    Hm_flooded: float = math.nan
    Hc_ratio: float = math.nan
    Hm_ratio: float = math.nan
    mass_balance_error: float = math.nan
    hoil: float = math.nan
    rho_c_Hc_over_hoil: float = math.nan
    inlet_flooded: bool | None = None


@dataclass(frozen=True)
class ThermalDetails:
    """What a thermal (TEHL) solve adds: the isothermal films on the same grid (Moes), the
    friction [N] and its coefficient, the decoupled friction (the thermal model on the
    isothermal film) [N], the largest temperature ``T_max`` [degC], the interior heat-balance
    error, the heat partition (into solid 1, solid 2), the slip, ``nz`` intervals across the
    film, the outer iterations, the estimated errors of the friction coefficient (relative) and
    of ``T_max`` [K], and for a starved line contact the :class:`StarvedDetails`."""

    Hc_isothermal: float = math.nan
    Hm_isothermal: float = math.nan
    friction: float = math.nan
    friction_coefficient: float = math.nan
    friction_decoupled: float = math.nan
    T_max: float = math.nan
    heat_balance_error: float = math.nan
    heat_partition: tuple[float, float] = (math.nan, math.nan)
    slip: float = math.nan
    nz: int = 0
    outer_iterations: int = 0
    friction_coefficient_error: float = math.nan
    T_max_error_K: float = math.nan
    starved: StarvedDetails | None = None


@dataclass(frozen=True, eq=False)  # (holds arrays: compared by identity)
class TransientDetails:
    """What a transient run adds: the times ``times`` (Venner's ``T = t u_m/b``, point
    ``t u_m/a``; step 0 is the start) and the central and minimum films at each (Moes
    ``Hc_series``, ``Hm_series``; metres ``hc_series``, ``hm_series``; read-only arrays);
    ``complete`` (False: the run ended before its last planned step, ``stop_reason`` says
    why), the steps done and planned, the time step ``dt``, the scheme, the feature
    (its description), the smooth steady films (Moes), the extremes over the run (Moes), the
    steps accepted with a stalled residual, and notes (e.g. on the oil supply)."""

    times: np.ndarray
    Hc_series: np.ndarray
    Hm_series: np.ndarray
    hc_series: np.ndarray
    hm_series: np.ndarray
    complete: bool = True
    stop_reason: str = ""
    steps: int = 0
    planned_steps: int = 0
    dt: float = math.nan
    scheme: str = ""
    feature: Mapping[str, Any] = field(default_factory=lambda: MappingProxyType({}))
    Hc_steady: float = math.nan
    Hm_steady: float = math.nan
    Hc_min: float = math.nan
    Hc_max: float = math.nan
    Hm_min: float = math.nan
    stalled_steps: int = 0
    notes: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        for name in ("times", "Hc_series", "Hm_series", "hc_series", "hm_series"):
            object.__setattr__(self, name, frozen_array(np.asarray(getattr(self, name), dtype=float)))
        if not isinstance(self.feature, MappingProxyType):
            object.__setattr__(self, "feature", MappingProxyType(dict(self.feature)))
        object.__setattr__(self, "notes", tuple(self.notes))


@dataclass(frozen=True, eq=False)  # (holds arrays: compared by identity)
class Solution:
    """The answer of :func:`ehl_multigrid.solve`, the same for every physics.

    Attributes
    ----------
    physics : ``"steady"``, ``"starved"``, ``"thermal"`` or ``"transient"``.
    contact : ``"line"``, ``"point"`` or ``"elliptic"``.
    outcome : :class:`Outcome` (``success``, ``status``, ``message`` are also properties here).
    Hc, Hm : central (X = 0, Y = 0) and minimum film, Moes-scaled (transient: at the last
        completed step; the series are in ``details``); NaN when the solve produced none.
    hc, hm : the same in metres (NaN for a Moes-only problem).
    error : :class:`ErrorEstimate`.
    fields : read-only mapping of name -> read-only array: ``X`` (and ``Y`` for point contacts)
        in units of the Hertzian half-width, ``P`` = p/pmax and ``H`` (Venner's film) on
        them (point arrays ``[j, i]`` over ``(Y, X)``), plus the physics' own (``theta``: film
        content; ``T``, ``Z``, ``tau`` or ``T_mid``, ``T_surface1``, ``T_surface2``: thermal).
    grid : :class:`Grid`.
    details : :class:`StarvedDetails`, :class:`ThermalDetails`, :class:`TransientDetails`,
        or None (steady).
    raw : the underlying solver's result object -- unstable: its type changes when the solvers
        move behind the front door; for the transition only.
    scene : the :class:`~ehl_multigrid.model.scene.Scene` solved (None for a Moes-only
        problem).
    """

    physics: str
    contact: str
    outcome: Outcome
    Hc: float = math.nan
    Hm: float = math.nan
    hc: float = math.nan
    hm: float = math.nan
    error: ErrorEstimate = field(default_factory=ErrorEstimate)
    fields: Mapping[str, np.ndarray] = field(default_factory=lambda: MappingProxyType({}))
    grid: Grid | None = None
    details: StarvedDetails | ThermalDetails | TransientDetails | None = None
    raw: Any = field(default=None, repr=False, compare=False)
    scene: Any = field(default=None, repr=False, compare=False)
    _result_builder: Callable[[], Any] | None = field(default=None, repr=False, compare=False)

    def __post_init__(self) -> None:
        require_choice("physics", self.physics, PHYSICS)
        require_choice("contact", self.contact, CONTACTS)
        if not isinstance(self.fields, MappingProxyType) or any(
                v.flags.writeable for v in self.fields.values()):
            object.__setattr__(self, "fields", frozen_fields(self.fields))

    # -- outcome --------------------------------------------------------------------------
    @property
    def success(self) -> bool:
        return self.outcome.success

    @property
    def status(self) -> Status:
        return self.outcome.status

    @property
    def message(self) -> str:
        return self.outcome.message

    # -- views ----------------------------------------------------------------------------
    def to_result(self) -> Any:
        """The package's HDF5 :class:`~ehl_multigrid.model.results.Result` (``.save(path)``)
        of the solution, with its outcome and error estimate (:func:`record_solution`).

        Raises
        ------
        TypeError
            When it cannot: a solve that ended without fields.
        """
        if self._result_builder is None:
            raise TypeError(f"this {self.physics} solution has no package Result (the solve produced no fields)")
        return record_solution(self._result_builder(), self)

    def summary(self) -> dict[str, Any]:
        """Plain scalars (for JSON): physics, contact, outcome, films, errors, grid and the
        scalar quantities of ``details`` (sequences and arrays left out)."""
        e = self.error
        out: dict[str, Any] = {
            "physics": self.physics, "contact": self.contact, "success": bool(self.success),
            "status": self.status.label, "message": self.message, "wall_s": as_float(self.outcome.wall_s),
            "work_units": as_float(self.outcome.work_units), "iterations": int(self.outcome.iterations),
            "Hc": as_float(self.Hc), "Hm": as_float(self.Hm), "hc": as_float(self.hc), "hm": as_float(self.hm),
            "Hc_error": as_float(e.Hc), "Hm_error": as_float(e.Hm), "error_dominant": e.dominant,
            "accuracy": e.target, "meets_target": bool(e.meets_target),
        }
        if self.grid is not None:
            out.update(points=self.grid.points, points_y=self.grid.points_y, levels=self.grid.levels)
        if self.details is not None:
            out.update(_scalars_of(self.details))
        return out


def record_solution(result: Any, sol: Solution) -> Any:
    """``result`` (a package :class:`~ehl_multigrid.model.results.Result` of ``sol``) with the
    outcome and error estimate of ``sol``, written the same way for every physics.

    Scalars ``status`` (``Status.label``), ``message``, ``success``, ``Hc_error``, ``Hm_error``
    (NaN when not estimated) and the physics' own stated errors (thermal:
    ``friction_coefficient_error``, relative, and ``T_max_error_K``); meta ``physics``,
    ``error_budget`` (part name -> ``{"Hc", "Hm"}``, the names of ``sol.error.parts``),
    ``error_notes`` and ``accuracy`` (the target, None without one). Returns ``result``.
    """
    e = sol.error
    result.set_scalar("status", sol.status.label)
    result.set_scalar("message", sol.message)
    result.set_scalar("success", bool(sol.success))
    result.set_scalar("Hc_error", as_float(e.Hc))
    result.set_scalar("Hm_error", as_float(e.Hm))
    if isinstance(sol.details, ThermalDetails):
        result.set_scalar("friction_coefficient_error", as_float(sol.details.friction_coefficient_error))
        result.set_scalar("T_max_error_K", as_float(sol.details.T_max_error_K), "K")
    result.meta["physics"] = sol.physics
    result.meta["error_budget"] = {name: {"Hc": p.Hc, "Hm": p.Hm} for name, p in e.parts.items()}
    result.meta["error_notes"] = list(e.notes)
    result.meta["accuracy"] = e.target
    return result


def _scalars_of(obj: Any, prefix: str = "") -> dict[str, Any]:
    """Scalar fields of a details dataclass (nested dataclasses flattened with a prefix)."""
    out: dict[str, Any] = {}
    for f in fields(obj):
        v = getattr(obj, f.name)
        if is_dataclass(v):
            out.update(_scalars_of(v, f"{f.name}_"))
        elif isinstance(v, (bool, np.bool_)):
            out[prefix + f.name] = bool(v)
        elif isinstance(v, (int, np.integer)):
            out[prefix + f.name] = int(v)
        elif isinstance(v, (float, np.floating)):
            out[prefix + f.name] = float(v)
        elif isinstance(v, str):
            out[prefix + f.name] = v
    return out


@dataclass(frozen=True)
class MoesProblem:
    """A contact given by the Moes groups alone (no scene): solved steady and isothermal.

    Attributes
    ----------
    contact : ``"line"``, ``"point"`` (circular) or ``"elliptic"``.
    M, L : Moes load and lubricant parameters.
    theta : ellipticity ``Rx/Ry`` (1 for line and point contacts; elliptic: in [0.01, 100],
        not 1).
    viscosity : ``"roelands"`` or ``"barus"`` (None: Roelands); density:
        ``"dowson-higginson"`` or ``"incompressible"`` (None: Dowson-Higginson).
    alpha [1/Pa], eta0 [Pa s], p0 [Pa] : oil data (None: the package's Moes-only defaults,
        :data:`~ehl_multigrid.model.constants.MOES_ONLY_DEFAULTS`).

    Validated at construction: a value out of range raises
    :class:`~ehl_multigrid.model.errors.InputError` naming the field, the value and the
    allowed range (the contact's solver problem is built to check it, with its ranges).
    """

    contact: str
    M: float
    L: float
    theta: float = 1.0
    viscosity: str | None = None
    density: str | None = None
    alpha: float | None = None
    eta0: float | None = None
    p0: float | None = None

    def __post_init__(self) -> None:
        require_choice("contact", self.contact, CONTACTS)
        require_range("theta", self.theta, THETA_MIN, THETA_MAX, "- (Rx/Ry)")
        if self.contact in ("line", "point") and self.theta != 1.0:
            raise InputError(f"theta = {self.theta:g} applies to contact = 'elliptic'; a {self.contact} "
                             f"contact has theta = 1")
        if self.contact == "elliptic" and self.theta == 1.0:
            raise InputError("theta = 1 with contact = 'elliptic' is a circular contact: give "
                             "contact = 'point', or theta in [0.01, 100] other than 1")
        for name, what in (("M", "load"), ("L", "lubricant")):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, numbers.Real):
                raise InputError(f"{name} = {value!r} is not a number (the Moes {what} parameter)")
        # the solver problem checks every value against its own ranges, which differ by contact
        # (line M in [0.1, 20000], point M in (0, 1e6]: the message names the contact's); a lazy
        # import: the solvers' modules load numba
        self.solver_problem()

    @property
    def oil(self) -> dict[str, float]:
        """``alpha``, ``eta0``, ``p0`` as given, the defaults filled in."""
        return {k: MOES_ONLY_DEFAULTS[k] if getattr(self, k) is None else float(getattr(self, k))
                for k in ("alpha", "eta0", "p0")}

    def solver_problem(self) -> Any:
        """The contact's dimensionless problem (:class:`~ehl_multigrid.line.LineProblem` or
        :class:`~ehl_multigrid.point.PointProblem`)."""
        law = {"viscosity": self.viscosity or "roelands", "density": self.density or "dowson-higginson"}
        if self.contact == "line":
            from .line.problem import LineProblem

            return LineProblem.from_moes(self.M, self.L, alpha=self.alpha, eta0=self.eta0, p0=self.p0, **law)
        from .point.problem import problem_from_moes

        return problem_from_moes(self.M, self.L, self.theta, law["viscosity"], law["density"],
                                 self.alpha, self.eta0, self.p0)
