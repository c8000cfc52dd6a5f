"""Is the algebraic (iteration) part of the error estimate honest on its own?

Reads the cases of ``build/validation/bench/grid_stop.json`` (``validation/bench/grid_stop.py``) (each solved with the default stop,
the residual rule alone and a deep reference with tolerances ten times tighter; the finest-grid
films of every cycle are stored) and evaluates rules that turn the last finest-grid changes into
an iteration-error estimate against the true distance to the deep solve:

* ``last``: the last change times ``rho/(1 - rho)`` when the changes contract more slowly than
  1/2, else times 1 (the rule of :func:`~ehl_multigrid.multigrid.accuracy.iteration_factor`
  before this study);
* ``floor2``: the same with a contraction up to 2/3 assumed (factor at least 2);
* ``prev``: the larger of ``last`` and half the change before it (a last change small by
  accident in a sequence that does not contract geometrically);
* ``floor2_prev``: both;
* ``..._rho2``: the contraction taken as the larger of the last two ratios of changes (a last
  ratio small by accident in a slowly drifting sequence); ``prev_rho2`` is the package's
  :func:`~ehl_multigrid.multigrid.accuracy.iteration_error`, called as such.

Each adds the load error times :data:`LOAD_SENSITIVITY`. A film is *covered* when its true
distance to the deep solve is within its estimate plus the deep solve's own estimate (same
rule). Writes ``build/validation/accuracy/iteration_estimate.json`` and prints a table.

    python validation/accuracy/iteration_estimate.py [PATH]
"""

from __future__ import annotations

import json
import math
import statistics
import sys
from pathlib import Path

from ehl_multigrid.multigrid.accuracy import LOAD_SENSITIVITY, MAX_ITERATION_FACTOR, iteration_error

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
from _paths import BUILD, out_dir, require  # noqa: E402

SOURCE = BUILD / "bench" / "grid_stop.json"


def factor(films: list[float], floor_rho: float, ratios: int = 1) -> float:
    """``rho/(1 - rho)`` of the last changes, at least ``floor_rho/(1 - floor_rho)`` (the
    contraction assumed when the changes fall faster); ``rho`` is the largest of the last
    ``ratios`` ratios of successive changes."""
    base = floor_rho / (1.0 - floor_rho)
    d = [abs(b - a) for a, b in zip(films[:-1], films[1:], strict=True)]
    if len(d) < 2 or d[-1] == 0.0:
        return base
    rho = 0.0
    for k in range(1, min(ratios, len(d) - 1) + 1):
        rho = max(rho, d[-k] / d[-k - 1] if d[-k - 1] > 0.0 else math.inf)
    if rho >= 0.95:
        return MAX_ITERATION_FACTOR
    return max(base, rho / (1.0 - rho))


def estimate(films: list[float], load_error: float, rule: str) -> float:
    if len(films) < 2:
        return math.nan
    last = films[-1]
    if rule == "prev_rho2":  # the rule the package adopted: evaluate the package's own code
        return iteration_error(films) / abs(last) + LOAD_SENSITIVITY * abs(load_error)
    floor_rho = 2.0 / 3.0 if rule.startswith("floor2") else 0.5
    est = abs(films[-1] - films[-2]) * factor(films, floor_rho, 2 if rule.endswith("rho2") else 1)
    if "prev" in rule and len(films) >= 3:
        est = max(est, 0.5 * abs(films[-2] - films[-3]))
    return est / abs(last) + LOAD_SENSITIVITY * abs(load_error)


RULES = ("last", "floor2", "prev", "floor2_prev", "prev_rho2", "floor2_prev_rho2")


def evaluate(rows: list[dict]) -> dict:
    out: dict = {}
    for variant in ("default", "residual"):
        for rule in RULES:
            ratios, covered, n = [], 0, 0
            for row in rows:
                r, ref = row[variant], row["deep"]
                if r.get("status") != "converged" or ref.get("status") != "converged":
                    continue
                if "finest" not in r or "finest" not in ref:
                    continue
                for f in ("Hc", "Hm"):
                    films = [c[f] for c in r["finest"]]
                    rfilms = [c[f] for c in ref["finest"]]
                    est = estimate(films, r["finest"][-1]["load_error"], rule)
                    rest = estimate(rfilms, ref["finest"][-1]["load_error"], rule)
                    if not (math.isfinite(est) and math.isfinite(rest)):
                        continue
                    true = abs(films[-1] / rfilms[-1] - 1.0)
                    n += 1
                    covered += true <= est + rest
                    ratios.append(true / est if est > 0 else math.inf)
            out[f"{variant}/{rule}"] = {
                "films": n, "covered": covered, "fraction": covered / n if n else math.nan,
                "median_true_over_est": statistics.median(ratios) if ratios else math.nan,
                "max_true_over_est": max(ratios) if ratios else math.nan}
    return out


def main() -> None:
    path = Path(sys.argv[1]) if len(sys.argv) > 1 else SOURCE
    rows = json.loads(require(path, "python validation/bench/grid_stop.py").read_text())["rows"]
    res = evaluate(rows)
    (out_dir("accuracy") / "iteration_estimate.json").write_text(json.dumps({"source": str(path), "rules": res}, indent=1))
    print("| stop / rule | films | covered | fraction | median true/est | max true/est |")
    print("|---|---|---|---|---|---|")
    for key, v in res.items():
        print(f"| {key} | {v['films']} | {v['covered']} | {v['fraction']:.3f} | "
              f"{v['median_true_over_est']:.3g} | {v['max_true_over_est']:.3g} |")


if __name__ == "__main__":
    main()
