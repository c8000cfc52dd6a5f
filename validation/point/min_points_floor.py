"""Is the grid floor of contacts long in the rolling direction still needed on stretched cells?

:func:`~ehl_multigrid.point.problem.min_points` multiplies the floor (129 / 257 / 513 points by
M) by ``2^ceil(log2(0.75 a/b))`` for b/a < 0.75, a rule measured on square cells (on which b has
b/a times the cells of a). The point solver's cells stretch with the ellipse, so b has as many
cells as a on every grid. This study solves Roelands + Dowson-Higginson contacts at theta 4 and
10 (b/a 0.40 and 0.22) plainly (``estimate=False``, default box and cells) on the floor without
the multiplier, twice that, and the floor with it, and records status, films, work units and
wall time (one thread).

    NUMBA_NUM_THREADS=1 python validation/point/min_points_floor.py

Writes ``build/validation/point/min_points_floor.json``.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

from tqdm import tqdm

from ehl_multigrid.point import solve_point
from ehl_multigrid.point.problem import min_points, problem_from_moes

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("point") / "min_points_floor.json"


def main() -> None:
    todo = []
    for theta in (4.0, 10.0):
        for M in (10.0, 100.0, 500.0, 1000.0):
            for L in (0.0, 10.0, 20.0):
                pb = problem_from_moes(M, L, theta, "roelands", "dowson-higginson", None, None, None)
                base = 129 if M < 200 else (257 if M < 1000 else 513)
                floor = min_points(M, pb.b_over_a)
                todo += [(theta, M, L, n, floor) for n in sorted({base, 2 * (base - 1) + 1, floor})]
    rows = []
    for theta, M, L, n, floor in tqdm(todo):
        t = time.perf_counter()
        s = solve_point(M, L, theta=theta, points=n, estimate=False, raise_on_failure=False)
        rows.append({"theta": theta, "M": M, "L": L, "points": n, "min_points": floor,
                     "status": s.status_name, "Hc": s.scalars.get("Hc"), "Hm": s.scalars.get("Hm"),
                     "work_units": s.work_units, "wall_s": time.perf_counter() - t})
        # after every solve: an interrupted run keeps what it finished
        tmp = OUT.with_suffix(".tmp")
        tmp.write_text(json.dumps(rows, indent=1, default=float))
        tmp.replace(OUT)
    below = [r for r in rows if r["points"] < r["min_points"]]
    print(f"{len(below)} solves below the floor: "
          f"{sum(r['status'] == 'converged' for r in below)} converged; at the floor: "
          f"{sum(r['status'] == 'converged' for r in rows if r['points'] == r['min_points'])} of "
          f"{sum(r['points'] == r['min_points'] for r in rows)}")


if __name__ == "__main__":
    main()
