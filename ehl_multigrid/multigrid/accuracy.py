"""Error estimates of an EHL result: how far its central and minimum film are from the exact
solution of the model, as relative errors, with the budget split into three parts.

* **grid** -- Richardson from the FMG's own coarser grids: FMG leaves on each grid ``k`` a
  solution within its algebraic error of that grid's discrete solution, so the films
  ``F_{k-2}, F_{k-1}, F_k`` of the last three grids give the observed order
  ``p = log2((F_{k-1} - F_{k-2})/(F_k - F_{k-1}))`` and the error of the finest grid
  ``|F_k - F_{k-1}|/(2^p - 1)``. The order is capped at 2 for Hc (the discretisation's
  formal order, so a lucky ratio never shrinks the estimate) and for Hm at 1.5 (point) and 1
  (line); where the differences change sign,
  ``p < 1`` or ``p > 4`` (pre-asymptotic, or the irregular minimum film) ``p = 1`` is used and
  the estimate is at least half the earlier difference. The estimate
  is multiplied by :data:`GRID_SAFETY`.
* **domain** -- the change of the film when the box is doubled at equal mesh size (two cheap
  solves on a coarse grid, done by the contact's solve function), times :data:`DOMAIN_SAFETY`
  (what is left beyond the doubled box: up to 1.5 times the change again at low M). Where
  that factor alone decides a miss of the target, the accuracy loop measures the decay of the
  change with a third box (4x, tight probe solves) and continues it geometrically instead
  (:func:`domain_from_decay`).
* **algebraic** -- the change of the film over the last finest-grid cycle (iteration error
  of a contracting iteration with factor <= 1/2; scaled by ``rho/(1 - rho)`` when the last
  changes contract more slowly, :func:`iteration_factor`), at least half the change before it
  (:func:`iteration_error`; zero after a direct finest-grid solve, whose residual is at
  round-off), plus the relative load error times the
  film's load sensitivity (|d ln H / d ln W| < 0.5 over the whole map).

The total is the sum of the three. Every estimate is checked against finer grids, wider
boxes and tighter tolerances by validation/accuracy.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import Any

from .controller import Candidate, Refinement, Resolution, control

#: multiplies the Richardson grid-error estimate
GRID_SAFETY = 1.5
#: order cap of the minimum film: it sits in the outlet constriction, whose position moves with
#: the grid, and converges irregularly (line (20, 10): local orders 1.3-2.3 between 513 and
#: 4097 points while the three-grid order says 2.3)
HM_MAX_ORDER = 1.5
#: the same cap for line contacts, whose Hm converges at about first order (own orders 0.7-3.3
#: on the fit map's line results; docs/accuracy.md, "Extrapolated films")
LINE_HM_MAX_ORDER = 1.0
#: the pair of differences before the last counts as regular in the line Hm's look back from this
#: order on (ratio 1.68): its first-order sequences fall by 1.8-3.7 per grid at L = 25 (converged
#: films on 8193-262145 points, M 1000-5000), and the first-order bound 1.5 |d| covers the
#: remainder |d|/(r - 1) of any later fall r >= 1.67 (docs/accuracy.md, "Why line films converge
#: irregularly")
LINE_HM_LOOK_BACK_ORDER = 0.75
#: an observed order above this (twice the formal 2) marks a sequence as pre-asymptotic, its last
#: difference small by accident; it takes the first-order bound (docs/accuracy.md, "Grid error")
SUSPECT_ORDER = 4.0
#: the domain part over the film's change when the box is doubled, where the boundary holds
#: ``P = 0`` (point contacts, the thermal layer; docs/accuracy.md, "Domain error")
DOMAIN_SAFETY = 3.0
#: the fixed factor where the boundary holds the far-field pressure (point contacts,
#: ``point.farfield``; docs/accuracy.md, "Far-field boundary")
FAR_DOMAIN_SAFETY = 2.0
#: the fixed factor of line contacts (``P = 0`` at an inlet 20 rigid lengths upstream,
#: ``line.problem.default_xmin``; docs/accuracy.md, "Domain error")
LINE_DOMAIN_SAFETY = 2.0
#: multiplies the geometric remainder ``|d2| r/(r - 1)`` of a box change ``d2`` that falls by ``r``
#: per doubling (:func:`domain_from_decay`, :func:`domain_correction`; docs/accuracy.md, "Domain error")
DECAY_SAFETY = 1.25
#: resolution of the tight probes' box changes (relative; three times their film and load
#: tolerances): a second change below it counts as this large, and when both are below it
#: their ratio is no decay and the fixed factor applies
DECAY_FLOOR = 3e-5
#: bound on |d ln H / d ln W| used to turn a load error into a film error
LOAD_SENSITIVITY = 0.5


@dataclass(frozen=True)
class Richardson:
    """Grid error of one film from a sequence of nested grids (coarse to fine)."""

    error: float  # estimated absolute error of the finest value
    order: float  # observed order (NaN with fewer than three grids)
    extrapolated: float
    regular: bool  # monotone with 1 <= p

    @property
    def relative(self) -> float:
        last = self.extrapolated - self.error if math.isfinite(self.extrapolated) else math.nan
        return abs(self.error / last) if last else math.inf


def hm_max_order(contact: str) -> float:
    """Order cap of the minimum film's Richardson estimate for a contact ("line" or "point")."""
    return LINE_HM_MAX_ORDER if contact == "line" else HM_MAX_ORDER


def line_hm_richardson(values: list[float], log_face: bool = False) -> Richardson:
    """Grid error of a line contact's minimum film: first order, and at least the difference
    before the last where the pair before it is not regular. The line's Hm converges at about
    first order with a part that oscillates as the outlet's pressure edge moves within its cell
    from grid to grid, so a small last difference may be an accident (docs/accuracy.md, "Why line
    films converge irregularly"). ``log_face``: the grids took the logarithmic face coefficient,
    whose Hm is not monotone over the grids either (docs/accuracy.md, "Face coefficient of the
    Poiseuille flux"): also at least half the difference before a last pair falling faster
    than second order."""
    return richardson(values, max_order=LINE_HM_MAX_ORDER, earlier_half=log_face, look_back=True,
                      look_back_order=LINE_HM_LOOK_BACK_ORDER)


def log_faces(result: Any) -> bool:
    """Whether a line result's grids took the logarithmic face coefficient
    (``multigrid.flux``; ``solve_line_problem`` records it in ``extra["face"]``)."""
    return getattr(result, "extra", {}).get("face") == "logarithmic"


def richardson(values: list[float], safety: float = GRID_SAFETY, max_order: float = 2.0,
               earlier_half: bool = False, look_back: bool = False,
               look_back_order: float = 1.0) -> Richardson:
    """Grid-error estimate of ``values[-1]`` from films on grids refined by 2 each time; the
    observed order is capped at ``max_order``. ``earlier_half``: at least half the difference
    before the last, as for an irregular sequence, also where the sequence falls faster than
    second order (a first-order quantity whose last difference may be small by accident).
    ``look_back``: with four grids or more, a pair of differences before the last that is not
    regular marks the sequence as not yet asymptotic, whatever its last ratio says; the error is
    then at least the larger of the last two differences (no decay assumed); that pair is regular
    from the order ``look_back_order`` on."""
    v = [float(x) for x in values if math.isfinite(x)]
    if len(v) < 2:
        return Richardson(math.inf, math.nan, math.nan, False)
    d2 = v[-1] - v[-2]
    if len(v) >= 3:
        d1 = v[-2] - v[-3]
        order = _pair_order(d1, d2)
        regular = 1.0 <= order <= SUSPECT_ORDER
    else:
        order, regular = math.nan, False
    p = min(order, max_order) if regular else 1.0
    err = abs(d2) / (2.0**p - 1.0)
    if (not regular or (earlier_half and order > 2.0)) and len(v) >= 3:
        # a non-monotone (or slower than first order) sequence: the last difference may be
        # small by accident; first order from the one before bounds it. Measured: line
        # (100, 20) at 2049 points, Hm 0.017595, 0.018897, 0.018845 on 513-2049 gave 0.17 %
        # for a true 1.04 % (now 5.3 %); the honesty set goes from 69 to 70 of 70 covered,
        # median true/estimate 0.43 -> 0.42
        err = max(err, 0.5 * abs(d1))
    if look_back and len(v) >= 4 and not look_back_order <= _pair_order(v[-3] - v[-4], d1) <= SUSPECT_ORDER:
        # isoviscous line (500, 0): converged Hm on 1025-8193 points with ratios 59, 5.5 (and
        # 4.0 over the FMG films), the 8193-point film as far from the limit as the difference
        # before it (docs/accuracy.md, "Why line films converge irregularly")
        err = max(err, abs(d2), abs(d1))
        regular = False
    extrap = v[-1] + d2 / (2.0**p - 1.0)
    return Richardson(safety * err, order, extrap, regular)


