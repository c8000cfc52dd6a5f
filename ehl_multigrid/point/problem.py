"""Dimensionless point-contact EHL problem (Venner's form, circular and elliptic).

Scaling: ``X = x/a``, ``Y = y/a`` (``a`` the Hertz semi-axis along the rolling direction x),
``P = p/pmax``, ``H = h Rx/a^2``. With Hertz ``a = f W^(1/3) Rx``, ``pmax = g W^(1/3) E'``
(``W = F/(E' Rx^2)``, f and g depending on the ellipticity ``theta = Rx/Ry`` only) the
equations become

* Reynolds  ``d/dX(eps dP/dX) + d/dY(eps dP/dY) - d(rho H)/dX = 0``, ``eps = rho H^3/(eta lambda)``,
  ``lambda = 6 eta0 us Rx^2/(a^3 pmax) = 6/(f^3 g M^(4/3))``;
* film ``H = H00 + X^2/2 + theta Y^2/2 + cd ∫∫ P/r dX'dY'``, ``cd = 2 g/(pi f)``;
* load ``∫∫ P dX dY = 1/(g f^2) = 2 pi b/(3 a)``;
* ``alpha_bar = alpha pmax = g L M^(1/3)``; ``H_Moes = H_Venner f^2 M^(2/3)``.

For a circular contact f = (3/2)^(1/3), g = f/pi, which gives Venner's
``lambda = (128 pi^3/(3 M^4))^(1/3)``, ``cd = 2/pi^2``, load ``2 pi/3`` and
``H_Moes = H_Venner (3M/2)^(2/3)``.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from ..model.constants import ETA_INF, MOES_ONLY_DEFAULTS, P_R
from ..model.errors import InputError, require_choice, require_range
from ..model.hertz import hertz_elliptic
from ..multigrid.rheology import DENSITY, VISCOSITY, pack


def hertz_shape(theta: float) -> tuple[float, float, float]:
    """``(f, g, b/a)`` of the exact Hertz solution for ellipticity ``theta = Rx/Ry``.

    ``a = f W^(1/3) Rx`` and ``pmax = g W^(1/3) E'`` with ``W = F/(E' Rx^2)``.
    """
    hz = hertz_elliptic(1.0, 1.0, 1.0 / theta, 1.0)
    return hz.a, hz.pmax, hz.b / hz.a


@dataclass(frozen=True)
class PointProblem:
    """Parameters of one dimensionless point-contact problem.

    Attributes
    ----------
    M, L : Moes load and lubricant parameters (point-contact groups used with (2.23)) [-]
    theta : ellipticity Rx/Ry [-]
    viscosity : ``roelands`` or ``barus``
    density : ``dowson-higginson`` or ``incompressible``
    alpha : pressure-viscosity coefficient [1/Pa]
    eta0 : ambient viscosity [Pa s]
    p_r : Roelands reference pressure [Pa]
    pmax : Hertz pressure [Pa] (``alpha_bar/alpha``; 0 when L = 0 in Moes-only mode)
    a, b : Hertz semi-axes [m] (NaN in Moes-only mode)
    Rx : reduced radius in x [m] (NaN in Moes-only mode)
    film_scale : metres per unit Moes film (NaN in Moes-only mode)
    """

    M: float
    L: float
    theta: float = 1.0
    viscosity: str = "roelands"
    density: str = "dowson-higginson"
    alpha: float = MOES_ONLY_DEFAULTS["alpha"]
    eta0: float = MOES_ONLY_DEFAULTS["eta0"]
    p_r: float = MOES_ONLY_DEFAULTS["p0"]
    a: float = math.nan
    b: float = math.nan
    Rx: float = math.nan
    film_scale: float = math.nan
    pmax_physical: float = math.nan

    def __post_init__(self) -> None:
        require_range("M", self.M, 0.0, 1e6, "-", lo_open=True)
        require_range("L", self.L, 0.0, 100.0, "-")
        require_range("theta (ellipticity Rx/Ry)", self.theta, 0.01, 100.0, "-")
        require_choice("viscosity", self.viscosity, VISCOSITY)
        require_choice("density", self.density, DENSITY)
        require_range("alpha", self.alpha, 1e-10, 1e-6, "1/Pa")
        require_range("eta0", self.eta0, ETA_INF, 1e6, "Pa s", lo_open=True)
        require_range("p0 (Roelands reference pressure)", self.p_r, 1e6, 1e10, "Pa")

    # -- Hertz shape --------------------------------------------------------------------------
    @property
    def shape(self) -> tuple[float, float, float]:
        return hertz_shape(self.theta)

    @property
    def b_over_a(self) -> float:
        return self.shape[2]

    @property
    def lam(self) -> float:
        """Venner's lambda ``6/(f^3 g M^(4/3))`` [-]."""
        f, g, _ = self.shape
        return 6.0 / (f**3 * g * self.M ** (4.0 / 3.0))

    @property
    def alpha_bar(self) -> float:
        """``alpha pmax = g L M^(1/3)`` [-]."""
        f, g, _ = self.shape
        return g * self.L * self.M ** (1.0 / 3.0)

    @property
    def pmax(self) -> float:
        """Hertz pressure [Pa] used by the Roelands and density relations."""
        if math.isfinite(self.pmax_physical):
            return self.pmax_physical
        return self.alpha_bar / self.alpha

    @property
    def cd(self) -> float:
        """Deformation coefficient ``2 g/(pi f)`` (``2/pi^2`` circular)."""
        f, g, _ = self.shape
        return 2.0 * g / (math.pi * f)

    @property
    def load(self) -> float:
        """Target ``∫∫ P dX dY = 2 pi b/(3 a)``."""
        return 2.0 * math.pi * self.b_over_a / 3.0

    @property
    def moes_factor(self) -> float:
        """``H_Moes / H_Venner = f^2 M^(2/3)``."""
        f, _, _ = self.shape
        return f * f * self.M ** (2.0 / 3.0)

    @property
    def roelands_z(self) -> float:
        """Roelands index equivalent to ``alpha`` at p = 0: ``z = alpha p_r/ln(eta0/eta_inf)``."""
        return self.alpha * self.p_r / math.log(self.eta0 / ETA_INF)

    @property
    def ln_eta_ratio(self) -> float:
        return math.log(self.eta0 / ETA_INF)

    @property
    def physical(self) -> bool:
        return math.isfinite(self.film_scale)

    def rheology(self) -> np.ndarray:
        """Packed viscosity and density parameters for the numba kernels."""
        return pack(self.viscosity, self.density, self.ln_eta_ratio, self.roelands_z,
                    self.pmax / self.p_r, self.alpha_bar, self.pmax)

    def to_dict(self) -> dict:
        d = asdict(self)
        d.update(lam=self.lam, alpha_bar=self.alpha_bar, pmax=self.pmax, cd=self.cd,
                 load_target=self.load, b_over_a=self.b_over_a, roelands_z=self.roelands_z)
        return d


