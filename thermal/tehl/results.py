"""TEHL solutions as package :class:`~ehl_multigrid.model.results.Result` objects (HDF5 with the
scene beside them): kinds ``"tehl_line"`` and ``"tehl_point"``."""

from __future__ import annotations

from typing import Any

import numpy as np

from ehl_multigrid.model.results import Result

#: units of the summary scalars that carry any
_UNITS = {"hc": "m", "hm": "m", "friction": "N", "friction_decoupled": "N", "T_max": "degC",
          "wall_s": "s"}


def _scalars(res: Result, summary: dict[str, Any]) -> None:
    for k, v in summary.items():
        if isinstance(v, (list, tuple)):
            for i, x in enumerate(v):
                res.set_scalar(f"{k}_{i + 1}", float(x))
        else:
            res.set_scalar(k, v, _UNITS.get(k, "-"))


def tehl_line_result(r: Any) -> Result:
    """``Result`` of kind ``"tehl_line"``: P, H and the factors along X; T and tau over (X, z/h);
    x [m], p [Pa], h [m]; the summary scalars (heat partition as ``heat_partition_1/2``) and the
    outer-iteration history."""
    res = Result("tehl_line", scene=r.scene)
    res.add_coord("X", r.X, "-", "x / b")
    res.add_coord("Z", r.Z, "-", "z / h (0: surface 1)")
    res.add_field("P", r.P, "-", ("X",), "p / pmax")
    res.add_field("H", r.H, "-", ("X",), "h R / b^2 (Venner)")
    res.add_field("T", r.T, "degC", ("X", "Z"), "temperature")
    res.add_field("tau", r.tau, "Pa", ("X", "Z"), "shear stress")
    res.add_field("flow_factor", r.a, "-", ("X",), "Poiseuille factor of the generalised Reynolds equation")
    res.add_field("couette_factor", r.c, "-", ("X",), "Couette density factor")
    res.add_coord("x", r.x, "m", "rolling direction")
    res.add_field("p", r.p, "Pa", ("x",), "pressure")
    res.add_field("h", r.h, "m", ("x",), "film thickness")
    _scalars(res, r.summary())
    _history(res, r.outer)
    return res


def tehl_point_result(r: Any) -> Result:
    """``Result`` of kind ``"tehl_point"`` (half domain Y >= 0): P, H, mid-film and surface
    temperatures and the factors over (Y, X); the summary scalars and the outer history."""
    res = Result("tehl_point", scene=r.scene)
    res.add_coord("X", r.X, "-", "x / a")
    res.add_coord("Y", r.Y, "-", "y / a")
    for name, data, units, long in (
            ("P", r.P, "-", "p / pmax"), ("H", r.H, "-", "film (Venner)"),
            ("T_mid", r.T_mid, "degC", "mid-film temperature"),
            ("T_surface1", r.T_surface1, "degC", "surface 1 temperature"),
            ("T_surface2", r.T_surface2, "degC", "surface 2 temperature"),
            ("flow_factor", r.a, "-", "Poiseuille factor"), ("couette_factor", r.c, "-", "Couette density factor")):
        res.add_field(name, data, units, ("Y", "X"), long)
    _scalars(res, r.summary())
    _history(res, r.outer)
    return res


def _history(res: Result, outer: list[dict[str, float]]) -> None:
    keys = sorted({k for o in outer for k, v in o.items() if isinstance(v, (int, float))})
    for k in keys:
        res.history[f"outer_{k}"] = np.array([float(o.get(k, np.nan)) for o in outer])
