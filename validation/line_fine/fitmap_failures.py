"""The fit map's 15 failing line cases (build/validation/extremes/fit_map_0.01_line.json,
accuracy 0.01) re-run with ``solve_line(M, L, accuracy=0.01)`` on the current code.
Writes ``build/validation/line_fine/fitmap_failures.json`` (status, points, Hc, Hm, estimated errors, the map's
status before)."""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

from tqdm import tqdm

from ehl_multigrid.line import solve_line

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import BUILD, out_dir, require  # noqa: E402

MAP = BUILD / "extremes" / "fit_map_0.01_line.json"
MAP_COMMAND = "python validation/extremes/accuracy_map.py --map fits --contact line --accuracy 0.01 --tag line"


def main() -> None:
    cases = json.loads(require(MAP, MAP_COMMAND).read_text())
    path = out_dir("line_fine") / "fitmap_failures.json"
    out = json.loads(path.read_text()) if path.exists() else {}
    for v in tqdm(list(cases.values())):
        c = v["case"]
        if v["result"]["status"] == "converged" or f"{c['viscosity']} M={c['M']:g} L={c['L']:g}" in out:
            continue  # (a re-run resumes: the cases already in build/validation/line_fine/ are kept)
        t = time.perf_counter()
        r = solve_line(c["M"], c["L"], viscosity=c["viscosity"], density=c["density"],
                       accuracy=v["accuracy"], raise_on_failure=False)
        out[f"{c['viscosity']} M={c['M']:g} L={c['L']:g}"] = {
            "before": {k: v["result"].get(k) for k in ("status", "points", "Hc", "Hm", "Hc_error", "Hm_error")},
            "after": {"status": r.status_name, "message": r.message, "points": int(r.X.shape[0]),
                      "Hc": r.Hc, "Hm": r.Hm,
                      "Hc_error": r.error.Hc if r.error is not None else None,
                      "Hm_error": r.error.Hm if r.error is not None else None,
                      "refinements": r.extra.get("refinements"),
                      "wall_s": time.perf_counter() - t}}
        path.write_text(json.dumps(out, indent=1, default=float))


if __name__ == "__main__":
    main()