def problem_from_moes(M: float, L: float, theta: float = 1.0, viscosity: str = "roelands",
                      density: str = "dowson-higginson", alpha: float | None = None,
                      eta0: float | None = None, p0: float | None = None) -> PointProblem:
    """Moes-only problem; the oil defaults are ``ehl_multigrid.model.constants.MOES_ONLY_DEFAULTS``."""
    from ..model.constants import MOES_ONLY_DEFAULTS as D

    return PointProblem(
        M=float(M), L=float(L), theta=float(theta), viscosity=viscosity, density=density,
        alpha=D["alpha"] if alpha is None else float(alpha),
        eta0=D["eta0"] if eta0 is None else float(eta0),
        p_r=D["p0"] if p0 is None else float(p0),
    )


def problem_from_scene(scene, viscosity: str = "roelands", density: str = "dowson-higginson") -> PointProblem:
    """Problem of a point or elliptic scene; eta0 and alpha at the oil inlet temperature."""
    if scene.kind == "line":
        raise InputError(f"scene {scene.name!r} is a line contact; the point solver needs kind point|elliptic")
    M, L = scene.moes()
    hz = scene.hertz
    lub = scene.lubricant
    # Roelands' z of the scene's oil: p_r chosen so that alpha(T_oil) = z ln(eta0/eta_inf)/p_r.
    eta0 = scene.eta0
    p_r = lub.z * math.log(eta0 / ETA_INF) / scene.alpha if scene.alpha > 0 else P_R
    with scene.naming_moes_inputs():
        return PointProblem(
            M=M, L=L, theta=scene.theta, viscosity=viscosity, density=density,
            alpha=scene.alpha, eta0=eta0, p_r=p_r, a=hz.a, b=hz.b, Rx=scene.Rx,
            film_scale=scene.film_scale(), pmax_physical=hz.pmax,
        )


