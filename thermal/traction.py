"""Friction of a scene at one slip (:func:`solve_traction`) and traction curves against slip
(:func:`traction_curve`), line and point contacts (thesis 3.2.1.6, 3.2.2.2, 3.3).

Slip ``S = 2 (u1 - u2)/(u1 + u2)`` (S = 2 is pure sliding), ``|S| <= 2``; the thesis's "100 %" is S = 1.
The friction force is positive when surface 1 is the faster one, so the curve is odd in S.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ehl_multigrid.model.convergence import ConvergenceReport
from ehl_multigrid.model.errors import InputError, require_range
from ehl_multigrid.model.hertz import HertzContact
from ehl_multigrid.model.lubricant import T_MAX_C, Lubricant, lubricant_preset
from ehl_multigrid.model.results import Result
from ehl_multigrid.model.scene import Scene
from ehl_multigrid.model.solved_film import SolvedFilm

from .line import Surroundings, ThermalLineSolution
from .options import ThermalOptions
from .parallel import LineJob, solve_thermal_lines
from .profiles import (
    LineProfile,
    hertz_profile,
    hertz_slices,
    profiles_from_fields,
    profiles_from_result,
)

INPUTS = ("hertz", "ehl")


@dataclass
class TractionPoint:
    """Friction of a contact at one operating point.

    force : friction force [N] (whole line length B, or the whole point contact), positive when
        surface 1 is faster; coefficient : force / load; mean_shear_stress : force / area [Pa];
    area : Hertz area [m^2]; h : central film used [m] (uniform-film input) or NaN;
    max/mean_temperature_rise : [K] (mean over the Hertz contact of the film-mean temperature);
    traction1, traction2 : shear force of the film on surface 1 / 2 along +x [N];
    solutions : one :class:`ThermalLineSolution` per line (one for a line contact, one per slice).
    """

    slip: float
    us: float
    u1: float
    u2: float
    load: float
    h: float
    force: float
    coefficient: float
    mean_shear_stress: float
    area: float
    max_temperature_rise: float
    mean_temperature_rise: float
    traction1: float
    traction2: float
    converged: bool
    report: ConvergenceReport
    solutions: list[ThermalLineSolution]
    input: str
    hertz: HertzContact
    thermal: bool
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def heat(self) -> dict[str, float]:
        """Heat budget summed over all lines [W] (per slice widths)."""
        keys = ("shear", "conduction1", "conduction2", "convection", "enthalpy_flux")
        out = {k: float(sum(s.heat.get(k, 0.0) * s.profile.width for s in self.solutions)) for k in keys}
        out["balance"] = (
            (out["shear"] - out["conduction1"] - out["conduction2"] - out["convection"]) / out["shear"]
            if out["shear"] > 0 else 0.0
        )
        return out


def resolve_lubricant(lubricant: Lubricant | str | None, scene: Scene) -> Lubricant:
    if lubricant is None:
        return scene.lubricant
    if isinstance(lubricant, Lubricant):
        return lubricant
    if isinstance(lubricant, str):
        return lubricant_preset(lubricant)
    raise InputError(f"lubricant = {lubricant!r} must be a Lubricant or a preset name")


def wall_speeds(us: float, slip: float) -> tuple[float, float]:
    """``(u1, u2)`` from the sum velocity and ``S = 2 (u1 - u2)/(u1 + u2)``."""
    require_range("us", us, 0.0, 1e3, "m/s", lo_open=True)
    require_range("slip", slip, -2.0, 2.0, "-")
    u1 = 0.5 * us * (1.0 + 0.5 * slip)
    u2 = 0.5 * us * (1.0 - 0.5 * slip)
    return max(u1, 0.0), max(u2, 0.0)


def build_profiles(
    scene: Scene, hz: HertzContact, h: float, options: ThermalOptions, input: str, ehl: Any
) -> list[LineProfile]:
    """The line profiles of the chosen pressure/film input."""
    if input == "hertz":
        x_out = 1.0 if options.x_out is None else options.x_out
        if scene.kind == "line":
            return [hertz_profile(hz.pmax, hz.b, h, nx=options.nx, x_in=options.x_in, x_out=x_out, width=scene.length)]
        return hertz_slices(
            hz.pmax, hz.a, hz.b, h, n=options.slices, nx=options.nx, x_in=options.x_in, x_out=x_out,
            rule=options.slice_rule, form=options.slice_pressure,
        )
    if input == "ehl":
        if isinstance(ehl, SolvedFilm):
            film = usable_film(ehl, scene)
            return profiles_from_fields(
                film.contact == "line", film.x, film.y, film.p, film.h, film.scene, nx=options.nx,
                x_in=options.x_in, x_out=options.x_out, slices=options.slices, rule=options.slice_rule, b=hz.a, b_y=hz.b, length=scene.length if scene.kind == "line" else None,
                viscosity=ehl_viscosity(film.scene),
            )
        res = ehl_result_from(ehl, scene)
        return profiles_from_result(
            res, nx=options.nx, x_in=options.x_in, x_out=options.x_out, slices=options.slices,
            rule=options.slice_rule, b=hz.a, b_y=hz.b, length=scene.length if scene.kind == "line" else None,
            viscosity=ehl_viscosity(res.scene if res.scene is not None else scene),
        )
    raise InputError(f"input = {input!r} is not one of {list(INPUTS)}")


def ehl_viscosity(scene: Scene) -> Callable[[np.ndarray], np.ndarray]:
    """The isothermal viscosity ``eta(p)`` [Pa s] the EHL solvers use for ``scene``: Roelands
    (2.6) of the scene's oil at its inlet temperature."""
    lub, T = scene.lubricant, scene.T_oil

    def eta(p: np.ndarray) -> np.ndarray:
        return np.asarray(lub.viscosity(p, T), dtype=float)

    return eta


