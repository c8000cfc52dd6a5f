"""The planner's temperature-rise estimate against the thermal solver.

For each built-in scene, slip and speed, compares

* the planner's cheap estimate ``ehl_multigrid.app.plan.temperature_rise_estimate`` (temperature rise
  dT_est [K] and the friction-sensitivity number the thermal decision uses), with
* the thermal Roelands-Eyring solver ``thermal.traction.solve_traction`` (Hertz pressure, uniform
  central film from the fit, the same film the estimate gets): maximum and contact-mean
  temperature rise above the oil temperature, and the relative change of friction
  ``f_thermal / f_isothermal - 1`` (``thermal=False`` holds the temperature at the oil value).

The planner's decision "thermal needed" (``THERMAL_DECISION_MARGIN * friction_sensitivity > tol``,
as in ``make_plan``; also reported without the margin) is scored against the truth ``|f_thermal / f_isothermal - 1| > tol`` at the fidelity tolerances
(fast 10 %, standard 2 %, reference 0.2 %).

Solver rows are cached in ``build/validation/plan/temperature_rise.json`` (written after every case, so an
interrupted run resumes); the estimate is cheap and recomputed from the current ``plan.py`` every
run, so a change to the estimate is re-scored with ``--no-solve``.

Usage::

    python validation/plan/temperature_rise.py            # full study, 616 cases (about 90 s on 1 core)
    python validation/plan/temperature_rise.py --quick    # 3 scenes, 2 slips, scene speed only (few s)
    python validation/plan/temperature_rise.py --no-solve # re-score cached rows only
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from ehl_multigrid.app import plan as planner
from ehl_multigrid.app.plan import (
    make_plan,
    slip_range,
    speed_range,
    temperature_rise_estimate,
)
from ehl_multigrid.model.errors import ConvergenceError, InputError
from ehl_multigrid.model.fidelity import FIDELITIES
from ehl_multigrid.model.scene import Scene, load_scene
from ehl_multigrid.model.solids import reduced_modulus

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("plan")
JSON_PATH = OUT / "temperature_rise.json"
PNG_PATH = OUT / "temperature_rise.png"
#: the estimate before this study's fix (same solver rows), kept for the before/after plot
BEFORE_PATH = OUT / "temperature_rise_before.json"

#: every built-in scene; cases whose thermal physics repeats an earlier case are skipped (the
#: series A-D scenes differ only in roughness, which the thermal model does not see)
SCENES = (
    "appendix_c_line_4240N", "appendix_c_line_42400N", "appendix_d_point",
    "page63_line_500N", "page63_line_2000N", "page63_line_8000N", "page63_line_16000N",
    "series_A_disc1_0.78GPa", "series_A_disc1_1GPa", "series_A_disc2_0.78GPa", "series_A_disc2_1GPa",
    "series_B_disc1_0.78GPa", "series_B_disc1_1GPa", "series_B_disc2_0.78GPa", "series_B_disc2_1GPa",
    "series_C_disc3_1.93GPa", "series_D_disc3_1.93GPa", "series_D_disc4_1.93GPa",
    "chapter6_starved_0.5GPa", "chapter6_starved_1.93GPa", "default",
    # not built in: an elliptic contact and a steel ball on a glass disc (another heat partition)
    "variant:elliptic", "variant:glass_disc",
)
QUICK_SCENES = ("appendix_c_line_42400N", "page63_line_2000N", "appendix_d_point")
SLIPS = (0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0)
SPEED_FACTORS = (0.1, 0.3, 1.0, 3.0, 10.0)
US_RANGE = (0.01, 50.0)  # m/s, the thermal corner range of the extremes matrix
#: optical-rig glass disc (typical soda-lime / BK7 values)
GLASS = {"name": "glass", "E": 81e9, "nu": 0.21, "rho": 2510.0, "k": 1.1, "cp": 840.0, "hardness": 6e9}


def scene_of(name: str) -> Scene:
    """A built-in scene, or one of the two variants of appendix_d_point."""
    if not name.startswith("variant:"):
        return load_scene(name)
    d = load_scene("appendix_d_point").to_dict()
    d.pop("ranges", None)
    d["name"] = name.replace(":", "_")
    if name == "variant:elliptic":
        d["contact"]["kind"] = "elliptic"
        d["geometry"]["Ry"] = 4.0 * d["geometry"]["Rx"]
    elif name == "variant:glass_disc":
        b1 = d["solids"]["body1"]
        d["solids"]["body2"] = dict(GLASS)
        d["solids"]["E_reduced"] = reduced_modulus(b1["E"], b1["nu"], GLASS["E"], GLASS["nu"])
    else:
        raise ValueError(name)
    return Scene.from_dict(d)


def physics_key(sc: Scene, us: float, slip: float) -> tuple:
    """What the thermal model and the estimate see of a case (roughness and supply excluded)."""
    return (sc.kind, sc.Rx, sc.Ry, sc.length, round(sc.load, 6), repr(sc.lubricant), repr(sc.body1), repr(sc.body2),
            sc.E_reduced, sc.T_oil, sc.T_surface1, sc.T_surface2, round(us, 9), slip,
            json.dumps(sc.solver.get("thermal", {}), sort_keys=True))


def compact(obj):
    """Floats to 8 significant digits (keeps the committed JSON small)."""
    if isinstance(obj, float):
        return obj if not math.isfinite(obj) else float(f"{obj:.8g}")
    if isinstance(obj, dict):
        return {k: compact(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [compact(v) for v in obj]
    if isinstance(obj, np.generic):
        return compact(obj.item())
    return obj


def to_table(rows: list[dict]) -> dict:
    """Rows as columns + data (the committed JSON repeats no key)."""
    cols: list[str] = []
    for r in rows:
        cols.extend(k for k in r if k not in cols)
    return {"columns": cols, "data": [[r.get(c) for c in cols] for r in rows]}


def from_table(t: dict | list) -> list[dict]:
    if isinstance(t, list):
        return t
    return [{c: v for c, v in zip(t["columns"], row, strict=True) if v is not None} for row in t["data"]]


def load_rows(path: Path) -> list[dict]:
    """Rows of a study JSON written by this script."""
    return from_table(json.loads(path.read_text()).get("rows", []))


def case_key(scene: str, us: float, slip: float) -> str:
    return f"{scene}|{us:.6g}|{slip:.6g}"


def solve_case(name: str, us: float, slip: float, nx: int | None, nz: int | None) -> dict:
    """Thermal and isothermal friction of one case (the expensive part)."""
    from thermal.traction import solve_traction

    sc = scene_of(name)
    h = float(sc.central_film_fit(us=us)[1])
    row: dict = {"scene": name, "kind": sc.kind, "us": us, "slip": slip, "h": h,
                 "pmax": sc.hertz.pmax, "T_oil": sc.T_oil}
    for label, th in (("th", True), ("iso", False)):
        t0 = time.perf_counter()
        try:
            r = solve_traction(sc, slip, us=us, h=h, thermal=th, nx=nx, nz=nz)
        except (ConvergenceError, InputError) as e:
            row[f"error_{label}"] = f"{type(e).__name__}: {e}"[:300]
            row[f"wall_{label}"] = time.perf_counter() - t0
            continue
        row[f"wall_{label}"] = time.perf_counter() - t0
        row[f"f_{label}"] = r.coefficient
        row[f"tau_{label}"] = r.mean_shear_stress
        row[f"converged_{label}"] = bool(r.converged)
        if th:
            row["dT_max"] = r.max_temperature_rise
            row["dT_mean"] = r.mean_temperature_rise
            if not r.converged or r.report.message != "converged":
                row["message_th"] = r.report.message[:200]
    if "f_th" in row and "f_iso" in row:
        row["friction_change"] = row["f_th"] / row["f_iso"] - 1.0
    return row


def add_estimate(row: dict) -> dict:
    """The planner's numbers for a row (recomputed from the current plan.py)."""
    sc = scene_of(row["scene"])
    t0 = time.perf_counter()
    est = temperature_rise_estimate(sc, row["us"], row["slip"], row["h"])
    row["wall_est"] = time.perf_counter() - t0
    row["dT_est"] = est["dT"]
    row["dT_est_mean"] = est.get("dT_mean", math.nan)
    row["dT_est_surface"] = est["dT_surface"]
    row["dT_est_isothermal_heat"] = est.get("dT_isothermal_heat", est["dT"])
    row["tau_est"] = est["tau"]
    row["sensitivity_est"] = est["friction_sensitivity"]
    row["sensitivity_est_linear"] = est.get("friction_sensitivity_linear", est["friction_sensitivity"])
    return row


