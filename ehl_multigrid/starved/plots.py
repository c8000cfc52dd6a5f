"""Plot of a starved line-contact solution: pressure, film and film content ``theta`` (the
starved inlet ahead of the meniscus included)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from ..multigrid.result import EHLResult


def plot_starved(sol: EHLResult, path: str | Path, title: str = "") -> Path:
    """Write ``<path>_PHtheta.png``: ``P`` and ``H/Hc`` (left axis) and ``theta`` (right axis)
    against ``X = x/b``; return the path."""
    s = sol.scalars
    X, P, H, theta = sol.X, sol.P, sol.H, sol.extra["theta"]
    up = sol.extra.get("upstream")
    Hc = s["Hc_venner"]
    fig = Figure(figsize=(6.8, 4.0), layout="constrained")
    ax = fig.subplots()
    ax.plot(X, P, "C0", lw=1.2, label="P = p/pmax")
    ax.plot(X, H / Hc, "C3", lw=1.2, label="H/Hc")
    ax.set_ylim(0.0, 2.5)
    ax.set_xlabel("X = x/b")
    ax2 = ax.twinx()
    ax2.plot(X, theta, "C2", lw=1.2, label="theta")
    if up is not None:
        ax.plot(up["X"], up["H"] / Hc, "C3", lw=1.2)
        ax2.plot(up["X"], up["theta"], "C2", lw=1.2)
        ax.axvline(s["meniscus_x"], color="grey", lw=0.6, ls=":")
    ax2.set_ylim(0.0, 1.05)
    ax2.set_ylabel("theta (film content)", color="C2")
    lo = max(float(np.min(X)) - 1.0, -3.0) if up is not None else max(float(np.min(X)), -3.0)
    ax.set_xlim(lo, float(np.max(X)))
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=8, loc="upper left")
    where = "flooded inlet" if s.get("inlet_flooded", False) else f"meniscus X = {s['meniscus_x']:.3f}"
    ax.set_title(f"{title or 'starved line contact'}: Hc/Hc_ff = {s['Hc_ratio']:.3f}, {where}", fontsize=9)
    out = Path(path)
    out = out.with_name(f"{out.name}_PHtheta.png")
    fig.savefig(out, dpi=100)
    return out
