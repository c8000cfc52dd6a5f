"""Honesty of the TEHL error estimate (thermal.tehl.accuracy.estimate_error): on line and point
cases, the estimated error of a solve against its difference from a reference solve one level
finer along X and across the film on a box twice as wide; and the box part alone against a
TEHL solve on a wider box at the solve's own mesh.

Usage: ``python validation/tehl/honesty.py [CASE ...]`` (default: all cases, then ``summary``);
``orders`` re-runs the point grid sequences behind the point orders of the estimate,
``extrapolated`` checks the extrapolated films' grid part against the extrapolation one grid finer,
``chapter5`` estimates the chapter 5 point solve (series D, disc 3). Each case
adds its row to ``build/validation/tehl/honesty.json``; ``summary`` computes the coverage and writes
``build/validation/tehl/honesty_summary.json`` and ``build/validation/tehl/honesty.png``.
"""

from __future__ import annotations

import json
import math
import statistics
import sys
import time
from pathlib import Path

from ehl_multigrid.model.scene import load_scene
from thermal.tehl import TEHLOptions
from thermal.tehl.accuracy import QUANTITIES, SolveCache, estimate_error

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
from _paths import out_dir  # noqa: E402

OUT = out_dir("tehl")
ROWS = OUT / "honesty.json"

#: name -> (scene, load or None, slip, points, nz, box check: None, or the box factor of a
#: solve at the case's own mesh to compare the box part with[, box of the reference: 2 unless
#: given; 1 where a finer solve on the doubled box is too slow for this study])
CASES = {
    "line_42400N_S0.1": ("appendix_c_line_42400N", None, 0.1, 513, 20, 4.0),
    "line_42400N_S1": ("appendix_c_line_42400N", None, 1.0, 513, 20, 4.0),
    "line_4240N_S0.1": ("appendix_c_line_4240N", None, 0.1, 513, 20, 4.0),
    "line_4240N_S1": ("appendix_c_line_4240N", None, 1.0, 513, 20, 4.0),
    "point_5N_S0.25": ("appendix_d_point", 5.0, 0.25, 129, 10, 2.0),
    "point_5N_S1": ("appendix_d_point", 5.0, 1.0, 129, 10, None),
    "point_15N_S0.5": ("appendix_d_point", 15.0, 0.5, 129, 10, None),
    "point_42.8N_S0.5": ("appendix_d_point", None, 0.5, 257, 20, None, 1.0),
}


def _load_rows() -> dict:
    return json.loads(ROWS.read_text()) if ROWS.exists() else {}


def _clean(v: float) -> float | None:
    return float(v) if math.isfinite(v) else None


def _rel(key: str, q: float, ref: float) -> float:
    return abs(q - ref) if key == "T_max" else abs(q - ref) / abs(ref)


def run_case(name: str) -> dict:
    scene_name, load, slip, n, nz, box_check, *rest = CASES[name]
    ref_box = rest[0] if rest else 2.0
    sc = load_scene(scene_name)
    if load is not None:
        sc = sc.with_operating(load=load)
    point = sc.kind != "line"
    opts = TEHLOptions(points=n, nz=nz)
    cache = SolveCache(sc, slip, opts, point)
    t = time.perf_counter()
    r = cache(n, nz, 1.0)
    wall_solve = time.perf_counter() - t
    t = time.perf_counter()
    est = estimate_error(r, cache=cache)
    wall_est = time.perf_counter() - t
    # reference: one level finer along X and across the film, on a box twice as wide
    # (the finer mesh on the doubled box: four times the intervals)
    n_ref = int(2 * ref_box * (n - 1)) + 1
    t = time.perf_counter()
    ref = cache(n_ref, 2 * nz, ref_box)
    wall_ref = time.perf_counter() - t
    row = {"scene": scene_name, "load": sc.load, "slip": slip, "points": n, "nz": nz,
           "reference": {"points": n_ref, "nz": 2 * nz, "box": ref_box},
           "wall_s": {"solve": wall_solve, "estimate": wall_est, "reference": wall_ref},
           "values": {k: float(getattr(r, k)) for k in QUANTITIES},
           "reference_values": {k: float(getattr(ref, k)) for k in QUANTITIES} if ref is not None else None,
           "budget": {k: {p: _clean(v) for p, v in est.budget[k].items()} for k in QUANTITIES},
           "domain_probe_points": est.domain["points"] if est.domain else None, "notes": est.notes}
    if ref is not None:
        row["true"] = {k: _rel(k, float(getattr(r, k)), float(getattr(ref, k))) for k in QUANTITIES}
    if box_check is not None:
        # the box part alone: a TEHL solve at the case's mesh on a box box_check times as wide
        nb = int(box_check * (n - 1)) + 1
        t = time.perf_counter()
        wide = cache(nb, nz, box_check)
        row["box_check"] = {"box": box_check, "points": nb, "wall_s": time.perf_counter() - t,
                            "true": {k: _rel(k, float(getattr(r, k)), float(getattr(wide, k))) for k in QUANTITIES}
                            if wide is not None else None,
                            "probe_change": {k: est.domain[k] for k in QUANTITIES} if est.domain else None,
                            "estimated": {k: _clean(est.budget[k]["domain"]) for k in QUANTITIES}}
    print(name, json.dumps({"true": row.get("true"), "est": {k: row["budget"][k]["total"] for k in QUANTITIES},
                            "box": row.get("box_check")}), flush=True)
    rows = _load_rows()
    rows[name] = row
    ROWS.write_text(json.dumps(rows, indent=1))
    return row


