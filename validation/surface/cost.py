"""Validation 4: cost of analysing a 1024 x 1024 height map (wall time, best of --repeat).

Steps timed separately: reading (.npy and CSV text), NaN fill (1 % missing), plane removal,
summits + statistics, one 3x3 low-pass pass, one ISO Gaussian low-pass, a whole
filter-until-psi study, and the `ehl surface` command end to end (a new Python process,
PNG included). Writes build/validation/surface/cost.json.

    python validation/surface/cost.py [--quick]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from mixed.surface import (
    HeightMap,
    filter_until_psi,
    find_summits,
    gaussian_lowpass,
    gaussian_random_surface,
    handle_missing,
    lowpass_3x3,
    read_height_map,
    remove_plane,
    surface_statistics,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("surface")


def best(fn, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        res = fn()
        times.append(time.perf_counter() - t0)
    return min(times), res


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="one repeat")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    rep = 1 if args.quick else args.repeat
    n = 1024
    OUT.mkdir(parents=True, exist_ok=True)
    hm = gaussian_random_surface(n, 0.781e-6, 0.19e-6, hurst=0.8, rolloff=50e-6, seed=5)
    rows = {}
    with tempfile.TemporaryDirectory() as td:
        npy = Path(td) / "map.npy"
        csv = Path(td) / "map.csv"
        np.save(npy, hm.z * 1e6)
        np.savetxt(csv, hm.z * 1e6, delimiter=",", fmt="%.5f")
        rows["read_npy"], _ = best(lambda: read_height_map(npy, dx="0.781um", units="um"), rep)
        rows["read_csv"], raw = best(lambda: read_height_map(csv, dx="0.781um", units="um"), 1)
        holes = hm.z.copy()
        rng = np.random.default_rng(0)
        holes.flat[rng.choice(holes.size, holes.size // 100, replace=False)] = np.nan
        hmn = HeightMap(holes, hm.dx, hm.dy)
        rows["fill_1pct_missing"], _ = best(lambda: handle_missing(hmn, "fill"), rep)
        rows["plane_removal"], lev = best(lambda: remove_plane(raw), rep)
        rows["summits"], _ = best(lambda: find_summits(lev), rep)
        rows["statistics_total"], st = best(lambda: surface_statistics(lev), rep)
        rows["lowpass_one_pass"], _ = best(lambda: lowpass_3x3(lev, 1), rep)
        rows["gaussian_lowpass"], _ = best(lambda: gaussian_lowpass(lev, 10e-6), rep)
        rows["filter_until_psi_lowpass"], study = best(lambda: filter_until_psi(lev, 1.0, "lowpass"), 1)
        env = {**os.environ, "MPLBACKEND": "Agg"}
        cmd = [sys.executable, "-m", "ehl_multigrid", "surface", str(npy), "--dx", "0.781um", "--units", "um",
               "--json", "--out", str(Path(td) / "o")]
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
        rows["cli_end_to_end_with_png"] = time.perf_counter() - t0
        if proc.returncode:
            print(proc.stderr)
    for k, v in rows.items():
        print(f"{k:<28} {v:8.3f} s")
    print(f"summits {st.n_summits}, until-psi steps {len(study.steps)} (psi {study.steps[0].stats.psi:.3g} -> "
          f"{study.result.stats.psi:.3g})")
    out = {"grid": [n, n], "repeat": rep, "wall_s": rows, "n_summits": st.n_summits,
           "until_psi_steps": len(study.steps), "machine": {"python": platform.python_version(),
                                                             "cpus": os.cpu_count()}}
    (OUT / "cost.json").write_text(json.dumps(out, separators=(",", ":")))


if __name__ == "__main__":
    main()
