"""Figures of a transient run: films over time, snapshots, and an animation."""

from __future__ import annotations

import textwrap
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from ..model.atomic import atomic_path, atomic_savefig
from .result import TransientResult


def plot_series(res: TransientResult, path: str | Path) -> Path:
    """Hc(T), Hm(T) and the pressure fluctuation against time."""
    return series_figure(res, path, "Hc (X = 0)", res.steady.Hc_venner, "H (Venner)", "T = t u_m / b")


def series_figure(res: TransientResult, path: str | Path, hc_label: str, hc_steady: float,
                  film_label: str, time_label: str) -> Path:
    """Hc(T), Hm(T) with the smooth steady ``hc_steady`` (top) and the pressure fluctuation
    and the largest pressure (bottom) against time, written to ``path``."""
    fig = Figure(figsize=(7, 5), layout="constrained")
    ax = fig.subplots(2, 1, sharex=True)
    ax[0].plot(res.T, res.Hc, label=hc_label)
    ax[0].plot(res.T, res.Hm, label="Hm")
    ax[0].axhline(hc_steady, color="k", ls=":", lw=0.8, label="smooth steady Hc")
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


def plot_snapshots(res: TransientResult, path: str | Path, count: int = 6) -> Path:
    """Film and pressure at up to ``count`` kept steps spread over the run."""
    pick = spread_steps(res, count)
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


def animate(res: TransientResult, path: str | Path, fps: int = 15) -> Path:
    """GIF of H and P over the kept steps (matplotlib's Pillow writer)."""
    steps = sorted(res.snapshots)
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

    return save_animation(fig, frame, steps, path, fps)


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
