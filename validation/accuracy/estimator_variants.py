"""What-if: would other rules for the error estimate be more honest? Every usable row of
out/honesty.json is re-estimated with the package's own Richardson rule
(``ehl_multigrid.multigrid.accuracy.richardson``, GRID_SAFETY, the order cap) fed with
different inputs, against the same true errors:

* ``current`` -- the estimate the solver reported;
* ``grid_converged`` -- the grid part from tight solves on N/4, N/2, N (converged discrete
  solutions) instead of the FMG's intermediate films, which two cycles per level leave far
  from the discrete solution in the hard cases (L = 0, L = 20, M >= 100);
* ``domain_decay`` -- the domain part from boxes 1x, 2x AND 4x at equal mesh: the measured
  decay r per doubling gives the remainder ``d2 r/(r - 1)``; times 1.25, or the current
  ``1.5 d2`` where r >= 3 (the current rule's assumption holds);
* ``hm_order_cap``, ``grid_converged_hm_cap`` -- the minimum film's order capped at 1.5
  instead of 2 (its measured asymptotic order on fine line grids is 1.5-1.6);
* ``both`` -- converged coarse solves with the Hm cap 1.5, and the measured box decay.

The box changes are the references' box series (mesh of the largest tested line grid, the
smallest tested point grid -- the point solver's probe mesh); the algebraic part is the one
the solver reported. Writes out/estimator_variants.json and prints the summary table.

    python validation/accuracy/estimator_variants.py
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
    usable,
    write_json,
)
from references import ref_path

from ehl_multigrid.multigrid.accuracy import DOMAIN_SAFETY, GRID_SAFETY, richardson

VARIANTS = ("current", "hm_order_cap", "grid_converged", "grid_converged_hm_cap", "domain_decay", "both")
#: order cap of the minimum film in the variants (measured asymptotic order 1.5-1.6 on line
#: grids 1025-32769 at (20, 10) and (100, 10); the central film keeps the cap 2)
HM_CAP = 1.5


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
    """The package's rule (accuracy.richardson: first order when irregular or p < 1, times
    GRID_SAFETY) with the order cap as a parameter; relative error of the last value."""
    if cap == 2.0:
        r = richardson(values)
        return abs(r.error / values[-1])
    v = [float(x) for x in values]
    d2 = v[-1] - v[-2]
    p = 1.0
    if len(v) >= 3:
        d1 = v[-2] - v[-3]
        if d1 != 0 and d2 != 0 and (d1 > 0) == (d2 > 0) and abs(d1) > abs(d2):
            order = math.log2(abs(d1 / d2))
            p = min(order, cap) if order >= 1.0 else 1.0
    return GRID_SAFETY * abs(d2) / (2.0**p - 1.0) / abs(v[-1])


def grid_from_converged(row: dict[str, Any], cap_hm: float = 2.0) -> dict[str, float] | None:
    c, M, L, t, n = row["contact"], row["M"], row["L"], row["theta"], row["points"]
    seq = [converged_films(c, M, L, t, (n - 1) // k + 1) for k in (4, 2, 1)]
    if seq[-1] is None or seq[-2] is None:
        return None
    seq = [s for s in seq if s is not None]
    return {k: richardson_capped([s[f"{k}_venner"] for s in seq], cap_hm if k == "Hm" else 2.0)
            for k in ("Hc", "Hm")}


def grid_from_fmg(row: dict[str, Any], cap_hm: float) -> dict[str, float]:
    """The solver's own grid estimate (FMG films of the coarser grids + the final film)."""
    from honesty import TESTED

    c, M, L, t, n = row["contact"], row["M"], row["L"], row["theta"], row["points"]
    rec = read_json(TESTED / f"{c}_M{M:g}_L{L:g}_t{t:g}_n{n}.json")
    top = max(d["level"] for d in rec["fmg"])
    fmg = [d for d in rec["fmg"] if d["level"] < top]
    return {k: richardson_capped([d[k] for d in fmg] + [rec[f"{k}_venner"]], cap_hm if k == "Hm" else 2.0)
            for k in ("Hc", "Hm")}


def domain_with_decay(ref: dict[str, Any], k: str) -> float:
    bx = ref["box"][k]
    d2, d4 = nan(bx.get("d2")), nan(bx.get("d4"))
    if not math.isfinite(d4):
        return DOMAIN_SAFETY * abs(d2)
    step = d4 - d2
    r = d2 / step if step != 0 else math.inf
    if not (r > 1.0):
        return math.inf  # the change does not shrink with the box: no bound
    if r >= 3.0:
        return DOMAIN_SAFETY * abs(d2)
    return 1.25 * abs(d2) * r / (r - 1.0)


def main() -> None:
    hon = read_json(OUT / "honesty.json")
    rows = [r for r in hon["rows"] if r.get("usable")]
    out = []
    for row in rows:
        ref = read_json(ref_path(row["contact"], row["M"], row["L"], row["theta"]))
        g = grid_from_converged(row)
        g15 = grid_from_converged(row, HM_CAP)
        f15 = grid_from_fmg(row, HM_CAP)
        rec: dict[str, Any] = {k: row[k] for k in ("contact", "M", "L", "theta", "points")}
        for k in ("Hc", "Hm"):
            q = row[k]
            pe = q["parts_est"]
            grid_c = g[k] if g is not None else pe["grid"]
            grid_c15 = g15[k] if g15 is not None else pe["grid"]
            dom_d = domain_with_decay(ref, k)
            est = {"current": q["est"],
                   "hm_order_cap": f15[k] + pe["domain"] + pe["algebraic"],
                   "grid_converged": grid_c + pe["domain"] + pe["algebraic"],
                   "grid_converged_hm_cap": grid_c15 + pe["domain"] + pe["algebraic"],
                   "domain_decay": pe["grid"] + dom_d + pe["algebraic"],
                   "both": grid_c15 + dom_d + pe["algebraic"]}
            rec[k] = {"true": abs(q["true"]), "est": est,
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
