"""Mass conservation of the starved point solver on the 55-supply map, before and after the exact
solve of the Poiseuille-dominated zone (ehl_multigrid/starved/point_mass.py).

Run: ``python validation/starved/study_mass.py [--order 1|2] [--quick]``. Writes
build/validation/starved/starved_mass_order{1,2}[_quick].json and .png. The "before" numbers are read from the
previous studies' JSON (build/validation/starved/starved_point.json for the first-order wedge, build/validation/starved/starved_order_map.json
for the second order); the supplies are the same multiples of the same flooded films
(``Hc_ff`` of those files), so each solve repeats one of theirs with the current code.

Per supply: status, cycles, relative mass imbalance (inlet face - outlet face - side faces,
``mass_balance_error``), Hc, Hm, wall, the mass re-solve's actions; the change of Hc and Hm
against the previous result, and, as the scale it must stay within, the previous result's mass
imbalance (the mass term of the solver's algebraic error estimate, ``starved_point_error``).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

from tqdm import tqdm

from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.starved.point import MASS_TOL, solve_starved_point

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir, require  # noqa: E402

OUT = out_dir("starved")
RATIOS = [4.0, 2.0, 1.5, 1.2, 1.0, 0.8, 0.6, 0.4, 0.25, 0.1, 0.03]
PLAN = [(20.0, 10.0, 129), (20.0, 10.0, 257), (100.0, 10.0, 257), (100.0, 5.0, 257), (179.0, 4.17, 257)]


def _before(order: int) -> dict:
    """The previous map's cases by (M, L, points), with ``Hc_ff`` (the supplies' unit)."""
    if order == 1:
        d = json.loads(require(OUT / "starved_point.json", "python validation/starved/study_point.py").read_text())
        return {(c["M"], c["L"], c["points"]): {"Hc_ff": c["Hc_ff"], "runs": c["runs"]} for c in d["cases"]}
    d = json.loads(require(OUT / "starved_order_map.json", "python validation/starved/study_order.py map").read_text())
    return {(c["M"], c["L"], c["points"]): {"Hc_ff": c["Hc_ff1"], "runs": c["runs"]} for c in d["cases"]}


def run(order: int, plan: list[tuple[float, float, int]]) -> dict:
    before = _before(order)
    cases = []
    jobs = [(M, L, n, r) for M, L, n in plan for r in [math.inf] + RATIOS]
    bar = tqdm(jobs, desc=f"order {order}", unit="solve")
    current = None
    for M, L, n, ratio in bar:
        if current is None or (current["M"], current["L"], current["points"]) != (M, L, n):
            b = before[(M, L, n)]
            old = {(r["hoil_over_Hc_ff"] if r["hoil_over_Hc_ff"] is not None else math.inf): r for r in b["runs"]}
            current = {"M": M, "L": L, "points": n, "Hc_ff": b["Hc_ff"], "runs": []}
            cases.append(current)
            pb = problem_from_moes(M, L)
        hoil = math.inf if math.isinf(ratio) else ratio * current["Hc_ff"]
        t0 = time.perf_counter()
        s = solve_starved_point(pb, hoil, points=n, half=True, raise_on_failure=False, wedge_order=order)
        wall = time.perf_counter() - t0
        o = old[ratio]
        Hc, Hm = float(s.scalars["Hc_venner"]), float(s.scalars["Hm_venner"])
        rec = {"hoil_over_Hc_ff": ratio, "status": s.status_name, "cycles": len(s.residual_history),
               "final_residual": float(s.residual_history[-1]), "Hc": Hc, "Hm": Hm,
               "mass_balance_error": float(s.extra["mass_balance_error"]), "wall_s": wall,
               "actions": [a for a in s.actions if "mass imbalance" in a or "coarse-grid" in a],
               "exact_kept": any("exact solve" in a and "kept the second" in a for a in s.actions),
               "before": {k: o.get(k) for k in ("status", "cycles", "Hc", "Hm", "mass_balance_error", "wall_s")},
               "dHc": Hc / o["Hc"] - 1.0, "dHm": Hm / o["Hm"] - 1.0}
        current["runs"].append(rec)
        bar.write(f"M {M:g} L {L:g} n {n} Hoil/Hcff {ratio:g}: {s.status_name} mb {rec['mass_balance_error']:.2e} "
                  f"(before {o['mass_balance_error']:.2e}) dHc {rec['dHc']:+.2e} cyc {rec['cycles']} {wall:.1f} s")
    return {"order": order, "mass_tol": MASS_TOL, "cases": cases, "summary": summarise(cases)}


def summarise(cases: list[dict]) -> dict:
    runs = [r for c in cases for r in c["runs"] if math.isfinite(r["hoil_over_Hc_ff"])]
    flooded = [r for c in cases for r in c["runs"] if not math.isfinite(r["hoil_over_Hc_ff"])]
    met_before = [r for r in runs if r["before"]["mass_balance_error"] <= MASS_TOL]
    missed_before = [r for r in runs if r["before"]["mass_balance_error"] > MASS_TOL]

    def mx(v: list[float]) -> float:
        return float(max(v)) if v else math.nan

    return {
        "supplies": len(runs),
        "converged": {"before": sum(r["before"]["status"] == "converged" for r in runs),
                      "after": sum(r["status"] == "converged" for r in runs)},
        "imbalance_below_tol": {"before": len(met_before),
                                "after": sum(r["mass_balance_error"] <= MASS_TOL for r in runs)},
        "largest_imbalance": {"before": mx([r["before"]["mass_balance_error"] for r in runs]),
                              "after": mx([r["mass_balance_error"] for r in runs])},
        "exact_resolve_kept": sum(r["exact_kept"] for r in runs),
        "met_before": {"n": len(met_before), "max_abs_dHc": mx([abs(r["dHc"]) for r in met_before]),
                       "max_abs_dHm": mx([abs(r["dHm"]) for r in met_before])},
        "missed_before": {"n": len(missed_before), "max_abs_dHc": mx([abs(r["dHc"]) for r in missed_before]),
                          "max_abs_dHm": mx([abs(r["dHm"]) for r in missed_before]),
                          "dHc_within_before_imbalance": sum(abs(r["dHc"]) <= r["before"]["mass_balance_error"]
                                                             for r in missed_before),
                          "max_dHc_over_before_imbalance": mx([abs(r["dHc"]) / r["before"]["mass_balance_error"]
                                                               for r in missed_before])},
        "cycles": {"before": [min(r["before"]["cycles"] for r in runs), max(r["before"]["cycles"] for r in runs)],
                   "after": [min(r["cycles"] for r in runs), max(r["cycles"] for r in runs)]},
        "wall_s": {"before": float(sum(r["before"]["wall_s"] for r in runs)),
                   "after": float(sum(r["wall_s"] for r in runs))},
        "flooded": {"n": len(flooded), "max_abs_dHc": mx([abs(r["dHc"]) for r in flooded]),
                    "largest_imbalance": mx([r["mass_balance_error"] for r in flooded])},
    }


def plot(data: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5))
    for c in data["cases"]:
        runs = [r for r in c["runs"] if math.isfinite(r["hoil_over_Hc_ff"])]
        x = [r["hoil_over_Hc_ff"] for r in runs]
        lab = f"({c['M']:g}, {c['L']:g}) {c['points']}^2"
        line = ax[0].loglog(x, [max(r["mass_balance_error"], 1e-13) for r in runs], "o-", label=lab)[0]
        ax[0].loglog(x, [max(r["before"]["mass_balance_error"], 1e-13) for r in runs], "x--",
                     color=line.get_color())
        ax[1].semilogx(x, [abs(r["dHc"]) for r in runs], "o-", color=line.get_color(), label=lab)
    ax[0].axhline(data["mass_tol"], color="k", lw=0.8)
    ax[0].set_xlabel("Hoil / Hc_ff")
    ax[0].set_ylabel("relative mass imbalance")
    ax[0].set_title(f"wedge order {data['order']}: after (o), before (x)")
    ax[0].legend(fontsize=7)
    ax[1].set_yscale("symlog", linthresh=1e-9)
    ax[1].set_xlabel("Hoil / Hc_ff")
    ax[1].set_ylabel("|Hc/Hc_before - 1|")
    ax[1].set_title("film change against the previous result")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--order", type=int, default=1, choices=(1, 2))
    ap.add_argument("--quick", action="store_true", help="(20, 10) at 129^2 only")
    args = ap.parse_args()
    OUT.mkdir(exist_ok=True)
    t0 = time.perf_counter()
    data = run(args.order, PLAN[:1] if args.quick else PLAN)
    data["wall_s"] = time.perf_counter() - t0
    tag = f"order{args.order}" + ("_quick" if args.quick else "")
    (OUT / f"starved_mass_{tag}.json").write_text(json.dumps(data, indent=1, default=float))
    plot(data, OUT / f"starved_mass_{tag}.png")
    print(json.dumps(data["summary"], indent=1), f"wall {data['wall_s']:.0f} s")


if __name__ == "__main__":
    main()
