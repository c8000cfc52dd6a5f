"""Speed benchmark of the multilevel point and line solvers (issue "Speed").

Cases (Roelands + Dowson-Higginson, plain solves at explicit grids, ``estimate=False``):

* ``point``      circular (M, L) = (20, 10), full domain (``half=False``), 129^2 .. 4097^2;
* ``point_half`` the same on the symmetric half domain (``half=True``, the solver's default);
* ``line``       (M, L) = (20, 10), 1025 .. 16385 points;
* ``line_1000``  (M, L) = (1000, 10), 1025 .. 16385 points;
* ``point_film``, ``point_film_fmg1``: ``point`` stopped when the films change by less than a
  quarter of the grid's discretisation error per cycle (the accuracy-driven stop), with two
  and with one cycle per FMG level (``--cases`` to select them); ``point_half_film`` the
  films' stop on the half domain; ``point_half_fmg1`` FMG with one cycle per level and no
  further cycles (textbook FMG: is Hc within its discretisation error?).

Each (case, grid) runs in a fresh subprocess: one warm-up solve of (20, 10) on a small grid
(numba cache load, imports), then ``--repeat`` timed solves (the median is the solver time
without start-up), with a garbage collection between them (the solver and its grid hierarchy
reference each other, so a previous solve's fields would otherwise still be alive). Recorded per run: wall times, work units, cycles, Hc, Hm, success, numba
threads, peak resident memory of the child (``ru_maxrss``; tracemalloc misses numpy's and
pocketfft's buffers) and its baseline after the warm-up, the number of deformation
evaluations (total and in finest-grid units) and the load average before and after. Hc
errors are taken against the Richardson extrapolation of the three finest grids of the case
(observed order, 2 when the observed one is not in (0.5, 4)). Start-up is measured
separately: ``ehl solve --help`` and the import of the solvers, each in a fresh process.

    python validation/bench/bench.py --quick --label before
    python validation/bench/bench.py --label after --max-point 2049

writes ``build/validation/bench/<label>.json``, ``<label>.md`` (table) and ``<label>.png``
(time against points, log-log, with the fitted cost exponent).
"""

from __future__ import annotations

import argparse
import gc
import json
import math
import os
import platform
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir, require  # noqa: E402

OUT = out_dir("bench")

CASES = {
    "point": {"contact": "point", "M": 20.0, "L": 10.0, "kw": {"half": False}},
    "point_half": {"contact": "point", "M": 20.0, "L": 10.0, "kw": {"half": True}},
    "line": {"contact": "line", "M": 20.0, "L": 10.0, "kw": {}},
    "line_1000": {"contact": "line", "M": 1000.0, "L": 10.0, "kw": {}},
    # stopped by the films instead of the residual: the films' change per cycle below a quarter
    # of the grid's discretisation error (Hc error 1.9e-3 at 257^2, second order: 125/(n-1)^2;
    # the table's Hc error column checks that the stop did not cut the accuracy)
    "point_film": {"contact": "point", "M": 20.0, "L": 10.0, "kw": {"half": False}, "film_tol_c": 31.0},
    # the same with one W cycle per FMG level instead of two (textbook FMG)
    "point_film_fmg1": {"contact": "point", "M": 20.0, "L": 10.0, "kw": {"cycles": 1, "half": False},
                        "film_tol_c": 31.0},
    # the half domain (what accuracy-driven solves use) with the films' stop
    "point_half_film": {"contact": "point", "M": 20.0, "L": 10.0, "kw": {"half": True}, "film_tol_c": 31.0},
    # textbook FMG: one cycle per FMG level and no further cycles (the Hc error column against
    # the grid's discretisation error says whether FMG alone reaches it)
    "point_half_fmg1": {"contact": "point", "M": 20.0, "L": 10.0,
                        "kw": {"half": True, "cycles": 1, "max_cycles": 0, "adapt": False},
                        "ref": "point_half"},
}


