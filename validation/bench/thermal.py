"""Speed benchmark of the thermal traction curves and the Stribeck curves (issue "Speed").

Cases (thermal Roelands-Eyring model, thesis ch. 3; Stribeck curves, thesis ch. 4-5):

* ``traction``: 21 slips over [0, 1] from Hertz input and from an EHL solution, thermal, the
  scene's thermal options (default nx = 80, nz = 20, 10 slices): the thesis's appendix C line
  (Fig. 3.8) and appendix D point (Fig. 3.27) contacts, the built-in roller bearing (line),
  6205 ball bearing (elliptic) and ball-on-disc (point) scenes. The EHL solutions (line
  solver on X in [-2.5, 1.5]; point solver 257^2 on the half domain) are solved once and kept
  in a disk cache, so every run (and every version of the code) reads the same input; their
  hash is recorded.
* ``stribeck``: 60 log-spaced sum velocities over 1e-3..100 m/s, isothermal and thermal,
  default options (transition speeds included): page-63 line (2000 N) and series C point
  (1.93 GPa).

Every case runs ``--repeat`` times (median reported) after one warm-up of the compiled kernels;
the 1-minute load average is read before and after each case, and the process CPU time (all
threads) is recorded next to the wall time: on a loaded machine it shows the work done. The friction coefficients are
stored, and with ``--reference`` (default ``build/validation/bench/thermal_before.json`` when the label is not
``before``) each case's largest friction-coefficient difference against that run is
reported (absolute and relative to the largest |f| of the curve).

    python validation/bench/thermal.py --label before
    python validation/bench/thermal.py --label after
    python validation/bench/thermal.py --label after --grid-study
    python validation/bench/thermal.py --label ratio --only roller --repeat 31 --interleave

(``--interleave``: the cases round-robin, one run each per round, and the median of the
per-round EHL/Hertz-input ratios: a drift of the machine's speed falls on both inputs alike.)

writes ``build/validation/bench/thermal_<label>.json``, ``thermal_<label>.md`` (table) and
``thermal_<label>.png`` (median wall time per case, with the reference's when given).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import os
import platform
import statistics
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
# this file is called thermal.py: keep its folder off the path so ``import thermal`` finds the
# package of the checkout it belongs to
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != HERE]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

sys.path.append(str(HERE.parent))
from _paths import out_dir  # noqa: E402

OUT = out_dir("bench")
CACHE = Path(os.environ.get("EHL_BENCH_CACHE", "/tmp/ehl_bench_thermal_cache"))

TRACTION_SCENES = [
    # (scene, EHL solve)
    ("appendix_c_line_42400N", "line"),
    ("roller_bearing_inner_race", "line"),
    ("appendix_d_point", "point"),
    ("bearing_6205_inner_race", "point"),
    ("ball_on_disc_tribometer", "point"),
]
STRIBECK_SCENES = ["page63_line_2000N", "series_C_disc3_1.93GPa"]
SLIPS = np.linspace(0.0, 1.0, 21)
US = np.geomspace(1e-3, 100.0, 60)

#: targets of the issue (2-core machine, idle) [s]
TARGETS = {
    "stribeck thermal point": 5.0,
    "stribeck isothermal": 0.5,
}


def ehl_result(name: str):
    """The EHL solution of scene ``name`` (solved once, then read from the disk cache)."""
    from ehl_multigrid.model.results import Result
    from ehl_multigrid.model.scene import load_scene

    CACHE.mkdir(parents=True, exist_ok=True)
    path = CACHE / f"{name}.h5"
    if path.exists():
        return Result.load(path)
    sc = load_scene(name)
    if sc.kind == "line":
        from ehl_multigrid.line.solver import solve_line

        sol = solve_line(scene=sc, xmin=-2.5, xmax=1.5)
    else:
        from ehl_multigrid.point import solve_point

        sol = solve_point(scene=sc, points=257, half=True)
    res = sol.to_result(sc)
    if not res.scalars.get("converged"):
        raise RuntimeError(f"EHL solve of {name} did not converge")
    res.save(path)
    return Result.load(path)


def field_hash(res) -> str:
    h = hashlib.sha256()
    for k in ("x", "y"):
        if k in res.coords:
            h.update(np.ascontiguousarray(res[k], dtype=float).tobytes())
    for k in ("p", "h"):
        h.update(np.ascontiguousarray(res[k], dtype=float).tobytes())
    return h.hexdigest()[:16]


def selected(name: str, only: str | None) -> bool:
    """Whether case ``name`` is run under ``--only`` (comma-separated parts, any of them)."""
    return only is None or any(part in name for part in only.split(","))


def cases(quick: bool, only: str | None = None) -> list[dict]:
    """The case list: name, group, a callable returning (coefficients, converged, extra); with
    ``only``, the selected cases (an EHL input is read or solved only for those)."""
    from ehl_multigrid.model.scene import load_scene
    from mixed.stribeck import stribeck_curve
    from thermal import traction_curve

    out = []
    scenes = TRACTION_SCENES[:1] + TRACTION_SCENES[2:3] if quick else TRACTION_SCENES
    for name, _ in scenes:
        sc = load_scene(name)
        for inp in ("hertz", "ehl"):
            if not selected(f"traction {inp} {name}", only):
                continue
            ehl = ehl_result(name) if inp == "ehl" else None

            def run(sc=sc, inp=inp, ehl=ehl):
                pts = traction_curve(sc, SLIPS, input=inp, ehl=ehl)
                return [p.coefficient for p in pts], all(p.converged for p in pts), {
                    "sweeps": [int(p.report.iterations) for p in pts],
                    "max_temperature_rise": [p.max_temperature_rise for p in pts]}

            extra = {"ehl_hash": field_hash(ehl)} if ehl is not None else {}
            out.append({"name": f"traction {inp} {name}", "group": f"traction {inp} {sc.kind}",
                        "scene": name, "kind": sc.kind, "points": int(SLIPS.size), "run": run, **extra})
    for name in STRIBECK_SCENES[:1] if quick else STRIBECK_SCENES:
        sc = load_scene(name)
        contact = "line" if sc.kind == "line" else "point"
        for thermal in (False, True):
            if not selected(f"stribeck {'thermal' if thermal else 'isothermal'} {name}", only):
                continue

            def run(sc=sc, thermal=thermal):
                c = stribeck_curve(sc, US, thermal=thermal)
                extra = {"transitions": c.transitions}
                if thermal:
                    extra["max_temperature_rise"] = c.friction.max_temperature_rise.tolist()
                return c.friction.coefficient.tolist(), c.converged, extra

            label = "thermal" if thermal else "isothermal"
            out.append({"name": f"stribeck {label} {name}", "group": f"stribeck {label} {contact}",
                        "scene": name, "kind": sc.kind, "points": int(US.size), "run": run})
    return out


def warm_up() -> None:
    """Load the compiled kernels (numba cache) before any timing."""
    from ehl_multigrid.model.scene import load_scene
    from mixed.stribeck import stribeck_curve
    from thermal import solve_traction

    solve_traction(load_scene("appendix_c_line_42400N"), 0.3)
    solve_traction(load_scene("appendix_d_point"), 0.3, slices=2)
    stribeck_curve(load_scene("series_C_disc3_1.93GPa"), US[::30], thermal=True)


def run_once(case: dict) -> tuple[float, float, list[float], tuple]:
    """One run of ``case``: wall and CPU time, the load average before and after, its output."""
    la0 = os.getloadavg()[0]
    c = time.process_time()
    t = time.perf_counter()
    result = case["run"]()
    return time.perf_counter() - t, time.process_time() - c, [la0, os.getloadavg()[0]], result


def record(case: dict, runs: list[tuple]) -> dict:
    """The case's record from its runs (:func:`run_once`), the output of the last one."""
    times, cpus, loads = [r[0] for r in runs], [r[1] for r in runs], [r[2] for r in runs]
    coeff, conv, extra = runs[-1][3]
    rec = {k: v for k, v in case.items() if k != "run"}
    rec.update(wall_s=times, median_s=statistics.median(times), cpu_s=cpus, median_cpu_s=statistics.median(cpus),
               loadavg=loads,
               coefficient=[float(c) for c in coeff], converged=bool(conv), extra=extra)
    return rec


