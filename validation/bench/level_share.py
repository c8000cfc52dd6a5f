"""Where a point solve spends its wall time, grid by grid, on one and on two threads: the share
that stays serial (grids below ``PointOptions.serial_below`` run one thread by design) and the
speed-up two threads can reach at most with it (Amdahl).

Each run is a fresh process: a warm-up on 65 points and one on the measured grid (numba cache,
kernel spectra), then one timed (20, 10) half-domain solve, Roelands + Dowson-Higginson, whose
hierarchy methods (relaxation, coarsest-grid solve, restriction, correction, FMG interpolation,
measurement) are timed per grid. An operation between two grids (restriction, correction)
counts toward the finer one; the rest of the wall time (the driver's Python) is "driver".
One and two threads alternate for ``--rounds`` rounds; medians are reported.

The bound: if every grid at or above ``serial_below`` ran ``--ceiling`` times faster on two
threads (1.9: what a kernel with nothing serial gains on this machine, ``thread_ceiling.py``)
and the rest as on one thread, the solve would gain ``1 / (s + (1 - s) / ceiling)``, where s
is the serial share of the one-thread time (those grids plus the driver).

    python validation/bench/level_share.py --points 513 1025 --rounds 3 [--label LABEL]

writes ``build/validation/bench/level_share_<label>.json`` and ``.md``.
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from outputs import write_study  # noqa: E402

OPS = ("relax", "coarse_solve", "restrict", "correct", "fmg_interpolate", "measure", "snapshot",
       "restore")


def child(points: int, threads: int) -> dict:
    """One timed solve in this process, its wall time split by grid."""
    from ehl_multigrid.multigrid.options import PointOptions
    from ehl_multigrid.point import fas, solve_point

    spent: dict[int, float] = collections.defaultdict(float)
    inside = [False]

    def timed(fn):
        def wrapper(self, *args, **kwargs):
            if inside[0]:
                return fn(self, *args, **kwargs)
            inside[0] = True
            t0 = time.perf_counter()
            try:
                return fn(self, *args, **kwargs)
            finally:
                inside[0] = False
                k = args[0] if args and isinstance(args[0], int) else None
                size = self.levels[k].npts if k is not None else -1
                spent[size] += time.perf_counter() - t0
        return wrapper

    for op in OPS:
        setattr(fas.PointHierarchy, op, timed(getattr(fas.PointHierarchy, op)))
    kw = {"half": True, "threads": threads, "estimate": False}
    solve_point(20.0, 10.0, points=65, **kw)
    solve_point(20.0, 10.0, points=points, **kw)
    spent.clear()
    t0 = time.perf_counter()
    res = solve_point(20.0, 10.0, points=points, **kw)
    wall = time.perf_counter() - t0
    grids = {str(n): t for n, t in sorted(spent.items()) if n > 0}
    return {"points": points, "threads": threads, "wall_s": wall, "grid_s": grids,
            "driver_s": wall - sum(grids.values()), "work_units": res.work_units,
            "Hc": res.Hc, "serial_below": PointOptions().serial_below}


def run(points: int, threads: int) -> dict:
    proc = subprocess.run([sys.executable, __file__, "--child", json.dumps([points, threads])],
                          capture_output=True, text=True, cwd="/")
    if proc.returncode != 0:
        raise RuntimeError(f"the {points}-point solve on {threads} thread(s) failed:\n"
                           f"{proc.stderr[-2000:]}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


def summarise(runs: list[dict], ceiling: float) -> dict:
    """Medians per grid for one and two threads, gains, serial share and the bound."""
    by = {t: [r for r in runs if r["threads"] == t] for t in (1, 2)}
    grids = sorted({int(n) for r in runs for n in r["grid_s"]})
    med = {t: {n: statistics.median(r["grid_s"][str(n)] for r in rs) for n in grids}
           for t, rs in by.items()}
    wall = {t: statistics.median(r["wall_s"] for r in rs) for t, rs in by.items()}
    driver = {t: statistics.median(r["driver_s"] for r in rs) for t, rs in by.items()}
    below = runs[0]["serial_below"]
    serial = sum(med[1][n] for n in grids if n < below) + driver[1]
    s = serial / wall[1]
    return {
        "grids": [{"npts": n, "one_s": med[1][n], "two_s": med[2][n],
                   "gain": med[1][n] / med[2][n], "share_one": med[1][n] / wall[1],
                   "serial": n < below} for n in grids],
        "driver": {"one_s": driver[1], "two_s": driver[2]},
        "wall": {"one_s": wall[1], "two_s": wall[2], "gain": wall[1] / wall[2]},
        "serial_share": s, "ceiling": ceiling, "bound": 1.0 / (s + (1.0 - s) / ceiling),
        "work_units": sorted({round(r["work_units"], 3) for r in runs}),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--child", help=argparse.SUPPRESS)
    ap.add_argument("--points", type=int, nargs="+", default=[513, 1025])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--ceiling", type=float, default=1.9)
    ap.add_argument("--label", default="level_share")
    a = ap.parse_args()
    if a.child:
        print(json.dumps(child(*json.loads(a.child))))
        return
    out = {"label": a.label, "rounds": a.rounds, "load_before": os.getloadavg(), "cases": []}
    lines = []
    for n in a.points:
        runs = []
        for _ in range(a.rounds):
            runs += [run(n, 1), run(n, 2)]
        summ = summarise(runs, a.ceiling)
        out["cases"].append({"points": n, "runs": runs, **summ})
        lines += [f"### {n}^2 half domain (median of {a.rounds})", "",
                  "| grid points | one thread [s] | two threads [s] | gain | share of one-thread wall |",
                  "|---|---|---|---|---|"]
        for g in summ["grids"]:
            tag = " (one thread by design)" if g["serial"] else ""
            lines.append(f"| {g['npts']}{tag} | {g['one_s']:.3f} | {g['two_s']:.3f} | "
                         f"{g['gain']:.2f} | {100 * g['share_one']:.1f} % |")
        d, w = summ["driver"], summ["wall"]
        lines += [f"| driver | {d['one_s']:.3f} | {d['two_s']:.3f} | {d['one_s'] / d['two_s']:.2f} | "
                  f"{100 * d['one_s'] / w['one_s']:.1f} % |",
                  f"| **whole solve** | {w['one_s']:.3f} | {w['two_s']:.3f} | **{w['gain']:.2f}** | |",
                  "", f"Serial share {100 * summ['serial_share']:.1f} %; with every other grid at "
                  f"{a.ceiling:g}x the solve could gain at most **{summ['bound']:.2f}x**. "
                  f"Work units {summ['work_units']}.", ""]
        print("\n".join(lines[-(len(summ['grids']) + 8):]), flush=True)
    out["load_after"] = os.getloadavg()
    lines.append(f"Load average before {out['load_before'][0]:.2f}, after {out['load_after'][0]:.2f}.")
    write_study(f"level_share_{a.label}", out, lines)


if __name__ == "__main__":
    main()
