"""Time-discretisation error estimate of a transient run (Richardson in the time step).

BDF2 is second order in ``dT``: with the same grid and start, the run at ``2 dT`` differs
from the run at ``dT`` by about ``(2^2 - 1)`` times the time error of the finer run, so

``e_T(dT) ~ max_T |H(dT) - H(2 dT)| / 3``

over the common time levels (``/1`` for backward Euler). The spatial error is that of the
grid: the steady core's grid error constants (``ehl_multigrid.multigrid.accuracy``) or a
grid-refinement pair measure it (validation/transient).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..line.problem import LineProblem
from ..model.errors import InputError
from .result import TransientResult
from .solve import solve_transient_line


def time_error(fine: TransientResult, coarse: TransientResult) -> dict[str, float]:
    """Relative time errors of Hc(T) and Hm(T) of ``fine`` (step dT) from ``coarse`` (step
    2 dT, same grid, feature and start): max over common times, over the smooth steady film."""
    if not math.isclose(coarse.dt, 2.0 * fine.dt, rel_tol=1e-9) or coarse.X.size != fine.X.size:
        raise ValueError("time_error needs the same grid and a coarse run at twice the step")
    p = 2 if fine.scheme == "bdf2" else 1
    m = min(coarse.Hc.size, (fine.Hc.size + 1) // 2)
    out = {}
    for name in ("Hc", "Hm"):
        f, c = getattr(fine, name)[::2][:m], getattr(coarse, name)[:m]
        out[name] = float(np.max(np.abs(f - c)) / (2**p - 1) / fine.steady_film(name))
    return out


def solve_with_time_error(problem: Any, feature: Any, *, dt: float,
                          steps: int, **kw: Any) -> tuple[TransientResult, dict[str, float]]:
    """Run at ``dt`` and at ``2 dt`` (``steps // 2`` steps) and return the fine run with its
    estimated relative time errors of Hc and Hm (costs about 1.5 runs). ``problem`` is a
    :class:`LineProblem` or a point problem (then :func:`~.point_solve.solve_transient_point`)."""
    if kw.get("time_tol") is not None:  # both runs would size their steps to the same error
        raise InputError("solve_with_time_error measures the time error of fixed steps: time_tol "
                         f"= {kw['time_tol']!r} is not allowed with it")
    run = solve_transient_line
    if not isinstance(problem, LineProblem):
        from .point_solve import solve_transient_point as run
    fine = run(problem, feature, dt=dt, steps=steps, **kw)
    # the run at twice the step keeps no checkpoint: it must not overwrite the fine run's
    own = {k: v for k, v in kw.items() if k not in ("checkpoint", "resume")}
    coarse = run(problem, feature, dt=2.0 * dt, steps=max(steps // 2, 1), **own)
    return fine, time_error(fine, coarse)
