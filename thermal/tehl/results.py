"""TEHL solutions: what line and point results hold in common (:class:`TEHLResult`), and
the results as package :class:`~ehl_multigrid.model.results.Result` objects (HDF5 with the
scene beside them): kinds ``"tehl_line"`` and ``"tehl_point"``."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ehl_multigrid.model.convergence import ConvergenceReport
from ehl_multigrid.model.results import Result
from ehl_multigrid.model.scene import Scene
from ehl_multigrid.point.postprocess import add_dimensional_film, full_fields

if TYPE_CHECKING:
    from .options import TEHLOptions


@dataclass(kw_only=True)
class TEHLResult:
    """A converged TEHL solution, line or point (Venner's X, P, H of the contact's grid).

    Hc, Hm : Moes central and minimum films (TEHL); Hc_isothermal, Hm_isothermal : the same of
    the isothermal Newtonian solve on the same grid; friction [N] (positive when surface 1 is
    faster, opposing its motion), friction_coefficient (friction / load), friction_decoupled
    [N] (the same thermal model on the isothermal film, thesis chapter 3); T_max [degC];
    heat : the interior heat budget; heat_partition : (share into solid 1, share into solid 2)
    of the conducted heat; heat_balance_error : its relative imbalance; a, c : final flow and
    Couette factors; outer : one dict per outer iteration (dP, dHc, dHm, dT, factor change,
    cycles, wall_s); options : the :class:`~thermal.tehl.options.TEHLOptions` of the solve.
    """

    scene: Scene
    slip: float
    problem: Any
    X: np.ndarray
    P: np.ndarray
    H: np.ndarray
    Hc: float
    Hm: float
    Hc_isothermal: float
    Hm_isothermal: float
    friction: float
    friction_coefficient: float
    friction_decoupled: float
    T_max: float
    heat: dict[str, float]
    heat_partition: tuple[float, float]
    heat_balance_error: float
    a: np.ndarray
    c: np.ndarray
    outer: list[dict[str, float]]
    report: ConvergenceReport
    options: TEHLOptions | None = None
    wall_s: float = math.nan
    #: (Hc, Hm) of the grid when the reported films are extrapolated over the grids
    #: (:func:`thermal.tehl.accuracy.corrected_result`), else None
    grid_films: tuple[float, float] | None = None

    def summary(self) -> dict[str, Any]:
        """The scalar outputs (the ``--json`` keys of a thermal solve); ``Hc_field`` and
        ``Hm_field`` (the grid's films) when the films are extrapolated."""
        return {
            "Hc": self.Hc, "Hm": self.Hm, "Hc_isothermal": self.Hc_isothermal,
            "Hm_isothermal": self.Hm_isothermal, **self._film_keys(), "friction": self.friction,
            "friction_coefficient": self.friction_coefficient, "friction_decoupled": self.friction_decoupled,
            "T_max": self.T_max, "heat_partition": list(self.heat_partition),
            "heat_balance_error": self.heat_balance_error, "outer_iterations": len(self.outer),
            "converged": bool(self.report.converged), "slip": self.slip, "wall_s": self.wall_s,
            **self._own_keys(),
            **({} if self.grid_films is None else {"Hc_field": self.grid_films[0], "Hm_field": self.grid_films[1]}),
        }

    @property
    def hc(self) -> float:
        """Central film [m]."""
        return self.Hc * self.problem.film_scale

    @property
    def hm(self) -> float:
        """Minimum film [m]."""
        return self.Hm * self.problem.film_scale

    @property
    def film_reduction(self) -> float:
        """Thermal reduction factor ``Hc / Hc_isothermal``."""
        return self.Hc / self.Hc_isothermal

    def _film_keys(self) -> dict[str, Any]:
        """Summary keys that follow the isothermal films."""
        return {"hc": self.hc, "hm": self.hm, "film_reduction": self.film_reduction}

    def _own_keys(self) -> dict[str, Any]:
        """Summary keys of the contact that follow the common ones."""
        return {}

#: units of the summary scalars that carry any
_UNITS = {"hc": "m", "hm": "m", "friction": "N", "friction_decoupled": "N", "T_max": "degC",
          "wall_s": "s"}


def _finish(res: Result, r: TEHLResult) -> Result:
    """``res`` with the summary scalars of ``r`` (heat partition as ``heat_partition_1/2``) and
    its outer-iteration history."""
    for k, v in r.summary().items():
        if isinstance(v, (list, tuple)):
            for i, x in enumerate(v):
                res.set_scalar(f"{k}_{i + 1}", float(x))
        else:
            res.set_scalar(k, v, _UNITS.get(k, "-"))
    keys = sorted({k for o in r.outer for k, v in o.items() if isinstance(v, (int, float))})
    for k in keys:
        res.history[f"outer_{k}"] = np.array([float(o.get(k, np.nan)) for o in r.outer])
    return res


def tehl_line_result(r: Any) -> Result:
    """``Result`` of kind ``"tehl_line"``: P, H and the factors along X; T and tau over (X, z/h);
    x [m], p [Pa], h [m]; the summary scalars and the outer-iteration history."""
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
    return _finish(res, r)


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
    # the dimensional film over the full domain, as the core's ``ehl_point`` result holds it
    # (the main job's later stages compute on it)
    add_dimensional_film(res, r.problem, r.X, *full_fields(r.X, r.Y, r.P, r.H, True))
    return _finish(res, r)
