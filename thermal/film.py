"""Film friction for the mixed-lubrication layer: a uniform film under Hertz pressure.

This is the contract the ``mixed`` package calls (thesis chapter 5: the film component's shear
stress comes from the thermal Eyring model at the film's load and thickness). Keep the
signature stable.
"""

from __future__ import annotations

import time
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

from ehl_multigrid.model.convergence import ConvergenceReport
from ehl_multigrid.model.errors import ConvergenceError, InputError, require_choice, require_range
from ehl_multigrid.model.scene import Scene

from .options import ThermalOptions
from .parallel import solve_thermal_lines
from .traction import TractionPoint, combine_setup, prepare_traction, solve_traction

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
    return _film_result(tp)


def film_frictions(
    scene: Scene,
    *,
    loads: Sequence[float],
    hs: Sequence[float],
    us: Sequence[float],
    slip: float,
    thermal: bool = True,
    pressure: str = "hertz",
    threads: int | None = None,
    **options: Any,
) -> Iterator[FilmFriction | ConvergenceError]:
    """:func:`film_friction` at many operating points ``(loads[i], hs[i], us[i])``, yielded
    in order; a point whose thermal solve fails yields its :class:`ConvergenceError`
    instead. The line problems of all points run on ``threads`` threads
    (:func:`~thermal.parallel.solve_thermal_lines`); each result is the one
    :func:`film_friction` gives, except ``report.wall_s``: the time since the previous point
    finished. Inputs are checked for every point before any is solved.
    """
    if not len(loads) == len(hs) == len(us):
        raise InputError(f"loads, hs and us must have the same length ({len(loads)}, {len(hs)}, {len(us)})")
    require_choice("pressure", pressure, PRESSURES)
    extra = {k: options.pop(k) for k in ("lubricant", "T_oil", "T_surface1", "T_surface2") if k in options}
    if scene.kind != "line":
        options.setdefault("slice_pressure", pressure)
    opts = ThermalOptions.from_scene(scene, thermal=thermal, **options)
    setups = []
    for load, h, u in zip(loads, hs, us, strict=True):
        require_range("film thickness h", h, 0.0, 1e-2, "m", lo_open=True)
        setups.append(prepare_traction(scene, slip, us=float(u), load=float(load), h=float(h), input="hertz",
                                       options=opts, **extra))
    lines = solve_thermal_lines([job for st in setups for job in st.jobs], threads=threads, keep_errors=True)
    try:
        t_prev = time.perf_counter()
        for st in setups:
            sols = [next(lines) for _ in st.jobs]
            t_now = time.perf_counter()
            failed = [s for s in sols if isinstance(s, ConvergenceError)]
            if failed:
                yield failed[0]
            else:
                yield _film_result(combine_setup(scene, st, sols, t_now - t_prev))
            t_prev = t_now
    finally:
        lines.close()


def _film_result(tp: TractionPoint) -> FilmFriction:
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
