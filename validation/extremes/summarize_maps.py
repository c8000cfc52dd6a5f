"""Summaries of the accuracy maps written by accuracy_map.py: counts per outcome and reason,
and the fit-check map as the package's answer to "how good are the fits".

    python validation/extremes/summarize_maps.py [--extremes build/validation/extremes/accuracy_map_0.02.json]
                                                 [--fits build/validation/extremes/fit_map_0.01.json]

Writes maps_summary.json and <fits stem>.png into ``--out`` (default build/validation/extremes/), and prints
markdown tables.

The fit deviation ``Hc/Hc_fit - 1`` is reported only for cases that converged to the target,
with the solve's own estimated error beside it: a deviation larger than that error is the fit's,
not the solver's.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("extremes")


def reason(rec: dict) -> str:
    """Short reason of an honest failure, from its status and message."""
    r = rec["result"]
    st, msg = r.get("status", "?"), str(r.get("message", ""))
    if st == "inaccurate":
        if "not known" in msg and "thick against the elastic" in msg:
            return "inaccurate: thick-film inlet (box error not measurable)"
        if "not known" in msg:
            return "inaccurate: error not estimable (no converged probe)"
        if "thick against the elastic" in msg:
            return "inaccurate: thick-film inlet (box)"
        if "grid error dominates" in msg:
            return "inaccurate: grid budget (max_points)"
        if "domain (box truncation) error dominates" in msg:
            return "inaccurate: box budget"
        if "did not converge" in msg:
            return "inaccurate: finer solve failed"
        return "inaccurate: other"
    if "piezoviscous-rigid regime" in msg:
        return f"{st}: piezoviscous peak far above Hertz (physical)"
    return st


def counts(records: dict) -> dict:
    c = Counter(rec["class"] for rec in records.values())
    why = Counter(reason(rec) for rec in records.values() if rec["class"] == "honest failure")
    return {"classes": dict(c), "failure_reasons": dict(why)}


def by_contact(records: dict) -> dict:
    out: dict[str, dict] = {}
    for rec in records.values():
        key = rec["case"]["contact"]
        if "viscosity" in rec["case"]:
            key += f" {rec['case']['viscosity']}+{rec['case']['density']}"
            if rec["case"]["contact"] == "point":
                key += f" theta {rec['case']['theta']:g}"
        out.setdefault(key, {})[json.dumps(rec["case"], sort_keys=True)] = rec
    return {k: counts(v) for k, v in out.items()}


def fit_rows(records: dict) -> list[dict]:
    rows = []
    for rec in records.values():
        c, r = rec["case"], rec["result"]
        row = {**c, "class": rec["class"], "status": r.get("status"), "points": r.get("points"),
               "wall_s": r.get("wall_s"), "Hc_fit": rec.get("Hc_fit")}
        if r.get("status") == "converged":
            row["deviation"] = r["Hc"] / rec["Hc_fit"] - 1.0
            row["Hc_error"] = r["Hc_error"]
        rows.append(row)
    return rows


def fit_table(rows: list[dict]) -> str:
    groups: dict[tuple, list[dict]] = {}
    for r in rows:
        groups.setdefault((r["contact"], r["viscosity"], r["density"], r["theta"]), []).append(r)
    lines = []
    for (contact, v, d, th), rs in groups.items():
        Ms = sorted({r["M"] for r in rs})
        Ls = sorted({r["L"] for r in rs})
        title = f"{contact} {v} + {d}" + (f", theta {th:g}" if contact == "point" else "")
        lines.append(f"\n{title}: 100 (Hc/Hc_fit - 1) [estimated solver error, %]; - = no converged answer\n")
        lines.append("| M \\ L | " + " | ".join(f"{L:g}" for L in Ls) + " |")
        lines.append("|---" * (len(Ls) + 1) + "|")
        for M in Ms:
            cells = []
            for L in Ls:
                r = next((x for x in rs if x["M"] == M and x["L"] == L), None)
                if r is None or "deviation" not in r:
                    cells.append("-" if r is None else f"- ({r['status']})")
                else:
                    cells.append(f"{100 * r['deviation']:+.1f} [{100 * r['Hc_error']:.2f}]")
            lines.append(f"| {M:g} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def fit_plot(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    import numpy as np

    groups: dict[tuple, list[dict]] = {}
    for r in rows:
        groups.setdefault((r["contact"], r["viscosity"], r["density"], r["theta"]), []).append(r)
    n = len(groups)
    fig, axes = plt.subplots(1, n, figsize=(3.0 * n, 3.0), squeeze=False)
    for ax, ((contact, v, d, th), rs) in zip(axes[0], groups.items(), strict=True):
        Ms = sorted({r["M"] for r in rs})
        Ls = sorted({r["L"] for r in rs})
        Z = np.full((len(Ms), len(Ls)), np.nan)
        for r in rs:
            if "deviation" in r:
                Z[Ms.index(r["M"]), Ls.index(r["L"])] = 100 * r["deviation"]
        im = ax.imshow(Z, cmap="RdBu_r", vmin=-15, vmax=15, origin="lower", aspect="auto")
        for i in range(len(Ms)):
            for j in range(len(Ls)):
                txt = "x" if math.isnan(Z[i, j]) else f"{Z[i, j]:+.0f}"
                ax.text(j, i, txt, ha="center", va="center", fontsize=7)
        ax.set_xticks(range(len(Ls)), [f"{L:g}" for L in Ls])
        ax.set_yticks(range(len(Ms)), [f"{M:g}" for M in Ms])
        ax.set_xlabel("L")
        ax.set_ylabel("M")
        t = f"{contact} {v[:3]}+{'DH' if d.startswith('dowson') else 'inc'}"
        ax.set_title(t + (f" th={th:g}" if contact == "point" else ""), fontsize=8)
    fig.colorbar(im, ax=axes[0].tolist(), shrink=0.8, label="Hc/Hc_fit - 1 [%] (x: no converged answer)")
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--extremes", default=str(OUT / "accuracy_map_0.02.json"))
    ap.add_argument("--fits", default=str(OUT / "fit_map_0.01.json"))
    ap.add_argument("--out", default=str(OUT), help="folder of maps_summary.json and the fit-map PNG")
    ap.add_argument("--override", action="append", default=[],
                    help="a later run of some of the cases (e.g. *_theta4.json after a solver change); "
                         "its records replace those of the same case (repeatable)")
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    overrides: dict = {}
    for f in a.override:
        overrides.update(json.loads(Path(f).read_text()))
    summary = {}
    for name, path, accuracy in (("extremes", Path(a.extremes), 0.02), ("fits", Path(a.fits), 0.01)):
        if not path.is_file():
            print(f"{path} is missing (skipped): run `python validation/extremes/accuracy_map.py "
                  f"--map {name} --accuracy {accuracy:g}` first")
            continue
        recs = json.loads(path.read_text())
        replaced = [k for k in recs if k in overrides]
        recs.update({k: overrides[k] for k in replaced})
        if replaced:
            print(f"\n{name}: {len(replaced)} records replaced by the later runs")
        summary[name] = {"file": path.name, "cases": len(recs), "replaced_by_later_runs": len(replaced),
                         **counts(recs), "by_model": by_contact(recs)}
        print(f"\n## {name} ({path.name}, {len(recs)} cases)\n")
        print(json.dumps(summary[name]["classes"]), json.dumps(summary[name]["failure_reasons"]))
        for k, v in summary[name]["by_model"].items():
            print(f"- {k}: {json.dumps(v['classes'])}")
        if name == "fits":
            rows = fit_rows(recs)
            summary[name]["rows"] = rows
            print(fit_table(rows))
            fit_plot(rows, out / f"{path.stem}.png")
    tmp = out / "maps_summary.tmp"
    tmp.write_text(json.dumps(summary, indent=1))
    tmp.replace(out / "maps_summary.json")


if __name__ == "__main__":
    main()