def decision_margin() -> float:
    """The planner's safety factor on the sensitivity (1 before it existed)."""
    return float(getattr(planner, "THERMAL_DECISION_MARGIN", 1.0))


def usable(r: dict) -> bool:
    """A grid case (not a per-scene plan check) where both solves converged."""
    return not r.get("scene_plan") and bool(r.get("converged_th") and r.get("converged_iso") and "friction_change" in r)


def confusion(rows: list[dict], tol: float, margin: float) -> dict:
    """Planner decision ``margin * sensitivity > tol`` against ``|f_th/f_iso - 1| > tol``."""
    tp = fp = fn = tn = 0
    misses = []
    fp_ratios = []
    for r in rows:
        said = margin * r["sensitivity_est"] > tol
        true = abs(r["friction_change"]) > tol
        tp += said and true
        fp += said and not true
        fn += (not said) and true
        tn += (not said) and not true
        if said and not true:
            fp_ratios.append(abs(r["friction_change"]) / tol)
        if true and not said:
            misses.append({k: r[k] for k in ("scene", "us", "slip", "friction_change", "sensitivity_est", "dT_est", "dT_max")})
    return {"tol": tol, "margin": margin, "tp": tp, "fp": fp, "fn": fn, "tn": tn, "false_negatives": misses,
            "false_positive_min_change_over_tol": min(fp_ratios) if fp_ratios else None}


