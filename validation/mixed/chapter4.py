"""Thesis chapter 4 line-contact results (Figs 4.4-4.15) and the critical load (4.3.1).

Run: ``python validation/mixed/chapter4.py [--quick]``. Writes build/validation/mixed/chapter4.json and PNGs
fig4_4.png, fig4_6_7.png, fig4_8.png, fig4_9_11.png, fig4_12_13.png, fig4_14.png, fig4_15.png,
critical_load.png. ``--quick`` uses 30 instead of 80 speeds and a coarser critical-load scan.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy import optimize, special

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import out_dir, plt, write_json  # noqa: E402

from ehl_multigrid.model.scene import Scene, load_scene  # noqa: E402
from mixed.critical import critical_load  # noqa: E402
from mixed.film import johnson_film  # noqa: E402
from mixed.gw import gw_f  # noqa: E402
from mixed.stribeck import stribeck_curve, transition_speed  # noqa: E402

LOADS = (500, 2000, 8000, 16000)


def with_roughness(sc: Scene, **changes: float) -> Scene:
    d = sc.to_dict()
    d["roughness"].update(changes)
    return Scene.from_dict(d)


def curve_numbers(c) -> dict:
    f = c.friction.coefficient
    k = int(np.argmin(f))
    return {
        "load": c.sharing.load, "pmax_GPa": c.sharing.pmax / 1e9,
        "us_bl_ml": c.transitions["us_bl_ml"], "us_ml_ehl": c.transitions["us_ml_ehl"],
        "us_ml_ehl_1pct": transition_speed(c.scene, 0.01), "us_ml_ehl_0.1pct": transition_speed(c.scene, 1e-3),
        "f_min": f[k], "us_at_f_min": c.us[k], "f_first": f[0], "f_last": f[-1],
        "hs_min_over_sigma": c.sharing.hs_min / c.sharing.roughness.Rq,
    }


def speed_where(us, y, value):
    """First sum velocity where y crosses value (log interpolation)."""
    s = np.sign(np.asarray(y) - value)
    idx = np.flatnonzero(s[:-1] != s[1:])
    if idx.size == 0:
        return math.nan
    i = idx[0]
    t = (value - y[i]) / (y[i + 1] - y[i])
    return float(np.exp(np.log(us[i]) + t * (np.log(us[i + 1]) - np.log(us[i]))))


def main(quick: bool = False) -> dict:
    t0 = time.perf_counter()
    OUT = out_dir(quick)
    us = np.geomspace(1e-3, 100.0, 30 if quick else 80)
    curves = {P: stribeck_curve(load_scene(f"page63_line_{P}N"), us) for P in LOADS}
    out: dict = {"us_range": [us[0], us[-1], us.size], "thresholds": curves[500].options}

    # Fig 4.4 / 4.5: friction for four loads, transitions
    out["fig4_4"] = {str(P): curve_numbers(c) for P, c in curves.items()}
    p = plt()
    fig, ax = p.subplots(figsize=(6.4, 4.4))
    for P, c in curves.items():
        ax.semilogx(us, c.friction.coefficient, label=f"P = {P} N, pmax = {c.sharing.pmax / 1e9:.2f} GPa")
    ax.set(xlabel="us [m/s]", ylabel="coefficient of friction", title="Fig. 4.4: effect of load (page-63 conditions)")
    ax.set_ylim(0, 0.14)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(OUT / "fig4_4.png", dpi=100)
    p.close(fig)

    # Figs 4.6 / 4.7: components at 1.7 GPa
    c = curves[16000]
    low = us <= 0.01
    out["fig4_6_7"] = {
        "film_load_share_at_us_0.001_0.01": [c.sharing.film_fraction[low].min(), c.sharing.film_fraction[low].max()],
        "film_friction_at_us_0.001_0.01": [c.friction.film[low].min(), c.friction.film[low].max()],
        "asperity_friction_at_us_0.001_0.01": [c.friction.asperity[low].min(), c.friction.asperity[low].max()],
    }
    fig, axes = p.subplots(1, 2, figsize=(11, 4.2))
    axes[0].semilogx(us, c.friction.coefficient, "k-", label="total")
    axes[0].semilogx(us, c.friction.asperity, "b--", label="asperity")
    axes[0].semilogx(us, c.friction.film, "r-.", label="EHL")
    axes[0].set(xlabel="us [m/s]", ylabel="coefficient of friction", title="Fig. 4.6 (1.7 GPa)")
    axes[1].semilogx(us, np.full_like(us, c.sharing.load), "k-", label="total load")
    axes[1].semilogx(us, c.sharing.Pa, "b--", label="asperity")
    axes[1].semilogx(us, c.sharing.Ph, "r-.", label="EHL")
    axes[1].set(xlabel="us [m/s]", ylabel="load [N]", title="Fig. 4.7 (1.7 GPa)")
    for a in axes:
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(OUT / "fig4_6_7.png", dpi=100)
    p.close(fig)

    # Fig 4.8: F_3/2 and hf,r^-10 against hss/sigma_s; where do their log slopes meet?
    sc = curves[2000].scene
    r = sc.roughness
    lam = np.linspace(-3, 3, 121)
    hfr = johnson_film(r.dd + r.sigma_s * lam, r.Rq) / r.Rq
    f32 = gw_f(1.5, lam)

    def slope_gap(lm, expo=10.0):
        hs = r.dd + r.sigma_s * lm
        t = hs / r.Rq
        film = expo * (r.sigma_s / r.Rq) * 0.5 * special.erfc(-t / math.sqrt(2)) / (johnson_film(hs, r.Rq) / r.Rq)
        return 1.5 * gw_f(0.5, lm) / gw_f(1.5, lm) - film

    out["fig4_8"] = {
        "equal_log_slope_hss_over_sigma_s_exponent_10": optimize.brentq(slope_gap, -3, 5),
        "thesis_value": 0.9,
        "note": "slopes of ln F_3/2 and ln hf,r^-10 against hss/sigma_s; hf,r in units of Rq",
    }
    fig, ax = p.subplots(figsize=(6.4, 4.4))
    ax.semilogy(lam, f32, "k-", label="F_3/2(hss/sigma_s)")
    ax.semilogy(lam, hfr**-10.0, "k--", label="(hf,r/Rq)^-10")
    ax.set(xlabel="hss/sigma_s", ylabel="dimensionless value", title="Fig. 4.8")
    ax.set_ylim(1e-4, 1e2)
    ax.legend()
    fig.tight_layout()
    fig.savefig(OUT / "fig4_8.png", dpi=100)
    p.close(fig)

    # Figs 4.9-4.13: film and separation
    fig4_9 = {}
    for P, cc in curves.items():
        ls = cc.sharing
        fig4_9[str(P)] = {
            "hfr_at_us_min": ls.hfr[0], "hfr_at_us_max": ls.hfr[-1], "hs_at_us_min": ls.hs[0],
            "hs_negative_below_us": speed_where(us, ls.hs, 0.0),
            "us_where_hs_over_sigma_is_1.4": speed_where(us, ls.hs / r.Rq, 1.4),
            "hfr_minus_hs_over_sigma_at_hs_1.4sigma": float(johnson_film(1.4 * r.Rq, r.Rq) / r.Rq - 1.4),
        }
    out["fig4_9_13"] = fig4_9
    out["fig4_9_13"]["thesis"] = "1.7 GPa: hf,r clearly larger than hs below hs/sigma = 1.4, reached at us = 0.8 m/s"
    fig, axes = p.subplots(1, 3, figsize=(15, 4.2))
    for cc in curves.values():
        axes[0].semilogx(us, cc.sharing.hfr, label=f"{cc.sharing.pmax / 1e9:.1f} GPa")
        axes[1].semilogx(us, cc.sharing.hs, label=f"{cc.sharing.pmax / 1e9:.1f} GPa")
        axes[2].semilogx(us, cc.sharing.hs, label=f"{cc.sharing.pmax / 1e9:.1f} GPa")
    axes[0].set(title="Fig. 4.9 film thickness hf,r", ylabel="m", ylim=(0, 5e-6))
    axes[1].set(title="Fig. 4.10 separation hs", ylabel="m", ylim=(0, 5e-6))
    axes[2].set(title="Fig. 4.11 separation hs (near 0)", ylabel="m", ylim=(-1e-7, 1e-7))
    for a in axes:
        a.set_xlabel("us [m/s]")
        a.axhline(0, color="0.7", lw=0.6)
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(OUT / "fig4_9_11.png", dpi=100)
    p.close(fig)
    from mixed.plots import plot_film_separation

    plot_film_separation(curves[16000], OUT / "fig4_12_13.png")

    # Fig 4.14: beta and n at constant n beta sigma_s = 0.05 (2000 N, sigma_s = 0.05 um)
    base = load_scene("page63_line_2000N")
    fig4_14 = {}
    fig, ax = p.subplots(figsize=(6.4, 4.4))
    for beta, n in ((0.4e-6, 2.5e12), (2e-6, 5e11), (10e-6, 1e11), (50e-6, 2e10)):
        cc = stribeck_curve(with_roughness(base, beta=beta, n=n), us)
        fig4_14[f"beta={beta * 1e6:g}um"] = curve_numbers(cc)
        ax.semilogx(us, cc.friction.coefficient, label=f"beta = {beta * 1e6:g} um, n = {n:.2g}")
    ax.set(xlabel="us [m/s]", ylabel="coefficient of friction", title="Fig. 4.14: beta and n (n beta sigma_s = 0.05)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(OUT / "fig4_14.png", dpi=100)
    p.close(fig)
    out["fig4_14"] = fig4_14

    # Fig 4.15: sigma_s and n at constant n beta sigma_s (beta = 10 um); Rq and dd as page 63
    fig4_15 = {}
    fig, ax = p.subplots(figsize=(6.4, 4.4))
    for ss, n in ((0.025e-6, 2e11), (0.05e-6, 1e11), (0.1e-6, 5e10), (0.5e-6, 1e10)):
        cc = stribeck_curve(with_roughness(base, sigma_s=ss, n=n), us)
        fig4_15[f"sigma_s={ss * 1e6:g}um"] = curve_numbers(cc)
        ax.semilogx(us, cc.friction.coefficient, label=f"sigma_s = {ss * 1e6:g} um, n = {n:.2g}")
    ax.set(xlabel="us [m/s]", ylabel="coefficient of friction", title="Fig. 4.15: sigma_s and n (beta = 10 um)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(OUT / "fig4_15.png", dpi=100)
    p.close(fig)
    out["fig4_15"] = fig4_15
    out["fig4_15"]["note"] = "Rq = 0.07 um and dd = 0.0575 um kept at the page-63 values (the thesis varies n and sigma_s only)"

    # critical load (4.3.1) for several transition fractions
    crit = {}
    fig, ax = p.subplots(figsize=(6.4, 4.4))
    for frac in (0.2, 0.1, 0.07, 0.05, 0.02, 0.01):
        cl = critical_load(base, fraction=frac, n_scan=13 if quick else 25)
        d = dataclasses.asdict(cl)
        loads, speeds = d.pop("loads"), d.pop("speeds")
        crit[str(frac)] = d
        ax.loglog(loads, speeds, ".-", label=f"Pa/P = {frac}: P* = {cl.load:.0f} N" + ("" if cl.interior else " (edge)"))
    # transition fraction at which the critical load equals the thesis's 8800 N
    g = lambda lf: math.log(critical_load(base, fraction=math.exp(lf), n_scan=9).load / 8800.0)  # noqa: E731
    f88 = math.exp(optimize.brentq(g, math.log(0.05), math.log(0.1), xtol=1e-3))
    cl88 = critical_load(base, fraction=f88, n_scan=9)
    crit["fraction_giving_8800N"] = {"fraction": f88, "load": cl88.load, "hss_over_sigma_s": cl88.hss_over_sigma_s,
                                     "us_transition": cl88.us_transition}
    crit["thesis"] = {"load": 8800.0, "hss_over_sigma_s": 0.9}
    ax.set(xlabel="load P [N]", ylabel="EHL-ML transition speed [m/s]", title="critical load: maximum of the transition speed")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(OUT / "critical_load.png", dpi=100)
    p.close(fig)
    out["critical_load"] = crit
    out["wall_s"] = time.perf_counter() - t0
    write_json("chapter4.json", out, quick)
    for P, v in out["fig4_4"].items():
        print(f"P={P}: BL-ML {v['us_bl_ml']:.4g}  ML-EHL(5%) {v['us_ml_ehl']:.4g}  (1%) {v['us_ml_ehl_1pct']:.4g}  "
              f"fmin {v['f_min']:.4f} at {v['us_at_f_min']:.3g}")
    for k, v in crit.items():
        print("critical", k, v)
    print(f"wall {out['wall_s']:.1f} s")
    return out


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true")
    main(ap.parse_args().quick)
