"""Re-evaluate the honesty set with the grid part recomputed by today's ``richardson`` (the
stored FMG films of ``build/validation/accuracy/tested/*.json``; true errors from ``honesty.json``
there, both written by ``honesty.py``), against the grid part those records were estimated with:
what a change of the Richardson rule does to the coverage and the median true/estimate without
re-running any solve.

    python validation/accuracy/richardson_fallback.py   # writes build/validation/accuracy/richardson_fallback.json
"""

from __future__ import annotations

import json
import math
import statistics

from common import OUT, require, write_json

from ehl_multigrid.multigrid.accuracy import HM_MAX_ORDER, richardson


def main() -> None:
    hon = json.loads(require(OUT / "honesty.json", "python validation/accuracy/honesty.py").read_text())
    rows = {(r["contact"], r["M"], r["L"], r["theta"], r["points"]): r for r in hon["rows"]}
    out = []
    for f in sorted((OUT / "tested").glob("*.json")):
        t = json.loads(f.read_text())
        key = (t["contact"], t["M"], t["L"], t["theta"], t["points"])
        r = rows.get(key)
        if r is None or not t.get("fmg"):
            continue
        top = max(d["level"] for d in t["fmg"])
        for film, max_order in (("Hc", 2.0), ("Hm", HM_MAX_ORDER)):
            if film not in r or r[film]["est"] is None or not math.isfinite(r[film]["est"]):
                continue
            H = t[f"{film}_venner"]
            values = [d[film] for d in t["fmg"] if d["level"] < top] + [H]
            stored_grid = t["budget"]["grid"][film]
            new_grid = richardson(values, max_order=max_order).error / abs(H)
            est = r[film]["est"] - stored_grid + new_grid
            true = abs(r[film]["true"])
            out.append({"case": list(key), "film": film, "true": true, "estimate_before": r[film]["est"],
                        "estimate_now": est, "covered_before": true <= r[film]["est"],
                        "covered_now": true <= est})
    summary = {
        "films": len(out),
        "covered_before": sum(o["covered_before"] for o in out),
        "covered_now": sum(o["covered_now"] for o in out),
        "median_ratio_before": statistics.median(o["true"] / o["estimate_before"] for o in out),
        "median_ratio_now": statistics.median(o["true"] / o["estimate_now"] for o in out),
    }
    write_json(OUT / "richardson_fallback.json", {"summary": summary, "rows": out})
    print(json.dumps(summary, indent=1))


if __name__ == "__main__":
    main()
