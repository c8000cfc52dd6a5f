"""Print the numbers of build/validation/line/*.json as Markdown tables (used to write REPORT.md)."""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("line")


def load(name: str) -> dict | None:
    p = OUT / f"{name}{sys.argv[1] if len(sys.argv) > 1 else ''}.json"
    return json.loads(p.read_text()) if p.is_file() else None


def f(x, fmt="{:.4f}"):
    return "-" if x is None or (isinstance(x, float) and not math.isfinite(x)) else fmt.format(x)


def main() -> None:
    g = load("grid")
    if g:
        print("## grid")
        for s in g.get("summary", []):
            print(f"\n(M, L) = ({s['M']}, {s['L']}); points {s['points']}")
            print("| quantity | " + " | ".join(str(n) for n in s["points"]) + " | order | Richardson |")
            print("|---" * (len(s["points"]) + 3) + "|")
            for q in ("Hc", "Hm", "p_spike"):
                print(f"| {q} | " + " | ".join(f(v) for v in s[q]) + f" | {f(s[q + '_order'], '{:.2f}')} | {f(s[q + '_richardson'])} |")
            if "Hc_error_pct" in s:
                print("| Hc error % | " + " | ".join(f(v, "{:.3f}") for v in s["Hc_error_pct"]) + " | | |")
        fails = [r for r in g["rows"] if not r.get("converged")]
        print("grid failures:", [(r["M"], r["points"], r.get("error")) for r in fails])
    fit = load("fit")
    if fit:
        print("\n## fit")
        print(json.dumps(fit.get("summary"), indent=1))
        for visc in ("barus", "roelands"):
            rows = [r for r in fit["rows"] if r.get("viscosity") == visc]
            Ms = sorted({r["M"] for r in rows})
            Ls = sorted({r["L"] for r in rows})
            print(f"\n{visc}: 100 (Hc/Hc_fit - 1), rows L, columns M")
            print("| L \\ M | " + " | ".join(str(m) for m in Ms) + " |")
            print("|---" * (len(Ms) + 1) + "|")
            for L in Ls:
                cells = []
                for M in Ms:
                    r = next((r for r in rows if r["M"] == M and r["L"] == L), None)
                    cells.append("fail" if r is None or "dev" not in r else f"{100 * r['dev']:.1f}")
                print(f"| {L} | " + " | ".join(cells) + " |")
            ge = [abs(r["grid_error_est"]) for r in rows if r.get("grid_error_est") is not None]
            if ge:
                print(f"max estimated grid error {100 * max(ge):.3f} %, cases > 0.5 %: "
                      f"{[(r['M'], r['L']) for r in rows if abs(r.get('grid_error_est') or 0) > 0.005]}")
    for name in ("limits", "extremes", "cost"):
        d = load(name)
        if d:
            print(f"\n## {name}")
            print(json.dumps(d.get("summary"), indent=1, default=str)[:6000])


if __name__ == "__main__":
    main()
