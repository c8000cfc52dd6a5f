"""Figures of a transient point-contact run: films over time, centre-line snapshots, film
maps, and an animation of the film map."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from .point_solve import PointTransientResult


def _centre_row(res: PointTransientResult) -> int:
    return int(np.argmin(np.abs(res.Y - res.yf)))


def plot_point_series(res: PointTransientResult, path: str | Path) -> Path:
    """Hc(T), Hm(T) and the pressure fluctuation against time."""
    fig = Figure(figsize=(7, 5), layout="constrained")
    ax = fig.subplots(2, 1, sharex=True)
    ax[0].plot(res.T, res.Hc, label="Hc (X = Y = 0)")
    ax[0].plot(res.T, res.Hm, label="Hm")
    ax[0].axhline(res.Hc_steady, color="k", ls=":", lw=0.8, label="smooth steady Hc")
    ax[0].set_ylabel("H = h Rx / a^2")
    ax[0].legend(fontsize=8)
    ax[1].plot(res.T, res.dP, label="max |P - P_smooth|")
    ax[1].plot(res.T, res.Pmax, label="max P")
    ax[1].set_xlabel("T = t u_m / a")
    ax[1].legend(fontsize=8)
    fig.savefig(path, dpi=110)
    return Path(path)


def plot_point_snapshots(res: PointTransientResult, path: str | Path, count: int = 4) -> Path:
    """Film maps at up to ``count`` kept steps (top) and the film and pressure on the row
    through the feature (bottom)."""
    steps = sorted(res.snapshots)
    pick = [steps[int(i)] for i in np.linspace(0, len(steps) - 1, min(count, len(steps)))]
    fig = Figure(figsize=(3 * len(pick), 7), layout="constrained")
    axes = fig.subplots(2, len(pick), squeeze=False)
    j = _centre_row(res)
    hi = 2.5 * res.Hc_steady
    for k, n in enumerate(pick):
        s = res.snapshots[n]
        ax = axes[0, k]
        im = ax.pcolormesh(res.X, res.Y, s["H"], vmin=0, vmax=hi, shading="auto", cmap="viridis")
        ax.contour(res.X, res.Y, s["P"], levels=[0.2, 0.5, 0.8], colors="w", linewidths=0.5)
        ax.set_xlim(-1.8, 1.5)
        ax.set_ylim(-1.5, 1.5)
        ax.set_aspect("equal")
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
    fig.savefig(path, dpi=100)
    return Path(path)


def animate_point(res: PointTransientResult, path: str | Path, fps: int = 12) -> Path:
    """GIF of the film map with pressure contours over the kept steps (Pillow writer)."""
    from matplotlib.animation import FuncAnimation, PillowWriter

    steps = sorted(res.snapshots)
    fig = Figure(figsize=(5, 4.5))
    ax = fig.subplots()
    hi = 2.5 * res.Hc_steady

    def frame(n: int):
        ax.clear()
        s = res.snapshots[n]
        ax.pcolormesh(res.X, res.Y, s["H"], vmin=0, vmax=hi, shading="auto", cmap="viridis")
        ax.contour(res.X, res.Y, s["P"], levels=[0.2, 0.5, 0.8], colors="w", linewidths=0.5)
        ax.set_xlim(-2.0, 1.5)
        ax.set_ylim(-1.5, 1.5)
        ax.set_aspect("equal")
        ax.set_title(f"H (0 .. {hi:.3g}), T = {res.T[n]:.3f}", fontsize=9)
        return []

    anim = FuncAnimation(fig, frame, frames=steps, blit=False)
    anim.save(str(path), writer=PillowWriter(fps=fps))
    return Path(path)