def _pair_order(d1: float, d2: float) -> float:
    """Observed order ``log2(d1/d2)`` of two successive differences falling monotonically
    (NaN where they change sign or do not fall)."""
    if d1 == 0.0 or d2 == 0.0 or (d1 > 0) != (d2 > 0) or abs(d1) <= abs(d2):
        return math.nan
    return math.log2(abs(d1 / d2))


#: ratios of successive film differences over the last grids that count as asymptotic for the
#: second-order extrapolation: observed orders 1.5-2.5
ASYMPTOTIC_RATIOS = (2.0**1.5, 2.0**2.5)
#: the error stated for an extrapolated film is at least this fraction of the last difference
EXTRAPOLATION_FLOOR = 0.01
#: ... for a line contact's Hc: line (1, 25) extrapolated over ratios of 3.9 (FMG films; the
#: converged films' 4.04) while its finer grids' ratios fall to 2.9-3.3, and stated 0.015 % for a
#: true 0.067 % (the reference check of the line maps, validation/extremes/REPORT.md); 0.15 of
#: the last difference covers it
LINE_EXTRAPOLATION_FLOOR = 0.15


def _next_order(r: float) -> float:
    """Error of the second-order extrapolation ``F_k + d_k/3`` in units of ``|d_k|`` that a
    ratio ``r = d_(k-1)/d_k`` of successive differences allows: ``|r - 4|/3``, exact for a
    first-order term beside the second-order one (``F = F* + a h + b h^2``, either sign, the
    ratio below 4 when the signs agree, above when they differ) and larger than the error an
    ``h^3`` term leaves (``|r - 4|/(3 (r - 1))``)."""
    return abs(r - 4.0) / 3.0


def extrapolated(values: list[float], floor: float = EXTRAPOLATION_FLOOR) -> tuple[float, float] | None:
    """Second-order extrapolation of ``values[-1]`` (films on grids refined by 2 each time,
    coarse to fine) and the absolute error it is stated with; None unless the last two ratios
    ``r`` of successive differences lie in :data:`ASYMPTOTIC_RATIOS`.

    The value is ``E = F_k + d_k/3`` (``d_k = F_k - F_(k-1)``); the error :data:`GRID_SAFETY`
    times the next-order term the finest ratio allows (:func:`_next_order`), at least
    ``floor`` ``|d_k|`` (:data:`EXTRAPOLATION_FLOOR`; a line's Hc
    :data:`LINE_EXTRAPOLATION_FLOOR`). The finest ratio, not the one before: a first-order
    term moves the ratios away from 4 as the grid is refined, higher-order terms and the
    coarse grids' own errors move the coarser ratio, which ``E`` does not depend on; but at
    least half the term of the ratio before (an ``h^3`` term halves the distance per grid). An
    algebraic error ``delta`` of the FMG film ``F_(k-1)`` moves ``E`` by ``delta/3`` and the
    finest ratio by about ``5 delta/d_k``, stated as about ``2.5 delta``. Measured against the
    point references (docs/accuracy.md, "Extrapolated films")."""
    v = [float(x) for x in values if math.isfinite(x)]
    if len(v) < 4:
        return None
    d = [b - a for a, b in zip(v, v[1:], strict=False)][-3:]
    lo, hi = ASYMPTOTIC_RATIOS
    if 0.0 in d[1:] or not all(lo <= a / b <= hi for a, b in zip(d, d[1:], strict=False)):
        return None
    # a smooth higher-order term at most halves the ratio's distance from 4 per grid: a finest
    # ratio closer than that is a coincidence of the FMG films' algebraic errors
    # (docs/accuracy.md, "Extrapolated films")
    term = max(_next_order(d[-2] / d[-1]), 0.5 * _next_order(d[-3] / d[-2]))
    return v[-1] + d[-1] / 3.0, GRID_SAFETY * max(term, floor) * abs(d[-1])


@dataclass
class ErrorEstimate:
    """Estimated relative errors of Hc and Hm and their budget."""

    Hc: float
    Hm: float
    budget: dict[str, dict[str, float]] = field(default_factory=dict)
    order_Hc: float = math.nan
    order_Hm: float = math.nan
    Hc_extrapolated: float = math.nan
    notes: list[str] = field(default_factory=list)
    #: the grid part of Hc or Hm is the first-order bound of an irregular sequence
    irregular: bool = False
    #: relative corrections of (Hc, Hm) the estimate is for, by part: ``"grid"`` (the
    #: extrapolated films, :func:`extrapolated`), ``"box"`` (:func:`domain_correction`); empty
    #: when the films are the grid's own on its box
    correction: dict[str, dict[str, float]] = field(default_factory=dict)
    #: the films reported as their extrapolation over the grids (``"Hc"``, ``"Hm"``)
    extrapolated: tuple[str, ...] = ()


#: largest factor by which a slowly contracting iteration's last change is scaled (rho = 0.95)
MAX_ITERATION_FACTOR = 19.0


def iteration_factor(films: list[float]) -> float:
    """Bound on (iteration error)/(last change) of a film from its last finest-grid values:
    ``rho/(1 - rho)`` with the observed contraction ``rho``, the larger of the last two ratios
    ``|d_k|/|d_(k-1)|`` of successive changes, 1 while ``rho <= 1/2`` (the factor the estimate
    assumes), :data:`MAX_ITERATION_FACTOR` when the changes do not fall. A stalled line
    iteration measured 3 % from its discrete solution with changes of 0.3 % per cycle (line
    (100, 0) Barus, 2049 points); a slowly drifting point film whose last ratio fell to 0.49
    after 0.9 was 1.1e-5 from its discrete solution with a last change of 3.4e-6 ((100, 20,
    theta 0.25), 513 points, validation/accuracy/iteration_estimate.py)."""
    d = [abs(b - a) for a, b in zip(films[:-1], films[1:], strict=True)][-3:]
    if len(d) < 2 or d[-1] == 0.0:
        return 1.0
    rho = max((b / a if a > 0.0 else math.inf) for a, b in zip(d[:-1], d[1:], strict=True))
    if rho <= 0.5:
        return 1.0
    return MAX_ITERATION_FACTOR if rho >= 0.95 else rho / (1.0 - rho)


def last_film_change(history: list[Any]) -> dict[str, float] | None:
    """Relative change of Hc and Hm over the last cycle of the finest grid in ``history`` (the
    driver's cycle records); None with fewer than two cycles there."""
    if not history:
        return None
    top = max(h.level for h in history)
    fin = [h for h in history if h.level == top][-2:]
    if len(fin) < 2:
        return None
    return {k: abs(getattr(fin[1], k) / getattr(fin[0], k) - 1.0) if getattr(fin[0], k) else math.nan
            for k in ("Hc", "Hm")}


#: finest-grid cycles before the last over which a solve at its residual floor measures its films'
#: wander (:func:`floor_film_spread`): the stall window that ends such a solve
FLOOR_SPREAD_CYCLES = 4


def floor_film_spread(history: list[Any], cycles: int = FLOOR_SPREAD_CYCLES) -> dict[str, float] | None:
    """Largest relative distance of the finest grid's films over its last ``cycles + 1`` cycles
    (the driver's records) from the last one, per film (Hc, Hm, Hm_sub); None with fewer than
    two cycles there. At a residual floor the films wander, not jitter about the answer: the
    (1000, 0, theta 0.1) probe on twice the box (1025 points, 64 coarse intervals) moved Hc by
    0.16 % in its last cycle, 1.8 % over its last four, and ended 2.1 % off."""
    if not history:
        return None
    top = max(h.level for h in history)
    fin = [h for h in history if h.level == top][-(cycles + 1):]
    if len(fin) < 2:
        return None
    out = {}
    for k in ("Hc", "Hm", "Hm_sub"):
        last = getattr(fin[-1], k, math.nan)
        out[k] = max(abs(getattr(h, k, math.nan) / last - 1.0) for h in fin[:-1]) if last else math.nan
    return out


#: a coarser grid's solve that ended at its relaxation's floor serves the grid sequence when its
#: films' last jump is below this fraction of their difference from the next finer grid's
FLOOR_JITTER_FRACTION = 0.1


