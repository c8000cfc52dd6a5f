"""Isoviscous and low-L line solves with and without the film-scale switch (REPORT.md,
"Isoviscous fine grids"). ``old`` passes ``switch_eps=0`` (the relaxation as before the
switch), ``new`` the default. Plain solves ``solve_line(M, L, points=N, estimate=False)``;
writes ``out/iso_sweep.json`` and prints one line per case."""

from __future__ import annotations

import json
import time
from pathlib import Path

from ehl_multigrid.line import solve_line

CASES = [(M, 0.0, n) for M in (0.5, 1, 2, 3, 5, 7, 10, 20, 50, 100, 200, 500, 1000, 2000)
         for n in (1025, 2049, 4097, 8193, 16385)] + \
    [(M, L, n) for M in (5, 20, 100) for L in (0.5, 1, 2, 3, 5) for n in (2049, 4097, 8193, 16385)]


def run(M: float, L: float, n: int, **kw) -> dict:
    t = time.perf_counter()
    r = solve_line(M, L, points=n, estimate=False, raise_on_failure=False, **kw)
    return {"status": r.status_name, "cycles": r.cycles, "work_units": r.work_units, "Hc": r.Hc,
            "Hm": r.Hm, "wall_s": time.perf_counter() - t}


def main() -> None:
    out = {}
    for M, L, n in CASES:
        o, w = run(M, L, n, switch_eps=0.0), run(M, L, n)
        out[f"M={M:g} L={L:g} N={n}"] = {"old": o, "new": w}
        print(f"({M:g}, {L:g}) {n:6d}  old {o['status']:10s} {o['cycles']:3d} {o['work_units']:6.0f} "
              f"{o['wall_s']:5.1f}s  new {w['status']:10s} {w['cycles']:3d} {w['work_units']:6.0f} "
              f"{w['wall_s']:5.1f}s  Hc {o['Hc']:.5f} -> {w['Hc']:.5f}", flush=True)
    path = Path(__file__).parent / "out" / "iso_sweep.json"
    path.write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
