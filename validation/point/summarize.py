"""Print markdown tables from build/validation/point/*.json (used to write REPORT.md)."""

import json
import sys

from common import OUT


def _load(name):
    p = OUT / name
    return json.loads(p.read_text()) if p.exists() else None


def f(v, fmt="{:.4g}"):
    return "-" if v is None else (fmt.format(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else str(v))


def main() -> None:
    q = "_quick" if "--quick" in sys.argv else ""
    t = _load("targets.json")
    if t:
        print("## targets")
        for n in ("513", "1025"):
            for r in t["runs"][n]:
                print(f"| {n} | {f(r['solver_wall_s'], '{:.2f}')} | {f(r.get('solve_cpu_s'), '{:.2f}')} | {f(r['Hc_err_pct'], '{:.3f}')} | "
                      f"{r['converged']} | {f(r['maxrss_MB'], '{:.0f}')} | {f(r['load_before'], '{:.1f}')} |")
    g = _load(f"grid_convergence_summary{q}.json")
    if g:
        print("## grid convergence")
        for k, s in g["summary"].items():
            print(f"| {k} | " + " | ".join(f(v) for v in s["Hc"]) + f" | {f(s['order_Hc'], '{:.2f}')} | {f(s['Hc_extrapolated'])} |")
            print(f"| {k} Hm | " + " | ".join(f(v) for v in s["Hm"]) + f" | {f(s['order_Hm'], '{:.2f}')} | {f(s['Hm_extrapolated'])} |")
            print(f"| {k} spike | " + " | ".join(f(v) for v in s["p_spike"]) + " | | |")
            print(f"| {k} conv | " + " | ".join(str(v) for v in s["converged"]) + " | | |")
    c = _load(f"cost_summary{q}.json")
    if c:
        print("## cost")
        print(json.dumps(c["summary"], indent=1)[:6000])
    e = _load(f"extremes_summary{q}.json")
    if e:
        print("## extremes", e["summary"]["counts"])
        for k, v in e["summary"]["failures"].items():
            print(" ", k, v)
    fc = _load(f"fit_check_summary{q}.json")
    if fc:
        print("## fit check")
        for k, v in fc["summary"].items():
            if isinstance(v, dict) and "dev_pct" in v:
                print(k, v["M"], v["L"])
                for L, row in zip(v["L"], v["dev_pct"], strict=True):
                    print(f"| {L} | " + " | ".join(f(x, '{:.1f}') for x in row) + " |")
        print(fc["summary"].get("counts"))


if __name__ == "__main__":
    main()
