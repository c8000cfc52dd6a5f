"""Film and pressure observables of a point-contact solution and the :class:`Result` that
carries them (naming contract of the EHL results, kind ``ehl_point``)."""

from __future__ import annotations

import math

import numpy as np

from ..model.results import Result
from ..multigrid.accuracy import correction_factors
from .deformation import mirror_full


def full_fields(X, Y, P, H, half: bool):
    """Full-domain ``(Y, P, H)`` (mirrored when ``half``); arrays stay ``[j, i]``."""
    if not half:
        return Y, P, H
    return np.concatenate([-Y[:0:-1], Y]), mirror_full(P), mirror_full(H)


def _interp_at(x, xs, ys) -> float:
    return float(np.interp(x, xs, ys))


#: least-squares fit of ``a + b x + c y + d x^2 + e y^2 + f x y`` to a 3 x 3 stencil (node
#: offsets -1, 0, 1; rows Y, columns X): the coefficients are this matrix times the 9 values
_xs, _ys = (g.ravel() for g in np.meshgrid([-1.0, 0.0, 1.0], [-1.0, 0.0, 1.0]))
_QUADRATIC_FIT = np.linalg.pinv(np.stack([np.ones(9), _xs, _ys, _xs**2, _ys**2, _xs * _ys], axis=1))


def subgrid_min_film(H: np.ndarray, half: bool) -> float:
    """Minimum film between the nodes of a uniform grid (``H[j, i]``, Y rows): the minimum of
    the quadratic ``a + b x + c y + d x^2 + e y^2 + f x y`` fitted (least squares) to the 3 x 3
    nodes around the smallest nodal film, where that quadratic has a minimum within one cell of
    the node; else the nodal minimum. ``half``: rows from Y = 0 up, mirrored below.

    The nodal minimum jumps from node to node in the narrow side constriction and converges
    irregularly; the sub-grid one converges at second order (successive-difference ratios
    4.0-4.6 on 129-2049 points against 2.8-7.1 for the nodal one: docs/accuracy.md,
    "Extrapolated films"), so the grid sequence of an accuracy-driven solve can be extrapolated.
    """
    j, i = np.unravel_index(int(np.argmin(H)), H.shape)
    h0 = float(H[j, i])
    rows = [abs(j - 1) if half else j - 1, j, j + 1]
    if not (0 < i < H.shape[1] - 1) or min(rows) < 0 or max(rows) >= H.shape[0]:
        return h0
    a0, bx, by, cxx, cyy, cxy = _QUADRATIC_FIT @ H[np.ix_(rows, [i - 1, i, i + 1])].ravel()
    det = 4.0 * cxx * cyy - cxy * cxy
    if not (cxx > 0.0 and det > 0.0):
        return h0
    x = (-2.0 * cyy * bx + cxy * by) / det
    y = (cxy * bx - 2.0 * cxx * by) / det
    if max(abs(x), abs(y)) > 1.0:
        return h0
    return float(a0 + bx * x + by * y + cxx * x * x + cyy * y * y + cxy * x * y)


