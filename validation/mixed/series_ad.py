"""WAM series A-D (thesis Figs 4.18-4.23), isothermal and thermal (Figs 5.9, 5.10).

Run: ``python validation/mixed/series_ad.py [--quick]``. Writes build/validation/mixed/series_ad.json and
fig4_18_19_20.png, fig4_19_20_<scene>.png, fig4_21.png, fig4_22_fig5_10.png, fig4_23.png,
fig5_9.png. ``--quick``: 12 speeds, no thermal.

Checks against the thesis text: the smooth-surface (gamma1 = 1) film at the ends of each
speed range and h/sigma_s (section 4.4.3), the temperature rises quoted for Figs 4.18, 4.22,
5.9; and the thesis's own isothermal film estimate (Eyring at pavehl) against the thermal
solver run isothermally on the Hertz pressure of the same load (a second path).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import out_dir, plt, write_json  # noqa: E402

from ehl_multigrid.model.scene import load_scene  # noqa: E402
from mixed.gw import plasticity_index  # noqa: E402
from mixed.stribeck import default_us, stribeck_curve  # noqa: E402

FIGURES = {
    "fig4_18_19_20": ["series_A_disc1_0.78GPa", "series_A_disc2_1GPa"],
    "fig4_21": ["series_B_disc1_0.78GPa", "series_B_disc2_1GPa"],
    "fig4_22_fig5_10": ["series_C_disc3_1.93GPa"],
    "fig4_23": ["series_D_disc3_1.93GPa", "series_D_disc4_1.93GPa"],
    "fig5_9": ["chapter6_starved_1.93GPa"],
}
# Section 4.4.3 text: smooth film at the (high, low) ends of the speed range [um], h/sigma_s
THESIS_FILM = {
    "series_A_disc1_0.78GPa": (0.04, 0.0004, 1.18, 0.012), "series_A_disc2_1GPa": (0.04, 0.0004, 1.38, 0.014),
    "series_B_disc1_0.78GPa": (0.13, 0.0018, 3.82, 0.05), "series_B_disc2_1GPa": (0.13, 0.0018, 4.48, 0.06),
    "series_C_disc3_1.93GPa": (0.03, None, 1.6, None),
    "series_D_disc3_1.93GPa": (0.12, 0.002, 6.67, 0.11), "series_D_disc4_1.93GPa": (0.12, 0.002, 0.44, 0.07),
}
THESIS_DT = {"series_A_disc2_1GPa": "5 degC at 2 m/s (smooth, thermal)", "series_C_disc3_1.93GPa": "49 degC at the high-speed end",
             "chapter6_starved_1.93GPa": "above 10 degC at 12 m/s (Fig. 5.9)"}


def second_path(sc, curve, idx) -> list[dict]:
    """Thesis's isothermal film term vs thermal.film_friction(thermal=False) on Hertz at Ph."""
    import thermal

    rows = []
    for i in idx:
        ff = thermal.film_friction(sc, load=float(curve.sharing.Ph[i]), h=float(curve.sharing.hfr[i]),
                                   us=float(curve.us[i]), slip=abs(sc.slip), thermal=False)
        rows.append({"us": curve.us[i], "pavehl_model_N": curve.friction.film_force[i], "hertz_profile_N": abs(ff.force),
                     "ratio": curve.friction.film_force[i] / abs(ff.force)})
    return rows


