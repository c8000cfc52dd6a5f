"""Finest grid of the multigrid solvers for a tolerance, from measured grid-error constants.

Both solvers converge at second order in the mesh size (validation/line, validation/point), so
the relative error of the central film on a grid of ``N`` points along X is ``C(M) / (N - 1)^2``.
``C`` was measured against a reference-resolution solve by the accuracy-cost study
(validation/pareto, written to ``ehl_multigrid/data/grid_error_<contact>.json`` by
validation/plan/planner_tables.py) at a few M; between them ``log C`` is interpolated linearly in
``log M`` and beyond them extrapolated with the end slope. The grid is the smallest ``2^k + 1``
whose predicted error is at most half the tolerance (the other half is left to the algebraic
error and to the interpolation in M), within the solver's limits.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

#: per contact: (smallest grid the solver is run on, largest grid the planner will choose)
LIMITS = {"line": (1025, 16385), "point": (129, 1025)}


@dataclass(frozen=True)
class GridChoice:
    """A grid and why: ``points`` along X, the predicted relative error of Hc on it, the
    constant ``C`` used and where it comes from."""

    points: int
    predicted_error: float
    C: float
    source: str

    @property
    def reason(self) -> str:
        return (f"{self.points} points: predicted grid error of Hc {self.predicted_error:.2g} "
                f"(C = {self.C:.3g}, {self.source})")

    def first_grid_reason(self, tolerance: float) -> str:
        """The reason as the accuracy loop's first grid for ``tolerance``: where the prediction
        misses half the tolerance the grid is the planner's largest, refined from by the loop."""
        capped = self.predicted_error > 0.5 * tolerance
        return (f"first grid {self.reason}"
                + ("; the largest first grid: the solver refines from it towards the tolerance" if capped else ""))


@lru_cache(maxsize=4)
def _table(contact: str) -> dict | None:
    res = resources.files("ehl_multigrid") / "data" / f"grid_error_{contact}.json"
    return json.loads(res.read_text()) if res.is_file() else None


def grid_error_constant(contact: str, M: float) -> tuple[float, str]:
    """``C(M)`` of ``error = C / (N - 1)^2`` and its source (a prior when no table is installed)."""
    tab = _table(contact)
    if tab is None:
        # prior: the line study's M = 100 value, scaled linearly in M
        return 1.3e4 * max(M, 1.0) / 100.0, "prior (no measured grid-error table installed)"
    Ms = [math.log(m) for m in tab["M"]]
    Cs = [math.log(c) for c in tab["C"]]
    x = math.log(max(M, 1e-12))
    if len(Ms) == 1:
        return math.exp(Cs[0]), tab["source"]
    k = 0
    while k < len(Ms) - 2 and x > Ms[k + 1]:
        k += 1
    t = (x - Ms[k]) / (Ms[k + 1] - Ms[k])
    return math.exp(Cs[k] + t * (Cs[k + 1] - Cs[k])), tab["source"]


def solver_grid(contact: str, M: float, tolerance: float, floor: int | None = None) -> GridChoice:
    """Smallest grid whose predicted grid error of Hc is <= tolerance / 2 (see module docstring).

    ``floor`` raises the smallest grid (e.g. the point solver's ``min_points(M)``).
    """
    lo, hi = LIMITS["line" if contact == "line" else "point"]
    if floor is not None:
        lo = max(lo, int(floor))
    C, src = grid_error_constant("line" if contact == "line" else "point", M)
    need = math.sqrt(C / (0.5 * tolerance))
    n = lo
    while n - 1 < need and n < hi:
        n = 2 * (n - 1) + 1
    return GridChoice(n, C / (n - 1) ** 2, C, src)