# -- child: one case on one grid ---------------------------------------------------------------
def _count_deformations(contact: str, counter: dict) -> None:
    """Wrap the solver's deformation factory so every evaluation is counted (total and in
    finest-grid units, filled in by the caller)."""
    if contact == "point":
        from ehl_multigrid.point import fas

        make = fas.make_deformation

        def counted(kind, nx, ny, *a, **k):
            op = make(kind, nx, ny, *a, **k)
            npts = nx * ny

            class Counted:
                def __getattr__(self, name):
                    return getattr(op, name)

                def __call__(self, P, **k):
                    counter[npts] = counter.get(npts, 0) + 1
                    return op(P, **k)

            return Counted()

        fas.make_deformation = counted
    else:
        from ehl_multigrid.line import level

        make = level.make_deformation

        def counted_line(n, *a, **k):
            op = make(n, *a, **k)

            class Counted:
                def __getattr__(self, name):
                    return getattr(op, name)

                def apply(self, P):
                    counter[n] = counter.get(n, 0) + 1
                    return op.apply(P)

            return Counted()

        level.make_deformation = counted_line


def child(spec: dict) -> dict:
    """Run one case in this (fresh) process and return its record."""
    t0 = time.perf_counter()
    import numba

    if spec["contact"] == "point":
        from ehl_multigrid.point import solve_point as solve
        warm_points = 65
    else:
        from ehl_multigrid.line import solve_line as solve
        warm_points = 257
    t_import = time.perf_counter() - t0
    kw = dict(spec["kw"])
    if spec.get("threads") is not None:
        kw["threads"] = spec["threads"]
    film_kw = {"film_tol": spec["film_tol_c"] / (spec["points"] - 1) ** 2} if "film_tol_c" in spec else {}
    counter: dict[int, int] = {}
    _count_deformations(spec["contact"], counter)
    t0 = time.perf_counter()
    # the same kernels on a small grid ((20, 10): high M does not solve on a coarse grid)
    solve(20.0, 10.0, points=warm_points, estimate=False, **kw)
    t_warm = time.perf_counter() - t0
    rss_base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    runs = []
    for _ in range(spec["repeat"]):
        counter.clear()
        c0 = _cpu()
        t0 = time.perf_counter()
        res = solve(spec["M"], spec["L"], points=spec["points"], estimate=False, **kw, **film_kw)
        wall = time.perf_counter() - t0
        cpu = _cpu() - c0
        fine = max(counter) if counter else 1
        runs.append({
            "wall_s": wall, "cpu_s": cpu, "work_units": float(res.work_units), "cycles": int(res.cycles),
            "Hc": float(res.Hc), "Hm": float(res.Hm), "success": bool(res.success),
            "deformations": int(sum(counter.values())),
            "deformation_wu": float(sum(c * n / fine for n, c in counter.items())),
            "deformations_by_size": {str(n): c for n, c in sorted(counter.items())},
        })
        # the solver and its grid hierarchy reference each other: without a collection the
        # previous solve's fields stay alive during the next one and double the peak
        del res
        gc.collect()
    walls = [r["wall_s"] for r in runs]
    last = runs[-1]
    return {
        **{k: last[k] for k in ("work_units", "cycles", "Hc", "Hm", "success", "deformations",
                                "deformation_wu", "deformations_by_size")},
        "wall_median_s": statistics.median(walls), "wall_all_s": walls,
        "cpu_median_s": statistics.median(r["cpu_s"] for r in runs),
        # the solve restores numba's thread count afterwards: record the one it ran with
        "threads": spec.get("threads") or numba.get_num_threads(), "threading_layer": _layer(),
        "import_s": t_import, "warmup_s": t_warm,
        "rss_baseline_mb": rss_base,
        "rss_peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0,
        "Hc_runs_equal": len({r["Hc"] for r in runs}) == 1,
    }


def _cpu() -> float:
    """User + system CPU seconds of this process (all threads): on a shared machine a
    better measure of work than wall time, though it counts spin-waiting threads too."""
    ru = resource.getrusage(resource.RUSAGE_SELF)
    return ru.ru_utime + ru.ru_stime


