"""PNG figures of a solved film, line or point (dpi 100), built with
``matplotlib.figure.Figure`` (no pyplot), so plotting never changes the process-wide backend.

* line contact: pressure and film over the whole domain, and a zoom on the contact that shows
  the pressure spike and the outlet constriction (``<stem>_PH.png``, ``<stem>_zoom.png``);
* point contact: pressure and film maps, centre-line profiles in x and y, and an
  interference-style film map (``<stem>_maps.png``, ``<stem>_profiles.png``,
  ``<stem>_interference.png``).

What a tribologist reads: with a physical scale (a scene) the axes show the film in nm, the
pressure in GPa and the plane in mm (or um), and the title quotes hc and hm in nm; without one
(Moes-only) they show X = x/b (x/a), P = p/pmax and H in Moes's scaling, the scaling of the
title's Hc and Hm. The maps keep the plane's true proportions (equal axes) unless the domain is
more than :data:`MAX_TRUE_ASPECT` times longer one way than the other (slender ellipses); then
each panel gets a readable shape and its title says by how much the axes are stretched.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.figure import Figure

from ..model.atomic import atomic_savefig
from ..model.results import Result

if TYPE_CHECKING:  # the line solver's package: not loaded to draw a point contact
    from ..line.solution import LineSolution

#: Largest height/width (or width/height) of the plotted plane drawn with equal axes.
MAX_TRUE_ASPECT = 3.0
#: Most points per axis a map draws: a map panel is about 340 pixels wide at the figures' dpi
#: (docs/performance.md: what the figures cost)
MAP_POINTS = 257


# -- shared by both geometries -------------------------------------------------------------------
def length_unit(span: float) -> tuple[str, float]:
    """``(unit, per_m)`` of a plane whose largest coordinate is ``span`` metres: mm, or um
    below a millimetre."""
    return ("mm", 1e3) if span >= 1e-3 else ("um", 1e6)


def moes_per_venner(s: dict[str, Any]) -> float:
    """H (Moes) per H (Venner) of a result's scalars ``s``."""
    return float(s["Hc"]) / float(s["Hc_venner"])


def film_text(hc: float, hm: float, physical: bool) -> str:
    """The central and minimum film of a title, in nm or in Moes's scaling."""
    return f"hc = {hc:.4g} nm, hm = {hm:.4g} nm" if physical else f"Hc = {hc:.4g}, Hm = {hm:.4g} (Moes)"


def save_figures(folder: str | Path, stem: str, makers: Sequence[tuple[str, Callable[[], Figure]]]) -> list[Path]:
    """Build and write each figure ``make()`` as ``<folder>/<stem>_<suffix>.png``, one at a time;
    return the paths."""
    files = []
    for suffix, make in makers:
        f = Path(folder) / f"{stem}_{suffix}.png"
        atomic_savefig(make(), f, dpi=100)
        files.append(f)
    return files


# -- line contact --------------------------------------------------------------------------------
def line_scales(sol: LineSolution) -> dict:
    """Plotted arrays, labels and title values of ``sol`` (physical or Moes-scaled)."""
    s = sol.scalars
    pb = sol.problem
    X, P, H = np.asarray(sol.X), np.asarray(sol.P), np.asarray(sol.H)
    if getattr(pb, "physical", False):
        unit, per_m = length_unit(float(np.abs(X).max() * pb.b))
        h_nm = H * pb.b**2 / pb.R * 1e9
        return {"x": X * pb.b * per_m, "p": P * pb.pmax / 1e9, "h": h_nm, "xlabel": f"x [{unit}]",
                "plabel": "p [GPa]", "hlabel": "h [nm]", "x_per_X": pb.b * per_m,
                "hc": float(s["hc"]) * 1e9, "hm": float(s["hm"]) * 1e9, "units": "nm",
                "h_per_H": pb.b**2 / pb.R * 1e9}
    moes = moes_per_venner(s)
    return {"x": X, "p": P, "h": H * moes, "xlabel": "X = x/b", "plabel": "P = p/pmax", "hlabel": "H (Moes)",
            "x_per_X": 1.0, "hc": float(s["Hc"]), "hm": float(s["Hm"]), "units": "(Moes)", "h_per_H": moes}