def ratio_stats(num: np.ndarray, den: np.ndarray) -> dict:
    m = (den > 0) & np.isfinite(num) & np.isfinite(den)
    r = num[m] / den[m]
    if r.size == 0:
        return {"n": 0}
    return {"n": int(r.size), "median": float(np.median(r)), "min": float(r.min()), "max": float(r.max()),
            "p10": float(np.percentile(r, 10)), "p90": float(np.percentile(r, 90))}


def summarise(rows: list[dict]) -> dict:
    ok = [r for r in rows if usable(r)]
    g = {k: np.array([r[k] for r in ok], dtype=float) for k in ("dT_est", "dT_est_mean", "dT_est_isothermal_heat", "dT_max", "dT_mean", "sensitivity_est", "friction_change", "tau_est", "tau_iso")}
    # only rises that matter numerically (below 0.1 K the ratio is round-off in both)
    big = g["dT_max"] > 0.1
    rel = np.abs(g["friction_change"])
    sens_ratio = ratio_stats(g["sensitivity_est"][rel > 1e-3], rel[rel > 1e-3])
    return {
        "cases": len(rows), "usable": len(ok),
        "failed_or_unconverged": [{k: r.get(k) for k in ("scene", "us", "slip", "error_th", "error_iso", "converged_th", "converged_iso")}
                                  for r in rows if not usable(r)],
        "ratio_dT_est_over_dT_max": ratio_stats(g["dT_est"][big], g["dT_max"][big]),
        "ratio_dT_est_isothermal_heat_over_dT_max": ratio_stats(g["dT_est_isothermal_heat"][big], g["dT_max"][big]),
        "ratio_dT_est_mean_over_dT_mean": ratio_stats(g["dT_est_mean"][big], g["dT_mean"][big]),
        "ratio_sensitivity_over_friction_change": sens_ratio,
        "ratio_tau_est_over_tau_isothermal": ratio_stats(g["tau_est"], g["tau_iso"]),
        "ratio_sensitivity_over_friction_change_linear_regime": ratio_stats(
            g["sensitivity_est"][(rel > 1e-3) & (rel < 0.05)], rel[(rel > 1e-3) & (rel < 0.05)]),
        "decision_margin": decision_margin(),
        "confusion": {fid: confusion(ok, f.tolerance, decision_margin()) for fid, f in FIDELITIES.items()},
        "confusion_without_margin": {fid: confusion(ok, f.tolerance, 1.0) for fid, f in FIDELITIES.items()},
        "wall_s": {"thermal_total": float(sum(r.get("wall_th", 0.0) for r in rows)),
                   "isothermal_total": float(sum(r.get("wall_iso", 0.0) for r in rows)),
                   "estimate_total": float(sum(r.get("wall_est", 0.0) for r in rows))},
    }