#: relative tolerance of :func:`check_ehl_contact` (the quantities are exact inputs; a scene
#: written to HDF5 and read back keeps them to round-off)
CONTACT_RTOL = 1e-6


def ehl_contact_quantities(scene: Scene) -> dict[str, tuple[Any, str]]:
    """What makes a scene's EHL film: ``name -> (value, units)`` for the contact kind, load,
    radii, line length, reduced modulus, sum velocity, the oil's viscosity at the oil
    temperature (at zero pressure and at the scene's Hertz pressure: the pressure-viscosity
    behaviour) and the supplied oil layer."""
    lub, T = scene.lubricant, scene.T_oil
    out: dict[str, tuple[Any, str]] = {
        "contact.kind": (scene.kind, ""), "load": (float(scene.load), "N"), "Rx": (float(scene.Rx), "m"),
        "Ry": (float(scene.Ry), "m"), "E_reduced": (float(scene.E_reduced), "Pa"), "us": (float(scene.us), "m/s"),
        "viscosity at T_oil, p = 0": (float(lub.viscosity(0.0, T)), "Pa s"),
        "[supply] hoil": (float(scene.supply.hoil), "m"),
    }
    if scene.kind == "line":
        out["length"] = (float(scene.length), "m")
    return out


def check_ehl_contact(film_scene: Scene, scene: Scene, source: str = "the EHL film") -> None:
    """Raise :class:`InputError` when the contact an EHL film was solved for (``film_scene``,
    stored beside it) is not the contact of ``scene``: kind, load, radii, line length, reduced
    modulus, sum velocity, viscosity at the oil temperature (at zero pressure and at the
    Hertz pressure) and oil supply must agree to :data:`CONTACT_RTOL`. The message names the
    first quantity that differs and both values."""
    mine = ehl_contact_quantities(scene)
    theirs = ehl_contact_quantities(film_scene)
    # the pressure-viscosity behaviour, at the pressure of the scene being run
    p = float(scene.hertz.pmax)
    for sc, q in ((scene, mine), (film_scene, theirs)):
        q["viscosity at T_oil, pmax"] = (float(sc.lubricant.viscosity(p, sc.T_oil)), "Pa s")
    for key, (want, units) in mine.items():
        got = theirs.get(key, (None, units))[0]
        if isinstance(want, str) or isinstance(got, str):
            same = want == got
        elif math.isinf(want) or math.isinf(got):
            same = want == got
        else:
            same = math.isclose(want, got, rel_tol=CONTACT_RTOL, abs_tol=0.0)
        if not same:
            u = f" {units}" if units else ""
            raise InputError(f"{source} was solved for another contact: its {key} is {got!r}{u} "
                             f"(scene {film_scene.name!r}), the scene {scene.name!r} has {want!r}{u} "
                             f"(relative tolerance {CONTACT_RTOL:g}); solve the film for this scene "
                             f"('ehl solve {scene.name}') or run the film's own scene")


