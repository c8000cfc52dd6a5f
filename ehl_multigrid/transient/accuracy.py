"""Time-discretisation error estimate of a transient run (Richardson in the time step).

BDF2 is second order in ``dT``: with the same grid and start, the run at ``2 dT`` differs
from the run at ``dT`` by about ``(2^2 - 1)`` times the time error of the finer run, so

``e_T(dT) ~ TIME_SAFETY max_T |H(dT) - H(2 dT)| / 3``

over the common time levels (``/1`` for backward Euler), with a safety factor of 2. A run whose steps are sized by a
local error tolerance (``time_tol``) is compared instead with a run at
:data:`TIGHTER_TOL` of its tolerance (steps about half as long):
``e_T(tol) ~ ADAPTIVE_FACTOR max_T |H(tol) - H(tol/8)|`` (:func:`adaptive_time_error`); that
run's output step is half the run's, so that where both would take their largest step (a film
that changes slowly) the two still differ by the time error of that step.

The grid (space) part comes from the same run, with the same time steps, on the grids with half
and a quarter of the intervals (:func:`grid_error`): Richardson in the mesh size on the largest
film differences over the run, as the steady films' grid part
(:func:`~ehl_multigrid.multigrid.accuracy.richardson`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..multigrid.accuracy import richardson
from .result import TransientResult

#: the fixed-step time part over its Richardson term: the runs are not quite in BDF2's
#: asymptotic range (true / Richardson 1.34-1.71 at the first step and up to 1.6 at an error
#: floor; docs/transient.md, "A time step refined to a target")
TIME_SAFETY = 2.0


def courant(run: TransientResult) -> float:
    """Mesh sizes per step of ``run`` at the faster of its feature and the mean flow."""
    return run.dt * max(abs(run.speed), 1.0) / abs(float(run.X[1] - run.X[0]))


#: a coarse run at this Courant number or above (the default step's) is outside BDF2's
#: asymptotic range: the Richardson term is taken at first order (docs/transient.md)
PREASYMPTOTIC_COURANT = 1.0 - 1e-9


def time_error(fine: TransientResult, coarse: TransientResult) -> dict[str, float]:
    """Relative time errors of Hc(T) and Hm(T) of ``fine`` (step dT) from ``coarse`` (step
    2 dT, same grid, feature and start): :data:`TIME_SAFETY` times the Richardson term
    ``|H(dT) - H(2 dT)| / (2^p - 1)``, max over common times, over the smooth steady film;
    ``p = 1`` where the coarse run moves a mesh size per step or more
    (:data:`PREASYMPTOTIC_COURANT`): a 0.5 um dent through the glass-disc tribometer at that
    step left the minimum film at its smooth value, and the second-order term stated 0.090 of
    the film for a true 0.15 (the first-order term 0.27)."""
    if not math.isclose(coarse.dt, 2.0 * fine.dt, rel_tol=1e-9) or coarse.X.size != fine.X.size:
        raise ValueError("time_error needs the same grid and a coarse run at twice the step")
    p = 2 if fine.scheme == "bdf2" and courant(coarse) < PREASYMPTOTIC_COURANT else 1
    m = min(coarse.Hc.size, (fine.Hc.size + 1) // 2)
    out = {}
    for name in ("Hc", "Hm"):
        f, c = getattr(fine, name)[::2][:m], getattr(coarse, name)[:m]
        out[name] = float(TIME_SAFETY * np.max(np.abs(f - c)) / (2**p - 1) / fine.steady_film(name))
    return out


#: the time tolerance of the second run of an adaptive run's time error, as a fraction of the
#: run's: BDF2's steps scale as tol^(1/3), so this halves them
TIGHTER_TOL = 1.0 / 8.0
#: the time error of an adaptive run over its largest difference from the run at
#: :data:`TIGHTER_TOL` of its tolerance (docs/transient.md, "The time error a run states")
ADAPTIVE_FACTOR = 2.0


def adaptive_time_error(run: TransientResult, tight: TransientResult) -> dict[str, float]:
    """Relative time errors of Hc(T) and Hm(T) of ``run`` (steps sized by ``time_tol``) from
    ``tight`` (the same run at :data:`TIGHTER_TOL` of that tolerance and half the output step,
    same grid, feature and start): :data:`ADAPTIVE_FACTOR` times the largest difference over
    the common output times, over the smooth steady film (as :func:`time_error`)."""
    if not math.isclose(tight.dt, 0.5 * run.dt, rel_tol=1e-9) or tight.X.size != run.X.size:
        raise ValueError("adaptive_time_error needs the same grid and a second run at half the output step")
    m = min(run.Hc.size, (tight.Hc.size + 1) // 2)
    return {name: float(ADAPTIVE_FACTOR * np.max(np.abs(getattr(run, name)[:m] - getattr(tight, name)[::2][:m]))
                        / run.steady_film(name)) for name in ("Hc", "Hm")}


def tighter_run_options(run: TransientResult, time_tol: float) -> dict[str, Any]:
    """The step options of the second run of :func:`adaptive_time_error` for ``run`` (made
    with ``time_tol``)."""
    return {"dt": 0.5 * run.dt, "steps": 2 * run.planned_steps, "t_end": None,
            "time_tol": time_tol * TIGHTER_TOL}



#: the grid part's largest observed order (the squeeze and wedge terms are differenced to first
#: or second order; a moving feature is not resolved better than that)
GRID_MAX_ORDER = 2.0


def grid_error(fine: TransientResult, coarser: list[TransientResult]) -> dict[str, float]:
    """Relative grid (space) errors of Hc(T) and Hm(T) of ``fine`` from the same run on grids
    with half (``coarser[0]``) and, when given, a quarter (``coarser[1]``) of its intervals
    (same box, time step, steps and start), over the smooth steady film of ``fine``; also the
    observed order of each (``order_Hc``, ``order_Hm``; NaN from two grids or an irregular
    sequence).

    The largest differences over the common times, ``d2 = max_T |H_h - H_2h|`` and ``d1 =
    max_T |H_2h - H_4h|``, are treated as the film differences of a grid sequence
    (:func:`~ehl_multigrid.multigrid.accuracy.richardson`, safety
    :data:`~ehl_multigrid.multigrid.accuracy.GRID_SAFETY`): the observed order
    ``log2(d1/d2)`` where it lies in [1, 4] (capped at :data:`GRID_MAX_ORDER`), else first
    order; at least half of ``d1`` where the order is irregular or above 2 (a difference over
    the run may fall fast by accident: the minimum film is a nodal minimum); from two grids,
    first order (docs/transient.md, "What a run's films are worth")."""
    runs = [fine, *coarser]
    for r in coarser:
        if not math.isclose(r.dt, fine.dt, rel_tol=1e-9) or not (
                math.isclose(float(r.X[0]), float(fine.X[0])) and math.isclose(float(r.X[-1]), float(fine.X[-1]))):
            raise ValueError("grid_error needs the same box and time step on every grid")
    m = min(r.Hc.size for r in runs)
    out: dict[str, float] = {}
    for name in ("Hc", "Hm"):
        series = [np.asarray(getattr(r, name)[:m], dtype=float) for r in runs]
        diffs = [float(np.max(np.abs(a - b))) for a, b in zip(series, series[1:], strict=False)]
        # the differences as those of a film on grids refined by two: coarse ... fine
        values = [float(v) for v in np.cumsum([0.0, *diffs[::-1]])]
        rich = richardson(values, max_order=GRID_MAX_ORDER, earlier_half=True)
        out[name] = float(rich.error / fine.steady_film(name))
        out[f"order_{name}"] = float(rich.order) if rich.regular else math.nan
    return out