def floor_films_usable(result: Any, finer: tuple[float, ...] | None) -> bool:
    """Whether the films of ``result``, a solve that ended at its residual floor (films
    wandering by :func:`floor_film_spread`), can stand in a grid sequence next to ``finer``
    (the next finer grid's films, :func:`final_films`): each film's spread below
    :data:`FLOOR_JITTER_FRACTION` of its difference from the finer film. The 6205 inner race on
    129 points: Hc jumps by 3e-5 against a difference of 4.5e-3 from 257 points, and the four
    grids let the 1025-point films extrapolate."""
    if finer is None:
        return False
    spread = floor_film_spread(result.history)
    if spread is None:
        return False
    films = final_films(result)
    for i, k in enumerate(("Hc", "Hm", "Hm_sub")):
        jump = spread[k] * abs(films[i]) if i < len(films) else math.nan
        diff = abs(finer[i] - films[i]) if i < len(finer) else math.nan
        if k == "Hm_sub" and not (math.isfinite(jump) and math.isfinite(diff)):
            continue
        if not jump < FLOOR_JITTER_FRACTION * diff:
            return False
    return True


def iteration_error(films: list[float]) -> float:
    """Estimated (absolute) iteration error of ``films[-1]``, the films of the finest-grid
    cycles in order: the last change times :func:`iteration_factor`, and at least half the
    change before it (a last change small by accident, in a sequence that does not contract
    geometrically, says little). Measured on 97 solves of 123 map cases
    (validation/accuracy/iteration_estimate.py, true error against solves with ten times
    tighter tolerances): the last change times the factor of the last ratio alone covered
    90.7 % of the films (up to 10.9x short); this rule covers 97.4 % (median true/estimate
    0.10)."""
    if len(films) < 2:
        return math.inf
    err = abs(films[-1] - films[-2]) * iteration_factor(films)
    if len(films) >= 3:
        err = max(err, 0.5 * abs(films[-2] - films[-3]))
    return err


def domain_from_decay(d2: float, d4: float) -> float:
    """Relative domain error of the default box from the film's relative changes when the
    box is doubled (``d2``) and doubled again (``d4``, from the 2x box), at equal mesh: the
    changes continued geometrically with the measured decay ``r = d2/d4`` per doubling,
    ``DECAY_SAFETY |d2| r/(r - 1)``; infinite (no bound) when the change does not shrink or
    changes sign. Changes below :data:`DECAY_FLOOR` are not resolved: a second change below it
    counts as the floor (with the first one's sign), and when both are below it the fixed
    :data:`DOMAIN_SAFETY` ``|d2|`` applies."""
    if max(abs(d2), abs(d4)) < DECAY_FLOOR:
        return DOMAIN_SAFETY * abs(d2)
    if abs(d4) < DECAY_FLOOR:
        d4 = math.copysign(DECAY_FLOOR, d2)
    r = d2 / d4
    if r <= 1.0:
        return math.inf
    return DECAY_SAFETY * abs(d2) * r / (r - 1.0)


@dataclass(frozen=True)
class BoxSeries:
    """Relative film changes (Hc, Hm) of a box series at equal mesh: ``d2`` from the solve's box
    to twice it, and either ``d4`` from twice to four times or ``below`` from half the solve's
    box to the solve's box (the other None), on the probe mesh; ``d2_coarse`` the first change
    again on a mesh twice as coarse (None when that pair did not converge); ``noise`` the bound
    on the iteration errors of the probes, per film (relative)."""

    d2: tuple[float, float]
    d4: tuple[float, float] | None
    d2_coarse: tuple[float, float] | None
    noise: tuple[float, float] = (0.0, 0.0)
    below: tuple[float, float] | None = None


#: smallest decay of the box change per doubling for which the films are corrected for the
#: box: slower decays (thick films) leave a remainder the geometric continuation does not bound
CORRECTION_MIN_DECAY = 2.0
#: multiplies the change of the first box change between the coarse and the probe mesh: Hm's
#: box change is irregular in the mesh (docs/accuracy.md, "Box correction")
MESH_SAFETY = 2.0


def domain_correction(d2: float, d4: float | None, d2_coarse: float | None, noise: float = 0.0,
                      below: float | None = None) -> tuple[float, float] | None:
    """Box correction of one film and the error it leaves, both relative: the film on an
    unbounded box is the film on the solve's box times ``1 + C``.

    With ``d4`` measured, ``C = (1 + d2)(1 + d4)(1 + b) - 1`` takes the two measured doublings
    beyond the solve's box and continues the changes geometrically beyond four times the box,
    ``b = d4/(r - 1)`` with the measured decay ``r = d2/d4``. With ``below`` instead (the
    change from half the solve's box to it), ``C = (1 + d2)(1 + b) - 1``, ``b = d2/(r - 1)``
    with ``r = below/d2``: the decay measured one box lower, where the change decays no
    faster than further out (the point references' box series: Hc's decay per doubling the
    same within 5 %, Hm's slower on the smaller boxes, 3.6 against 5.9 at circular (20, 10)).
    The error is :data:`DECAY_SAFETY` times the sum of ``|b|`` (the unmeasured part, counted
    whole), the mesh dependence of the measured changes (:data:`MESH_SAFETY` times the change
    of ``d2`` from the coarse mesh to the probe mesh, scaled to ``C``) and the probes'
    iteration ``noise``. None (no correction) when the decay is slower than
    :data:`CORRECTION_MIN_DECAY`, the changes differ in sign, or the mesh dependence was not
    measured. Measured (circular (20, 10), Roelands, box changes on meshes of 65 to 513 points
    per default box): ``d2`` of Hc converges at second order in the mesh (1.111, 1.060,
    1.048 %), that of Hm irregularly (1.129, 1.541, 1.414, 1.45 %)."""
    outer = d4 if d4 is not None else below
    if d2_coarse is None or outer is None or d2 == 0.0 or outer == 0.0 or (d2 > 0.0) != (outer > 0.0):
        return None
    r = d2 / d4 if d4 is not None else below / d2
    if r < CORRECTION_MIN_DECAY:
        return None
    if d4 is not None:
        beyond = d4 / (r - 1.0)
        c = (1.0 + d2) * (1.0 + d4) * (1.0 + beyond) - 1.0
    else:
        beyond = d2 / (r - 1.0)
        c = (1.0 + d2) * (1.0 + beyond) - 1.0
    mesh = MESH_SAFETY * abs(d2 - d2_coarse) * abs(c / d2)
    return c, DECAY_SAFETY * (abs(beyond) + mesh + noise)


#: a solve started on its finest grid from a given solution (no FMG) states as its iteration
#: error at least the largest film change over this many last cycles (docs/robustness.md,
#: "Line solver defaults")
FROM_GUESS_CHANGES = 3


def _largest_change(films: list[float]) -> float:
    tail = films[-(FROM_GUESS_CHANGES + 1):]
    return max(abs(b - a) for a, b in zip(tail, tail[1:], strict=False))


def _finest_points(result: Any) -> int | None:
    X = getattr(result, "X", None)
    return None if X is None else len(X)


def _converged_films(films: tuple[float, ...]) -> dict[str, float]:
    """The FMG-record films of a converged solve's ``(Hc, Hm[, Hm_sub])``."""
    return {"Hc": films[0], "Hm": films[1], "Hm_sub": films[2] if len(films) > 2 else math.nan}


def final_films(result: Any) -> tuple[float, float, float]:
    """``(Hc, Hm, Hm_sub)`` of a converged result (Venner units): its films and the sub-grid
    minimum film of its last finest-grid cycle (NaN where not measured)."""
    top = getattr(result, "levels", 0) - 1
    fin = [h for h in getattr(result, "history", ()) if h.level == top]
    return (float(result.scalars["Hc_venner"]), float(result.scalars["Hm_venner"]),
            float(getattr(fin[-1], "Hm_sub", math.nan)) if fin else math.nan)