def measure(case: dict, repeat: int) -> dict:
    return record(case, [run_once(case) for _ in range(repeat)])


def measure_interleaved(cases: list[dict], repeat: int) -> list[dict]:
    """Every case once per round, ``repeat`` rounds: a drift of the machine's speed falls on
    all cases alike, so per-round ratios (EHL against Hertz input) compare like with like."""
    runs: list[list[tuple]] = [[] for _ in cases]
    for _ in range(repeat):
        for k, case in enumerate(cases):
            runs[k].append(run_once(case))
    return [record(case, r) for case, r in zip(cases, runs, strict=True)]


def paired_ratios(data: dict) -> dict:
    """Median over rounds of the EHL-input curve's time over the Hertz-input curve's, wall and
    CPU, per traction scene (meaningful for interleaved runs: the same round, the same load)."""
    out = {}
    for name, rec in data["cases"].items():
        if name.startswith("traction ehl"):
            hz = data["cases"].get(name.replace("traction ehl", "traction hertz"))
            if hz is not None and len(hz["wall_s"]) == len(rec["wall_s"]):
                out[rec["scene"]] = {
                    q: statistics.median(e / h for e, h in zip(rec[f"{q}_s"], hz[f"{q}_s"], strict=True))
                    for q in ("wall", "cpu")}
    return out


