"""Is the algebraic part of the accuracy-driven solves' estimate honest? (line maps)

For every converged line result of the given accuracy maps (solved at the map's accuracy,
stopped on the films' change per cycle, ``film_tol``), the same discrete problem (grid, default
box) is solved deep (tolerances 1e-7 / 1e-8) and the films' distance to it is compared with the
result's stated algebraic error (``error_budget["algebraic"]``, floored at 1e-12: round-off) and
with its total estimate.
Writes ``out/algebraic_map_scan.json``.

    python validation/accuracy/algebraic_map_scan.py validation/extremes/out/fit_map_0.01_session9.json \
        validation/extremes/out/accuracy_map_0.02_session9.json
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from tqdm import tqdm

from ehl_multigrid.line import solve_line

OUT = Path(__file__).parent / "out" / "algebraic_map_scan.json"


def main() -> None:
    todo = []
    for f in sys.argv[1:]:
        for v in json.loads(Path(f).read_text()).values():
            c, r = v["case"], v["result"]
            box = (r.get("refinements") or [{}])[-1].get("box", 1.0)
            if c["contact"] == "line" and r["status"] == "converged" and box == 1.0:
                todo.append((Path(f).name, c, r))
    rows = []
    for name, c, r in tqdm(todo, desc="deep solves"):
        model = {m: c[m] for m in ("viscosity", "density") if m in c}
        deep = solve_line(c["M"], c["L"], points=r["points"], estimate=False, tol=1e-7, tol_load=1e-8,
                          max_cycles=200, raise_on_failure=False, **model)
        row = {"map": name, "case": c, "points": r["points"], "deep_status": deep.status_name}
        if deep.success:
            true = {h: abs(r[h] / deep.scalars[h] - 1.0) for h in ("Hc", "Hm")}
            alg = r["error_budget"]["algebraic"]
            row.update(true=true, algebraic=alg, total={h: r[h + "_error"] for h in ("Hc", "Hm")},
                       ratio_algebraic=max(true[h] / max(alg[h], 1e-12) for h in true),
                       ratio_total=max(true[h] / r[h + "_error"] for h in true))
        rows.append(row)
    ok = [w for w in rows if "true" in w]
    summary = {"results": len(rows), "deep converged": len(ok),
               "algebraic part exceeded": sum(w["ratio_algebraic"] > 1.0 for w in ok),
               "total estimate exceeded by the iteration error alone": sum(w["ratio_total"] > 1.0 for w in ok),
               "largest true/algebraic": max((w["ratio_algebraic"] for w in ok), default=None),
               "largest true/total": max((w["ratio_total"] for w in ok), default=None)}
    OUT.parent.mkdir(exist_ok=True)
    tmp = OUT.with_suffix(".tmp")
    tmp.write_text(json.dumps({"summary": summary, "rows": rows}, indent=1))
    tmp.replace(OUT)
    print(json.dumps(summary, indent=1))
    for w in sorted(ok, key=lambda w: -w["ratio_algebraic"])[:5]:
        print(w["case"], w["points"], {h: f"{w['true'][h]:.2e}/{w['algebraic'][h]:.2e}" for h in ("Hc", "Hm")},
              f"total ratio {w['ratio_total']:.2f}")


if __name__ == "__main__":
    main()