def film_metrics(X: np.ndarray, Y: np.ndarray, P: np.ndarray, H: np.ndarray) -> dict:
    """Central and minimum film, pressure spike (full-domain arrays ``[j, i]``).

    * ``Hc_center``: H at X = Y = 0 (linear interpolation along X if 0 is not a node);
    * ``Hc_dpdx0`` and ``X_dpdx0``: H on the centre line where dP/dX = 0, the zero of the
      central-difference gradient closest to X = 0 inside the loaded zone;
    * ``Hm``, ``X_Hm``, ``Y_Hm``: minimum of H over the grid (the side lobes);
      ``Hm_centerline``, ``X_Hm_centerline``: minimum on Y = 0 (the outlet constriction);
    * ``p_spike``, ``X_spike``: the downstream-most local maximum of P on Y = 0 with X > 0
      (NaN when the centre-line pressure has a single maximum, e.g. low L);
    * ``P_max``.
    """
    jc = int(np.argmin(np.abs(Y)))
    pc, hc = P[jc], H[jc]
    out: dict = {"Hc_center": _interp_at(0.0, X, hc)}
    g = np.gradient(pc, X)
    loaded = pc > 1e-3 * max(pc.max(), 1e-300)
    cand = []
    for i in range(len(X) - 1):
        if loaded[i] and loaded[i + 1] and g[i] > 0.0 >= g[i + 1]:
            t = g[i] / (g[i] - g[i + 1])
            cand.append(X[i] + t * (X[i + 1] - X[i]))
    if cand:
        xz = min(cand, key=abs)
        out["X_dpdx0"] = float(xz)
        out["Hc_dpdx0"] = _interp_at(xz, X, hc)
    else:
        out["X_dpdx0"] = math.nan
        out["Hc_dpdx0"] = math.nan
    k = int(np.argmin(H))
    j, i = np.unravel_index(k, H.shape)
    out.update(Hm=float(H[j, i]), X_Hm=float(X[i]), Y_Hm=float(Y[j]))
    ic = int(np.argmin(hc))
    out.update(Hm_centerline=float(hc[ic]), X_Hm_centerline=float(X[ic]))
    spike = math.nan
    xs = math.nan
    for i in range(len(X) - 2, 0, -1):
        if X[i] <= 0.0:
            break
        if pc[i] > pc[i - 1] and pc[i] >= pc[i + 1] and pc[i] > 0.0:
            spike, xs = float(pc[i]), float(X[i])
            break
    out.update(p_spike=spike, X_spike=xs, P_max=float(P.max()))
    return out


def solution_metrics(X: np.ndarray, Y: np.ndarray, P: np.ndarray, H: np.ndarray, half: bool) -> dict:
    """:func:`film_metrics` of a solution on its own grid, without mirroring a half domain.

    The half domain's rows are taken from the largest Y down to 0, the order of the mirrored
    domain's lower half, so every argmin (and its tie-break) is the full domain's."""
    if not half:
        return film_metrics(X, Y, P, H)
    return film_metrics(X, -Y[::-1], P[::-1], H[::-1])


def build_result(sol, scene=None, extra_scalars: dict | None = None, fields: bool = True) -> Result:
    """Result of kind ``ehl_point`` from a point-contact
    :class:`~ehl_multigrid.multigrid.result.EHLResult` (FAS or Newton path).

    ``fields=False`` gives the scalars only: no mirrored or transposed copies of the fields,
    which at 2049^2 (full domain) were 134 MB above the solve's own peak."""
    pb = sol.problem
    m = solution_metrics(sol.X, sol.Y, sol.P, sol.H, sol.half)
    fac = pb.moes_factor
    res = Result("ehl_point", scene=scene)
    if fields:
        _add_fields(res, sol)
    res.add_report(sol.report)
    Hc_v = m["Hc_center"]
    Hm_v = m["Hm"]
    corr = getattr(sol, "extra", {}).get("film_correction")
    if corr:
        # an accuracy-driven solve reports its films extrapolated over the grids and the box
        res.set_scalar("Hc_field", Hc_v * fac)
        res.set_scalar("Hm_field", Hm_v * fac)
        res.meta["film_correction"] = corr
        fc, fm = correction_factors(corr)
        Hc_v, Hm_v = Hc_v * fc, Hm_v * fm
    res.set_scalar("Hc_venner", Hc_v)
    res.set_scalar("Hm_venner", Hm_v)
    res.set_scalar("Hc", Hc_v * fac)
    res.set_scalar("Hm", Hm_v * fac)
    res.set_scalar("Hc_dpdx0_venner", m["Hc_dpdx0"])
    res.set_scalar("Hc_dpdx0", m["Hc_dpdx0"] * fac)
    res.set_scalar("X_dpdx0", m["X_dpdx0"])
    for k in ("X_Hm", "Y_Hm", "X_Hm_centerline", "X_spike", "P_max"):
        res.set_scalar(k, m[k])
    res.set_scalar("Hm_centerline", m["Hm_centerline"] * fac)
    res.set_scalar("p_spike", m["p_spike"])
    if pb.physical:
        s = pb.a * pb.a / pb.Rx
        res.set_scalar("hc", Hc_v * s, "m")
        res.set_scalar("hm", Hm_v * s, "m")
        res.set_scalar("p_spike_Pa", m["p_spike"] * pb.pmax, "Pa")
    else:
        res.set_scalar("hc", None, "m")
        res.set_scalar("hm", None, "m")
    load = sol.report.load_error_history[-1] if sol.report.load_error_history.size else math.nan
    res.set_scalar("load_error", float(load))
    res.set_scalar("levels", int(sol.levels))
    res.set_scalar("points", int(len(sol.X)))
    res.set_scalar("cycles", int(sol.report.iterations))
    res.set_scalar("wall_s", float(sol.report.wall_s), "s")
    for key in ("wall_total_s", "estimate_s"):  # the whole accuracy sequence, and its estimates
        if key in sol.extra:
            res.set_scalar(key, float(sol.extra[key]), "s")
    res.set_scalar("converged", bool(sol.report.converged))
    res.set_scalar("H00", float(sol.H00))
    res.set_scalar("M", pb.M)
    res.set_scalar("L", pb.L)
    res.set_scalar("theta", pb.theta)
    res.set_scalar("lambda_venner", pb.lam)
    res.set_scalar("alpha_bar", pb.alpha_bar)
    res.set_scalar("pmax", pb.pmax, "Pa")
    for k, v in (extra_scalars or {}).items():
        res.set_scalar(k, v)
    res.meta["problem"] = pb.to_dict()
    res.meta["options"] = {k: v for k, v in vars(sol.options).items()}
    res.meta["actions"] = list(sol.actions)
    res.meta["solver"] = sol.solver
    res.set_scalar("status", sol.status_name)
    if getattr(sol, "error", None) is not None:
        res.set_scalar("Hc_error", float(sol.error.Hc))
        res.set_scalar("Hm_error", float(sol.error.Hm))
        res.meta["error_budget"] = sol.error.budget
        res.meta["accuracy"] = sol.accuracy
    return res