#: statuses of an EHL film that friction is computed on: its iteration converged
#: (``inaccurate``: only its estimated error misses a requested target)
USABLE_EHL_STATUS = ("converged", "inaccurate")


def require_usable_status(status: str | None, message: Any = None) -> None:
    """Raise :class:`InputError` unless an EHL film's ``status`` is None (not stated) or one of
    :data:`USABLE_EHL_STATUS`; ``message`` (the solve's) says why it failed."""
    if status is not None and status not in USABLE_EHL_STATUS:
        lines = str(message or "").splitlines()
        why = f" ({lines[0][:160]})" if lines else ""
        raise InputError(f"ehl: the EHL film's status is {status!r}{why}, allowed: "
                         f"{', '.join(USABLE_EHL_STATUS)}; friction on a film that did not converge "
                         f"would be wrong: solve the film again (e.g. more points)")


def usable_film(film: SolvedFilm, scene: Scene) -> SolvedFilm:
    """``film`` when friction on ``scene`` may be computed on it: a film of the same contact
    (:func:`check_ehl_contact`) whose solve converged (:data:`USABLE_EHL_STATUS`)."""
    require_usable_status(film.status)
    check_ehl_contact(film.scene, scene)
    return film


def ehl_result_from(ehl: Any, scene: Scene) -> Result:
    """Accept an EHL :class:`Result` or plain arrays: ``(x, p, h)`` for a line contact,
    ``(x, y, p, h)`` for a point contact (x, y [m], p [Pa], h [m]), or a dict with those keys.

    A Result that carries its scene must be a film of the same contact
    (:func:`check_ehl_contact`), and one that carries its solve's status must have converged
    (:data:`USABLE_EHL_STATUS`): the solvers return a failed film rather than raising, and
    friction on it would be wrong. Plain arrays are taken as the scene's."""
    if ehl is None:
        raise InputError("input = 'ehl' needs the EHL solution (ehl=SolvedFilm, Result or arrays x, p, h)")
    if isinstance(ehl, Result):
        status = ehl.scalars.get("status")
        if isinstance(status, bytes):
            status = status.decode()
        require_usable_status(status, ehl.scalars.get("message"))
        if ehl.scene is not None:
            check_ehl_contact(ehl.scene, scene)
        return ehl
    if isinstance(ehl, dict):
        keys = ("x", "p", "h") if scene.kind == "line" else ("x", "y", "p", "h")
        missing = [k for k in keys if k not in ehl]
        if missing:
            raise InputError(f"EHL arrays missing {missing}; give {list(keys)}")
        ehl = tuple(ehl[k] for k in keys)
    ehl = tuple(ehl)
    if scene.kind == "line":
        if len(ehl) != 3:
            raise InputError("EHL arrays for a line contact are (x [m], p [Pa], h [m])")
        x, p, h = (np.asarray(a, dtype=float) for a in ehl)
        r = Result("ehl_line", scene=scene)
        r.add_coord("x", x, "m")
        r.add_field("p", p, "Pa", ("x",))
        r.add_field("h", h, "m", ("x",))
        return r
    if len(ehl) != 4:
        raise InputError("EHL arrays for a point contact are (x [m], y [m], p [Pa] (x, y), h [m] (x, y))")
    x, y, p, h = (np.asarray(a, dtype=float) for a in ehl)
    r = Result("ehl_point", scene=scene)
    r.add_coord("x", x, "m")
    r.add_coord("y", y, "m")
    r.add_field("p", p, "Pa", ("x", "y"))
    r.add_field("h", h, "m", ("x", "y"))
    return r


