"""Is the algebraic part of the accuracy-driven solves' estimate honest?

For every converged result of the given accuracy maps (solved at the map's accuracy, stopped on
the films' change per cycle, ``film_tol``), the same discrete problem (grid, box, cells) is
solved deep and the films' distance to it is compared with the result's stated algebraic error
(``error_budget["algebraic"]``, floored at 1e-12: round-off) and with its total estimate.
Line: default box only, tolerances 1e-7 / 1e-8. Point (``--contact point``): the result's box,
tolerances 1e-7 / 1e-6 (the point load error stalls near 5e-8 at 513 points), square cells when
the result came from the square-cell retry, results up to ``--max-points`` (default 1025).
Writes ``build/validation/accuracy/algebraic_map_scan.json`` (line) or ``..._point.json``
(resumable: a row already there for the same result is not solved again).

    python validation/accuracy/algebraic_map_scan.py [--contact point] [--max-points N] \
        build/validation/extremes/fit_map_0.01.json build/validation/extremes/accuracy_map_0.02.json

(the maps are written by ``validation/extremes/accuracy_map.py``).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from tqdm import tqdm

from ehl_multigrid.line import solve_line
from ehl_multigrid.point import solve_point

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[0] / "extremes"))
sys.path.insert(0, str(HERE.parent))
from _paths import out_dir, require  # noqa: E402
from accuracy_map import box_of  # noqa: E402
from reference_check import reference_films  # noqa: E402

MAP_COMMAND = "python validation/extremes/accuracy_map.py"


def deep_solve(c: dict, r: dict, box: float):
    """The result's discrete problem solved with tight tolerances."""
    model = {m: c[m] for m in ("viscosity", "density") if m in c}
    if c["contact"] == "line":
        return solve_line(c["M"], c["L"], points=r["points"], estimate=False, tol=1e-7, tol_load=1e-8,
                          max_cycles=200, raise_on_failure=False, **model)
    cells = {"y_ratio": 1.0} if any(t in a for a in r.get("actions", [])
                                             for t in ("RETRY_SQUARE_CELLS", "retry_square_cells")) else {}
    return solve_point(c["M"], c["L"], theta=c["theta"], points=r["points"], estimate=False, tol=1e-7,
                       tol_load=1e-6, max_cycles=100, raise_on_failure=False, **model, **cells,
                       **box_of(c, box))


def main() -> None:
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--contact", choices=("line", "point"), default="line")
    ap.add_argument("--max-points", type=int, default=1025, help="largest point grid scanned")
    ap.add_argument("--override", action="append", default=[],
                    help="a later run of some of the cases (e.g. *_theta4.json after a solver change); "
                         "its records replace those of the same case in the files (repeatable)")
    ap.add_argument("files", nargs="+")
    a = ap.parse_args()
    overrides: dict = {}
    for f in a.override:
        overrides.update({k: (Path(f).name, v) for k, v in json.loads(require(Path(f), MAP_COMMAND).read_text()).items()})
    out = out_dir("accuracy") / ("algebraic_map_scan.json" if a.contact == "line" else "algebraic_map_scan_point.json")
    todo = []
    for f in a.files:
        recs = json.loads(require(Path(f), MAP_COMMAND).read_text())
        for k, v in recs.items():
            name, v = overrides.get(k, (Path(f).name, v))
            c, r = v["case"], v["result"]
            box = (r.get("refinements") or [{}])[-1].get("box", 1.0)
            if c["contact"] != a.contact or r["status"] != "converged":
                continue
            if a.contact == "line" and box != 1.0 or a.contact == "point" and r["points"] > a.max_points:
                continue
            todo.append((name, c, r, box))
    before = json.loads(out.read_text())["rows"] if out.is_file() else []
    done = {json.dumps([w["case"], w.get("result_films")], sort_keys=True): w for w in before}
    rows = []

    def save(summary: dict | None = None) -> None:
        tmp = out.with_suffix(".tmp")
        tmp.write_text(json.dumps({"summary": summary, "rows": rows}, indent=1, default=float))
        tmp.replace(out)

    todo.sort(key=lambda t: (t[2]["points"], t[1]["M"]))
    for name, c, r, box in tqdm(todo, desc="deep solves"):
        films = [r["Hc"], r["Hm"]]
        key = json.dumps([c, films], sort_keys=True)
        if key in done and ("true" in done[key] or done[key]["deep_status"] != "max_cycles"
                            or "band_checked" in done[key]):
            rows.append(done[key])
            continue
        deep = deep_solve(c, r, box)
        row = {"map": name, "case": c, "points": r["points"], "box": box, "result_films": films,
               "deep_status": deep.status_name, "deep_wall_s": deep.wall_s,
               "band_checked": not deep.success}
        ref = reference_films(deep)
        if ref is not None:
            films, unc = ref
            true = {h: abs(r[h] / films[h] - 1.0) for h in ("Hc", "Hm")}
            alg = r["error_budget"]["algebraic"]
            row.update(true=true, algebraic=alg, total={h: r[h + "_error"] for h in ("Hc", "Hm")},
                       reference_uncertainty=unc,
                       ratio_algebraic=max(true[h] / (max(alg[h], 1e-12) + unc[h]) for h in true),
                       ratio_total=max(true[h] / (r[h + "_error"] + unc[h]) for h in true))
        rows.append(row)
        save()
    ok = [w for w in rows if "true" in w]
    summary = {"results": len(rows), "deep converged": sum(w["deep_status"] == "converged" for w in rows),
               "compared (converged, or films settled in a band)": len(ok),
               "algebraic part exceeded": sum(w["ratio_algebraic"] > 1.0 for w in ok),
               "total estimate exceeded by the iteration error alone": sum(w["ratio_total"] > 1.0 for w in ok),
               "largest true/algebraic": max((w["ratio_algebraic"] for w in ok), default=None),
               "largest true/total": max((w["ratio_total"] for w in ok), default=None)}
    save(summary)
    print(json.dumps(summary, indent=1))
    for w in sorted(ok, key=lambda w: -w["ratio_algebraic"])[:5]:
        print(w["case"], w["points"], {h: f"{w['true'][h]:.2e}/{w['algebraic'][h]:.2e}" for h in ("Hc", "Hm")},
              f"total ratio {w['ratio_total']:.2f}")


if __name__ == "__main__":
    main()
