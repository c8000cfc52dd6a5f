"""Plots of starved solutions: pressure, film and film content ``theta`` of a line contact
(the starved inlet ahead of the meniscus included) and of a point contact (centre line and
the ``theta`` map)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from ..model.atomic import atomic_savefig
from ..multigrid.result import EHLResult


def _centre_line(ax: Any, X: np.ndarray, P: np.ndarray, H_rel: np.ndarray, theta: np.ndarray,
                 xlabel: str) -> Any:
    """``P`` and ``H/Hc`` on ``ax`` and ``theta`` on its twin axis (returned)."""
    ax.plot(X, P, "C0", lw=1.2, label="P = p/pmax")
    ax.plot(X, H_rel, "C3", lw=1.2, label="H/Hc")
    ax.set_ylim(0.0, 2.5)
    ax.set_xlabel(xlabel)
    ax2 = ax.twinx()
    ax2.plot(X, theta, "C2", lw=1.2, label="theta")
    ax2.set_ylim(0.0, 1.05)
    ax2.set_ylabel("theta (film content)", color="C2")
    return ax2


def _legend_and_save(fig: Figure, ax: Any, ax2: Any, path: str | Path) -> Path:
    """One legend for both axes; the figure written to ``<path>_PHtheta.png``."""
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=8, loc="upper left")
    out = Path(path)
    out = out.with_name(f"{out.name}_PHtheta.png")
    atomic_savefig(fig, out, dpi=100)
    return out


def plot_starved(sol: EHLResult, path: str | Path, title: str = "") -> Path:
    """Write ``<path>_PHtheta.png``: ``P`` and ``H/Hc`` (left axis) and ``theta`` (right axis)
    against ``X = x/b``; return the path."""
    s = sol.scalars
    X, up, Hc = sol.X, sol.extra.get("upstream"), s["Hc_venner"]
    fig = Figure(figsize=(6.8, 4.0), layout="constrained")
    ax = fig.subplots()
    ax2 = _centre_line(ax, X, sol.P, sol.H / Hc, sol.extra["theta"], "X = x/b")
    if up is not None:
        ax.plot(up["X"], up["H"] / Hc, "C3", lw=1.2)
        ax2.plot(up["X"], up["theta"], "C2", lw=1.2)
        ax.axvline(s["meniscus_x"], color="grey", lw=0.6, ls=":")
    lo = max(float(np.min(X)) - 1.0, -3.0) if up is not None else max(float(np.min(X)), -3.0)
    ax.set_xlim(lo, float(np.max(X)))
    where = "flooded inlet" if s.get("inlet_flooded", False) else f"meniscus X = {s['meniscus_x']:.3f}"
    ax.set_title(f"{title or 'starved line contact'}: Hc/Hc_ff = {s['Hc_ratio']:.3f}, {where}", fontsize=9)
    return _legend_and_save(fig, ax, ax2, path)


def plot_starved_point(sol: EHLResult, path: str | Path, title: str = "") -> Path:
    """Write ``<path>_PHtheta.png`` for a starved point contact: ``P``, ``H/Hc`` and
    ``theta`` along the centre line (left) and the film content ``theta`` over the contact
    (right, the meniscus is where it reaches 1); return the path."""
    s = sol.scalars
    X, Y, P, theta = sol.X, sol.Y, sol.P, sol.extra["theta"]
    row = 0 if sol.half else (len(Y) - 1) // 2
    fig = Figure(figsize=(11.0, 4.0), layout="constrained")
    ax, axm = fig.subplots(1, 2)
    ax2 = _centre_line(ax, X, P[row], sol.H[row] / s["Hc_venner"], theta[row], "X = x/a (Y = 0)")
    ax.axvline(s["meniscus_x"], color="grey", lw=0.6, ls=":")
    if sol.half:  # mirror the half domain for the map
        Yf = np.concatenate([-Y[:0:-1], Y])
        Tf = np.concatenate([theta[:0:-1], theta])
        Pf = np.concatenate([P[:0:-1], P])
    else:
        Yf, Tf, Pf = Y, theta, P
    im = axm.pcolormesh(X, Yf, Tf, shading="auto", cmap="viridis", vmin=0.0, vmax=1.0)
    axm.contour(X, Yf, Pf, levels=[0.05, 0.5], colors="w", linewidths=0.6)
    axm.set_aspect("equal")
    axm.set_xlabel("X = x/a")
    axm.set_ylabel("Y = y/a")
    fig.colorbar(im, ax=axm, label="theta (white: P = 0.05, 0.5)")
    ratio = s.get("Hc_ratio")
    head = f"Hc/Hc_ff = {ratio:.3f}, " if ratio is not None else ""
    fig.suptitle(f"{title or 'starved point contact'}: {head}meniscus X = {s['meniscus_x']:.3f}",
                 fontsize=9)
    return _legend_and_save(fig, ax, ax2, path)
