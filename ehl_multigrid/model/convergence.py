"""Convergence reports shared by every iterative solver in the package.

Modelled on scipy.optimize's result objects: one report carries ``converged``, a message,
iteration counts and the histories, so callers never parse printed text.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .errors import ConvergenceError


@dataclass
class ConvergenceReport:
    """Outcome of an iterative solve.

    Attributes
    ----------
    converged : bool
        True only when every stated tolerance was met.
    message : str
        Why the solver stopped.
    iterations : int
        Cycles (multigrid) or outer iterations performed.
    residual_history : ndarray
        Residual norm after each iteration.
    load_error_history : ndarray
        Relative load-balance error after each iteration (empty where not applicable).
    tolerances : dict
        The tolerances the verdict was judged against.
    work_units : float
        Cost in relaxations of the finest grid (multigrid), or NaN.
    wall_s : float
        Wall-clock time [s].
    extra : dict
        Solver-specific history (per-level residuals, FMG differences, actions taken ...).
    """

    converged: bool
    message: str
    iterations: int = 0
    residual_history: np.ndarray = field(default_factory=lambda: np.zeros(0))
    load_error_history: np.ndarray = field(default_factory=lambda: np.zeros(0))
    tolerances: dict[str, float] = field(default_factory=dict)
    work_units: float = float("nan")
    wall_s: float = float("nan")
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def success(self) -> bool:
        """Alias of ``converged`` (scipy naming)."""
        return self.converged

    def scalars(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "converged": bool(self.converged),
            "message": self.message,
            "iterations": int(self.iterations),
            "work_units": float(self.work_units),
            "wall_s": float(self.wall_s),
        }
        if self.residual_history.size:
            out["final_residual"] = float(self.residual_history[-1])
        if self.load_error_history.size:
            out["load_error"] = float(self.load_error_history[-1])
        for k, v in self.tolerances.items():
            out[f"tol_{k}"] = float(v)
        return out

    def histories(self) -> dict[str, np.ndarray]:
        out = {"residual": np.asarray(self.residual_history, dtype=float)}
        if self.load_error_history.size:
            out["load_error"] = np.asarray(self.load_error_history, dtype=float)
        for k, v in self.extra.items():
            arr = np.asarray(v)
            if arr.dtype.kind in "fiub" and arr.size:
                out[k] = arr
        return out


def check_finite(name: str, values: np.ndarray, report: ConvergenceReport | None = None, hint: str = "") -> None:
    """Raise :class:`ConvergenceError` if ``values`` holds NaN or inf."""
    arr = np.asarray(values)
    if not np.all(np.isfinite(arr)):
        bad = int(np.count_nonzero(~np.isfinite(arr)))
        raise ConvergenceError(f"{name} contains {bad} non-finite value(s) (NaN/inf)", report, hint)