def compare(rec: dict, ref: dict | None) -> None:
    """Largest friction-coefficient difference against the reference run of the same case."""
    if ref is None:
        return
    r = ref.get("cases", {}).get(rec["name"])
    if r is None:
        return
    a, b = np.array(rec["coefficient"], dtype=float), np.array(r["coefficient"], dtype=float)
    if a.shape != b.shape:
        return
    if rec.get("ehl_hash") != r.get("ehl_hash"):
        rec["reference_warning"] = "EHL input differs from the reference run's"
    d = np.abs(a - b)
    rec["reference_median_s"] = r["median_s"]
    rec["reference_median_cpu_s"] = r.get("median_cpu_s")
    rec["speedup"] = r["median_s"] / rec["median_s"]
    rec["max_abs_df"] = float(np.nanmax(d))
    rec["max_rel_df"] = float(np.nanmax(d) / np.nanmax(np.abs(b)))


def table(data: dict) -> str:
    ref = data.get("reference_label")
    head = ["case", "points", f"{data['label']} median [s]", "runs [s]", "CPU [s]", "load before/after"]
    if ref:
        head += [f"{ref} median [s]", f"{ref} CPU [s]", "speed-up", "max |df|", "max |df| / max |f|"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for rec in data["cases"].values():
        runs = ", ".join(f"{t:.3g}" for t in rec["wall_s"])
        la = "; ".join(f"{a:.2f}/{b:.2f}" for a, b in rec["loadavg"])
        row = [rec["name"], str(rec["points"]), f"{rec['median_s']:.3g}", runs, f"{rec['median_cpu_s']:.3g}", la]
        if ref:
            if "reference_median_s" in rec:
                ref_cpu = rec.get("reference_median_cpu_s")
                row += [f"{rec['reference_median_s']:.3g}", "-" if ref_cpu is None else f"{ref_cpu:.3g}",
                        f"{rec['speedup']:.2f}", f"{rec['max_abs_df']:.2e}", f"{rec['max_rel_df']:.2e}"]
            else:
                row += ["-"] * 5
        if not rec["converged"]:
            row[0] += " (not all converged)"
        lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines) + "\n"


