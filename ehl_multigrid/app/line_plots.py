"""PNG plots of a line-contact solution: P and H over the whole domain, and a zoom on the
contact that shows the pressure spike and the outlet constriction."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from ..line.solution import LineSolution


def plot_solution(sol: LineSolution, path: str | Path, title: str = "") -> list[Path]:
    """Write ``<path>_PH.png`` (whole domain) and ``<path>_zoom.png``; return both paths."""
    path = Path(path)
    out = []
    s = sol.scalars
    label = title or f"M = {s['M']:.4g}, L = {s['L']:.4g}"
    for suffix, lim in (("PH", None), ("zoom", (-1.3, 1.3))):
        fig = Figure(figsize=(6.4, 3.8))
        ax = fig.subplots()
        ax.plot(sol.X, sol.P, "C0", lw=1.2, label="P = p/pmax")
        ax.set_xlabel("X = x/b")
        ax.set_ylabel("P", color="C0")
        ax2 = ax.twinx()
        ax2.plot(sol.X, sol.H, "C3", lw=1.2, label="H = h R/b²")
        ax2.set_ylabel("H (Venner)", color="C3")
        if lim is not None:
            ax.set_xlim(*lim)
            inside = (sol.X >= lim[0]) & (sol.X <= lim[1])
            hmax = float(np.max(sol.H[inside]))
            ax2.set_ylim(0.0, min(hmax, 4.0 * s["Hc_venner"]))
            ax2.axhline(s["Hm_venner"], color="C3", ls=":", lw=0.8)
            ax2.plot([s["X_Hm"]], [s["Hm_venner"]], "v", color="C3")
        ax.set_title(f"{label}: Hc = {s['Hc']:.4g}, Hm = {s['Hm']:.4g} (Moes), "
                     f"{'converged' if s['converged'] else 'NOT converged'}", fontsize=9)
        fig.tight_layout()
        p = path.with_name(f"{path.name}_{suffix}.png")
        fig.savefig(p, dpi=100)
        out.append(p)
    return out
