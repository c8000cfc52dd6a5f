"""Validation of the starved, mass-conserving point (circular) contact (ehl_multigrid.starved.point).

Run: ``python validation/starved/study_point.py [--quick]``. Writes build/validation/starved/starved_point.json and
build/validation/starved/starved_point.png. Every number in the point section of REPORT.md comes from the JSON.

Checks, each against something independent of the starved solver:

* flooded limit: ``Hoil = inf`` and a thick layer against the core flooded point solver on the
  same grid (first-order wedge, as the starved solver) and the core's default second-order
  solve; the core's own grid change 129 -> 257 sets the scale of its error;
* mass conservation: relative imbalance of the boundary flows (inlet face, outlet face, side);
* the starved limit: ``rho_c Hc/Hoil`` (1 when the central film carries the supply);
* film reduction ``Hc/Hc_ff`` against Chevalier's reduction (6.1), ``r = Hoil/(Hc_ff rho_c,ff)``,
  with the mixed layer's ``delta = 3.5`` and the least-squares ``delta`` of the point solver;
* grid change 129 -> 257 and cost; the convergence status of every solve.

Half domain (Y >= 0), Roelands + Dowson-Higginson, the point core's default box.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
import scipy.optimize

from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.point.solve import solve_fas
from ehl_multigrid.starved.point import STARVED_TOL, solve_starved_point
from mixed.starvation import chevalier_reduction

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("starved")
#: supplied layer as multiples of the flooded central film
RATIOS = [4.0, 2.0, 1.5, 1.2, 1.0, 0.8, 0.6, 0.4, 0.25, 0.1, 0.03]
DELTA_MIXED = 3.5


def run_case(M: float, L: float, points: int, ratios: list[float], theta: float = 1.0) -> dict:
    pb = problem_from_moes(M, L, theta)
    kw = dict(points=points, half=True, raise_on_failure=False, tol=STARVED_TOL, max_cycles=40)
    t0 = time.perf_counter()
    ff1 = solve_fas(pb, wedge_order=1, **kw)
    t_ff = time.perf_counter() - t0
    ff2 = solve_fas(pb, points=points, half=True, raise_on_failure=False)
    Hff = ff1.scalars["Hc_venner"]
    Hmff = ff1.scalars["Hm_venner"]
    i0 = int(np.argmin(np.abs(ff1.X)))
    from ehl_multigrid.multigrid.rheology import density  # noqa: PLC0415 (study only)
    rho_c = float(density(float(ff1.P[0, i0]), ff1.problem.rheology())[0])
    out = {"M": M, "L": L, "theta": theta, "points": points, "Hc_ff": Hff, "Hm_ff": Hmff, "rho_c_ff": rho_c,
           "Hc_ff_order2": ff2.scalars["Hc_venner"], "Hm_ff_order2": ff2.scalars["Hm_venner"],
           "flooded_status": ff1.status_name, "flooded_wall_s": t_ff, "runs": []}
    # the starved solves with the solver's own tolerance rules (STARVED_TOL, MASS_TOL, STARVED_MAX_CYCLES)
    skw = {k: v for k, v in kw.items() if k not in ("max_cycles", "tol")}
    for ratio in [math.inf] + ratios:
        hoil = math.inf if math.isinf(ratio) else ratio * Hff
        t0 = time.perf_counter()
        s = solve_starved_point(pb, hoil, **skw)
        wall = time.perf_counter() - t0
        e = s.extra
        Hc, Hm = s.scalars["Hc_venner"], s.scalars["Hm_venner"]
        rec = {"hoil_over_Hc_ff": ratio, "hoil": hoil, "status": s.status_name,
               "cycles": len(s.residual_history), "final_residual": float(s.residual_history[-1]) if len(s.residual_history) else math.nan,
               "Hc": Hc, "Hm": Hm, "Hc_ratio": Hc / Hff, "Hm_ratio": Hm / Hmff,
               "meniscus_x": e["meniscus_x"], "mass_balance_error": e["mass_balance_error"],
               "fluxes": e["fluxes"], "rho_c": e["rho_c"], "wall_s": wall,
               "second_rule": [a for a in s.actions if "theta frozen on every coarse grid" in a]}
        if math.isfinite(hoil):
            rec["r"] = hoil / (Hff * rho_c)
            rec["rho_c_Hc_over_hoil"] = e["rho_c"] * Hc / hoil
            rec["outlet_over_supply"] = (e["fluxes"]["out"] / e["fluxes"]["in"] if e["fluxes"]["in"]
                                         else math.nan)  # a failed solve carries no flux
            rec["chevalier_3p5"] = float(chevalier_reduction(rec["r"], DELTA_MIXED))
        out["runs"].append(rec)
        print(f"M {M:g} L {L:g} theta {theta:g} n {points} Hoil/Hcff {ratio:g}: {s.status_name} Hc/Hcff "
              f"{Hc / Hff:.5f} mb {e['mass_balance_error']:.2e} cycles {rec['cycles']} "
              f"{wall:.1f} s", flush=True)
    return out


def resumable(path: Path, plan: dict) -> tuple[dict, Callable[[], None]]:
    """The study record at ``path`` when it was made for the same ``plan`` (an interrupted run
    resumes), else a fresh one; and the function that saves it atomically (temporary + rename)."""
    data: dict = {"plan": plan, "cases": []}
    if path.exists():
        prev = json.loads(path.read_text())
        if prev.get("plan") == json.loads(json.dumps(plan)):
            data = prev

    def save() -> None:
        tmp = path.with_suffix(".json.tmp")
        tmp.write_text(json.dumps(data, indent=1, default=float))
        tmp.replace(path)

    return data, save


def fit_delta(runs: list[dict]) -> dict:
    pts = [(r["r"], r["Hc_ratio"]) for r in runs if "r" in r and r["status"] == "converged"]
    rr = np.array([p[0] for p in pts])
    hh = np.array([p[1] for p in pts])

    def misfit(d: float) -> float:
        return float(np.sum(np.log(chevalier_reduction(rr, d) / hh) ** 2))

    res = scipy.optimize.minimize_scalar(misfit, bounds=(0.5, 20.0), method="bounded")
    d = float(res.x)
    return {"delta": d, "rms_log_misfit": math.sqrt(misfit(d) / len(rr)),
            "rms_log_misfit_3p5": math.sqrt(misfit(DELTA_MIXED) / len(rr)),
            "max_rel_dev": float(np.max(np.abs(chevalier_reduction(rr, d) / hh - 1.0))),
            "max_rel_dev_3p5": float(np.max(np.abs(chevalier_reduction(rr, DELTA_MIXED) / hh - 1.0))),
            "n": len(rr)}


def plot(data: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    rgrid = np.logspace(-2, 1, 200)
    for c in data["cases"]:
        ok = [r for r in c["runs"] if "r" in r]
        conv = [r for r in ok if r["status"] == "converged"]
        bad = [r for r in ok if r["status"] != "converged"]
        lab = f"M={c['M']:g}, L={c['L']:g}, {c['points']}^2"
        ax[0].loglog([r["r"] for r in conv], [r["Hc_ratio"] for r in conv], "o", label=lab)
        if bad:
            ax[0].loglog([r["r"] for r in bad], [r["Hc_ratio"] for r in bad], "x", color="k")
        ax[1].loglog([r["r"] for r in ok], [max(r["mass_balance_error"], 1e-16) for r in ok], "o", label=lab)
        ax[2].semilogx([r["r"] for r in ok], [r["rho_c_Hc_over_hoil"] for r in ok], "o", label=lab)
    ax[0].loglog(rgrid, chevalier_reduction(rgrid, DELTA_MIXED), "k-", label="Chevalier delta 3.5")
    d = data["fit"]["delta"]
    ax[0].loglog(rgrid, chevalier_reduction(rgrid, d), "k--", label=f"Chevalier delta {d:.2f} (fit)")
    ax[0].set_xlabel("r = Hoil/(Hc_ff rho_c)")
    ax[0].set_ylabel("Hc/Hc_ff")
    ax[0].legend(fontsize=7)
    ax[0].set_title("film reduction (x: not converged)")
    ax[1].set_xlabel("r")
    ax[1].set_ylabel("relative mass imbalance")
    ax[1].set_title("mass conservation")
    ax[2].set_xlabel("r")
    ax[2].set_ylabel("rho_c Hc / Hoil")
    ax[2].axhline(1.0, color="k", lw=0.5)
    ax[2].set_title("starved limit")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_fields(M: float, L: float, points: int, ratio: float, path: Path) -> dict:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pb = problem_from_moes(M, L)
    ff = solve_fas(pb, points=points, half=True, wedge_order=1, raise_on_failure=False, tol=STARVED_TOL)
    hoil = ratio * ff.scalars["Hc_venner"]
    s = solve_starved_point(pb, hoil, points=points, half=True, raise_on_failure=False)
    th = s.extra["theta"]
    X, Y = s.X, s.Y
    fig, ax = plt.subplots(1, 3, figsize=(15, 4))
    ax[0].plot(X, s.P[0], label="P starved")
    ax[0].plot(X, ff.P[0], "--", label="P flooded")
    ax[0].plot(X, th[0], label="theta")
    ax[0].set_xlim(-2.5, 1.5)
    ax[0].legend(fontsize=8)
    ax[0].set_title(f"centre line, Hoil = {ratio:g} Hc_ff")
    ax[1].plot(X, s.H[0], label="H starved")
    ax[1].plot(X, ff.H[0], "--", label="H flooded")
    ax[1].set_xlim(-2.5, 1.5)
    ax[1].set_ylim(0, 3 * ff.scalars["Hc_venner"])
    ax[1].legend(fontsize=8)
    Yf = np.concatenate([-Y[:0:-1], Y])
    thf = np.vstack([th[:0:-1], th])
    cs = ax[2].contourf(X, Yf, thf, levels=np.linspace(0, 1, 11))
    fig.colorbar(cs, ax=ax[2])
    ax[2].set_aspect("equal")
    ax[2].set_title("film content theta (meniscus: theta -> 1)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return {"hoil_over_Hc_ff": ratio, "status": s.status_name, "meniscus_x": s.extra["meniscus_x"]}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    OUT.mkdir(exist_ok=True)
    t0 = time.perf_counter()
    if args.quick:
        plan = [(20.0, 10.0, 129)]
    else:
        plan = [(20.0, 10.0, 129), (20.0, 10.0, 257), (100.0, 10.0, 257), (100.0, 5.0, 257),
                (179.0, 4.17, 257)]  # the last: the chapter-6 0.5 GPa scene's (M, L)
    cases = [run_case(M, L, n, RATIOS) for M, L, n in plan]
    runs = [r for c in cases for r in c["runs"]]
    data = {"tol": STARVED_TOL, "delta_mixed": DELTA_MIXED, "cases": cases, "fit": fit_delta(runs)}
    for c in cases:
        c["fit"] = fit_delta(c["runs"])
    tag = "_quick" if args.quick else ""
    data["fields"] = plot_fields(20.0, 10.0, 129, 0.4, OUT / f"starved_point_fields{tag}.png")
    data["wall_s"] = time.perf_counter() - t0
    (OUT / f"starved_point{tag}.json").write_text(json.dumps(data, indent=1, default=float))
    plot(data, OUT / f"starved_point{tag}.png")
    print(json.dumps(data["fit"], indent=1), f"wall {data['wall_s']:.0f} s")


if __name__ == "__main__":
    main()
