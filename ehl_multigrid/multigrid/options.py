"""Numerical options of the multilevel EHL solvers: one immutable type per contact, one name
per concept.

:class:`MultigridOptions` holds what every FAS/FMG solve has (grid, cycle, relaxation, film
constant, tolerances, threads); :class:`LineOptions` and :class:`PointOptions` add what only
one discretisation has and carry that contact's measured defaults. Options never change during
a solve: the adaptive choices of a solve (under-relaxation, cycle type, switch) live in its
:class:`~ehl_multigrid.multigrid.policy.Settings`.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields, replace
from numbers import Integral
from typing import Any, ClassVar

from ..model.errors import InputError, require_choice, require_range

#: Poiseuille face coefficients (``multigrid.flux.FACE_MODES``; not imported here: numba)
FACES = ("arithmetic", "logarithmic", "auto")

CYCLES = ("V", "W", "F")
DEFORMATIONS = ("mlmi", "fft", "direct")
#: the robustness retries of a failed point solve (:class:`PointOptions`, docs/robustness.md)
RETRIES = ("retry_square_cells", "retry_full_refresh", "retry_finer_start", "retry_coarser_start",
           "retry_uncapped_start", "retry_from_neighbour")


@dataclass(frozen=True)
class MultigridOptions:
    """Options shared by every multilevel EHL solve (defaults per contact in the subclasses).

    Attributes
    ----------
    points : finest-grid points along X (``2^k n0 + 1``).
    levels : number of grids (None: the contact's rule for the coarsest grid).
    cycle : ``"V"``, ``"W"`` or ``"F"`` FAS cycles.
    cycles : cycles per FMG level.
    max_cycles : extra finest-grid cycles allowed to reach the tolerances.
    nu1, nu2 : pre- and post-relaxations per level visit.
    deformation : ``"mlmi"``, ``"fft"`` or ``"direct"`` evaluation of the elastic integral.
    switch : Gauss-Seidel / Jacobi-distributive switch on ``eps/h^2`` (None: the contact's
        rule from ``alpha_bar``); Jacobi-distributive where ``eps/h^2 < switch``.
    omega, omega_jd : under-relaxation of Gauss-Seidel and Jacobi-distributive changes.
    h00_gain : film-constant step per unit load error (None: 0.1 for V and 0.05 for W/F
        cycles, divided by 4 when L > 10 or M > 1000 -- the classic settings).
    tol : relative residual tolerance; tol_load : relative load-error tolerance.
    wedge_order : upwind order of the wedge term ``d(rho H)/dX`` (1 or 2).
    threads : numba threads and FFT workers for this solve (None: the current numba setting,
        which is restored afterwards).
    adapt : False disables the adaptive robustness policy (fixed classic settings).
    raise_on_failure : False (the default of every solver): a numerical failure is returned --
        ``success`` False, a status other than ``converged``, the message and what was
        computed; True: raised as :class:`ConvergenceError` instead (for callers whose
        control flow is the exception, e.g. a search that catches it).
    film_tol : stop instead when the last finest-grid cycle changed Hc and Hm by less than this
        (relative) and the relative load error is below it: the films' algebraic error, which
        is what the error estimate counts, rather than a residual (None: residual rule).
    grid_stop : also stop (before the residual tolerance is met) when both films' iteration
        error (:func:`~ehl_multigrid.multigrid.accuracy.iteration_error` plus the load error's
        share) is below this fraction of the larger of their grid errors (Richardson from the
        FMG's coarser grids) and below ``GRID_STOP_CAP`` (1e-4), the load error is below
        ``tol_load`` and the residual within ``GRID_STOP_RESIDUAL`` times ``tol``: further
        cycles would move the films by less than this fraction of what the grid already costs
        (Brandt's rule: iterate to the discretisation error, not to a fixed residual). Needs
        three finest-grid cycles and a coarser FMG grid; only the steady solvers use it
        (None: residual rule only).
    confirm_early_stop : a stop of a V- or F-cycle solve before the residual meets ``tol``
        (``film_tol``, ``grid_stop``) is confirmed by one W cycle over which the stop's test
        must hold again (False: the first stop stands). See docs/robustness.md.
    """

    points: int = 129
    levels: int | None = None
    cycle: str = "V"
    cycles: int = 2
    max_cycles: int = 60
    nu1: int = 2
    nu2: int = 1
    deformation: str = "fft"
    switch: float | None = None
    omega: float = 0.5
    omega_jd: float = 0.3
    h00_gain: float | None = None
    tol: float = 1e-5
    tol_load: float = 1e-6
    wedge_order: int = 2
    threads: int | None = None
    adapt: bool = True
    raise_on_failure: bool = False
    film_tol: float | None = None
    grid_stop: float | None = 0.25
    confirm_early_stop: bool = True

    #: the contact chooses the cycle type when ``cycle`` is None
    CYCLE_OPTIONAL: ClassVar[bool] = False

    def __post_init__(self) -> None:
        require_range("points", self.points, 9, 2**20 + 1, "grid points")
        if int(self.points) != self.points or (int(self.points) - 1) % 2:
            raise InputError(f"points = {self.points} must be 2^k n0 + 1 (e.g. 129, 257, 513, 1025)")
        if self.levels is not None:
            require_range("levels", self.levels, 1, 20, "-")
            if int(self.levels) != self.levels:
                raise InputError(f"levels = {self.levels} must be an integer")
        if self.cycle is not None or not self.CYCLE_OPTIONAL:
            require_choice("cycle", self.cycle, CYCLES)
        require_range("cycles", self.cycles, 1, 50, "cycles per FMG level")
        require_range("max_cycles", self.max_cycles, 0, 10000, "cycles")
        require_range("nu1", self.nu1, 0, 50)
        require_range("nu2", self.nu2, 0, 50)
        if self.nu1 + self.nu2 < 1:
            raise InputError("nu1 + nu2 must be >= 1 (at least one relaxation per level)")
        require_choice("deformation", self.deformation, DEFORMATIONS)
        if self.switch is not None:
            require_range("switch", self.switch, 0.0, 1e6)
        require_range("omega", self.omega, 0.0, 1.5, lo_open=True)
        require_range("omega_jd", self.omega_jd, 0.0, 1.0, lo_open=True)
        if self.h00_gain is not None:
            require_range("h00_gain", self.h00_gain, 0.0, 1.0)
        require_range("tol", self.tol, 1e-14, 1e-1)
        require_range("tol_load", self.tol_load, 1e-14, 1e-1)
        require_choice("wedge_order", self.wedge_order, (1, 2))
        if self.threads is not None:
            require_range("threads", self.threads, 1, 1024, "threads")
        if self.film_tol is not None:
            require_range("film_tol", self.film_tol, 1e-12, 0.1, "- (relative film change)")
        if self.grid_stop is not None:
            require_range("grid_stop", self.grid_stop, 0.0, 1.0, "- (fraction of the grid error)",
                          lo_open=True)
        require_choice("confirm_early_stop", self.confirm_early_stop, (True, False))
        for f in fields(self):
            # a switch given as a word ("no") would count as true
            if f.type in ("bool", "bool | None"):
                require_choice(f.name, getattr(self, f.name), (True, False) if f.type == "bool" else (True, False, None))

    @classmethod
    def build(cls, options: MultigridOptions | None = None, **kw: Any):
        """Options of this type from ``options`` with keyword overrides; unknown names raise
        :class:`InputError`."""
        names = {f.name for f in fields(cls)}
        out: dict[str, Any] = {}
        for key, value in kw.items():
            if key not in names:
                raise InputError(f"unknown solver option {key!r}; known: {sorted(names)}")
            out[key] = value
        if options is None:
            return cls(**out)
        if not isinstance(options, cls):
            base = {k: v for k, v in asdict(options).items() if k in names}
            return cls(**{**base, **out})
        return replace(options, **out) if out else options

    def default_h00_gain(self, M: float, L: float) -> float:
        """The classic film-constant step: 0.1 (V) or 0.05 (W, F), /4 when L > 10 or M > 1000."""
        c = 0.1 if self.cycle == "V" else 0.05
        return c / 4.0 if (L > 10 or M > 1000) else c

    def describe(self) -> dict[str, Any]:
        return {k: v for k, v in asdict(self).items() if not (isinstance(v, float) and math.isnan(v))}


@dataclass(frozen=True)
class LineOptions(MultigridOptions):
    """Line-contact options (defaults measured on the line solver's test set).

    Adds: ``switch_h`` -- h-scaled switch on fine grids, Jacobi-distributive where
    ``eps/h^2 < switch_h/h`` (None: from ``alpha_bar``); ``switch_eps`` -- film-scale switch
    on every grid, Jacobi-distributive also where ``eps < switch_eps`` (None: twice the
    contact's central ``eps`` from the Moes fit, ``line.solver.default_switch_eps``; 0: off; the
    steady solver only); ``band`` -- half band width of the
    collective line systems; ``mlmi_order``, ``mlmi_radius`` -- MLMI interpolation order and
    correction radius; ``correction_mask`` -- no coarse-grid correction where ``eps/h^2``
    exceeds it; ``fmg_start_points`` -- grid on which FMG starts (None: from M);
    ``fmg_match_film`` -- carry the central film (not H0) to each finer FMG grid;
    ``local_newton`` -- grids of at least this many points finish each post-relaxation (and,
    where ``alpha_bar > line.solver.LOCAL_NEWTON_PRE_ALPHA``, each pre-relaxation) with a
    windowed Newton solve where the residual concentrates on a few points (None: never; the
    steady solver only, see ``line.solver.LineHierarchy.relax``); ``retry_finer_start`` -- a
    solve whose FMG diverges below its finest grid is solved again with the coarsest grid
    twice as fine (one level fewer), while at least two levels remain (``adapt`` and the
    automatic levels only; the steady solver, ``line.solver.solve_line_problem``); ``face`` --
    the Poiseuille face coefficient, ``"arithmetic"`` or ``"logarithmic"`` mean of the
    neighbours' ``eps`` (``multigrid.flux``; every line solver: steady, starved, thermal EHL and
    transient), or ``"auto"``: logarithmic where ``alpha_bar >= line.solver.FACE_LOG_ALPHA``,
    arithmetic below. Error estimates with the logarithmic one are validated for the steady
    solver from that ``alpha_bar`` on (``solve_line`` refuses it below); the default stays
    arithmetic (docs/accuracy.md, "Face coefficient of the Poiseuille flux").
    """

    points: int = 1025
    cycle: str = "V"
    max_cycles: int = 60
    deformation: str = "fft"
    switch: float | None = 0.3
    omega: float = 0.5
    omega_jd: float = 0.3
    tol: float = 1e-5
    tol_load: float = 1e-6
    raise_on_failure: bool = False
    switch_h: float | None = None
    switch_eps: float | None = None
    band: int = 4
    mlmi_order: int = 12
    mlmi_radius: int = 48
    correction_mask: float | None = None
    fmg_start_points: int | None = None
    fmg_match_film: bool = True
    local_newton: int | None = 1025
    retry_finer_start: bool = True
    face: str = "arithmetic"

    def __post_init__(self) -> None:
        super().__post_init__()
        require_choice("face", self.face, FACES)
        n = int(self.points) - 1
        if self.points < 33 or n & (n - 1):
            raise InputError(f"points = {self.points} must be 2^k + 1 >= 33 (e.g. 257, 1025, 4097)")
        if self.switch_h is not None:
            require_range("switch_h", self.switch_h, 0.0, 1e3)
        if self.switch_eps is not None:
            require_range("switch_eps", self.switch_eps, 0.0, 1e6)
        require_range("band", self.band, 1, 8)
        require_range("mlmi_order", self.mlmi_order, 2, 32)
        require_range("mlmi_radius", self.mlmi_radius, 1, 4096)
        if self.local_newton is not None:
            require_range("local_newton", self.local_newton, 33, 1 << 20)


@dataclass(frozen=True)
class PointOptions(MultigridOptions):
    """Point- and elliptic-contact options.

    Adds: ``n_coarse`` -- intervals of the coarsest grid along X (None: from M and the
    domain); ``xmin, xmax, ymax`` -- domain in units of a (None: the default box, widened at
    low M); ``y_ratio`` -- (points along Y - 1)/(points - 1), a power of 2 (None: cells
    stretched with the ellipse, hy/hx ~ b/a, square cells as the retry of a diverged solve); ``half`` -- solve Y >= 0 only (symmetric contact); ``coarse_sweeps`` -- relaxations
    per coarsest-grid visit; ``elastic`` -- False for rigid surfaces; ``far_field`` -- the
    boundary holds the far-field pressure of the gap (undeformed, with the elastic far
    deformation) and the load balance counts the load beyond the box (``point.farfield``,
    ``point.farfield_angular``; the steady flooded solver only; None: on);
    ``alternating`` -- relax
    Y lines after every X-line sweep (None: on every grid when b/a < 0.5, contacts long in the
    rolling direction; wider contacts on their grids of at least 129 points in solves of at
    least 513 points, where the resolved pressure spike's oblique ridge otherwise leaves an
    error floor; True: every grid; False: never); ``cycle`` -- None: F cycles for the steady
    solve of contacts that start with X lines, W cycles where every grid alternates from the
    start and for the starved, transient and thermal solvers (see ``point.fas.point_cycle``).
    The GS/JD ``switch`` is raised x4 on meshes as fine as 2049 points on the classic box
    (``point.fas.sweep_switch``). ``y_pre`` -- False: the fine grids of wider contacts relax
    Y lines in the post-relaxation only (14 % fewer work units, no faster in wall time, and
    less robust over the extremes map: validation/bench/point_variants.py).
    ``local_film_update`` -- False: the film between the X and Y halves of an alternating sweep
    is refreshed by a whole deformation evaluation instead of locally (the steady solve's
    retry when the local refresh fails, ``retry_full_refresh``).

    Robustness retries of a failed solve (each True by default; False leaves the failure as
    it is; what each costs: docs/robustness.md). The retries of one solve act only with
    ``adapt``, the coarse-grid ones only on the automatic coarse grid (``n_coarse`` and
    ``levels`` None):
    ``retry_square_cells`` -- a contact with b/a < 1 that diverges on the default cells
    (``y_ratio`` None) is solved again on square cells, before the other retries;
    ``retry_full_refresh`` -- a contact with b/a >= 0.5 that still fails after the retry with
    X and Y lines alternating on every grid is solved again with ``local_film_update`` off;
    ``retry_finer_start`` -- a diverged contact with b/a < 0.5 is solved again from four times
    as many coarse intervals; ``retry_coarser_start`` -- a solve still diverged is solved again
    from half as many; ``retry_uncapped_start`` -- a wide contact (b/a >= 4) whose coarse
    grid was capped at 64 intervals and that ends at its residual floor or out of cycles is
    solved again from the rule's uncapped coarse grid; ``retry_from_neighbour`` -- in an accuracy-driven sequence
    (``point.solve.solve_point``), a refinement whose own start fails is solved again from the
    last converged solution of the sequence.
    ``serial_below`` -- grids of fewer points (``nx ny``) run their kernels on one numba
    thread, finer grids on ``threads``: on a small grid a thread barrier costs more than the
    work it splits (docs/robustness.md).
    ``exact_rules`` -- the starved solver only: the coarse-grid theta rules (None: the default
    rule; k: theta free on the k grids below the current one, frozen below) under which its
    mass re-solve with the exact zone solve is tried after the solve's own rule; ``()``: the
    solve's own rule only.
    """

    CYCLE_OPTIONAL: ClassVar[bool] = True
    points: int = 129
    cycle: str | None = None
    max_cycles: int = 30
    deformation: str = "fft"
    omega: float = 0.6
    omega_jd: float = 0.3
    tol: float = 1e-4
    tol_load: float = 1e-5
    n_coarse: int | None = None
    xmin: float | None = None
    xmax: float | None = None
    ymax: float | None = None
    y_ratio: float | None = None
    half: bool = False
    coarse_sweeps: int = 10
    elastic: bool = True
    far_field: bool | None = None
    y_pre: bool = True
    local_film_update: bool = True
    alternating: bool | None = None
    retry_square_cells: bool = True
    retry_full_refresh: bool = True
    retry_finer_start: bool = True
    retry_coarser_start: bool = True
    retry_uncapped_start: bool = True
    retry_from_neighbour: bool = True
    exact_rules: tuple[int | None, ...] = (None, 1)
    serial_below: int = 129 * 129

    def __post_init__(self) -> None:
        super().__post_init__()
        require_range("points", self.points, 9, 8193)
        for name in RETRIES:
            require_choice(name, getattr(self, name), (True, False))
        require_range("serial_below", self.serial_below, 1, 2**31, "grid points (nx ny)")
        if self.far_field is not None:
            require_choice("far_field", self.far_field, (True, False))
        if int(self.serial_below) != self.serial_below:
            raise InputError(f"serial_below = {self.serial_below} must be an integer (grid points)")
        rules = self.exact_rules
        if not isinstance(rules, (tuple, list)) or not all(
                r is None or (isinstance(r, Integral) and not isinstance(r, bool) and 0 <= r <= 20)
                for r in rules):
            raise InputError(f"exact_rules = {rules!r} must be a sequence of coarse-grid theta "
                             "rules, each None (the default rule) or an integer in [0, 20] (the "
                             "grids below the current one where theta moves)")
        # a tuple of ints, so that the options stay hashable (a list from a mapping of options)
        object.__setattr__(self, "exact_rules", tuple(None if r is None else int(r) for r in rules))
        # rigid surfaces carry the load within a few sqrt(2 H) of the centre, far inside the
        # Hertz circle at high M or theta (point.problem.default_domain)
        edge, side = (1.05, 0.5) if self.elastic else (1e-4, 1e-4)
        if self.xmin is not None:
            require_range("xmin", self.xmin, -20000.0, -edge, "- (x/a)")
        if self.xmax is not None:
            require_range("xmax", self.xmax, edge, 20000.0, "- (x/a)")
        if self.ymax is not None:
            require_range("ymax", self.ymax, side, 20000.0, "- (y/a)")
        if self.y_ratio is not None:
            require_range("y_ratio", self.y_ratio, 0.125, 8.0, "-")
            if abs(math.log2(self.y_ratio) - round(math.log2(self.y_ratio))) > 1e-12:
                raise InputError(f"y_ratio = {self.y_ratio:g} must be a power of 2 in [1/8, 8]")
        if self.levels is not None:
            require_range("levels", self.levels, 1, 12)
        require_range("coarse_sweeps", self.coarse_sweeps, 1, 1000)


#: keys of a scene's ``[solver.ehl]`` table that set the problem rather than the numerics
MODEL_KEYS = {"line": ("viscosity", "density", "xmin", "xmax"), "point": ("viscosity", "density")}


def scene_solver_table(scene: Any, contact: str) -> tuple[dict[str, Any], dict[str, Any]]:
    """``(model, options)`` keywords from the scene's ``[solver.ehl]`` table: the problem keys
    (viscosity and density laws; the line contact's domain) and the solver options, which
    :meth:`MultigridOptions.build` validates."""
    table = dict((getattr(scene, "solver", None) or {}).get("ehl") or {})
    model = {k: table.pop(k) for k in MODEL_KEYS[contact] if k in table}
    return model, table


def build_scene_options(cls: type[MultigridOptions], options: MultigridOptions | None,
                        table: dict[str, Any], kw: dict[str, Any]) -> MultigridOptions:
    """Options from ``options``, then the scene's ``[solver.ehl]`` table, then keywords;
    an error in the table names the table."""
    try:
        base = cls.build(options, **table) if table else options
    except InputError as exc:
        raise InputError(f"[solver.ehl] {exc}") from None
    return cls.build(base, **kw)