def _add_fields(res: Result, sol) -> None:
    pb = sol.problem
    Yf, Pf, Hf = full_fields(sol.X, sol.Y, sol.P, sol.H, sol.half)
    res.add_coord("X", sol.X, "-", "x / a")
    res.add_coord("Y", Yf, "-", "y / a")
    res.add_field("P", Pf.T.copy(), "-", ("X", "Y"), "p / pmax")
    res.add_field("H", Hf.T.copy(), "-", ("X", "Y"), "h Rx / a^2 (Venner)")
    add_dimensional_film(res, pb, sol.X, Yf, Pf, Hf)


def add_dimensional_film(res: Result, pb, X: np.ndarray, Y: np.ndarray, P: np.ndarray, H: np.ndarray) -> None:
    """Coordinates ``x``, ``y`` [m] and fields ``p`` [Pa], ``h`` [m] over ``(x, y)`` of the
    full-domain Venner fields ``P``, ``H`` (rows ``[j, i]``) of problem ``pb``; nothing in
    Moes-only mode."""
    if pb.physical:
        a = pb.a
        res.add_coord("x", X * a, "m", "rolling direction")
        res.add_coord("y", Y * a, "m", "transverse direction")
        res.add_field("p", P.T * pb.pmax, "Pa", ("x", "y"), "pressure")
        res.add_field("h", H.T * a * a / pb.Rx, "m", ("x", "y"), "film thickness")


def summary_payload(res: Result) -> dict:
    """JSON keys of ``ehl solve`` (same as the line solver) plus point-contact extras."""
    keys = ["Hc", "Hm", "Hc_venner", "Hm_venner", "hc", "hm", "p_spike", "load_error", "levels",
            "points", "cycles", "wall_s", "converged", "Hc_dpdx0", "X_dpdx0", "X_Hm", "Y_Hm",
            "Hm_centerline", "X_spike", "P_max", "H00", "M", "L", "theta", "final_residual",
            "work_units", "message", "status", "Hc_error", "Hm_error", "wall_total_s", "estimate_s"]
    out = {k: res.scalars.get(k) for k in keys if k != "estimate_s" or k in res.scalars}
    out.update({k: res.scalars[k] for k in ("Hc_field", "Hm_field") if k in res.scalars})
    out["actions"] = res.meta.get("actions", [])
    if "error_budget" in res.meta:
        out["error_budget"] = res.meta["error_budget"]
        out["accuracy"] = res.meta.get("accuracy")
    return out