def rigid_length(problem: PointProblem) -> float:
    """Inlet length scale ``s = sqrt(2 H)`` [a], H the fitted central film (Venner units).

    Where the film is thick compared with the elastic deformation (low M) the pressure spreads
    over a few ``s`` around the contact instead of over the Hertz circle.
    """
    from ..model.fits import nijenbanning_central

    H = float(nijenbanning_central(problem.M, problem.L, problem.theta)) / problem.moes_factor
    return math.sqrt(2.0 * H)


def rigid_film(problem: PointProblem) -> float:
    """Central film of the same contact with rigid surfaces (Venner units): Nijenbanning's
    rigid asymptotes (2.25, 2.27) combined as ``(HRI^3 + HRP^3)^(1/3)``, the form (2.23) takes
    without its elastic terms (``s = 3`` where the rigid film dominates)."""
    from ..model.fits import nijenbanning_terms

    t = nijenbanning_terms(problem.M, problem.L, problem.theta)
    H = (float(t["HRI"]) ** 3 + (float(t["HRP"]) ** 3 if problem.L > 0 else 0.0)) ** (1.0 / 3.0)
    return H / problem.moes_factor


def rigid_film_length(problem: PointProblem) -> float:
    """Inlet length ``s = sqrt(2 H)`` [a] of the rigid film :func:`rigid_film`: the size of a
    rigid contact's pressure zone."""
    return math.sqrt(2.0 * rigid_film(problem))


def rigid_coarse_intervals(length: float, points: int, s: float) -> int:
    """Coarse intervals along X of a rigid-surface solve: the smallest ``16 * 2^k`` whose mesh
    is at most :data:`RIGID_COARSE_CELL` times the rigid inlet length ``s = sqrt(2 H)``
    (:func:`rigid_film`), and no more than the finest grid has. Without the elastic
    deformation the pressure is carried within a few ``s`` of the centre (0.12 a at circular
    (20, 0)), and a coarse grid that cannot hold it drives the load balance to blow up."""
    n = 16
    while length / n > RIGID_COARSE_CELL * s and n < points - 1:
        n *= 2
    return min(n, points - 1)


#: coarsest mesh of a rigid-surface solve in units of its inlet length (rigid_coarse_intervals)
RIGID_COARSE_CELL = 0.8


def domain_scale(problem: PointProblem) -> float:
    """Factor >= 1 by which the default domain is widened in the thick-film (low M) regime:
    ``max(1, (1 + 3 s)/4.5)``, so that the inlet holds at least 3 inlet lengths ``s`` upstream
    of the contact (s from :func:`rigid_length`). It is 1 (the classic domain) while
    s <= 1.17 (M >~ 5 at L = 0, every M >= 10 for L <= 25) and 5.5 at M = 1, L = 0."""
    return max(1.0, (1.0 + 3.0 * rigid_length(problem)) / 4.5)


#: default box of a rigid-surface solve in units of its inlet length s (rigid_film): X in
#: [-RIGID_BOX[0] s, RIGID_BOX[1] s], |Y| <= RIGID_BOX[2] s / sqrt(theta)
RIGID_BOX = (24.0, 8.0, 16.0)


def default_domain(problem: PointProblem, elastic: bool = True) -> tuple[float, float, float]:
    """Default ``(xmin, xmax, ymax)`` in units of a: the classic X in [-4.5, 1.5],
    Y in [-3, 3] b/a, scaled by :func:`domain_scale` at low M. Rigid surfaces
    (``elastic=False``): :data:`RIGID_BOX` in units of the rigid inlet length
    ``s = sqrt(2 H)`` (:func:`rigid_film`), the size of their pressure zone (0.15 a at circular
    (20, 0), 0.03 a at theta 4), whatever the Hertz circle.

    Doubling this box at equal mesh size raises Hc by 1.2 % at (M, L) = (20, 10) and more at
    lighter loads (docs/accuracy.md, "Domain error").
    """
    if not elastic:
        s = rigid_film_length(problem)
        return -RIGID_BOX[0] * s, RIGID_BOX[1] * s, RIGID_BOX[2] * s / math.sqrt(problem.theta)
    f = domain_scale(problem)
    return -4.5 * f, 1.5 * f, 3.0 * f * problem.b_over_a


