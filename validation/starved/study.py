"""Validation of the starved, mass-conserving line solver (ehl_multigrid.starved).

Run: ``python validation/starved/study.py [--quick]``. Writes build/validation/starved/starved_line.json and
build/validation/starved/starved_line.png (film reduction, starved limit, fields of one solution, grid
convergence). Every number in REPORT.md comes from the JSON.

Checks, each against something independent of the starved solver:

* flooded limit: a thick supply against the core flooded line solver (its own error estimate);
  the Elrod-Adams outlet against the Reynolds outlet on the same grid;
* mass conservation: flux through the first and last face, and the outlet layer against the
  supply, over the whole map;
* the starved limit: ``rho_c Hc/Hoil`` (1 when the central film carries the supply);
* film reduction ``Hc/Hc_ff`` against Chevalier's reduction (6.1)
  ``r/(1 + r^delta)^(1/delta)``, ``r = Hoil/(Hc_ff rho_bar(pmax))``, with the mixed layer's
  ``delta = 3.5`` and the least-squares ``delta`` of the line solver;
* the coupled inlet relaxation (meniscus inside the multilevel iteration) against the outer
  meniscus search;
* grid convergence at fixed supply (observed order, Richardson value) and cost.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
import scipy.optimize

from ehl_multigrid.line import LineProblem, solve_line
from ehl_multigrid.model.errors import ConvergenceError
from ehl_multigrid.multigrid.accuracy import richardson
from ehl_multigrid.starved import solve_starved_line
from ehl_multigrid.starved.line import solve_starved_problem, starved_options
from mixed.starvation import chevalier_reduction

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("starved")
#: (M, L) of the map: moderate and high load, a compressible thick film, low pressure-viscosity
CASES = [(20.0, 10.0), (100.0, 10.0), (5.0, 5.0), (50.0, 5.0)]
#: supplies as fractions of the flooded flux (beyond 1: flooded)
FRACTIONS = [0.15, 0.25, 0.4, 0.6, 0.8, 0.9, 0.95]
DELTA_MIXED = 3.5


def scalars(r) -> dict:
    keys = ["Hc_venner", "Hm_venner", "Hc_flooded_venner", "Hm_flooded_venner", "Hc_ratio", "Hm_ratio",
            "meniscus_x", "cavitation_x", "mass_balance_error", "supply_mismatch", "outlet_layer_venner",
            "rho_c", "rho_c_Hc_over_hoil", "flux_flooded", "rho_bar_pmax", "Hc_error", "Hm_error",
            "outlet_change_Hc", "outlet_change_Hm", "hoil_venner"]
    out = {k: float(r.scalars[k]) for k in keys if k in r.scalars}
    out.update(wall_s=float(r.wall_s), meniscus_solves=int(r.extra.get("meniscus_solves", 1)),
               status=r.status_name)
    return out


def flooded_limit(points: int) -> dict:
    core = solve_line(20.0, 10.0, points=points)
    thick = solve_starved_line(LineProblem.from_moes(20.0, 10.0), 10.0, points=points)
    return {"points": points, "core_Hc": core.Hc, "core_Hm": core.Hm, "core_Hc_error": core.Hc_error,
            "core_Hm_error": core.Hm_error, "starved_Hc": thick.Hc, "starved_Hm": thick.Hm,
            "dHc_rel": thick.Hc / core.Hc - 1.0, "dHm_rel": thick.Hm / core.Hm - 1.0,
            "outlet_change_Hc": thick.scalars["outlet_change_Hc"],
            "outlet_change_Hm": thick.scalars["outlet_change_Hm"],
            "mass_balance_error": thick.scalars["mass_balance_error"],
            "inlet_flooded": bool(thick.scalars["inlet_flooded"])}


def reduction_map(points: int, cases: list, fractions: list) -> list[dict]:
    rows = []
    for M, L in cases:
        pb = LineProblem.from_moes(M, L)
        ff = solve_starved_line(pb, math.inf, points=points, estimate=False)
        F_ff = ff.scalars["flux_flooded"]
        for frac in fractions:
            hoil = frac * F_ff
            t = time.perf_counter()
            try:
                r = solve_starved_line(pb, hoil, points=points, raise_on_failure=True)
                row = scalars(r)
            except ConvergenceError as exc:
                row = {"status": "failed", "message": str(exc).split("\n")[0]}
            row.update(M=M, L=L, fraction_of_flooded_flux=frac, hoil_venner=hoil, wall_s=time.perf_counter() - t)
            if "Hc_ratio" in row:
                row["r"] = hoil / (row["Hc_flooded_venner"] * row["rho_bar_pmax"])
                row["chevalier_3.5"] = float(chevalier_reduction(row["r"], DELTA_MIXED))
                row["solver_over_fit"] = row["Hc_ratio"] / row["chevalier_3.5"]
            rows.append(row)
            print(f"M={M:g} L={L:g} F/Fff={frac:.2f}: {row.get('status')} Hc/Hcff={row.get('Hc_ratio', math.nan):.4f} "
                  f"fit={row.get('chevalier_3.5', math.nan):.4f} mb={row.get('mass_balance_error', math.nan):.1e} "
                  f"{row['wall_s']:.1f}s", flush=True)
    return rows


def best_delta(rows: list[dict]) -> dict:
    ok = [r for r in rows if "r" in r]
    r = np.array([x["r"] for x in ok])
    y = np.array([x["Hc_ratio"] for x in ok])

    def misfit(d: float) -> float:
        return float(np.sum((np.log(chevalier_reduction(r, d)) - np.log(y)) ** 2))

    res = scipy.optimize.minimize_scalar(misfit, bounds=(0.5, 20.0), method="bounded")
    d = float(res.x)
    return {"delta": d, "rms_log_misfit": math.sqrt(misfit(d) / len(ok)),
            "rms_log_misfit_3.5": math.sqrt(misfit(DELTA_MIXED) / len(ok)),
            "max_rel_dev_best": float(np.max(np.abs(chevalier_reduction(r, d) / y - 1.0))),
            "max_rel_dev_3.5": float(np.max(np.abs(chevalier_reduction(r, DELTA_MIXED) / y - 1.0))),
            "min_ratio": {"solver": float(np.min(y)), "r": float(r[np.argmin(y)])}}


def coupled_check(points: int) -> list[dict]:
    pb = LineProblem.from_moes(20.0, 10.0)
    rows = []
    for hoil in (0.07, 0.05, 0.02):
        t = time.perf_counter()
        c = solve_starved_problem(pb, hoil, starved_options(points=points, raise_on_failure=False))
        tc = time.perf_counter() - t
        o = solve_starved_line(pb, hoil, points=points, estimate=False)
        rows.append({"hoil_venner": hoil, "points": points, "coupled_status": c.status_name,
                     "coupled_Hc": c.scalars.get("Hc_venner", math.nan), "outer_Hc": o.scalars["Hc_venner"],
                     "coupled_Hm": c.scalars.get("Hm_venner", math.nan), "outer_Hm": o.scalars["Hm_venner"],
                     "coupled_meniscus_x": c.scalars.get("meniscus_x", math.nan),
                     "outer_meniscus_x": o.scalars["meniscus_x"],
                     "coupled_mass_balance_error": c.scalars.get("mass_balance_error", math.nan),
                     "coupled_cycles": c.cycles, "coupled_wall_s": tc, "outer_wall_s": o.wall_s})
        print("coupled", rows[-1], flush=True)
    return rows


def grid_convergence(grids: list[int], hoil: float) -> dict:
    pb = LineProblem.from_moes(20.0, 10.0)
    rows = []
    for n in grids:
        r = solve_starved_line(pb, hoil, points=n)
        rows.append({"points": n, **scalars(r), "work_units": float(r.work_units)})
        print("grid", n, rows[-1]["Hc_venner"], rows[-1]["Hm_venner"], rows[-1]["wall_s"], flush=True)
    out: dict = {"hoil_venner": hoil, "rows": rows}
    for key in ("Hc_venner", "Hm_venner", "meniscus_x", "Hc_ratio"):
        v = [x[key] for x in rows]
        rich = richardson(v, safety=1.0)
        out[key] = {"order": rich.order, "extrapolated": rich.extrapolated,
                    "finest_rel_error_vs_extrapolated": abs(v[-1] / rich.extrapolated - 1.0)
                    if math.isfinite(rich.extrapolated) else math.nan}
    return out


def starved_limit(points: int) -> list[dict]:
    pb = LineProblem.from_moes(20.0, 10.0)
    rows = []
    for hoil in (0.09, 0.05, 0.02, 0.01, 0.007):
        try:
            r = solve_starved_line(pb, hoil, points=points, estimate=False, raise_on_failure=True)
            rows.append({"hoil_venner": hoil, "Hc_ratio": r.scalars["Hc_ratio"],
                         "rho_c_Hc_over_hoil": r.scalars["rho_c_Hc_over_hoil"], "rho_c": r.scalars["rho_c"],
                         "meniscus_x": r.scalars["meniscus_x"]})
        except ConvergenceError as exc:
            rows.append({"hoil_venner": hoil, "status": "failed", "message": str(exc).split("\n")[0]})
        print("limit", rows[-1], flush=True)
    return rows


def estimate_check(cases: list[tuple[float, float, float]], points: int = 513, fine: int = 2049) -> list[dict]:
    """Estimated errors on ``points`` against the change to a grid four times finer (the true
    error is at least close to that change when the estimate is honest)."""
    rows = []
    for M, L, frac in cases:
        pb = LineProblem.from_moes(M, L)
        F_ff = solve_starved_line(pb, math.inf, points=points, estimate=False).scalars["flux_flooded"]
        hoil = frac * F_ff
        a = solve_starved_line(pb, hoil, points=points)
        b = solve_starved_line(pb, hoil, points=fine, estimate=False)
        row = {"M": M, "L": L, "fraction_of_flooded_flux": frac, "hoil_venner": hoil, "points": points,
               "fine_points": fine}
        for k in ("Hc", "Hm"):
            row[f"{k}_error_estimated"] = float(getattr(a, f"{k}_error"))
            row[f"{k}_change_to_fine"] = abs(a.scalars[f"{k}_venner"] / b.scalars[f"{k}_venner"] - 1.0)
            row[f"{k}_within"] = bool(row[f"{k}_change_to_fine"] <= row[f"{k}_error_estimated"])
        rows.append(row)
        print("estimate", row, flush=True)
    return rows


def plot(data: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(2, 2, figsize=(11, 8.5))
    a = ax[0, 0]
    rr = np.logspace(-1.3, 0.7, 200)
    a.plot(rr, chevalier_reduction(rr, DELTA_MIXED), "k--", label=f"Chevalier, delta = {DELTA_MIXED}")
    d = data["best_delta"]["delta"]
    a.plot(rr, chevalier_reduction(rr, d), "k:", label=f"Chevalier, best delta = {d:.1f}")
    for (M, L), mk in zip(CASES, "osd^", strict=False):
        rows = [x for x in data["map"] if x.get("M") == M and x.get("L") == L and "r" in x]
        a.plot([x["r"] for x in rows], [x["Hc_ratio"] for x in rows], mk, mfc="none", ms=5 + 2 * CASES.index((M, L)),
               label=f"solver M={M:g}, L={L:g}")
    a.set_xscale("log")
    a.set_xlabel("r = Hoil/(Hc_ff rho_bar(pmax))")
    a.set_ylabel("Hc/Hc_ff")
    a.legend(fontsize=7)
    a.set_title("film reduction: line solver vs fit")
    a = ax[0, 1]
    rows = [x for x in data["starved_limit"] if "rho_c_Hc_over_hoil" in x]
    a.semilogx([x["Hc_ratio"] for x in rows], [x["rho_c_Hc_over_hoil"] - 1.0 for x in rows], "o-")
    a.set_xlabel("Hc/Hc_ff")
    a.set_ylabel("rho_c Hc/Hoil - 1")
    a.set_title("starved limit (M=20, L=10)")
    a = ax[1, 0]
    f = data["fields"]
    a.plot(f["X"], f["P"], label="P")
    a.plot(f["X"], np.array(f["H"]) / f["Hc"], label="H/Hc")
    a.plot(f["X"], f["theta"], label="theta")
    a.plot(f["X_up"], f["theta_up"], "C2")
    a.axvline(f["meniscus_x"], color="grey", lw=0.5)
    a.set_xlim(-2.0, 1.5)
    a.set_ylim(0, 2.5)
    a.set_xlabel("X")
    a.legend(fontsize=8)
    a.set_title(f"M=20, L=10, Hoil={f['hoil']:g} ({f['points']} points)")
    a = ax[1, 1]
    g = data["grid"]["rows"]
    n = np.array([x["points"] for x in g])
    for key in ("Hc_venner", "Hm_venner"):
        v = np.array([x[key] for x in g])
        ext = data["grid"][key]["extrapolated"]
        if math.isfinite(ext):
            a.loglog(n, np.abs(v / ext - 1.0), "o-", label=f"{key} vs Richardson")
    a.set_xticks(n, [str(v) for v in n], minor=False)
    a.minorticks_off()
    a.set_xlabel("points")
    a.set_ylabel("relative difference")
    a.legend(fontsize=8)
    a.set_title("grid convergence at fixed supply")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(quick: bool) -> None:
    OUT.mkdir(exist_ok=True)
    t0 = time.perf_counter()
    pts = 257 if quick else 513
    data: dict = {"quick": quick, "points": pts, "delta_mixed": DELTA_MIXED}
    data["flooded_limit"] = [flooded_limit(n) for n in ((513,) if quick else (513, 1025))]
    print("flooded", data["flooded_limit"], flush=True)
    data["map"] = reduction_map(pts, CASES[:2] if quick else CASES, FRACTIONS)
    data["best_delta"] = best_delta(data["map"])
    ok = [x for x in data["map"] if "mass_balance_error" in x]
    data["mass_balance_max"] = max(x["mass_balance_error"] for x in ok)
    data["outlet_layer_max_rel_dev"] = max(abs(x["outlet_layer_venner"] / x["hoil_venner"] - 1.0) for x in ok)
    data["starved_limit"] = starved_limit(pts)
    data["coupled"] = coupled_check(257 if quick else 513)
    data["grid"] = grid_convergence([257, 513, 1025] if quick else [257, 513, 1025, 2049, 4097], 0.05)
    pb = LineProblem.from_moes(20.0, 10.0)
    r = solve_starved_line(pb, 0.05, points=1025, estimate=False)
    up = r.extra["upstream"]
    data["fields"] = {"X": r.X.tolist(), "P": r.P.tolist(), "H": r.H.tolist(), "theta": r.extra["theta"].tolist(),
                      "X_up": up["X"].tolist(), "theta_up": up["theta"].tolist(), "Hc": r.scalars["Hc_venner"],
                      "meniscus_x": r.scalars["meniscus_x"], "hoil": 0.05, "points": 1025}
    data["wall_s"] = time.perf_counter() - t0
    name = "starved_line_quick" if quick else "starved_line"
    (OUT / f"{name}.json").write_text(json.dumps(data, indent=1, default=float))
    plot(data, OUT / f"{name}.png")
    print(f"wrote {OUT / name}.json/.png in {data['wall_s']:.0f} s")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="coarser grids, two (M, L)")
    ap.add_argument("--replot", action="store_true", help="only redraw the PNG from the JSON")
    ap.add_argument("--estimate-check", action="store_true",
                    help="only the estimate honesty check (build/validation/starved/estimate_check.json)")
    a = ap.parse_args()
    if a.estimate_check:
        OUT.mkdir(exist_ok=True)
        rows = estimate_check([(100.0, 10.0, 0.6), (5.0, 5.0, 0.8), (50.0, 5.0, 0.6), (20.0, 10.0, 0.25)])
        (OUT / "estimate_check.json").write_text(json.dumps(rows, indent=1))
    elif a.replot:
        stem = OUT / ("starved_line_quick" if a.quick else "starved_line")
        plot(json.loads(stem.with_suffix(".json").read_text()), stem.with_suffix(".png"))
    else:
        main(a.quick)
