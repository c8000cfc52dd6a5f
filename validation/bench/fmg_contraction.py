"""Why FMG with one cycle per level misses the discretisation error on the finest grids: the
finest-grid cycle's contraction of the Hc error, per grid, against what textbook FMG needs.

For circular (M, L) = (20, 10), Roelands + Dowson-Higginson, half domain, one thread, the
default F(2,1) cycle: FMG with one cycle per level, then k = 1, 2, 3 more finest-grid cycles
(``max_cycles=k``, tolerances out of reach, no grid rule, no adaptation: the same iteration each
time, stopped after k cycles). The algebraic error after each is ``|Hc - Hc_deep|`` against the
deep solve of the same grid, read from ``fmg_textbook.py``'s JSON (its deep solves, and the
Richardson limit of their three finest grids). Reported per grid:

* the algebraic error after FMG and after each further cycle, and their ratios (the cycle's
  contraction of the Hc error, until the deep solve's own jitter, about 1e-6 relative, is reached);
* the grid's discretisation error and its ratio to the next coarser grid's.

FMG with one cycle per level reaches the discretisation error on grid n when the cycle's
contraction rho satisfies roughly ``rho (E(n/2) + A(n/2)) <= E(n)``, where E is the
discretisation error and A the algebraic error left on the coarser grid.
So rho must stay below ``E(n) / (E(n/2) + A(n/2))``, the "needed" column.

    python validation/bench/fmg_contraction.py --points 513 1025 2049 --label fmg_contraction

writes ``build/validation/bench/<label>.json`` and ``.md``.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))
from _paths import require  # noqa: E402
from outputs import OUT, write_study  # noqa: E402


def errors_after_cycles(case: dict, points: int, hc_deep: float, extra: int) -> list[dict]:
    """Hc and WU after FMG (one cycle per level) and after 1..extra more finest-grid cycles, for
    the reference's ``case`` (M, L, theta)."""
    from ehl_multigrid.point import solve_point

    rows = []
    for k in range(extra + 1):
        s = solve_point(case["M"], case["L"], theta=case["theta"], points=points, half=True,
                        threads=1, estimate=False, raise_on_failure=False, cycles=1, max_cycles=k, adapt=False, tol=1e-14,
                        tol_load=1e-14, grid_stop=None)
        rows.append({"extra_cycles": k, "WU": s.work_units, "Hc": s.scalars["Hc"],
                     "error": abs(s.scalars["Hc"] - hc_deep)})
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--points", type=int, nargs="+", default=[513, 1025, 2049])
    ap.add_argument("--extra", type=int, default=3, help="finest-grid cycles after FMG")
    ap.add_argument("--reference", default=str(OUT / "fmg_textbook.json"),
                    help="fmg_textbook.py JSON with the deep solves")
    ap.add_argument("--label", default="fmg_contraction")
    a = ap.parse_args()
    os.environ.setdefault("NUMBA_NUM_THREADS", "1")
    import fmg_textbook

    ref = json.loads(require(Path(a.reference), "python validation/bench/fmg_textbook.py").read_text())
    deep = {int(n): r for n, r in ref["deep"].items()
            if r["status"] in ("converged", "residual_floor")}
    limit, order = fmg_textbook.limit(deep, "Hc")
    out = {"reference": a.reference, "reference_commit": ref["commit"], "case": ref["case"],
           "limit_Hc": limit,
           "order_Hc": order, "grids": {}}
    lines = [f"Hc limit {limit:.7f} (order {order:.2f}) from the deep solves of {a.reference} "
             f"(commit {ref['commit']}); errors absolute (Hc about 4.16)", "",
             "| grid | E: grid error | E(n/2) / E(n) | A after FMG (A / E) | after +1, +2, +3 cycles | "
             "contraction per cycle | needed |",
             "|---|---|---|---|---|---|---|"]
    previous = None
    for n in sorted(a.points):
        grid_err = abs(deep[n]["Hc"] - limit)
        rows = errors_after_cycles(ref["case"], n, deep[n]["Hc"], a.extra)
        errs = [r["error"] for r in rows]
        rho = [errs[i + 1] / errs[i] for i in range(len(errs) - 1) if errs[i] > 0]
        coarse = abs(deep[n // 2 + 1]["Hc"] - limit) if n // 2 + 1 in deep else None
        a_coarse = previous["rows"][0]["error"] if previous and previous["points"] == n // 2 + 1 else None
        needed = grid_err / (coarse + a_coarse) if coarse is not None and a_coarse is not None else None
        rec = {"points": n, "grid_error": grid_err, "coarse_grid_error": coarse, "rows": rows,
               "contraction": rho, "needed": needed}
        out["grids"][str(n)] = rec
        previous = rec
        lines.append(
            f"| {n} | {grid_err:.2e} | {'-' if coarse is None else f'{coarse / grid_err:.1f}'} | "
            f"{errs[0]:.2e} ({errs[0] / grid_err:.2f}) | {', '.join(f'{e:.1e}' for e in errs[1:])} | "
            f"{', '.join(f'{r:.2f}' for r in rho)} | {'-' if needed is None else f'{needed:.2f}'} |")
        print(lines[-1], flush=True)
    write_study(a.label, out, lines)


if __name__ == "__main__":
    main()