def resolve_domain(problem: PointProblem, xmin: float | None, xmax: float | None,
                   ymax: float | None, elastic: bool = True) -> tuple[float, float, float]:
    """``(xmin, xmax, ymax)``: the given values, :func:`default_domain` where None."""
    dx0, dx1, dy = default_domain(problem, elastic)
    return (dx0 if xmin is None else float(xmin), dx1 if xmax is None else float(xmax),
            dy if ymax is None else float(ymax))


#: Contacts at least this wide (b/a; theta <~ 0.12) keep at most :data:`WIDE_COARSE_MAX`
#: coarse intervals along X (:func:`coarse_intervals`; measurements in docs/robustness.md).
WIDE_CONTACT = 4.0
WIDE_COARSE_MAX = 64


def coarse_intervals(M: float, length: float, points: int, scale: float = 1.0,
                     inlet: float = 0.0, b_over_a: float = 1.0) -> int:
    """Intervals of the coarsest grid along X: the smallest ``16 * 2^k`` that gives a coarse
    mesh size <= 0.375 a (M < 200), 0.1875 a (200 <= M < 1000) or 0.094 a (M >= 1000), and no
    more than the finest grid has. The Hertz zone must be resolved on the coarsest grid for
    the load balance to steer H00 (a [-13.5, 3.5] domain with 16 coarse intervals diverges at
    (20, 10); validation/point/REPORT.md).

    In the thick-film regime (``scale > 1``, :func:`domain_scale`) the pressure spreads over
    the inlet length ``inlet`` = s (:func:`rigid_length`) instead of the Hertz circle, and the
    coarse mesh may be as coarse as s: a coarse mesh tied to a instead leaves a wide box with
    two or three levels whose far field converges over hundreds of cycles.

    Wide contacts (``b_over_a >=`` :data:`WIDE_CONTACT`) stop at :data:`WIDE_COARSE_MAX`
    intervals: their coarsest grid is long in Y too, and with 128 intervals on twice the
    default box its relaxation does not balance the load (docs/robustness.md, "Point solver
    defaults")."""
    h = (0.375 if M < 200 else (0.1875 if M < 1000 else 0.094)) * scale
    if scale > 1.0:
        h = max(h, inlet)
    n = 16
    top = WIDE_COARSE_MAX if b_over_a >= WIDE_CONTACT else points - 1
    while length / n > h and n < min(points - 1, top):
        n *= 2
    return min(n, points - 1)


#: Contacts narrower than this (b/a; theta >~ 6) at M >= 1000 need more cells across b than
#: min_points' b/a scaling gives: their side constriction at |Y| = b is thinner relative to b
#: than a circular contact's outlet constriction is to a (docs/robustness.md).
NARROW_BELOW = 0.3


def min_points(M: float, b_over_a: float = 1.0, cap: int | None = 2049) -> int:
    """Smallest finest grid (points along X) at which the FAS solver is expected to converge
    with the default domain: 129 below M = 200, 257 below M = 1000, 513 from M = 1000 on, times
    ``2^ceil(log2(0.75 a/b))`` for contacts narrower than long (b/a < 0.75, theta > ~2), so the
    semi-axis b keeps about as many cells as a circular contact has across a; contacts with
    b/a < :data:`NARROW_BELOW` need twice that from M = 1000 and four times from M = 3000 (a
    lower bound there: 4097 points fail at (5000, theta 10), 8193 were not tried). Capped at
    ``cap`` (None: uncapped, the grid a failure message asks for). The measured limits are in
    docs/robustness.md, "Point solver defaults"."""
    n = 129 if M < 200 else (257 if M < 1000 else 513)
    if b_over_a < 0.75:
        n = (n - 1) * 2 ** math.ceil(math.log2(0.75 / b_over_a)) + 1
    if b_over_a < NARROW_BELOW and M >= 1000:
        n = (n - 1) * (2 if M < 3000 else 4) + 1
    return n if cap is None else min(n, cap)
