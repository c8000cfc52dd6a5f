"""The grid rule of the steady solvers (``options.grid_stop``) against the residual rule.

Every case is solved three times on the same grid: with the default stopping rule (residual
tolerance, or the grid rule: both films' iteration error below 0.25 of their larger grid error,
at most 1e-4), with the residual rule alone (``grid_stop=None``, the rule before), and a deep
reference (residual rule with tolerances ten times tighter, up to 60 extra cycles). Recorded:
work units, wall time, cycles, which rule stopped, the films, the algebraic error the result
states (:func:`~ehl_multigrid.multigrid.accuracy.estimate_error`) and the true iteration error
against the deep reference. A stop is *honest* when the true error is within the stated one.

    python validation/bench/grid_stop.py [--set map|fine|all] [--quick] [--label NAME]

``map``: every point case of the extremes matrix and the fit-check map on 513 points (half
domain); ``fine``: (20, 10), (100, 10), (1000, 10) and theta 4 point contacts on 1025 and 2049
points, line contacts up to 16385 points. Writes ``build/validation/bench/<label>.json`` and ``build/validation/bench/<label>.md``.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

from tqdm import tqdm

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "extremes"))
from accuracy_map import cases, fit_cases  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("bench")

FINE = ([{"contact": "point", "M": M, "L": 10.0, "theta": 1.0, "points": n}
         for M in (20.0, 100.0, 1000.0) for n in (1025, 2049)]
        + [{"contact": "point", "M": 20.0, "L": 10.0, "theta": 4.0, "points": 1025}]
        + [{"contact": "line", "M": M, "L": L, "points": n}
           for M, L in ((20.0, 10.0), (100.0, 0.0), (1000.0, 10.0), (200.0, 5.0))
           for n in (4097, 16385)])


def solve(case: dict, **kw) -> dict:
    from ehl_multigrid.multigrid.accuracy import estimate_error

    model = {k: case[k] for k in ("viscosity", "density") if k in case}
    t0 = time.perf_counter()
    try:
        if case["contact"] == "point":
            from ehl_multigrid.point import solve_point

            r = solve_point(case["M"], case["L"], theta=case.get("theta", 1.0), points=case["points"],
                            half=True, estimate=False, raise_on_failure=False, **model, **kw)
        else:
            from ehl_multigrid.line import solve_line

            r = solve_line(case["M"], case["L"], points=case["points"], estimate=False,
                           raise_on_failure=False, **model, **kw)
    except Exception as exc:  # a clear error is an outcome
        return {"status": "error", "message": f"{type(exc).__name__}: {exc}".splitlines()[0]}
    out = {"status": r.status_name, "WU": r.work_units, "wall_s": time.perf_counter() - t0,
           "cycles": r.cycles, "Hc": r.scalars.get("Hc_venner"), "Hm": r.scalars.get("Hm_venner"),
           "residual": float(r.residual_history[-1]) if len(r.residual_history) else math.nan,
           "grid_rule": any(a.startswith("stopped on the grid rule") for a in r.actions),
           # the finest-grid films and load errors per cycle: estimator variants are evaluated
           # from these without re-solving (validation/accuracy/iteration_estimate.py)
           "finest": [{"Hc": h.Hc, "Hm": h.Hm, "load_error": h.load_error, "residual": h.residual}
                      for h in r.history if h.level == r.levels - 1 and h.cycle >= 0]}
    if r.success:
        est = estimate_error(r)
        out["algebraic"] = est.budget["algebraic"]
        out["grid"] = est.budget["grid"]
    return out


def compare(row: dict) -> None:
    """True iteration error of the default and residual-rule solves against the deep one."""
    ref = row["deep"]
    for key in ("default", "residual"):
        r = row[key]
        if r["status"] != "converged" or ref["status"] != "converged":
            continue
        r["true"] = {f: abs(r[f] / ref[f] - 1.0) for f in ("Hc", "Hm")}
        r["honest"] = all(r["true"][f] <= r["algebraic"][f] + ref["algebraic"][f] for f in ("Hc", "Hm"))


def table(rows: list[dict]) -> str:
    lines = ["| case | points | rule | WU (residual rule) | wall s (residual rule) | cycles | "
             "Hc true / stated alg. | Hm true / stated alg. | honest |", "|---|---|---|---|---|---|---|---|---|"]
    for row in rows:
        d, b = row["default"], row["residual"]
        name = f"{row['contact']} ({row['M']:g}, {row['L']:g}" + (f", {row['theta']:g})" if "theta" in row else ")")
        if d["status"] != "converged":
            lines.append(f"| {name} | {row['points']} | {d['status']} | | | | | | |")
            continue
        tr = d.get("true")
        cells = {f: f"{tr[f]:.1e} / {d['algebraic'][f]:.1e}" if tr else "n/a" for f in ("Hc", "Hm")}
        lines.append(f"| {name} | {row['points']} | {'grid' if d['grid_rule'] else 'residual'} | "
                     f"{d['WU']:.1f} ({b.get('WU', math.nan):.1f}) | {d['wall_s']:.2f} ({b.get('wall_s', math.nan):.2f}) | "
                     f"{d['cycles']} ({b.get('cycles', '-')}) | {cells['Hc']} | {cells['Hm']} | "
                     f"{d.get('honest', 'n/a')} |")
    return "\n".join(lines)


def summary(rows: list[dict]) -> dict:
    conv = [r for r in rows if r["default"]["status"] == "converged" and r["residual"]["status"] == "converged"]
    grid = [r for r in conv if r["default"]["grid_rule"]]
    checked = [r for r in grid if "honest" in r["default"]]
    return {
        "cases": len(rows),
        "converged_default": sum(r["default"]["status"] == "converged" for r in rows),
        "converged_residual_rule": sum(r["residual"]["status"] == "converged" for r in rows),
        "stopped_by_grid_rule": len(grid),
        "grid_rule_checked": len(checked),
        "grid_rule_honest": sum(bool(r["default"]["honest"]) for r in checked),
        "WU_ratio_grid_rule_cases": (sum(r["default"]["WU"] for r in grid) / sum(r["residual"]["WU"] for r in grid)
                                     if grid else math.nan),
        "wall_ratio_grid_rule_cases": (sum(r["default"]["wall_s"] for r in grid)
                                       / sum(r["residual"]["wall_s"] for r in grid) if grid else math.nan),
        "WU_ratio_all": (sum(r["default"]["WU"] for r in conv) / sum(r["residual"]["WU"] for r in conv)
                         if conv else math.nan),
        "largest_true_over_stated": max((max(r["default"]["true"][f] / max(r["default"]["algebraic"][f], 1e-300)
                                             for f in ("Hc", "Hm")) for r in checked), default=math.nan),
    }


def save_json(path: Path, payload: dict) -> None:
    """Write ``payload`` beside ``path`` and rename: an interrupted run leaves no half file."""
    tmp = path.with_suffix(".json.tmp")
    tmp.write_text(json.dumps(payload, indent=1))
    tmp.replace(path)


def write_report(path: Path, table_text: str, summary_: dict) -> None:
    """The markdown table and the summary lines (also printed)."""
    text = table_text + "\n\n" + "\n".join(f"- {k}: {v}" for k, v in summary_.items()) + "\n"
    path.write_text(text)
    print(text)


def main() -> None:
    from ehl_multigrid.point.problem import min_points, problem_from_moes

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--set", choices=("map", "fine", "all"), default="all")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--label", default="grid_stop", help="output file stem under build/validation/bench/")
    a = ap.parse_args()
    todo: list[dict] = []
    if a.set in ("map", "all"):
        for c in [c for c in cases(a.quick) + fit_cases(a.quick) if c["contact"] == "point"]:
            pb = problem_from_moes(c["M"], c["L"], c["theta"])
            todo.append({**c, "points": max(513, min_points(c["M"], pb.b_over_a))})
    if a.set in ("fine", "all"):
        todo += FINE[:3] if a.quick else FINE
    OUT.mkdir(exist_ok=True)
    # no table of an earlier run beside this run's rows
    (OUT / f"{a.label}.md").unlink(missing_ok=True)
    rows = []
    for c in tqdm(todo, desc="cases"):
        row = {**c, "default": solve(c), "residual": solve(c, grid_stop=None)}
        tight = {"grid_stop": None, "max_cycles": 60}
        if row["residual"]["status"] == "converged":
            tol, tol_load = (1e-5, 1e-6) if c["contact"] == "point" else (1e-6, 1e-7)
            tight.update(tol=tol, tol_load=tol_load)
            row["deep"] = solve(c, **tight)
            compare(row)
        else:
            row["deep"] = {"status": "skipped"}
        rows.append(row)
        save_json(OUT / f"{a.label}.json", {"rows": rows, "summary": summary(rows)})
    write_report(OUT / f"{a.label}.md", table(rows), summary(rows))


if __name__ == "__main__":
    main()
