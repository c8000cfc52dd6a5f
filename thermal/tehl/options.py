"""Options of a TEHL solve, line or point (:class:`TEHLOptions`)."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

from ehl_multigrid.model.errors import InputError, require_range
from ehl_multigrid.multigrid.options import LineOptions

from ..options import SURFACE_KERNELS, ThermalOptions


@dataclass(frozen=True)
class TEHLOptions:
    """Options of a TEHL line or point solve.

    points : EHL grid points (2^k + 1); the thermal stations are its nodes.
    nz : thermal intervals across the film (20: interior heat budget within 0.4 % on the
        appendix C line contacts at S = 0.5; 10 gives up to 1.4 %).
    xmin : inlet X = x/b (None: the core's default box); xmax : outlet X.
    box : the box scaled by this factor (line: the inlet moved upstream, ``xmax - xmin`` times
        ``box``; point: X and Y limits times ``box``); the error estimate's probe doubles it.
    relax : starting under-relaxation of the factors' logarithms per outer iteration (0, 1];
        halved (down to ``MIN_RELAX``) when the changes double in one outer iteration or grow
        in two in a row.
    max_outer : outer iterations allowed; an iteration whose trend still reaches the tolerances
        goes on up to 2.5 times as many (``thermal.tehl.outer.EXTEND_OUTER``).
    anderson : depth of the Anderson mixing (Walker & Ni 2011) of the damped factor update
        (the thermal layer's :func:`thermal.kernels._anderson_step`); 0 = plain damping.
    tol_P : |dP| / |P| (L2) between outer iterations; tol_H : relative change of Hc and Hm;
    tol_T : max |dT| [K] between outer iterations; each change is divided by the iteration's
        under-relaxation before it is compared with its tolerance. An iteration settled at its
        inner solves' noise floor converges too (``thermal.tehl.outer.settled``).
    tol_thermal : relative temperature tolerance of the thermal march (tol_T, tol_tau of
        :class:`~thermal.options.ThermalOptions`).
    thermal : False holds T = T_oil (Eyring shear thinning on the flow only).
    shear_thinning : False gives the flow the Newtonian eta(p, T) (Eyring stays in the friction).
    surface_kernel : surface-temperature kernel of the thermal layer.
    compressive_heating : the energy equation carries the compression work
        ``-(T/rho)(d rho/d T)_p u dp/dx`` (Bruyere et al. 2012; Habchi 2008) besides the
        thesis's terms (3.5) (:class:`~thermal.options.ThermalOptions`); False is the thesis's
        energy equation.
    warm_thermal : each thermal solve of the outer iteration starts from the previous one's
        temperatures (the same field within ``tol_thermal``, in fewer sweeps); False starts
        every one from the oil temperature.
    multigrid : overrides of the core :class:`LineOptions` (tol, cycle, levels ...); by default
        each multilevel solve stops on the films (``film_tol = tol_H / 4``: Hc and Hm change by
        less between two finest-grid cycles, load error below it), since a residual of 1e-5
        leaves Hm uncertain to about 7e-4 (docs/thermal.md).
    """

    points: int = 513
    nz: int = 20
    xmin: float | None = None
    xmax: float = 1.5
    box: float = 1.0
    relax: float = 0.5
    max_outer: int = 60
    anderson: int = 4
    tol_P: float = 1e-4
    tol_H: float = 1e-4
    tol_T: float = 1e-2
    tol_thermal: float = 1e-7
    thermal: bool = True
    shear_thinning: bool = True
    surface_kernel: str = "moving-strip"
    compressive_heating: bool = True
    multigrid: dict[str, Any] = field(default_factory=dict)
    warm_thermal: bool = True

    def __post_init__(self) -> None:
        n = int(self.points) - 1
        if isinstance(self.points, bool) or self.points != int(self.points) or self.points < 65 or n & (n - 1):
            raise InputError(f"points = {self.points!r} must be 2^k + 1 >= 65 (e.g. 257, 513, 1025)")
        if isinstance(self.nz, bool) or not isinstance(self.nz, int) or not 4 <= self.nz <= 400:
            raise InputError(f"nz = {self.nz!r} must be an integer in [4, 400] (intervals across the film)")
        if self.xmin is not None:
            require_range("xmin", self.xmin, -1000.0, -1.0, "- (x/b)")
        require_range("xmax", self.xmax, 1.0, 100.0, "- (x/b)")
        require_range("box", self.box, 0.25, 64.0, "- (times the default box)")
        require_range("relax", self.relax, 0.0, 1.0, "-", lo_open=True)
        require_range("max_outer", self.max_outer, 1, 1000, "outer iterations")
        if isinstance(self.anderson, bool) or not isinstance(self.anderson, int) or not 0 <= self.anderson <= 20:
            raise InputError(f"anderson = {self.anderson!r} must be an integer in [0, 20] (mixing depth)")
        require_range("tol_P", self.tol_P, 1e-10, 0.1, "-")
        require_range("tol_H", self.tol_H, 1e-10, 0.1, "-")
        require_range("tol_T", self.tol_T, 1e-8, 10.0, "K")
        require_range("tol_thermal", self.tol_thermal, 1e-12, 1e-3, "-")
        if self.surface_kernel not in SURFACE_KERNELS:
            raise InputError(f"surface_kernel = {self.surface_kernel!r} is not one of {list(SURFACE_KERNELS)}")
        if not isinstance(self.compressive_heating, bool):
            raise InputError(f"compressive_heating = {self.compressive_heating!r} must be true or false")

    def line_options(self) -> LineOptions:
        return LineOptions.build(None, **{"points": self.points, "raise_on_failure": False,
                                          "film_tol": 0.25 * self.tol_H, **self.multigrid})

    def thermal_options(self) -> ThermalOptions:
        return ThermalOptions(nx=self.points, nz=self.nz, tol_T=self.tol_thermal, tol_tau=self.tol_thermal,
                              max_inner=500, max_sweeps=400, momentum="on", thermal=self.thermal,
                              surface_kernel=self.surface_kernel, compressive_heating=self.compressive_heating)

    def with_changes(self, **changes: Any) -> TEHLOptions:
        return replace(self, **changes)
