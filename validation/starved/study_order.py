"""Second-order (per-face) wedge of the starved point solver against first order.

Run: ``python validation/starved/study_order.py {map,map1,grid,scene,scenefine,summary,all}
[--quick]``
(about 18 min in all on the shared 2-core box); writes
``build/validation/starved/starved_order_<part>.json``. Every number of the "second-order wedge" part of REPORT.md
comes from these files.

* ``map``: the 55-supply map of study_point.py (same cases, same supplies in units of the
  first-order flooded film, so the supplies are identical to the first-order run in
  build/validation/starved/starved_point.json) solved with ``wedge_order = 2``; flooded limit against the core's
  default second-order solve on the same grid; status, cycles, mass imbalance, wall time;
  the film ratios against the first-order ones (read from build/validation/starved/starved_point.json).
* ``map1``: the same map with ``wedge_order = 1`` and the current code (the first-order
  reference of the comparison; ``first`` in each record is the older build/validation/starved/starved_point.json).
* ``grid``: Hc and Hm on 129/257/513 for a few supplies, first and second order: observed
  order and Richardson value.
* ``scene``: the chapter-6 0.5 GPa scene with a 20 nm layer through
  ``solve_starved_point_scene`` at 257 and 513 points: error estimate and the film's change
  to the next grid.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.point.solve import solve_fas
from ehl_multigrid.starved.point import STARVED_TOL, solve_starved_point

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir, require  # noqa: E402

OUT = out_dir("starved")
RATIOS = [4.0, 2.0, 1.5, 1.2, 1.0, 0.8, 0.6, 0.4, 0.25, 0.1, 0.03]
PLAN = [(20.0, 10.0, 129), (20.0, 10.0, 257), (100.0, 10.0, 257), (100.0, 5.0, 257), (179.0, 4.17, 257)]


def _first_order_map() -> dict:
    path = OUT / "starved_point.json"
    if not path.exists():
        return {}
    d = json.loads(path.read_text())
    return {(c["M"], c["L"], c["points"]): c for c in d["cases"]}


def run_map(plan: list[tuple[float, float, int]], order: int = 2) -> dict:
    first = _first_order_map()
    cases = []
    for M, L, n in plan:
        pb = problem_from_moes(M, L)
        kw = dict(points=n, half=True, raise_on_failure=False)
        ff1 = solve_fas(pb, wedge_order=1, tol=STARVED_TOL, max_cycles=40, **kw)
        ff2 = solve_fas(pb, tol=STARVED_TOL, max_cycles=40, **kw)
        H1 = ff1.scalars["Hc_venner"]
        f1 = first.get((M, L, n), {"runs": []})
        f1runs = {r["hoil_over_Hc_ff"] if r["hoil_over_Hc_ff"] is not None else math.inf: r for r in f1["runs"]}
        case = {"M": M, "L": L, "points": n, "Hc_ff1": H1, "Hc_ff2_core": ff2.scalars["Hc_venner"],
                "Hm_ff2_core": ff2.scalars["Hm_venner"], "core2_status": ff2.status_name, "runs": []}
        Hff2 = Hmff2 = math.nan
        for ratio in [math.inf] + RATIOS:
            hoil = math.inf if math.isinf(ratio) else ratio * H1
            t0 = time.perf_counter()
            s = solve_starved_point(pb, hoil, wedge_order=order, **kw)
            wall = time.perf_counter() - t0
            Hc, Hm = s.scalars["Hc_venner"], s.scalars["Hm_venner"]
            if math.isinf(ratio):
                Hff2, Hmff2 = Hc, Hm
            rec = {"hoil_over_Hc_ff": ratio, "status": s.status_name, "cycles": len(s.residual_history),
                   "final_residual": float(s.residual_history[-1]), "Hc": Hc, "Hm": Hm,
                   "Hc_ratio": Hc / Hff2, "Hm_ratio": Hm / Hmff2,
                   "mass_balance_error": s.extra["mass_balance_error"], "wall_s": wall,
                   "meniscus_x": s.extra["meniscus_x"], "actions": [a for a in s.actions if "coarse-grid" in a
                                                                    or "mass imbalance" in a]}
            o1 = f1runs.get(ratio)
            if o1 is not None:
                rec["first"] = {k: o1.get(k) for k in ("status", "cycles", "Hc", "Hm", "Hc_ratio", "Hm_ratio",
                                                        "mass_balance_error", "wall_s")}
                if o1.get("Hc_ratio") is not None and math.isfinite(ratio):
                    rec["Hc_ratio_change"] = rec["Hc_ratio"] / o1["Hc_ratio"] - 1.0
                    rec["Hm_ratio_change"] = rec["Hm_ratio"] / o1["Hm_ratio"] - 1.0
            if math.isinf(ratio):
                rec["Hc_vs_core2"] = Hc / ff2.scalars["Hc_venner"] - 1.0
                rec["Hm_vs_core2"] = Hm / ff2.scalars["Hm_venner"] - 1.0
            case["runs"].append(rec)
            print(f"M {M:g} L {L:g} n {n} Hoil/Hcff {ratio:g}: {s.status_name} Hc/Hcff {rec['Hc_ratio']:.5f} "
                  f"(1st {o1['Hc_ratio'] if o1 else float('nan'):.5f}, {o1['status'] if o1 else '-'}) "
                  f"mb {rec['mass_balance_error']:.2e} cyc {rec['cycles']} {wall:.1f} s", flush=True)
        cases.append(case)
    return {"cases": cases}


def _order(v: list[float]) -> dict:
    d1, d2 = v[1] - v[0], v[2] - v[1]
    p = math.log2(abs(d1 / d2)) if d1 * d2 > 0 and d2 != 0 else math.nan
    pp = p if math.isfinite(p) else 1.0
    return {"values": v, "order": p, "richardson": v[2] + d2 / (2.0**pp - 1.0)}


def run_grid(cases: list[tuple[float, float, float]], grids: list[int]) -> dict:
    out = []
    for M, L, ratio in cases:
        pb = problem_from_moes(M, L)
        ff = solve_fas(pb, points=257, half=True, wedge_order=1, tol=STARVED_TOL, max_cycles=40,
                       raise_on_failure=False)
        hoil = ratio * ff.scalars["Hc_venner"]  # supply fixed in Venner units across grids
        rec = {"M": M, "L": L, "hoil_over_Hc_ff257": ratio, "hoil": hoil}
        for order in (1, 2):
            Hc, Hm, st, wall = [], [], [], []
            for n in grids:
                t0 = time.perf_counter()
                s = solve_starved_point(pb, hoil, points=n, half=True, raise_on_failure=False, wedge_order=order)
                wall.append(time.perf_counter() - t0)
                Hc.append(s.scalars["Hc_venner"])
                Hm.append(s.scalars["Hm_venner"])
                st.append(s.status_name)
                print(f"grid M {M:g} L {L:g} ratio {ratio:g} order {order} n {n}: {s.status_name} "
                      f"Hc {Hc[-1]:.7g} Hm {Hm[-1]:.7g} mb {s.extra['mass_balance_error']:.1e} {wall[-1]:.1f} s", flush=True)
            r = {"grids": grids, "status": st, "wall_s": wall, "Hc": _order(Hc), "Hm": _order(Hm)}
            for key in ("Hc", "Hm"):
                ex = r[key]["richardson"]
                r[key]["rel_error"] = [abs(x / ex - 1.0) for x in r[key]["values"]]
            rec[f"order{order}"] = r
        out.append(rec)
    return {"cases": out}


def run_scene(points: list[int]) -> dict:
    from ehl_multigrid.model.scene import load_scene
    from ehl_multigrid.starved import solve_starved_point_scene

    scene = load_scene("chapter6_starved_0.5GPa")
    out = []
    for order in (2, 1):
        for n in points:
            t0 = time.perf_counter()
            s = solve_starved_point_scene(scene, hoil=20e-9, points=n, accuracy=0.005,
                                          raise_on_failure=False, wedge_order=order)
            wall = time.perf_counter() - t0
            e = s.error
            rec = {"order": order, "points": n, "status": s.status_name, "wall_s": wall,
                   "Hc": s.scalars["Hc_venner"], "Hm": s.scalars["Hm_venner"],
                   "Hc_ratio": s.scalars.get("Hc_ratio"), "Hm_ratio": s.scalars.get("Hm_ratio"),
                   "Hc_error": e.Hc, "Hm_error": e.Hm, "budget": e.budget,
                   "mass_balance_error": s.scalars["mass_balance_error"], "meniscus_x": s.scalars["meniscus_x"]}
            out.append(rec)
            print(f"scene order {order} n {n}: {s.status_name} Hc {rec['Hc']:.7g} Hm {rec['Hm']:.7g} "
                  f"est Hc {e.Hc:.2e} Hm {e.Hm:.2e} {wall:.1f} s", flush=True)
    return {"runs": out}


def run_scene_fine(plan: list[tuple[int, int]]) -> dict:
    """The chapter-6 scene (20 nm) on finer grids without estimate or flooded companion:
    the next grids of the ``scene`` part's sequences (does the 513 estimate cover them?)."""
    from ehl_multigrid.model.scene import load_scene
    from ehl_multigrid.starved import solve_starved_point_scene

    scene = load_scene("chapter6_starved_0.5GPa")
    out = []
    for order, n in plan:
        t0 = time.perf_counter()
        s = solve_starved_point_scene(scene, hoil=20e-9, points=n, estimate=False, flooded=False,
                                      raise_on_failure=False, wedge_order=order)
        rec = {"order": order, "points": n, "status": s.status_name, "Hc": s.scalars["Hc_venner"],
               "Hm": s.scalars["Hm_venner"], "mass_balance_error": s.scalars["mass_balance_error"],
               "wall_s": time.perf_counter() - t0, "actions": s.actions}
        print(rec, flush=True)
        out.append(rec)
    return {"runs": out}


