"""The fidelity levels of the main job (``ehl run --fidelity``): one table for every layer.

Each level holds the planner's target accuracy and the thermal friction grids the layers above
use at that target (the traction stage's per contact, the Stribeck stage's). The layers read
this table (:data:`FIDELITIES`) and keep no grids of their own.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType


@dataclass(frozen=True)
class ThermalGrid:
    """A thermal friction grid: ``nx`` cells along the film, ``nz`` across it and, for a point
    contact, ``slices`` across the rolling direction (None: the thermal options' default)."""

    nx: int
    nz: int
    slices: int | None = None

    def as_options(self) -> dict[str, int]:
        """The grid as thermal options (``nx``, ``nz`` and ``slices`` when set)."""
        out = {"nx": self.nx, "nz": self.nz}
        if self.slices is not None:
            out["slices"] = self.slices
        return out


@dataclass(frozen=True)
class Fidelity:
    """One fidelity level.

    Attributes
    ----------
    name : ``"fast"``, ``"standard"`` or ``"reference"``.
    tolerance : relative accuracy targeted on film thickness and friction (the planner's).
    traction_line, traction_point : the traction stage's thermal grid per contact.
    stribeck : the Stribeck stage's thermal film-friction grid.
    """

    name: str
    tolerance: float
    traction_line: ThermalGrid
    traction_point: ThermalGrid
    stribeck: ThermalGrid

    def traction_grid(self, contact: str) -> ThermalGrid:
        """The traction grid of a ``"line"`` contact, else of a point (or elliptic) one."""
        return self.traction_line if contact == "line" else self.traction_point


#: Every fidelity level by name. Tolerances: what each buys, docs/accuracy.md ("What an accuracy
#: costs"); traction grids: the cheapest within the tolerance over slips 0.02-1, docs/thermal.md;
#: Stribeck grids: the coarsest within it on series C, docs/mixed.md.
FIDELITIES: Mapping[str, Fidelity] = MappingProxyType({
    f.name: f for f in (
        Fidelity("fast", 0.1, ThermalGrid(20, 5), ThermalGrid(20, 5, 5), ThermalGrid(20, 5)),
        Fidelity("standard", 0.02, ThermalGrid(40, 10), ThermalGrid(40, 10, 5), ThermalGrid(40, 10)),
        Fidelity("reference", 0.002, ThermalGrid(160, 40), ThermalGrid(80, 20, 10), ThermalGrid(80, 20)),
    )
})