def estimate_error(result: Any, domain: tuple[float, float] | None = None,
                   converged: dict[int, tuple[float, ...]] | None = None,
                   decay: tuple[tuple[float, float], tuple[float, float]] | BoxSeries | None = None,
                   extrapolate: bool = False, domain_safety: float = DOMAIN_SAFETY) -> ErrorEstimate:
    """Error estimate of a converged multilevel result (films in Venner units).

    ``result`` has ``fmg`` (per FMG grid: ``points``, ``Hc``, ``Hm``), ``history`` (per cycle:
    level, ``Hc``, ``Hm``), ``load_error_history``, ``levels`` and the final ``Hc_venner``,
    ``Hm_venner`` scalars; ``domain`` is the relative change of (Hc, Hm) when the box is
    doubled, or None when it was not measured (then the domain part is NaN and the total
    is not known); the domain part is ``domain_safety`` times it (:data:`DOMAIN_SAFETY`, or
    :data:`FAR_DOMAIN_SAFETY` for a far-field boundary). ``converged`` maps a coarser grid's points to the films ``(Hc, Hm)`` of a
    converged solve of the same discrete problem (same box and options): they replace that
    grid's FMG films, which carry the algebraic error of the FMG's few cycles there (line
    (21.9, 3.25) Roelands: 0.4 % at 1025 and 2049 points against grid differences of 0.2 %,
    so the FMG sequence looked irregular and took the first-order bound, 1.1 % for a true
    0.07 %). ``decay`` = ``((d2_Hc, d2_Hm), (d4_Hc, d4_Hm))``, the changes of two successive
    doublings of the box measured by tight probes, replaces ``domain`` and the fixed factor by
    :func:`domain_from_decay`. A :class:`BoxSeries` instead asks for films corrected for the box
    (:func:`domain_correction`): the estimate is then of the corrected films
    (``correction``, applied to the returned result by :func:`apply_correction`), its domain
    part what the correction leaves; where the series allows no correction, as a pair of changes.
    ``extrapolate`` reports each film whose grid sequence is asymptotic as its second-order
    extrapolation (:func:`extrapolated`; ``correction["grid"]``), the grid part then being
    that extrapolation's error.
    """
    Hc, Hm = float(result.scalars["Hc_venner"]), float(result.scalars["Hm_venner"])
    top = result.levels - 1
    fmg = [d for d in result.fmg if d.get("level", -1) < top]
    notes = []
    if converged:
        used = [d["points"] for d in fmg if d.get("points") in converged]
        fmg = [{**d, **_converged_films(converged[d["points"]])}
               if d.get("points") in converged else d for d in fmg]
        n_top = _finest_points(result)
        # grids the FMG did not visit (a solve started on its finest grid from a given
        # solution, as the line's continuation in M does): their converged films, down from
        # the finest grid while the chain of grids is unbroken
        have = {d.get("points") for d in fmg}
        extra, n = [], n_top or 0
        while n > 3:
            n = (n - 1) // 2 + 1
            if n in have or n not in converged:
                break
            extra.append({"points": n, **_converged_films(converged[n])})
        if extra:
            below = [d for d in fmg if d.get("points", 0) <= n] if n in have else []
            fmg = sorted(below + extra, key=lambda d: d["points"])
            used += [d["points"] for d in extra]
        if 0 < len(fmg) < 2:
            # an FMG resumed from a solve that started on its own finest grid (the line's
            # continuation in M) visited one coarser grid: the converged films below it
            n = fmg[0]["points"]
            while n > 3 and (n - 1) // 2 + 1 in converged:
                n = (n - 1) // 2 + 1
                fmg.insert(0, {"points": n, **_converged_films(converged[n])})
                used.append(n)
        if used:
            notes.append(f"Richardson with the converged films of the solves on {used} points")
    rc = richardson([d["Hc"] for d in fmg] + [Hc])
    if getattr(result, "contact", "") == "line" and rc.regular and rc.order > FAST_ORDER:
        # a line's Hc falling faster than FAST_ORDER is not yet asymptotic, and slower grids may
        # follow: isoviscous (1, 0) on 1025 points (converged ratios above 5.7, then about 2.9)
        # stated 0.0183 % at order 2 for a true 0.0197 % (the line maps' reference check)
        rc = richardson([d["Hc"] for d in fmg] + [Hc], max_order=LINE_FAST_HC_ORDER)
    hm_films = [d["Hm"] for d in fmg] + [Hm]
    rm = line_hm_richardson(hm_films, log_faces(result)) if getattr(result, "contact", "") == "line" else \
        richardson(hm_films, max_order=HM_MAX_ORDER)
    if not rc.regular:
        notes.append("Hc converges irregularly over the last grids: first-order estimate")
    if not rm.regular:
        notes.append("Hm converges irregularly over the last grids: first-order estimate")
    grid = {"Hc": abs(rc.error / Hc), "Hm": abs(rm.error / Hm)}
    fin = [h for h in result.history if h.level == top]
    if fin and fin[-1].cycle == -1:
        # finished by a direct solve of the finest grid (dense Newton): its residual, not the
        # jump from the last cycle, measures what is left of the iteration
        alg_c = alg_m = 0.0
        notes.append("finished by a direct solve: iteration error from the load error only")
    elif len(fin) >= 2:
        fc, fm = iteration_factor([h.Hc for h in fin]), iteration_factor([h.Hm for h in fin])
        alg_c = iteration_error([h.Hc for h in fin]) / abs(Hc)
        alg_m = iteration_error([h.Hm for h in fin]) / abs(Hm)
        if max(fc, fm) > 1.0:
            notes.append("the last cycles contract slowly: iteration error scaled by rho/(1 - rho)")
        if not any(d.get("level", -1) < top for d in result.fmg) and len(fin) >= 4:
            # started on the finest grid from a given solution: no FMG brought the films near
            # the discrete solution, and a slow mode can hide behind a last small change
            alg_c = max(alg_c, _largest_change([h.Hc for h in fin]) / abs(Hc))
            alg_m = max(alg_m, _largest_change([h.Hm for h in fin]) / abs(Hm))
            notes.append("started on the finest grid: iteration error at least the largest film "
                         f"change of the last {FROM_GUESS_CHANGES} cycles")
    else:
        alg_c = alg_m = grid["Hc"]
        notes.append("fewer than two finest-grid cycles: algebraic error bounded by the grid error")
    le = abs(float(result.load_error_history[-1])) if len(result.load_error_history) else math.inf
    algebraic = {"Hc": alg_c + LOAD_SENSITIVITY * le, "Hm": alg_m + LOAD_SENSITIVITY * le}
    correction: dict[str, dict[str, float]] = {}
    fixes, floor_fixed = None, False
    if isinstance(decay, BoxSeries):
        fixes = [domain_correction(decay.d2[i], None if decay.d4 is None else decay.d4[i],
                                   None if decay.d2_coarse is None else decay.d2_coarse[i],
                                   decay.noise[i], None if decay.below is None else decay.below[i])
                 for i in (0, 1)]
        if None in fixes:
            # the series' film-stopped probes were not calibrated for the decay alone: the
            # estimate is never below the fixed factor's
            notes.append("box series measured but not used for a correction (slow decay, sign "
                         "change or no coarse-mesh pair): domain part " + (
                             "the fixed factor" if decay.d4 is None else
                             "the larger of the fixed factor and the geometric continuation"))
            domain, floor_fixed = decay.d2, True
            decay = None if decay.d4 is None else (decay.d2, decay.d4)
    if fixes is not None and None not in fixes:
        (cc, ec), (cm, em) = fixes
        domain = decay.d2
        correction["box"] = {"Hc": cc, "Hm": cm}
        dom = {"Hc": ec, "Hm": em}
        pair, other = ("below and beyond the box", decay.below) if decay.d4 is None else \
            ("two doublings", decay.d4)
        notes.append(f"films corrected for the box (Hc {cc:+.3%}, Hm {cm:+.3%}) from the changes of "
                     f"{pair} (Hc {decay.d2[0]:.3g}, {other[0]:.3g}; Hm {decay.d2[1]:.3g}, "
                     f"{other[1]:.3g}) continued geometrically; domain part = what the correction "
                     f"leaves")
    elif decay is not None:
        (d2c, d2m), (d4c, d4m) = decay
        domain = (d2c, d2m)
        # the measurement replaces the assumption both ways: a slow decay gives more than the
        # fixed factor ((5, 0): 4.9 |d2| against a true 2.6 |d2|; the decay speeds up beyond
        # the third box), a change that does not shrink gives no bound
        dom = {"Hc": domain_from_decay(d2c, d4c), "Hm": domain_from_decay(d2m, d4m)}
        if floor_fixed:
            dom = {"Hc": max(dom["Hc"], domain_safety * abs(d2c)), "Hm": max(dom["Hm"], domain_safety * abs(d2m))}
        notes.append(f"domain error from the box changes of two doublings (Hc {d2c:.3g}, {d4c:.3g}; "
                     f"Hm {d2m:.3g}, {d4m:.3g}) continued geometrically")
    elif domain is None:
        dom = {"Hc": math.nan, "Hm": math.nan}
        notes.append("domain error not measured")
    else:
        dom = {"Hc": domain_safety * abs(domain[0]), "Hm": domain_safety * abs(domain[1])}
    if extrapolate:
        fix = {}
        sub = [d.get("Hm_sub", math.nan) for d in fmg] + [getattr(fin[-1], "Hm_sub", math.nan) if fin else math.nan]
        sequences = [("Hc", [d["Hc"] for d in fmg] + [Hc], Hc)]
        if getattr(result, "contact", "") != "line":
            # not the line's minimum film: it converges at about first order (ratios 2.2-3.6
            # on 513-32769 points at (100, 10) and (20, 20))
            if all(math.isfinite(v) for v in sub):
                # the minimum between the nodes converges regularly where the nodal one jumps
                # from node to node (subgrid_min_film); both tend to the same minimum film
                sequences.append(("Hm", sub, Hm))
            sequences.append(("Hm", [d["Hm"] for d in fmg] + [Hm], Hm))
        floor = LINE_EXTRAPOLATION_FLOOR if getattr(result, "contact", "") == "line" else EXTRAPOLATION_FLOOR
        for k, films, F in sequences:
            x = extrapolated(films, floor) if k not in fix else None
            if x is not None:
                fix[k] = x[0] / F - 1.0
                grid[k] = x[1] / abs(F)
        if fix:
            correction["grid"] = {"Hc": fix.get("Hc", 0.0), "Hm": fix.get("Hm", 0.0)}
            notes.append(f"{' and '.join(fix)} extrapolated over the grids (second order; the last "
                         f"grids' sequence is asymptotic): grid part = the change of the extrapolation")
    budget = {"grid": grid, "domain": dom, "algebraic": algebraic}
    tot = {k: grid[k] + algebraic[k] + (0.0 if math.isnan(dom[k]) else dom[k]) for k in ("Hc", "Hm")}
    if domain is None:
        tot = {k: math.nan for k in tot}
    return ErrorEstimate(tot["Hc"], tot["Hm"], budget, rc.order, rm.order, rc.extrapolated, notes,
                         not (rc.regular and rm.regular), correction,
                         tuple(fix) if extrapolate else ())