def _part(part: str) -> dict:
    """The JSON of another part of this study (written by ``study_order.py <part>``)."""
    path = OUT / f"starved_order_{part}.json"
    return json.loads(require(path, f"python validation/starved/study_order.py {part}").read_text())


def summarise() -> dict:
    """Tables of REPORT.md from the JSON of the other parts: map statistics per case (both
    orders with the current code), grid orders, and the estimate check (the two-grid estimate
    of starved_point_error's grid part on the finer grid of a pair against the change to the
    next grid and against the three-grid Richardson value)."""
    from ehl_multigrid.multigrid.accuracy import GRID_SAFETY
    from ehl_multigrid.starved.point import GRID_ORDER

    m2 = _part("map")
    m1 = _part("map1")
    rows = []
    for c2, c1 in zip(m2["cases"], m1["cases"], strict=True):
        row = {"case": [c2["M"], c2["L"], c2["points"]]}
        for tag, c in (("order2", c2), ("order1", c1)):
            runs = [r for r in c["runs"] if math.isfinite(r["hoil_over_Hc_ff"])]
            mb = [r["mass_balance_error"] for r in runs]
            row[tag] = {"converged": sum(r["status"] == "converged" for r in runs), "n": len(runs),
                        "mb_max": max(mb), "mb_below_1e-6": sum(m <= 1e-6 for m in mb),
                        "mb_max_mild": max(m for r, m in zip(runs, mb, strict=True) if r["hoil_over_Hc_ff"] <= 0.6),
                        "cycles": [min(r["cycles"] for r in runs), max(r["cycles"] for r in runs)],
                        "wall_s": sum(r["wall_s"] for r in runs)}
        flood = next(r for r in c2["runs"] if not math.isfinite(r["hoil_over_Hc_ff"]))
        row["flooded_vs_core2"] = {"Hc": flood["Hc_vs_core2"], "Hm": flood["Hm_vs_core2"]}
        row["core2_over_core1"] = c2["Hc_ff2_core"] / c2["Hc_ff1"] - 1.0
        r1 = {r["hoil_over_Hc_ff"]: r for r in c1["runs"]}
        row["Hc_ratio"] = {str(r["hoil_over_Hc_ff"]): [r["Hc_ratio"], r1[r["hoil_over_Hc_ff"]]["Hc_ratio"]]
                           for r in c2["runs"] if math.isfinite(r["hoil_over_Hc_ff"])}
        # the same supplies against the same (second-order core) flooded film
        row["Hc_over_core2_ff"] = {str(r["hoil_over_Hc_ff"]): [r["Hc"] / c2["Hc_ff2_core"],
                                                                 r1[r["hoil_over_Hc_ff"]]["Hc"] / c2["Hc_ff2_core"]]
                                   for r in c2["runs"] if math.isfinite(r["hoil_over_Hc_ff"])}
        rows.append(row)
    checks = []
    g = _part("grid")
    for c in g["cases"]:
        for order in (1, 2):
            r = c[f"order{order}"]
            for key, p in zip(("Hc", "Hm"), GRID_ORDER[order], strict=True):
                v = r[key]["values"]
                est = GRID_SAFETY * abs(v[1] - v[0]) / (2.0**p - 1.0) / abs(v[1])
                checks.append({"case": [c["M"], c["L"], c["hoil_over_Hc_ff257"]], "order": order, "film": key,
                               "grid": 257, "coarse_converged": r["status"][0] == "converged",
                               "estimate": est, "change_to_513": abs(v[2] / v[1] - 1.0),
                               "vs_richardson": abs(v[1] / r[key]["richardson"] - 1.0)})
    sc = _part("scene")["runs"]
    for order in (1, 2):
        a, b = [x for x in sc if x["order"] == order]
        for key in ("Hc", "Hm"):
            checks.append({"case": "chapter6 20 nm", "order": order, "film": key, "grid": a["points"],
                           "estimate": a[f"{key}_error"], "change_to_513": abs(b[key] / a[key] - 1.0)})
    fine_path = OUT / "starved_order_scenefine.json"
    scene_seq = {}
    if fine_path.exists():
        fine = json.loads(fine_path.read_text())["runs"]
        for order in (1, 2):
            seq = sorted([(x["points"], x["Hc"], x["Hm"]) for x in sc if x["order"] == order]
                         + [(x["points"], x["Hc"], x["Hm"]) for x in fine if x["order"] == order])
            scene_seq[order] = {"points": [q[0] for q in seq], "Hc": [q[1] for q in seq],
                                "Hm": [q[2] for q in seq]}
        # reference: Richardson of the last three second-order grids (observed order)
        ref = {}
        for key in ("Hc", "Hm"):
            v = scene_seq[2][key][-3:]
            ref[key] = _order(v)
        scene_seq["reference_order2"] = ref
        for x in sc:
            for key in ("Hc", "Hm"):
                checks.append({"case": "chapter6 20 nm", "order": x["order"], "film": key, "grid": x["points"],
                               "estimate": x[f"{key}_error"],
                               "vs_2049_richardson": abs(x[key] / ref[key]["richardson"] - 1.0)})
    return {"map": rows, "estimate_checks": checks, "scene_sequence": scene_seq,
            "scene": [{k: x[k] for k in ("order", "points", "status", "Hc", "Hm", "Hc_ratio", "Hm_ratio",
                                         "Hc_error", "Hm_error", "mass_balance_error", "wall_s")} for x in sc]}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("part", choices=["map", "map1", "grid", "scene", "scenefine", "summary", "all"])
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    OUT.mkdir(exist_ok=True)
    tag = "_quick" if args.quick else ""
    parts = (["map", "map1", "grid", "scene", "scenefine", "summary"] if args.part == "all"
             else [args.part])
    for part in parts:
        t0 = time.perf_counter()
        if part in ("map", "map1"):
            # map1: the first-order solver on the same map with the current code (policy)
            data = run_map(PLAN[:1] if args.quick else PLAN, 1 if part == "map1" else 2)
        elif part == "grid":
            cases = [(20.0, 10.0, 0.4)] if args.quick else [(20.0, 10.0, 0.4), (20.0, 10.0, 1.0),
                                                             (179.0, 4.17, 0.6)]
            data = run_grid(cases, [65, 129, 257] if args.quick else [129, 257, 513])
        elif part == "scene":
            data = run_scene([129] if args.quick else [257, 513])
        elif part == "scenefine":
            data = run_scene_fine([(2, 257)] if args.quick else [(2, 1025), (1, 1025), (2, 2049)])
        else:
            data = summarise()
        data["wall_s"] = time.perf_counter() - t0
        (OUT / f"starved_order_{part}{tag}.json").write_text(json.dumps(data, indent=1, default=float))
        print(part, f"wall {data['wall_s']:.0f} s", flush=True)


if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
