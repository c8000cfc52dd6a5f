"""Figures of a thermal EHL solution (a ``tehl_line`` or ``tehl_point`` :class:`Result`):
pressure and film along the rolling direction with the isothermal central film for reference,
and the temperature across the film (line) or the mid-film temperature over the contact
(point). Built with ``matplotlib.figure.Figure`` (no pyplot)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from ehl_multigrid.model.atomic import atomic_savefig
from ehl_multigrid.model.results import Result

DPI = 110


def plot_tehl(res: Result, path: Path) -> Path:
    """One figure: P and H (Venner units) with the isothermal central film, and the temperature
    map (line: T(X, z/h); point: mid-film T over the half plane). Returns ``path``."""
    fig = Figure(figsize=(11, 4.2))
    ax1, ax2 = fig.subplots(1, 2)
    point = res.kind == "tehl_point"
    X = res["X"]
    P = res["P"][0] if point else res["P"]
    H = res["H"][0] if point else res["H"]
    ax1.plot(X, P, "C0-", lw=1.2, label="P = p/pmax")
    ax1.set_xlabel("X = x/a" if point else "X = x/b")
    ax1.set_ylabel("P")
    axh = ax1.twinx()
    axh.plot(X, H, "C1-", lw=1.2, label="H (thermal EHL)")
    Hc_iso = res.scalars.get("Hc_isothermal")
    if Hc_iso is not None:
        # Moes-scaled scalars; the field H is in Venner units: draw the ratio at the centre
        Hc = res.scalars["Hc"]
        axh.axhline(float(np.interp(0.0, X, H)) * Hc_iso / Hc, color="C1", ls="--", lw=0.8,
                    label="isothermal central film")
    axh.set_ylabel("H (Venner)")
    axh.set_ylim(0.0, 4.0 * float(np.interp(0.0, X, H)))
    lines = ax1.get_lines() + axh.get_lines()
    ax1.legend(lines, [ln.get_label() for ln in lines], fontsize=8, loc="upper left")
    ax1.set_title(f"slip {res.scalars.get('slip', float('nan')):g}: Hc/Hc_iso = "
                  f"{res.scalars['Hc'] / Hc_iso:.4f}" if Hc_iso else "", fontsize=9)
    if point:
        m = ax2.pcolormesh(X, res["Y"], res["T_mid"], shading="auto", cmap="inferno")
        ax2.set_xlabel("X = x/a")
        ax2.set_ylabel("Y = y/a")
        ax2.set_title("mid-film temperature", fontsize=9)
    else:
        m = ax2.pcolormesh(X, res["Z"], res["T"].T, shading="auto", cmap="inferno")
        ax2.set_xlabel("X = x/b")
        ax2.set_ylabel("z/h (0: surface 1)")
        ax2.set_xlim(-1.5, 1.5)
        ax2.set_title("temperature across the film", fontsize=9)
    fig.colorbar(m, ax=ax2, label="T [degC]")
    fig.subplots_adjust(left=0.06, right=0.97, bottom=0.12, top=0.92, wspace=0.3)
    atomic_savefig(fig, path, dpi=DPI)
    return Path(path)