#: largest order at which a line contact's stated Hm error is predicted to fall per grid (it fell
#: by 2.3-3.7 per grid at M = 1000-5000; docs/accuracy.md)
LINE_HM_PREDICT_ORDER = 1.5
#: a box change whose domain part (the contact's fixed factor times it) is below this fraction of
#: the target is not measured again on finer grids of the same box (docs/accuracy.md)
DOMAIN_REUSE_BELOW = 0.1
#: with an accuracy target the cycles stop when the films change by less than this fraction of it
FILM_TOL_FRACTION = 0.05
#: film tolerance (relative change per cycle) of the domain probes' solves: their difference must
#: measure the box, not two iteration errors (docs/accuracy.md, "Domain error")
PROBE_FILM_TOL = 1e-4


def film_tol(options: Any, accuracy: float | None, tol_factor: float = 1.0) -> float | None:
    """Stopping rule of an accuracy-driven solve: the films' change per cycle below
    :data:`FILM_TOL_FRACTION` of the target (the algebraic error then takes a twentieth of
    the budget instead of the residual tolerance's tiny fraction); the options' own
    ``film_tol`` when given, none without a target."""
    if options.film_tol is not None or accuracy is None:
        return None if options.film_tol is None else options.film_tol * tol_factor
    return min(FILM_TOL_FRACTION * accuracy * tol_factor, 0.1)


def film_change(solve_default: Any, solve_wide: Any, floor_ok: bool = False,
                hm_sub: bool = False) -> tuple[float, float] | None:
    """Relative change of (Hc, Hm) from the default-box solve to the wide-box solve (two
    callables returning results); None when either raises a clear error or does not converge.
    With ``hm_sub`` Hm is the sub-grid minimum film of the last cycle (:func:`final_films`)
    where both solves record one.

    With ``floor_ok`` a solve that ended at its relaxation's floor (``residual_floor``: films
    wandering above the film tolerance at a residual that no longer falls) counts, and its
    films' spread over the last cycles (:func:`floor_film_spread`) is added to the magnitude of
    the change: the box effect is then known only to within that spread, and the change stated
    is its upper end. Measured: the circular
    (5000, 0) probes on 1025-2049 points jitter by 1e-4 to 4e-4 in Hm at residuals of 1e-6;
    refused, such a probe sent the measurement to grids twice as fine (4097 points on a box
    twice as wide, minutes), where the jitter is the same."""
    from ..model.errors import ConvergenceError, InputError

    films, jitter = [], [0.0, 0.0]
    for solve in (solve_default, solve_wide):
        try:
            r = solve()
        except (ConvergenceError, InputError):
            return None
        if not r.success:
            d = floor_film_spread(r.history) if floor_ok and r.status_name == "residual_floor" else None
            if d is None or not (math.isfinite(d["Hc"]) and math.isfinite(d["Hm"])):
                return None
            jitter = [jitter[0] + d["Hc"], jitter[1] + d["Hm"]]
        films.append(final_films(r))
    (c0, m0, s0), (c1, m1, s1) = films
    if hm_sub and math.isfinite(s0) and math.isfinite(s1):
        m0, m1 = s0, s1
    dc, dm = c1 / c0 - 1.0, m1 / m0 - 1.0
    return (math.copysign(abs(dc) + jitter[0], dc), math.copysign(abs(dm) + jitter[1], dm))


#: the film scalars a box correction scales, per film (Moes, Venner and dimensional units)
CORRECTED_SCALARS = {"Hc": ("Hc", "Hc_venner", "hc"), "Hm": ("Hm", "Hm_venner", "hm")}


def correction_factors(parts: dict[str, dict[str, float]] | None) -> tuple[float, float]:
    """Factors on (Hc, Hm) of the corrections ``parts`` (by part, as ``ErrorEstimate.correction``)."""
    parts = parts or {}
    return (math.prod(1.0 + c["Hc"] for c in parts.values()), math.prod(1.0 + c["Hm"] for c in parts.values()))


def apply_correction(result: Any) -> None:
    """Scale the film scalars of ``result`` by the box correction its estimate is for (nothing
    when it has none). The films of the fields on the solve's own box stay as ``Hc_field`` and
    ``Hm_field`` (Moes units); the pressure and film fields are not changed."""
    est = getattr(result, "error", None)
    corr = getattr(est, "correction", None)
    if not corr or result.extra.get("film_correction"):
        return
    scal = result.scalars
    for film, factor in zip(CORRECTED_SCALARS, correction_factors(corr), strict=True):
        keys = CORRECTED_SCALARS[film]
        scal[f"{film}_field"] = scal.get(film)
        for k in keys:
            if isinstance(scal.get(k), (int, float)):
                scal[k] = float(scal[k]) * factor
    result.extra["film_correction"] = {name: dict(part) for name, part in corr.items()}
    said = {"grid": "extrapolated over the grids", "box": "corrected for the box"}
    # the grid part names only the films extrapolated (a line's Hm never is)
    films = {"grid": tuple(getattr(est, "extrapolated", ())) or ("Hc", "Hm"), "box": ("Hc", "Hm")}
    result.message += "; " + "; ".join(
        f"{' and '.join(films[name])} {said[name]} (" + ", ".join(f"{part[f]:+.2%}" for f in films[name]) + ")"
        for name, part in corr.items()
    ) + "; the fields are the finest grid's on the solve's box"


def attach_estimate(result: Any, estimate: ErrorEstimate, accuracy: float | None) -> None:
    """Store the estimate in the result and judge it against ``accuracy``: a result whose
    iteration converged but whose estimated error exceeds the target gets status 6."""
    result.error = estimate
    result.scalars.update(Hc_error=estimate.Hc, Hm_error=estimate.Hm)
    result.extra["error_budget"] = estimate.budget
    result.extra["error_notes"] = list(estimate.notes)
    result.accuracy = accuracy
    if accuracy is None or not result.success:
        result.scalars["converged"] = bool(result.success)
        return
    worst = max(estimate.Hc, estimate.Hm)
    if not math.isfinite(worst):
        unknown = [k for k, v in estimate.budget.items() if not all(map(math.isfinite, v.values()))]
        result.set_status(6, f"iteration converged but its error is not known: the {' and '.join(unknown)} "
                             f"part{'s' if len(unknown) > 1 else ''} could not be estimated (no converged "
                             f"solve on a coarser grid or a wider box), so the accuracy {accuracy:g} "
                             f"cannot be confirmed")
    elif worst > accuracy:
        result.set_status(6, f"iteration converged but the estimated error (Hc {estimate.Hc:.2g}, "
                             f"Hm {estimate.Hm:.2g}) exceeds the requested accuracy {accuracy:g}")
    result.scalars["converged"] = bool(result.success)


#: measured fall of the domain error when the box is doubled (4-7x in the studies; 4 assumed)
DOMAIN_DECAY = 4.0
#: how much smaller a box correction leaves the domain part than the fixed factor (circular
#: (20, 10) and elliptic (50, 10) at 1025 points: 6-12x; docs/accuracy.md)
CORRECTION_GAIN = 4.0
#: no jump of two grids while the estimated grid error (relative, either film) is above this: the
#: grid is not yet in its asymptotic range (docs/accuracy.md, "The accuracy controller")
PREASYMPTOTIC_GRID = 0.1
#: a line solve jumps three grids at once where two are predicted to leave more than this
#: multiple of the target: two-grid jumps lowered the stated Hm by 4.3-13.4 (median 7.2)
#: against the 8 predicted (docs/accuracy.md, "The accuracy controller")
THREE_GRIDS_BEYOND = 1.5