@dataclass
class TractionSetup:
    """One operating point ready for the line solves: what :func:`combine` needs besides them."""

    slip: float
    us: float
    u1: float
    u2: float
    load: float
    h: float | None
    input: str
    hz: HertzContact
    options: ThermalOptions
    jobs: list[LineJob]


def prepare_traction(
    scene: Scene,
    slip: float | None = None,
    *,
    us: float | None = None,
    load: float | None = None,
    h: float | None = None,
    input: str = "hertz",
    ehl: Any = None,
    options: ThermalOptions | None = None,
    lubricant: Lubricant | str | None = None,
    T_oil: float | None = None,
    T_surface1: float | None = None,
    T_surface2: float | None = None,
    profiles: list[LineProfile] | None = None,
    **overrides: Any,
) -> TractionSetup:
    """Check the inputs of :func:`solve_traction` and set up its line problems.

    ``profiles`` reuses the line profiles of an earlier setup with the same load, film, input
    and options (they do not depend on the slip).
    """
    if options is None:
        options = ThermalOptions.from_scene(scene, **overrides)
    elif overrides:
        options = options.with_changes(**overrides)
    slip = scene.slip if slip is None else slip
    us = scene.us if us is None else us
    load = scene.load if load is None else load
    require_range("load", load, 0.0, 1e9, "N", lo_open=True)
    u1, u2 = wall_speeds(us, slip)
    lub = resolve_lubricant(lubricant, scene)
    env = Surroundings(
        lubricant=lub, body1=scene.body1, body2=scene.body2, u1=u1, u2=u2,
        T_oil=scene.T_oil if T_oil is None else T_oil,
        T_surface1=scene.T_surface1 if T_surface1 is None else T_surface1,
        T_surface2=scene.T_surface2 if T_surface2 is None else T_surface2,
    )
    hz = scene.hertz_at(load)
    if input == "hertz":
        if h is None:
            h = scene.supplied_film_fit(us, load)[1]
        require_range("film thickness h", h, 0.0, 1e-2, "m", lo_open=True)
    elif h is not None:
        raise InputError("h applies to input = 'hertz' only; the EHL input carries its own film")
    if profiles is None:
        profiles = build_profiles(scene, hz, h if h is not None else math.nan, options, input, ehl)
    if options.kernel_length is not None:
        klen = options.kernel_length
    else:
        klen = scene.length if scene.kind == "line" else 2.0 * hz.b
    jobs = [LineJob(prof, env, options, klen) for prof in profiles]
    return TractionSetup(float(slip), float(us), u1, u2, float(load), h, input, hz, options, jobs)


def solve_traction(
    scene: Scene,
    slip: float | None = None,
    *,
    us: float | None = None,
    load: float | None = None,
    h: float | None = None,
    input: str = "hertz",
    ehl: Any = None,
    options: ThermalOptions | None = None,
    lubricant: Lubricant | str | None = None,
    T_oil: float | None = None,
    T_surface1: float | None = None,
    T_surface2: float | None = None,
    threads: int | None = None,
    **overrides: Any,
) -> TractionPoint:
    """Thermal (or isothermal) Eyring friction of ``scene`` at one slip.

    Parameters
    ----------
    scene : the contact; its operating values are defaults for slip, us, load and temperatures.
    slip : S = 2 (u1 - u2)/(u1 + u2), in [-2, 2].
    us : sum velocity [m/s]; load : normal force [N].
    h : uniform film [m] for ``input='hertz'`` (default: Moes / Nijenbanning central film at
        us and load, reduced by Chevalier's (6.1) for a starved scene: ``scene.supplied_film_fit``).
    input : ``hertz`` (Hertz pressure, uniform film) or ``ehl`` (``ehl`` = the main job's
        :class:`~ehl_multigrid.model.solved_film.SolvedFilm`, an ``ehl_line`` / ``ehl_point``
        Result or plain arrays).
    options : :class:`ThermalOptions`; ``overrides`` update it (or the scene's
        ``[solver.thermal]`` when ``options`` is None), e.g. ``nx=120, thermal=False``.
    lubricant : a Lubricant or preset name replacing the scene's oil.
    T_oil, T_surface1, T_surface2 : temperatures [degC] replacing the scene's.
    threads : threads for the slices of a point contact (default: numba's thread count; see
        :func:`~thermal.parallel.solve_thermal_lines`).
    """
    t0 = time.perf_counter()
    st = prepare_traction(scene, slip, us=us, load=load, h=h, input=input, ehl=ehl, options=options,
                          lubricant=lubricant, T_oil=T_oil, T_surface1=T_surface1, T_surface2=T_surface2,
                          **overrides)
    sols = list(solve_thermal_lines(st.jobs, threads=threads))
    return combine_setup(scene, st, sols, time.perf_counter() - t0)


