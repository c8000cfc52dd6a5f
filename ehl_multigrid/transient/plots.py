"""Figures of a transient run of either contact: films over time, snapshots (line: film and
pressure profiles; point: film maps and the row through the feature), and an animation."""

from __future__ import annotations

import textwrap
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from ..model.atomic import atomic_path, atomic_savefig
from .result import TransientResult

#: per contact: the label of Hc, the film unit and the time unit of the series figure
SERIES_LABELS = {False: ("Hc (X = 0)", "H (Venner)", "T = t u_m / b"),
                 True: ("Hc (X = Y = 0)", "H = h Rx / a^2", "T = t u_m / a")}


def is_point(res: TransientResult) -> bool:
    """Whether ``res`` is a point-contact run (its fields are maps on ``(Y, X)``)."""
    return getattr(res, "Y", None) is not None


def plot_series(res: TransientResult, path: str | Path) -> Path:
    """Hc(T), Hm(T) with the smooth steady Hc (top) and the pressure fluctuation and the
    largest pressure (bottom) against time, written to ``path``."""
    hc_label, film_label, time_label = SERIES_LABELS[is_point(res)]
    fig = Figure(figsize=(7, 5), layout="constrained")
    ax = fig.subplots(2, 1, sharex=True)
    ax[0].plot(res.T, res.Hc, label=hc_label)
    ax[0].plot(res.T, res.Hm, label="Hm")
    ax[0].axhline(res.steady_film("Hc"), color="k", ls=":", lw=0.8, label="smooth steady Hc")
    ax[0].set_ylabel(film_label)
    ax[0].legend(fontsize=8)
    ax[1].plot(res.T, res.dP, label="max |P - P_smooth|")
    ax[1].plot(res.T, res.Pmax, label="max P")
    ax[1].set_xlabel(time_label)
    ax[1].legend(fontsize=8)
    mark_incomplete(fig, res)
    return atomic_savefig(fig, path, dpi=110)


def mark_incomplete(fig: Figure, res: TransientResult) -> None:
    """A red title on a figure of a run that ended before its last step, saying why."""
    if not res.complete:
        text = f"INCOMPLETE: {res.steps} of {res.planned_steps} steps: {res.stop_reason.split(';')[0]}"
        fig.suptitle("\n".join(textwrap.wrap(text, 110, max_lines=2)), color="C3", fontsize=8)


def plot_snapshots(res: TransientResult, path: str | Path, count: int | None = None) -> Path:
    """Film and pressure at up to ``count`` kept steps spread over the run (default 6 line
    profiles, 4 point film maps)."""
    if is_point(res):
        return _plot_point_snapshots(res, path, 4 if count is None else count)
    pick = spread_steps(res, 6 if count is None else count)
    fig = Figure(figsize=(7, 6), layout="constrained")
    ax = fig.subplots(2, 1, sharex=True)
    T = res.T
    for n in pick:
        s = res.snapshots[n]
        ax[0].plot(res.X, s["H"], lw=1, label=f"T = {T[n]:.3g}")
        ax[1].plot(res.X, s["P"], lw=1)
    ax[0].plot(res.X, res.steady.H, "k:", lw=1, label="smooth")
    ax[0].set_ylim(0, 4 * res.steady.Hc_venner)
    ax[0].set_ylabel("H")
    ax[0].legend(fontsize=7, ncol=2)
    ax[1].set_ylabel("P")
    ax[1].set_xlabel("X = x / b")
    ax[1].set_xlim(max(res.X[0], -2.5), res.X[-1])
    mark_incomplete(fig, res)
    return atomic_savefig(fig, path, dpi=110)


def animate(res: TransientResult, path: str | Path, fps: int | None = None) -> Path:
    """GIF over the kept steps (matplotlib's Pillow writer): H and P (line, 15 frames/s), the
    film map with pressure contours (point, 12 frames/s)."""
    steps = sorted(res.snapshots)
    if is_point(res):
        return _animate_point(res, path, steps, 12 if fps is None else fps)
    fig = Figure(figsize=(6, 5))
    ax = fig.subplots(2, 1, sharex=True)
    (lh,) = ax[0].plot(res.X, res.snapshots[steps[0]]["H"])
    (lp,) = ax[1].plot(res.X, res.snapshots[steps[0]]["P"])
    ax[0].plot(res.X, res.steady.H, "k:", lw=0.8)
    ax[0].set_ylim(0, 4 * res.steady.Hc_venner)
    ax[1].set_ylim(0, 1.2 * max(float(np.max(res.Pmax)), 1.0))
    ax[1].set_xlim(max(res.X[0], -2.5), res.X[-1])
    title = ax[0].set_title("")

    def frame(n: int):
        lh.set_ydata(res.snapshots[n]["H"])
        lp.set_ydata(res.snapshots[n]["P"])
        title.set_text(f"T = {res.T[n]:.3f}")
        return lh, lp, title

    return save_animation(fig, frame, steps, path, 15 if fps is None else fps)


def spread_steps(res: TransientResult, count: int) -> list[int]:
    """Up to ``count`` kept steps spread evenly over the run (first and last included)."""
    steps = sorted(res.snapshots)
    return [steps[int(i)] for i in np.linspace(0, len(steps) - 1, min(count, len(steps)))]


def save_animation(fig: Figure, frame: Callable[[int], Any], steps: list[int], path: str | Path,
                   fps: int) -> Path:
    """GIF of ``frame(step)`` over ``steps`` (matplotlib's Pillow writer)."""
    from matplotlib.animation import FuncAnimation, PillowWriter

    anim = FuncAnimation(fig, frame, frames=steps, blit=False)
    with atomic_path(path, keep_suffix=True) as tmp:  # Pillow picks the format by the suffix
        anim.save(str(tmp), writer=PillowWriter(fps=fps))
    return Path(path)


def _film_map(ax: Any, res: Any, snap: dict[str, np.ndarray], hi: float,
              xmin: float) -> Any:
    """Film map ``0 .. hi`` with pressure contours on ``X in [xmin, 1.5]``, ``|Y| <= 1.5``."""
    im = ax.pcolormesh(res.X, res.Y, snap["H"], vmin=0, vmax=hi, shading="auto", cmap="viridis")
    ax.contour(res.X, res.Y, snap["P"], levels=[0.2, 0.5, 0.8], colors="w", linewidths=0.5)
    ax.set_xlim(xmin, 1.5)
    ax.set_ylim(-1.5, 1.5)
    ax.set_aspect("equal")
    return im


def _plot_point_snapshots(res: Any, path: str | Path, count: int) -> Path:
    """Film maps at up to ``count`` kept steps (top) and the film and pressure on the row
    through the feature (bottom)."""
    pick = spread_steps(res, count)
    fig = Figure(figsize=(3 * len(pick), 7), layout="constrained")
    axes = fig.subplots(2, len(pick), squeeze=False)
    j = int(np.argmin(np.abs(res.Y - res.yf)))
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


def _animate_point(res: Any, path: str | Path, steps: list[int], fps: int) -> Path:
    """GIF of the film map with pressure contours over the kept ``steps`` (Pillow writer)."""
    fig = Figure(figsize=(5, 4.5))
    ax = fig.subplots()
    hi = 2.5 * res.Hc_steady

    def frame(n: int):
        ax.clear()
        _film_map(ax, res, res.snapshots[n], hi, -2.0)
        ax.set_title(f"H (0 .. {hi:.3g}), T = {res.T[n]:.3f}", fontsize=9)
        return []

    return save_animation(fig, frame, steps, path, fps)