def refinement_candidates(budget: dict[str, dict[str, float]], accuracy: float, points: int, box: float,
                          tol_factor: float, max_points: int, box_limit: float,
                          corrects: bool = False, grid_gain: dict[str, float] | None = None,
                          two_grids: bool = False, one_grid: bool = False) -> list[Candidate]:
    """The refinements of a steady solve and the larger film error each is predicted to leave:
    one more grid (grid error / 4, or per film / ``grid_gain[film]``), with ``two_grids`` two
    more grids on the same box (grid error / gain^2) and, where those are predicted to miss
    the target by more than :data:`THREE_GRIDS_BEYOND`, three (gain^3), a box twice as wide at
    the same mesh (domain error / :data:`DOMAIN_DECAY`) or on the same points (grid error x 4),
    both, or tolerances ten times tighter (algebraic / 10). No jump of two grids while the grid
    error is above :data:`PREASYMPTOTIC_GRID`, nor with ``one_grid``.

    Where the domain part is not known (its probes did not converge) but the grid part is and
    the known parts miss ``accuracy``, the one candidate is the finer grid, its prediction
    unknown: the finer grid's probes run on a finer mesh and may then measure the domain part
    (Barus (5, 20, theta 4) at 1 %: the 257-point solve's probes failed).

    With ``corrects`` (the solve corrects its films for the box), a finer grid on a wider box,
    and on a box at least twice the default a finer grid on the same box, also carries the
    prediction hoped for when its box series allows a correction (the domain part a further
    :data:`CORRECTION_GAIN` smaller), for the controller's hopeful step."""
    dom_known = all(math.isfinite(budget["domain"][k]) for k in ("Hc", "Hm"))
    grid_known = all(math.isfinite(budget["grid"][k]) for k in ("Hc", "Hm"))

    gain = {"Hc": 4.0, "Hm": 4.0, **(grid_gain or {})}

    def total(g: float, d: float, a: float, steps: int = 0) -> float:
        # steps: grids finer on the same mesh family, each dividing a film's grid part by its gain
        return max(g * gain[k] ** -steps * budget["grid"][k] + d * (budget["domain"][k] if dom_known else 0.0)
                   + a * budget["algebraic"][k] for k in ("Hc", "Hm"))

    here = Resolution(points, box, tol_factor)
    finer = here.finer()
    if not dom_known:
        if grid_known and finer.points <= max_points and total(1.0, 0.0, 1.0) > accuracy:
            return [Candidate("points", finer, 1, math.nan)]
        return []
    wide = 2.0 * box <= box_limit
    out = []
    if wide:
        # twice the box on the same points: a coarser mesh (grid error x4 at second order)
        # that pays where the box error dominates and the mesh is fine for the film's scale
        out.append(Candidate("box", replace(here, box=2.0 * box), 0, total(4.0, 1.0 / DOMAIN_DECAY, 1.0)))
    if finer.points <= max_points:
        # on a box at least twice the default the correction is measured one box lower
        # (point_box_series), so the finer grid on the same box may hope for it too
        out.append(Candidate("points", finer, 1, total(1.0, 1.0, 1.0, 1),
                             total(1.0, 1.0 / CORRECTION_GAIN, 1.0, 1) if corrects and box >= 2.0
                             else math.nan))
        if wide:
            out.append(Candidate("points+box", replace(finer, box=2.0 * box), 1,
                                 total(1.0, 1.0 / DOMAIN_DECAY, 1.0),
                                 total(1.0, 1.0 / (DOMAIN_DECAY * CORRECTION_GAIN), 1.0) if corrects
                                 else math.nan))
        rough = max(budget["grid"].values()) > PREASYMPTOTIC_GRID or one_grid
        two = finer.finer()
        if two_grids and two.points <= max_points and not rough:
            out.append(Candidate("2 points", two, 2, total(1.0, 1.0, 1.0, 2)))
            three = two.finer()
            if three.points <= max_points and total(1.0, 1.0, 1.0, 2) > THREE_GRIDS_BEYOND * accuracy:
                out.append(Candidate("3 points", three, 3, total(1.0, 1.0, 1.0, 3)))
        if two.points <= max_points and wide and not rough:
            out.append(Candidate("2 points+box", replace(two, box=2.0 * box), 2,
                                 total(0.25, 1.0 / DOMAIN_DECAY, 1.0)))
    if tol_factor > 1e-4:
        out.append(Candidate("tolerance", replace(here, tol=0.1 * tol_factor), 0, total(1.0, 1.0, 0.1)))
    return out


def points_needed(budget: dict[str, dict[str, float]], accuracy: float, points: int,
                  order: float = 2.0) -> int | None:
    """Finest grid (points along X, ``2^k m + 1``) predicted to bring the grid part of the
    budget under what the other parts leave of ``accuracy`` (grid error ~ h^order); None when
    the other parts alone exceed it."""
    need = 1.0
    for k in ("Hc", "Hm"):
        rest = accuracy - sum(v[k] for name, v in budget.items() if name != "grid" and math.isfinite(v[k]))
        if rest <= 0.0:
            return None
        need = max(need, (budget["grid"][k] / rest) ** (1.0 / order))
    n = points
    while need > 1.01:  # the prediction is not sharper than 1 %
        n, need = 2 * (n - 1) + 1, need / 2.0
    return n


def _why_short(est: ErrorEstimate, accuracy: float, points: int, max_points: int, box: float,
               box_limit: float) -> str:
    """What the budget says is missing, in the user's terms."""
    b = est.budget
    if any(v == math.inf for v in b["domain"].values()):
        return ("the domain (box truncation) error has no bound: the film changed as much or more "
                "when the box was doubled a second time")
    part = max(("grid", "domain", "algebraic"),
               key=lambda n: max(v if math.isfinite(v) else 0.0 for v in b[n].values()))
    if part == "grid":
        n = points_needed(b, accuracy, points)
        if n is None:
            return "the grid error dominates and the other parts alone exceed the target"
        # within the prediction's 1 % the solve's own grid is the answer, but it missed: the next
        # grid is the one to ask for (circular (5000, 0) at 2 %: 2.035 % stated on 4097 points)
        n = max(n, 2 * (points - 1) + 1)
        return (f"the grid error dominates: about {n} points along X are predicted to meet "
                f"{accuracy:g} (max_points = {max_points}; a larger max_points, --max-points of "
                f"ehl solve or ehl run, allows it)")
    if part == "domain":
        return (f"the domain (box truncation) error dominates at a box {box:g} times the default "
                f"(limit {box_limit:g}); the film depends on the oil far upstream of the contact")
    return "the iteration (algebraic) error dominates"


#: coarser grids solved to convergence (tolerances x 0.1) when the FMG films converge irregularly
#: and the estimate misses the target; one more for a point film not extrapolated
#: (docs/accuracy.md, "Extrapolated films")
REPAIR_LEVELS = 2
#: smallest grid solved for the repair
REPAIR_MIN_POINTS = 65
#: an observed order above this of a film not extrapolated also asks for the repair, met target
#: or not: FMG films off their grids' converged ones can make a sequence look this fast
#: (circular Barus (1000, 20) at 1 %; docs/accuracy.md, "Extrapolated films")
FAST_ORDER = 2.5
#: ... and the order a line's Hc sequence that falls faster than it is estimated with
LINE_FAST_HC_ORDER = 1.5


def decay_could_meet(est: ErrorEstimate, accuracy: float, domain_safety: float = DOMAIN_SAFETY) -> bool:
    """Whether a measured decay of the box change could bring an estimate that misses
    ``accuracy`` within it: the domain part at its smallest, ``DECAY_SAFETY/domain_safety`` of
    the fixed-factor one (a change that stops after the first doubling), would meet it."""
    b = est.budget
    if not max(est.Hc, est.Hm) > accuracy:
        return False
    for k in ("Hc", "Hm"):
        d = b["domain"][k]
        if not math.isfinite(d) or b["grid"][k] + b["algebraic"][k] + d * DECAY_SAFETY / domain_safety > accuracy:
            return False
    return True


def correction_could_meet(est: ErrorEstimate, accuracy: float) -> bool:
    """Whether a box correction could bring an estimate that misses ``accuracy`` within it:
    the grid and algebraic parts alone meet it, the domain part is known."""
    b = est.budget
    if not max(est.Hc, est.Hm) > accuracy:
        return False
    return all(math.isfinite(b["domain"][k]) and b["grid"][k] + b["algebraic"][k] < accuracy
               for k in ("Hc", "Hm"))