def combine_setup(scene: Scene, st: TractionSetup, sols: list[ThermalLineSolution], wall: float) -> TractionPoint:
    """:func:`combine` for a :class:`TractionSetup`."""
    return combine(scene, sols, st.hz, st.load, st.slip, st.us, st.u1, st.u2, st.h, st.input, st.options, wall)


def combine(
    scene: Scene, sols: list[ThermalLineSolution], hz: HertzContact, load: float, slip: float, us: float,
    u1: float, u2: float, h: float | None, input: str, options: ThermalOptions, wall: float,
) -> TractionPoint:
    """Integrate the line solutions over the contact width."""
    widths = np.array([s.profile.width for s in sols])
    force = float(sum(s.force_per_length * w for s, w in zip(sols, widths, strict=True)))
    t1 = float(sum(s.traction1_per_length * w for s, w in zip(sols, widths, strict=True)))
    t2 = float(sum(s.traction2_per_length * w for s, w in zip(sols, widths, strict=True)))
    area = hz.area
    rises = np.array([s.mean_temperature_rise() for s in sols])
    aw = widths * np.array([s.profile.b * s.profile.contact_half for s in sols])
    mean_rise = float(np.sum(rises * aw) / np.sum(aw)) if options.thermal else 0.0
    max_rise = float(max(s.max_temperature_rise() for s in sols)) if options.thermal else 0.0
    converged = all(s.report.converged for s in sols)
    worst = max(sols, key=lambda s: (not s.report.converged, s.report.iterations))
    msgs = sorted({s.report.message for s in sols if not s.report.converged})
    warnings = []
    tmax = max(float(np.max(s.T)) for s in sols)
    if any(s.report.extra.get("warnings") for s in sols):
        warnings.append(f"temperature reaches {tmax:.4g} degC, above the {T_MAX_C:g} degC limit of the lubricant "
                        "property model: the oil would degrade; treat the result as qualitative")
    report = ConvergenceReport(
        converged=converged,
        message=("converged" if converged else f"{sum(not s.report.converged for s in sols)} of {len(sols)} line(s) unconverged: "
                 + "; ".join(msgs)) + "".join(f"; warning: {w}" for w in warnings[:1]),
        iterations=int(max(s.report.iterations for s in sols)),
        residual_history=worst.report.residual_history.copy(),
        tolerances=dict(worst.report.tolerances),
        wall_s=wall,
        extra={
            "sweeps_per_line": np.array([s.report.iterations for s in sols]),
            "max_inner_per_line": np.array([int(np.max(s.report.extra["inner_iterations"])) for s in sols]),
            "reverse_flow_nodes": int(sum(s.report.extra["reverse_flow_nodes"] for s in sols)),
            "warnings": warnings,
        },
    )
    load_p = float(sum(np.trapezoid(s.profile.p, s.profile.x) * s.profile.width for s in sols))
    return TractionPoint(
        slip=float(slip), us=float(us), u1=u1, u2=u2, load=float(load),
        h=float(h) if h is not None and math.isfinite(h) else math.nan,
        force=force, coefficient=force / load, mean_shear_stress=force / area, area=area,
        max_temperature_rise=max_rise, mean_temperature_rise=mean_rise, traction1=t1, traction2=t2,
        converged=converged, report=report, solutions=sols, input=input, hertz=hz,
        thermal=options.thermal, extra={"load_from_pressure": load_p},
    )


