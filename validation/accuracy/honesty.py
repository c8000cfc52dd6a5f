"""Are the error estimates honest? Every case of common.LINE_CASES / POINT_CASES is solved with
the default options at its tested grids (``solve_line(M, L, points=N)``,
``solve_point(M, L, theta=theta, points=N)``: the estimate is on by default) and its estimated
relative errors of Hc and Hm are compared with the true errors against the independent
references of references.py. The true error is also split like the budget:

* algebraic: the default solve against a tight-tolerance solve on the same grid and box;
* grid: the tight solve on the default box against the default box's grid limit (Richardson);
* domain: the default box's grid limit against the reference (box extrapolated).

Targets: the true error is below the estimate in >= 95 % of the cases, and the median of
true/estimated lies between 0.2 and 1.

    python validation/accuracy/honesty.py           # runs what is missing, writes build/validation/accuracy/honesty.*
"""

from __future__ import annotations

import math
import statistics
import time
from typing import Any

import numpy as np
from common import (
    LINE_CASES,
    OUT,
    POINT_CASES,
    code_version,
    fmt,
    load_avg,
    nan,
    read_json,
    usable,
    write_json,
)
from references import ref_path, reference
from tqdm import tqdm

TESTED = OUT / "tested"
TESTED.mkdir(exist_ok=True)
PARTS = ("grid", "domain", "algebraic")


def cases() -> list[tuple[str, float, float, float, int]]:
    out = [("line", M, L, 1.0, n) for (M, L), grids in LINE_CASES.items() for n in grids]
    out += [("point", M, L, t, n) for (M, L, t), grids in POINT_CASES.items() for n in grids]
    return out


def tested_solve(contact: str, M: float, L: float, theta: float, n: int) -> dict[str, Any]:
    """The default solve with its error estimate, cached in build/validation/accuracy/tested."""
    path = TESTED / f"{contact}_M{fmt(M)}_L{fmt(L)}_t{fmt(theta)}_n{n}.json"
    rec = read_json(path)
    if rec is not None and rec.get("code") == code_version():
        return rec
    from ehl_multigrid.line import solve_line
    from ehl_multigrid.point import solve_point

    load0, t0, c0 = load_avg(), time.perf_counter(), time.process_time()
    try:
        if contact == "line":
            sol = solve_line(M, L, points=n, raise_on_failure=False)
        else:
            sol = solve_point(M, L, theta=theta, points=n)
        e = sol.error
        rec = {"Hc_venner": sol.scalars["Hc_venner"], "Hm_venner": sol.scalars["Hm_venner"],
               "status": sol.status_name, "success": bool(sol.success), "message": sol.message,
               "Hc_error": nan(sol.scalars.get("Hc_error")), "Hm_error": nan(sol.scalars.get("Hm_error")),
               "budget": e.budget if e is not None else None,
               "order_Hc": e.order_Hc if e is not None else None,
               "order_Hm": e.order_Hm if e is not None else None,
               "notes": list(e.notes) if e is not None else [],
               "fmg": [{k: d.get(k) for k in ("level", "points", "Hc", "Hm")} for d in sol.fmg],
               "refinements": sol.extra.get("refinements"), "solver_wall_s": float(sol.wall_s)}
    except Exception as exc:  # noqa: BLE001 -- a failed default solve is a result of the study
        rec = {"status": "error", "success": False, "message": f"{type(exc).__name__}: {exc}"}
    rec.update(contact=contact, M=M, L=L, theta=theta, points=n, code=code_version(),
               wall_s=time.perf_counter() - t0,
               cpu_s=time.process_time() - c0, load_before=load0, load_after=load_avg())
    write_json(path, rec)
    return rec


