"""Grid sequences of the solves fixed in validation/line_fine (REPORT.md): Hc and Hm (Moes
units) of plain solves on successive grids, their differences and the observed order
``log2(d_k / d_{k+1})``. Writes ``build/validation/line_fine/sequence.json``."""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

from tqdm import tqdm

from ehl_multigrid.line import solve_line

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

R, B = "roelands", "barus"
SEQUENCES = [(R, 100, 0, (1025, 2049, 4097, 8193)), (R, 500, 0, (2049, 4097, 8193, 16385)),
             (R, 1000, 0, (4097, 8193, 16385, 32769)), (B, 100, 20, (1025, 2049, 4097)),
             (R, 100, 20, (1025, 2049, 4097, 8193)), (B, 20, 10, (1025, 2049, 4097, 8193))]


def order(vals: list[float]) -> list[float]:
    d = [b - a for a, b in zip(vals, vals[1:], strict=False)]
    return [math.log2(abs(x / y)) if y != 0 and x * y > 0 else math.nan for x, y in zip(d, d[1:], strict=False)]


def main() -> None:
    out = {}
    for visc, M, L, grids in tqdm(SEQUENCES):
        kw = {} if visc == R else {"viscosity": "barus", "density": "incompressible"}
        rows = []
        for n in grids:
            r = solve_line(M, L, points=n, estimate=False, raise_on_failure=False, **kw)
            rows.append({"points": n, "status": r.status_name, "cycles": r.cycles,
                         "work_units": r.work_units, "Hc": r.Hc, "Hm": r.Hm})
        ok = [x for x in rows if x["status"] == "converged"]
        out[f"{visc} M={M} L={L}"] = {
            "solves": rows,
            "Hc_order": order([x["Hc"] for x in ok]), "Hm_order": order([x["Hm"] for x in ok])}
        (out_dir("line_fine") / "sequence.json").write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