def targets(data: dict) -> dict:
    """The issue's targets against this run's medians."""
    c = data["cases"]
    out = {}
    for name, rec in c.items():
        if rec["group"] == "stribeck thermal point":
            out[f"{name} < {TARGETS['stribeck thermal point']} s"] = rec["median_s"] < TARGETS["stribeck thermal point"]
        if rec["group"].startswith("stribeck isothermal"):
            out[f"{name} < {TARGETS['stribeck isothermal']} s"] = rec["median_s"] < TARGETS["stribeck isothermal"]
    for name, rec in c.items():
        if rec["name"].startswith("traction ehl"):
            hz = c.get(rec["name"].replace("traction ehl", "traction hertz"))
            if hz is not None:
                # "as fast as": within the run-to-run spread of this machine (10 %)
                out[f"{name} <= 1.1 x Hertz input ({hz['median_s']:.3g} s)"] = rec["median_s"] <= 1.1 * hz["median_s"]
    return out


def plot(data: dict, ref: dict | None, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    names = list(data["cases"])
    y = np.arange(len(names))
    fig, ax = plt.subplots(figsize=(8.5, 0.32 * len(names) + 1.4))
    now = [data["cases"][n]["median_s"] for n in names]
    if ref is not None:
        old = [ref["cases"].get(n, {}).get("median_s", math.nan) for n in names]
        ax.barh(y + 0.2, old, height=0.4, color="0.7", label=data["reference_label"])
        ax.barh(y - 0.2, now, height=0.4, color="C0", label=data["label"])
    else:
        ax.barh(y, now, height=0.6, color="C0", label=data["label"])
    ax.axvline(TARGETS["stribeck thermal point"], color="C3", lw=0.8, ls="--", label="5 s (thermal Stribeck, point)")
    ax.axvline(TARGETS["stribeck isothermal"], color="C2", lw=0.8, ls=":", label="0.5 s (isothermal Stribeck)")
    ax.set_yticks(y, names, fontsize=7)
    ax.invert_yaxis()
    ax.set_xscale("log")
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlabel("median wall time [s]")
    ax.set_title(f"thermal traction (21 slips) and Stribeck curves (60 speeds); {data['machine']['cpus']} cpus", fontsize=9)
    ax.legend(fontsize=7, loc="lower right")
    ax.grid(alpha=0.3, axis="x", which="both")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


#: grids of the Stribeck grid study: the library default (appendix C/D grid), the Stribeck
#: stage's (ehl_multigrid.model.fidelity.FIDELITIES), the point "standard" fidelity and a finer reference
GRID_STUDY = {
    "reference 160x40, 20 slices": {"nx": 160, "nz": 40, "slices": 20},
    "default 80x20, 10 slices": {},
    "40x10, 5 slices": {"nx": 40, "nz": 10, "slices": 5},
    "20x5, 5 slices": {"nx": 20, "nz": 5, "slices": 5},
}


def grid_study(label: str) -> None:
    """Thermal 60-point Stribeck curve of the series C point contact on each grid of
    :data:`GRID_STUDY`: wall/CPU time (one run) and the friction change against the finest."""
    from ehl_multigrid.model.scene import load_scene
    from mixed.stribeck import stribeck_curve

    warm_up()
    sc = load_scene(STRIBECK_SCENES[1])
    out: dict = {"scene": sc.name, "us": US.tolist(), "grids": {}}
    ref = None
    for name, opts in GRID_STUDY.items():
        la0 = os.getloadavg()[0]
        c0, t0 = time.process_time(), time.perf_counter()
        c = stribeck_curve(sc, US, thermal=True, thermal_options=opts or None)
        rec = {"options": opts, "wall_s": time.perf_counter() - t0, "cpu_s": time.process_time() - c0,
               "loadavg": [la0, os.getloadavg()[0]], "coefficient": c.friction.coefficient.tolist(),
               "film": c.friction.film.tolist(), "converged": c.converged}
        if ref is None:
            ref = c.friction
        else:
            rec["max_abs_df"] = float(np.nanmax(np.abs(c.friction.coefficient - ref.coefficient)))
            rec["max_rel_df"] = float(np.nanmax(np.abs(c.friction.coefficient - ref.coefficient) / ref.coefficient))
            rec["max_rel_dfilm"] = float(np.nanmax(np.abs(c.friction.film - ref.film) / ref.coefficient))
        out["grids"][name] = rec
        print(f"{name:28s} wall {rec['wall_s']:7.2f} s  cpu {rec['cpu_s']:7.2f} s  "
              f"max |df|/f {rec.get('max_rel_df', 0.0):.2e}", flush=True)
    (OUT / f"thermal_grid_{label}.json").write_text(json.dumps(out, indent=1))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--label", required=True, help="run label: build/validation/bench/thermal_<label>.json")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="two traction scenes, the line Stribeck curves only")
    ap.add_argument("--reference", default=None, help="JSON of an earlier run (default build/validation/bench/thermal_before.json)")
    ap.add_argument("--only", default=None,
                    help="run only the cases whose name contains this text (several: comma-separated, any of them)")
    ap.add_argument("--interleave", action="store_true",
                    help="run the cases round-robin, one run each per round (--repeat rounds), and "
                         "report per-round EHL/Hertz ratios")
    ap.add_argument("--grid-study", action="store_true",
                    help="instead: the thermal Stribeck curve (series C) on four grids, build/validation/bench/thermal_grid_<label>.json")
    args = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    if args.grid_study:
        grid_study(args.label)
        return
    ref_path = Path(args.reference) if args.reference else OUT / "thermal_before.json"
    ref = json.loads(ref_path.read_text()) if ref_path.exists() and (args.reference or args.label != "before") else None
    import numba

    t_start = time.perf_counter()
    la_start = os.getloadavg()
    warm_up()
    data = {
        "label": args.label,
        "source": str(ROOT),
        "reference_label": ref["label"] if ref else None,
        "machine": {"cpus": os.cpu_count(), "platform": platform.platform(), "python": platform.python_version(),
                    "numba_threads": numba.get_num_threads(), "numba": numba.__version__,
                    "loadavg_start": la_start},
        "repeat": args.repeat,
        "cases": {},
    }
    selected_cases = cases(args.quick, args.only)
    if args.interleave:
        recs = measure_interleaved(selected_cases, args.repeat)
    else:
        recs = (measure(case, args.repeat) for case in selected_cases)
    for rec in recs:
        compare(rec, ref)
        data["cases"][rec["name"]] = rec
        extra = f"  x{rec['speedup']:.2f}, max|df| {rec['max_abs_df']:.2e}" if "speedup" in rec else ""
        print(f"{rec['name']:55s} {rec['median_s']:8.3f} s  load {rec['loadavg'][0][0]:.2f}->{rec['loadavg'][-1][1]:.2f}"
              f"{'' if rec['converged'] else '  NOT CONVERGED'}{extra}", flush=True)
    data["interleaved"] = bool(args.interleave)
    if args.interleave:
        data["ehl_over_hertz"] = paired_ratios(data)
    data["targets"] = targets(data)
    data["machine"]["loadavg_end"] = os.getloadavg()
    data["total_s"] = time.perf_counter() - t_start
    stem = OUT / f"thermal_{args.label}"
    stem.with_suffix(".json").write_text(json.dumps(data, indent=1))
    md = table(data) + "\nTargets:\n\n" + "".join(f"- {k}: {'met' if v else 'not met'}\n" for k, v in data["targets"].items())
    for scene, r in data.get("ehl_over_hertz", {}).items():
        md += f"- {scene}: EHL / Hertz input, median of per-round ratios: wall {r['wall']:.3f}, CPU {r['cpu']:.3f}\n"
    stem.with_suffix(".md").write_text(md)
    plot(data, ref, stem.with_suffix(".png"))
    print(md)
    print(f"wrote {stem}.json/.md/.png ({data['total_s']:.0f} s)")


if __name__ == "__main__":
    main()