def compare(case: tuple[str, float, float, float, int], ref: dict[str, Any], t: dict[str, Any]) -> dict[str, Any]:
    contact, M, L, theta, n = case
    row: dict[str, Any] = {"contact": contact, "M": M, "L": L, "theta": theta, "points": n,
                           "status": t.get("status"), "wall_s": t.get("wall_s"),
                           "solver_wall_s": t.get("solver_wall_s"), "notes": t.get("notes"),
                           "ref_method": ref.get("method")}
    if not ref.get("ok") or t.get("Hc_venner") is None:
        row["usable"] = False
        row["reason"] = ref.get("reason") if not ref.get("ok") else t.get("message")
        return row
    tight = ref["solves"].get(f"{n}_box1")
    for k in ("Hc", "Hm"):
        F, R, R1 = t[f"{k}_venner"], ref[f"{k}_ref"], ref["grid_ref"][k]
        true = F / R - 1.0
        est = nan(t.get(f"{k}_error"))
        parts_true = {"domain": R1 / R - 1.0}
        if usable(tight):
            Ft = tight[f"{k}_venner"]
            parts_true["algebraic"] = F / Ft - 1.0
            parts_true["grid"] = Ft / R1 - 1.0
        b = t.get("budget") or {}
        row[k] = {"value": F, "ref": R, "ref_unc": ref[f"{k}_unc"], "true": true, "est": est,
                  "ratio": abs(true) / est if est and math.isfinite(est) else math.nan,
                  "covered": bool(abs(true) <= est) if math.isfinite(est) else False,
                  "ambiguous": bool(abs(abs(true) - est) <= ref[f"{k}_unc"]) if math.isfinite(est) else False,
                  "parts_true": parts_true,
                  "parts_est": {p: nan((b.get(p) or {}).get(k)) for p in PARTS}}
        # which part of the budget is short of its true counterpart
        row[k]["short"] = [p for p in PARTS if p in parts_true and math.isfinite(row[k]["parts_est"][p])
                           and abs(parts_true[p]) > row[k]["parts_est"][p]]
    row["usable"] = math.isfinite(row["Hc"]["est"]) and math.isfinite(row["Hm"]["est"])
    if not row["usable"]:
        row["reason"] = "estimate not available (NaN or inf)"
    return row


def summary(rows: list[dict[str, Any]]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for name, sel in (("line", "line"), ("point", "point"), ("overall", None)):
        rr = [r for r in rows if r.get("usable") and (sel is None or r["contact"] == sel)]
        s: dict[str, Any] = {"cases": len(rr),
                             "without_estimate": len([r for r in rows if not r.get("usable")
                                                      and (sel is None or r["contact"] == sel)])}
        for k in ("Hc", "Hm", "both"):
            ks = ("Hc", "Hm") if k == "both" else (k,)
            cov = [r[q]["covered"] for r in rr for q in ks]
            rat = [r[q]["ratio"] for r in rr for q in ks if math.isfinite(r[q]["ratio"])]
            amb = [r[q]["ambiguous"] and not r[q]["covered"] for r in rr for q in ks]
            s[k] = {"n": len(cov), "fraction_covered": sum(cov) / len(cov) if cov else math.nan,
                    "median_ratio": statistics.median(rat) if rat else math.nan,
                    "ratio_p10_p90": [float(np.percentile(rat, 10)), float(np.percentile(rat, 90))] if rat else None,
                    "uncovered_within_ref_uncertainty": sum(amb)}
        out[name] = s
    return out


def plot(rows: list[dict[str, Any]], path) -> None:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10, 4.6))
    for ax, k in zip(fig.subplots(1, 2), ("Hc", "Hm"), strict=True):
        for contact, mk, col in (("line", "o", "C0"), ("point", "s", "C3")):
            rr = [r for r in rows if r.get("usable") and r["contact"] == contact]
            est = np.array([r[k]["est"] for r in rr])
            tru = np.array([max(abs(r[k]["true"]), 1e-5) for r in rr])
            unc = np.array([r[k]["ref_unc"] for r in rr])
            ax.errorbar(est, tru, yerr=np.minimum(unc, 0.999 * tru), fmt=mk, color=col, ms=5,
                        alpha=0.8, label=f"{contact} ({len(rr)})", elinewidth=0.8)
        lo, hi = 1e-4, 10.0
        ax.plot([lo, hi], [lo, hi], "k-", lw=1, label="true = estimate")
        ax.plot([lo, hi], [0.2 * lo, 0.2 * hi], "k:", lw=1, label="true = 0.2 x estimate")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(lo, hi)
        ax.set_ylim(lo, hi)
        ax.set_xlabel(f"estimated relative error of {k}")
        ax.set_ylabel(f"true relative error of {k} (bar: reference uncertainty)")
        ax.grid(True, which="major", alpha=0.3)
        ax.legend(fontsize=8, loc="upper left")
    fig.suptitle("Error estimates of the default solves against independent references")
    fig.tight_layout()
    fig.savefig(path, dpi=130)


