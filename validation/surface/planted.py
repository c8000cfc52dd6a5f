"""Validation 1: planted spherical asperities -> recovered n, beta, sigma_s, dd.

Caps of one radius with normal apex heights on a flat base (mixed.surface.planted_asperities);
the 9-point rule and the 3-point curvature should return what was planted. The reference for
each case is what a perfect detector would see: the caps whose nearest grid point is an
interior point (edge points cannot be tested). Writes build/validation/surface/planted.json and build/validation/surface/planted.png.

    python validation/surface/planted.py [--quick]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from mixed.surface import analyse_surface, parse_filter, planted_asperities

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("surface")

CASES = [
    # name, dx, density, radius, height mean, height std, noise Rq, filter
    ("A: beta 30 um, dx 0.5 um", 0.5e-6, 1e10, 30e-6, 0.06e-6, 0.012e-6, 0.0, "none"),
    ("B: beta 60 um, dx 0.5 um", 0.5e-6, 5e9, 60e-6, 0.08e-6, 0.016e-6, 0.0, "none"),
    ("C: A sampled at dx 1 um", 1.0e-6, 1e10, 30e-6, 0.06e-6, 0.012e-6, 0.0, "none"),
    ("D: A + 0.5 nm noise", 0.5e-6, 1e10, 30e-6, 0.06e-6, 0.012e-6, 0.5e-9, "none"),
    ("E: D + 2 low-pass passes", 0.5e-6, 1e10, 30e-6, 0.06e-6, 0.012e-6, 0.5e-9, "lowpass:2"),
]


def run_case(name, dx, dens, R, mu, sd, noise, filt, npts, seed):
    t0 = time.perf_counter()
    hm, truth = planted_asperities(npts, dx, dens, R, mu, sd, noise_rq=noise, seed=seed)
    an = analyse_surface(hm, levelling="mean", filter=parse_filter(filt))
    st = an.stats
    jx, jy = np.rint(truth.x / dx).astype(int), np.rint(truth.y / dx).astype(int)
    inner = (jx >= 1) & (jx <= hm.nx - 2) & (jy >= 1) & (jy <= hm.ny - 2)
    n_ref = inner.sum() / ((hm.nx - 2) * (hm.ny - 2) * dx * dx)
    ss_ref = float(np.std(truth.apex[inner], ddof=1))
    dd_ref = float(np.mean(truth.apex[inner]) - np.mean(hm.z))
    row = {
        "case": name, "dx": dx, "grid": npts, "noise_rq": noise, "filter": filt,
        "n_planted": truth.density, "n_ref": n_ref, "n": st.n, "n_err": st.n / n_ref - 1,
        "beta_planted": R, "beta": st.beta, "beta_err": st.beta / R - 1,
        "beta_mean_radius": st.beta_mean_radius,
        "sigma_s_ref": ss_ref, "sigma_s": st.sigma_s, "sigma_s_err": st.sigma_s / ss_ref - 1,
        "dd_ref": dd_ref, "dd": st.dd, "dd_err": st.dd / dd_ref - 1,
        "dd_pixel_bias_pred": -dx**2 / (12 * R) / dd_ref,
        "n_summits": st.n_summits, "n_caps_interior": int(inner.sum()), "psi": st.psi,
        "wall_s": time.perf_counter() - t0,
    }
    return row, an, truth


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="512 x 512 maps instead of 1024 x 1024")
    args = ap.parse_args()
    npts = 512 if args.quick else 1024
    OUT.mkdir(parents=True, exist_ok=True)
    rows = []
    keep = {}
    for i, c in enumerate(CASES):
        row, an, truth = run_case(*c, npts=npts, seed=100 + i)
        rows.append(row)
        keep[c[0][0]] = (an, truth)
        print(f"{row['case']:<28} n err {row['n_err']:+.4f}  beta err {row['beta_err']:+.4f}  "
              f"sigma_s err {row['sigma_s_err']:+.4f}  dd err {row['dd_err']:+.4f} "
              f"(pixel bias pred {row['dd_pixel_bias_pred']:+.4f})  summits {row['n_summits']}/{row['n_caps_interior']}")
    (OUT / "planted.json").write_text(json.dumps({"grid": npts, "cases": rows}, separators=(",", ":")))
    _plot(keep, rows)


def _plot(keep, rows) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(1, 3, figsize=(14, 4.3))
    an, truth = keep["A"]
    hm = an.surface
    m = 160
    axs[0].imshow(hm.z[:m, :m] * 1e9, extent=(0, m * hm.dx * 1e6, m * hm.dy * 1e6, 0), cmap="viridis")
    s = an.summits
    sel = (s.iy < m) & (s.ix < m)
    axs[0].plot(s.ix[sel] * hm.dx * 1e6, s.iy[sel] * hm.dy * 1e6, "r.", ms=4, label="9-point summits")
    tsel = (truth.x < m * hm.dx) & (truth.y < m * hm.dy)
    axs[0].plot(truth.x[tsel] * 1e6, truth.y[tsel] * 1e6, "wx", ms=4, label="planted centres")
    axs[0].set_title("case A (corner), heights [nm]", fontsize=9)
    axs[0].set_xlabel("x [um]")
    axs[0].legend(fontsize=7, loc="lower right")
    h = an.summits.height
    axs[1].hist(truth.apex - an.raw.z.mean(), bins=40, density=True, alpha=0.5, label="planted apex heights")
    axs[1].hist(h, bins=40, density=True, histtype="step", color="r", label="recovered summit heights")
    axs[1].set_xlabel("height above mean plane [m]")
    axs[1].legend(fontsize=7)
    axs[1].set_title("case A: summit heights", fontsize=9)
    labels = [r["case"][:1] for r in rows]
    x = np.arange(len(rows))
    for k, key in enumerate(("n_err", "beta_err", "sigma_s_err", "dd_err")):
        vals = np.array([r[key] for r in rows]) * 100
        axs[2].bar(x + (k - 1.5) * 0.2, np.clip(vals, -100, 300), 0.2, label=key.replace("_err", ""))
    axs[2].set_xticks(x, labels)
    axs[2].set_yscale("symlog", linthresh=1)
    axs[2].set_ylabel("recovered / planted - 1 [%] (clipped at 300)")
    axs[2].axhline(0, color="k", lw=0.5)
    axs[2].legend(fontsize=7)
    axs[2].set_title("errors per case (A-E, see REPORT.md)", fontsize=9)
    fig.tight_layout()
    fig.savefig(OUT / "planted.png", dpi=100)
    plt.close(fig)


if __name__ == "__main__":
    main()