def plot(rows: list[dict], path: Path, before: dict | None = None) -> None:
    """Estimate against solver (log-log, 1:1 line); ``before`` adds an earlier estimate in grey."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ok = [r for r in rows if usable(r)]
    fig, axs = plt.subplots(1, 2, figsize=(11, 4.8), layout="constrained")
    if before:
        old = {case_key(r["scene"], r["us"], r["slip"]): r for r in from_table(before.get("rows", []))}
        pairs = [(r, old[k]) for r in ok if (k := case_key(r["scene"], r["us"], r["slip"])) in old]
        axs[0].scatter([max(r["dT_max"], 1e-4) for r, _ in pairs], [max(o["dT_est"], 1e-4) for _, o in pairs],
                       marker="x", s=12, c="0.7", lw=0.7, label="before (plan.py at git HEAD)")
        axs[1].scatter([max(abs(r["friction_change"]), 1e-6) for r, _ in pairs],
                       [max(o["sensitivity_est"], 1e-6) for _, o in pairs],
                       marker="x", s=12, c="0.7", lw=0.7, label="before (plan.py at git HEAD)")
    sc = None
    for kind, mk in (("line", "o"), ("point", "s"), ("elliptic", "^")):
        sel = [r for r in ok if r["kind"] == kind]
        if not sel:
            continue
        c = np.log10([r["slip"] for r in sel])
        kw = {"c": c, "cmap": "viridis", "marker": mk, "s": 16, "vmin": -2, "vmax": math.log10(2), "label": kind}
        sc = axs[0].scatter([max(r["dT_max"], 1e-4) for r in sel], [max(r["dT_est"], 1e-4) for r in sel], **kw)
        axs[1].scatter([max(abs(r["friction_change"]), 1e-6) for r in sel],
                       [max(r["sensitivity_est"], 1e-6) for r in sel], **kw)
    lo, hi = 1e-4, 1e4
    axs[0].plot([lo, hi], [lo, hi], "k-", lw=0.8, label="1:1")
    axs[0].set(xscale="log", yscale="log", xlabel="thermal solver: max temperature rise [K]",
               ylabel="planner estimate dT (max, mid-film) [K]", xlim=(lo, hi), ylim=(lo, hi), title="temperature rise")
    lo, hi = 1e-6, 10.0
    axs[1].plot([lo, hi], [lo, hi], "k-", lw=0.8, label="1:1")
    m = decision_margin()
    for tol in (f.tolerance for f in FIDELITIES.values()):
        axs[1].axvline(tol, color="r", lw=0.5, ls=":")
        axs[1].axhline(tol / m, color="r", lw=0.5, ls=":")
    axs[1].set(xscale="log", yscale="log", xlabel="thermal solver: |f_thermal / f_isothermal - 1|",
               ylabel="planner friction sensitivity", xlim=(lo, hi), ylim=(lo, hi),
               title=f"friction change (dotted: tol and tol/{m:g})")
    for ax in axs:
        ax.legend(loc="upper left", fontsize=8)
        ax.grid(True, which="major", lw=0.3)
    if sc is not None:
        fig.colorbar(sc, ax=axs, label="log10 slip", shrink=0.8)
    fig.savefig(path, dpi=100)
    plt.close(fig)


def scene_plan_rows(names: tuple[str, ...], cached: dict[str, dict]) -> list[dict]:
    """``make_plan``'s thermal decision for each built-in scene at each fidelity, against the
    thermal solver at the scene's worst case (largest |slip| and speed of its ranges)."""
    out, seen = [], {}
    for name in names:
        if name.startswith("variant:"):
            continue
        sc = load_scene(name)
        s_worst = float(np.max(np.abs(slip_range(sc))))
        u_worst = float(np.max(speed_range(sc)))
        if s_worst == 0:
            continue
        key = physics_key(sc, u_worst, s_worst)
        if key in seen:
            row = dict(seen[key], scene=name)
        else:
            ck = "plan|" + case_key(name, u_worst, s_worst)
            row = cached.get(ck) or solve_case(name, u_worst, s_worst, None, None)
            row["key"] = ck
            seen[key] = row
        row = dict(row)
        for fid in FIDELITIES:
            d = make_plan(sc, fidelity=fid).get("thermal")
            row[f"plan_{fid}"] = {"include": d.include, "estimate": d.estimate, "threshold": d.threshold}
        out.append(row)
    return out


