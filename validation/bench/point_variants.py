"""A point-solver variant against the default over the point cases of the grid-rule study.

Variants (``--variant``): ``y_post`` -- fine-grid Y lines in the post-relaxation only
(``PointOptions.y_pre=False``) against both relaxations alternating (the default); ``hw_first``
-- the robustness policy's ladder starting with "halve the under-relaxation, W cycles" instead
of "alternate on every grid" (then "alternate", "switch"), for rejected and stalled cycles.

Every point case of ``build/validation/bench/grid_stop.json`` (the extremes matrix and the fit-check map on 513
points or the case's minimum grid, and the fine grids up to 2049^2) is solved twice with the
default options otherwise, paired (new rule, then old rule): status, work units, wall time, cycles, the
films and the algebraic error each result states. The true iteration error is taken against
the study's deep reference (tolerances ten times tighter, same grid and box: the discrete
solution does not depend on the smoother). A result is *honest* when its true error lies within
its stated algebraic error plus the reference's.

    python validation/bench/point_variants.py [--variant y_post|hw_first] [--quick] [--label NAME]

Writes ``build/validation/bench/<label>.json`` and ``build/validation/bench/<label>.md`` (default label: the variant's name); an
interrupted run resumes from its JSON (cases of the same list only).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
from pathlib import Path

from tqdm import tqdm

sys.path.insert(0, str(Path(__file__).resolve().parent))
from grid_stop import save_json, solve, write_report  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir, require  # noqa: E402

OUT = out_dir("bench")


def solve_hw_first(case: dict) -> dict:
    """The default solve with the policy's ladder reordered: halve + W, alternate, switch."""
    from ehl_multigrid.point import fas

    saved = fas.POINT_POLICY
    ladder = (("halve", "W"), ("alternate",), ("switch",))
    fas.POINT_POLICY = dataclasses.replace(saved, reject_ladder=ladder, stall_ladder=ladder)
    try:
        return solve(case)
    finally:
        fas.POINT_POLICY = saved


VARIANTS = {"y_post": lambda case: solve(case, y_pre=False), "hw_first": solve_hw_first}
KEYS = ("contact", "M", "L", "theta", "points", "viscosity", "density")


def case_key(c: dict) -> str:
    return json.dumps({k: c[k] for k in KEYS if k in c}, sort_keys=True)


def honest(r: dict, ref: dict) -> bool | None:
    if r["status"] != "converged" or ref.get("status") != "converged":
        return None
    true = {f: abs(r[f] / ref[f] - 1.0) for f in ("Hc", "Hm")}
    r["true"] = true
    return all(true[f] <= r["algebraic"][f] + ref["algebraic"][f] for f in ("Hc", "Hm"))


def summary(rows: list[dict]) -> dict:
    both = [r for r in rows if r["new"]["status"] == "converged" and r["old"]["status"] == "converged"]
    fine = [r for r in both if r["points"] >= 1025]
    checked = [r for r in rows if r["new"].get("honest") is not None]
    return {
        "cases": len(rows),
        "converged_new": sum(r["new"]["status"] == "converged" for r in rows),
        "converged_old": sum(r["old"]["status"] == "converged" for r in rows),
        "lost": [case_key(r) for r in rows if r["old"]["status"] == "converged" and r["new"]["status"] != "converged"],
        "gained": [case_key(r) for r in rows if r["new"]["status"] == "converged" and r["old"]["status"] != "converged"],
        "WU_ratio_both_converged": (sum(r["new"]["WU"] for r in both) / sum(r["old"]["WU"] for r in both)
                                    if both else math.nan),
        "wall_ratio_both_converged": (sum(r["new"]["wall_s"] for r in both) / sum(r["old"]["wall_s"] for r in both)
                                      if both else math.nan),
        "WU_ratio_fine": (sum(r["new"]["WU"] for r in fine) / sum(r["old"]["WU"] for r in fine)
                          if fine else math.nan),
        "cases_more_work": sum(r["new"]["WU"] > 1.05 * r["old"]["WU"] for r in both),
        "cases_less_work": sum(r["new"]["WU"] < 0.95 * r["old"]["WU"] for r in both),
        "checked_new": len(checked),
        "honest_new": sum(bool(r["new"]["honest"]) for r in checked),
        "honest_old": sum(bool(r["old"].get("honest")) for r in checked),
    }


def table(rows: list[dict]) -> str:
    lines = ["| case | points | status new (old) | WU new (old) | wall s new (old) | cycles new (old) | "
             "Hc true / stated (new) | Hm true / stated (new) | honest new (old) |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        n, o = r["new"], r["old"]
        name = f"({r['M']:g}, {r['L']:g}, {r['theta']:g})" + (f" {r['viscosity']}" if "viscosity" in r else "")
        tr = n.get("true")
        cells = {f: f"{tr[f]:.1e} / {n['algebraic'][f]:.1e}" if tr else "n/a" for f in ("Hc", "Hm")}
        lines.append(f"| {name} | {r['points']} | {n['status']} ({o['status']}) | {n.get('WU', math.nan):.1f} "
                     f"({o.get('WU', math.nan):.1f}) | {n.get('wall_s', math.nan):.2f} ({o.get('wall_s', math.nan):.2f}) | "
                     f"{n.get('cycles', '-')} ({o.get('cycles', '-')}) | {cells['Hc']} | {cells['Hm']} | "
                     f"{n.get('honest', 'n/a')} ({o.get('honest', 'n/a')}) |")
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="every sixth case only")
    ap.add_argument("--variant", choices=sorted(VARIANTS), default="y_post")
    ap.add_argument("--label", default=None, help="output stem (default: the variant)")
    a = ap.parse_args()
    src = json.loads(require(OUT / "grid_stop.json", "python validation/bench/grid_stop.py").read_text())["rows"]
    todo = [r for r in src if r["contact"] == "point"]
    if a.quick:
        todo = todo[::6]
    label = a.label or a.variant
    path = OUT / f"{label}.json"
    (OUT / f"{label}.md").unlink(missing_ok=True)
    done: dict[str, dict] = {}
    if path.exists():
        prev = json.loads(path.read_text())
        if prev.get("cases") == [case_key(c) for c in todo] and prev.get("variant", "y_post") == a.variant:
            done = {case_key(r): r for r in prev["rows"]}
    rows = []
    for c in tqdm(todo, desc="cases"):
        key = case_key(c)
        if key in done:
            rows.append(done[key])
            continue
        case = {k: c[k] for k in KEYS if k in c}
        row = {**case, "new": VARIANTS[a.variant](case), "old": solve(case)}
        for k in ("new", "old"):
            row[k].pop("finest", None)
            row[k]["honest"] = honest(row[k], c["deep"])
        rows.append(row)
        save_json(path, {"variant": a.variant, "cases": [case_key(c) for c in todo], "rows": rows,
                         "summary": summary(rows)})
    write_report(OUT / f"{label}.md", table(rows), summary(rows))


if __name__ == "__main__":
    main()
