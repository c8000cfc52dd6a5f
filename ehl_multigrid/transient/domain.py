"""The box part of a transient run's error: the truncation of its domain.

A run solves every step on one box, with ``P = 0`` at its inlet ``xmin`` (point: on all four
sides). That truncation is measured on the run's steady start, as the steady solvers measure
theirs: the change of the steady films when the inlet is moved upstream by the box length at
equal mesh size (line: :func:`~ehl_multigrid.line.solver.line_domain_change`; point: the box
doubled in X and Y, :func:`~ehl_multigrid.point.solve.point_domain_change`), times the steady
solver's factor (:data:`~ehl_multigrid.multigrid.accuracy.LINE_DOMAIN_SAFETY`,
:data:`~ehl_multigrid.multigrid.accuracy.DOMAIN_SAFETY`). A feature passing through the
contact moves the films by about the steady film's own box change: appendix C at 4240 N
(M 10.2, L 7.6), a 20 nm dent at S = 0 on 2049 points, inlet moved from -4.5 to -10.5 at
equal mesh: the run's Hc(T) and Hm(T) moved by at most 0.43 % and 0.44 % of the steady film,
the steady films by 0.41 % and 0.33 % (docs/transient.md, "What a run's films are worth").

A starved inlet (the film content below 1 at ``xmin``) carries the supplied layer unpressurised
up to its meniscus, so moving the inlet further upstream changes nothing: its part is zero.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np

from ..multigrid.accuracy import DOMAIN_SAFETY, LINE_DOMAIN_SAFETY


def starved_inlet(steady: Any) -> bool:
    """Whether the steady start's film content is below 1 somewhere on its inlet boundary
    (line: the first node; point: the first column)."""
    theta = steady.extra.get("theta") if getattr(steady, "extra", None) else None
    if theta is None:
        return False
    theta = np.asarray(theta)
    inlet = theta[0] if theta.ndim == 1 else theta[:, 0]
    return bool(np.min(inlet) < 1.0)


def box_part(run: Any, line: bool) -> tuple[dict[str, float] | None, str]:
    """The box part ``{"Hc", "Hm"}`` (relative, of the steady films) of ``run`` (a completed
    :class:`~.result.TransientResult`), with a note saying how it was found; None with the
    reason when the probe solves do not converge."""
    steady = run.steady
    xmin = float(run.X[0])
    if starved_inlet(steady):
        return {"Hc": 0.0, "Hm": 0.0}, (
            f"box part zero: the inlet at X = {xmin:g} is starved (film content below 1 there), so "
            f"moving it upstream changes nothing")
    if line:
        from ..line.solver import line_domain_change

        change = line_domain_change(run.problem, run.options, steady)
        safety, how = LINE_DOMAIN_SAFETY, "the inlet moved upstream by the box length"
    else:
        from ..point.solve import point_domain_change

        change = point_domain_change(run.problem, replace(run.options, far_field=False), steady)
        safety, how = DOMAIN_SAFETY, "the box doubled in X and Y"
    if change is None or not all(math.isfinite(c) for c in change):
        return None, (f"box part not measured: the steady probes with {how} at equal mesh did not "
                      f"converge")
    part = {"Hc": safety * abs(float(change[0])), "Hm": safety * abs(float(change[1]))}
    return part, (f"box part: {safety:g} times the steady films' change with {how} at equal mesh "
                  f"(Hc {change[0]:+.2g}, Hm {change[1]:+.2g}; inlet at X = {xmin:g})")
