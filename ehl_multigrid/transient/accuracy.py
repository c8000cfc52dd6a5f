"""Time-discretisation error estimate of a transient run (Richardson in the time step).

BDF2 is second order in ``dT``: with the same grid and start, the run at ``2 dT`` differs
from the run at ``dT`` by about ``(2^2 - 1)`` times the time error of the finer run, so

``e_T(dT) ~ TIME_SAFETY max_T |H(dT) - H(2 dT)| / 3``

over the common time levels (``/1`` for backward Euler), with a safety factor of 2. A run whose steps are sized by a
local error tolerance (``time_tol``) is compared instead with a run at
:data:`TIGHTER_TOL` of its tolerance (steps about half as long):
``e_T(tol) ~ ADAPTIVE_FACTOR max_T |H(tol) - H(tol/8)|`` (:func:`adaptive_time_error`); that
run's output step is half the run's, so that where both would take their largest step (a film
that changes slowly) the two still differ by the time error of that step. The
spatial error is that of the grid: the steady core's grid error constants
(``ehl_multigrid.multigrid.accuracy``) or a grid-refinement pair measure it
(validation/transient).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

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