# -- traction curves ------------------------------------------------------------------------
def default_slips(scene: Scene) -> np.ndarray:
    """``scene.ranges['slip']`` if present, else 21 values from 0 to the operating slip's side
    and at least 1 in size: ``[0, 1]`` for an operating slip in [0, 1], ``[0, -1]`` for one in
    [-1, 0), ``[0, S]`` beyond (a ball on a flat at rest, S = 2), so the curve holds the
    operating point."""
    if "slip" in scene.ranges:
        return scene.ranges["slip"].values()
    s = float(scene.slip)
    end = math.copysign(max(1.0, abs(s)), s) if s != 0.0 else 1.0
    return np.linspace(0.0, end, 21)


def traction_curve(
    scene: Scene,
    slips: Sequence[float] | None = None,
    *,
    progress: bool = False,
    on_point: Callable[[list[TractionPoint]], None] | None = None,
    threads: int | None = None,
    **kwargs: Any,
) -> list[TractionPoint]:
    """:func:`solve_traction` at each slip (keyword arguments passed through).

    The line profiles (pressure and film on the thermal grid) do not depend on the slip: they
    are built once. The line problems of all slips (and slices) run on ``threads`` threads
    (:func:`~thermal.parallel.solve_thermal_lines`); each point is the one :func:`solve_traction`
    gives. ``on_point(points_so_far)`` is called after each finished point, in slip order
    (used to save partial results, so an interrupted run keeps its finished points); a point's
    ``report.wall_s`` is the time since the previous point finished.
    """
    slips = default_slips(scene) if slips is None else np.asarray(slips, dtype=float)
    if slips.size == 0:
        raise InputError("slip list is empty")
    for i, s in enumerate(slips):
        require_range(f"slip[{i}]", float(s), -2.0, 2.0, "-")
    t0 = time.perf_counter()
    setups: list[TractionSetup] = []
    for s in slips:
        profiles = [job.profile for job in setups[0].jobs] if setups else None
        setups.append(prepare_traction(scene, float(s), profiles=profiles, **kwargs))
    jobs = [job for st in setups for job in st.jobs]
    points: list[TractionPoint] = []
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=len(setups), desc=f"traction {scene.name}", unit="slip")
    lines = solve_thermal_lines(jobs, threads=threads)
    try:
        t_prev = t0
        for st in setups:
            sols = [next(lines) for _ in st.jobs]
            t_now = time.perf_counter()
            points.append(combine_setup(scene, st, sols, t_now - t_prev))
            t_prev = t_now
            if bar is not None:
                bar.update(1)
            if on_point is not None:
                on_point(points)
    finally:
        lines.close()
        if bar is not None:
            bar.close()
    return points


