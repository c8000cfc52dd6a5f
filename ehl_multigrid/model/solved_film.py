"""The film the main job's film stage solved, as the later stages read it.

The film stage writes its film to HDF5 as a :class:`~ehl_multigrid.model.results.Result`; the
stages after it (traction, Stribeck) read this typed view instead of the container's string
keys (``RunContext.film()``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from .errors import InputError
from .scene import Scene

#: result kinds of a solved EHL film (the naming contract of the line and point solvers; the
#: thermal layer's coupled TEHL line film)
FILM_KINDS = {"ehl_line": "line", "ehl_point": "point", "tehl_line": "line", "tehl_point": "point"}


def _read_only(a: Any) -> np.ndarray:
    """``a`` as a float array that cannot be written to (a view: no copy of a float array)."""
    out = np.asarray(a, dtype=float).view()
    out.flags.writeable = False
    return out


@dataclass(frozen=True, eq=False)  # arrays: compared by identity
class SolvedFilm:
    """A converged (or only inaccurate) multigrid film, in metres and pascals.

    Attributes
    ----------
    contact : ``"line"`` or ``"point"`` (point and elliptic contacts).
    scene : the scene the film was solved for.
    hc : central film thickness [m].
    Hc_ratio : a starved solve's Hc / Hc of the flooded film of the same discretisation; None
        for a flooded solve.
    x : coordinate along the rolling direction [m].
    y : transverse coordinate [m] (point contacts; None for a line contact).
    p : pressure [Pa], shape ``(x,)`` or ``(x, y)``.
    h : film thickness [m], the shape of ``p``.
    status : the solve's status label (``"converged"`` or ``"inaccurate"``; None when the
        result does not say).
    thermal : the film of the coupled thermal EHL solve (result kind ``tehl_line``), whose
        viscosity follows the temperature across the film; False: an isothermal film.
    grid : the solve's finest grid (:class:`~ehl_multigrid.solution.Grid`: points, box in
        units of the Hertzian half-width, half domain), where the stage that solved the film
        gives it; None otherwise. A later stage solves the same box on coarser grids with it.
    """

    contact: str
    scene: Scene
    hc: float
    Hc_ratio: float | None
    x: np.ndarray
    y: np.ndarray | None
    p: np.ndarray
    h: np.ndarray
    status: str | None
    thermal: bool = False
    grid: Any = None

    @property
    def kind(self) -> str:
        """The result kind of the film (``"ehl_line"``, ``"ehl_point"`` or ``"tehl_line"``)."""
        return f"{'tehl' if self.thermal else 'ehl'}_{self.contact}"

    @classmethod
    def from_result(cls, res: Any, grid: Any = None) -> SolvedFilm:
        """The film of an ``ehl_line``, ``ehl_point``, ``tehl_line`` or ``tehl_point``
        :class:`~ehl_multigrid.model.results.Result`
        that carries its scene and the dimensional fields ``x`` (``y``), ``p``, ``h``; ``grid``
        the solve's finest grid where known.

        Raises
        ------
        InputError
            For another kind of result, or one without its scene, ``hc`` or those fields.
        """
        contact = FILM_KINDS.get(res.kind)
        if contact is None:
            raise InputError(f"result kind {res.kind!r} is not a solved film ({sorted(FILM_KINDS)})")
        if res.scene is None or res.scalars.get("hc") is None:
            raise InputError("a solved film needs its scene and its central film hc [m]")
        names = ("x", "p", "h") + (("y",) if contact == "point" else ())
        missing = [n for n in names if n not in res.coords and n not in res.fields]
        if missing:
            raise InputError(f"the {res.kind} result has no {missing} (dimensional fields)")
        ratio = res.scalars.get("Hc_ratio")
        status = res.scalars.get("status")
        return cls(
            contact=contact, scene=res.scene, hc=float(res.scalars["hc"]),
            Hc_ratio=None if ratio is None else float(ratio),
            x=_read_only(res["x"]), y=_read_only(res["y"]) if contact == "point" else None,
            p=_read_only(res["p"]), h=_read_only(res["h"]),
            status=None if status is None else status.decode() if isinstance(status, bytes) else str(status),
            thermal=res.kind.startswith("tehl_"), grid=grid,
        )
