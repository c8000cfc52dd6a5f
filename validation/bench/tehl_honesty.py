"""Thermal EHL line answers against finer nested solves: is the stated error of each film
within it? (issue "Converged means right" for the TEHL accuracy loop.)

For each built-in line scene and slip, `ehl_multigrid.solve(scene, physics="thermal",
accuracy=a)` gives the answer (its grid, nz and box). The reference is a nested chain of
fixed-grid solves on the answer's box and nz (`thermal.tehl.line.solve_tehl_line(...,
coarse=...)`), from a quarter of the answer's points to four times them (at most `--max-points`).
Its finest three films give the reference: extrapolated at the observed order when the ratio of
their differences lies in 2.5-6 (second order, as the answer's Hc is), else the finest film
with its last difference as its uncertainty. A film is *within its estimate* when
`|answer - reference| <= stated * answer + reference uncertainty`; the reference's own
uncertainty is listed beside. The box and nz are the answer's: their parts are not checked here.
T_max (degC) is checked the same way, in kelvin, against its stated `T_max_error_K`; a T_max whose
error the answer states as unknown (not grid-converged) is counted apart.

    python validation/bench/tehl_honesty.py --label NAME [--accuracies 0.02 0.005] [--max-points 8193]
        [--cases appendix_c_line_4240N:0 spur_gear_pitch_point]

writes build/validation/bench/tehl_honesty_NAME.json (after every case).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path
from typing import Any

# this folder's thermal.py (the traction benchmark) would shadow the thermal package
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != Path(__file__).resolve().parent]
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = Path(out_dir("bench"))
CASES = (("appendix_c_line_4240N", None), ("appendix_c_line_42400N", None), ("page63_line_2000N", None),
         ("roller_bearing_inner_race", None), ("roller_bearing_inner_race", 1.0),
         ("spur_gear_pitch_point", None), ("spur_gear_pitch_point", 0.5), ("spur_gear_pitch_point", 1.0),
         ("appendix_c_line_42400N", 1.0), ("page63_line_500N", 2.0))


def reference(films: list[tuple[int, float]]) -> tuple[float, float, str]:
    """``(value, uncertainty, how)`` of the limit of nested films ``[(points, film), ...]``."""
    (_, a), (_, b), (_, c) = films[-3:]
    d1, d2 = b - a, c - b
    if d2 != 0.0 and 2.5 <= d1 / d2 <= 6.0:
        r = d1 / d2
        tail = d2 / (r - 1.0)
        # the extrapolation's own error: at most the change a ratio of 4 would give instead
        return c + tail, abs(tail - d2 / 3.0), f"extrapolated (ratio {r:.2f})"
    return c, abs(d2), f"finest film (ratio {d1 / d2 if d2 else math.nan:.2f})"


def chain(scene: Any, slip: float, points: int, nz: int, box: float, max_points: int) -> list[dict[str, Any]]:
    from ehl_multigrid.model.errors import ConvergenceError
    from thermal.tehl.line import solve_tehl_line

    n = max((points - 1) // 4 + 1, 129)
    out, coarse = [], None
    while n <= min(4 * (points - 1) + 1, max_points):
        t = time.perf_counter()
        try:
            coarse = solve_tehl_line(scene, slip, points=n, nz=nz, box=box, coarse=coarse)
            out.append({"points": n, "Hc": coarse.Hc, "Hm": coarse.Hm, "T_max": coarse.T_max,
                        "wall_s": time.perf_counter() - t})
        except ConvergenceError as exc:
            out.append({"points": n, "failed": str(exc).splitlines()[0][:160]})
            break
        n = 2 * (n - 1) + 1
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--label", required=True)
    ap.add_argument("--accuracies", type=float, nargs="+", default=[0.02, 0.005])
    ap.add_argument("--max-points", type=int, default=8193)
    ap.add_argument("--cases", nargs="+", default=None,
                    help="scene or scene:slip (default: the built-in list)")
    args = ap.parse_args(argv)
    import ehl_multigrid as ehl

    path = OUT / f"tehl_honesty_{args.label}.json"
    rows: list[dict[str, Any]] = []
    cases = CASES if args.cases is None else [
        (c.split(":")[0], float(c.split(":")[1]) if ":" in c else None) for c in args.cases]
    for name, slip in cases:
        scene = ehl.load_scene(name)
        if slip is not None:
            scene = scene.with_operating(slip=slip)
        for acc in args.accuracies:
            t = time.perf_counter()
            sol = ehl.solve(scene, physics="thermal", accuracy=acc, options={"time_budget": 600})
            row: dict[str, Any] = {"scene": name, "slip": float(scene.slip), "accuracy": acc,
                                   "status": sol.status.label, "wall_s": time.perf_counter() - t}
            if sol.grid is not None and sol.success:
                o = sol.raw.result.options
                row.update(points=o.points, nz=o.nz, box=o.box, Hc=sol.Hc, Hm=sol.Hm,
                           stated_Hc=sol.error.Hc, stated_Hm=sol.error.Hm, T_max=sol.details.T_max,
                           stated_T_max_K=sol.details.T_max_error_K)
                films = chain(scene, float(scene.slip), o.points, o.nz, o.box, args.max_points)
                row["chain"] = films
                ok = [f for f in films if "failed" not in f]
                if len(ok) >= 3 and ok[-1]["points"] > o.points:
                    for key in ("Hc", "Hm"):
                        ref, unc, how = reference([(f["points"], f[key]) for f in ok])
                        true = abs(row[key] / ref - 1.0)
                        row[f"ref_{key}"], row[f"ref_unc_{key}"], row[f"ref_how_{key}"] = ref, unc / ref, how
                        row[f"true_{key}"] = true
                        row[f"within_{key}"] = true <= row[f"stated_{key}"] + unc / ref
                    ref, unc, how = reference([(f["points"], f["T_max"]) for f in ok])
                    row.update(ref_T_max=ref, ref_unc_T_max_K=unc, ref_how_T_max=how,
                               true_T_max_K=abs(row["T_max"] - ref))
                    if math.isfinite(row["stated_T_max_K"]):
                        row["within_T_max"] = row["true_T_max_K"] <= row["stated_T_max_K"] + unc
            rows.append(row)
            print(json.dumps({k: v for k, v in row.items() if k != "chain"}), flush=True)
            path.write_text(json.dumps(rows, indent=1))
    checked = [(r, k) for r in rows for k in ("Hc", "Hm") if f"within_{k}" in r]
    ratios = sorted(r[f"true_{k}"] / r[f"stated_{k}"] for r, k in checked if r[f"stated_{k}"] > 0)
    print(f"{sum(r[f'within_{k}'] for r, k in checked)} of {len(checked)} films within their estimate; "
          f"true/stated median {ratios[len(ratios) // 2] if ratios else math.nan:.2f}, "
          f"largest {ratios[-1] if ratios else math.nan:.2f}; wrote {path}")
    t_rows = [r for r in rows if "true_T_max_K" in r]
    print(f"T_max: {sum(r.get('within_T_max', False) for r in t_rows)} of "
          f"{sum('within_T_max' in r for r in t_rows)} stated errors hold; "
          f"{sum('within_T_max' not in r for r in t_rows)} of {len(t_rows)} stated unknown")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
