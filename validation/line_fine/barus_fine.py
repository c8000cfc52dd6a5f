"""Barus + incompressible fine grids with and without the local Newton solve after the
pre-relaxations (line/solver.py ``LOCAL_NEWTON_PRE_ALPHA``; REPORT.md "Barus fine grids").

``off`` sets ``LOCAL_NEWTON_PRE_ALPHA`` to infinity (the solver as before), ``on`` keeps the
default. Plain solves ``solve_line(M, L, points=N, estimate=False)`` of the three listed cases
at tol 1e-8 / tol_load 1e-9 and at the default tolerance, and of a scan of M = 50-1000,
L = 10-30 on 4097 and 8193 points plus some 16385/32769-point cases (all alpha_bar > 20) at the
default tolerance. Writes ``build/validation/line_fine/barus_fine.json`` and prints one line per solve.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

from tqdm import tqdm

import ehl_multigrid.line.solver as line_solver_module

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402
from study import plain_solve, save  # noqa: E402

BARUS = {"viscosity": "barus", "density": "incompressible"}
DEEP = {"tol": 1e-8, "tol_load": 1e-9, "max_cycles": 200}
LISTED = [(100, 20, 16385), (500, 20, 65537), (5, 5, 4097)]
SCAN = [(M, L, n) for M in (50, 100, 200, 500, 1000) for L in (10, 15, 20, 25, 30)
        for n in (4097, 8193)] + [
    (20, 20, 8193), (20, 20, 16385), (20, 30, 8193), (20, 30, 16385), (20, 15, 16385),
    (50, 10, 16385), (50, 15, 16385), (50, 20, 16385), (100, 10, 16385), (100, 15, 16385),
    (200, 10, 16385), (100, 20, 32769)]


def main() -> None:
    default = line_solver_module.LOCAL_NEWTON_PRE_ALPHA
    out: dict[str, dict] = {}
    path = out_dir("line_fine") / "barus_fine.json"
    jobs = [(c, "tol 1e-8", DEEP) for c in LISTED] + [(c, "default", {}) for c in LISTED] + \
        [(c, "default", {}) for c in SCAN]
    for (M, L, n), tag, kw in tqdm(jobs):
        row = {}
        try:
            for mode, alpha in (("off", math.inf), ("on", default)):
                line_solver_module.LOCAL_NEWTON_PRE_ALPHA = alpha
                row[mode] = plain_solve(M, L, n, **BARUS, **kw)
        finally:
            line_solver_module.LOCAL_NEWTON_PRE_ALPHA = default
        out[f"M={M} L={L} N={n} {tag}"] = row
        save(path, out)
        o, w = row["off"], row["on"]
        nan = float("nan")
        tqdm.write(f"({M}, {L}) {n:6d} {tag:8s} off {o['status']:10s} {o.get('cycles', 0):3d} "
                   f"{o.get('work_units', 0):6.1f} {o.get('wall_s', 0):5.1f}s  on {w['status']:10s} "
                   f"{w.get('cycles', 0):3d} {w.get('work_units', 0):6.1f} {w.get('wall_s', 0):5.1f}s  "
                   f"Hc {o.get('Hc', nan):.6f} -> {w.get('Hc', nan):.6f}  "
                   f"Hm {o.get('Hm', nan):.6f} -> {w.get('Hm', nan):.6f}")


if __name__ == "__main__":
    main()