def summary() -> dict:
    rows = _load_rows()
    out: dict = {"cases": len(rows), "quantities": {}}
    for k in QUANTITIES:
        ratios, covered = [], 0
        for row in rows.values():
            e = row["budget"][k]["total"]
            tr = (row.get("true") or {}).get(k)
            if tr is None or e is None:
                continue
            ratios.append(tr / e if e > 0 else math.inf)
            covered += tr <= e
        out["quantities"][k] = {"covered": covered, "of": len(ratios),
                                "median_true_over_estimate": statistics.median(ratios) if ratios else None,
                                "max_true_over_estimate": max(ratios) if ratios else None}
    box = {}
    for name, row in rows.items():
        b = row.get("box_check")
        if b and b["true"] and b["estimated"]:
            box[name] = {k: {"true": b["true"][k], "estimated": b["estimated"][k],
                             "probe_change": (b["probe_change"] or {}).get(k)} for k in ("Hc", "Hm")}
    out["box_checks"] = box
    (OUT / "honesty_summary.json").write_text(json.dumps(out, indent=1))
    print(json.dumps(out, indent=1))
    _plot(rows)
    return out


def _plot(rows: dict) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.2, 5.2))
    marks = {"Hc": "o", "Hm": "s", "friction_coefficient": "^"}
    lo, hi = math.inf, 0.0
    for k, m in marks.items():
        xs, ys = [], []
        for row in rows.values():
            e, tr = row["budget"][k]["total"], (row.get("true") or {}).get(k)
            if e is not None and tr is not None and e > 0 and tr > 0:
                xs.append(e)
                ys.append(tr)
        ax.loglog(xs, ys, m, mfc="none", label=k)
        lo, hi = min([lo] + xs + ys), max([hi] + xs + ys)
    ax.plot([lo, hi], [lo, hi], "k-", lw=0.8, label="true = estimated")
    ax.set(xlabel="estimated relative error", ylabel="difference from the finer, wider solve",
           title="TEHL error estimate: line and point cases")
    ax.legend()
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(OUT / "honesty.png", dpi=120)
    plt.close(fig)
    print("wrote build/validation/tehl/honesty.png")


def _order(v: list[float]) -> float:
    """Observed order of three values on grids refined by 2."""
    return math.log2(abs((v[1] - v[0]) / (v[2] - v[1])))


def orders() -> None:
    """The point grid sequences behind the point orders of the estimate (appendix D, 1 GPa):
    along X at nz = 20 (S = 0.5 and 1), across the film at 257 points (S = 0.5)."""
    from thermal.tehl.point import solve_tehl_point

    sc = load_scene("appendix_d_point")
    rows = []
    for slip, runs in ((0.5, ((129, 20), (257, 20), (257, 10), (257, 5), (257, 40), (513, 20))),
                       (1.0, ((129, 20), (257, 20), (513, 20), (257, 10)))):
        for n, nz in runs:
            t = time.perf_counter()
            r = solve_tehl_point(sc, slip, points=n, nz=nz, threads=1)
            rows.append({"slip": slip, "points": n, "nz": nz, "Hc": r.Hc, "Hm": r.Hm,
                         "friction_coefficient": r.friction_coefficient, "T_max": r.T_max,
                         "outer": len(r.outer), "wall_s": time.perf_counter() - t})
            print(rows[-1], flush=True)
    out = {"scene": sc.name, "note": "solve_tehl_point(scene, slip, points=n, nz=nz, threads=1)", "rows": rows,
           "orders": {}}
    for slip in (0.5, 1.0):
        x = sorted((r for r in rows if r["slip"] == slip and r["nz"] == 20), key=lambda r: r["points"])
        out["orders"][f"X_S{slip}"] = {k: _order([r[k] for r in x]) for k in QUANTITIES}
    z = sorted((r for r in rows if r["slip"] == 0.5 and r["points"] == 257), key=lambda r: r["nz"])
    out["orders"]["Z_S0.5"] = {k: [_order([r[k] for r in z[i:i + 3]]) for i in range(len(z) - 2)]
                               for k in QUANTITIES}
    (OUT / "point_orders.json").write_text(json.dumps(out, indent=1))


