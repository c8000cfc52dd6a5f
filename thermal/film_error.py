"""The part of a friction coefficient's error that comes from the film it is computed on.

The traction stage computes the friction at the operating slip on the film stage's pressure and
film, fields of the solve's finest grid. Their discretisation error moves the friction: a diesel
fuel-pump roller (line, M 62, L 4.5) solved to the planner's 2 % on 1025 points gives 0.0110370,
and the same friction on the films of 2049-16385 points 0.0110197, 0.0110154, 0.0110141 (second
order): 2.3e-5 away, four times the error stated without this part. The part is measured, as the
films' own grid error is: the friction on the same box on the grids with half and a quarter of
the intervals, Richardson over the three (:func:`~ehl_multigrid.multigrid.accuracy.richardson`,
observed order capped at 2, first order where the sequence is irregular); a point contact takes
the grid with half the intervals alone, at first order (its coarse solves cost seconds).

A film of the isothermal flooded core and a starved line film are solved again on the coarser
grids. A coupled thermal film and a starved point film (whose coarse solves can cost more than
the film) are measured on the core's isothermal flooded films of the same contact, grid and
box: their relative change is applied to the friction. The thermal/isothermal film ratio
converges long before the films (docs/thermal.md, "Anchored point films"), so the grid
sensitivity is the isothermal film's; a starved film is flatter than the flooded one, so its
proxy overstates (a starved line measured both ways: 1.7e-4 by proxy, 3.7e-7 itself).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any

from ehl_multigrid.model.scene import Scene
from ehl_multigrid.model.solved_film import SolvedFilm
from ehl_multigrid.multigrid.accuracy import richardson

from .options import ThermalOptions
from .traction import solve_traction

#: coarsest grid (points along X) a film is solved on for this part
COARSEST_POINTS = 33


@dataclass(frozen=True)
class FilmPart:
    """The friction error from the film's grid (absolute, a coefficient; NaN when not
    measured), the frictions it was measured from (coarse to fine), how, and the wall time."""

    error: float
    frictions: tuple[float, ...]
    how: str
    wall_s: float = 0.0


def solved_again(film: SolvedFilm) -> bool:
    """Is ``film`` measured on coarser solves of its own physics: an isothermal flooded film, or
    a starved line film (its meniscus search is cheap); otherwise on the core's proxy films."""
    return not film.thermal and (not _starved(film) or film.contact == "line")


def _starved(film: SolvedFilm) -> bool:
    return film.Hc_ratio is not None or math.isfinite(film.scene.supply.hoil)


def _core_film(scene: Scene, film: SolvedFilm, points: int) -> SolvedFilm | None:
    """The film of ``scene`` on ``points`` along X, the physics of ``film`` where
    :func:`solved_again`, else the core's isothermal flooded film on ``film``'s box; None when
    that solve does not converge."""
    from ehl_multigrid import front
    from ehl_multigrid.solution import Status

    g = film.grid
    if solved_again(film) and _starved(film):  # a starved line: each grid its meniscus
        sol = front.solve(scene, physics="starved", accuracy=None, options={"points": points})
        return SolvedFilm.from_result(sol.to_result(), sol.grid) if sol.status is Status.CONVERGED else None
    opts: dict[str, Any] = {"points": points, "xmin": g.box[0], "xmax": g.box[1]}
    if film.contact != "line":
        opts.update(ymax=g.box[3], half=bool(g.half))
    flooded = scene.with_supply(hoil=math.inf) if math.isfinite(scene.supply.hoil) else scene
    sol = front.solve(flooded, physics="steady", accuracy=None, options=opts)
    if sol.status is not Status.CONVERGED:
        return None
    return SolvedFilm.from_result(sol.to_result(), sol.grid)


def film_friction_part(scene: Scene, film: SolvedFilm | None, options: ThermalOptions,
                       friction: float, **traction: Any) -> FilmPart:
    """The friction error from ``film``'s grid at ``scene.slip``: ``friction`` computed on
    ``film`` with ``options`` (the operating point's traction grid), ``traction`` the other
    keywords of :func:`~thermal.traction.solve_traction`. NaN where ``film`` carries no grid
    (a film not solved by a stage of this run) or its coarser grid does not converge.
    """
    t0 = time.perf_counter()
    if film is None or film.grid is None:
        return FilmPart(math.nan, (), "the film's grid is not known")
    n = int(film.grid.points)
    own = solved_again(film)
    # a point contact's coarse solves cost seconds (the default ball: 129 points 1.1 s, 257
    # points 2.7 s; an MTM-like ball at M 2780: 11 s each): the grid with half the intervals
    # alone, whose two-grid estimate is first order
    grids = [m for m in ((n - 1) // 4 + 1, (n - 1) // 2 + 1)[film.contact != "line":] if m >= COARSEST_POINTS]
    values: list[float] = []
    for m in grids:
        coarse = _core_film(scene, film, m)
        if coarse is None:
            values = []  # only a sequence of nested grids up to the film's own counts
            continue
        # (a starved scene's proxy films are of its flooded twin, which their friction is computed for)
        values.append(solve_traction(coarse.scene, scene.slip, options=options, **{**traction, "ehl": coarse}).coefficient)
    if not values:
        return FilmPart(math.nan, (), f"the core's film on {grids[-1] if grids else n} points did not converge",
                        time.perf_counter() - t0)
    if own:
        top, how = friction, "the film and the same solve on coarser grids"
    else:
        ref = _core_film(scene, film, n)
        if ref is None:
            return FilmPart(math.nan, (), f"the core's film on {n} points did not converge", time.perf_counter() - t0)
        top = solve_traction(ref.scene, scene.slip, options=options, **{**traction, "ehl": ref}).coefficient
        how = "the core's isothermal flooded films of the grid and box (a proxy for this film's grid)"
    seq = [*values, top]
    rich = richardson(seq, max_order=2.0)
    err = rich.error if own else rich.error / abs(top) * abs(friction) if top != 0.0 else math.inf
    return FilmPart(float(err), tuple(seq), f"{how}: {', '.join(f'{v:.6g}' for v in seq)}", time.perf_counter() - t0)