def traction_result(scene: Scene, points: list[TractionPoint], options: ThermalOptions | None = None) -> Result:
    """Store a traction curve in a core :class:`Result` of kind ``traction``.

    Coordinates: ``slip``, ``X`` (x/b; for Hertz slices of a point contact x over the slice's own
    half-width a sqrt(1 - Y^2)), ``Z`` (z/h), ``Y`` (slice positions y/b_y, point contacts).
    Fields against slip: friction_force [N], friction_coefficient, max/mean_temperature_rise [K],
    converged, sweeps. Field maps: T [degC], tau [Pa], u [m/s] on (slip, X, Z) for line contacts,
    (slip, Y, X, Z) for point contacts; T_surface1, T_surface2 [degC] on (slip, X) or
    (slip, Y, X); p [Pa] and h [m] on (X,) or (Y, X) of the first point.
    """
    if not points:
        raise InputError("no traction points to store")
    res = Result("traction", scene=scene)
    S = np.array([p.slip for p in points])
    res.add_coord("slip", S, "-", "S = 2 (u1 - u2)/(u1 + u2)")
    first = points[0]
    X = first.solutions[0].profile.X
    Z = first.solutions[0].Z
    res.add_coord("X", X, "-", "x / b")
    res.add_coord("Z", Z, "-", "z / h(x)")
    res.add_field("friction_force", np.array([p.force for p in points]), "N", ("slip",), "friction force")
    res.add_field("friction_coefficient", np.array([p.coefficient for p in points]), "-", ("slip",), "force / load")
    res.add_field("mean_shear_stress", np.array([p.mean_shear_stress for p in points]), "Pa", ("slip",), "force / Hertz area")
    res.add_field("max_temperature_rise", np.array([p.max_temperature_rise for p in points]), "K", ("slip",))
    res.add_field("mean_temperature_rise", np.array([p.mean_temperature_rise for p in points]), "K", ("slip",))
    res.add_field("traction_surface1", np.array([p.traction1 for p in points]), "N", ("slip",), "film shear force on surface 1 along +x")
    res.add_field("traction_surface2", np.array([p.traction2 for p in points]), "N", ("slip",), "film shear force on surface 2 along +x")
    res.add_field("converged", np.array([p.converged for p in points], dtype=np.int8), "-", ("slip",))
    res.add_field("sweeps", np.array([p.report.iterations for p in points]), "-", ("slip",))
    res.add_field("wall_s", np.array([p.report.wall_s for p in points]), "s", ("slip",))
    res.add_field("heat_balance", np.array([p.heat["balance"] if p.thermal else 0.0 for p in points]), "-", ("slip",),
                  "(shear - conduction - convection) / shear")
    point_kind = len(first.solutions) > 1 or scene.kind != "line"
    if point_kind:
        res.add_coord("Y", np.array([s.profile.Y for s in first.solutions]), "-", "slice position y / b_y")
        dims3 = ("slip", "Y", "X", "Z")
        dims2 = ("slip", "Y", "X")

        def stack(attr: str) -> np.ndarray:
            return np.array([[getattr(s, attr) for s in p.solutions] for p in points])

        res.add_field("p", np.array([s.profile.p for s in first.solutions]), "Pa", ("Y", "X"), "pressure")
        res.add_field("h", np.array([s.profile.h for s in first.solutions]), "m", ("Y", "X"), "film")
    else:
        dims3 = ("slip", "X", "Z")
        dims2 = ("slip", "X")

        def stack(attr: str) -> np.ndarray:
            return np.array([getattr(p.solutions[0], attr) for p in points])

        res.add_field("p", first.solutions[0].profile.p, "Pa", ("X",), "pressure")
        res.add_field("h", first.solutions[0].profile.h, "m", ("X",), "film")
    res.add_field("T", stack("T"), "degC", dims3, "temperature")
    res.add_field("tau", stack("tau"), "Pa", dims3, "shear stress")
    res.add_field("u", stack("u"), "m/s", dims3, "velocity")
    res.add_field("T_surface1", stack("T_surface1"), "degC", dims2, "surface 1 temperature")
    res.add_field("T_surface2", stack("T_surface2"), "degC", dims2, "surface 2 temperature")
    hz = first.hertz
    res.set_scalar("load", first.load, "N")
    res.set_scalar("us", first.us, "m/s")
    res.set_scalar("pmax", hz.pmax, "Pa")
    res.set_scalar("b", hz.a, "m")
    res.set_scalar("area", hz.area, "m^2")
    res.set_scalar("h_uniform", first.h, "m")
    res.set_scalar("input", first.input)
    res.set_scalar("thermal", bool(first.thermal))
    res.set_scalar("converged", bool(all(p.converged for p in points)))
    res.set_scalar("wall_s", float(sum(p.report.wall_s for p in points)), "s")
    res.history["sweep_change_last_point"] = points[-1].report.residual_history
    if options is not None:
        res.meta["options"] = options.to_dict()
    res.meta["slip_convention"] = "S = 2 (u1 - u2)/(u1 + u2); thesis 100 % = 1.0"
    res.meta["messages"] = [p.report.message for p in points]
    return res


def save_partial(path: Path, scene: Scene, options: ThermalOptions | None) -> Callable[[list[TractionPoint]], None]:
    """An ``on_point`` callback that rewrites ``path`` (atomically) after each finished point."""

    def _save(points: list[TractionPoint]) -> None:
        r = traction_result(scene, points, options)
        r.meta["partial"] = True
        r.save(path)

    return _save
