"""Result of a line-contact solve, and its conversion to the core :class:`Result`.

Definitions (Venner's dimensionless variables, MODEL.md 5):

* ``Hc_venner`` -- film at ``X = 0`` (linear interpolation between nodes);
* ``Hm_venner``, ``X_Hm`` -- minimum film and its position (the outlet constriction); the
  minimum is searched where the pressure is positive or within the contact ``|X| <= 1.5``;
* ``p_spike``, ``X_spike`` -- the pressure spike: the outlet-most local maximum of ``P`` at
  ``X > 0`` that is not the central (Hertz-like) maximum; NaN when the pressure has no
  such second peak (low L, or a spike too weak to be resolved);
* Moes-scaled films ``Hc = Hc_venner 8 M / pi`` (likewise ``Hm``);
* physical values (``x = X b``, ``p = P pmax``, ``h = H b^2 / R``) where the geometry is known.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from ..model.convergence import ConvergenceReport
from ..model.results import Result, ScalarAccess
from .problem import LineProblem


def spike_index(X: np.ndarray, P: np.ndarray) -> int | None:
    """Index of the pressure spike (see module docstring), or None."""
    i = np.arange(1, P.shape[0] - 1)
    peak = i[(P[i] > P[i - 1]) & (P[i] >= P[i + 1]) & (X[i] > 0.0) & (P[i] > 0.0)]
    top = int(np.argmax(P))
    if X[top] >= 0.5:  # the spike is higher than the central pressure
        return top
    # a spike rises out of a trough: keep peaks with a lower point between them and the centre
    keep = [k for k in peak if k > top and np.min(P[top:k + 1]) < P[k]]
    return int(keep[-1]) if keep else None


@dataclass
class LineSolution(ScalarAccess):
    problem: LineProblem
    options: dict[str, Any]
    X: np.ndarray
    P: np.ndarray
    H: np.ndarray
    H0: float
    report: ConvergenceReport
    scalars: dict[str, Any] = field(default_factory=dict)

    @classmethod
    def from_solver(cls, solver: Any, report: ConvergenceReport) -> LineSolution:
        lv = solver.levels[-1]
        st = lv.state()
        sol = cls(solver.problem, asdict(solver.options), lv.X.copy(), lv.P.copy(), st.H.copy(),
                  float(lv.H0), report)
        sol._derive(solver)
        return sol

    def _derive(self, solver: Any) -> None:
        pb, X, P, H = self.problem, self.X, self.P, self.H
        Hc = float(np.interp(0.0, X, H))
        zone = (np.abs(X) <= 1.5) | (P > 0)
        idx = np.flatnonzero(zone)
        im = idx[np.argmin(H[idx])]
        isp = spike_index(X, P)
        s = self.scalars
        s["Hc_venner"] = Hc
        s["Hm_venner"] = float(H[im])
        s["X_Hm"] = float(X[im])
        s["Hc"] = pb.moes_from_venner(Hc)
        s["Hm"] = pb.moes_from_venner(H[im])
        s["p_spike"] = float(P[isp]) if isp is not None else math.nan
        s["X_spike"] = float(X[isp]) if isp is not None else math.nan
        s["H0"] = self.H0
        s["load_error"] = float(solver.load_errors[-1]) if solver.load_errors else math.nan
        s["residual"] = float(solver.residuals[-1]) if solver.residuals else math.nan
        s["converged"] = bool(self.report.converged)
        s["levels"] = len(solver.levels)
        s["points"] = int(X.shape[0])
        s["cycles"] = int(len(solver.history))
        s["finest_cycles"] = int(len(solver.residuals))
        s["work_units"] = float(solver.work_units)
        s["wall_s"] = float(self.report.wall_s)
        s["M"], s["L"] = pb.M, pb.L
        s["lambda_venner"], s["alpha_bar"] = pb.lam, pb.alpha_bar
        s["pmax"] = pb.pmax
        if pb.physical:
            scale = pb.b**2 / pb.R
            s["hc"] = Hc * scale
            s["hm"] = float(H[im]) * scale
        else:
            s["hc"] = None
            s["hm"] = None

    # -- convenience ----------------------------------------------------------------------
    def payload(self) -> dict[str, Any]:
        """The JSON payload of ``ehl solve`` (keys of the naming contract first)."""
        keys = ["Hc", "Hm", "Hc_venner", "Hm_venner", "hc", "hm", "p_spike", "load_error",
                "levels", "points", "cycles", "wall_s", "converged", "X_Hm", "X_spike",
                "residual", "work_units", "finest_cycles", "M", "L", "pmax", "alpha_bar",
                "lambda_venner"]
        out = {k: self.scalars.get(k) for k in keys}
        out["actions"] = list(self.report.extra.get("actions", []))
        return out

    def to_result(self, scene: Any = None) -> Result:
        """Core :class:`Result` of kind ``"ehl_line"`` (naming contract of COMMON.md)."""
        pb = self.problem
        res = Result("ehl_line", scene=scene)
        res.add_coord("X", self.X, "-", "x / b")
        res.add_field("P", self.P, "-", ("X",), "p / pmax")
        res.add_field("H", self.H, "-", ("X",), "h R / b^2 (Venner)")
        if pb.physical:
            res.add_coord("x", self.X * pb.b, "m", "rolling direction")
            res.add_field("p", self.P * pb.pmax, "Pa", ("x",), "pressure")
            res.add_field("h", self.H * pb.b**2 / pb.R, "m", ("x",), "film thickness")
        units = {"hc": "m", "hm": "m", "wall_s": "s", "pmax": "Pa"}
        res.add_report(self.report)
        for k, v in self.scalars.items():
            res.set_scalar(k, v, units.get(k, "-"))
        res.meta["problem"] = pb.describe()
        res.meta["options"] = self.options
        res.meta["actions"] = list(self.report.extra.get("actions", []))
        res.meta["definitions"] = (
            "Hc at X=0; Hm minimum film and X_Hm its position; p_spike max P for X >= 0; "
            "Moes films H = H_venner 8M/pi; load_error = h sum P/(pi/2) - 1")
        return res
