"""Before/after study of the line solver's fine-grid stalls (validation/line_fine/REPORT.md).

Plain solves (``solve_line(M, L, points=N, estimate=False)``) of the fit map's failing
fine-grid solves (validation/extremes, accuracy 0.01) and of a regression set of solves that
converged before. Usage: ``python study.py TAG`` writes ``build/validation/line_fine/TAG.json``; run it once with the
old code on PYTHONPATH (TAG = before) and once with the current code (TAG = after).
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

from tqdm import tqdm

import ehl_multigrid
from ehl_multigrid.line import solve_line

R, B = "roelands", "barus"
#: the fit map's failing fine-grid solves (task list) and the switch_h = 1 losses of its REPORT
LISTED = [(R, 100, 0, 4097), (B, 20, 20, 4097), (B, 100, 0, 4097), (B, 100, 10, 8193),
          (B, 100, 20, 2049), (B, 500, 0, 8193), (B, 500, 20, 8193), (B, 1000, 20, 16385),
          (R, 100, 20, 4097), (R, 500, 0, 8193), (R, 20, 0, 8193), (B, 20, 10, 4097),
          (B, 1000, 10, 32769), (B, 500, 10, 8193), (B, 20, 10, 8193), (B, 100, 20, 4097),
          (B, 1000, 0, 16385), (R, 1000, 0, 16385), (R, 1000, 20, 16385), (R, 500, 20, 8193),
          (B, 20, 0, 8193)]
#: solves that converged before: the fit map's converged cases at their accuracy-chosen grid
#: and grid sequences of (20, 10) and (1000, 10), Roelands
REGRESSION = [(R, 20, 10, n) for n in (1025, 2049, 4097, 8193, 16385)] + \
    [(R, 1000, 10, n) for n in (4097, 8193, 16385)] + [
    (B, 5, 0, 1025), (B, 5, 5, 1025), (B, 5, 10, 1025), (B, 5, 20, 1025),
    (R, 5, 0, 1025), (R, 5, 5, 1025), (R, 5, 10, 1025), (R, 5, 20, 1025),
    (B, 20, 0, 4097), (B, 20, 5, 1025), (B, 20, 10, 2049), (R, 20, 0, 4097), (R, 20, 5, 1025),
    (R, 20, 20, 2049), (R, 20, 20, 4097), (B, 100, 5, 2049), (B, 100, 5, 4097),
    (R, 100, 5, 2049), (R, 100, 10, 2049), (R, 100, 10, 4097), (B, 500, 5, 8193),
    (R, 500, 5, 8193), (R, 500, 10, 16385), (B, 1000, 5, 32769), (R, 1000, 5, 32769),
    (R, 1000, 10, 32769), (B, 1000, 10, 16385)]


def plain_solve(M: float, L: float, n: int, **kw) -> dict:
    """One plain solve ``solve_line(M, L, points=n, estimate=False, **kw)`` as a record (an
    exception is a result of the study too)."""
    t = time.perf_counter()
    try:
        r = solve_line(M, L, points=n, estimate=False, raise_on_failure=False, **kw)
    except Exception as exc:  # noqa: BLE001
        return {"status": "error", "message": str(exc)[:200]}
    return {"status": r.status_name, "message": r.message, "cycles": r.cycles,
            "work_units": r.work_units, "Hc": r.Hc, "Hm": r.Hm,
            "residual": float(r.residual_history[-1]) if len(r.residual_history) else None,
            "load_error": float(r.load_error_history[-1]) if len(r.load_error_history) else None,
            "wall_s": time.perf_counter() - t, "actions": r.actions}


def save(path: Path, data: dict) -> None:
    """Write ``data`` whole (temporary file, then rename): an interrupted study keeps the
    cases it finished."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(data, indent=1))
    tmp.replace(path)


def run(case: tuple) -> dict:
    visc, M, L, n = case
    kw = {} if visc == R else {"viscosity": "barus", "density": "incompressible"}
    return plain_solve(M, L, n, **kw)


def main() -> None:
    tag = sys.argv[1]
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from _paths import out_dir

    out = out_dir("line_fine")
    res = {"code": str(Path(ehl_multigrid.__file__).parent), "cases": {}}
    seen = set()
    cases = [("listed", c) for c in LISTED] + [("regression", c) for c in REGRESSION]
    for group, c in tqdm(cases):
        if c in seen:
            continue
        seen.add(c)
        res["cases"][f"{c[0]} M={c[1]} L={c[2]} N={c[3]}"] = {"group": group, **run(c)}
        save(out / f"{tag}.json", res)


if __name__ == "__main__":
    main()
