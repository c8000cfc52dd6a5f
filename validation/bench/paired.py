"""Paired before/after timing on a shared machine: the same (case, grid) solved alternately by
an old source tree and the working tree, each solve in a fresh process (bench.py's child:
warm-up, then one timed solve), so both see the same background load.

    git archive <commit> | tar -x -C /tmp/old
    python validation/bench/paired.py --old /tmp/old --cases point,point_half --points 513 1025

writes ``build/validation/bench/paired.json`` and ``build/validation/bench/paired.md`` (median wall and CPU time of each side, their
ratio, the load average over the runs). ``--threads-pair`` compares one thread ("old" column)
with two threads ("new" column) on the working tree instead.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from bench import CASES, OUT  # noqa: E402


def one(tree: str | None, name: str, points: int, threads: int | None) -> dict:
    env = dict(os.environ)
    if tree:
        env["PYTHONPATH"] = tree
    spec = {**CASES[name], "points": points, "repeat": 1, "threads": threads}
    load = os.getloadavg()[0]
    proc = subprocess.run([sys.executable, str(HERE / "bench.py"), "--child", json.dumps(spec)],
                          capture_output=True, text=True, env=env, cwd="/", check=True)
    row = json.loads(proc.stdout.strip().splitlines()[-1])
    row["load"] = (load + os.getloadavg()[0]) / 2.0
    return row


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--old", help="source tree of the 'before' code")
    ap.add_argument("--new", default=None, help="source tree of the 'after' code (default: installed)")
    ap.add_argument("--threads-pair", action="store_true",
                    help="one thread against two threads, both on the working tree")
    ap.add_argument("--cases", default="point,point_half")
    ap.add_argument("--points", type=int, nargs="+", default=[513, 1025])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--threads", type=int, default=None)
    ap.add_argument("--label", default="paired")
    a = ap.parse_args()
    if not (a.old or a.threads_pair):
        ap.error("give --old TREE or --threads-pair")
    out = {"old": a.old, "new": a.new, "threads_pair": a.threads_pair, "threads": a.threads, "rounds": a.rounds, "rows": []}
    lines = ["| case | points | wall old | wall new | new/old | CPU old | CPU new | new/old | "
             "WU old/new | Hc old | Hc new | load |", "|" + "---|" * 12]
    for name in a.cases.split(","):
        for n in a.points:
            runs = {"old": [], "new": []}
            for _ in range(a.rounds):
                if a.threads_pair:
                    runs["old"].append(one(a.new, name, n, 1))
                    runs["new"].append(one(a.new, name, n, 2))
                else:
                    runs["old"].append(one(a.old, name, n, a.threads))
                    runs["new"].append(one(a.new, name, n, a.threads))
            med = {k: {q: statistics.median(r[q] for r in v)
                       for q in ("wall_median_s", "cpu_median_s", "load")} for k, v in runs.items()}
            row = {"case": name, "points": n, "runs": runs, "median": med}
            out["rows"].append(row)
            o, w = med["old"], med["new"]
            ro, rn = runs["old"][-1], runs["new"][-1]
            lines.append(
                f"| {name} | {n} | {o['wall_median_s']:.3f} | {w['wall_median_s']:.3f} | "
                f"{w['wall_median_s'] / o['wall_median_s']:.2f} | {o['cpu_median_s']:.3f} | "
                f"{w['cpu_median_s']:.3f} | {w['cpu_median_s'] / o['cpu_median_s']:.2f} | "
                f"{ro['work_units']:.1f}/{rn['work_units']:.1f} | {ro['Hc']:.9f} | {rn['Hc']:.9f} | "
                f"{(o['load'] + w['load']) / 2:.1f} |")
            print(lines[-1], flush=True)
            (OUT / f"{a.label}.json").write_text(json.dumps(out, indent=1))
    (OUT / f"{a.label}.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
