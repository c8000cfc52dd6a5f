"""Film friction for the mixed-lubrication layer: a uniform film under Hertz pressure.

This is the contract the ``mixed`` package calls (thesis chapter 5: the film component's shear
stress comes from the thermal Eyring model at the film's load and thickness). Keep the
signature stable.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ehl_multigrid.model.convergence import ConvergenceReport
from ehl_multigrid.model.errors import require_choice, require_range
from ehl_multigrid.model.scene import Scene

from .traction import solve_traction

PRESSURES = ("hertz", "thesis")


@dataclass
class FilmFriction:
    force: float  # N, friction force of the film (whole line length B for line contacts)
    coefficient: float  # force / load
    mean_shear_stress: float  # Pa, force / area
    area: float  # m^2, Hertz area at `load`
    max_temperature_rise: float  # K (0 when isothermal)
    mean_temperature_rise: float  # K
    converged: bool
    report: ConvergenceReport


def film_friction(
    scene: Scene,
    *,
    load: float,
    h: float,
    us: float,
    slip: float,
    thermal: bool = True,
    pressure: str = "hertz",
    **options: Any,
) -> FilmFriction:
    """Friction of a uniform film h [m] under Hertz pressure at `load` [N] on the scene's geometry,
    at sum velocity us [m/s] and slip S; the scene gives oil, solids and temperatures.

    ``pressure``: ``hertz`` (true Hertz pressure; for point contacts the Hertz slice
    pmax sqrt(1 - X^2 - Y^2)) or ``thesis`` (point contacts: the thesis slice (3.20); line
    contacts: same as ``hertz``). ``options`` are :class:`~thermal.options.ThermalOptions`
    fields (nx, nz, slices, tol_T, ...) overriding the scene's ``[solver.thermal]``, plus
    ``lubricant``, ``T_oil``, ``T_surface1``, ``T_surface2`` as in
    :func:`~thermal.traction.solve_traction`. The force is positive when surface 1 is faster.
    """
    require_range("film thickness h", h, 0.0, 1e-2, "m", lo_open=True)
    require_choice("pressure", pressure, PRESSURES)
    extra = {k: options.pop(k) for k in ("lubricant", "T_oil", "T_surface1", "T_surface2") if k in options}
    if scene.kind != "line":
        options.setdefault("slice_pressure", pressure)
    tp = solve_traction(scene, slip, us=us, load=load, h=h, input="hertz", thermal=thermal, **extra, **options)
    return FilmFriction(
        force=tp.force,
        coefficient=tp.coefficient,
        mean_shear_stress=tp.mean_shear_stress,
        area=tp.area,
        max_temperature_rise=tp.max_temperature_rise,
        mean_temperature_rise=tp.mean_temperature_rise,
        converged=tp.converged,
        report=tp.report,
    )
