"""Time-dependent isothermal EHL point (circular or elliptic) contact: surface features
passing through the contact.

Venner's dimensionless transient Reynolds equation of a point contact (Venner & Lubrecht
2000, ch. 13; ``X = x/a``, ``Y = y/a``, ``H = h Rx/a^2``, ``T = t u_m/a``)

``d/dX(eps dP/dX) + d/dY(eps dP/dY) - d(rho H)/dX - d(rho H)/dT = 0``

(wedge and squeeze terms carry the same factor, so neither has a coefficient), with the film
of :mod:`.features` and the load ``int int P dX dY = 2 pi b/(3a)`` at every step
(constant load, H00(T) free). The design is the line contact's (the time loop of :mod:`.stepping`): BDF2 steps
(the first backward Euler), one FAS solve per step by the shared driver on
:class:`~.hierarchy.TransientPointHierarchy` started from the previous solution
extrapolated in time, the deformation (FFT) recomputed after every relaxation sweep. The
start is the core steady solution, then the steady equations with the feature frozen at its
``T = 0`` position.

Cavitation: the projection ``P >= 0`` of the steady core (default), or mass-conserving
Elrod-Adams cavitation (``cavitation="mass-conserving"``: the starved point solver's film
content ``theta`` and discretisation with the squeeze term ``d(theta rho H)/dT``,
:mod:`.cavitated`), which also takes a finite supplied layer ``hoil``.

Limits: no mixed lubrication (a film that closes raises :class:`ConvergenceError`). The full
domain is solved (features need not be symmetric in Y).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np

from ..model.errors import InputError, require_choice
from ..multigrid.options import PointOptions
from ..multigrid.result import EHLResult
from ..multigrid.threads import preserved_threads
from ..point.fas import HINT, POINT_POLICY, point_settings
from ..point.problem import PointProblem
from ..point.solve import solve_fas
from ..starved.point import STARVED_MAX_CYCLES_2, STARVED_TOL, solve_starved_point
from .cavitated import CavitatedPointStepHierarchy
from .checkpoint import Checkpoint
from .features import PointFeature, Smooth, default_end_time, feature_speed
from .hierarchy import TransientPointHierarchy
from .oil_balance import MASS_TOL
from .result import PointTransientResult
from .stepping import (
    Stepper,
    max_time_step,
    model_inputs,
    require_steady_start,
    start_and_march,
    time_steps,
)

#: Default numerics of a point time step: FFT deformation, a residual below the time error of
#: the default step (measured: 4-6 cycles per step at Courant 1).
POINT_TRANSIENT_DEFAULTS = {"points": 129, "deformation": "fft", "tol": 1e-5, "tol_load": 1e-6,
                            "max_cycles": 40, "raise_on_failure": False, "half": False}

#: A mass-conserving step's stall (at any residual) turns on X/Y alternating lines, then halves
#: the under-relaxations, then ends the cycles for the fine-grid finish
#: (:meth:`~.cavitated.CavitatedPointStepHierarchy.last_resort`; docs/transient.md)
CAVITATED_POINT_POLICY = replace(POINT_POLICY, stall_ladder=(("alternate",), ("halve", "W"), ("fail",)),
                                 cyclic_stall=False, shared_ladder=False, quiet_below=0.0)


def point_transient_options(options: PointOptions | None = None, **kw: Any) -> PointOptions:
    """Point options of the time steps: :data:`POINT_TRANSIENT_DEFAULTS` below ``options``
    and keywords (always the full domain; ``raise_on_failure`` always False, as
    :func:`~.solve.transient_options`)."""
    base = PointOptions.build(None, **POINT_TRANSIENT_DEFAULTS) if options is None else options
    if kw.get("half") or (options is not None and options.half and "half" not in kw):
        raise InputError("half = True: the transient point solver needs the full domain "
                         "(features are not symmetric in Y)")
    return PointOptions.build(base, **{**kw, "raise_on_failure": False, "half": False})


#: largest ``dT`` accepted: the line contact's rule, along X (:func:`~.stepping.max_time_step`)
max_point_time_step = max_time_step


def solve_transient_point(
    problem: PointProblem, feature: PointFeature | None, *, body: int = 1, slide_roll: float = 0.0,
    dt: float | None = None, steps: int | None = None, t_end: float | None = None,
    options: PointOptions | None = None, scheme: str = "bdf2", snapshot_every: int = 10,
    initial: tuple[np.ndarray, float] | None = None, accept_stall: float = 1e-3,
    on_film_collapse: str = "raise",
    callback: Callable[[dict[str, Any]], None] | None = None, checkpoint: Checkpoint | None = None,
    resume: dict[str, Any] | None = None, cavitation: str = "projection",
    hoil: float | Callable[[float], float] = math.inf, time_tol: float | None = None,
    mass_tol: float | None = MASS_TOL, hoil_y: Callable[[float], float] | None = None, **kw: Any,
) -> PointTransientResult:
    """Run a surface feature through an EHL point contact at constant load.

    Parameters
    ----------
    problem : the steady :class:`PointProblem` (M, L, theta, lubricant).
    feature : :class:`~.features.Waviness2D`, :class:`~.features.Dent2D`,
        :class:`~.features.HeightMap` (film units ``a_phys Rx/a^2``, lengths in a);
        None for smooth surfaces.
    dt : time step ``dT`` (``T = t u_m/a``); default: one mesh size per step at the faster of
        the feature and the mean flow (Courant 1). Allowed: ``(0, max_point_time_step]``.
    steps, t_end : number of steps, or the end time (default: until a dent's centre or a
        map's upstream edge has reached ``xmax``; waviness: one transit plus three periods).
    options : :class:`PointOptions` of every step (defaults :data:`POINT_TRANSIENT_DEFAULTS`);
        keywords override fields.
    body, slide_roll, scheme, snapshot_every, initial, callback, checkpoint, resume, time_tol,
    mass_tol : as :func:`~.solve.solve_transient_line` (``initial`` is ``(P[j, i], H00)``).
    accept_stall : a step whose cycles end above the tolerances (stalled, cycle limit, or
        rejected cycles: seen as a limit cycle of the cavitation boundary when a dent or rough
        patch leaves the contact) is accepted when the relative residual and load error of
        the iterate it leaves are below this; it is flagged in the ``stalled`` series and
        counted in the summary. 0 accepts no such step.
    on_film_collapse : ``"raise"`` (:class:`ConvergenceError`) or ``"stop"``: end the run at
        the step whose film closes (a feature or rough patch cutting through it: mixed
        lubrication, not modelled) and return the steps before it, with ``failed_step`` and
        ``stop_reason`` set (rough-surface studies: the time of first contact).
    cavitation : ``"projection"`` (``P >= 0``: oil is created and lost where the film
        ruptures and reforms) or ``"mass-conserving"`` (Elrod-Adams film content ``theta``,
        the starved point solver's discretisation with the squeeze term
        ``d(theta rho H)/dT``: :mod:`.cavitated`). The result's ``mass_error`` series
        (mass-conserving only) is the oil the whole grid gained in a step over the inflow;
        snapshots carry ``theta``.
    hoil : the oil layer supplied ahead of the contact (Venner units ``hoil Rx/a^2``, both
        surfaces, ambient density: :func:`~ehl_multigrid.starved.supply.hoil_venner` with
        ``a``, ``Rx`` converts metres); ``inf``: a flooded inlet; or a function of ``T``. A
        finite layer needs mass-conserving cavitation: the start is then the starved steady
        solution of ``hoil(0)`` on the run's grid
        (:func:`~ehl_multigrid.starved.point.solve_starved_point`), and every step feeds the
        inlet the layer of its time.

    hoil_y : instead of ``hoil``, a layer that varies across the track and not in time: a
        function of ``Y`` (``y/a``) giving the layer in Venner units (a scene's ``[supply]
        hoil_profile``); mass-conserving cavitation only. The start is the starved steady
        solution of that profile, and the result's ``hoil`` its mean over the rows.

    Returns
    -------
    PointTransientResult

    Raises
    ------
    InputError : bad feature (too large for the domain), time step, step count or options.
    ConvergenceError : the steady start or a step's multilevel solve failed, or the film closed
        (``on_film_collapse="raise"``), naming the step; ``partial`` holds the steps before it.
        Raised whatever ``raise_on_failure``, as by :func:`~.solve.solve_transient_line`.
    """
    require_choice("on_film_collapse", on_film_collapse, ("raise", "stop"))
    if hoil_y is not None and (callable(hoil) or math.isfinite(hoil)):
        raise InputError("hoil and hoil_y both given: a layer across the track (hoil_y) or one "
                         "uniform layer (hoil), not both")
    if hoil_y is not None and cavitation != "mass-conserving":
        raise InputError(f"hoil_y (a layer across the track) needs cavitation = 'mass-conserving'; "
                         f"got {cavitation!r}")
    supply, hoil, mass_tol = model_inputs(scheme, cavitation, hoil, time_tol, mass_tol)
    layer: Any = hoil if hoil_y is None else hoil_y  # what the grids and the start are fed
    feature = Smooth() if feature is None else feature
    speed = feature_speed(body, slide_roll)
    opts = point_transient_options(options, **kw)
    if not opts.elastic:
        raise InputError("elastic = False: the transient point solver needs elastic surfaces")
    mass_conserving = cavitation == "mass-conserving"
    with preserved_threads():
        if mass_conserving:
            hz = CavitatedPointStepHierarchy(problem, opts, feature.height, layer)
            hz.mass_tol = mass_tol
        else:
            hz = TransientPointHierarchy(problem, opts, feature.height)
    fine = hz.fine
    feature.check_domain(hz.xmin, hz.xmax, hz.ymax)
    dt, steps, snapshot_every = time_steps(
        feature, speed, fine.hx, dt, steps, t_end, snapshot_every, accept_stall, "a",
        lambda: default_end_time(hz.xmin, hz.xmax, feature, speed))

    t0 = time.perf_counter()
    stepper = _PointStepper(hz, problem, opts)
    if mass_conserving:
        stepper.policy = CAVITATED_POINT_POLICY
    stepper.supply = supply
    with preserved_threads():
        theta0 = None
        if hoil_y is None and not math.isfinite(hoil):
            # the time steps hold P = 0 on the boundary (far_field_ok): so does their start
            steady = solve_fas(problem, replace(opts, far_field=False))
            require_steady_start("point", steady, initial, HINT)
        else:
            # the starved steady solution of the run's grid (its discretisation and supply;
            # it solves its own flooded start, so the core's flooded solve is not made)
            steady = solve_starved_point(problem, layer, replace(
                opts, tol=min(opts.tol, STARVED_TOL), tol_load=min(opts.tol_load, STARVED_TOL),
                max_cycles=max(opts.max_cycles, STARVED_MAX_CYCLES_2)))
            if not _within_step_tolerance(steady, opts):
                require_steady_start("point (starved)", steady, initial, HINT)
            theta0 = steady.extra["theta"]
        out = PointTransientResult(problem=problem, feature=feature, body=body, slide_roll=slide_roll,
                                   speed=speed, dt=float(dt), scheme=scheme, options=opts, steady=steady,
                                   X=fine.X.copy(), Y=fine.Y.copy(), yf=float(getattr(feature, "y_ref", getattr(feature, "y0", 0.0))),
                                   cavitation=cavitation, hoil=hz.hoil if mass_conserving else hoil,
                                   mass_tol=getattr(hz, "mass_tol", None))
        out.Hc_steady = float(steady.H[int(np.argmin(np.abs(fine.Y))), int(np.argmin(np.abs(fine.X)))])
        out.Hm_steady = float(np.min(steady.H[out.within(1.5) | (steady.P > 0)]))
        hz.h00_step_max = 0.1 * max(out.Hc_steady, 1e-6)
        # the mass-conserving model starts from its own steady discretisation (the core's
        # solution is the projection's, with another outlet and wedge)
        start_and_march(stepper, out, steady, theta0, initial, feature.kind != "smooth" or mass_conserving,
                        resume, t0, speed=speed, dt=dt, steps=steps, scheme=scheme,
                        snapshot_every=snapshot_every, accept_stall=accept_stall,
                        on_film_collapse=on_film_collapse, callback=callback, checkpoint=checkpoint,
                        time_tol=time_tol)
    return out


class _PointStepper(Stepper):
    """The point contact's side of the time loop (either cavitation model, whose ``policy``
    the run sets); ``supply`` (optional): the supplied layer as a function of time."""

    name = "point"
    hint = HINT
    policy = POINT_POLICY
    settings = staticmethod(point_settings)

    @property
    def grid_text(self) -> str:
        return f"{self.hz.fine.P.shape}"

    @property
    def H0(self) -> float:
        return self.hz.H00

    def set_unknowns(self, P: np.ndarray, H0: float) -> None:
        self.hz.fine.P, self.hz.H00 = np.ascontiguousarray(P), H0

    def film(self) -> tuple[np.ndarray, np.ndarray]:
        fine = self.hz.fine
        if getattr(fine, "theta", None) is None:
            return fine.H, fine.rho * fine.H
        return fine.H, fine.theta * fine.rho * fine.H  # mass-conserving: the oil carried

    def accept_stalled(self, res: EHLResult, accept_stall: float) -> bool:
        # cycles that stall, hit the cycle limit or are rejected leave the best accepted
        # iterate: accept it when its own residual and load error are below accept_stall
        if res.status not in (1, 2, 3):
            return False
        m = self.hz.measure(len(self.hz.levels) - 1)
        return bool(m.ok and m.residual < accept_stall and m.load_error < accept_stall)


def _within_step_tolerance(res: EHLResult, opts: PointOptions) -> bool:
    """Whether a steady start that missed its own (starved) tolerance still meets the steps'
    tolerances: its last residual and load error below ``opts.tol``, ``opts.tol_load`` (the
    starved solve stops at a residual floor of a few 1e-8 for mildly starved supplies, e.g.
    (20, 10), 65^2, Hoil = 0.6 at 3.5e-8; the steps start with the steady equations anyway)."""
    if res.success:
        return True
    r, le = res.residual_history, res.load_error_history
    return bool(r.size and np.all(np.isfinite(res.P)) and r[-1] < opts.tol
                and abs(le[-1]) < opts.tol_load)
