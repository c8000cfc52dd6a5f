"""Solves at a target accuracy against the deep references, in one process: time, grid, box,
status, the estimated and the true error of Hc and Hm (issue "Accuracy per second").

Every reference of validation/accuracy of the chosen contact (`python
validation/accuracy/references.py --contact point|line` writes them to
build/validation/accuracy/references) is solved through `ehl_multigrid.solve` at each accuracy,
one case after another in this process (numba warm after small warm-up solves; no process
start-up in the times, unlike verified.py). A film is *within its estimate* when |true error|
<= the stated error; the references' own uncertainty is listed beside. `--refs` chooses them:
`p0` (references.py, P = 0 on boxes up to 8x; point Hm's uncertainty reaches 0.2-0.4 % where
its box change depends on the mesh, and (5, 0) is not resolved), `far` (far_references.py, the
far-field boundary, circular contacts; Hm within 0.01-0.2 %) or, the default, per film the
sharper of the two (they agree within their joint uncertainty on every circular case).

    python validation/bench/honesty_table.py --label after                 # point contacts
    python validation/bench/honesty_table.py --contact line --label after
    python validation/bench/honesty_table.py --contact line --face auto --label auto
    git worktree add /tmp/before REV && python validation/bench/honesty_table.py --label before --code /tmp/before

writes build/validation/bench/<contact>_honesty_<label>.json and .md (kept after every case).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402
from verified import reference  # noqa: E402  (this folder is the script's own path entry)

OUT = Path(out_dir("bench"))
CASES = {"point": ((20, 10, 1), (100, 10, 1), (100, 20, 1), (20, 0, 1), (20, 10, 0.25), (20, 10, 4),
                   (1000, 10, 1), (5, 0, 1)),
         # the line cases of validation/accuracy/common.LINE_CASES
         "line": ((5, 0, 1), (5, 10, 1), (20, 0, 1), (20, 10, 1), (20, 20, 1), (100, 0, 1), (100, 10, 1),
                  (100, 20, 1), (1000, 10, 1), (1000, 20, 1), (3000, 10, 1))}


def table(rows: list[dict[str, Any]]) -> str:
    out = ["| (M, L, theta) | target | status | wall s | points | box | est Hc | est Hm | true Hc | true Hm | "
           "ref +- Hc | ref +- Hm |", "|" + " --- |" * 12]
    for r in rows:
        t = r["true"] or [math.nan, math.nan]
        out.append(f"| ({r['M']:g}, {r['L']:g}, {r['theta']:g}) | {r['accuracy']:g} | {r['status']} | "
                   f"{r['wall_s']:.1f} | {r['points']} | {r['box']:g} | {r['est'][0]:.2%} | {r['est'][1]:.2%} | "
                   f"{t[0]:+.2%} | {t[1]:+.2%} | {r['ref_unc'][0]:.2%} | {r['ref_unc'][1]:.2%} |")
    films = [(abs(t), e, u, f"({r['M']:g}, {r['L']:g}, {r['theta']:g}) {k} at {r['accuracy']:g}")
             for r in rows if r["status"] == "converged" and r["true"]
             for t, e, u, k in zip(r["true"], r["est"], r["ref_unc"], ("Hc", "Hm"), strict=True)]
    within = [t <= e for t, e, _, _ in films]
    ratios = sorted(t / e for t, e, _, _ in films)
    if ratios:
        out.append(f"\nConverged films within their estimate: {sum(within)} of {len(within)}; median "
                   f"true/estimated {ratios[len(ratios) // 2]:.2f}, largest {ratios[-1]:.2f}.")
        # a reference less certain than the estimate cannot show the film outside it
        blind = [f"{name} (true {t:.3%}, stated {e:.3%}, reference +- {u:.3%})"
                 for t, e, u, name in films if t > e and u >= e]
        if blind:
            out.append("Outside, but the reference cannot decide (its uncertainty is at least the "
                       "stated error): " + "; ".join(blind) + ".")
    return "\n".join(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--label", default="table")
    ap.add_argument("--contact", choices=("point", "line"), default="point")
    ap.add_argument("--accuracies", nargs="*", type=float, default=[0.005, 0.01])
    ap.add_argument("--code", default=None, help="import the package of this checkout (a git worktree)")
    ap.add_argument("--refs", choices=("p0", "far", "sharper"), default="sharper",
                    help="references: P = 0 boxes, far field, or per film the sharper (verified.reference)")
    ap.add_argument("--face", choices=("arithmetic", "logarithmic", "auto"), default=None,
                    help="line contacts: the Poiseuille face coefficient (LineOptions.face)")
    args = ap.parse_args()
    opts = {"face": args.face} if args.face else None
    if args.code:
        sys.path.insert(0, os.path.abspath(args.code))
    import ehl_multigrid as ehl

    def problem(M: float, L: float, theta: float) -> Any:
        if args.contact == "line":
            return ehl.MoesProblem("line", M=M, L=L)
        return ehl.MoesProblem("point" if theta == 1 else "elliptic", M=M, L=L, theta=theta)

    for theta in (1, 4) if args.contact == "point" else (1,):  # numba compiled and loaded before timing
        ehl.solve(problem(20, 10, theta), accuracy=0.05)
    rows: list[dict[str, Any]] = []
    path = OUT / f"{args.contact}_honesty_{args.label}.json"
    for acc in args.accuracies:
        for M, L, theta in CASES[args.contact]:
            ref = reference((args.contact, float(M), float(L), float(theta)), args.refs)
            t0 = time.perf_counter()
            sol = ehl.solve(problem(M, L, theta), accuracy=acc, options=opts)
            wall = time.perf_counter() - t0
            raw = sol.raw
            films = (raw.scalars["Hc_venner"], raw.scalars["Hm_venner"])
            true = [f / ref[k] - 1.0 for f, k in zip(films, ("Hc_ref", "Hm_ref"), strict=True)] if ref else None
            steps = raw.extra.get("refinements", [])
            rows.append(dict(M=M, L=L, theta=theta, accuracy=acc, status=sol.status.name.lower(),
                             wall_s=wall, points=int(raw.X.shape[0]), box=steps[-1]["box"] if steps else 1.0,
                             est=[sol.error.Hc, sol.error.Hm], true=true,
                             ref_unc=[ref["Hc_unc"], ref["Hm_unc"]] if ref else [math.nan, math.nan],
                             ref_kind=ref.get("kind") if ref else None,
                             budget=raw.error.budget, correction=raw.extra.get("film_correction"),
                             solves=[(s["points"], s["box"], s["purpose"]) for s in steps]))
            print(table(rows[-1:]).splitlines()[2], file=sys.stderr, flush=True)  # the row
            tmp = path.with_suffix(".json.tmp")
            tmp.write_text(json.dumps({"rows": rows, "code": args.code or "installed"}, indent=1, default=str))
            tmp.replace(path)
    path.with_suffix(".md").write_text(table(rows) + "\n")
    print(table(rows))


if __name__ == "__main__":
    main()
