"""Error budget of a TEHL solution (line or point) and the accuracy-driven TEHL solve.

A TEHL result is judged as an isothermal one (:mod:`ehl_multigrid.multigrid.accuracy`): its
error is estimated in parts, and a result is converged only when its outer iteration
converged AND the estimate meets the requested accuracy.

Parts of the budget (relative for Hc, Hm and the friction coefficient, kelvin for T_max):

* ``grid_x`` -- Richardson along the rolling direction from a solve on every other node,
  ``|q_h - q_2h| / (2^p - 1)`` with the measured order ``p`` of :data:`ORDERS`, times the
  core's :data:`~ehl_multigrid.multigrid.accuracy.GRID_SAFETY` (at the measured order the
  Richardson value is the error itself, with nothing to spare: on the appendix C line
  contacts at 513 points it came within 2-5 % of the error against a solve one level finer,
  scaled to the limit);
* ``grid_z`` -- the same across the film from a solve on ``nz / 2`` intervals;
* ``domain`` -- the change of the solution when the box is doubled at equal mesh size,
  measured by two TEHL solves on a coarser grid (:func:`domain_change`), times the core's
  :data:`~ehl_multigrid.multigrid.accuracy.DOMAIN_SAFETY`;
* ``iteration`` -- the last outer change divided by the damping it was made with (the
  stopping rule's measure of the distance to the fixed point), and at least the films'
  alternation between the inner multilevel cycles; for a starved solve plus the meniscus
  search's supply mismatch ``|F/Hoil - 1|`` (the film follows the supply it carries).

A starved line solve (finite ``[supply] hoil``) is estimated at fixed supply: the coarser
solves are starved solves with their own meniscus search, and the domain part is 0 (the box
starts at the meniscus), as for the isothermal starved solver.

``total`` is their sum; it is NaN when a part could not be measured (a coarser solve or
the box probe did not converge), and such a result cannot be called accurate.

**Anchored films** (point contacts with a target the direct estimate misses,
:func:`anchored_estimate`): the thermal film is reported as the thermal/isothermal ratio of its
grid times the isothermal film converged by the core, ``H = (H_h / H_iso,h) H_iso*``. The ratio
converges long before the films do, since the grid errors of the thermal and isothermal films
of one grid largely cancel (the default ball at 0.5 m/s, slip 1: Hc ratio 0.9402, 0.9432,
0.9438 on 513-2049 points, where the isothermal Hc moves 4.3 % and 1.0 %). Its parts: the
ratio's ``grid_x`` (Richardson on the ratio, order 1.5 for Hc, 1 for Hm, whose ratio converges
irregularly), the ratio's ``domain`` change, ``grid_z`` and ``iteration`` as above, and
``isothermal``, the reference's own estimated error.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ehl_multigrid.model.errors import ConvergenceError, InputError, require_range
from ehl_multigrid.model.scene import Scene
from ehl_multigrid.multigrid.accuracy import (
    DOMAIN_DECAY,
    DOMAIN_REUSE_BELOW,
    DOMAIN_SAFETY,
    GRID_SAFETY,
    extrapolated,
    richardson,
)
from ehl_multigrid.multigrid.controller import (
    Candidate,
    Refinement,
    Resolution,
    TimeBudgetSpent,
    control,
)
from ehl_multigrid.point.postprocess import subgrid_min_film

from ..traction import wall_speeds
from .options import TEHLOptions
from .outer import CoarseStartError
from .point import require_flooded_point

#: orders (along X, across the film) of the TEHL discretisation in the estimate: the observed
#: orders, except 1.5 along X for point contacts, below the minimum film's (the core caps Hm's
#: order at 1.5 too; docs/thermal.md, "Orders of the TEHL error estimate")
ORDERS = {"line": (2.0, 2.0), "point": (1.5, 2.0)}
#: the order along X of the minimum film's grid part, at most: a line contact's Hm converges
#: irregularly, as the core's does (the spur gear at S = 1: ratios 6.1, 2.4, 3.5 on 257-2049
#: points; at second order its 513-point Hm stated 1.66 % for a true 1.87 %; docs/thermal.md)
HM_ORDER_X = 1.5
#: the parts of a TEHL error budget
PARTS = ("grid_x", "grid_z", "domain", "iteration")
#: the result contract's name of each part (``Solution.error.parts``, saved files, ``--json``)
CONTRACT_PARTS = {"grid_x": "grid", "grid_z": "nz", "domain": "domain", "iteration": "iteration",
                  "isothermal": "isothermal"}
#: share of the target the isothermal reference of an anchored estimate is solved to
ANCHOR_SHARE = 0.5
#: orders along X of the thermal/isothermal film ratios in an anchored estimate: Hc's ratio
#: converged at order 2.2-2.3 on the default ball (0.5 m/s, slip 1, 257-2049 points), Hm's
#: alternated (+4.1 %, -0.6 %, +0.35 %), so first order (docs/thermal.md, "Anchored films")
RATIO_ORDERS = {"Hc": 1.5, "Hm": 1.0}
#: quantities of the budget; the accuracy target applies to the films
QUANTITIES = ("Hc", "Hm", "friction_coefficient", "T_max")
#: largest pressure change between neighbouring nodes (p/pmax) at which T_max's grid part is
#: estimated: a steeper outlet drop is not resolved, and the heating peak at it appears only on
#: finer grids (rolling line contacts: it appeared where the drop fell to 0.056-0.089 per node)
RESOLVED_PRESSURE_STEP = 0.05
#: temperature changes between grids [K] below which T_max's grid part does not call a node's
#: change growing (round-off and the thermal march's tolerance, far below any thermometer)
T_SCATTER_K = 1e-3
#: smallest grid along X a TEHL solve takes (TEHLOptions)
MIN_POINTS = 65
#: smallest mesh (points per default box) of a point contact's box probe: the appendix D
#: point's outer iteration stalls on 65 (docs/thermal.md, "Extrapolated TEHL films")
POINT_PROBE_POINTS = 129
#: largest number of intervals across the film the refinement goes to
MAX_NZ = 80
#: default largest grid along X of the refinement (line, point)
MAX_POINTS = {"line": 16385, "point": 1025}


def _is_point(result: Any) -> bool:
    return getattr(result.scene, "kind", "line") != "line"


class SolveCache:
    """TEHL solves of one contact and slip keyed by ``(points, nz, box)``; a solve that raises a
    clear error (no convergence, a grid too coarse) is kept as ``None``. The estimate and the
    refinement share one cache, so a solve is never repeated. A flooded solve starts from the
    cached solve with half its intervals (same nz and box) when there is one (``coarse`` of
    :func:`~thermal.tehl.point.solve_tehl_point` and :func:`~thermal.tehl.line.solve_tehl_line`),
    and again from its own isothermal start when that start fails (:class:`CoarseStartError`).
    ``start``: a line solve of another slip on the grid and box of ``options``; the solve with
    exactly those options continues from it (:func:`~thermal.tehl.line.continuation`), the
    others (an estimate's coarser grids, a refinement) start on their own."""

    def __init__(self, scene: Scene, slip: float, options: TEHLOptions, point: bool,
                 start: Any = None) -> None:
        self.scene, self.slip, self.options, self.point = scene, float(slip), options, point
        self.results: dict[tuple[int, int, float], Any] = {}
        self.errors: dict[tuple[int, int, float], str] = {}
        #: wall seconds of each solve made (failed ones too), in the order made
        self.walls: list[tuple[tuple[int, int, float], float]] = []
        #: a starved solve's meniscus: where the searches of the other grids start
        self.meniscus: float | None = None
        self.start = start

    @classmethod
    def of(cls, result: Any) -> SolveCache:
        cache = cls(result.scene, result.slip, result.options, _is_point(result))
        cache.add(result)
        return cache

    def add(self, result: Any) -> None:
        o = result.options
        self.results[(o.points, o.nz, o.box)] = result
        xm = (getattr(result, "starved", None) or {}).get("meniscus_x")
        if self.meniscus is None and xm is not None and math.isfinite(xm):
            self.meniscus = float(xm)

    def __call__(self, points: int, nz: int, box: float) -> Any:
        key = (int(points), int(nz), float(box))
        if key not in self.results:
            t0 = time.perf_counter()
            self._solve(key)
            self.walls.append((key, time.perf_counter() - t0))
        return self.results[key]

    def _solve(self, key: tuple[int, int, float]) -> None:
        """Solve ``key`` = (points, nz, box) into :attr:`results` (None and the error when it fails)."""
        from .line import solve_tehl_line
        from .point import solve_tehl_point

        opts = self.options.with_changes(points=key[0], nz=key[1], box=key[2])
        coarser = self.results.get(((key[0] - 1) // 2 + 1, key[1], key[2]))
        warm: dict[str, Any] = {"meniscus": self.meniscus}
        o = self.options
        if self.start is not None and key == (int(o.points), int(o.nz), float(o.box)):
            from .line import continuation

            warm.update(continuation(self.start, self.scene))
            coarser = None  # the start is the solve's own (it sets the factors)
        if not self.point and math.isfinite(self.scene.supply.hoil):
            coarser = None  # a starved solve searches its own meniscus: no coarse start
        for start in ([coarser, None] if coarser is not None else [None]):
            try:
                if self.point:
                    res = solve_tehl_point(self.scene, self.slip, opts, coarse=start)
                else:
                    res = solve_tehl_line(self.scene, self.slip, opts, coarse=start, **warm)
            except (ConvergenceError, InputError) as exc:
                self.results[key] = None
                self.errors[key] = str(exc).splitlines()[0][:200]
                if isinstance(exc, CoarseStartError):
                    # the coarser grid's factors can start the finer grid's multilevel solve
                    # where it diverges (the spur gear at S = 0.5 on 2049 points): solved
                    # again from its own isothermal start
                    continue
                break
            if start is None and coarser is not None:
                res.report.extra.setdefault("actions", []).append(
                    f"the start from the factors of the {coarser.options.points}-point solve failed "
                    f"({self.errors.pop(key)}): solved from the isothermal start")
            self.results[key] = res
            self.add(res)
            break


def _value(result: Any, key: str) -> float:
    return float(getattr(result, key))


def _difference(key: str, q: float, other: float) -> float:
    """Relative difference (kelvin for T_max) of ``other`` from ``q``."""
    if key == "T_max":
        return abs(q - other)
    if q == other:
        return 0.0
    return abs(q - other) / abs(q) if q != 0.0 else math.inf


def _temperature_peaks(result: Any) -> tuple[np.ndarray | None, np.ndarray]:
    """The largest temperature across the film at each node [degC] and the nodes' X."""
    if _is_point(result):
        return getattr(result, "T_peak", None), result.X
    return result.T.max(axis=1), result.X


def peak_fields(*results: Any) -> tuple[list[np.ndarray], np.ndarray] | None:
    """The across-film temperature maxima of ``results`` (each grid with half the intervals
    of the one before, finest first) at the nodes of the coarsest, and those nodes' X. A line
    whose boxes differ (a starved inlet's meniscus) takes the finer fields interpolated onto the
    coarsest nodes they all cover. None when the fields cannot be compared (a point solve
    without them, point grids that do not nest)."""
    fields = [_temperature_peaks(r) for r in results]
    if any(T is None for T, _ in fields):
        return None
    Tc, Xc = fields[-1]
    if _is_point(results[0]):
        out = []
        for k, (T, X) in enumerate(fields):
            step = 2 ** (len(fields) - 1 - k)
            if T[::step, ::step].shape != Tc.shape or not np.allclose(X[::step], Xc, atol=1e-9):
                return None
            out.append(T[::step, ::step])
        return out, Xc
    inside = np.ones(Xc.shape, bool)
    for _, X in fields:
        inside &= (Xc >= X[0]) & (Xc <= X[-1])
    if not inside.any():
        return None
    return [np.interp(Xc[inside], X, T) for T, X in fields], Xc[inside]


def domain_change(result: Any, cache: SolveCache | None = None) -> dict[str, Any] | None:
    """Change of Hc, Hm, friction coefficient (relative) and T_max (K) when the box of
    ``result`` is doubled at equal mesh size: a TEHL solve on a quarter of its points (at least
    :data:`MIN_POINTS`; a half when that does not converge) and one on the doubled box at that
    mesh. None when neither pair converges.

    Why it bounds the box error of the TEHL solve: the probe is the TEHL solve itself, so it
    sees both ways the box enters -- the inlet pressure build-up of the Reynolds equation and
    the thermal inlet station, where the oil is held at the supply temperature and the warm
    back flow leaves. Both are far-field effects upstream of the contact that vary over the
    inlet length, not over the mesh, so the change measured on a coarser mesh is that of the
    fine one to within the coarse grid's error of a small difference; what is left beyond
    the doubled box the estimate bounds by :data:`~ehl_multigrid.multigrid.accuracy.DOMAIN_SAFETY`
    times the first doubling's change, the factor measured for the isothermal core (the
    whole box error 1.06-2.55 times the first doubling's change). Checked against a TEHL solve
    on a box four times the default in validation/tehl (part ``honesty``).
    """
    cache = cache or SolveCache.of(result)
    o = result.options
    # a point probe keeps at least POINT_PROBE_POINTS per default box: on a coarser mesh its
    # change is the mesh's, not the box's
    least = int(round((POINT_PROBE_POINTS - 1) * o.box)) + 1 if _is_point(result) else MIN_POINTS
    sizes = sorted({max((o.points - 1) // 4 + 1, least), max((o.points - 1) // 2 + 1, least)})
    for n in sizes:
        base = cache(n, o.nz, o.box)
        if base is None:
            continue
        wide = cache(2 * (n - 1) + 1, o.nz, 2.0 * o.box)
        if wide is None:
            continue
        out: dict[str, Any] = {k: _difference(k, _value(base, k), _value(wide, k)) for k in QUANTITIES}
        out["points"] = n
        # the thermal/isothermal ratios' change too (an anchored estimate's box part)
        rb, rw = film_ratios(base), film_ratios(wide)
        out.update({f"ratio_{k}": _difference(k, rb[k], rw[k]) for k in ("Hc", "Hm")})
        return out
    return None


@dataclass(frozen=True)
class IsothermalReference:
    """The isothermal films of a scene converged by the core (Moes ``Hc``, ``Hm``), their
    estimated relative errors, the grid (points along X) and the seconds it took."""

    Hc: float
    Hm: float
    error_Hc: float
    error_Hm: float
    points: int
    wall_s: float


def isothermal_reference(scene: Scene, accuracy: float, time_budget: float) -> IsothermalReference | None:
    """The scene's isothermal films solved by the core towards ``accuracy`` (the front door,
    ``physics="steady"``) within ``time_budget`` seconds, with the errors it states (a solve
    short of the target counts with its larger error); None when it failed or states none."""
    from ehl_multigrid import front
    from ehl_multigrid.solution import Status

    t0 = time.perf_counter()
    sol = front.solve(scene, physics="steady", accuracy=accuracy, options={"time_budget": time_budget})
    if sol.status not in (Status.CONVERGED, Status.INACCURATE) or not (
            math.isfinite(sol.error.Hc) and math.isfinite(sol.error.Hm)):
        return None
    return IsothermalReference(float(sol.Hc), float(sol.Hm), float(sol.error.Hc), float(sol.error.Hm),
                               int(sol.grid.points), time.perf_counter() - t0)


def film_ratios(result: Any) -> dict[str, float]:
    """Thermal over isothermal film of one TEHL solve (same grid and box)."""
    return {"Hc": result.Hc / result.Hc_isothermal, "Hm": result.Hm / result.Hm_isothermal}


def anchored_estimate(est: TEHLErrorEstimate, result: Any, cache: SolveCache,
                      ref: IsothermalReference) -> TEHLErrorEstimate | None:
    """The error budget of the films anchored on the isothermal reference ``ref``:
    ``H = (H_h / H_iso,h) H_iso*`` (module docstring). The grid_x part is the ratio's change from
    the solve on every other node (``RATIO_ORDERS``), the domain part the ratio's change in the
    box probe of ``est`` (:func:`domain_change`; the films' change where it lacks it), grid_z and
    iteration those of ``est``, and ``isothermal`` the reference's error. None when the solve on
    every other node is not in ``cache``."""
    o = result.options
    coarse = cache.results.get(((o.points - 1) // 2 + 1, o.nz, o.box))
    if coarse is None:
        return None
    ratio, ratio_coarse = film_ratios(result), film_ratios(coarse)
    box_change = est.domain
    if est.domain is not None and "ratio_Hc" in est.domain:
        box_change = {k: est.domain[f"ratio_{k}"] for k in ("Hc", "Hm")}
    budget = {k: dict(v) for k, v in est.budget.items()}
    correction = {}
    for key, iso, iso_error in (("Hc", ref.Hc, ref.error_Hc), ("Hm", ref.Hm, ref.error_Hm)):
        b = est.budget[key]
        gx = GRID_SAFETY * _difference(key, ratio[key], ratio_coarse[key]) / (2.0 ** RATIO_ORDERS[key] - 1.0)
        dom = DOMAIN_SAFETY * box_change[key] if box_change is not None else math.nan
        parts = {"grid_x": gx, "grid_z": b["grid_z"], "domain": dom, "iteration": b["iteration"],
                 "isothermal": iso_error}
        budget[key] = {**parts, "total": sum(parts.values())}
        correction[key] = iso / float(getattr(result, f"{key}_isothermal")) - 1.0
    notes = [n for n in est.notes if "extrapolated over the grids" not in n]
    notes.append(f"Hc and Hm anchored on the isothermal films converged by the core on {ref.points} points "
                 f"(stated errors {ref.error_Hc:.2g}, {ref.error_Hm:.2g}; {ref.wall_s:.1f} s): the thermal/"
                 f"isothermal ratios of the grid times them; grid_x and domain parts are the ratios'")
    return replace(est, budget=budget, notes=notes, correction=correction, anchor=ref)


@dataclass
class TEHLErrorEstimate:
    """Estimated errors of a TEHL solution: ``budget[quantity][part]`` with the parts
    ``grid_x``, ``grid_z``, ``domain``, ``iteration`` and their ``total`` (relative for ``Hc``,
    ``Hm``, ``friction_coefficient``; kelvin for ``T_max``); ``estimate["Hc"]`` reads the budget."""

    budget: dict[str, dict[str, float]]
    orders: tuple[float, float]
    domain: dict[str, Any] | None
    film_noise: float
    notes: list[str] = field(default_factory=list)
    wall_s: float = math.nan
    #: relative corrections of the films the estimate is for (``"Hc"``, ``"Hm"``): their
    #: second-order extrapolation over the grids along X; empty when the films are the grid's
    correction: dict[str, float] = field(default_factory=dict)
    #: relative changes of every quantity from ``nz / 2`` to ``nz`` (the grid_z part's measure)
    z_change: dict[str, float] | None = None
    #: the isothermal reference the films are anchored on (:func:`anchored_estimate`), else None
    anchor: IsothermalReference | None = None

    def __getitem__(self, key: str) -> dict[str, float]:
        return self.budget[key]

    @property
    def Hc(self) -> float:
        return self.budget["Hc"]["total"]

    @property
    def Hm(self) -> float:
        return self.budget["Hm"]["total"]

    def unknown_parts(self) -> list[str]:
        """The parts whose film errors could not be estimated (NaN or inf)."""
        return [part for part in (*PARTS, "isothermal")
                if not all(math.isfinite(self.budget[k].get(part, 0.0)) for k in ("Hc", "Hm"))]

    def known(self) -> bool:
        """Whether both film errors are estimated."""
        return math.isfinite(self.Hc) and math.isfinite(self.Hm)

    @property
    def worst(self) -> float:
        """The larger film error; inf when it is not known."""
        w = max(self.Hc, self.Hm)
        return w if math.isfinite(w) else math.inf

    def payload(self) -> dict[str, Any]:
        """The ``--json`` keys: ``Hc_error``, ``Hm_error``, ``friction_coefficient_error``,
        ``T_max_error_K`` (the totals), ``error_budget`` (part -> quantity -> value, under the
        result contract's part names :data:`CONTRACT_PARTS`, as every physics states it) and
        ``error_notes``."""
        out: dict[str, Any] = {f"{k}_error": self.budget[k]["total"] for k in QUANTITIES if k != "T_max"}
        out["T_max_error_K"] = self.budget["T_max"]["total"]
        out["error_budget"] = {name: {q: self.budget[q][part] for q in QUANTITIES if part in self.budget[q]}
                               for part, name in CONTRACT_PARTS.items()
                               if any(part in self.budget[q] for q in QUANTITIES)}
        out["error_notes"] = list(self.notes)
        return out


def grid_sequence(result: Any, cache: SolveCache) -> list[Any] | None:
    """The converged solves on ``points / 8``, ``/ 4``, ``/ 2`` and ``result`` itself (same nz
    and box), coarse to fine; None when the coarsest is below :data:`MIN_POINTS` or one of
    them did not converge."""
    o = result.options
    ns = [o.points]
    for _ in range(3):
        ns.insert(0, (ns[0] - 1) // 2 + 1)
    if ns[0] < MIN_POINTS:
        return None
    seq = [cache(n, o.nz, o.box) for n in ns[:-1]] + [result]
    return None if any(r is None for r in seq) else seq


def extrapolated_films(seq: list[Any]) -> dict[str, tuple[float, float]]:
    """Films of the finest solve of ``seq`` (:func:`grid_sequence`) reported as their
    second-order extrapolation over the grids, as the core does (:func:`~ehl_multigrid.
    multigrid.accuracy.extrapolated`: the last two ratios of successive differences
    asymptotic): ``{film: (relative correction, relative error stated)}`` for each film that
    passes. Hc always; Hm of point contacts only, from the minimum between the nodes first (it
    converges regularly where the nodal one jumps), else the nodal one. A line's Hm converges
    at about first order in the core and is not extrapolated."""
    fine = seq[-1]
    sequences = [("Hc", [r.Hc for r in seq])]
    if _is_point(fine):
        sequences += [("Hm", [subgrid_min_film(r.H, True) * r.problem.moes_factor for r in seq]),
                      ("Hm", [r.Hm for r in seq])]
    out: dict[str, tuple[float, float]] = {}
    for key, films in sequences:
        x = extrapolated(films) if key not in out else None
        if x is not None:
            F = float(getattr(fine, key))
            out[key] = (x[0] / F - 1.0, x[1] / abs(F))
    return out


def estimate_error(result: Any, *, cache: SolveCache | None = None,
                   domain: dict[str, Any] | None | bool = True, extrapolate: bool = False,
                   z_change: dict[str, float] | None = None) -> TEHLErrorEstimate:
    """Error budget of a TEHL line or point solution (see the module docstring for the parts).

    Parameters
    ----------
    result : a :class:`~thermal.tehl.line.TEHLLineResult` or
        :class:`~thermal.tehl.point.TEHLPointResult` on at least 129 points and nz >= 8.
    cache : the solves of the same contact already made (:class:`SolveCache`).
    domain : True measures the box part (:func:`domain_change`); a dict is a change measured
        before at the same box (it does not depend on the grid); False leaves it unknown
        (the totals are then NaN).
    extrapolate : report the films whose grid sequence along X is asymptotic as their
        extrapolation (:func:`extrapolated_films`, flooded contacts): the estimate is then of
        the corrected films (``correction``), its grid_x part that extrapolation's error. Costs
        a solve on ``points / 8`` beyond those the estimate makes anyway.
    z_change : the changes from ``nz / 2`` measured before on a coarser grid of the same nz
        and box (``TEHLErrorEstimate.z_change``), used instead of a solve on ``nz / 2``.

    Costs a solve on every other node, one on nz/2 (together about one more solve for a line,
    two thirds of one for a point) and the box probe (a quarter and a half of a solve for a
    line, a sixteenth and a quarter for a point).
    """
    t0 = time.perf_counter()
    o = result.options
    face = (getattr(o, "multigrid", None) or {}).get("face", "arithmetic")
    if face != "arithmetic":
        # the parts' rules were measured with the core's arithmetic face coefficient
        raise InputError(f"face = {face!r}: the TEHL error estimate is validated with the arithmetic "
                         f"face coefficient only (docs/accuracy.md)")
    if o.points < 2 * (MIN_POINTS - 1) + 1 or o.nz < 8:
        raise InputError(f"estimate_error needs points >= {2 * (MIN_POINTS - 1) + 1} and nz >= 8 (got "
                         f"{o.points}, {o.nz}): it solves again on half the grid")
    cache = cache or SolveCache.of(result)
    cache.add(result)
    px, pz = ORDERS["point" if _is_point(result) else "line"]
    notes: list[str] = []
    coarse_x = cache((o.points - 1) // 2 + 1, o.nz, o.box)
    if coarse_x is None:
        notes.append(f"the solve on {(o.points - 1) // 2 + 1} points did not converge: grid error along X unknown")
    if z_change is None:
        coarse_z = cache(o.points, o.nz // 2, o.box)
        if coarse_z is None:
            notes.append(f"the solve on nz = {o.nz // 2} did not converge: grid error across the film unknown")
        else:
            z_change = {k: _difference(k, _value(result, k), _value(coarse_z, k)) for k in QUANTITIES}
    else:
        notes.append(f"grid error across the film from the change nz = {o.nz // 2} -> {o.nz} measured on a "
                     f"coarser grid along X (it does not depend on that grid)")
    starved = getattr(result, "starved", None) or {}
    if starved and not starved.get("inlet_flooded", True):
        # the box starts at the meniscus, ahead of which the starved inlet carries the layer
        # at zero pressure (and the oil at its supply temperature): no box to enlarge
        domain = dict.fromkeys(QUANTITIES, 0.0)
        notes.append("domain part 0: the box starts at the meniscus (starved inlet)")
        notes.append("Hc_ratio and Hm_ratio divide by the flooded thermal films on the same grid and the "
                     "default box, whose own error is not estimated (a heavily loaded flooded contact "
                     "needs a finer grid than its starved film)")
    elif domain is True:
        domain = domain_change(result, cache)
        if domain is None:
            notes.append("the box probe did not converge: domain error unknown")
    elif domain is False or domain is None:
        domain = None
        notes.append("domain error not measured")
    last = result.outer[-1]
    w = float(last.get("relax", 1.0))
    noise = float(max(o_.get("film_noise", 0.0) for o_ in result.outer[-2:]))
    # a starved film is set by the supply it carries (rho_c Hc -> Hoil in the limit): the
    # meniscus search's supply mismatch is a relative error of the films and the friction
    supply = float(starved.get("supply_mismatch", 0.0))
    if supply:
        notes.append(f"iteration part includes the meniscus search's supply mismatch {supply:.2g}")
    iteration = {"Hc": max(last["dHc"] / w, noise) + supply, "Hm": max(last["dHm"] / w, noise) + supply,
                 "friction_coefficient": last["dP"] / w + supply, "T_max": last["dT"] / w}
    floor = result.report.extra.get("noise_floor") if result.report is not None else None
    if floor:
        # settled at the inner solves' noise floor: the last iterate lies within the window's
        # spread of the others, and the drift bounds how far the window's mean is from the end
        friction = (floor["friction"] + floor["spread_friction"] if floor.get("films_only")
                    else floor["P"] + floor["spread_P"])
        iteration = {"Hc": max(floor["Hc"] + floor["spread_Hc"], noise) + supply,
                     "Hm": max(floor["Hm"] + floor["spread_Hm"], noise) + supply,
                     "friction_coefficient": friction + supply,
                     "T_max": floor["T_max"] + floor["spread_T_max"]}
        notes.append("the outer iteration settled at the inner solves' noise floor: its iteration part "
                     "is the drift and spread of its last iterations" + (
                         "; the temperature at some nodes did not settle" if floor.get("films_only") else ""))
    fixes: dict[str, tuple[float, float]] = {}
    if extrapolate and coarse_x is not None and not starved:
        seq = grid_sequence(result, cache)
        fixes = extrapolated_films(seq) if seq is not None else {}
        if fixes:
            notes.append(f"{' and '.join(fixes)} extrapolated over the grids along X (second order; the last "
                         f"grids' sequence is asymptotic): grid_x part = the extrapolation's error")
    budget: dict[str, dict[str, float]] = {}
    for key in QUANTITIES:
        q = _value(result, key)
        pk = min(px, HM_ORDER_X) if key == "Hm" else px
        gx = (GRID_SAFETY * _difference(key, q, _value(coarse_x, key)) / (2.0**pk - 1.0)
              if coarse_x is not None else math.nan)
        if key == "Hm" and coarse_x is not None:
            # the core's rules for a sequence: first order from the difference before where the
            # last one is small by accident (page-63 500 N at S = 2: Hm ratios 17, 1.2 on
            # 257-2049 points). A line contact solves the quarter grid for it when it is not
            # made already: a starved roller-bearing film (hoil 0.2 um) has Hm 3.40367, 3.41782,
            # 3.41644, 3.41844, 3.41903 on 129-2049 points; its last difference alone would state
            # 0.033 % on 513 points for a true 0.083 %
            qp = (coarse_x.options.points - 1) // 2 + 1
            quarter = cache.results.get((qp, o.nz, o.box))
            if quarter is None and not _is_point(result) and qp >= MIN_POINTS:
                quarter = cache(qp, o.nz, o.box)
            if quarter is not None:
                films = [_value(quarter, key), _value(coarse_x, key), q]
                gx = max(gx, richardson(films, max_order=pk).error / abs(q))
        if key == "T_max" and coarse_x is not None:
            gx = _peak_temperature_part(result, coarse_x, cache, pk, iteration["T_max"], notes, gx)
        if key in fixes:
            gx = fixes[key][1]
        gz = GRID_SAFETY * z_change[key] / (2.0**pz - 1.0) if z_change is not None else math.nan
        dom = DOMAIN_SAFETY * domain[key] if domain is not None else math.nan
        parts = {"grid_x": gx, "grid_z": gz, "domain": dom, "iteration": iteration[key]}
        budget[key] = {**parts, "total": sum(parts.values())}  # NaN when a part is unknown
    if float(result.slip) == 0.0:
        budget["friction_coefficient"] = dict.fromkeys((*PARTS, "total"), math.nan)
        notes.append("pure rolling: the friction is zero to round-off (this model has no rolling "
                     "resistance), so its relative error is not defined")
    return TEHLErrorEstimate(budget, (px, pz), domain, noise, notes, time.perf_counter() - t0,
                             {k: v[0] for k, v in fixes.items()}, z_change)


def steepest_pressure_step(result: Any) -> tuple[float, float]:
    """The largest change of P (p/pmax) between neighbouring nodes along X of ``result``
    (every row of a point contact) and the X where it is."""
    P = np.atleast_2d(np.asarray(result.P, dtype=float))
    d = np.abs(np.diff(P, axis=-1))
    j, i = np.unravel_index(int(np.argmax(d)), d.shape)
    return float(d[j, i]), float(0.5 * (result.X[i] + result.X[i + 1]))


def _peak_temperature_part(result: Any, coarse: Any, cache: SolveCache, order: float, iteration: float,
                           notes: list[str], gx: float) -> float:
    """T_max's grid part along X, from the whole temperature field and not only its maximum: a
    peak that finer grids resolve better can overtake the maximum (the outlet spike in rolling;
    docs/thermal.md, "The largest oil temperature").

    Each node of the quarter grid (solved for it, a sixteenth of a point solve) carries the
    Richardson bound ``R`` of its across-film maximum by the core's rules
    (:func:`~ehl_multigrid.multigrid.accuracy.richardson`: the ratio of its last two changes up
    to ``2^p`` where it is at least 2, else first order and at least half the change before,
    times ``GRID_SAFETY``); the part is at least ``gx`` (T_max's own) and the largest
    ``T_h + R`` above T_max. A node whose change grew (beyond :data:`T_SCATTER_K` and ten times
    the outer iteration's scatter) has no bound, however far below T_max it lies: the part is
    inf, with a note. Without the quarter grid the part is inf unless every change is that
    small: two grids cannot tell a converging peak from a growing one. Before all that, the
    part is inf while the pressure steps by more than :data:`RESOLVED_PRESSURE_STEP` between
    neighbouring nodes: a peak at a drop no grid resolves is invisible to the three grids."""
    step, x_step = steepest_pressure_step(result)
    if step > RESOLVED_PRESSURE_STEP:
        notes.append(f"T_max's grid error unknown: the pressure changes by up to {step:.2g} pmax between "
                     f"neighbouring nodes (at X = {x_step:.3g}), a drop this grid does not resolve; the "
                     f"heating at it shows only on grids where that step is below {RESOLVED_PRESSURE_STEP:g}")
        return math.inf
    o = coarse.options
    qp = (o.points - 1) // 2 + 1
    quarter = cache(qp, o.nz, o.box) if qp >= MIN_POINTS else None
    top = float(result.T_max)
    three = peak_fields(result, coarse, quarter) if quarter is not None else None
    if three is None:
        two = peak_fields(result, coarse)
        if two is None:
            return gx
        (Th, T2h), X = two
        d = np.abs(Th - T2h)
        if np.max(d) <= max(10.0 * iteration, T_SCATTER_K):
            return max(gx, GRID_SAFETY * float(np.max(d)) / (2.0**order - 1.0))
        k = int(np.argmax(d))
        notes.append(f"T_max's grid error unknown: the temperature at X = {X.flat[k % X.size]:.3g} changed by "
                     f"{d.flat[k]:.3g} K between the last two grids, and the solve on {qp} points that would "
                     f"show whether such changes fall did not converge")
        return math.inf
    (Th, T2h, T4h), X = three
    d, before = np.abs(Th - T2h), np.abs(T2h - T4h)
    # the core's rules at each node: the observed order where it lies in 1..p, else first
    # order and at least half the change before
    ratio = before / np.maximum(d, 1e-300)
    regular = ratio >= 2.0
    R = GRID_SAFETY * np.where(regular, d / (np.minimum(ratio, 2.0**order) - 1.0), np.maximum(d, 0.5 * before))
    growing = (d > before) & (d > max(10.0 * iteration, T_SCATTER_K))
    part = max(gx, float(np.max(np.where(growing, -np.inf, Th + R))) - top)
    if growing.any():
        k = int(np.argmax(np.where(growing, d, -1.0)))
        notes.append(f"T_max is not grid-converged: the temperature at X = {X.flat[k % X.size]:.3g}, "
                     f"{top - Th.flat[k]:.3g} K below it, changed by {before.flat[k]:.3g} K then "
                     f"{d.flat[k]:.3g} K over the last three grids; its error is unknown")
        return math.inf
    return part


def corrected_result(result: Any, correction: dict[str, float]) -> Any:
    """A copy of a TEHL ``result`` whose films are extrapolated by the relative ``correction``
    (``TEHLErrorEstimate.correction``); the isothermal films are scaled by the same factors,
    so that the thermal reduction ratios stay those of one grid, where the grid errors of the
    thermal and the isothermal film cancel. The fields and ``grid_films`` stay the grid's."""
    if not correction:
        return result
    c, m = 1.0 + correction.get("Hc", 0.0), 1.0 + correction.get("Hm", 0.0)
    return replace(result, Hc=result.Hc * c, Hm=result.Hm * m, Hc_isothermal=result.Hc_isothermal * c,
                   Hm_isothermal=result.Hm_isothermal * m, grid_films=(float(result.Hc), float(result.Hm)))


@dataclass
class AccurateTEHL:
    """Outcome of :func:`solve_tehl_to_accuracy`: the returned ``result`` (the most accurate
    solve of the sequence), its ``estimate``, whether it is ``accurate`` (estimate within
    ``accuracy``; True without a target), the ``refinements`` made and a ``message``. A film
    solved without its estimate (:func:`thermal.front.film_alone`) has ``estimate`` None and is
    accurate only without a target."""

    result: Any
    estimate: TEHLErrorEstimate | None
    accuracy: float | None
    accurate: bool
    refinements: list[Refinement]
    message: str
    wall_s: float


def _predicted(est: TEHLErrorEstimate, fx: float, fz: float, fd: float, tighter: bool) -> float:
    """Larger film error after a refinement that scales the grid and box parts by the factors
    (``fx = 2^-p`` for one grid finer: Hm's part falls by at most ``2^-HM_ORDER_X``)."""
    worst = 0.0
    for k in ("Hc", "Hm"):
        b = est.budget[k]
        it = max(b["iteration"] * 0.1, est.film_noise) if tighter else b["iteration"]
        f = max(fx, 2.0**-HM_ORDER_X) if k == "Hm" and fx < 1.0 else fx
        worst = max(worst, f * b["grid_x"] + fz * b["grid_z"] + fd * b["domain"] + it + b.get("isothermal", 0.0))
    return worst


def step_candidates(est: TEHLErrorEstimate, points: int, nz: int, box: float, tol_scale: float,
                    max_points: int, max_nz: int = MAX_NZ, box_limit: float = 4.0) -> list[Candidate]:
    """The refinements of a TEHL solve and the larger film error each is predicted to leave:
    twice the points along X (grid_x / 2^p), twice nz (grid_z / 2^p), twice the box at equal
    mesh (domain / 4, the core's :data:`~ehl_multigrid.multigrid.accuracy.DOMAIN_DECAY`), outer
    tolerances ten times tighter (iteration / 10, not below the inner films' alternation). A
    part that could not be measured is refined first (prediction NaN): a coarser solve that
    did not converge asks for more points, an unknown box probe too (its probes then run on
    finer grids)."""
    px, pz = est.orders
    here = Resolution(points, box, tol_scale, nz)
    finer = here.finer()
    parts = {p: max(est.budget[k][p] for k in ("Hc", "Hm")) for p in ("grid_x", "grid_z", "domain")}
    if not all(math.isfinite(v) for v in parts.values()):
        if not math.isfinite(parts["grid_z"]) and 2 * nz <= max_nz:
            return [Candidate("nz", replace(here, nz=2 * nz), 0, math.nan)]
        return [Candidate("points", finer, 1, math.nan)] if finer.points <= max_points else []
    out = []
    if 2 * nz <= max_nz:
        out.append(Candidate("nz", replace(here, nz=2 * nz), 0, _predicted(est, 1.0, 2.0**-pz, 1.0, False)))
    if tol_scale > 1e-3:
        out.append(Candidate("tolerance", replace(here, tol=0.1 * tol_scale), 0,
                             _predicted(est, 1.0, 1.0, 1.0, True)))
    if finer.points <= max_points:
        out.append(Candidate("points", finer, 1, _predicted(est, 2.0**-px, 1.0, 1.0, False)))
        if 2.0 * box <= box_limit:
            out.append(Candidate("box", replace(finer, box=2.0 * box), 1,
                                 _predicted(est, 1.0, 1.0, 1.0 / DOMAIN_DECAY, False)))
    return out


def _dominant(est: TEHLErrorEstimate) -> str:
    unknown = est.unknown_parts()
    if unknown:
        return f"the {' and '.join(unknown)} part{'s' if len(unknown) > 1 else ''} could not be measured"
    vals = {p: max(est.budget[k].get(p, 0.0) for k in ("Hc", "Hm")) for p in (*PARTS, "isothermal")}
    p = max(vals, key=lambda n: vals[n])
    return f"the {p} part dominates ({vals[p]:.2g})"


def solve_tehl_to_accuracy(scene: Scene, slip: float | None = None, options: TEHLOptions | None = None,
                           accuracy: float | None = 0.005, *, refine: bool = True,
                           max_points: int | None = None, max_nz: int = MAX_NZ, box_limit: float = 4.0,
                           time_budget: float = 600.0, progress: Callable[[str], None] | None = None,
                           start: Any = None) -> AccurateTEHL:
    """Solve a TEHL line or point contact, estimate its error (:func:`estimate_error`) and,
    with ``refine`` and an ``accuracy`` (relative error of Hc and Hm), refine the part that
    dominates (:func:`step_candidates`: points along X, nz, the box, the outer tolerances) with
    the package's one accuracy controller (:func:`~ehl_multigrid.multigrid.controller.control`)
    until the estimate meets the target or a budget runs out: ``max_points`` along X (default
    16385 line, 1025 point), ``max_nz``, a box ``box_limit`` times the default, ``time_budget``
    seconds (a refinement predicted to overrun it is not started). Solves already made for an
    estimate are reused. ``progress(text)`` receives one line per solve. ``start``: a line
    solve of the same scene at another slip on the grid and box of ``options``, from which the
    first solve continues (:class:`SolveCache`).

    Returns the most accurate converged solve of the sequence (smallest estimated film error)
    with its estimate; ``accurate`` is False when that estimate misses the target (or is
    unknown), and ``message`` says why the refinement stopped. Raises
    :class:`ConvergenceError` when the first solve, and every finer one tried, fails.
    """
    point = scene.kind != "line"
    opts = options or TEHLOptions(points=257 if point else 513)
    if accuracy is not None:
        require_range("accuracy", accuracy, 1e-5, 0.5, "- (relative error)")
    require_range("time_budget", time_budget, 0.0, 1e6, "s")
    require_range("max_nz", max_nz, opts.nz, 640, "intervals across the film")  # at least the options' nz
    limit = max_points or MAX_POINTS["point" if point else "line"]
    slip = scene.slip if slip is None else float(slip)
    # bad input is refused here, not turned into a solve that "did not converge" by the cache
    wall_speeds(scene.us, slip)
    if point:
        require_flooded_point(scene)
    if point and start is not None:
        raise InputError("start applies to line contacts: a TEHL point solve starts from its own "
                         "isothermal solve")
    tehl = _TEHLControl(scene, slip, opts, point, limit, max_nz, box_limit, accuracy, start, time_budget)
    out = control(tehl, Resolution(opts.points, opts.box, 1.0, opts.nz), accuracy, refine=refine,
                  time_budget=time_budget, max_points=limit, progress=progress)
    if not out.converged:
        at = out.steps[-1]
        error = TimeBudgetSpent if out.budget_spent else ConvergenceError
        hint = ("a larger time_budget (or a looser accuracy)" if out.budget_spent else
                "another grid (more points, or a coarser one: a finer grid's outer iteration or "
                "meniscus search can fail where a coarser one converged), a lower relax, or check the inputs")
        raise error(f"TEHL: the solve on {at.points} points, nz = {at.nz} did not converge: {out.why}",
                    None, hint)
    res, est = out.result, tehl.estimates[id(out.result)]
    accurate = out.met
    res = corrected_result(res, est.correction)
    if accurate:
        msg = "converged" if accuracy is None else f"converged; estimated error within {accuracy:g}"
    else:
        o = res.options
        at = f" at {o.points} points, nz = {o.nz}, box x{o.box:g}" if refine else ""
        if est.known():
            msg = (f"the estimated error (Hc {est.Hc:.2g}, Hm {est.Hm:.2g}){at} exceeds the requested "
                   f"accuracy {accuracy:g}")
            why = f" ({_dominant(est)})"
        else:  # a part could not be measured: no accuracy can be confirmed
            msg = (f"the error{at} is not known ({_dominant(est)}), so the accuracy {accuracy:g} "
                   f"cannot be confirmed")
            why = ""
        msg += f"; not refined further: {out.why}" if refine else \
            f"{why}: refine (more points, nz) or --accuracy none"
    if est.anchor is not None:
        msg += (f"; Hc and Hm anchored on the isothermal films converged on {est.anchor.points} points (the "
                f"thermal/isothermal ratios of the {res.options.points}-point grid times them: " + ", ".join(
                    f"{k} {v:+.2%}" for k, v in est.correction.items()) + "); the fields are the grid's")
    elif est.correction:
        msg += (f"; {' and '.join(est.correction)} extrapolated over the grids (" + ", ".join(
            f"{k} {v:+.2%}" for k, v in est.correction.items()) + "; the isothermal films by the same "
            "factors); the fields are the finest grid's")
    return AccurateTEHL(res, est, accuracy, accurate, out.steps, msg, out.wall_s)


class _TEHLControl:
    """A TEHL line or point solve as a :class:`~ehl_multigrid.multigrid.controller.Controlled`
    physics: solves shared through one :class:`SolveCache` per tolerance scale, the estimate of
    :func:`estimate_error` (its box part measured once per box), the candidates of
    :func:`step_candidates`."""

    def __init__(self, scene: Scene, slip: float, opts: TEHLOptions, point: bool, limit: int,
                 max_nz: int, box_limit: float, accuracy: float | None = None, start: Any = None,
                 time_budget: float = 600.0) -> None:
        self.scene, self.slip, self.opts, self.point = scene, slip, opts, point
        self.time_budget = time_budget
        #: the isothermal reference of anchored point films: solved once, when first needed
        self.reference: IsothermalReference | None = None
        self.reference_tried = False
        self.limit, self.max_nz, self.box_limit = limit, max_nz, box_limit
        self.accuracy = accuracy
        #: changes from nz / 2 by (nz, box, tolerance scale), kept where their grid_z part is
        #: below DOMAIN_REUSE_BELOW of the target (the core's rule for the box change)
        self.z_changes: dict[tuple[int, float, float], dict[str, float]] = {}
        self.dimensions = 2 if point else 1
        self.cache = SolveCache(scene, slip, opts, point, start)
        self.cache_scale = 1.0
        self.domains: dict[float, dict[str, Any]] = {}
        self.estimates: dict[int, TEHLErrorEstimate] = {}
        self.errors: dict[Resolution, str] = {}
        #: the cache of the current round and how many solves it had made before the round
        self.round: tuple[SolveCache, int] = (self.cache, 0)

    def solve(self, at: Resolution) -> Any:
        if at.tol != self.cache_scale:
            # tighter outer tolerances: a new sequence of solves (the coarse ones too)
            o = self.opts
            self.cache = SolveCache(self.scene, self.slip, o.with_changes(
                tol_P=o.tol_P * at.tol, tol_H=o.tol_H * at.tol, tol_T=o.tol_T * at.tol), self.point)
            self.cache_scale = at.tol
        self.round = (self.cache, len(self.cache.walls))
        res = self.cache(at.points, at.nz, at.box)
        if res is None:
            self.errors[at] = self.cache.errors[(at.points, at.nz, float(at.box))]
            return at
        return res

    def converged(self, result: Any) -> bool:
        return not isinstance(result, Resolution)

    def failure(self, result: Any) -> str:
        return self.errors.get(result, "did not converge")

    def remedy(self, result: Any, at: Resolution, first: bool) -> Resolution | None:
        # a grid too coarse for the contact: the finer grid is the remedy
        return at.finer() if first else None

    def estimate(self, res: Any, at: Resolution, record: Any) -> tuple[float, float]:
        zkey = (at.nz, float(at.box), float(at.tol))
        est = estimate_error(res, cache=self.cache, domain=self.domains.get(at.box, True),
                             extrapolate=self.accuracy is not None, z_change=self.z_changes.get(zkey))
        if est.domain is not None:
            self.domains[at.box] = est.domain  # a far-field change: the same at every grid of this box
        if (self.accuracy is not None and est.z_change is not None and zkey not in self.z_changes
                and max(est["Hc"]["grid_z"], est["Hm"]["grid_z"]) < DOMAIN_REUSE_BELOW * self.accuracy):
            self.z_changes[zkey] = est.z_change
        coarse = self.cache.results.get(((at.points - 1) // 2 + 1, at.nz, float(at.box)))
        if (self.point and self.accuracy is not None and est.worst > self.accuracy and coarse is not None
                and est.domain is not None):
            # the point films converge slowly along X (the grid cap): anchored on the
            # isothermal films where that states the smaller error (the reference is solved
            # only where the ratio's grid and box changes are measured)
            if not self.reference_tried:
                self.reference_tried = True
                self.reference = isothermal_reference(self.scene, ANCHOR_SHARE * self.accuracy,
                                                      0.5 * self.time_budget)
            anchored = anchored_estimate(est, res, self.cache, self.reference) if self.reference else None
            if anchored is not None and anchored.worst < est.worst:
                est = anchored
        self.estimates[id(res)] = est
        return est.Hc, est.Hm

    def recurring_seconds(self, at: Resolution) -> float | None:
        """Seconds of the last round's solves on ``at``'s grid (the solve and its nz and box
        probes): a refinement repeats those on its finer grid, not the coarser grids of the
        estimate (the next round's coarse grid is this one) nor the isothermal reference.
        Series A disc 1 at 1 GPa, 2 %: a 41 s round on 257 points (its solves there 23 s,
        the 129-point grid 14 s, the reference 4.5 s) predicted 163 s for 513 points as a
        whole, 90 s now; it took 19 s."""
        cache, first = self.round
        own = (int(at.points), int(at.nz), float(at.box))
        walls = cache.walls[first:]
        total = sum(w for key, w in walls if key[0] >= at.points)
        if all(key != own for key, _ in walls):  # the solve itself was made in an earlier round
            total += next((w for key, w in cache.walls if key == own), 0.0)
        return total if total > 0.0 else None

    def candidates(self, res: Any, at: Resolution) -> list[Candidate]:
        return step_candidates(self.estimates[id(res)], at.points, at.nz, at.box, at.tol, self.limit,
                               self.max_nz, self.box_limit)

    def why_short(self, res: Any, at: Resolution) -> str:
        return (f"no refinement within {self.limit} points, nz = {self.max_nz} and a box "
                f"{self.box_limit:g} times the default is predicted to help: "
                f"{_dominant(self.estimates[id(res)])}")