def solve_to_accuracy(solve: Any, probe: Any, accuracy: float | None, points: int, max_points: int,
                      box_limit: float = 4.0, refine: bool = True, time_budget: float = math.inf,
                      decay_probe: Any = None, progress: Any = None, dimensions: int = 2,
                      correct_box: bool = False, extrapolate: bool = False,
                      hope_correction: bool = False, start: Any = None,
                      domain_safety: float = DOMAIN_SAFETY, no_film: Any = None,
                      min_points: int = 0) -> Any:
    """Solve, estimate, and refine until the estimated errors of Hc and Hm meet ``accuracy``.

    ``solve(points, box, tol_factor) -> result`` runs the contact's solver on a grid of
    ``points`` along X, the default box scaled by ``box`` and the iteration tolerances scaled
    by ``tol_factor``; ``probe(result, box) -> (dHc, dHm)`` measures the relative change when
    that box is doubled; ``decay_probe(result, box) -> ((d2_Hc, d2_Hm), (d4_Hc, d4_Hm))`` (optional)
    measures the changes of two successive doublings with tight probe solves, and is called
    only when the fixed domain factor alone decides a miss (:func:`decay_could_meet`). The
    part of the budget that dominates is refined: one more FMG grid
    (``points`` doubled, up to ``max_points``), a box twice as wide at the same mesh size
    (twice the points; up to ``box_limit``) or tolerances ten times tighter. With ``refine=False`` (explicit grid or box) the first
    result is only judged. Every solve is recorded in ``result.extra['refinements']``; the wall
    time of the whole sequence (solves, repair solves and domain probes) in
    ``result.extra['wall_total_s']`` and the scalar ``wall_total_s``, the part spent estimating
    (probes, repair solves) in ``estimate_s`` (``wall_s`` stays the
    returned solve's own).

    When the target is not met the returned result is the most accurate one of the sequence
    (smallest estimated error among the solves whose iteration converged), so a finer solve
    that fails to converge never replaces a converged coarser one; its message says why the
    refinement stopped (also in ``result.extra['not_refined_because']``, for callers).
    ``progress(text)``, when given, receives one line per solve of the sequence (grid, box,
    outcome, estimate, seconds so far) and, before each refinement, its predicted time: the
    command line shows them.

    ``time_budget`` (seconds) bounds the sequence: a refinement is not started when its
    predicted time (:func:`~ehl_multigrid.multigrid.controller.predicted_seconds`, ``dimensions`` 2 for point, 1 for line
    contacts) would exceed what is left of it, and the sequence stops once it is spent; the
    most accurate result so far is returned, its status ``inaccurate`` when it misses the
    target. A solve already running is not interrupted.

    With ``correct_box`` the ``decay_probe`` returns a :class:`BoxSeries` and is called where a
    box correction could meet the target (:func:`correction_could_meet`); the returned result's
    films are then corrected for the box (:func:`apply_correction`) and its estimate is theirs.
    With ``extrapolate`` and an ``accuracy``, films whose grid sequence is asymptotic are
    reported extrapolated (:func:`extrapolated`). ``hope_correction`` (with ``correct_box``):
    the contact's box change is expected to decay fast enough for a correction, which the
    controller's hopeful step may count on (:func:`refinement_candidates`). ``start(points) ->
    (points, box)``, when given, chooses the first solve's grid and box (its time counts in the
    sequence's). ``domain_safety`` multiplies a probe's box change into the domain part
    (:func:`estimate_error`). ``no_film(points, box) -> bool``, when given, names the coarser
    grids the sequence found without a positive discrete film: the repair does not solve them.
    ``min_points``: the smallest grid the solver is expected to converge on for this load; a
    first solve that fails on a coarser grid (the planner caps its first grid) moves to the next.
    """
    clock = EstimateClock()
    probe, decay_probe, start = clock.timed(probe), clock.timed(decay_probe), clock.timed(start)
    steady = _SteadyControl(solve, probe, decay_probe, accuracy, refine, max_points, box_limit,
                            dimensions, correct_box, extrapolate and accuracy is not None,
                            correct_box and hope_correction, domain_safety, no_film, min_points, clock)
    t0 = time.perf_counter()
    first = Resolution(points) if start is None or not refine else Resolution(*start(points))
    out = control(steady, first, accuracy, refine=refine, time_budget=time_budget,
                  max_points=max_points, progress=progress, started=t0,
                  fallback=Resolution(points) if first != Resolution(points) else None)
    res = out.result
    res.extra["refinements"] = [vars(s) for s in out.steps]
    if out.converged and out.why:
        if res is not out.last:
            n_b = res.X.shape[0] if getattr(res, "X", None) is not None else "?"
            res.message += f"; returned the most accurate solve of the sequence ({n_b} points)"
        res.message += f"; not refined further: {out.why}"
        res.extra["not_refined_because"] = out.why
    apply_correction(res)
    return _stamp(res, t0, clock.seconds)


class EstimateClock:
    """Seconds spent in the functions it wraps (:meth:`timed`), a call inside another timed call
    counted once: the estimator's share of an accuracy sequence (probes before the first solve,
    repair solves, the estimates)."""

    def __init__(self) -> None:
        self.seconds = 0.0
        self._depth = 0

    def timed(self, f: Any) -> Any:
        if f is None:
            return None

        def run(*args: Any, **kw: Any) -> Any:
            if self._depth:
                return f(*args, **kw)
            self._depth += 1
            t0 = time.perf_counter()
            try:
                return f(*args, **kw)
            finally:
                self.seconds += time.perf_counter() - t0
                self._depth -= 1
        return run


