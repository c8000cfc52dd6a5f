"""Robustness screen of the point solver's cycle type: every point case of the extremes matrix
and of the fit-check map (validation/extremes/accuracy_map.py) solved on one fixed grid (257
points, or the solver's smallest grid for the load, at most 513; half domain, default box and
tolerances) with W cycles and with F cycles. Writes ``build/validation/bench/<label>.json`` (default
``cycle_screen``) with status, work units, wall time and films per case and cycle type.

    python validation/bench/cycle_screen.py [--quick] [--label NAME]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from tqdm import tqdm

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "extremes"))
from accuracy_map import cases, fit_cases  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("bench")


def run(case: dict, cycle: str, points: int) -> dict:
    from ehl_multigrid.point import solve_point

    model = {k: case[k] for k in ("viscosity", "density") if k in case}
    t0 = time.perf_counter()
    try:
        s = solve_point(case["M"], case["L"], theta=case["theta"], points=points, half=True,
                        cycle=cycle, estimate=False, raise_on_failure=False, **model)
    except Exception as exc:  # a clear error is an outcome
        return {"status": "error", "message": f"{type(exc).__name__}: {exc}".splitlines()[0]}
    return {"status": s.status_name, "WU": s.work_units, "wall_s": time.perf_counter() - t0,
            "cycles": s.cycles, "Hc": s.scalars.get("Hc"), "Hm": s.scalars.get("Hm"),
            "actions": list(s.actions)}


def main() -> None:
    from ehl_multigrid.point.problem import min_points, problem_from_moes

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--label", default="cycle_screen", help="output file stem under build/validation/bench/")
    a = ap.parse_args()
    todo = [c for c in cases(a.quick) if c["contact"] == "point"]
    todo += [c for c in fit_cases(a.quick) if c["contact"] == "point"]
    OUT.mkdir(exist_ok=True)
    rows = []
    for c in tqdm(todo, desc="cases"):
        pb = problem_from_moes(c["M"], c["L"], c["theta"])
        n = min(max(257, min_points(c["M"], pb.b_over_a)), 513)
        rows.append({**c, "points": n, "W": run(c, "W", n), "F": run(c, "F", n)})
        (OUT / f"{a.label}.json").write_text(json.dumps(rows, indent=1))
    ok = {k: sum(r[k]["status"] == "converged" for r in rows) for k in ("W", "F")}
    both = [r for r in rows if r["W"]["status"] == r["F"]["status"] == "converged"]
    wu = sum(r["F"]["WU"] for r in both) / max(sum(r["W"]["WU"] for r in both), 1e-300)
    wall = sum(r["F"]["wall_s"] for r in both) / max(sum(r["W"]["wall_s"] for r in both), 1e-300)
    print(f"{len(rows)} cases: converged W {ok['W']}, F {ok['F']}; on the {len(both)} both "
          f"converge, F/W work units {wu:.2f}, wall {wall:.2f}")
    for r in rows:
        if r["W"]["status"] != r["F"]["status"]:
            print(r["M"], r["L"], r["theta"], r.get("viscosity", ""), r["points"], "W", r["W"]["status"],
                  "F", r["F"]["status"])


if __name__ == "__main__":
    main()
