"""Figures of a traction :class:`Result`: traction curve, temperature map (as thesis Fig. 3.9),
velocity profiles (Fig. 3.13) and inlet-region temperatures (Figs 3.15-3.17). Point-contact
results are shown on the slice nearest the centre line. Figures are built with
``matplotlib.figure.Figure`` (no pyplot), so plotting never changes the process-wide backend."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from ehl_multigrid.model.atomic import atomic_savefig
from ehl_multigrid.model.results import Result

DPI = 100
# figures keep fixed margins: a tight layout costs about 0.3 s per figure (docs/performance.md)


def _slice(res: Result, name: str, k: int) -> np.ndarray:
    a = res[name][k]
    if "Y" in res.coords and res.fields[name].dims[1] == "Y":
        a = a[0]
    return a


def slip_index(res: Result, slip: float | None = None) -> int:
    """Index of the slip nearest ``slip`` (default: nearest 0.4, the thesis's Fig. 3.9 value)."""
    S = res["slip"]
    return int(np.argmin(np.abs(S - (0.4 if slip is None else slip))))


def plot_traction_curve(res: Result, path: Path, reference: dict | None = None) -> Path:
    """Friction force and coefficient against slip (S in %)."""
    S = res["slip"] * 100
    fig = Figure(figsize=(6, 3.8))
    ax = fig.subplots()
    ax.plot(S, res["friction_force"], "o-", ms=3, label=f"{'thermal' if res.scalars.get('thermal') else 'isothermal'} ({res.scalars.get('input')})")
    bad = res["converged"] == 0
    if np.any(bad):
        ax.plot(S[bad], res["friction_force"][bad], "rx", label="not converged")
    if reference:
        for lab, (s, f) in reference.items():
            ax.plot(np.asarray(s) * 100, f, "--", label=lab)
    ax.set_xlabel("slip S [%]")
    ax.set_ylabel("friction force [N]")
    ax2 = ax.twinx()
    load = res.scalars["load"]
    lo, hi = ax.get_ylim()
    ax2.set_ylim(lo / load, hi / load)
    ax2.set_ylabel("coefficient of friction [-]")
    sc = res.scene
    ax.set_title(f"{sc.name if sc else ''}: pmax = {res.scalars['pmax'] / 1e9:.3g} GPa, us = {res.scalars['us']:.3g} m/s", fontsize=9)
    ax.legend(fontsize=8, loc="best")
    ax.grid(alpha=0.3)
    fig.subplots_adjust(left=0.12, right=0.86, bottom=0.13, top=0.92)
    atomic_savefig(fig, path, dpi=DPI)
    return path


def plot_temperature_map(res: Result, path: Path, k: int | None = None, xlim: tuple[float, float] | None = (-1.2, 1.0)) -> Path:
    """T(X, Z) map and both surface temperatures along X at slip index ``k``."""
    k = slip_index(res) if k is None else k
    X, Z = res["X"], res["Z"]
    T = _slice(res, "T", k)
    fig = Figure(figsize=(6.5, 5.5))
    a1, a2 = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    m = a1.pcolormesh(X, Z, T.T, shading="auto", cmap="inferno")
    fig.colorbar(m, ax=a1, label="T [degC]")
    a1.set_ylabel("Z = z/h")
    a1.set_title(f"temperature, S = {res['slip'][k] * 100:.3g} %, max rise {res['max_temperature_rise'][k]:.3g} K", fontsize=9)
    a2.plot(X, _slice(res, "T_surface1", k), label="surface 1 (Z = 0)")
    a2.plot(X, _slice(res, "T_surface2", k), label="surface 2 (Z = 1)")
    a2.plot(X, T[:, T.shape[1] // 2], "k--", lw=0.8, label="centre line Z = 0.5")
    a2.set_xlabel("X = x/b")
    a2.set_ylabel("T [degC]")
    a2.legend(fontsize=7)
    if xlim:
        a2.set_xlim(max(xlim[0], X[0]), min(xlim[1], X[-1]))
    fig.subplots_adjust(left=0.12, right=0.97, bottom=0.09, top=0.94, hspace=0.1)
    atomic_savefig(fig, path, dpi=DPI)
    return path


def plot_velocity_profiles(res: Result, path: Path, k: int | None = None, Xs: tuple[float, ...] = (-1.0, -0.97, 0.0, 0.95)) -> Path:
    """u(Z) at chosen X (thesis Fig. 3.13)."""
    k = slip_index(res) if k is None else k
    X, Z = res["X"], res["Z"]
    U = _slice(res, "u", k)
    fig = Figure(figsize=(5, 4))
    ax = fig.subplots()
    for xv in Xs:
        i = int(np.argmin(np.abs(X - xv)))
        ax.plot(U[i], Z, label=f"X = {X[i]:.3g}")
    ax.set_xlabel("u [m/s]")
    ax.set_ylabel("Z = z/h")
    ax.set_title(f"velocity across the film, S = {res['slip'][k] * 100:.3g} %", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.subplots_adjust(left=0.14, right=0.96, bottom=0.12, top=0.92)
    atomic_savefig(fig, path, dpi=DPI)
    return path


def plot_inlet_temperatures(res: Result, path: Path, k: int | None = None, x_end: float = -1.0) -> Path:
    """Inlet region X < -1: T(X, Z) map, surface temperatures and the centre line (Figs 3.15-3.17)."""
    k = slip_index(res) if k is None else k
    X, Z = res["X"], res["Z"]
    sel = X <= x_end + 1e-9
    T = _slice(res, "T", k)
    fig = Figure(figsize=(11, 3.4))
    ax = fig.subplots(1, 3)
    m = ax[0].pcolormesh(X[sel], Z, T[sel].T, shading="auto", cmap="inferno")
    fig.colorbar(m, ax=ax[0], label="T [degC]")
    ax[0].set_xlabel("X")
    ax[0].set_ylabel("Z")
    ax[0].set_title("oil temperature, inlet (Fig. 3.15)", fontsize=9)
    ax[1].plot(X[sel], _slice(res, "T_surface1", k)[sel], label="surface 1")
    ax[1].plot(X[sel], _slice(res, "T_surface2", k)[sel], label="surface 2")
    ax[1].set_title("surface temperatures (Fig. 3.16)", fontsize=9)
    ax[1].set_xlabel("X")
    ax[1].legend(fontsize=7)
    ax[2].plot(X[sel], T[sel, T.shape[1] // 2])
    ax[2].set_title("centre line Z = 0.5 (Fig. 3.17)", fontsize=9)
    ax[2].set_xlabel("X")
    for a in ax[1:]:
        a.set_ylabel("T [degC]")
        a.grid(alpha=0.3)
    fig.suptitle(f"S = {res['slip'][k] * 100:.3g} %", fontsize=9)
    fig.subplots_adjust(left=0.06, right=0.98, bottom=0.15, top=0.86, wspace=0.5)
    atomic_savefig(fig, path, dpi=DPI)
    return path


def plot_all(res: Result, outdir: Path, stem: str) -> dict[str, str]:
    outdir.mkdir(parents=True, exist_ok=True)
    out = {"traction": str(plot_traction_curve(res, outdir / f"{stem}_traction.png"))}
    if res.scalars.get("thermal"):
        out["temperature"] = str(plot_temperature_map(res, outdir / f"{stem}_temperature.png"))
        if res["X"][0] < -1.0:
            out["inlet"] = str(plot_inlet_temperatures(res, outdir / f"{stem}_inlet.png"))
    out["velocity"] = str(plot_velocity_profiles(res, outdir / f"{stem}_velocity.png"))
    return out