class _SteadyControl:
    """The steady line or point solve as a :class:`~ehl_multigrid.multigrid.controller.Controlled`
    physics: the estimate of :func:`estimate_error` with the domain probes, the repair of
    irregular FMG films (:data:`REPAIR_LEVELS`) and the decay probe; the candidates of
    :func:`refinement_candidates`."""

    def __init__(self, solve: Any, probe: Any, decay_probe: Any, accuracy: float | None, refine: bool,
                 max_points: int, box_limit: float, dimensions: int, correct_box: bool = False,
                 extrapolate: bool = False, hope_correction: bool = False,
                 domain_safety: float = DOMAIN_SAFETY, no_film: Any = None, min_points: int = 0,
                 clock: EstimateClock | None = None) -> None:
        self._solve, self.probe, self.decay_probe = solve, probe, decay_probe
        self.no_film, self.min_points = no_film, min_points
        #: the seconds spent estimating over the sequence (probes, repair solves, the estimate)
        self.clock = EstimateClock() if clock is None else clock
        self.domain_safety = domain_safety
        self.correct_box, self.extrapolate = correct_box, extrapolate
        self.hope_correction = hope_correction
        self.accuracy, self.refine = accuracy, refine
        self.max_points, self.box_limit, self.dimensions = max_points, box_limit, dimensions
        # per box (and cell aspect): films of the converged solves (the same discrete problem on
        # each grid; a point solve that fell back to square cells is another problem)
        self.finals: dict[tuple[float, Any], dict[int, tuple[float, ...]]] = {}
        self.last_domain: tuple[float, float] | None = None
        # per box: (points, change) of a box change measured far below the target
        self.small_domain: dict[tuple[float, Any], tuple[int, tuple[float, float]]] = {}

    def solve(self, at: Resolution) -> Any:
        return self._solve(at.points, at.box, at.tol)

    def converged(self, result: Any) -> bool:
        return bool(result.success)

    def failure(self, result: Any) -> str:
        return f"{result.status_name}: {result.message.split(';')[0]}"

    def remedy(self, result: Any, at: Resolution, first: bool) -> Resolution | None:
        # a grid too coarse for the load: the finer grid is the only remedy. So is a first grid
        # that fails below the solver's smallest for the load: elliptic theta 10 at (5000, 10)
        # ends max_cycles on the planner's 2049 points and needs 8193 (point.problem.min_points)
        if result.status_name == "film_not_positive" or (first and at.points < self.min_points):
            return at.finer()
        return None

    def estimate(self, res: Any, at: Resolution, record: Any) -> tuple[float, float]:
        """The estimate of one solve (probes and repair solves included), timed by :attr:`clock`."""
        return self.clock.timed(self._estimate)(res, at, record)

    def _estimate(self, res: Any, at: Resolution, record: Any) -> tuple[float, float]:
        box, tol = at.box, at.tol
        key = (box, getattr(res, "extra", {}).get("y_ratio"))
        small = self.small_domain.get(key)
        if small is not None and self.accuracy is not None and small[0] < at.points:
            # measured on a coarser grid of this box, far below the target: the finer grid's
            # probes would cost more than the refinement and change only a negligible part
            dom = small[1]
            res.extra["domain_note"] = (f"domain error from the box change measured with the "
                                        f"{small[0]}-point solve of this box (below "
                                        f"{DOMAIN_REUSE_BELOW:g} of the target)")
        else:
            dom = self.probe(res, box)
        if (dom is not None and self.accuracy is not None
                and self.domain_safety * max(abs(dom[0]), abs(dom[1])) < DOMAIN_REUSE_BELOW * self.accuracy):
            self.small_domain.setdefault(key, (at.points, dom))
        if dom is None and self.last_domain is not None:
            # the change measured around a smaller box bounds the one around a wider box
            dom = self.last_domain
            res.extra["domain_note"] = "domain error bounded by the change measured at a smaller box"
        self.last_domain = dom if dom is not None else self.last_domain
        est = estimate_error(res, dom, self.finals.get(key), extrapolate=self.extrapolate,
                             domain_safety=self.domain_safety)
        grid_unknown = not all(math.isfinite(v) for v in est.budget["grid"].values())
        changes: Any = None

        def missed(e: ErrorEstimate) -> bool:
            return self.refine and self.accuracy is not None and max(e.Hc, e.Hm) > self.accuracy

        def short(e: ErrorEstimate) -> bool:
            # a film not extrapolated may be held back by the FMG films alone (the default
            # scene, (216, 8.9) on 513 points: FMG Hm ratios 2.0, 2.5; converged 5.5, 3.1);
            # a line contact extrapolates Hc only
            return self.extrapolate and len(e.extrapolated) < (1 if self.dimensions == 1 else 2)

        def repair(e: ErrorEstimate) -> ErrorEstimate:
            # the FMG films may be what is irregular: the coarser grids solved to convergence;
            # also where the FMG left no films below the finest grid (a start from a given
            # solution), so that every result states its grid error, explicit grids too
            known = self.finals.setdefault(key, {})
            n = at.points
            for _ in range(REPAIR_LEVELS + int(short(e))):
                n = (n - 1) // 2 + 1
                if n < REPAIR_MIN_POINTS or n in known or (self.no_film is not None and self.no_film(n, box)):
                    continue
                rc = self._solve(n, box, 0.1 * tol)
                record(Refinement(n, box, 0.1 * tol, math.nan, math.nan, rc.wall_s, "levels"))
                finer = known.get(2 * (n - 1) + 1) or (final_films(res) if 2 * (n - 1) + 1 == at.points else None)
                # a floor's films only three grids or more below the solve's: they then enter the
                # asymptotic test, not the finest ratio that sets the stated error (extrapolated)
                deep = 8 * (n - 1) <= at.points - 1
                if rc.success or (deep and rc.status_name == "residual_floor" and floor_films_usable(rc, finer)):
                    key_c = (box, getattr(rc, "extra", {}).get("y_ratio"))
                    self.finals.setdefault(key_c, {})[n] = final_films(rc)
            return estimate_error(res, dom, known, decay=changes, extrapolate=self.extrapolate,
                                  domain_safety=self.domain_safety)

        def could(e: ErrorEstimate, target: float) -> bool:
            if self.correct_box:
                return correction_could_meet(e, target)
            return decay_could_meet(e, target, self.domain_safety)
        b = est.budget
        # a film held back only by its FMG films (not irregular) while the domain part decides
        # the miss: the box series first, the converged coarser grids only if it still misses
        # (circular (20, 10) and elliptic (50, 10, theta 0.3) at 0.5 %: the series met, the
        # repair's 0.6 and 1.6 s were not needed)
        domain_first = (not est.irregular and not grid_unknown and self.accuracy is not None
                        and self.decay_probe is not None and could(est, self.accuracy)
                        and max(b["domain"].values()) > max(b["grid"].values()))
        repaired = False
        # a line's Hm with logarithmic faces converges within the FMG films' own algebraic
        # error on the coarse grids ((5, 20): FMG films falling, converged ones rising), so its
        # sequence is always taken from converged coarser solves (docs/accuracy.md)
        if (((est.irregular or short(est)) and (grid_unknown or missed(est)) and not domain_first)
                or self.superconvergent(est, at.points, key) or self.filmless_below(res, est, at.points, key)
                or log_faces(res)):
            est, repaired = repair(est), True
        if self.accuracy is not None and self.decay_probe is not None and could(est, self.accuracy):
            if self.correct_box:
                # what the grid and iteration parts leave of the target to the corrected box
                b = est.budget
                left = tuple(self.accuracy - b["grid"][k] - b["algebraic"][k] for k in ("Hc", "Hm"))
                changes = self.decay_probe(res, box, left)
            else:
                changes = self.decay_probe(res, box)
            if changes is not None:
                if not isinstance(changes, BoxSeries):
                    res.extra["domain_changes"] = [list(changes[0]), list(changes[1])]
                elif changes.d4 is not None:
                    res.extra["domain_changes"] = [list(changes.d2), list(changes.d4)]
                else:  # measured one box lower: [below, d2]
                    res.extra["domain_changes_below"] = [list(changes.below), list(changes.d2)]
                est = estimate_error(res, dom, self.finals.get(key), decay=changes,
                                     extrapolate=self.extrapolate, domain_safety=self.domain_safety)
        if not repaired and (est.irregular or short(est)) and missed(est):
            est = repair(est)
        if None not in (res.scalars.get("Hc_venner"), res.scalars.get("Hm_venner")):
            self.finals.setdefault(key, {})[at.points] = final_films(res)
        attach_estimate(res, est, self.accuracy)
        return est.Hc, est.Hm

    def filmless_below(self, res: Any, est: ErrorEstimate, points: int, key: Any) -> bool:
        """A point film not extrapolated whose grid sequence starts just above a grid without a
        positive film: the FMG film of the grid below the three the Richardson estimate reads
        is not positive, while the grid below the solve's is not yet solved to convergence. The
        FMG films next to that grid carry large algebraic errors (interpolated from a solution
        that is no film; docs/accuracy.md, "Grid error")."""
        if self.dimensions == 1 or ((points - 1) // 2 + 1) in self.finals.get(key, {}):
            return False
        top = int(getattr(res, "levels", 0) or 0) - 1
        fmg = [d for d in (getattr(res, "fmg", None) or []) if d.get("level", -1) < top]
        if len(fmg) < 3:
            return False
        below = fmg[-3]
        return (any(f not in est.extrapolated for f in ("Hc", "Hm"))
                and not (below.get("Hc", 0.0) > 0.0 and below.get("Hm", 0.0) > 0.0))

    def superconvergent(self, est: ErrorEstimate, points: int, key: Any) -> bool:
        """A film not extrapolated whose FMG films converge faster than :data:`FAST_ORDER`,
        while the grid below is not yet solved to convergence: the FMG films' own algebraic
        error may be what makes the sequence look fast."""
        if ((points - 1) // 2 + 1) in self.finals.get(key, {}):
            return False
        return any(math.isfinite(o) and o > FAST_ORDER
                   for f, o in (("Hc", est.order_Hc), ("Hm", est.order_Hm)) if f not in est.extrapolated)

    def candidates(self, res: Any, at: Resolution) -> list[Candidate]:
        gain = None
        if self.dimensions == 1:
            # a line film's stated grid part falls as its grid differences do, by 2^p per grid,
            # p the observed order up to LINE_HM_PREDICT_ORDER for Hm (docs/accuracy.md); a
            # jump of two grids costs at most twice the solve it replaces in one dimension
            est = res.error
            gain = {k: 2.0 ** min(max(o, 1.0), cap) if math.isfinite(o) else 2.0
                    for k, o, cap in (("Hc", est.order_Hc, 2.0), ("Hm", est.order_Hm, LINE_HM_PREDICT_ORDER))}
        # an irregular sequence's first-order bound says nothing of how fast the next grids
        # lower it: one grid at a time, whose film judges the sequence again
        return refinement_candidates(res.error.budget, self.accuracy, at.points, at.box, at.tol,
                                     self.max_points, self.box_limit, self.hope_correction,
                                     grid_gain=gain, two_grids=self.dimensions == 1,
                                     one_grid=res.error.irregular and log_faces(res))

    def why_short(self, res: Any, at: Resolution) -> str:
        est = res.error
        why = (f"no refinement within {self.max_points} points and a box of {self.box_limit:g} "
               f"times the default is predicted to help")
        if math.isfinite(max(est.Hc, est.Hm)):
            why += ": " + _why_short(est, self.accuracy, at.points, self.max_points, at.box, self.box_limit)
        return why


def _stamp(res: Any, t0: float, estimate_s: float | None = None) -> Any:
    """Record the wall time of the whole accuracy sequence on the returned result, and of its
    estimates (``estimate_s``: probes, repair solves and the estimate itself) where measured."""
    total = time.perf_counter() - t0
    stamps = {"wall_total_s": total} if estimate_s is None else {"wall_total_s": total, "estimate_s": estimate_s}
    res.extra.update(stamps)
    if isinstance(getattr(res, "scalars", None), dict):
        res.scalars.update(stamps)
    return res
