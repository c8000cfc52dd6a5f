"""The steady isothermal EHL line-contact problem in Venner's dimensionless form (Venner & Lubrecht 2000).

A :class:`LineProblem` holds the Moes groups (M, L), the lubricant model (viscosity and density
laws with the oil data they need), the domain and whether the surfaces deform. Build it from a
scene (physical units; ``eta0`` at the oil inlet temperature through Roelands' temperature
term) with :meth:`LineProblem.from_scene`, or from Moes (M, L) with
:meth:`LineProblem.from_moes` (oil defaults :data:`ehl_multigrid.model.constants.MOES_ONLY_DEFAULTS`).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from ..model import groups
from ..model.constants import ETA_INF, MOES_ONLY_DEFAULTS, P_R
from ..model.errors import InputError, require_choice, require_range
from ..multigrid.rheology import DENSITY, VISCOSITY, pack

#: Range of the Moes groups the solver accepts (beyond it the grids it would need are
#: impractical or the groups are meaningless).
M_RANGE = (0.1, 2.0e4)
L_RANGE = (0.0, 40.0)


@dataclass(frozen=True)
class LineProblem:
    """Dimensionless line-contact EHL problem.

    Attributes
    ----------
    M, L : Moes load and lubricant parameters (sum-velocity scaling, thesis 2.1.4).
    viscosity : ``"roelands"`` or ``"barus"``.
    density : ``"dowson-higginson"`` or ``"incompressible"``.
    alpha : pressure-viscosity coefficient [1/Pa] (Roelands-equivalent at p = 0).
    eta0 : ambient-pressure viscosity at the inlet temperature [Pa s].
    p0 : Roelands reference pressure [Pa].
    z : Roelands pressure-viscosity index [-].
    pmax : Hertzian maximum pressure [Pa] (``alpha pmax = alpha_bar``).
    xmin, xmax : domain ``X = x/b`` in ``[xmin, xmax]`` (default xmin: :func:`default_xmin`).
    elastic : False switches the elastic deformation off (rigid surfaces).
    b, R, film_scale : half-width [m], reduced radius [m] and metres per Moes film unit
        (physical mode only, NaN in Moes-only mode).
    """

    M: float
    L: float
    viscosity: str = "roelands"
    density: str = "dowson-higginson"
    alpha: float = MOES_ONLY_DEFAULTS["alpha"]
    eta0: float = MOES_ONLY_DEFAULTS["eta0"]
    p0: float = MOES_ONLY_DEFAULTS["p0"]
    z: float = math.nan
    pmax: float = math.nan
    xmin: float = math.nan
    xmax: float = 1.5
    elastic: bool = True
    b: float = math.nan
    R: float = math.nan
    film_scale: float = math.nan
    source: str = "moes"

    def __post_init__(self) -> None:
        require_range("M", self.M, *M_RANGE, "-")
        try:
            require_range("L", self.L, *L_RANGE, "-")
        except InputError as exc:
            raise InputError(f"{exc}: the line solver is not checked beyond it (a cold, viscous oil or a "
                             "high speed; such a contact is also far from isothermal)") from None
        require_choice("viscosity", self.viscosity, VISCOSITY)
        require_choice("density", self.density, DENSITY)
        require_range("alpha", self.alpha, 1e-10, 1e-7, "1/Pa")
        require_range("eta0", self.eta0, ETA_INF, 1e6, "Pa s", lo_open=True)
        require_range("p0", self.p0, 1e6, 1e10, "Pa")
        if not math.isfinite(self.xmin):
            object.__setattr__(self, "xmin", default_xmin(self.M, self.L))
        require_range("xmin", self.xmin, -1000.0, -0.5, "- (x/b)")
        require_range("xmax", self.xmax, 0.1, 100.0, "- (x/b)")
        if not math.isfinite(self.z):
            object.__setattr__(self, "z", self.alpha * self.p0 / math.log(self.eta0 / ETA_INF))
        if not math.isfinite(self.pmax):
            object.__setattr__(self, "pmax", self.alpha_bar / self.alpha)

    # -- constructors ---------------------------------------------------------------------
    @classmethod
    def from_moes(
        cls, M: float, L: float, *, viscosity: str = "roelands", density: str = "dowson-higginson",
        alpha: float | None = None, eta0: float | None = None, p0: float | None = None,
        xmin: float | None = None, xmax: float = 1.5, elastic: bool = True,
    ) -> LineProblem:
        """Problem from the Moes groups. The oil data default to ``MOES_ONLY_DEFAULTS``
        (``p0 = 1.96e8 Pa``, ``alpha = 2.2e-8 1/Pa``, ``eta0 = 0.04 Pa s``); the Hertzian
        pressure follows from ``alpha pmax = alpha_bar = L sqrt(M/(2 pi))``."""
        d = MOES_ONLY_DEFAULTS
        return cls(
            M=M, L=L, viscosity=viscosity, density=density,
            alpha=d["alpha"] if alpha is None else alpha,
            eta0=d["eta0"] if eta0 is None else eta0,
            p0=d["p0"] if p0 is None else p0,
            xmin=math.nan if xmin is None else xmin, xmax=xmax, elastic=elastic,
        )

    @classmethod
    def from_scene(
        cls, scene: Any, *, viscosity: str = "roelands", density: str = "dowson-higginson",
        xmin: float | None = None, xmax: float = 1.5, elastic: bool = True,
        us: float | None = None, load: float | None = None,
    ) -> LineProblem:
        """Problem for a line-contact :class:`~ehl_multigrid.model.scene.Scene` at its operating
        point (or the given ``us`` [m/s], ``load`` [N]). ``eta0`` and ``alpha`` are taken at
        the oil temperature ``T_oil`` (Roelands' temperature term); ``z`` is the oil's."""
        if scene.kind != "line":
            raise InputError(f"contact.kind = {scene.kind!r}: the line solver needs a line contact")
        sc = scene if us is None and load is None else scene.with_operating(
            **{k: v for k, v in (("us", us), ("load", load)) if v is not None})
        M, L = sc.moes()
        hz = sc.hertz
        with sc.naming_moes_inputs():
            return cls(
                M=M, L=L, viscosity=viscosity, density=density, alpha=sc.alpha, eta0=sc.eta0,
                p0=P_R, z=sc.lubricant.z, pmax=hz.pmax, xmin=math.nan if xmin is None else xmin,
                xmax=xmax, elastic=elastic,
                b=hz.b, R=sc.Rx, film_scale=sc.film_scale(), source=f"scene {sc.name}",
            )

    # -- derived --------------------------------------------------------------------------
    @property
    def lam(self) -> float:
        """Venner's ``lambda = 3 pi^2/(8 M^2)``."""
        return float(groups.venner_line(self.M, self.L)[0])

    @property
    def alpha_bar(self) -> float:
        """``alpha_bar = alpha pmax = L sqrt(M/(2 pi))``."""
        return float(groups.venner_line(self.M, self.L)[1])

    @property
    def physical(self) -> bool:
        """True when the geometry is known (scene mode): films in metres are available."""
        return math.isfinite(self.film_scale)

    def rheology(self) -> np.ndarray:
        """Packed parameters for the numba kernels (rheology.pack)."""
        lnr = math.log(self.eta0 / ETA_INF)
        return pack(self.viscosity, self.density, lnr, self.z, self.pmax / self.p0,
                    self.alpha_bar, self.pmax)

    def moes_from_venner(self, H: float) -> float:
        """``H_Moes = H_Venner 8 M / pi`` (:func:`~ehl_multigrid.model.groups.moes_from_venner_line`)."""
        return float(groups.moes_from_venner_line(H, self.M))

    def describe(self) -> dict[str, Any]:
        d = asdict(self)
        d.update(lam=self.lam, alpha_bar=self.alpha_bar)
        return d


def fit_central_film(M: float, L: float) -> float:
    """Central film of the Moes line fit in Venner units, ``H = H_Moes pi / (8 M)``."""
    from ..model.fits import moes_line_central

    return float(groups.venner_from_moes_line(moes_line_central(M, L), M))


def default_xmin(M: float, L: float) -> float:
    """Default inlet ``X = x/b``: -4.5 (Venner & Lubrecht's classic box), moved upstream at low load.

    The inlet zone scales with the rigid length ``sqrt(2 H)`` (H Venner, from the Moes fit);
    the inlet is put 20 such lengths upstream of the contact edge when that is beyond -4.5,
    since the classic box thins the film at low load (docs/accuracy.md, "Domain error").
    """
    H = fit_central_film(M, L)
    return float(min(-4.5, math.floor(2.0 * (-1.0 - 20.0 * math.sqrt(2.0 * H))) / 2.0))


def box_ratio(problem: LineProblem) -> float:
    """The problem's box length over that of its default box ``[default_xmin, 1.5]``."""
    return (problem.xmax - problem.xmin) / (1.5 - default_xmin(problem.M, problem.L))


def check_grid(points: int, levels: int, min_coarse: int = 17) -> int:
    """Validate ``points = 2^k + 1`` and ``levels``; return the coarsest grid's points."""
    require_range("points", points, 33, 2**20 + 1, "grid points")
    n = int(points) - 1
    if points != int(points) or n & (n - 1):
        raise InputError(f"points = {points} must be 2^k + 1 (e.g. 257, 1025, 4097)")
    require_range("levels", levels, 1, 20, "-")
    if levels != int(levels):
        raise InputError(f"levels = {levels} must be an integer")
    coarse = n // 2 ** (int(levels) - 1)
    if coarse < min_coarse - 1:
        top = int(math.log2(n / (min_coarse - 1))) + 1
        raise InputError(
            f"levels = {levels} is outside the allowed range [1, {top}] for points = {points}: "
            f"the coarsest grid needs at least {min_coarse} points"
        )
    return coarse + 1
