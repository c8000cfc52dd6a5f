"""Markdown tables of REPORT.md from before.json, after.json (``study.py``), sequence.json
(``sequence.py``) and fitmap_failures.json (``fitmap_failures.py``) in
build/validation/line_fine/ (prints them)."""

from __future__ import annotations

import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir, require  # noqa: E402

OUT = out_dir("line_fine")
SCRIPT = "python validation/line_fine/"


def read(name: str, command: str, note: str = "") -> dict:
    return json.loads(require(OUT / name, SCRIPT + command, note).read_text())


def num(z: float | None) -> str:
    return "nan" if z is None else f"{z:.3g}"


def cell(r: dict) -> str:
    if r.get("status") in (None, "error"):
        return f"{r.get('status')} | | | |"
    return f"{r['status']} | {r['cycles']} | {r['work_units']:.0f} | {r['Hc']:.5f} | {r['Hm']:.5f}"


def main() -> None:
    b = read("before.json", "study.py before", "; run it with the code before the change on PYTHONPATH")["cases"]
    a = read("after.json", "study.py after")["cases"]
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
    seq = read("sequence.json", "sequence.py")
    print("\n| case | grids: Hc (status) | Hc order | Hm order |\n|---|---|---|---|")
    for k, v in seq.items():
        g = ", ".join(f"{x['points']}: {x['Hc']:.5f}" + ("" if x["status"] == "converged" else f" ({x['status']})")
                      for x in v["solves"])
        print(f"| {k} | {g} | {', '.join(f'{p:.2f}' for p in v['Hc_order'])} | "
              f"{', '.join(f'{p:.2f}' for p in v['Hm_order'])} |")
    fm = read("fitmap_failures.json", "fitmap_failures.py")
    print("\n| case | map before | points | after | points | Hc | Hm | Hc_error | Hm_error |\n|---|---|---|---|---|---|---|---|---|")
    for k, v in fm.items():
        x, y = v["before"], v["after"]
        print(f"| {k} | {x['status']} | {x['points']} | {y['status']} | {y['points']} | {y['Hc']:.4f} | "
              f"{y['Hm']:.4f} | {num(y['Hc_error'])} | {num(y['Hm_error'])} |")


if __name__ == "__main__":
    main()
