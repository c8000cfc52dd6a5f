"""Result of a line-contact solve, and its conversion to the core :class:`Result`.

Definitions (Venner's dimensionless variables, Venner & Lubrecht 2000):

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
from typing import Any

import numpy as np

from ..model.results import Result
from ..multigrid.result import EHLResult


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


#: The answer of a line-contact solve is the package's one EHL result type.
LineSolution = EHLResult


def line_scalars(sol: EHLResult, solver: Any) -> dict[str, Any]:
    """Observables of a line-contact solution (see module docstring)."""
    pb, X, P, H = sol.problem, sol.X, sol.P, sol.H
    Hc = float(np.interp(0.0, X, H))
    zone = (np.abs(X) <= 1.5) | (P > 0)
    idx = np.flatnonzero(zone)
    im = idx[np.argmin(H[idx])]
    isp = spike_index(X, P)
    Hm, X_Hm = float(H[im]), float(X[im])
    if sol.status_name == "start_failed":  # the fields are the initial guess: no film to report
        Hc = Hm = X_Hm = math.nan
    s: dict[str, Any] = {}
    s["Hc_venner"] = Hc
    s["Hm_venner"] = Hm
    s["X_Hm"] = X_Hm
    s["Hc"] = pb.moes_from_venner(Hc)
    s["Hm"] = pb.moes_from_venner(Hm)
    s["p_spike"] = float(P[isp]) if isp is not None else math.nan
    s["X_spike"] = float(X[isp]) if isp is not None else math.nan
    s["H0"] = sol.H0
    s["load_error"] = float(sol.load_error_history[-1]) if sol.load_error_history.size else math.nan
    s["residual"] = float(sol.residual_history[-1]) if sol.residual_history.size else math.nan
    s["converged"] = bool(sol.success)
    s["levels"] = sol.levels
    s["points"] = int(X.shape[0])
    s["cycles"] = int(sol.cycles)
    s["finest_cycles"] = int(sol.residual_history.size)
    s["work_units"] = float(sol.work_units)
    s["wall_s"] = float(sol.wall_s)
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
    return s


def finish_line_result(sol: EHLResult, solver: Any, scene: Any = None) -> EHLResult:
    """Fill the line-contact fields and scalars of a driver's result."""
    hz = solver.hierarchy
    lv = hz.levels[-1]
    st = lv.state()
    sol.contact, sol.solver, sol.scene = "line", "fas", scene
    sol.problem, sol.options = hz.problem, solver.options
    sol.X, sol.P, sol.H, sol.H0 = lv.X.copy(), lv.P.copy(), st.H.copy(), float(lv.H0)
    sol.levels = len(hz.levels)
    sol.extra["newton_iterations"] = hz.newton_iterations
    sol.extra["start_points"] = hz.levels[solver.start_level].n
    sol.scalars = line_scalars(sol, solver)
    sol.builder = line_result
    return sol


def line_result(sol: EHLResult, scene: Any = None) -> Result:
    """Package :class:`Result` of kind ``"ehl_line"`` (the naming contract of EHL results)."""
    pb = sol.problem
    res = Result("ehl_line", scene=scene)
    res.add_coord("X", sol.X, "-", "x / b")
    res.add_field("P", sol.P, "-", ("X",), "p / pmax")
    res.add_field("H", sol.H, "-", ("X",), "h R / b^2 (Venner)")
    if pb.physical:
        res.add_coord("x", sol.X * pb.b, "m", "rolling direction")
        res.add_field("p", sol.P * pb.pmax, "Pa", ("x",), "pressure")
        res.add_field("h", sol.H * pb.b**2 / pb.R, "m", ("x",), "film thickness")
    units = {"hc": "m", "hm": "m", "wall_s": "s", "wall_total_s": "s", "estimate_s": "s", "pmax": "Pa"}
    res.add_report(sol.report)
    for k, v in sol.scalars.items():
        res.set_scalar(k, v, units.get(k, "-"))
    res.set_scalar("status", sol.status_name)
    if sol.error is not None:
        res.meta["error_budget"] = sol.error.budget
        res.meta["accuracy"] = sol.accuracy
    res.meta["problem"] = pb.describe()
    res.meta["options"] = sol.options.describe()
    res.meta["actions"] = list(sol.actions)
    res.meta["definitions"] = (
        "Hc at X=0; Hm minimum film and X_Hm its position; p_spike max P for X >= 0; "
        "Moes films H = H_venner 8M/pi; load_error = h sum P/(pi/2) - 1")
    return res
