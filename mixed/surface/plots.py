"""PNG output of ``ehl surface``: the map with its summits, the height histograms with their
Gaussian equivalents (as thesis Figs 4.16-4.17), the summit radii, and psi per filter step."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from ehl_multigrid.model.atomic import atomic_savefig

from .analysis import Analysis
from .statistics import height_histograms

MAX_MAP_POINTS = 1024  # the map panel is decimated to at most this many points per side


def plot_analysis(an: Analysis, path: str | Path, title: str = "") -> Path:
    hm, st, s = an.surface, an.stats, an.summits
    fig = Figure(figsize=(11, 8.5))
    axs = fig.subplots(2, 2)
    # (a) map and summit positions
    ax = axs[0, 0]
    step = max(1, int(np.ceil(max(hm.shape) / MAX_MAP_POINTS)))
    z = (hm.z - np.nanmean(hm.z))[::step, ::step] * 1e6
    ext = (0, hm.nx * hm.dx * 1e6, hm.ny * hm.dy * 1e6, 0)
    im = ax.imshow(z, extent=ext, cmap="viridis", interpolation="nearest")
    fig.colorbar(im, ax=ax, label="height [um]")
    if s.count:
        ax.plot(s.ix * hm.dx * 1e6, s.iy * hm.dy * 1e6, ".", ms=2, color="r", alpha=0.7,
                label=f"{s.count} summits (9-point)")
        ax.legend(loc="upper right", fontsize=8)
    ax.set_xlabel("x [um]")
    ax.set_ylabel("y [um]")
    ax.set_title("map and summits", fontsize=10)
    # (b) height densities (Figs 4.16-4.17)
    ax = axs[0, 1]
    h = height_histograms(hm, st, s)
    x = h["height"]
    ax.plot(x, h["surface_density"], "-", color="C0", label="measured surface height density")
    ax.plot(x, h["surface_gaussian"], "--", color="C0", label=f"Gaussian, sigma = {st.Rq:.3g} m")
    ax.plot(h["summit_height"], h["summit_density"], "-", color="C3", label="measured summit height density")
    ax.plot(x, h["summit_gaussian"], "--", color="C3", label=f"Gaussian, dd = {st.dd:.3g}, sigma_s = {st.sigma_s:.3g} m")
    ax.set_xlabel("height [m]")
    ax.set_ylabel("probability density [1/m]")
    ax.legend(fontsize=7)
    ax.set_title("height densities (as thesis Figs 4.16-4.17)", fontsize=10)
    # (c) summit radii
    ax = axs[1, 0]
    if s.count:
        r = 1.0 / s.kappa * 1e6
        bins = np.logspace(np.log10(max(r.min(), 1e-3)), np.log10(r.max() * 1.01), 40)
        ax.hist(r, bins=bins, color="C2", alpha=0.8)
        ax.set_xscale("log")
        ax.axvline(st.beta * 1e6, color="k", ls="--", label=f"beta = 1/mean(kappa) = {st.beta * 1e6:.3g} um")
        ax.legend(fontsize=8)
    ax.set_xlabel("summit radius 1/kappa [um]")
    ax.set_ylabel("count")
    ax.set_title("summit radii", fontsize=10)
    # (d) filter study or summary
    ax = axs[1, 1]
    if an.study is not None and an.study.steps:
        xs = [stp.setting * (1 if stp.method == "lowpass" else 1e6) for stp in an.study.steps]
        ax.plot(xs, [stp.stats.psi for stp in an.study.steps], "o-", label="psi")
        ax.axhline(an.study.target, color="k", ls=":", label=f"target {an.study.target:g}")
        ax.set_xlabel("low-pass passes" if an.study.steps[0].method == "lowpass" else "lambda_c [um]")
        ax.set_ylabel("plasticity index psi")
        ax.legend(fontsize=8)
        ax.set_title("filter until psi (thesis 5.3)", fontsize=10)
    else:
        ax.axis("off")
        lines = [
            f"Ra = {st.Ra:.4g} m", f"Rq = {st.Rq:.4g} m", f"Rsk = {st.Rsk:.3g}, Rku = {st.Rku:.3g}",
            f"n = {st.n:.4g} 1/m^2 ({st.n_summits} summits)", f"beta = {st.beta:.4g} m",
            f"sigma_s = {st.sigma_s:.4g} m", f"dd = {st.dd:.4g} m",
            f"psi = {st.psi:.3g} (E' = {st.E_reduced:.3g} Pa, H' = {st.hardness:.3g} Pa)",
            f"filter: {an.filter.describe()}",
        ]
        ax.text(0.0, 1.0, "\n".join(lines), va="top", family="monospace", fontsize=9)
    fig.suptitle(title or Path(an.raw.source).name, fontsize=11)
    fig.tight_layout()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    atomic_savefig(fig, path, dpi=100)
    return path