def main(quick: bool = False) -> dict:
    t0 = time.perf_counter()
    OUT = out_dir(quick)
    out: dict = {}
    p = plt()
    for fig, names in FIGURES.items():
        fig_out = {}
        f, ax = p.subplots(figsize=(6.8, 4.6))
        ax2 = None
        for k, name in enumerate(names):
            sc = load_scene(name)
            us = default_us(sc, 12 if quick else None)
            if name.startswith("chapter6"):
                us = np.geomspace(0.02, 12.0, 12 if quick else 40)
            iso = stribeck_curve(sc, us)
            r = sc.roughness
            hc_hi = sc.central_film_fit(us[-1])[1]
            hc_lo = sc.central_film_fit(us[0])[1]
            d = {
                "pmax_GPa": sc.hertz.pmax / 1e9, "load": sc.load, "slip": sc.slip, "us": [us[0], us[-1]],
                "plasticity_index": plasticity_index(sc.E_reduced, r.hardness, r.sigma_s, r.beta),
                "smooth_film_um_high_low": [hc_hi * 1e6, hc_lo * 1e6],
                "h_over_sigma_s_high_low": [hc_hi / r.sigma_s, hc_lo / r.sigma_s],
                "thesis_film_um_high_low_and_h_over_sigma_s": THESIS_FILM.get(name),
                "iso": {"f_low": iso.friction.coefficient[0], "f_high": iso.friction.coefficient[-1],
                        "f_min": iso.friction.coefficient.min(), "us_at_f_min": us[int(np.argmin(iso.friction.coefficient))],
                        "Lambda_high": iso.sharing.Lambda[-1], "asperity_share_high": iso.sharing.asperity_fraction[-1],
                        **iso.transitions},
            }
            color = f"C{k}"
            if fig == "fig4_18_19_20":  # Figs 4.19 and 4.20: asperity and EHL parts
                from mixed.plots import plot_friction

                plot_friction(iso, OUT / f"fig4_19_20_{name}.png", f"Figs 4.19/4.20: {name} (isothermal)")
            ax.semilogx(us, iso.friction.coefficient, "-", color=color, label=f"{name} isothermal")
            if not quick:
                th = stribeck_curve(sc, us, thermal=True, transitions=False)
                d["thermal"] = {
                    "converged": th.converged, "f_low": th.friction.coefficient[0], "f_high": th.friction.coefficient[-1],
                    "f_min": th.friction.coefficient.min(), "us_at_f_min": us[int(np.argmin(th.friction.coefficient))],
                    "mean_dT_high": th.friction.mean_temperature_rise[-1], "max_dT_high": th.friction.max_temperature_rise[-1],
                    "film_friction_ratio_thermal_over_iso_high": th.friction.film[-1] / iso.friction.film[-1],
                    "wall_s": th.wall_s,
                }
                d["thesis_temperature_rise"] = THESIS_DT.get(name)
                d["isothermal_second_path"] = second_path(sc, iso, [0, us.size // 2, us.size - 1])
                # the thermal path integrates over the Hertz profile: compare it with the
                # isothermal solve on the same profile to isolate the temperature effect
                d["thermal"]["film_ratio_thermal_over_isothermal_hertz_high"] = (
                    th.friction.film_force[-1] / d["isothermal_second_path"][-1]["hertz_profile_N"])
                ax.semilogx(us, th.friction.coefficient, "--", color=color, label=f"{name} thermal")
                if ax2 is None:
                    ax2 = ax.twinx()
                    ax2.set_ylabel("mean temperature rise [K]", color="g")
                ax2.semilogx(us, th.friction.mean_temperature_rise, ":", color=color)
            fig_out[name] = d
            print(name, {k: v for k, v in d.items() if k in ("iso", "thermal")})
        ax.set(xlabel="us [m/s]", ylabel="coefficient of friction", title=fig.replace("_", " ") + " (dotted: mean temperature rise)")
        ax.set_ylim(bottom=0)
        ax.legend(fontsize=7, loc="lower left")
        f.tight_layout()
        f.savefig(OUT / f"{fig}.png", dpi=100)
        p.close(f)
        out[fig] = fig_out
    out["wall_s"] = time.perf_counter() - t0
    out["quick"] = quick
    write_json("series_ad.json", out, quick)
    print(f"wall {out['wall_s']:.1f} s")
    return out


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true")
    main(ap.parse_args().quick)
