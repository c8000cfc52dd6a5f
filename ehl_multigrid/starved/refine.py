"""What the starved line and point solvers share around their solves: the accuracy
controller's glue (:class:`StarvedControl`; the geometry supplies the solve, the estimate and
the error a finer grid is predicted to leave) and the scalars that compare a starved film
with the supply and with the flooded film."""

from __future__ import annotations

import math
from typing import Any

from ..multigrid.controller import Candidate, ControlOutcome, Resolution
from ..multigrid.result import EHLResult


class StarvedControl:
    """A starved solve as a :class:`~ehl_multigrid.multigrid.controller.Controlled` physics
    whose one refinement is the grid. A geometry provides ``solve``, ``estimate`` and
    :meth:`predicted`, and may provide a :meth:`remedy` for a failed first grid."""

    #: said after the reason when the next grid exceeds ``max_points``
    raise_hint = ""
    #: why a finer grid is not worth solving
    not_worth = "a finer grid is not predicted to lower the error by 10 %"

    def __init__(self, accuracy: float | None, estimate: bool, max_points: int) -> None:
        self.accuracy, self.with_estimate, self.max_points = accuracy, estimate, max_points

    def converged(self, result: EHLResult) -> bool:
        return bool(result.success)

    def failure(self, result: EHLResult) -> str:
        return f"{result.status_name}: {result.message.splitlines()[0] if result.message else ''}"

    def remedy(self, result: EHLResult, at: Resolution, first: bool) -> Resolution | None:
        return None

    def predicted(self, res: EHLResult, budget: dict[str, dict[str, float]]) -> float:
        """The largest relative film error the next grid is predicted to leave."""
        raise NotImplementedError

    def candidates(self, res: EHLResult, at: Resolution) -> list[Candidate]:
        finer = at.finer()
        if finer.points > self.max_points or getattr(res, "error", None) is None:
            return []
        return [Candidate("points", finer, 1, self.predicted(res, res.error.budget))]

    def why_short(self, res: EHLResult, at: Resolution) -> str:
        if at.finer().points > self.max_points:
            return (f"the next grid ({at.finer().points} points) exceeds max_points = {self.max_points}"
                    f"{self.raise_hint}")
        return self.not_worth


def note_not_refined(res: EHLResult, out: ControlOutcome, action: bool = False) -> None:
    """Why a converged sequence stopped refining: in the message, ``extra`` and (``action``)
    the actions."""
    res.message += f"; not refined further: {out.why}"
    res.extra["not_refined_because"] = out.why
    if action:
        res.actions.append(f"not refined further: {out.why}")


def supply_ratio(rho_c: float, Hc: float, hoil: float) -> float:
    """``rho_c Hc / Hoil``: the central mass flow over the supplied layer (1 in the starved
    limit, NaN at a flooded inlet)."""
    return rho_c * Hc / hoil if math.isfinite(hoil) else math.nan


def compare_flooded(s: dict[str, Any], Hc_ff: float, Hm_ff: float, Hc_ff_moes: float,
                    Hm_ff_moes: float) -> None:
    """The flooded films (Venner, Moes) and the starved films' ratios to them into ``s``."""
    s.update(Hc_flooded_venner=Hc_ff, Hm_flooded_venner=Hm_ff, Hc_flooded=Hc_ff_moes,
             Hm_flooded=Hm_ff_moes, Hc_ratio=s["Hc_venner"] / Hc_ff, Hm_ratio=s["Hm_venner"] / Hm_ff)