def cases(scenes: tuple[str, ...], slips: tuple[float, ...], factors: tuple[float, ...]) -> list[tuple[str, float, float]]:
    out, seen = [], set()
    for name in scenes:
        sc = scene_of(name)
        for f in factors:
            us = float(sc.us * f)
            if not US_RANGE[0] <= us <= US_RANGE[1]:
                continue
            for s in slips:
                key = physics_key(sc, us, float(s))
                if key not in seen:
                    seen.add(key)
                    out.append((name, us, float(s)))
    return out


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="3 scenes, slips 0.05 and 1, scene speed only")
    ap.add_argument("--no-solve", action="store_true", help="re-score the cached solver rows only")
    ap.add_argument("--resolve", action="store_true", help="ignore cached solver rows")
    ap.add_argument("--nx", type=int, default=None, help="thermal nx (default: scene / 80)")
    ap.add_argument("--nz", type=int, default=None, help="thermal nz (default: scene / 20)")
    ap.add_argument("--out", type=Path, default=None, help="JSON path (default build/validation/plan/temperature_rise[_quick].json)")
    args = ap.parse_args(argv)
    if args.out is None:
        args.out = JSON_PATH.with_name("temperature_rise_quick.json") if args.quick else JSON_PATH

    if args.quick:
        todo = cases(QUICK_SCENES, (0.05, 1.0), (1.0,))
    else:
        todo = cases(SCENES, SLIPS, SPEED_FACTORS)
    cached: dict[str, dict] = {}
    if args.out.exists() and not args.resolve:
        cached = {r.get("key") or case_key(r["scene"], r["us"], r["slip"]): r
                  for r in load_rows(args.out)}
    rows: list[dict] = []
    args.out.parent.mkdir(parents=True, exist_ok=True)

    def write(summary: dict | None = None) -> None:
        payload = {"description": "planner temperature-rise estimate vs thermal solver (validation/plan/temperature_rise.py)",
                   "solver": "thermal.traction.solve_traction, input=hertz, uniform film = scene.central_film_fit",
                   "summary": summary, "rows": to_table(rows)}
        tmp = args.out.with_suffix(".tmp")
        tmp.write_text(json.dumps(compact(payload), separators=(",", ":")))
        tmp.replace(args.out)

    from tqdm import tqdm

    for name, us, slip in tqdm(todo, desc="temperature rise", unit="case"):
        key = case_key(name, us, slip)
        if key in cached:
            row = cached[key]
        elif args.no_solve:
            continue
        else:
            row = solve_case(name, us, slip, args.nx, args.nz)
        rows.append(add_estimate(row))
        if key not in cached:
            write()
    summary = summarise(rows)
    if not args.quick:
        plan_rows = scene_plan_rows(SCENES, cached)
        summary["scene_plans"] = [
            {"scene": r["scene"], "slip": r["slip"], "us": r["us"], "friction_change": r.get("friction_change"),
             "converged": usable(r), **{f"plan_{f}": r[f"plan_{f}"] for f in FIDELITIES}} for r in plan_rows]
        rows.extend(dict(r, scene_plan=True) for r in plan_rows if r["key"] not in {x.get("key") for x in rows})
    write(summary)
    if rows:
        before = BEFORE_PATH if BEFORE_PATH.exists() else None
        plot(rows, PNG_PATH if args.out == JSON_PATH else args.out.with_suffix(".png"),
             {"rows": load_rows(before)} if before else None)
    print_summary(summary)
    return summary


def print_summary(s: dict) -> None:
    print(f"cases {s['cases']}, usable {s['usable']}")
    for k in ("ratio_dT_est_over_dT_max", "ratio_dT_est_isothermal_heat_over_dT_max", "ratio_dT_est_mean_over_dT_mean", "ratio_sensitivity_over_friction_change",
              "ratio_sensitivity_over_friction_change_linear_regime", "ratio_tau_est_over_tau_isothermal"):
        v = s[k]
        if v.get("n"):
            print(f"  {k:<42} n={v['n']:<4} median {v['median']:.3g}  min {v['min']:.3g}  max {v['max']:.3g}  "
                  f"p10 {v['p10']:.3g}  p90 {v['p90']:.3g}")
    for label in ("confusion", "confusion_without_margin"):
        print(f"  {label} (planner 'thermal needed' vs |f_th/f_iso - 1| > tol):")
        for fid, c in s[label].items():
            print(f"    {fid:<9} tol {c['tol']:<6g} margin {c['margin']:<5g} TP {c['tp']:<4} FP {c['fp']:<4} FN {c['fn']:<4} "
                  f"TN {c['tn']:<4} smallest FP change/tol {c['false_positive_min_change_over_tol']}")
            for m in c["false_negatives"]:
                print(f"       FN {m['scene']} us={m['us']:.3g} S={m['slip']:g}: change {m['friction_change']:+.3g}, "
                      f"sens {m['sensitivity_est']:.3g}, dT est {m['dT_est']:.3g} / max {m['dT_max']:.3g} K")
    for p in s.get("scene_plans", []):
        print(f"  plan {p['scene']:<26} S {p['slip']:<4g} us {p['us']:<6.3g} solver change {p['friction_change']:+.3g}  "
              + "  ".join(f"{f}: {'yes' if p['plan_' + f]['include'] else 'no'} ({p['plan_' + f]['estimate']:.3g})"
                          for f in FIDELITIES))
    for f in s["failed_or_unconverged"]:
        print(f"  not usable: {f}")
    print(f"  wall: {s['wall_s']}")


if __name__ == "__main__":
    main()