def chapter5(default_tol: bool = False) -> None:
    """The estimate on the chapter 5 point condition (series D, disc 3, M = 1595) at 513 points
    with the loosened outer tolerances that converge there (study.py part chapter5): what it
    can say about the accuracy of that answer. ``default_tol``: the default outer tolerances
    instead (they converge with the point core's fine-grid alternation), at
    S = 0.05 and 0.5, written to ``honesty_chapter5_default.json``."""
    sc = load_scene("series_D_disc3_1.93GPa")
    tol = {} if default_tol else {"tol_H": 5e-3, "tol_P": 5e-4, "tol_T": 0.1}
    rows = {}
    for slip in ((0.05, 0.5) if default_tol else (0.05,)):
        cache = SolveCache(sc, slip, TEHLOptions(points=513, nz=20, **tol), True)
        t = time.perf_counter()
        r = cache(513, 20, 1.0)
        wall = time.perf_counter() - t
        if r is None:
            rows[str(slip)] = {"error": cache.errors[(513, 20, 1.0)], "wall_s": wall}
            continue
        t = time.perf_counter()
        est = estimate_error(r, cache=cache)
        rows[str(slip)] = {"values": {k: float(getattr(r, k)) for k in QUANTITIES}, "wall_s": wall,
                           "estimate_wall_s": time.perf_counter() - t,
                           "budget": {k: {p: _clean(v) for p, v in est.budget[k].items()} for k in QUANTITIES},
                           "film_noise": est.film_noise, "notes": est.notes, "failed_solves": {
                               f"{k[0]} points, nz {k[1]}, box {k[2]:g}": v for k, v in cache.errors.items()}}
        print(json.dumps(rows[str(slip)], indent=1), flush=True)
    name = "honesty_chapter5_default.json" if default_tol else "honesty_chapter5.json"
    (OUT / name).write_text(json.dumps({"scene": sc.name, "points": 513, **tol, "rows": rows},
                                                          indent=1))


#: name -> (scene, slip, points of the checked solve): the extrapolated films
EXTRAPOLATED = {
    "line_42400N_S0.1": ("appendix_c_line_42400N", 0.1, 513),
    "line_42400N_S1": ("appendix_c_line_42400N", 1.0, 513),
    "line_4240N_S0.1": ("appendix_c_line_4240N", 0.1, 513),
    "line_4240N_S1": ("appendix_c_line_4240N", 1.0, 513),
    "point_42.8N_S0": ("appendix_d_point", 0.0, 513),
    "point_42.8N_S0.5": ("appendix_d_point", 0.5, 513),
}


def extrapolated() -> None:
    """The grid part of an extrapolated TEHL film (``estimate_error(..., extrapolate=True)``,
    nz = 20, default box) against the same extrapolation one grid finer (five grids), whose own
    stated error is the reference's uncertainty: the box and nz parts do not change with it.
    Writes ``build/validation/tehl/honesty_extrapolated.json``."""
    from thermal.tehl.accuracy import extrapolated_films, grid_sequence

    out = {}
    for name, (scene_name, slip, n) in EXTRAPOLATED.items():
        sc = load_scene(scene_name)
        point = sc.kind != "line"
        cache = SolveCache(sc, slip, TEHLOptions(points=n, nz=20), point)
        t = time.perf_counter()
        r = cache(n, 20, 1.0)
        est = estimate_error(r, cache=cache, extrapolate=True)
        wall = time.perf_counter() - t
        fine = cache(2 * n - 1, 20, 1.0)
        row = {"scene": scene_name, "slip": slip, "points": n, "wall_s": wall, "correction": est.correction,
               "grid_x": {k: est.budget[k]["grid_x"] for k in ("Hc", "Hm")}}
        if fine is not None:
            ref = extrapolated_films(grid_sequence(fine, cache))
            row["reference_points"] = 2 * n - 1
            for k in ("Hc", "Hm"):
                value = getattr(r, k) * (1.0 + est.correction.get(k, 0.0))
                if k in ref:
                    truth = getattr(fine, k) * (1.0 + ref[k][0])
                    row[k] = {"true": abs(value / truth - 1.0), "reference_uncertainty": ref[k][1],
                              "stated": est.budget[k]["grid_x"], "extrapolated": k in est.correction}
        else:
            row["reference_error"] = cache.errors.get((2 * n - 1, 20, 1.0))
        out[name] = row
        print(name, json.dumps(row), flush=True)
        (OUT / "honesty_extrapolated.json").write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    names = sys.argv[1:] or [*CASES, "summary"]
    for name in names:
        if name == "summary":
            summary()
        elif name == "orders":
            orders()
        elif name == "extrapolated":
            extrapolated()
        elif name == "chapter5":
            chapter5()
        elif name == "chapter5_default":
            chapter5(default_tol=True)
        else:
            run_case(name)