def table(rows: list[dict[str, Any]]) -> str:
    lines = ["| contact | (M, L, theta) | N | Hc est | Hc true | ratio | Hm est | Hm true | ratio | "
             "short parts (true > est) |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        case = f"({r['M']:g}, {r['L']:g}" + (f", {r['theta']:g})" if r["contact"] == "point" else ")")
        if not r.get("usable"):
            lines.append(f"| {r['contact']} | {case} | {r['points']} | - | - | - | - | - | - | "
                         f"{r.get('reason', '')[:90]} |")
            continue
        c, m = r["Hc"], r["Hm"]

        def cell(q):
            flag = "" if q["covered"] else (" **(a)**" if q["ambiguous"] else " **!**")
            return f"{100 * q['est']:.3g} % | {100 * q['true']:+.3g} %{flag} | {q['ratio']:.2f}"
        short = "; ".join(f"{k}: {', '.join(r[k]['short'])}" for k in ("Hc", "Hm") if r[k]["short"])
        lines.append(f"| {r['contact']} | {case} | {r['points']} | {cell(c)} | {cell(m)} | {short} |")
    return "\n".join(lines)


def main() -> None:
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--contact", choices=("line", "point", "all", "none"), default="all",
                    help="run the missing solves of this contact (none: only assemble what exists)")
    args = ap.parse_args()
    todo = [c for c in cases() if args.contact in ("all", c[0])]
    bar = tqdm(todo, desc="honesty")
    for case in bar:
        contact, M, L, theta, n = case
        bar.set_postfix_str(f"{contact} ({M:g}, {L:g}, {theta:g}) {n}")
        reference(contact, M, L, theta, bar)
        tested_solve(*case)
    rows = []
    for case in cases():
        contact, M, L, theta, n = case
        ref = read_json(ref_path(contact, M, L, theta))
        t = read_json(TESTED / f"{contact}_M{fmt(M)}_L{fmt(L)}_t{fmt(theta)}_n{n}.json")
        if ref is None or t is None:
            continue
        rows.append(compare(case, ref, t))
    summ = summary(rows)
    write_json(OUT / "honesty.json", {"summary": summ, "rows": rows,
                                      "targets": {"fraction_covered": 0.95, "median_ratio": [0.2, 1.0]}})
    plot(rows, OUT / "honesty.png")
    print(table(rows))
    print()
    print("| set | cases | fraction true <= est (Hc, Hm, both) | median true/est (Hc, Hm, both) | no estimate |")
    print("|---|---|---|---|---|")
    for name, s in summ.items():
        fr = ", ".join(f"{100 * s[k]['fraction_covered']:.0f} %" for k in ("Hc", "Hm", "both"))
        md = ", ".join(f"{s[k]['median_ratio']:.2f}" for k in ("Hc", "Hm", "both"))
        print(f"| {name} | {s['cases']} | {fr} | {md} | {s['without_estimate']} |")


if __name__ == "__main__":
    main()
