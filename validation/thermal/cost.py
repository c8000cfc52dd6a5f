"""Validation 5: cost. Wall time of a 21-point traction curve for appendix C at nx = 80,
nz = 20 (thermal and isothermal, Hertz and EHL input), of film_friction calls (the Stribeck
use), and how the time of one slip point grows with nx * nz.

Run: python validation/thermal/cost.py [--quick]     (about 1 min; timings depend on machine load)
"""

from __future__ import annotations

import os
import time

import numpy as np
from common import OUT, ehl_line_result, plt, quick_flag, write_json

from ehl_multigrid.model.scene import load_scene
from thermal import film_friction, solve_traction, traction_curve


def timed(fn, repeat: int = 1) -> float:
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return best


def main() -> None:
    quick = quick_flag()
    sc_hi = load_scene("appendix_c_line_42400N")
    sc_lo = load_scene("appendix_c_line_4240N")
    pt = load_scene("appendix_d_point")
    solve_traction(sc_hi, 0.3)  # load the compiled kernels (numba cache) before timing
    slips = list(np.linspace(0, 1, 21))
    curves = {}
    for label, sc, kw in (("appendix_c_42400N thermal hertz", sc_hi, {}), ("appendix_c_42400N isothermal", sc_hi, {"thermal": False}),
                          ("appendix_c_4240N thermal hertz", sc_lo, {}),
                          ("appendix_d_point thermal (10 slices)", pt, {})):
        t = time.perf_counter()
        pts = traction_curve(sc, slips, nx=80, nz=20, **kw)
        curves[label] = {"wall_s": time.perf_counter() - t, "points": len(pts), "converged": all(p.converged for p in pts),
                         "max_sweeps": max(p.report.iterations for p in pts)}
    ehl = ehl_line_result(sc_hi)
    if ehl is not None:
        t = time.perf_counter()
        pts = traction_curve(sc_hi, slips, nx=80, nz=20, input="ehl", ehl=ehl)
        curves["appendix_c_42400N thermal EHL input"] = {"wall_s": time.perf_counter() - t, "points": 21,
                                                          "converged": all(p.converged for p in pts),
                                                          "max_sweeps": max(p.report.iterations for p in pts)}
    # film_friction as the mixed layer calls it: 60 calls over a speed range
    us = np.geomspace(0.05, 10, 12 if quick else 60)
    calls = {}
    for label, sc in (("line appendix_c_4240N", sc_lo), ("point appendix_d (10 slices)", pt)):
        t = time.perf_counter()
        for u in us:
            h = sc.central_film_fit(u)[1]
            film_friction(sc, load=sc.load, h=h, us=float(u), slip=0.02)
        dt = time.perf_counter() - t
        calls[label] = {"calls": len(us), "wall_s": dt, "per_call_s": dt / len(us)}
    # scaling with nx * nz (one slip point, S = 0.4)
    grid = []
    nxs = [40, 80, 160] if quick else [40, 80, 160, 320, 640]
    nzs = [10, 20, 40] if quick else [10, 20, 40, 80]
    for nx in nxs:
        for nz in nzs:
            w = timed(lambda nx=nx, nz=nz: solve_traction(sc_hi, 0.4, nx=nx, nz=nz), repeat=2)
            grid.append({"nx": nx, "nz": nz, "cells": nx * nz, "wall_s": w})
    n = np.array([g["cells"] for g in grid], dtype=float)
    w = np.array([g["wall_s"] for g in grid])
    big = n >= 1600
    slope = float(np.polyfit(np.log(n[big]), np.log(w[big]), 1)[0])
    nx_arr = np.array([g["nx"] for g in grid], dtype=float)
    nz_arr = np.array([g["nz"] for g in grid], dtype=float)
    A = np.column_stack([np.ones(big.sum()), np.log(nx_arr[big]), np.log(nz_arr[big])])
    coef = np.linalg.lstsq(A, np.log(w[big]), rcond=None)[0]
    out = {"machine": {"cpus": os.cpu_count(), "load_avg": os.getloadavg()}, "curves_21_points": curves,
           "film_friction": calls, "grid_scaling": grid,
           "exponent_in_nx_nz": slope, "exponent_nx": float(coef[1]), "exponent_nz": float(coef[2])}
    write_json("cost.json", out)
    fig, ax = plt().subplots(figsize=(5.5, 3.8))
    for nz in nzs:
        sel = [g for g in grid if g["nz"] == nz]
        ax.loglog([g["cells"] for g in sel], [g["wall_s"] for g in sel], "o-", label=f"nz = {nz}")
    ax.set_xlabel("nx * nz")
    ax.set_ylabel("wall time of one slip point [s]")
    ax.set_title(f"appendix C 42400 N, S = 0.4: time ~ nx^{coef[1]:.2f} nz^{coef[2]:.2f}", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(OUT / "cost_scaling.png", dpi=100)
    for k, v in curves.items():
        print(f"{k:40s} 21 points: {v['wall_s']:.2f} s")
    for k, v in calls.items():
        print(f"film_friction {k}: {v['per_call_s'] * 1e3:.1f} ms per call")
    print(f"time ~ (nx nz)^{slope:.2f}; nx^{coef[1]:.2f} nz^{coef[2]:.2f}")


if __name__ == "__main__":
    main()