def line_figure(sol: LineSolution, sc: dict, label: str, zoom: tuple[float, float] | None) -> Figure:
    """Pressure and film of ``sol`` against x, over the whole domain or ``zoom`` (in X)."""
    s = sol.scalars
    fig = Figure(figsize=(6.4, 3.8))
    # fixed margins: a constrained layout costs 0.15-0.25 s per figure
    fig.subplots_adjust(left=0.11, right=0.88, bottom=0.13, top=0.91)
    ax = fig.subplots()
    ax.plot(sc["x"], sc["p"], "C0", lw=1.2, label="pressure")
    ax.set_xlabel(sc["xlabel"])
    ax.set_ylabel(sc["plabel"], color="C0")
    ax2 = ax.twinx()
    ax2.plot(sc["x"], sc["h"], "C3", lw=1.2, label="film")
    ax2.set_ylabel(sc["hlabel"], color="C3")
    if zoom is not None:
        ax.set_xlim(zoom[0] * sc["x_per_X"], zoom[1] * sc["x_per_X"])
        inside = (sol.X >= zoom[0]) & (sol.X <= zoom[1])
        hmax = float(np.max(sc["h"][inside]))
        ax2.set_ylim(0.0, min(hmax, 4.0 * s["Hc_venner"] * sc["h_per_H"]))
        ax2.axhline(sc["hm"], color="C3", ls=":", lw=0.8)
        ax2.plot([s["X_Hm"] * sc["x_per_X"]], [sc["hm"]], "v", color="C3")
    films = film_text(sc["hc"], sc["hm"], sc["units"] == "nm")
    ax.set_title(f"{label}: {films}, {'converged' if s['converged'] else 'NOT converged'}", fontsize=9)
    return fig


def plot_solution(sol: LineSolution, folder: str | Path, stem: str, title: str = "") -> list[Path]:
    """Write ``<stem>_PH.png`` (whole domain) and ``<stem>_zoom.png`` into ``folder``; return
    both paths."""
    sc = line_scales(sol)
    label = title or f"M = {sol.scalars['M']:.4g}, L = {sol.scalars['L']:.4g}"
    return save_figures(folder, stem, [(suffix, lambda zoom=zoom: line_figure(sol, sc, label, zoom))
                                       for suffix, zoom in (("PH", None), ("zoom", (-1.3, 1.3)))])


# -- point contact -------------------------------------------------------------------------------
def interference_rgb(h_m: np.ndarray, n_oil: float = 1.5, wavelengths=(650e-9, 532e-9, 450e-9)) -> np.ndarray:
    """Two-beam interference colours ``I = cos^2(2 pi n h / lambda)`` for red, green, blue."""
    rgb = [np.cos(2.0 * np.pi * n_oil * h_m / lam) ** 2 for lam in wavelengths]
    return np.clip(np.stack(rgb, axis=-1), 0.0, 1.0)


@dataclass
class MapScales:
    """The quantities the plots draw, in the units their labels and titles state."""

    x: np.ndarray  # along the rolling direction (axis 0 of the fields)
    y: np.ndarray
    p: np.ndarray  # [j, i] (rows y, columns x) for contour plots
    h: np.ndarray
    xlabel: str
    ylabel: str
    plabel: str
    hlabel: str
    hc: float  # central and minimum film in the units of hlabel
    hm: float
    x_hm: float  # where the minimum film is, in plane units
    y_hm: float
    physical: bool
    title: str
    length_unit: float  # metres per plane unit (nan for X = x/a)


def map_scales(res: Result, name: str = "") -> MapScales:
    """Units of the plots of ``res``: physical (nm, GPa, mm or um) when the result carries
    ``p``, ``h``, ``x``, ``y``; Moes-scaled otherwise."""
    s = res.scalars
    X, Y = np.asarray(res["X"]), np.asarray(res["Y"])
    physical = {"p", "h"} <= set(res.fields) and {"x", "y"} <= set(res.coords)
    prefix = name + ": " if name else ""
    if physical:
        x_m, y_m = np.asarray(res["x"]), np.asarray(res["y"])
        a = (x_m[-1] - x_m[0]) / (X[-1] - X[0])  # metres per X unit (the Hertz half-width a)
        unit, per_m = length_unit(max(np.abs(x_m).max(), np.abs(y_m).max()))
        h_nm = np.asarray(res["h"]).T * 1e9
        hc, hm = float(s["hc"]) * 1e9, float(s["hm"]) * 1e9
        pmax = float(s.get("pmax", np.nan))
        title = (f"{prefix}{film_text(hc, hm, True)}"
                 + (f", pmax = {pmax / 1e9:.3g} GPa" if math.isfinite(pmax) else ""))
        return MapScales(x_m * per_m, y_m * per_m, np.asarray(res["p"]).T / 1e9, h_nm,
                         f"x [{unit}]", f"y [{unit}]", "p [GPa]", "h [nm]", hc, hm,
                         float(s["X_Hm"]) * a * per_m, float(s["Y_Hm"]) * a * per_m, True, title, 1.0 / per_m)
    title = (f"{prefix}M = {s['M']:.4g}, L = {s['L']:.4g}, theta = {s['theta']:.3g}; "
             f"{film_text(s['Hc'], s['Hm'], False)}")
    return MapScales(X, Y, np.asarray(res["P"]).T, np.asarray(res["H"]).T * moes_per_venner(s),
                     "X = x/a", "Y = y/a", "P = p/pmax", "H (Moes)", float(s["Hc"]), float(s["Hm"]),
                     float(s["X_Hm"]), float(s["Y_Hm"]), False, title, math.nan)


