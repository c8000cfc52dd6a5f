"""PNG plots of a line-contact solution: pressure and film over the whole domain, and a zoom on
the contact that shows the pressure spike and the outlet constriction.

With a physical scale (a scene) the axes are x in mm (or um), p in GPa and h in nm, and the
title quotes hc and hm in nm; without one (Moes-only) X = x/b, P = p/pmax and H in Moes's
scaling, the scaling of the title's Hc and Hm."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from ..line.solution import LineSolution
from ..model.atomic import atomic_savefig


def line_scales(sol: LineSolution) -> dict:
    """Plotted arrays, labels and title values of ``sol`` (physical or Moes-scaled)."""
    s = sol.scalars
    pb = sol.problem
    X, P, H = np.asarray(sol.X), np.asarray(sol.P), np.asarray(sol.H)
    if getattr(pb, "physical", False):
        span = float(np.abs(X).max() * pb.b)
        unit, per_m = ("mm", 1e3) if span >= 1e-3 else ("um", 1e6)
        h_nm = H * pb.b**2 / pb.R * 1e9
        return {"x": X * pb.b * per_m, "p": P * pb.pmax / 1e9, "h": h_nm, "xlabel": f"x [{unit}]",
                "plabel": "p [GPa]", "hlabel": "h [nm]", "x_per_X": pb.b * per_m,
                "hc": float(s["hc"]) * 1e9, "hm": float(s["hm"]) * 1e9, "units": "nm",
                "h_per_H": pb.b**2 / pb.R * 1e9}
    moes = float(s["Hc"]) / float(s["Hc_venner"])  # H (Moes) per H (Venner)
    return {"x": X, "p": P, "h": H * moes, "xlabel": "X = x/b", "plabel": "P = p/pmax", "hlabel": "H (Moes)",
            "x_per_X": 1.0, "hc": float(s["Hc"]), "hm": float(s["Hm"]), "units": "(Moes)", "h_per_H": moes}


def plot_solution(sol: LineSolution, path: str | Path, title: str = "") -> list[Path]:
    """Write ``<path>_PH.png`` (whole domain) and ``<path>_zoom.png``; return both paths."""
    path = Path(path)
    out = []
    s = sol.scalars
    sc = line_scales(sol)
    label = title or f"M = {s['M']:.4g}, L = {s['L']:.4g}"
    films = (f"hc = {sc['hc']:.4g} nm, hm = {sc['hm']:.4g} nm" if sc["units"] == "nm"
             else f"Hc = {sc['hc']:.4g}, Hm = {sc['hm']:.4g} (Moes)")
    for suffix, lim in (("PH", None), ("zoom", (-1.3, 1.3))):
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
        if lim is not None:
            ax.set_xlim(lim[0] * sc["x_per_X"], lim[1] * sc["x_per_X"])
            inside = (sol.X >= lim[0]) & (sol.X <= lim[1])
            hmax = float(np.max(sc["h"][inside]))
            ax2.set_ylim(0.0, min(hmax, 4.0 * s["Hc_venner"] * sc["h_per_H"]))
            ax2.axhline(sc["hm"], color="C3", ls=":", lw=0.8)
            ax2.plot([s["X_Hm"] * sc["x_per_X"]], [sc["hm"]], "v", color="C3")
        ax.set_title(f"{label}: {films}, {'converged' if s['converged'] else 'NOT converged'}", fontsize=9)
        p = path.with_name(f"{path.name}_{suffix}.png")
        atomic_savefig(fig, p, dpi=100)
        out.append(p)
    return out
