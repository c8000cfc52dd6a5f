"""Thesis chapter 6: Stribeck curves of starved point contacts (Figs 6.2-6.7) and varsigma (6.4).

Run: ``python validation/mixed/chapter6.py [--quick]``. Writes build/validation/mixed/chapter6.json and
fig6_2.png ... fig6_7.png. Isothermal, as in the thesis; delta = 3.5.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import out_dir, write_json  # noqa: E402

from ehl_multigrid.model.scene import load_scene  # noqa: E402
from mixed.plots import plot_cases  # noqa: E402
from mixed.starvation import limiting_inlet_film, limiting_inlet_film_for_roughness  # noqa: E402
from mixed.stribeck import stribeck_curve  # noqa: E402

CASES = {
    "chapter6_starved_1.93GPa": ((0.1, 0.5, 1.0, 2.0, 3.0, 6.0, math.inf), ("fig6_2", "fig6_3", "fig6_4")),
    "chapter6_starved_0.5GPa": ((0.5, 0.8, 1.0, 1.5, 2.0, 3.0, 6.0, math.inf), ("fig6_5", "fig6_6", "fig6_7")),
}
THESIS = {
    "chapter6_starved_1.93GPa": "hoil = 0.1 sigma: constant boundary friction; lowest friction near 8 m/s (0.5 sigma) and "
    "16 m/s (1 sigma); hoil = 6 sigma equals flooded below 100 m/s; varsigma = 0.10",
    "chapter6_starved_0.5GPa": "hoil = 0.5 sigma stays at boundary friction (insufficient oil); friction much lower than at "
    "1.93 GPa; varsigma = 0.46",
}


def main(quick: bool = False) -> dict:
    t0 = time.perf_counter()
    OUT = out_dir(quick)
    us = np.geomspace(0.01, 100.0, 25 if quick else 80)
    out: dict = {"us_range": [us[0], us[-1], us.size], "delta": 3.5}
    for name, (hoils, figs) in CASES.items():
        sc = load_scene(name)
        r = sc.roughness
        hz = sc.hertz
        curves = [stribeck_curve(sc, us, hoil=h * r.Rq) for h in hoils]
        flooded = curves[-1]
        rows = {}
        for h, c in zip(hoils, curves, strict=True):
            f = c.friction.coefficient
            k = int(np.argmin(f))
            departs = np.flatnonzero(c.sharing.hfr < 0.95 * flooded.sharing.hfr)
            rows[str(h)] = {
                "f_at_0.01": f[0], "f_at_100": f[-1], "f_min": f[k], "us_at_f_min": us[k],
                "boundary_points": int(c.sharing.boundary.sum()), "all_boundary": bool(np.all(c.sharing.boundary)),
                "hfr_at_100_over_sigma": c.sharing.hfr[-1] / r.Rq,
                "hoil_over_rho_bar_over_sigma": (h / (1 + 0.34615 * hz.pmax / (0.59263e9 + hz.pmax))) if math.isfinite(h) else None,
                "hs_at_0.01_over_sigma": c.sharing.hs[0] / r.Rq,
                "film_5pct_below_flooded_from_us": us[departs[0]] if departs.size else None,
                "max_rel_diff_f_vs_flooded_below_100": float(np.max(np.abs(f / flooded.friction.coefficient - 1))),
                **c.transitions,
            }
        exact_scene = limiting_inlet_film_for_roughness(sc.load, hz.area, hz.pmax, sc.E_reduced, r.Rq, r.sigma_s, r.dd, r.n, r.beta)
        thesis_params = limiting_inlet_film(hz.pmax)
        out[name] = {
            "pmax_GPa": hz.pmax / 1e9, "load": sc.load, "hs_min_over_sigma": flooded.sharing.hs_min / r.Rq,
            "curves": rows,
            "varsigma_thesis_parameters": thesis_params.to_dict(),
            "varsigma_scene_roughness": exact_scene.to_dict(),
            "thesis": THESIS[name],
        }
        plot_cases(curves, OUT / f"{figs[0]}.png", "friction", "coefficient of friction", f"{figs[0]}: {name}")
        plot_cases(curves, OUT / f"{figs[1]}.png", "hfr", "film thickness hf,r [m]", f"{figs[1]}: {name}")
        plot_cases(curves, OUT / f"{figs[2]}.png", "hs", "separation hs [m]", f"{figs[2]}: {name}")
        print(name)
        for h, v in rows.items():
            print(f"  hoil/sigma={h:>4}: f(0.01)={v['f_at_0.01']:.4f} fmin={v['f_min']:.4f} at {v['us_at_f_min']:.3g} "
                  f"f(100)={v['f_at_100']:.4f} BL pts={v['boundary_points']} hfr(100)/sigma={v['hfr_at_100_over_sigma']:.3f}")
        tp = thesis_params
        print(f"  varsigma (thesis parameters): exact {tp.varsigma_exact:.4f}, approx {tp.varsigma_approx:.4f}, diff {tp.difference:.4f}")
        es = exact_scene
        print(f"  varsigma (scene roughness):   exact {es.varsigma_exact:.4f}, approx {es.varsigma_approx:.4f}, "
              f"rho_bar*exact {es.varsigma_compressed:.4f}")
    out["wall_s"] = time.perf_counter() - t0
    write_json("chapter6.json", out, quick)
    print(f"wall {out['wall_s']:.1f} s")
    return out


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true")
    main(ap.parse_args().quick)
