"""Isoviscous and low-L line solves with and without the film-scale switch (REPORT.md,
"Isoviscous fine grids"). ``old`` passes ``switch_eps=0`` (the relaxation as before the
switch), ``new`` the default. Plain solves ``solve_line(M, L, points=N, estimate=False)``;
writes ``build/validation/line_fine/iso_sweep.json`` and prints one line per case."""

from __future__ import annotations

import sys
from pathlib import Path

from tqdm import tqdm

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402
from study import plain_solve, save  # noqa: E402

CASES = [(M, 0.0, n) for M in (0.5, 1, 2, 3, 5, 7, 10, 20, 50, 100, 200, 500, 1000, 2000)
         for n in (1025, 2049, 4097, 8193, 16385)] + \
    [(M, L, n) for M in (5, 20, 100) for L in (0.5, 1, 2, 3, 5) for n in (2049, 4097, 8193, 16385)]


def main() -> None:
    out = {}
    path = out_dir("line_fine") / "iso_sweep.json"
    for M, L, n in tqdm(CASES):
        o, w = plain_solve(M, L, n, switch_eps=0.0), plain_solve(M, L, n)
        out[f"M={M:g} L={L:g} N={n}"] = {"old": o, "new": w}
        save(path, out)
        tqdm.write(f"({M:g}, {L:g}) {n:6d}  old {o['status']:10s} {o.get('cycles', 0):3d} "
                   f"{o.get('work_units', 0):6.0f} {o.get('wall_s', 0):5.1f}s  new {w['status']:10s} "
                   f"{w.get('cycles', 0):3d} {w.get('work_units', 0):6.0f} {w.get('wall_s', 0):5.1f}s  "
                   f"Hc {o.get('Hc', float('nan')):.5f} -> {w.get('Hc', float('nan')):.5f}")


if __name__ == "__main__":
    main()
