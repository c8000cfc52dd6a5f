"""The package :class:`~ehl_multigrid.model.results.Result` of a transient run's
:class:`~ehl_multigrid.solution.Solution` (kinds ``"transient_line"``, ``"transient_point"``):
the fields of the last completed step and the film series over time, what ``to_result()``
gives for every physics. The run's own file, with its snapshots and the state to continue
from, stays :meth:`~ehl_multigrid.transient.result.TransientResult.to_hdf5`."""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..model.results import Result


def transient_result(contact: str, scene: Any, fields: Mapping[str, np.ndarray], details: Any,
                     films: Mapping[str, float]) -> Result:
    """``Result`` of a transient run: ``P``, ``H`` of the last completed step over ``X`` (line)
    or ``(Y, X)`` (point); the Moes films ``Hc``, ``Hm`` and the films in metres ``hc``, ``hm``
    over the times ``T``; the films of the last step (``films``) and the scalars of
    ``details`` (a :class:`~ehl_multigrid.solution.TransientDetails`) as scalars, its feature
    and notes in meta."""
    line = contact == "line"
    half = "b" if line else "a"
    res = Result(f"transient_{'line' if line else 'point'}", scene=scene)
    res.add_coord("X", fields["X"], "-", f"x / {half}")
    dims: tuple[str, ...] = ("X",)
    if not line:
        res.add_coord("Y", fields["Y"], "-", f"y / {half}")
        dims = ("Y", "X")
    res.add_field("P", fields["P"], "-", dims, "p / pmax (last completed step)")
    res.add_field("H", fields["H"], "-", dims, "film (Venner, last completed step)")
    res.add_coord("T", details.times, "-", f"t u_m / {half}")
    for name, data, units, long in (("Hc", details.Hc_series, "-", "central film (Moes)"),
                                    ("Hm", details.Hm_series, "-", "minimum film (Moes)"),
                                    ("hc", details.hc_series, "m", "central film"),
                                    ("hm", details.hm_series, "m", "minimum film")):
        res.add_field(f"{name}_series", data, units, ("T",), long)
    for k, v in films.items():
        res.set_scalar(k, float(v), "m" if k in ("hc", "hm") else "-")
    for k in ("complete", "stop_reason", "steps", "planned_steps", "dt", "scheme", "Hc_steady",
              "Hm_steady", "Hc_min", "Hc_max", "Hm_min", "stalled_steps"):
        res.set_scalar(k, getattr(details, k))
    res.meta["feature"] = json.loads(json.dumps(dict(details.feature), default=str))
    res.meta["notes"] = list(details.notes)
    return res
