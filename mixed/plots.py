"""PNG figures of Stribeck curves (as thesis Figs 4.4, 4.6, 4.7, 4.9-4.13, 5.9-5.10, 6.2-6.7).

Figures are built with ``matplotlib.figure.Figure`` (no pyplot), so plotting never changes
the process-wide backend; dpi <= 110.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from ehl_multigrid.model.atomic import atomic_savefig

DPI = 100
# figures keep fixed margins: a tight layout costs about 0.3 s per figure (docs/performance.md)


def _label(curve) -> str:
    h = curve.hoil
    if math.isinf(h):
        return "flooded"
    return f"hoil = {h / curve.sharing.roughness.Rq:.3g} Rq"


def plot_friction(curve, path: Path, title: str = "") -> Path:
    """Total friction with its asperity and film parts (Fig. 4.6); thermal: temperature rise."""
    fig = Figure(figsize=(6.4, 4.4))
    ax = fig.subplots()
    us = curve.us
    fr = curve.friction
    ax.semilogx(us, fr.coefficient, "k-", label="total")
    ax.semilogx(us, fr.asperity, "b--", label="asperity part fc Pa/P")
    ax.semilogx(us, fr.film, "r-.", label="film part")
    ax.set_xlabel("sum velocity us [m/s]")
    ax.set_ylabel("coefficient of friction [-]")
    ax.set_ylim(bottom=0.0)
    _shade_regimes(ax, curve)
    if fr.thermal and fr.mean_temperature_rise is not None:
        ax2 = ax.twinx()
        ax2.semilogx(us, fr.mean_temperature_rise, "g:", label="mean temperature rise")
        ax2.semilogx(us, fr.max_temperature_rise, "g--", lw=0.8, label="max temperature rise")
        ax2.set_ylabel("temperature rise [K]", color="g")
        ax2.legend(loc="center right", fontsize=8)
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title(title or f"{curve.scene.name}: Stribeck curve ({'thermal' if fr.thermal else 'isothermal'})", fontsize=9)
    fig.subplots_adjust(left=0.12, right=0.88, bottom=0.12, top=0.93)
    atomic_savefig(fig, path, dpi=DPI)
    return path


def _shade_regimes(ax, curve) -> None:
    t = curve.transitions
    lo, hi = t.get("us_bl_ml", math.nan), t.get("us_ml_ehl", math.nan)
    for x, name in ((lo, "BL|ML"), (hi, "ML|EHL")):
        if math.isfinite(x) and curve.us[0] <= x <= curve.us[-1]:
            ax.axvline(x, color="0.6", lw=0.8, ls=":")
            ax.text(x, ax.get_ylim()[1] * 0.98, name, fontsize=7, ha="center", va="top", color="0.4")


def plot_load_shares(curve, path: Path) -> Path:
    """Total, asperity and film loads against us (Fig. 4.7)."""
    fig = Figure(figsize=(6.4, 4.4))
    ax = fig.subplots()
    ls = curve.sharing
    ax.semilogx(ls.us, np.full_like(ls.us, ls.load), "k-", label="total load")
    ax.semilogx(ls.us, ls.Pa, "b--", label="asperity load Pa")
    ax.semilogx(ls.us, ls.Ph, "r-.", label="film load Ph")
    ax.set_xlabel("sum velocity us [m/s]")
    ax.set_ylabel("load [N]")
    ax.set_ylim(0.0, 1.08 * ls.load)
    ax.legend(fontsize=8)
    ax.set_title(f"{curve.scene.name}: load sharing ({_label(curve)})", fontsize=9)
    fig.subplots_adjust(left=0.13, right=0.96, bottom=0.12, top=0.93)
    atomic_savefig(fig, path, dpi=DPI)
    return path


def plot_film_separation(curve, path: Path) -> Path:
    """Film thickness hf,r and separation hs against us, full scale and near zero (Figs 4.12-4.13)."""
    fig = Figure(figsize=(10, 4.2))
    axes = fig.subplots(1, 2)
    ls = curve.sharing
    for ax, zoom in zip(axes, (False, True), strict=True):
        ax.semilogx(ls.us, ls.hfr, "k-", label="film thickness hf,r")
        ax.semilogx(ls.us, ls.hs, "b--", label="separation hs")
        ax.axhline(0.0, color="0.7", lw=0.6)
        ax.set_xlabel("sum velocity us [m/s]")
        ax.set_ylabel("distance [m]")
        if zoom:
            r = 3.0 * ls.roughness.Rq
            ax.set_ylim(-r, r)
            ax.set_title("near zero (hs < 0 at high load)", fontsize=9)
        else:
            ax.set_title(f"{curve.scene.name}: film and separation ({_label(curve)})", fontsize=9)
        ax.legend(fontsize=8)
    fig.subplots_adjust(left=0.08, right=0.98, bottom=0.12, top=0.92, wspace=0.25)
    atomic_savefig(fig, path, dpi=DPI)
    return path


def plot_cases(curves: Sequence, path: Path, quantity: str, ylabel: str, title: str) -> Path:
    """One quantity for several curves (several loads as Fig. 4.4, or inlet films as Figs 6.2-6.7).

    ``quantity``: ``friction``, ``hfr`` or ``hs``.
    """
    fig = Figure(figsize=(6.4, 4.4))
    ax = fig.subplots()
    for c in curves:
        if quantity == "friction":
            y = c.friction.coefficient
        else:
            y = getattr(c.sharing, quantity)
        lab = _label(c) if len({cc.sharing.load for cc in curves}) == 1 else f"P = {c.sharing.load:.4g} N, pmax = {c.sharing.pmax / 1e9:.2g} GPa"
        ax.semilogx(c.us, y, label=lab)
    ax.set_xlabel("sum velocity us [m/s]")
    ax.set_ylabel(ylabel)
    if quantity == "friction":
        ax.set_ylim(bottom=0.0)
    else:
        ax.axhline(0.0, color="0.7", lw=0.6)
    ax.legend(fontsize=7)
    ax.set_title(title, fontsize=9)
    fig.subplots_adjust(left=0.13, right=0.96, bottom=0.12, top=0.93)
    atomic_savefig(fig, path, dpi=DPI)
    return path


def stribeck_figures(curves: Sequence, out: Path, stem: str) -> list[Path]:
    """The standard set for a run: friction, loads and film of the first curve; the same
    quantities for all curves when there are several (inlet films)."""
    out.mkdir(parents=True, exist_ok=True)
    c0 = curves[0]
    files = [
        plot_friction(c0, out / f"{stem}_friction.png"),
        plot_load_shares(c0, out / f"{stem}_loads.png"),
        plot_film_separation(c0, out / f"{stem}_film.png"),
    ]
    if len(curves) > 1:
        name = c0.scene.name
        files.append(plot_cases(curves, out / f"{stem}_cases_friction.png", "friction", "coefficient of friction [-]",
                                f"{name}: Stribeck curves for several inlet films"))
        files.append(plot_cases(curves, out / f"{stem}_cases_film.png", "hfr", "film thickness hf,r [m]",
                                f"{name}: film thickness"))
        files.append(plot_cases(curves, out / f"{stem}_cases_separation.png", "hs", "separation hs [m]",
                                f"{name}: separation"))
    return files
