"""Markdown tables of REPORT.md from out/before.json, out/after.json, out/sequence.json and
out/fitmap_failures.json (prints them)."""

from __future__ import annotations

import json
from pathlib import Path

OUT = Path(__file__).parent / "out"


def num(z: float | None) -> str:
    return "nan" if z is None else f"{z:.3g}"


def cell(r: dict) -> str:
    if r.get("status") in (None, "error"):
        return f"{r.get('status')} | | | |"
    return f"{r['status']} | {r['cycles']} | {r['work_units']:.0f} | {r['Hc']:.5f} | {r['Hm']:.5f}"


def main() -> None:
    b = json.loads((OUT / "before.json").read_text())["cases"]
    a = json.loads((OUT / "after.json").read_text())["cases"]
    for group in ("listed", "regression"):
        print(f"\n{group}\n")
        print("| case | before: status | cycles | WU | Hc | Hm | after: status | cycles | WU | Hc | Hm |")
        print("|---|---|---|---|---|---|---|---|---|---|---|")
        for k, x in b.items():
            if x["group"] == group:
                print(f"| {k} | {cell(x)} | {cell(a[k])} |")
        conv = [k for k, x in b.items() if x["group"] == group]
        nb = sum(b[k]["status"] == "converged" for k in conv)
        na = sum(a[k]["status"] == "converged" for k in conv)
        lost = [k for k in conv if b[k]["status"] == "converged" and a[k]["status"] != "converged"]
        print(f"\nconverged before {nb}/{len(conv)}, after {na}/{len(conv)}, lost {lost}")
    seq = json.loads((OUT / "sequence.json").read_text())
    print("\n| case | grids: Hc (status) | Hc order | Hm order |\n|---|---|---|---|")
    for k, v in seq.items():
        g = ", ".join(f"{x['points']}: {x['Hc']:.5f}" + ("" if x["status"] == "converged" else f" ({x['status']})")
                      for x in v["solves"])
        print(f"| {k} | {g} | {', '.join(f'{p:.2f}' for p in v['Hc_order'])} | "
              f"{', '.join(f'{p:.2f}' for p in v['Hm_order'])} |")
    fm = json.loads((OUT / "fitmap_failures.json").read_text())
    print("\n| case | map before | points | after | points | Hc | Hm | Hc_error | Hm_error |\n|---|---|---|---|---|---|---|---|---|")
    for k, v in fm.items():
        x, y = v["before"], v["after"]
        print(f"| {k} | {x['status']} | {x['points']} | {y['status']} | {y['points']} | {y['Hc']:.4f} | "
              f"{y['Hm']:.4f} | {num(y['Hc_error'])} | {num(y['Hm_error'])} |")


if __name__ == "__main__":
    main()
