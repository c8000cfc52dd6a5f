"""The true grid error of a map answer from two finer grids solved from it.

    python validation/extremes/finer_sequence.py --accuracy 0.01 \
        --case '{"contact": "point", "M": 1000.0, "L": 20.0, "theta": 1.0, "viscosity": "barus", "density": "incompressible"}'

Solves the case as the map does (accuracy-driven, ``accuracy_map.solve``), then the same
contact on 2n - 1 and 4n - 3 points, each started from the converged solution one grid coarser
(no FMG, a quarter of the tolerances). With the answer's raw finest film F_n and the two finer
films, the observed ratio r = (F_2n - F_n)/(F_4n - F_2n) gives the limit F_4n + (F_4n - F_2n)/(r - 1)
and so the answer's true grid error on its own box, beside its stated grid + algebraic part and
total. Appends one JSON line to build/validation/extremes/finer_sequence.jsonl.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from accuracy_map import OUT, films_on_box, from_converged, solve  # noqa: E402


def finer_sequence(case: dict, accuracy: float) -> dict:
    kept: list = []
    r = solve(case, accuracy, keep=kept)
    out: dict = {"case": case, "accuracy": accuracy, "result": r}
    if r["status"] != "converged" or case["contact"] != "point":
        return out
    s = kept[0]
    on_box, raw = films_on_box(r, s)
    prev, films = s, []
    for n in (2 * (r["points"] - 1) + 1, 4 * (r["points"] - 1) + 1):
        step: list = []
        films.append(from_converged(prev, n, keep=step, options=s.options))
        if films[-1]["status"] != "converged":
            return {**out, "finer": films}
        prev = step[0]
    b = r["error_budget"]
    out["finer"] = films
    for f in ("Hc", "Hm"):
        F1, F2, F4 = raw[f], films[0][f], films[1][f]
        ratio = (F2 - F1) / (F4 - F2) if F4 != F2 else float("inf")
        limit = F4 + (F4 - F2) / (ratio - 1.0) if ratio > 1.0 else float("nan")
        out[f] = {"ratio": ratio, "true_on_box": abs(on_box[f] / limit - 1.0),
                  "stated_grid_alg": b["grid"][f] + b["algebraic"][f], "stated_total": r[f + "_error"]}
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", required=True, help="a map case as JSON (point contacts)")
    ap.add_argument("--accuracy", type=float, default=0.01)
    a = ap.parse_args()
    rec = finer_sequence(json.loads(a.case), a.accuracy)
    OUT.mkdir(parents=True, exist_ok=True)
    with open(OUT / "finer_sequence.jsonl", "a") as fh:
        fh.write(json.dumps(rec) + "\n")
    for f in ("Hc", "Hm"):
        if f in rec:
            v = rec[f]
            print(f"{f}: ratio {v['ratio']:.2f}, true {100 * v['true_on_box']:.3f} %, stated grid + alg. "
                  f"{100 * v['stated_grid_alg']:.3f} %, total {100 * v['stated_total']:.3f} %")
    if not any(f in rec for f in ("Hc", "Hm")):
        print(json.dumps({k: rec.get(k) for k in ("result", "finer")})[:400])


if __name__ == "__main__":
    main()