def _layer() -> str:
    import numba

    try:
        return str(numba.threading_layer())
    except ValueError:  # no parallel kernel has run yet
        return str(numba.config.THREADING_LAYER)


# -- parent ------------------------------------------------------------------------------------
def startup(repeat: int = 3) -> dict:
    """Wall time of fresh processes: ``ehl solve --help`` and importing both solvers."""
    out = {}
    cmds = {
        "ehl_solve_help_s": ["ehl", "solve", "--help"],
        "import_solvers_s": [sys.executable, "-c",
                             "import ehl_multigrid.point, ehl_multigrid.line"],
    }
    for key, cmd in cmds.items():
        times = []
        for _ in range(repeat):
            t0 = time.perf_counter()
            subprocess.run(cmd, check=True, capture_output=True)
            times.append(time.perf_counter() - t0)
        out[key] = statistics.median(times)
        out[key[:-2] + "_all_s"] = times
    return out


def run_case(name: str, points: int, repeat: int, threads: int | None, timeout: float) -> dict:
    spec = {**CASES[name], "points": points, "repeat": repeat, "threads": threads}
    row = {"case": name, "points": points, "repeat": repeat, "load_before": os.getloadavg()}
    t0 = time.perf_counter()
    try:
        proc = subprocess.run([sys.executable, __file__, "--child", json.dumps(spec)],
                              capture_output=True, text=True, timeout=timeout)
        if proc.returncode == 0:
            row.update(json.loads(proc.stdout.strip().splitlines()[-1]))
            row["status"] = "ok"
        else:
            row.update(status="error", error=proc.stderr[-2000:])
    except subprocess.TimeoutExpired:
        row.update(status="timeout", error=f"more than {timeout:g} s")
    row["process_s"] = time.perf_counter() - t0
    row["load_after"] = os.getloadavg()
    return row


