"""Cost of a 60-point Stribeck curve, isothermal and thermal, and of the GW kernels.

Run: ``python validation/mixed/cost.py [--quick]`` (``--quick`` skips the thermal curves).
Writes build/validation/mixed/cost.json. Wall times on this (shared, 2-core) machine; the first call of a
process also loads numba's cached kernels, so every timing is the best of ``repeat`` runs
after one warm-up.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import write_json  # noqa: E402

from ehl_multigrid.model.scene import load_scene  # noqa: E402
from mixed.film import johnson_film, separation_from_film  # noqa: E402
from mixed.gw import gw_f32  # noqa: E402
from mixed.sharing import load_sharing  # noqa: E402
from mixed.stribeck import stribeck_curve  # noqa: E402


def best_of(fn, repeat: int) -> float:
    fn()
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def main(quick: bool = False) -> dict:
    out: dict = {}
    lam = np.random.default_rng(1).uniform(-10, 8, 100_000)
    out["gw_f32_per_point_us"] = 1e6 * best_of(lambda: gw_f32(lam), 3) / lam.size
    hf = johnson_film(lam * 7e-8, 7e-8)
    out["film_inverse_per_point_us"] = 1e6 * best_of(lambda: separation_from_film(hf, 7e-8), 3) / lam.size
    for name, lo, hi in (("page63_line_2000N", 1e-3, 100.0), ("series_C_disc3_1.93GPa", 2e-3, 2.0),
                         ("series_C_disc3_1.93GPa", 1e-3, 100.0)):
        sc = load_scene(name)
        us = np.geomspace(lo, hi, 60)
        d = {
            "us_range": [lo, hi],
            "load_sharing_60pt_s": best_of(lambda sc=sc, us=us: load_sharing(sc, us), 5),
            "stribeck_isothermal_60pt_s": best_of(lambda sc=sc, us=us: stribeck_curve(sc, us), 3),
            "stribeck_isothermal_60pt_no_transitions_s": best_of(lambda sc=sc, us=us: stribeck_curve(sc, us, transitions=False), 3),
        }
        if not quick:
            t = time.perf_counter()
            c = stribeck_curve(sc, us, thermal=True, transitions=False)
            d["stribeck_thermal_60pt_s"] = time.perf_counter() - t
            d["thermal_points_solved"] = int(np.sum(c.friction.thermal_used))
            d["thermal_converged"] = c.converged
            d["thermal_messages"] = c.friction.thermal_messages
            d["max_mean_temperature_rise_K"] = float(np.nanmax(c.friction.mean_temperature_rise))
        out[f"{name}_{lo:g}-{hi:g}"] = d
        print(name, d)
    print({k: v for k, v in out.items() if not isinstance(v, dict)})
    write_json("cost.json", out, quick)
    return out


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true")
    main(ap.parse_args().quick)
