"""Options of the thermal friction model, read from ``[solver.thermal]`` of a scene and keyword
overrides, validated with the core's error helpers."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields, replace
from typing import Any

from ehl_multigrid.model.errors import (
    InputError,
    reject_unknown_keys,
    require_choice,
    require_range,
)
from ehl_multigrid.model.fidelity import FIDELITIES

SLICE_RULES = ("cosine", "midpoint")
SLICE_PRESSURES = ("hertz", "thesis")
SURFACE_KERNELS = ("moving-strip", "carslaw-jaeger")
MOMENTUM = ("auto", "flux", "on", "off")

#: scene / thesis names accepted as aliases
_ALIASES = {"ny": "slices"}


@dataclass(frozen=True)
class ThermalOptions:
    """Numerical options (defaults follow appendix C: nx = 80, nz = 20, tolerances 1e-5).

    Attributes
    ----------
    nx : stations along x over [x_in, x_out] (uniform spacing).
    nz : intervals across the film (nz + 1 nodes in Z).
    x_in : inlet boundary X = x/b (thesis -2.5; -4 for the larger inlet of Figs 3.20-3.22).
    x_out : outlet X (None: 1 for Hertz input, the end of the EHL domain for solver input).
    tol_T : relative change of absolute temperature ending a station's iteration (thesis 1e-5).
    tol_tau : relative change of shear stress ending a station's iteration (thesis 1e-5).
    max_inner, max_sweeps : iteration limits (station iteration, inlet-to-outlet sweeps; a thick
        EHL inlet with strong back flow, e.g. appendix C from X = -4 with 40 degC oil, took 63
        with forward sweeps alone, 6 with a backward pass per sweep, and takes 5 now that the
        recirculation zone is relaxed within each sweep).
    relax : initial under-relaxation of the temperature update.
    slices : number of slices over half the point contact (thesis ny = 10).
    slice_rule : ``midpoint`` (uniform Y, thesis Fig. 3.7) or ``cosine`` (Y = sin(theta), theta at
        midpoints; second order even where the slice force has a square-root edge).
    slice_pressure : ``hertz`` (pmax sqrt(1 - X^2 - Y^2)) or ``thesis`` ((3.20)).
    surface_kernel : ``moving-strip`` (exact at any speed) or ``carslaw-jaeger`` ((3.6)-(3.7)).
    kernel_length : strip length of the moving-strip kernel [m] (None: B for a line contact,
        the transverse contact width 2b for a point contact).
    G : fluid shear modulus override [Pa] (None: the lubricant's; 1e30 = Maxwell term off).
    thermal : False holds the temperature at the oil inlet value (isothermal switch).
    compressive_heating : add the compression work ``-(T/rho)(d rho/d T)_p u dp/dx`` (T
        absolute, density (3.10)) to the energy equation (3.5), as in the TEHL energy equation
        of Bruyere et al. (2012) and Habchi (2008): heating where the oil is compressed (the
        inlet), cooling where it expands (the outlet). False (default) is the thesis's (3.5).
    momentum : pressure term of (3.4) (tau linear across the film, slope G = h dp/dx).
        ``flux``: G is chosen at each station so that the pressure-driven flow carries the EHL
        solution's pressure-driven flux ``-h^3/(12 eta) dp/dx`` (Reynolds, isothermal
        Newtonian, computed on the EHL grid); ``on``: G = h dp/dx of the given pressure;
        ``off``: no pressure term; ``auto``: ``flux`` for EHL input, ``off`` for Hertz pressure
        with a uniform film. A uniform film carries no net Poiseuille flux (mass conservation),
        and the square-root edges of the Hertz pressure make the Eyring Poiseuille heating at
        the edge nodes grow without bound under grid refinement; ``on`` keeps it anyway
        (docs/thermal.md). With a fixed gradient, the steep outlet of an
        EHL field (wall stress h/2 |dp/dx| of several tau0 where the pressure falls from the
        spike) drives an Eyring flow that the heating thins further: the Poiseuille flow and its
        heat run away (hundreds of kelvin, then NaN) although the EHL film carries a modest
        flux there; keeping the flux bounds them.
    """

    nx: int = 80
    nz: int = 20
    x_in: float = -2.5
    x_out: float | None = None
    tol_T: float = 1e-5
    tol_tau: float = 1e-5
    max_inner: int = 200
    max_sweeps: int = 100
    relax: float = 1.0
    slices: int = 10
    slice_rule: str = "midpoint"
    slice_pressure: str = "hertz"
    surface_kernel: str = "moving-strip"
    kernel_length: float | None = None
    G: float | None = None
    thermal: bool = True
    momentum: str = "auto"
    compressive_heating: bool = False

    def __post_init__(self) -> None:
        _int("nx", self.nx, 8, 100000)
        _int("nz", self.nz, 4, 10000)
        _int("max_inner", self.max_inner, 1, 100000)
        _int("max_sweeps", self.max_sweeps, 1, 10000)
        _int("slices", self.slices, 1, 10000)
        require_range("x_in", self.x_in, -50.0, -1.0, "-")
        if self.x_out is not None:
            require_range("x_out", self.x_out, self.x_in, 50.0, "-", lo_open=True)
        require_range("tol_T", self.tol_T, 0.0, 0.1, "-", lo_open=True)
        require_range("tol_tau", self.tol_tau, 0.0, 0.1, "-", lo_open=True)
        require_range("relax", self.relax, 0.0, 1.0, "-", lo_open=True)
        require_choice("slice_rule", self.slice_rule, SLICE_RULES)
        require_choice("slice_pressure", self.slice_pressure, SLICE_PRESSURES)
        require_choice("surface_kernel", self.surface_kernel, SURFACE_KERNELS)
        require_choice("momentum", self.momentum, MOMENTUM)
        if self.kernel_length is not None:
            require_range("kernel_length", self.kernel_length, 0.0, math.inf, "m", lo_open=True)
        if self.G is not None:
            require_range("G", self.G, 0.0, math.inf, "Pa", lo_open=True)
        if not isinstance(self.thermal, bool):
            raise InputError(f"thermal = {self.thermal!r} must be true or false")
        if not isinstance(self.compressive_heating, bool):
            raise InputError(f"compressive_heating = {self.compressive_heating!r} must be true or false")

    @classmethod
    def from_scene(cls, scene: Any = None, **overrides: Any) -> ThermalOptions:
        """Options from ``scene.solver['thermal']`` updated with non-None ``overrides``."""
        base: dict[str, Any] = {}
        if scene is not None:
            base.update(_normalise(dict(scene.solver.get("thermal", {})), "solver.thermal"))
        base.update(_normalise({k: v for k, v in overrides.items() if v is not None}, "thermal options"))
        return cls(**base)

    @classmethod
    def for_fidelity(cls, scene: Any, fidelity: str, **overrides: Any) -> ThermalOptions:
        """Options of :meth:`from_scene` with the traction grid of ``fidelity`` for the scene's
        contact (:data:`~ehl_multigrid.model.fidelity.FIDELITIES`), unless the scene's
        ``[solver.thermal]`` table sets it; an unknown ``fidelity`` sets no grid."""
        table = _normalise(dict(scene.solver.get("thermal", {})), "solver.thermal") if scene is not None else {}
        contact = "line" if getattr(scene, "kind", "line") == "line" else "point"
        level = FIDELITIES.get(fidelity)
        grid = level.traction_grid(contact).as_options() if level is not None else {}
        chosen = {k: v for k, v in grid.items() if k not in table and overrides.get(k) is None}
        return cls.from_scene(scene, **{**overrides, **chosen})

    def with_changes(self, **changes: Any) -> ThermalOptions:
        return replace(self, **_normalise(changes, "thermal options"))

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


def _normalise(d: dict[str, Any], section: str) -> dict[str, Any]:
    out = {}
    for k, v in d.items():
        out[_ALIASES.get(k, k)] = v
    reject_unknown_keys(section, out, {f.name for f in fields(ThermalOptions)})
    return out


def _int(name: str, value: Any, lo: int, hi: int) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or not lo <= value <= hi:
        raise InputError(f"{name} = {value!r} must be an integer in [{lo}, {hi}]")
