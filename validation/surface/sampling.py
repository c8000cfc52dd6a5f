"""Validation 2: summit statistics of Gaussian random surfaces against the random-process
predictions, as a function of the sampling interval (the thesis's warning, 4.3.2 / 4.4.1).

Surface: isotropic Gaussian autocorrelation R(r) = Rq^2 exp(-(r/l)^2) (Nayak alpha = 3),
generated at each sampling interval h by circulant embedding (exact covariance R(k h)).
References, neither of which uses a generated surface:
  * Nayak (1971), continuous surface, from m0, m2, m4: n = m4/(6 pi sqrt3 m2),
    mean summit curvature (8/3) sqrt(m4/pi), dd = 4 sigma/sqrt(pi alpha),
    sigma_s = sigma sqrt(1 - 0.8968/alpha);
  * the discrete 9-point rule at interval h: Monte Carlo over the 9-dimensional normal
    distribution of a 3 x 3 neighbourhood (mixed.surface.nine_point_prediction).
Second part: a self-affine surface (Hurst 0.8) analysed at 1, 2, 4, 8 times its finest
interval (decimation of the same map) - no limit exists, n and beta keep changing.
Writes build/validation/surface/sampling.json and build/validation/surface/sampling.png.

    python validation/surface/sampling.py [--quick]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from mixed.surface import (
    HeightMap,
    gaussian_acf,
    gaussian_acf_moments,
    gaussian_random_surface,
    nayak_continuous,
    nine_point_prediction,
    surface_statistics,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir, require  # noqa: E402

OUT = out_dir("surface")
ELL = 1e-6  # correlation length [m]
RQ = 0.1e-6
RATIOS = (0.05, 0.1, 0.2, 0.35, 0.5, 0.7, 1.0, 1.5, 2.0, 3.0)
KEYS = ("n", "kappa_mean", "sigma_s", "dd")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="512^2 maps, 1 seed, 1e6 Monte Carlo samples")
    ap.add_argument("--plot-only", action="store_true", help="redraw sampling.png from sampling.json (build/validation/surface/)")
    args = ap.parse_args()
    if args.plot_only:
        d = json.loads(require(OUT / "sampling.json", "python validation/surface/sampling.py").read_text())
        _plot(d["rows"], d["continuous"], d["self_affine"])
        return
    npts, seeds, nmc = (512, 1, 1_000_000) if args.quick else (1024, 3, 4_000_000)
    OUT.mkdir(parents=True, exist_ok=True)
    mom = gaussian_acf_moments(RQ, ELL)
    cont = nayak_continuous(mom["m0"], mom["m2"], mom["m4"])
    rows = []
    for r in RATIOS:
        h = r * ELL
        t0 = time.perf_counter()
        # at the finest intervals the summit probability is small: more samples keep the error ~2 %
        pred = nine_point_prediction(gaussian_acf(ELL), RQ, h, n_samples=int(nmc * (4 if r < 0.15 else 1)), seed=7)
        meas = []
        for s in range(seeds):
            if npts * h < 8 * ELL:
                continue
            st = surface_statistics(gaussian_random_surface(npts, h, RQ, corr_length=ELL, seed=1000 * s + int(r * 100)))
            meas.append(st)
        row = {"h_over_l": r, "h": h, "pred": {k: pred[k] for k in (*KEYS, "n_se", "kappa_mean_se", "p_summit")},
               "wall_s": 0.0}
        if meas:
            row["measured"] = {k: float(np.mean([getattr(m, k) for m in meas])) for k in KEYS}
            row["measured_n_summits"] = int(sum(m.n_summits for m in meas))
            row["measured_over_pred"] = {k: row["measured"][k] / pred[k] - 1 for k in KEYS}
        row["pred_over_continuous"] = {k: pred[k] / cont[k] for k in KEYS}
        row["wall_s"] = time.perf_counter() - t0
        rows.append(row)
        mo = row.get("measured_over_pred", {})
        print(f"h/l = {r:5.2f}: discrete/continuous n {row['pred_over_continuous']['n']:.3f} "
              f"kappa {row['pred_over_continuous']['kappa_mean']:.3f} sigma_s {row['pred_over_continuous']['sigma_s']:.3f} "
              f"dd {row['pred_over_continuous']['dd']:.3f} | measured/discrete - 1: "
              + " ".join(f"{k} {v:+.3f}" for k, v in mo.items()))
    fractal = _fractal(npts)
    (OUT / "sampling.json").write_text(json.dumps(
        {"corr_length": ELL, "Rq": RQ, "grid": npts, "seeds": seeds, "mc_samples": nmc,
         "continuous": cont, "moments": mom, "rows": rows, "self_affine": fractal}, separators=(",", ":")))
    _plot(rows, cont, fractal)


def _fractal(npts: int) -> list[dict]:
    base = gaussian_random_surface(2 * npts, 0.25e-6, 0.1e-6, hurst=0.8, seed=3)
    out = []
    for k in (1, 2, 4, 8):
        hm = HeightMap(base.z[::k, ::k], base.dx * k, base.dy * k)
        st = surface_statistics(hm)
        out.append({"h": hm.dx, "n": st.n, "beta": st.beta, "sigma_s": st.sigma_s, "dd": st.dd, "psi": st.psi,
                    "n_summits": st.n_summits})
        print(f"self-affine H=0.8, h = {hm.dx * 1e6:.2f} um: n = {st.n:.3g} 1/m^2, beta = {st.beta * 1e6:.3g} um, "
              f"sigma_s = {st.sigma_s * 1e9:.3g} nm, psi = {st.psi:.3g}")
    return out


def _plot(rows, cont, fractal) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    r = np.array([x["h_over_l"] for x in rows])
    fig, axs = plt.subplots(1, 3, figsize=(14, 4.3))
    for ax, k, lab in ((axs[0], "n", "summit density n / n_Nayak"), (axs[0], "kappa_mean", "mean curvature / Nayak")):
        pred = np.array([x["pred_over_continuous"][k] for x in rows])
        ax.plot(r, pred, "-", label=f"{lab}: 9-point prediction")
        mr = [(x["h_over_l"], x["measured"][k] / cont[k]) for x in rows if "measured" in x]
        ax.plot(*zip(*mr, strict=True), "o", color=ax.lines[-1].get_color(), label=f"{lab}: synthetic surfaces")
    axs[0].plot(r, 1 / (9 * (r * ELL) ** 2) / cont["n"], ":", color="gray", label="1/(9 h^2): uncorrelated heights")
    axs[0].set_xscale("log")
    axs[0].set_yscale("log")
    axs[0].set_ylim(0.02, 3)
    axs[0].set_xlabel("sampling interval h / correlation length")
    axs[0].legend(fontsize=7)
    axs[0].set_title("summit density and curvature vs sampling", fontsize=9)
    for k, lab in (("sigma_s", "sigma_s / Nayak"), ("dd", "dd / Nayak")):
        pred = np.array([x["pred_over_continuous"][k] for x in rows])
        axs[1].plot(r, pred, "-", label=f"{lab}: 9-point prediction")
        mr = [(x["h_over_l"], x["measured"][k] / cont[k]) for x in rows if "measured" in x]
        axs[1].plot(*zip(*mr, strict=True), "o", color=axs[1].lines[-1].get_color(), label=f"{lab}: synthetic")
    axs[1].set_xscale("log")
    axs[1].set_xlabel("sampling interval h / correlation length")
    axs[1].legend(fontsize=7)
    axs[1].set_title("summit heights vs sampling", fontsize=9)
    h = np.array([f["h"] for f in fractal]) * 1e6
    for key, mark in (("n", "o-"), ("beta", "s-"), ("sigma_s", "v-"), ("psi", "^-")):
        v = np.array([f[key] for f in fractal])
        axs[2].loglog(h, v / v[0], mark, label=f"{key} / {key}(h = {h[0]:.2g} um) (= {v[0]:.3g})")
    axs[2].set_xlabel("sampling interval h [um]")
    axs[2].set_ylabel("relative to the finest sampling")
    axs[2].legend(fontsize=7)
    axs[2].set_title("self-affine surface (H = 0.8), same map decimated", fontsize=9)
    fig.tight_layout()
    fig.savefig(OUT / "sampling.png", dpi=100)
    plt.close(fig)


if __name__ == "__main__":
    main()