def thinned(sc: MapScales, most: int = MAP_POINTS) -> MapScales:
    """``sc`` with its maps at every k-th point along each axis (the last point kept), at most
    ``most`` per axis; the scalars and titles unchanged."""

    def index(n: int) -> np.ndarray:
        step = max(1, math.ceil((n - 1) / (most - 1)))
        return np.unique(np.r_[np.arange(0, n, step), n - 1])

    ix, iy = index(sc.x.size), index(sc.y.size)
    return replace(sc, x=sc.x[ix], y=sc.y[iy], p=sc.p[np.ix_(iy, ix)], h=sc.h[np.ix_(iy, ix)])


def plane_aspect(x: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """``(box_aspect, stretch)`` of a map panel: the plane's height/width when within
    :data:`MAX_TRUE_ASPECT` (``stretch`` 1: equal axes), else clipped to it, with ``stretch``
    the factor by which the y axis is drawn longer (> 1) or shorter than true."""
    true = float((y[-1] - y[0]) / (x[-1] - x[0]))
    box = min(max(true, 1.0 / MAX_TRUE_ASPECT), MAX_TRUE_ASPECT)
    return box, box / true


def _stretch_note(stretch: float) -> str:
    if math.isclose(stretch, 1.0):
        return ""
    return f" (y drawn x{stretch:.3g}: not to scale)" if stretch > 1 else f" (y drawn x{stretch:.2g}: not to scale)"


def _plane_axes(ax, sc: MapScales, box: float, stretch: float) -> None:
    ax.set_xlabel(sc.xlabel)
    ax.set_ylabel(sc.ylabel)
    if math.isclose(stretch, 1.0):
        ax.set_aspect("equal")
    else:
        ax.set_box_aspect(box)


def maps_figure(res: Result, name: str = "") -> Figure:
    """Pressure and film maps of ``res`` (see the module docstring for units and aspect)."""
    sc = thinned(map_scales(res, name))
    box, stretch = plane_aspect(sc.x, sc.y)
    tall = box > 1.0
    # two panels side by side, each about 3.4 in wide once the colour bars have their room
    height = 3.4 * max(box, 0.55) + 1.0
    fig = Figure(figsize=(10.0, height))
    # fixed margins: a constrained layout costs 0.25 s per figure
    fig.subplots_adjust(left=0.07, right=0.93, bottom=0.5 / height, top=1.0 - 0.75 / height, wspace=0.35)
    ax = fig.subplots(1, 2)
    c0 = ax[0].contourf(sc.x, sc.y, sc.p, levels=30, cmap="viridis")
    fig.colorbar(c0, ax=ax[0], label=sc.plabel, shrink=0.9 if tall else 1.0)
    ax[0].set_title("pressure" + _stretch_note(stretch), fontsize=9)
    hmax = min(float(np.nanmax(sc.h)), 3.0 * sc.hc)
    c1 = ax[1].contourf(sc.x, sc.y, np.minimum(sc.h, hmax), levels=30, cmap="magma")
    fig.colorbar(c1, ax=ax[1], label=sc.hlabel + " (clipped at 3 hc)" if sc.physical else sc.hlabel + " (clipped at 3 Hc)")
    ax[1].plot([sc.x_hm], [sc.y_hm], "c+", ms=10, label="minimum film")
    ax[1].set_title("film" + _stretch_note(stretch), fontsize=9)
    ax[1].legend(loc="lower left", fontsize=7)
    for a in ax:
        _plane_axes(a, sc, box, stretch)
    fig.suptitle(sc.title, fontsize=10)
    return fig


def profiles_figure(res: Result, name: str = "") -> Figure:
    """Centre-line profiles: along the rolling direction at y = 0, across it at x = 0 and
    through the minimum film."""
    sc = map_scales(res, name)
    jc = int(np.argmin(np.abs(sc.y)))
    ic = int(np.argmin(np.abs(sc.x)))
    i0 = int(np.argmin(np.abs(sc.x - sc.x_hm))) if np.isfinite(sc.x_hm) else ic
    fig = Figure(figsize=(10, 4))
    fig.subplots_adjust(left=0.07, right=0.93, bottom=0.12, top=0.84, wspace=0.42)
    ax = fig.subplots(1, 2)
    ax[0].plot(sc.x, sc.p[jc], label="pressure")
    ax2 = ax[0].twinx()
    ax2.plot(sc.x, sc.h[jc], "r-", label="film")
    ax2.set_ylim(0, 3.0 * sc.hc)
    ax[0].set_xlabel(sc.xlabel)
    ax[0].set_ylabel(sc.plabel)
    ax2.set_ylabel(sc.hlabel, color="r")
    ax[0].set_title("centre line y = 0", fontsize=9)
    ax[1].plot(sc.y, sc.p[:, ic], label="pressure at x = 0")
    ax[1].plot(sc.y, sc.p[:, i0], "--", label=f"pressure at x = {sc.x[i0]:.3g} (minimum film)")
    ax3 = ax[1].twinx()
    ax3.plot(sc.y, sc.h[:, ic], "r-")
    ax3.plot(sc.y, sc.h[:, i0], "r--")
    ax3.set_ylim(0, 3.0 * sc.hc)
    ax3.set_ylabel(sc.hlabel, color="r")
    ax[1].set_xlabel(sc.ylabel)
    ax[1].set_ylabel(sc.plabel)
    ax[1].legend(fontsize=7)
    ax[1].set_title("across the contact", fontsize=9)
    fig.suptitle(sc.title, fontsize=10)
    return fig


def interference_figure(res: Result, name: str = "") -> Figure:
    """Interference-style film map (white light through oil of index 1.5 on the film in m; a
    Moes-only result, having no physical scale, is drawn with 1 Moes unit = 1 um)."""
    # twice the maps' points: the fringes are finer than the contours (an image costs little)
    sc = thinned(map_scales(res, name), 2 * MAP_POINTS - 1)
    h_m = sc.h * 1e-9 if sc.physical else sc.h * 1e-6
    box, stretch = plane_aspect(sc.x, sc.y)
    height = 5.5 * min(max(box, 0.5), 1.6) + 0.6
    fig = Figure(figsize=(5.5, height))
    fig.subplots_adjust(left=0.13, right=0.96, bottom=0.55 / height, top=1.0 - 0.7 / height)
    ax = fig.subplots()
    ax.imshow(interference_rgb(np.maximum(h_m, 0.0)), origin="lower",
              extent=(sc.x[0], sc.x[-1], sc.y[0], sc.y[-1]), interpolation="bilinear", aspect="auto")
    _plane_axes(ax, sc, box, stretch)
    scale = "film in nm" if sc.physical else "H (Moes) x 1 um: no physical scale"
    ax.set_title(f"interference-style film map ({scale}){_stretch_note(stretch)}", fontsize=8)
    fig.suptitle(sc.title, fontsize=9)
    return fig


def plot_result(res: Result, outdir: str | Path, name: str) -> list[Path]:
    """Write ``<name>_maps.png``, ``<name>_profiles.png``, ``<name>_interference.png``."""
    Path(outdir).mkdir(parents=True, exist_ok=True)
    label = res.scene.name if res.scene is not None else ""
    return save_figures(outdir, name, [(suffix, lambda make=make: make(res, label)) for suffix, make in (
        ("maps", maps_figure), ("profiles", profiles_figure), ("interference", interference_figure))])


# -- the figures of a contact --------------------------------------------------------------------
def film_figures(kind: str, raw: Any, res: Result, folder: Path, stem: str, title: str) -> list[Path]:
    """The figures of a solved film in ``folder``, named after ``stem``: a line contact's
    (``kind`` ``"line"``) from the solver's result ``raw``, titled ``title``; a point or elliptic
    contact's from the HDF5 result ``res``, titled by its scene."""
    if kind == "line":
        return plot_solution(raw, folder, stem, title)
    return plot_result(res, folder, stem)


def starved_figure(kind: str, raw: Any, folder: Path, stem: str, title: str) -> Path:
    """The film content ``theta`` of a starved solve ``raw``: ``<folder>/<stem>_PHtheta.png``."""
    from ..starved.plots import plot_starved, plot_starved_point

    plot = plot_starved if kind == "line" else plot_starved_point
    return Path(plot(raw, folder / stem, title))
