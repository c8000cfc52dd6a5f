"""Figures of a transient point-contact run: films over time, centre-line snapshots, film
maps, and an animation of the film map."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from ..model.atomic import atomic_savefig
from .plots import mark_incomplete, save_animation, series_figure, spread_steps
from .point_solve import PointTransientResult


def _centre_row(res: PointTransientResult) -> int:
    return int(np.argmin(np.abs(res.Y - res.yf)))


def plot_point_series(res: PointTransientResult, path: str | Path) -> Path:
    """Hc(T), Hm(T) and the pressure fluctuation against time."""
    return series_figure(res, path, "Hc (X = Y = 0)", res.Hc_steady, "H = h Rx / a^2", "T = t u_m / a")


def _film_map(ax: Any, res: PointTransientResult, snap: dict[str, np.ndarray], hi: float,
              xmin: float) -> Any:
    """Film map ``0 .. hi`` with pressure contours on ``X in [xmin, 1.5]``, ``|Y| <= 1.5``."""
    im = ax.pcolormesh(res.X, res.Y, snap["H"], vmin=0, vmax=hi, shading="auto", cmap="viridis")
    ax.contour(res.X, res.Y, snap["P"], levels=[0.2, 0.5, 0.8], colors="w", linewidths=0.5)
    ax.set_xlim(xmin, 1.5)
    ax.set_ylim(-1.5, 1.5)
    ax.set_aspect("equal")
    return im


def plot_point_snapshots(res: PointTransientResult, path: str | Path, count: int = 4) -> Path:
    """Film maps at up to ``count`` kept steps (top) and the film and pressure on the row
    through the feature (bottom)."""
    pick = spread_steps(res, count)
    fig = Figure(figsize=(3 * len(pick), 7), layout="constrained")
    axes = fig.subplots(2, len(pick), squeeze=False)
    j = _centre_row(res)
    hi = 2.5 * res.Hc_steady
    for k, n in enumerate(pick):
        s = res.snapshots[n]
        ax = axes[0, k]
        im = _film_map(ax, res, s, hi, -1.8)
        ax.set_title(f"H, T = {res.T[n]:.3g}", fontsize=9)
        ax2 = axes[1, k]
        ax2.plot(res.X, s["H"][j], label="H")
        ax2.plot(res.X, res.steady.H[j], "k:", lw=0.8, label="smooth H")
        ax2.set_ylim(0, hi)
        ax2.set_xlim(-1.8, 1.5)
        ax3 = ax2.twinx()
        ax3.plot(res.X, s["P"][j], "r", lw=0.8)
        ax3.set_ylim(0, 1.5 * max(float(np.max(res.Pmax)), 1.0))
        ax2.set_xlabel("X = x / a")
    fig.colorbar(im, ax=axes[0, -1])
    axes[1, 0].legend(fontsize=7)
    mark_incomplete(fig, res)
    return atomic_savefig(fig, path, dpi=100)


def animate_point(res: PointTransientResult, path: str | Path, fps: int = 12) -> Path:
    """GIF of the film map with pressure contours over the kept steps (Pillow writer)."""
    steps = sorted(res.snapshots)
    fig = Figure(figsize=(5, 4.5))
    ax = fig.subplots()
    hi = 2.5 * res.Hc_steady

    def frame(n: int):
        ax.clear()
        _film_map(ax, res, res.snapshots[n], hi, -2.0)
        ax.set_title(f"H (0 .. {hi:.3g}), T = {res.T[n]:.3f}", fontsize=9)
        return []

    return save_animation(fig, frame, steps, path, fps)
