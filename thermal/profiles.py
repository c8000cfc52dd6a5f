"""Pressure and film input of the thermal model: one line profile per line contact or per
point-contact slice (thesis 3.2.1.5, 3.2.2.2; slice pressure (3.20)).

Sources, one interface (:class:`LineProfile`):

* Hertz pressure with a uniform film (the thesis's simple model): :func:`hertz_profile`;
* an EHL solution as plain arrays (x, p, h): :func:`profile_from_arrays`;
* an EHL :class:`~ehl_multigrid.model.results.Result` of kind ``ehl_line`` / ``ehl_point`` following the
  naming contract (coords ``x`` [m], fields ``p`` [Pa], ``h`` [m] on ("x",) or ("x", "y")):
  :func:`profiles_from_result`; its fields, or the main job's typed film
  (:class:`~ehl_multigrid.model.solved_film.SolvedFilm`): :func:`profiles_from_fields`;
* point contacts sliced in Y, each slice a line problem: :func:`hertz_slices` (true Hertz slice
  ``pmax sqrt(1 - X^2 - Y^2)`` or the thesis slice (3.20) ``pmax sqrt((1 - X^2)(1 - Y^2))``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ehl_multigrid.model.errors import InputError, require_positive, require_range


@dataclass(frozen=True)
class LineProfile:
    """Pressure and film along one line (a line contact, or one slice of a point contact).

    Attributes
    ----------
    X : stations x/b, uniform [-]
    b : length scale of X (Hertz half-width along x) [m]
    p : pressure [Pa]; h : film thickness [m] (both on X)
    width : length of contact this line stands for [m] (B for a line contact, the slice's share
        of the transverse width for a point contact)
    source : where p and h came from (``hertz``, ``thesis-slice``, ``ehl``, ``arrays``)
    Y : slice position y/b_y (0 for a line contact)
    contact_half : half-length of the Hertz contact on this line in X units (1 for a line;
        ``sqrt(1 - Y^2)`` for a slice); statistics "in the contact" use |X| <= contact_half
    gradient : dp/dx [Pa/m] on X taken from the source grid of an EHL field (None: differences
        of ``p`` on X)
    poiseuille_flux : pressure-driven volume flux per unit width of the EHL solution,
        ``-h^3/(12 eta) dp/dx`` [m^2/s], on X (None for Hertz input)
    """

    X: np.ndarray
    b: float
    p: np.ndarray
    h: np.ndarray
    width: float
    source: str
    Y: float = 0.0
    contact_half: float = 1.0
    gradient: np.ndarray | None = None
    poiseuille_flux: np.ndarray | None = None

    @property
    def x(self) -> np.ndarray:
        return self.X * self.b

    @property
    def dx(self) -> float:
        return float(self.X[1] - self.X[0]) * self.b

    @property
    def dpdx(self) -> np.ndarray:
        """Pressure gradient [Pa/m]: the source grid's for an EHL field, else second-order
        differences of the nodal pressure (bounded where the Hertz pressure has infinite slope)."""
        if self.gradient is not None:
            return self.gradient
        g = np.gradient(self.p, self.dx)
        # where p = 0 (ambient / cavitated, and the Hertz edge itself) no pressure gradient drives
        # flow; the one-sided slope of a square-root edge would otherwise put a grid-dependent
        # Poiseuille hot spot on the low-viscosity edge node
        return np.where(self.p > 0.0, g, 0.0)

    @property
    def contact_mask(self) -> np.ndarray:
        return np.abs(self.X) <= self.contact_half + 1e-12


def _check_film(h: np.ndarray, what: str) -> None:
    if not np.all(np.isfinite(h)) or np.any(h <= 0):
        bad = h[~(np.isfinite(h) & (h > 0))]
        raise InputError(
            f"{what}: film thickness h = {bad.ravel()[:3]} m must be finite and > 0 everywhere "
            "(a zero film has no thermal EHL solution; use the mixed-lubrication layer)"
        )


def _grid(nx: int, x_in: float, x_out: float) -> np.ndarray:
    if not x_out > x_in:
        raise InputError(f"x_out = {x_out:.6g} must exceed x_in = {x_in:.6g} (X = x/b)")
    return np.linspace(x_in, x_out, nx)


def edge_aligned_grid(nx: int, x_in: float, x_out: float) -> np.ndarray:
    """``nx`` uniform stations near [x_in, x_out] with X = -1 and X = 1 on nodes.

    The spacing is ``2/nc`` with ``nc`` cells across the contact; the ends move by less than
    half a cell. Nodes on the square-root edges of the Hertz pressure make the x quadrature
    error regular (order 1.5) instead of depending on where the edges fall between nodes.
    """
    if not x_out > x_in:
        raise InputError(f"x_out = {x_out:.6g} must exceed x_in = {x_in:.6g} (X = x/b)")
    if x_in > -1.0 or x_out < 1.0:
        return _grid(nx, x_in, x_out)
    nc = max(2, int(round(2.0 * (nx - 1) / (x_out - x_in))))
    dX = 2.0 / nc
    n_out = int(round((x_out - 1.0) / dX))
    n_in = nx - 1 - nc - n_out
    if n_in < 0:
        return _grid(nx, x_in, x_out)
    return -1.0 - n_in * dX + dX * np.arange(nx)


def hertz_profile(
    pmax: float,
    b: float,
    h: float,
    *,
    nx: int,
    x_in: float = -2.5,
    x_out: float = 1.0,
    width: float,
    Y: float = 0.0,
    form: str = "hertz",
) -> LineProfile:
    """Hertz pressure with a uniform film ``h`` [m], on edge-aligned stations.

    ``form='hertz'``: ``pmax sqrt(1 - X^2 - Y^2)``; the slice at Y is itself a Hertz line profile
    of half-width ``b c`` and peak ``pmax c``, ``c = sqrt(1 - Y^2)``, and X is measured in that
    half-width (Y = 0: the line contact).
    ``form='thesis'``: the thesis slice (3.20) ``pmax sqrt((1 - X^2)(1 - Y^2))``, X = x/b.
    """
    require_positive("pmax", pmax, "Pa")
    require_positive("b", b, "m")
    require_range("film thickness h", h, 0.0, 1e-2, "m", lo_open=True)
    require_range("Y", Y, 0.0, 1.0, "-", hi_open=True)
    X = edge_aligned_grid(nx, x_in, x_out)
    c = math.sqrt(1.0 - Y * Y)
    if form == "hertz":
        p = pmax * c * np.sqrt(np.clip(1.0 - X * X, 0.0, None))
        scale = b * c
        source = "hertz"
    elif form == "thesis":
        p = pmax * c * np.sqrt(np.clip(1.0 - X * X, 0.0, None))
        scale = b
        source = "thesis-slice"
    else:
        raise InputError(f"slice pressure form = {form!r} is not one of ['hertz', 'thesis']")
    return LineProfile(X, scale, p, np.full_like(X, float(h)), float(width), source, float(Y), 1.0)


def profile_from_arrays(
    x: np.ndarray,
    p: np.ndarray,
    h: np.ndarray,
    *,
    b: float,
    nx: int,
    width: float,
    x_in: float | None = -2.5,
    x_out: float | None = None,
    Y: float = 0.0,
    contact_half: float = 1.0,
    source: str = "arrays",
    viscosity: Callable[[np.ndarray], np.ndarray] | None = None,
) -> LineProfile:
    """Resample an EHL profile (x [m], p [Pa], h [m]) onto ``nx`` uniform stations.

    The thermal domain is ``[max(x_in, x_min/b), x_out or x_max/b]``: it cannot start upstream of
    the given arrays. Negative pressures (cavitation) are set to zero.

    The pressure gradient is differentiated on the given grid and then interpolated, so that
    every station gets the local p, dp/dx and h of the EHL solution. Differentiating the
    resampled pressure instead puts the drop of the outlet spike, taken across two coarse
    cells, on a station whose own pressure (and viscosity) is already low: a Poiseuille flow
    many times the film's and a hot spot that moves with nx. With ``viscosity`` (the EHL
    solver's isothermal ``eta(p)`` [Pa s]) the Reynolds pressure-driven flux
    ``-h^3/(12 eta) dp/dx`` [m^2/s] is computed on the given grid as well and resampled; the
    thermal march keeps this flux (:func:`thermal.kernels.solve_stress_slope`). It is taken at
    the given nodes: evaluated between them with the mean of ``h^3/(12 eta)`` (the solvers'
    discretisation) the flux next to the spike, where eta changes by orders of magnitude from
    node to node, lands on coarse stations of high viscosity and doubles their Poiseuille heat
    (measured: 1.9 times the Newtonian dissipation at nx = 20 against 0.5 with nodal values).
    """
    x = np.asarray(x, dtype=float)
    p = np.asarray(p, dtype=float)
    h = np.asarray(h, dtype=float)
    if x.ndim != 1 or p.shape != x.shape or h.shape != x.shape or x.size < 3:
        raise InputError(f"EHL arrays must be 1-D of equal length >= 3 (x {x.shape}, p {p.shape}, h {h.shape})")
    if np.any(np.diff(x) <= 0):
        raise InputError("EHL array x must be strictly increasing [m]")
    if not np.all(np.isfinite(p)):
        raise InputError("EHL pressure p contains non-finite values [Pa]")
    _check_film(h, "EHL input")
    require_positive("b", b, "m")
    Xd = x / b
    lo = Xd[0] if x_in is None else max(x_in, Xd[0])
    hi = Xd[-1] if x_out is None else min(x_out, Xd[-1])
    X = _grid(nx, lo, hi)
    pp = np.clip(np.interp(X, Xd, p), 0.0, None)
    hh = np.interp(X, Xd, h)
    pc = np.clip(p, 0.0, None)
    # no pressure gradient drives flow where p = 0 (ambient or cavitated)
    gd = np.where(pc > 0.0, np.gradient(pc, x), 0.0)
    inside = pp > 0.0
    grad = np.where(inside, np.interp(X, Xd, gd), 0.0)
    flux = None
    if viscosity is not None:
        wet = pc > 0.0
        if wet.any() and np.ptp(h[wet]) <= 1e-9 * float(np.max(h[wet])):
            # a uniform film (Hertz pressure with a fitted film, not a Reynolds solution): by
            # continuity (um h + q_p constant along x) its pressure-driven flux is the value where
            # the pressure ends, zero, as for the Hertz input
            flux = np.zeros_like(X)
        else:
            qd = -h**3 * gd / (12.0 * np.asarray(viscosity(pc), dtype=float))
            flux = np.where(inside, np.interp(X, Xd, qd), 0.0)
    return LineProfile(X, float(b), pp, hh, float(width), source, float(Y), float(contact_half), grad, flux)


def slice_positions(n: int, rule: str = "midpoint") -> tuple[np.ndarray, np.ndarray]:
    """Slice centres ``Y_j`` in (0, 1) and widths ``dY_j`` over half the contact (sum dY = 1).

    ``midpoint``: uniform slices (the thesis's figure 3.7). ``cosine``: ``Y = sin(theta)`` with
    theta at the midpoints of [0, pi/2], weights ``cos(theta) dtheta``; this removes the
    square-root edge of the Hertz slice force and converges faster in n.
    """
    if rule == "midpoint":
        Y = (np.arange(n) + 0.5) / n
        return Y, np.full(n, 1.0 / n)
    if rule == "cosine":
        dth = 0.5 * math.pi / n
        th = (np.arange(n) + 0.5) * dth
        w = np.cos(th) * dth
        return np.sin(th), w / w.sum()
    raise InputError(f"slice_rule = {rule!r} is not one of ['cosine', 'midpoint']")


def hertz_slices(
    pmax: float,
    a: float,
    b_y: float,
    h: float,
    *,
    n: int,
    nx: int,
    x_in: float = -2.5,
    x_out: float = 1.0,
    rule: str = "midpoint",
    form: str = "hertz",
) -> list[LineProfile]:
    """Slices of a point contact (semi-axes ``a`` along x, ``b_y`` along y) with a uniform film.

    Each slice stands for a strip of width ``2 b_y dY_j`` (both halves of the contact, which is
    symmetric in y).
    """
    Y, dY = slice_positions(n, rule)
    return [
        hertz_profile(pmax, a, h, nx=nx, x_in=x_in, x_out=x_out, width=2.0 * b_y * w, Y=float(yy), form=form)
        for yy, w in zip(Y, dY, strict=True)
    ]


def profiles_from_result(
    result,
    *,
    nx: int,
    x_in: float | None = -2.5,
    x_out: float | None = None,
    slices: int = 10,
    rule: str = "midpoint",
    b: float | None = None,
    b_y: float | None = None,
    length: float | None = None,
    viscosity: Callable[[np.ndarray], np.ndarray] | None = None,
) -> list[LineProfile]:
    """Line profiles from an EHL :class:`Result` (kinds ``ehl_line``, ``ehl_point``).

    Length scales come from the result's scene (Hertz half-widths) unless given. Line results
    give one profile of width B; point results are sliced at ``Y_j`` (y/b_y) by linear
    interpolation of p(x, y) and h(x, y) between grid lines, using the half y >= 0 (the EHL
    point solution is symmetric in y). ``viscosity`` as in :func:`profile_from_arrays`.
    """
    kind = getattr(result, "kind", None)
    if kind not in ("ehl_line", "ehl_point"):
        raise InputError(f"EHL input result kind = {kind!r} is not one of ['ehl_line', 'ehl_point']")
    for name in ("p", "h"):
        if name not in result.fields:
            raise InputError(f"EHL result has no field {name!r} (needs p [Pa] and h [m]; naming contract)")
    if "x" not in result.coords:
        raise InputError("EHL result has no coordinate 'x' [m] (naming contract)")
    y = result["y"] if kind == "ehl_point" and "y" in result.coords else None
    return profiles_from_fields(
        kind == "ehl_line", result["x"], y, result["p"], result["h"], result.scene, nx=nx, x_in=x_in,
        x_out=x_out, slices=slices, rule=rule, b=b, b_y=b_y, length=length, viscosity=viscosity)


def profiles_from_fields(
    line: bool,
    x: np.ndarray,
    y: np.ndarray | None,
    p: np.ndarray,
    h: np.ndarray,
    scene: Any = None,
    *,
    nx: int,
    x_in: float | None = -2.5,
    x_out: float | None = None,
    slices: int = 10,
    rule: str = "midpoint",
    b: float | None = None,
    b_y: float | None = None,
    length: float | None = None,
    viscosity: Callable[[np.ndarray], np.ndarray] | None = None,
) -> list[LineProfile]:
    """Line profiles of an EHL film: x [m], p [Pa] and h [m] on ``(x,)`` for a ``line``
    contact, on ``(x, y)`` with y [m] for a point contact (sliced as in
    :func:`profiles_from_result`). Length scales default to the Hertz half-widths and the line
    length of ``scene``."""
    if b is None:
        if scene is None:
            raise InputError("EHL result without a scene: give the half-width b [m]")
        b = scene.hertz.a
    x = np.asarray(x, dtype=float)
    p = np.asarray(p, dtype=float)
    h = np.asarray(h, dtype=float)
    if line:
        if length is None:
            if scene is None:
                raise InputError("EHL line result without a scene: give the line length [m]")
            length = scene.length
        return [profile_from_arrays(x, p, h, b=b, nx=nx, width=length, x_in=x_in, x_out=x_out, source="ehl",
                                    viscosity=viscosity)]
    if y is None:
        raise InputError("EHL point result has no coordinate 'y' [m] (naming contract)")
    y = np.asarray(y, dtype=float)
    if p.shape != (x.size, y.size) or h.shape != p.shape:
        raise InputError(f"EHL point fields must have shape (x, y) = ({x.size}, {y.size}); got p {p.shape}, h {h.shape}")
    if b_y is None:
        if scene is None:
            raise InputError("EHL point result without a scene: give the transverse half-width b_y [m]")
        b_y = scene.hertz.b
    Yc, dY = slice_positions(slices, rule)
    out = []
    for yy, w in zip(Yc, dY, strict=True):
        yv = yy * b_y
        if yv > y.max() + 1e-15 or yv < max(y.min(), 0.0) - 1e-15:
            raise InputError(f"EHL point field does not cover slice y = {yv:.4g} m (y in [{y.min():.4g}, {y.max():.4g}])")
        k = int(np.clip(np.searchsorted(y, yv) - 1, 0, y.size - 2))
        t = (yv - y[k]) / (y[k + 1] - y[k])
        ps = (1 - t) * p[:, k] + t * p[:, k + 1]
        hs = (1 - t) * h[:, k] + t * h[:, k + 1]
        out.append(
            profile_from_arrays(
                x, ps, hs, b=b, nx=nx, width=2.0 * b_y * w, x_in=x_in, x_out=x_out, Y=float(yy),
                contact_half=math.sqrt(max(1.0 - yy * yy, 0.0)), source="ehl", viscosity=viscosity,
            )
        )
    return out