def grid_points(row: dict) -> int:
    """Unknowns of the finest grid (the point grid's Y points from its y ratio)."""
    n = row["points"]
    if CASES[row["case"]]["contact"] == "line":
        return n
    half = CASES[row["case"]]["kw"].get("half", False)
    # (M, L) = (20, 10) runs with square cells on a square box: (n-1) intervals along Y
    return n * (n // 2 + 1 if half else n)


def richardson(hs: list[float]) -> tuple[float, float]:
    """Extrapolated value and observed order from three grids (each twice as fine)."""
    h1, h2, h3 = hs[-3:]
    d1, d2 = h2 - h1, h3 - h2
    p = math.log2(d1 / d2) if d1 * d2 > 0 and d2 != 0 else float("nan")
    if not (0.5 < p < 4.0):
        p = 2.0
    return h3 + (h3 - h2) / (2.0**p - 1.0), p


def analyse(rows: list[dict]) -> dict:
    """Per case: extrapolated Hc, each grid's error, and the cost exponent of wall time in
    the number of unknowns (least squares in log-log)."""
    import numpy as np

    out = {}
    for name in dict.fromkeys(r["case"] for r in rows):
        ok = sorted((r for r in rows if r["case"] == name and r["status"] == "ok" and r["success"]),
                    key=lambda r: r["points"])
        info: dict = {}
        ref = out.get(CASES.get(name, {}).get("ref", ""), {})
        if "Hc_extrapolated" in ref:
            # stopped on purpose before the tolerances (FMG alone): errors against the
            # converged case's extrapolation
            for r in rows:
                if r["case"] == name and r["status"] == "ok":
                    r["Hc_error"] = r["Hc"] / ref["Hc_extrapolated"] - 1.0
            ok = sorted((r for r in rows if r["case"] == name and r["status"] == "ok"),
                        key=lambda r: r["points"])
        elif len(ok) >= 3:
            ext, p = richardson([r["Hc"] for r in ok])
            info.update(Hc_extrapolated=ext, order=p)
            for r in ok:
                r["Hc_error"] = r["Hc"] / ext - 1.0
        big = [r for r in ok if grid_points(r) >= (257**2 if "point" in name else 1025)]
        if len(big) >= 2:
            x = np.log([grid_points(r) for r in big])
            y = np.log([r["wall_median_s"] for r in big])
            info["cost_exponent"] = float(np.polyfit(x, y, 1)[0])
            info["cost_exponent_from"] = big[0]["points"]
            y = np.log([r["work_units"] for r in big])
            info["wu_exponent"] = float(np.polyfit(x, y, 1)[0])
        out[name] = info
    return out


def table(data: dict) -> str:
    head = ("| case | points | wall s (median) | CPU s | WU | cycles | defo evals (fine units) | Hc | "
            "Hc err | threads | peak MB (base) | load before/after |")
    lines = [head, "|" + "---|" * 12]
    for r in data["rows"]:
        if r["status"] != "ok":
            lines.append(f"| {r['case']} | {r['points']} | {r['status']} | | | | | | | | | "
                         f"{r['load_before'][0]:.2f}/{r['load_after'][0]:.2f} |")
            continue
        err = f"{r['Hc_error']:+.2e}" if "Hc_error" in r else ""
        lines.append(
            f"| {r['case']} | {r['points']} | {r['wall_median_s']:.3f} ({r['repeat']}) | "
            f"{r['cpu_median_s']:.3f} | {r['work_units']:.1f} | "
            f"{r['cycles']} | {r['deformations']} ({r['deformation_wu']:.1f}) | {r['Hc']:.6f} | "
            f"{err} | {r['threads']} | {r['rss_peak_mb']:.0f} ({r['rss_baseline_mb']:.0f}) | "
            f"{r['load_before'][0]:.2f}/{r['load_after'][0]:.2f} |")
    lines.append("")
    for name, info in data["analysis"].items():
        if "cost_exponent" in info:
            lines.append(f"- {name}: wall-time exponent in unknowns {info['cost_exponent']:.2f} "
                         f"(WU exponent {info['wu_exponent']:.2f}) from {info['cost_exponent_from']} "
                         f"points; Hc extrapolated {info.get('Hc_extrapolated', float('nan')):.6f} "
                         f"(order {info.get('order', float('nan')):.2f})")
    s = data["startup"]
    lines.append(f"- start-up: `ehl solve --help` {s['ehl_solve_help_s']:.2f} s, import of both "
                 f"solvers {s['import_solvers_s']:.2f} s (fresh processes, median of 3)")
    return "\n".join(lines) + "\n"


def plot(data: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    for name, info in data["analysis"].items():
        ok = sorted((r for r in data["rows"] if r["case"] == name and r["status"] == "ok"),
                    key=lambda r: r["points"])
        if not ok:
            continue
        lab = name + (f" (exponent {info['cost_exponent']:.2f})" if "cost_exponent" in info else "")
        ax.loglog([grid_points(r) for r in ok], [r["wall_median_s"] for r in ok], "o-", label=lab)
    ax.set_xlabel("unknowns of the finest grid")
    ax.set_ylabel("solver wall time [s] (median, without start-up)")
    ax.set_title(f"{data['label']}: {data['host']['cpus']} CPUs, threads {data['threads'] or 'default'}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def compare(labels: list[str]) -> str:
    """Markdown table of the runs ``labels`` side by side (wall, CPU, WU, cycles, peak MB)."""
    runs = [json.loads(require(OUT / f"{lab}.json", f"python validation/bench/bench.py --label {lab}").read_text())
            for lab in labels]
    keys = list(dict.fromkeys((r["case"], r["points"]) for d in runs for r in d["rows"]))
    cols = ["wall s", "CPU s", "WU", "cycles", "defo evals", "peak MB", "load"]
    head = "| case | points | " + " | ".join(f"{c} {lab}" for c in cols for lab in labels) + " |"
    lines = [head, "|" + "---|" * (2 + len(cols) * len(labels))]
    for case, n in keys:
        rows = [next((r for r in d["rows"] if (r["case"], r["points"]) == (case, n)), None)
                for d in runs]

        def cell(r, key, fmt):
            if r is None:
                return "-"
            if r["status"] != "ok":
                return r["status"]
            v = r[key]
            return fmt.format(v[0] if isinstance(v, list) else v)

        cells = []
        for key, fmt in (("wall_median_s", "{:.3f}"), ("cpu_median_s", "{:.3f}"),
                         ("work_units", "{:.1f}"), ("cycles", "{:d}"), ("deformations", "{:d}"),
                         ("rss_peak_mb", "{:.0f}"), ("load_before", "{:.1f}")):
            cells += [cell(r, key, fmt) for r in rows]
        lines.append(f"| {case} | {n} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--child", help=argparse.SUPPRESS)
    ap.add_argument("--quick", action="store_true", help="point up to 1025^2 (default 2049^2)")
    ap.add_argument("--label", default="bench")
    ap.add_argument("--cases", default="point,point_half,line,line_1000")
    ap.add_argument("--max-point", type=int, default=None, help="largest point grid (<= 4097)")
    ap.add_argument("--max-line", type=int, default=16385)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--repeat-big", type=int, default=None,
                    help="timed solves on point grids of 2049^2 and more (default --repeat)")
    ap.add_argument("--threads", type=int, default=None)
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds per (case, grid)")
    ap.add_argument("--append", action="store_true",
                    help="keep the other cases' rows of an existing <label>.json")
    ap.add_argument("--compare", nargs="+", metavar="LABEL",
                    help="only write build/validation/bench/compare.md from earlier runs")
    a = ap.parse_args()
    if a.compare:
        text = compare(a.compare)
        (OUT / "compare.md").write_text(text)
        print(text)
        return
    if a.child:
        print(json.dumps(child(json.loads(a.child))))
        return
    max_point = a.max_point or (1025 if a.quick else 2049)
    grids = {"point": [n for n in (129, 257, 513, 1025, 2049, 4097) if n <= max_point],
             "line": [n for n in (1025, 2049, 4097, 8193, 16385) if n <= a.max_line]}
    OUT.mkdir(parents=True, exist_ok=True)
    data = {"label": a.label, "threads": a.threads, "repeat": a.repeat,
            "host": {"cpus": os.cpu_count(), "python": platform.python_version(),
                     "machine": platform.machine()},
            "started": time.strftime("%Y-%m-%d %H:%M:%S"), "startup": startup(), "rows": []}
    old = OUT / f"{a.label}.json"
    if a.append and old.exists():
        prev = json.loads(old.read_text())
        data["rows"] = [r for r in prev["rows"] if r["case"] not in a.cases.split(",")]
        data["startup"] = prev["startup"]
    for name in a.cases.split(","):
        for n in grids[CASES[name]["contact"]]:
            big = CASES[name]["contact"] == "point" and n >= 2049 and a.repeat_big is not None
            row = run_case(name, n, a.repeat_big if big else a.repeat, a.threads, a.timeout)
            data["rows"].append(row)
            msg = (f"{row['wall_median_s']:.3f} s, WU {row['work_units']:.1f}, "
                   f"{row['cycles']} cycles, Hc {row['Hc']:.6f}, {row['rss_peak_mb']:.0f} MB"
                   if row["status"] == "ok" else row["status"] + " " + row.get("error", "")[-300:])
            print(f"{name} {n}: {msg} (load {row['load_before'][0]:.2f} -> {row['load_after'][0]:.2f})",
                  flush=True)
            data["analysis"] = analyse(data["rows"])
            (OUT / f"{a.label}.json").write_text(json.dumps(data, indent=1))
    data["finished"] = time.strftime("%Y-%m-%d %H:%M:%S")
    data["analysis"] = analyse(data["rows"])
    (OUT / f"{a.label}.json").write_text(json.dumps(data, indent=1))
    (OUT / f"{a.label}.md").write_text(table(data))
    plot(data, OUT / f"{a.label}.png")
    print(table(data))


if __name__ == "__main__":
    main()
