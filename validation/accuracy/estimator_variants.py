"""What-if: would other rules for the error estimate be more honest? Every usable row of
build/validation/accuracy/honesty.json (from ``honesty.py``) is re-estimated with the package's Richardson rule (GRID_SAFETY, the order
caps) fed with different inputs, against the same true errors. The solver's domain part is
``DOMAIN_SAFETY |d2|`` with ``d2`` the probe's change when the box is doubled, so ``|d2|``
is recovered from the reported budget.

* ``current`` -- the estimate the solver reported (the code the rows were run with);
* ``domain_x1.5`` -- the domain part with the earlier safety factor 1.5;
* ``grid_converged`` -- the grid part from tight solves on N/4, N/2, N (converged discrete
  solutions) instead of the FMG's intermediate films, which two cycles per level leave far
  from the discrete solution in the hard cases (L = 0, L = 20, M >= 100);
* ``domain_decay`` -- the domain part ``1.25 |d2| r/(r - 1)`` with ``r`` the decay of the box
  change per doubling that a third probe box (4x) measures (taken from the references' box
  series at equal mesh), instead of a fixed factor;
* ``both`` -- converged coarse solves and the measured decay.

    python validation/accuracy/estimator_variants.py   # writes build/validation/accuracy/estimator_variants.json
"""

from __future__ import annotations

import math
import statistics
from typing import Any

from common import (
    OUT,
    POINT_TIGHT,
    cached_solve,
    line_reference_solve,
    nan,
    read_json,
    require,
    usable,
    write_json,
)
from references import ref_path

from ehl_multigrid.multigrid.accuracy import DOMAIN_SAFETY, HM_MAX_ORDER, richardson

VARIANTS = ("current", "domain_x1.5", "grid_converged", "domain_decay", "both")


def converged_films(contact: str, M: float, L: float, theta: float, n: int) -> dict[str, Any] | None:
    if contact == "line":
        if n < 33:
            return None
        rec = line_reference_solve(M, L, n, 1.0)
    else:
        if n < 17:
            return None
        rec = cached_solve("point", M, L, theta, n, 1.0, **{**POINT_TIGHT, "half": True})
    return rec if usable(rec) else None


def richardson_capped(values: list[float], cap: float) -> float:
    """The package's grid-error rule with the order cap ``cap``; relative error of the last value."""
    r = richardson(values, max_order=cap)
    return abs(r.error / values[-1])


def grid_from_converged(row: dict[str, Any], cap_hm: float = 2.0) -> dict[str, float] | None:
    c, M, L, t, n = row["contact"], row["M"], row["L"], row["theta"], row["points"]
    seq = [converged_films(c, M, L, t, (n - 1) // k + 1) for k in (4, 2, 1)]
    if seq[-1] is None or seq[-2] is None:
        return None
    seq = [s for s in seq if s is not None]
    return {k: richardson_capped([s[f"{k}_venner"] for s in seq], cap_hm if k == "Hm" else 2.0)
            for k in ("Hc", "Hm")}


def box_decay(ref: dict[str, Any], k: str) -> float:
    """Decay of the box change per doubling, from boxes 1x, 2x, 4x at equal mesh (NaN without
    a 4x box; inf when the change stops; <= 1 when it does not shrink)."""
    bx = ref["box"][k]
    d2, d4 = nan(bx.get("d2")), nan(bx.get("d4"))
    step = d4 - d2
    return d2 / step if step != 0 else math.inf


def domain_with_decay(d2_probe: float, r: float) -> float:
    if not math.isfinite(r):
        return DOMAIN_SAFETY * d2_probe if math.isnan(r) else 1.25 * d2_probe
    if r <= 1.0:
        return math.inf  # the change does not shrink with the box: no bound
    return 1.25 * d2_probe * r / (r - 1.0)


def main() -> None:
    hon = read_json(require(OUT / "honesty.json", "python validation/accuracy/honesty.py"))
    rows = [r for r in hon["rows"] if r.get("usable")]
    out = []
    for row in rows:
        ref = read_json(ref_path(row["contact"], row["M"], row["L"], row["theta"]))
        g = grid_from_converged(row, HM_MAX_ORDER)
        rec: dict[str, Any] = {k: row[k] for k in ("contact", "M", "L", "theta", "points")}
        for k in ("Hc", "Hm"):
            q = row[k]
            pe = q["parts_est"]
            grid_c = g[k] if g is not None else pe["grid"]
            d2 = pe["domain"] / DOMAIN_SAFETY
            r = box_decay(ref, k)
            dom_d = domain_with_decay(d2, r)
            est = {"current": q["est"],
                   "domain_x1.5": pe["grid"] + 1.5 * d2 + pe["algebraic"],
                   "grid_converged": grid_c + pe["domain"] + pe["algebraic"],
                   "domain_decay": pe["grid"] + dom_d + pe["algebraic"],
                   "both": grid_c + dom_d + pe["algebraic"]}
            rec[k] = {"true": abs(q["true"]), "est": est, "decay": r, "d2_probe": d2,
                      "grid_converged_available": g is not None}
        out.append(rec)
    summ: dict[str, Any] = {}
    for v in VARIANTS:
        for name, sel in (("line", "line"), ("point", "point"), ("overall", None)):
            rr = [r for r in out if sel is None or r["contact"] == sel]
            cov = [r[k]["true"] <= r[k]["est"][v] for r in rr for k in ("Hc", "Hm")]
            rat = [r[k]["true"] / r[k]["est"][v] for r in rr for k in ("Hc", "Hm")]
            summ.setdefault(v, {})[name] = {"fraction_covered": sum(cov) / len(cov),
                                            "median_ratio": statistics.median(rat),
                                            "worst_ratio": max(rat), "n": len(cov)}
    write_json(OUT / "estimator_variants.json", {"summary": summ, "rows": out})
    print("| variant | line: covered, median true/est, worst | point | overall |")
    print("|---|---|---|---|")
    for v in VARIANTS:
        cells = [f"{100 * s['fraction_covered']:.0f} %, {s['median_ratio']:.2f}, {s['worst_ratio']:.2f}"
                 for s in (summ[v][n] for n in ("line", "point", "overall"))]
        print(f"| {v} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
