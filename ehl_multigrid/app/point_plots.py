"""PNG plots of a point-contact result: P and H contour maps, centre-line profiles in X and
Y, and an interference-style film map (dpi <= 110). Figures are built with
``matplotlib.figure.Figure`` (no pyplot), so plotting never changes the process-wide backend."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from ..model.results import Result


def interference_rgb(h_m: np.ndarray, n_oil: float = 1.5, wavelengths=(650e-9, 532e-9, 450e-9)) -> np.ndarray:
    """Two-beam interference colours ``I = cos^2(2 pi n h / lambda)`` for red, green, blue."""
    rgb = [np.cos(2.0 * np.pi * n_oil * h_m / lam) ** 2 for lam in wavelengths]
    return np.clip(np.stack(rgb, axis=-1), 0.0, 1.0)


def plot_result(res: Result, outdir: str | Path, name: str) -> list[Path]:
    """Write ``<name>_maps.png``, ``<name>_profiles.png``, ``<name>_interference.png``."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    X, Y = res["X"], res["Y"]
    P, H = res["P"].T, res["H"].T  # [j, i]
    files = []
    fig = Figure(figsize=(10, 4))
    ax = fig.subplots(1, 2)
    c0 = ax[0].contourf(X, Y, P, levels=30, cmap="viridis")
    fig.colorbar(c0, ax=ax[0], label="P = p/pmax")
    ax[0].set_title("pressure P")
    Hmax = min(float(H.max()), 3.0 * float(res.scalars["Hc_venner"]))
    c1 = ax[1].contourf(X, Y, np.minimum(H, Hmax), levels=30, cmap="magma")
    fig.colorbar(c1, ax=ax[1], label="H (Venner)")
    ax[1].plot([res.scalars["X_Hm"]], [res.scalars["Y_Hm"]], "c+", ms=10, label="Hm")
    ax[1].set_title("film H (clipped at 3 Hc)")
    ax[1].legend(loc="lower left", fontsize=7)
    for a in ax:
        a.set_xlabel("X = x/a")
        a.set_ylabel("Y = y/a")
        a.set_aspect("equal")
    fig.suptitle(f"M = {res.scalars['M']:.4g}, L = {res.scalars['L']:.4g}, theta = {res.scalars['theta']:.3g}; "
                 f"Hc = {res.scalars['Hc']:.4g}, Hm = {res.scalars['Hm']:.4g} (Moes)")
    fig.tight_layout()
    f = outdir / f"{name}_maps.png"
    fig.savefig(f, dpi=100)
    files.append(f)

    jc = int(np.argmin(np.abs(Y)))
    i0 = int(np.argmin(np.abs(X - res.scalars["X_Hm"]))) if np.isfinite(res.scalars["X_Hm"]) else int(np.argmin(np.abs(X)))
    ic = int(np.argmin(np.abs(X)))
    fig = Figure(figsize=(10, 4))
    ax = fig.subplots(1, 2)
    ax[0].plot(X, P[jc], label="P(X, 0)")
    ax2 = ax[0].twinx()
    ax2.plot(X, H[jc], "r-", label="H(X, 0)")
    ax2.set_ylim(0, 3.0 * res.scalars["Hc_venner"])
    ax[0].set_xlabel("X")
    ax[0].set_ylabel("P")
    ax2.set_ylabel("H", color="r")
    ax[0].set_title("centre line Y = 0")
    ax[1].plot(Y, P[:, ic], label="P(0, Y)")
    ax[1].plot(Y, P[:, i0], "--", label=f"P(X={X[i0]:.2f}, Y)")
    ax3 = ax[1].twinx()
    ax3.plot(Y, H[:, ic], "r-")
    ax3.plot(Y, H[:, i0], "r--")
    ax3.set_ylim(0, 3.0 * res.scalars["Hc_venner"])
    ax[1].set_xlabel("Y")
    ax[1].legend(fontsize=7)
    ax[1].set_title("cross sections at X = 0 and through Hm")
    fig.tight_layout()
    f = outdir / f"{name}_profiles.png"
    fig.savefig(f, dpi=100)
    files.append(f)

    if "h" in res.fields:
        hm = res["h"].T
        label = "h [m]"
    else:  # Moes-only: an arbitrary but fixed scale, 1 Venner unit = 1 um
        hm = H * 1e-6
        label = "H x 1 um (no physical scale)"
    fig = Figure(figsize=(5, 5))
    ax = fig.subplots()
    ax.imshow(interference_rgb(np.maximum(hm, 0.0)), origin="lower",
              extent=(X[0], X[-1], Y[0], Y[-1]), interpolation="bilinear")
    ax.set_xlabel("X")
    ax.set_ylabel("Y")
    ax.set_title(f"interference-style film map ({label})", fontsize=8)
    fig.tight_layout()
    f = outdir / f"{name}_interference.png"
    fig.savefig(f, dpi=100)
    files.append(f)
    return files
