"""Time to a verified answer: the whole `ehl solve` process at a target accuracy, its status, its
estimated error and, where a deep reference exists, its true error (issue "Accuracy per second").

Each (case, accuracy) runs `python -m ehl_multigrid solve ... --json --no-plots` in a fresh
process (numba cache warm: one warm-up run first) and records the wall time of the process, the
status, Hc and Hm with their estimated errors, the grid, box and work units of the returned solve,
the refinement sequence (solves and their purpose) and the load average before and after. The
true error is taken against the stored deep references of validation/accuracy
(`python validation/accuracy/references.py` writes them to build/validation/accuracy/references;
without them the column is empty). A verified answer is one whose status is converged and whose
true error is within the estimate.

    python validation/bench/verified.py --label before
    python validation/bench/verified.py --label quick --accuracies 0.05 0.01 --cases circular_20_10
    git worktree add /tmp/before REV && python validation/bench/verified.py --label before --code /tmp/before

writes build/validation/bench/verified_<label>.json and .md. Timings depend on the machine's
load: compare labels measured under the same conditions (the load average is recorded).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("bench")
REFS = Path(out_dir("accuracy/references"))
FAR_REFS = Path(out_dir("accuracy/far_references"))

#: name -> (arguments of `ehl solve`, reference key (contact, M, L, theta) or None)
CASES: dict[str, tuple[list[str], tuple[str, float, float, float] | None]] = {
    "circular_20_10": (["--contact", "point", "--M", "20", "--L", "10"], ("point", 20.0, 10.0, 1.0)),
    "circular_100_10": (["--contact", "point", "--M", "100", "--L", "10"], ("point", 100.0, 10.0, 1.0)),
    "elliptic_50_10_theta0.3": (["--contact", "elliptic", "--M", "50", "--L", "10", "--ellipticity", "0.3"], None),
    "elliptic_50_10_theta3": (["--contact", "elliptic", "--M", "50", "--L", "10", "--ellipticity", "3"], None),
    "line_3000_6": (["--contact", "line", "--M", "3000", "--L", "6"], None),
    "line_1500_8": (["--contact", "line", "--M", "1500", "--L", "8"], None),
    "line_1000_10": (["--contact", "line", "--M", "1000", "--L", "10"], ("line", 1000.0, 10.0, 1.0)),
    "line_5000_25": (["--contact", "line", "--M", "5000", "--L", "25"], None),
    "line_100_20": (["--contact", "line", "--M", "100", "--L", "20"], ("line", 100.0, 20.0, 1.0)),
    "bearing_6205": (["bearing_6205_inner_race"], None),
    "thermal_T9_line": (["appendix_c_line_4240N", "--thermal"], None),
    "thermal_T9_point": (["appendix_d_point", "--thermal"], None),
}
ACCURACIES = (0.05, 0.01, 0.005, 0.001)


def load() -> float:
    return os.getloadavg()[0]


def reference(key: tuple[str, float, float, float] | None, refs: str = "sharper") -> dict[str, Any] | None:
    """The stored deep reference of validation/accuracy for ``key``, or None: ``refs`` "p0"
    (references.py: P = 0 on boxes up to 8x, extrapolated), "far" (far_references.py: the
    far-field boundary; circular contacts) or "sharper" (per film, the one of smaller
    uncertainty; the two agree within their joint uncertainty on every circular case)."""
    if key is None:
        return None
    contact, M, L, theta = key
    name = f"{contact}_M{M:g}_L{L:g}_t{theta:g}.json"  # validation/accuracy/references.ref_path
    found = {}
    for kind, root in (("p0", REFS), ("far", FAR_REFS)):
        path = root / name
        if refs in (kind, "sharper") and path.exists():
            rec = json.loads(path.read_text())
            if rec.get("ok"):
                found[kind] = rec
    if len(found) < 2:
        return next(iter(found.values()), None)
    out: dict[str, Any] = {"ok": True, "kind": {}}
    for k in ("Hc", "Hm"):
        kind = min(found, key=lambda q: found[q][k + "_unc"])
        out.update({k + "_ref": found[kind][k + "_ref"], k + "_unc": found[kind][k + "_unc"]})
        out["kind"][k] = kind
    return out


def ehl_command(code: str | None = None) -> list[str]:
    """The command that runs `ehl`: the installed package, or the package of the checkout
    ``code`` (a git worktree of another revision: the "before" of a before/after table)."""
    if code is None:
        return [sys.executable, "-m", "ehl_multigrid"]
    boot = ("import runpy, sys; sys.path.insert(0, sys.argv.pop(1)); "
            "runpy.run_module('ehl_multigrid', run_name='__main__', alter_sys=True)")
    return [sys.executable, "-c", boot, str(Path(code).resolve())]


def run(case: str, accuracy: float, timeout: float, code: str | None = None) -> dict[str, Any]:
    args, key = CASES[case]
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [*ehl_command(code), "solve", *args, "--accuracy", f"{accuracy:g}",
               "--json", "--no-plots", "--out", tmp]
        l0, t0 = load(), time.perf_counter()
        try:
            p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            return {"case": case, "accuracy": accuracy, "status": "timeout", "wall_s": timeout}
        wall = time.perf_counter() - t0
    row: dict[str, Any] = {"case": case, "accuracy": accuracy, "wall_s": wall, "exit": p.returncode,
                           "load_before": l0, "load_after": load()}
    try:
        out = json.loads(p.stdout)
    except json.JSONDecodeError:
        row.update(status="no output", stderr=p.stderr[-400:])
        return row
    for k in ("status", "Hc", "Hm", "Hc_venner", "Hm_venner", "Hc_error", "Hm_error", "points",
              "work_units", "wall_total_s", "estimate_s", "levels", "Hc_field", "Hm_field", "message"):
        row[k] = out.get(k)  # Hc_field, Hm_field: the finest grid's films where Hc, Hm are extrapolated
    ref = reference(key)
    if ref is not None and out.get("Hc_venner") is not None:
        row["Hc_true"] = abs(out["Hc_venner"] / ref["Hc_ref"] - 1.0)
        row["Hm_true"] = abs(out["Hm_venner"] / ref["Hm_ref"] - 1.0)
        row["verified"] = (row["status"] == "converged" and row["Hc_true"] <= row["Hc_error"]
                           and row["Hm_true"] <= row["Hm_error"])
    return row


def table(rows: list[dict[str, Any]]) -> str:
    def pct(v: Any) -> str:
        return "" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{100 * v:.3g} %"

    def estimator(r: dict[str, Any]) -> str:
        # the estimates' seconds (probes, repair solves) and their share of the solves' own
        est, total = r.get("estimate_s"), r.get("wall_total_s")
        if est is None or total is None or total <= est:
            return ""
        return f"{est:.2f} ({est / (total - est):.0%})"

    lines = ["| case | accuracy | wall [s] | status | points | levels | WU | estimator [s] (of the solves) "
             "| est. Hc / Hm | true Hc / Hm | verified | load |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        wu = r.get("work_units")
        lines.append(f"| {r['case']} | {r['accuracy']:g} | {r['wall_s']:.1f} | {r.get('status')} | "
                     f"{r.get('points', '')} | {r.get('levels', '')} | {'' if wu is None else f'{wu:.0f}'} | "
                     f"{estimator(r)} | {pct(r.get('Hc_error'))} / {pct(r.get('Hm_error'))} | "
                     f"{pct(r.get('Hc_true'))} / {pct(r.get('Hm_true'))} | {r.get('verified', '')} | "
                     f"{r.get('load_before', math.nan):.1f} |")
    return "\n".join(lines)


def revision(code: str | None) -> str:
    """The git revision of the package that ran (the checkout ``code`` or this one)."""
    where = Path(code) if code else Path(__file__).resolve().parents[2]
    p = subprocess.run(["git", "-C", str(where), "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
    return p.stdout.strip() or "unknown"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--label", default="verified")
    ap.add_argument("--cases", nargs="*", default=list(CASES), choices=list(CASES))
    ap.add_argument("--accuracies", nargs="*", type=float, default=list(ACCURACIES))
    ap.add_argument("--timeout", type=float, default=1800.0, help="seconds per run")
    ap.add_argument("--code", default=None,
                    help="run the package of this checkout instead of the installed one (e.g. a "
                         "`git worktree add /tmp/before REV`: the 'before' of a before/after table)")
    args = ap.parse_args()
    # numba cache and imports warm before timing
    subprocess.run([*ehl_command(args.code), "solve", "--contact", "point", "--M", "20",
                    "--L", "10", "--accuracy", "0.1", "--json", "--no-plots", "--out",
                    tempfile.mkdtemp()], capture_output=True)
    rows = []
    path = Path(OUT) / f"verified_{args.label}.json"
    for case in args.cases:
        for acc in args.accuracies:
            row = run(case, acc, args.timeout, args.code)
            rows.append(row)
            print(f"{case} at {acc:g}: {row['wall_s']:.1f} s, {row.get('status')}, "
                  f"est. {row.get('Hc_error')}, {row.get('Hm_error')}", file=sys.stderr)
            tmp = path.with_suffix(".json.tmp")
            tmp.write_text(json.dumps({"rows": rows, "python": sys.version, "code": revision(args.code)},
                                      indent=1))
            tmp.replace(path)  # every finished run kept when interrupted
    md = path.with_suffix(".md")
    md.write_text(table(rows) + "\n")
    print(table(rows))


if __name__ == "__main__":
    main()
