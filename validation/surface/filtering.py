"""Validation 3: plasticity index against low-pass passes and Gaussian cut-off for a rough
synthetic surface like the thesis's run-in disc (section 5.2: Rq 0.19 um, n 4.95e10 1/m^2,
beta 9.39 um, sigma_s 0.17 um, psi 3.12, sampled at 0.781 um on 736 x 480 points), and the
Stribeck curves before and after filtering (as thesis Figs 5.4 and 5.7: pmax 1.93 GPa,
slip 5 %, T9 at 80 degC - built-in scene series_D_disc3_1.93GPa with the roughness replaced).

The surface is a self-affine Gaussian random surface (Hurst 0.8, roll-off 50 um) - no
measured map of the thesis is available, so the numbers compare in kind, not digit by digit.
Writes build/validation/surface/filtering.json and build/validation/surface/filtering.png.

    python validation/surface/filtering.py [--quick]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from ehl_multigrid.model.scene import Scene, load_scene
from mixed.surface import (
    filter_until_psi,
    gaussian_lowpass,
    gaussian_random_surface,
    lowpass_3x3,
    surface_statistics,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("surface")
BASE_SCENE = "series_D_disc3_1.93GPa"
E_THESIS = 2.3e11
KEYS = ("Ra", "Rq", "n", "beta", "sigma_s", "dd", "psi", "n_summits")


def stats_row(label, st, setting):
    return {"label": label, "setting": setting, **{k: getattr(st, k) for k in KEYS}}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="fewer filter settings and Stribeck points")
    args = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    hm = gaussian_random_surface((480, 736), 0.781e-6, 0.19e-6, hurst=0.8, rolloff=50e-6, seed=5)
    st0 = surface_statistics(hm, E_reduced=E_THESIS)
    print(f"unfiltered: Rq {st0.Rq:.3g} n {st0.n:.3g} beta {st0.beta:.3g} sigma_s {st0.sigma_s:.3g} psi {st0.psi:.3g}")

    passes_max = 12 if args.quick else 30
    lowpass = {}
    for w in ("binomial", "box"):
        rows, cur = [stats_row("lowpass", st0, 0)], hm
        for k in range(1, passes_max + 1):
            cur = lowpass_3x3(cur, 1, weights=w)
            rows.append(stats_row("lowpass", surface_statistics(cur, E_reduced=E_THESIS), k))
        lowpass[w] = rows
    lcs = np.geomspace(1.2e-6, 60e-6, 12 if args.quick else 24)
    gauss = [stats_row("gaussian", surface_statistics(gaussian_lowpass(hm, lc), E_reduced=E_THESIS), lc) for lc in lcs]
    until_lp = filter_until_psi(hm, 1.0, "lowpass", E_reduced=E_THESIS)
    until_g = filter_until_psi(hm, 1.0, "gaussian", cutoffs=np.geomspace(1.2e-6, 60e-6, 48), E_reduced=E_THESIS)
    chosen = {"unfiltered": st0, f"low-pass x {until_lp.result.setting:g}": until_lp.result.stats,
              f"Gaussian lambda_c = {until_g.result.setting * 1e6:.3g} um": until_g.result.stats}
    for k, s in chosen.items():
        print(f"{k}: n {s.n:.3g} beta {s.beta:.3g} sigma_s {s.sigma_s:.3g} Rq {s.Rq:.3g} psi {s.psi:.3g}")

    stribeck = _stribeck(chosen, 20 if args.quick else 40)
    out = {
        "surface": {"shape": [480, 736], "dx": 0.781e-6, "Rq": 0.19e-6, "hurst": 0.8, "rolloff": 50e-6, "seed": 5},
        "E_reduced": E_THESIS, "hardness": st0.hardness,
        "lowpass": lowpass, "gaussian": gauss,
        "until_psi": {"lowpass": until_lp.to_dict(), "gaussian": until_g.to_dict()},
        "stribeck": stribeck, "wall_s": time.perf_counter() - t0,
    }
    (OUT / "filtering.json").write_text(json.dumps(out, separators=(",", ":"), default=float))
    _plot(lowpass, gauss, stribeck)


def _stribeck(chosen, npts):
    try:
        from mixed.stribeck import stribeck_curve
    except ImportError as exc:
        print(f"Stribeck curves skipped: mixed.stribeck unavailable ({exc})")
        return {"available": False, "reason": str(exc)}
    base = load_scene(BASE_SCENE)
    us = np.geomspace(0.02, 12.0, npts)
    curves = {}
    for label, st in chosen.items():
        d = base.to_dict()
        d["roughness"] = st.roughness_block(fc=base.roughness.fc)
        sc = Scene.from_dict(d, origin=f"{BASE_SCENE} + {label}")
        c = stribeck_curve(sc, us)
        curves[label] = {"psi": st.psi, "us": us.tolist(), "f": np.asarray(c.friction.coefficient).tolist(),
                         "asperity_fraction": np.asarray(c.sharing.asperity_fraction).tolist(),
                         "transitions": {k: float(v) if np.isscalar(v) else str(v)
                                         for k, v in (c.transitions or {}).items()}}
        print(f"Stribeck {label}: f(0.02) {curves[label]['f'][0]:.4f}, f(1 m/s) "
              f"{np.interp(1.0, us, curves[label]['f']):.4f}, f(12) {curves[label]['f'][-1]:.4f}")
    return {"available": True, "scene": BASE_SCENE, "curves": curves}


def _plot(lowpass, gauss, stribeck) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(1, 3, figsize=(15, 4.3))
    for w, rows in lowpass.items():
        axs[0].plot([r["setting"] for r in rows], [r["psi"] for r in rows], "o-", ms=3, label=f"3x3 {w}")
    axs[0].axhline(1.0, color="k", ls=":")
    axs[0].set_xlabel("low-pass passes")
    axs[0].set_ylabel("plasticity index psi")
    axs[0].legend(fontsize=8)
    axs[0].set_title("psi vs low-pass passes (thesis 5.3)", fontsize=9)
    ax = axs[1]
    lc = np.array([r["setting"] for r in gauss]) * 1e6
    ax.semilogx(lc, [r["psi"] for r in gauss], "o-", ms=3, label="psi")
    ax.axhline(1.0, color="k", ls=":")
    ax.set_xlabel("Gaussian cut-off lambda_c [um]")
    ax.set_ylabel("psi")
    ax2 = ax.twinx()
    ax2.loglog(lc, [r["n"] for r in gauss], "s--", ms=3, color="C1", label="n [1/m^2]")
    ax2.loglog(lc, [r["beta"] * 1e16 for r in gauss], "^--", ms=3, color="C2", label="beta [m] x 1e16")
    ax.legend(loc="upper center", fontsize=8)
    ax2.legend(loc="upper right", fontsize=8)
    ax.set_title("psi, n, beta vs ISO Gaussian cut-off", fontsize=9)
    ax = axs[2]
    if stribeck.get("available"):
        for label, c in stribeck["curves"].items():
            ax.semilogx(c["us"], c["f"], label=f"{label} (psi = {c['psi']:.2f})")
        ax.set_xlabel("sum velocity us [m/s]")
        ax.set_ylabel("coefficient of friction")
        ax.legend(fontsize=7)
        ax.set_title(f"Stribeck curves, {stribeck['scene']} (as Figs 5.4, 5.7)", fontsize=9)
    else:
        ax.axis("off")
        ax.text(0, 0.5, "Stribeck curves unavailable:\n" + stribeck.get("reason", ""), fontsize=9)
    fig.tight_layout()
    fig.savefig(OUT / "filtering.png", dpi=100)
    plt.close(fig)


if __name__ == "__main__":
    main()
