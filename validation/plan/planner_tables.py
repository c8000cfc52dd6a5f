"""Turn measured studies into the planner's tables (package data), so `ehl plan` decides with
measured numbers instead of priors.

* ``ehl_multigrid/data/fit_deviation_line.json`` / ``_point.json``: relative deviation of the
  Moes / Nijenbanning central-film fit from the Roelands + Dowson-Higginson multigrid solution,
  ``(Hc_fit - Hc_solver) / Hc_solver``, on the (M, L) map of the fit-check studies
  (validation/line/out/fit.json, validation/point/out/fit.json).

Usage: python validation/plan/planner_tables.py
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "ehl_multigrid" / "data"


def table_from_rows(rows: list[dict], source: str) -> dict | None:
    sel = [r for r in rows if r.get("viscosity") == "roelands" and r.get("density") == "dowson-higginson"
           and r.get("converged") and r.get("Hc") and (float(r.get("theta", 1.0)) == 1.0)]
    if not sel:
        return None
    Ms = sorted({float(r["M"]) for r in sel})
    Ls = sorted({float(r["L"]) for r in sel})
    dev = np.full((len(Ms), len(Ls)), math.nan)
    for r in sel:
        fit = r["fit"] if "fit" in r else r["Hc_fit"]
        dev[Ms.index(float(r["M"])), Ls.index(float(r["L"]))] = (fit - r["Hc"]) / r["Hc"]
    return {"M": Ms, "L": Ls, "deviation": [[None if not np.isfinite(v) else float(v) for v in row] for row in dev],
            "definition": "(Hc_fit - Hc_solver) / Hc_solver, Roelands + Dowson-Higginson, converged solves",
            "source": source}


def main() -> None:
    DATA.mkdir(exist_ok=True)
    for contact, name in (("line", "fit.json"), ("point", "fit_check.json")):
        f = ROOT / "validation" / contact / "out" / name
        if not f.exists():
            print(f"{contact}: no {f.relative_to(ROOT)}; table not written")
            continue
        data = json.loads(f.read_text())
        rows = data.get("rows", []) if "rows" in data else [v for v in data.values() if isinstance(v, dict)]
        tab = table_from_rows(rows, f"validation/{contact}/out/{name}")
        if tab is None:
            print(f"{contact}: no converged Roelands + Dowson-Higginson rows; table not written")
            continue
        out = DATA / f"fit_deviation_{contact}.json"
        out.write_text(json.dumps(tab, indent=1))
        d = np.array([[np.nan if v is None else v for v in row] for row in tab["deviation"]])
        print(f"{contact}: wrote {out.relative_to(ROOT)}; deviation {np.nanmin(d):+.3f} .. {np.nanmax(d):+.3f}")


if __name__ == "__main__":
    main()
