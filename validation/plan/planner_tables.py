"""Turn measured studies into the planner's tables (package data), so `ehl plan` decides with
measured numbers instead of priors.

* ``ehl_multigrid/data/fit_deviation_line.json`` / ``_point.json``: relative deviation of the
  Moes / Nijenbanning central-film fit from the Roelands + Dowson-Higginson multigrid solution,
  ``(Hc_fit - Hc_solver) / Hc_solver``, on the (M, L) map of the fit-check studies
  (build/validation/line/fit.json from ``validation/line/studies.py --study fit --full``,
  build/validation/point/fit_check.json from ``validation/point/fit_check.py --roelands``).

* ``ehl_multigrid/data/grid_error_line.json`` / ``_point.json``: the constant ``C(M)`` of the
  second-order grid error of Hc, ``|error| = C / (N - 1)^2``, from the accuracy-cost study
  (build/validation/pareto/pareto.json from ``validation/pareto/pareto.py``: V cycles, FFT deformation, against its reference grid;
  ``C = |e| / ((N-1)^-2 - (N_ref-1)^-2)``, median over the grids listed in GRIDS).

Usage: python validation/plan/planner_tables.py
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "ehl_multigrid" / "data"
sys.path.insert(0, str(ROOT / "validation"))
from _paths import BUILD  # noqa: E402

#: the studies read, and the command that writes each
PARETO = BUILD / "pareto" / "pareto.json", "python validation/pareto/pareto.py"
FITS = {"line": (BUILD / "line" / "fit.json", "python validation/line/studies.py --study fit --full"),
        "point": (BUILD / "point" / "fit_check.json", "python validation/point/fit_check.py --roelands")}


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


GRIDS = {"line_ehl": (1025, 2049, 4097), "point_ehl": (129, 257, 513)}
CASES = {"line_ehl": "LINE_CASES", "point_ehl": "POINT_CASES"}


def grid_error_tables() -> None:
    f, command = PARETO
    if not f.exists():
        print(f"no {f.relative_to(ROOT)} (run `{command}` first); grid-error tables not written")
        return
    import importlib.util

    spec = importlib.util.spec_from_file_location("pareto", ROOT / "validation" / "pareto" / "pareto.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    store = json.loads(f.read_text())
    for model, grids in GRIDS.items():
        rec = store.get(model)
        if not rec or "{}" not in rec["refs"]:
            print(f"{model}: not in pareto.json; table not written")
            continue
        ref = rec["refs"]["{}"]
        n_ref = ref["setting"]["points"]
        cases = getattr(mod, CASES[model])
        per_case: list[list[float]] = [[] for _ in cases]
        for r in rec["rows"].values():
            s = r["setting"]
            if s.get("cycle") != "V" or s.get("deformation") != "fft" or s.get("points") not in grids or "value" not in r:
                continue
            w = (s["points"] - 1) ** -2 - (n_ref - 1) ** -2
            for i, (v, v0) in enumerate(zip(r["value"], ref["value"], strict=True)):
                per_case[i].append(abs(v - v0) / abs(v0) / w)
        Ms, Cs = [], []
        for (M, _L), cs in zip(cases, per_case, strict=True):
            if cs:
                Ms.append(float(M))
                Cs.append(float(np.median(cs)))
        if not Ms:
            print(f"{model}: no converged V/FFT rows on {grids}; table not written")
            continue
        contact = model.split("_")[0]
        tab = {"M": Ms, "L": [float(L) for _M, L in cases][:len(Ms)], "C": Cs, "order": 2,
               "reference_points": n_ref, "grids": list(grids),
               "definition": "relative error of Hc = C / (points - 1)^2 (Roelands + Dowson-Higginson)",
               "source": f"{f.relative_to(ROOT)} ({command})"}
        out = DATA / f"grid_error_{contact}.json"
        out.write_text(json.dumps(tab, indent=1))
        print(f"{contact}: wrote {out.relative_to(ROOT)}: " + ", ".join(f"C({M:g}) = {C:.3g}" for M, C in zip(Ms, Cs, strict=True)))


def main() -> None:
    DATA.mkdir(exist_ok=True)
    grid_error_tables()
    for contact, (f, command) in FITS.items():
        if not f.exists():
            print(f"{contact}: no {f.relative_to(ROOT)} (run `{command}` first); table not written")
            continue
        data = json.loads(f.read_text())
        rows = data.get("rows", []) if "rows" in data else [v for v in data.values() if isinstance(v, dict)]
        tab = table_from_rows(rows, f"{f.relative_to(ROOT)} ({command})")
        if tab is None:
            print(f"{contact}: no converged Roelands + Dowson-Higginson rows; table not written")
            continue
        out = DATA / f"fit_deviation_{contact}.json"
        out.write_text(json.dumps(tab, indent=1))
        d = np.array([[np.nan if v is None else v for v in row] for row in tab["deviation"]])
        print(f"{contact}: wrote {out.relative_to(ROOT)}; deviation {np.nanmin(d):+.3f} .. {np.nanmax(d):+.3f}")


if __name__ == "__main__":
    main()
