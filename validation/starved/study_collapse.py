"""Does one flooded-inlet parameter collapse the starved point contact's film reduction?

Damiens et al. (2004, J. Tribol. 126, 105-111) report that for a uniform supply layer a single
parameter, characteristic of the inlet length of the fully flooded contact, determines the
starved film decay of circular contacts; the thesis (section 6.2.1) quotes Chevalier et al.
(1998): the exponent ``delta`` of the reduction (6.1) lies between 2 and 5. The formula of that
parameter was not reachable here, so this study tests the collapse itself with the inlet length
the flooded solution implies: in Venner units (``H = h R/a^2``, ``X = x/a``) the Hertzian gap
outside the contact grows as ``(X - 1)^(3/2)``, so the distance over which the gap closes to
a multiple of the flooded central film scales as ``Hc_ff^(2/3)``: contacts with the same
``Hc_ff`` (Venner) have the same flooded inlet length whatever their (M, L).

For each (M, L) the 11-supply reduction map of ``study_point.run_case`` (first-order wedge,
half domain, 129^2: delta changes by 0.006 from 129^2 to 257^2 at (20, 10)) gives the
least-squares ``delta`` of Chevalier's reduction. Pairs of (M, L) with different L are chosen
(by a root search on the flooded solve) to share ``Hc_ff``: if the inlet length is the
parameter, their ``delta`` agree; the spread at equal ``Hc_ff`` is set against the spread over
the map and against the spread at equal M.

    python validation/starved/study_collapse.py [--quick]

Writes ``build/validation/starved/starved_collapse.json`` and ``build/validation/starved/starved_collapse.png`` (``_quick`` with
``--quick``); resumes from the JSON of an interrupted run with the same plan.
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

sys.path.insert(0, str(Path(__file__).resolve().parent))
from study_point import RATIOS, fit_delta, resumable, run_case  # noqa: E402

from ehl_multigrid.point.problem import problem_from_moes  # noqa: E402
from ehl_multigrid.point.solve import solve_fas  # noqa: E402
from ehl_multigrid.starved.point import STARVED_TOL  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("starved")
POINTS = 129
#: (M, L) of the earlier map (study_point.py), the last the chapter-6 0.5 GPa scene
BASE = [(20.0, 10.0), (100.0, 10.0), (100.0, 5.0), (179.0, 4.17)]
#: for each base case's Hc_ff: the loads found at these L that give the same flooded film
MATCH_L = (2.0, 20.0)


def flooded_hc(M: float, L: float) -> float:
    """Flooded central film (Venner units) of the first-order discretisation the starved
    solver uses, on the study's grid."""
    kw = dict(points=POINTS, half=True, raise_on_failure=False, tol=STARVED_TOL, max_cycles=40)
    s = solve_fas(problem_from_moes(M, L), wedge_order=1, **kw)
    if s.status_name != "converged":
        raise RuntimeError(f"flooded solve (M, L) = ({M:g}, {L:g}) did not converge: {s.status_name}")
    return float(s.scalars["Hc_venner"])


def matching_load(target: float, L: float) -> tuple[float | None, str]:
    """M at which the flooded Hc (Venner) equals ``target`` for this L, searched from M = 20
    outwards by factors of 2 up to 4..4000 (None and the reason when no converged bracket)."""
    def f(m: float) -> float:
        return math.log(flooded_hc(m, L) / target)

    m, fm = 20.0, None
    try:
        fm = f(m)
        step = 2.0 if fm > 0 else 0.5  # Hc_ff (Venner) falls as M rises
        while True:
            m2 = m * step
            if not 4.0 <= m2 <= 4000.0:
                return None, f"Hc_ff = {target:.4g} at L = {L:g} needs M outside 4..4000"
            f2 = f(m2)
            if f2 * fm <= 0:
                lo, hi = sorted((m, m2))
                break
            m, fm = m2, f2
    except RuntimeError as exc:
        return None, str(exc)
    root = scipy.optimize.brentq(lambda lm: f(math.exp(lm)), math.log(lo), math.log(hi), xtol=1e-3)
    return float(math.exp(root)), ""


def spread(values: list[float]) -> float:
    return float(max(values) - min(values)) if len(values) > 1 else 0.0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="one base case and one match")
    a = ap.parse_args()
    OUT.mkdir(exist_ok=True)
    tag = "_quick" if a.quick else ""
    path = OUT / f"starved_collapse{tag}.json"
    base = BASE[:1] if a.quick else BASE
    match_l = MATCH_L[:1] if a.quick else MATCH_L
    plan_key = {"base": base, "match_l": list(match_l), "points": POINTS, "ratios": RATIOS}
    data, save = resumable(path, plan_key)
    done = {(c["M"], c["L"]) for c in data["cases"]}
    t0 = time.perf_counter()

    todo: list[tuple[float, float, str]] = [(M, L, f"base {i}") for i, (M, L) in enumerate(base)]
    for i, (M, L) in enumerate(base):
        target = flooded_hc(M, L)
        for Lm in match_l:
            key = f"match {i} L {Lm:g}"
            known = [c for c in data["cases"] if c["group"] == key]
            if known:
                continue
            Mm, why = matching_load(target, Lm)
            if Mm is None:
                data.setdefault("no_match", {})[key] = why
                save()
                continue
            todo.append((round(Mm, 3), Lm, key))
    for M, L, group in todo:
        if (M, L) in done:
            continue
        c = run_case(M, L, POINTS, RATIOS)
        c["group"] = group
        c["fit"] = fit_delta(c["runs"])
        c["all_converged"] = all(r["status"] == "converged" for r in c["runs"])
        data["cases"].append(c)
        done.add((M, L))
        save()
    # groups sharing Hc_ff: a base case and its matches
    groups = []
    for i, (M, L) in enumerate(base):
        members = [c for c in data["cases"]
                   if c["group"] == f"base {i}" or c["group"].startswith(f"match {i} ")]
        groups.append({"base": [M, L], "Hc_ff": [c["Hc_ff"] for c in members],
                       "M": [c["M"] for c in members], "L": [c["L"] for c in members],
                       "delta": [c["fit"]["delta"] for c in members],
                       "delta_spread": spread([c["fit"]["delta"] for c in members])})
    deltas = [c["fit"]["delta"] for c in data["cases"]]
    hcs = np.array([c["Hc_ff"] for c in data["cases"]])
    # one curve delta(log Hc_ff): how far the cases lie from a straight-line fit
    if len(deltas) >= 3:
        coef = np.polyfit(np.log10(hcs), deltas, 1)
        resid = np.array(deltas) - np.polyval(coef, np.log10(hcs))
        line = {"slope_per_decade": float(coef[0]), "intercept": float(coef[1]),
                "max_abs_residual": float(np.max(np.abs(resid))), "rms_residual": float(np.sqrt(np.mean(resid ** 2)))}
    else:
        line = None
    data["summary"] = {"groups": groups, "delta_range": [min(deltas), max(deltas)],
                       "delta_spread_all": spread(deltas),
                       "largest_spread_at_equal_Hc_ff": max((g["delta_spread"] for g in groups), default=0.0),
                       "delta_vs_log10_Hc_ff": line, "wall_s": data.get("wall_s", 0.0) + time.perf_counter() - t0}
    data["wall_s"] = data["summary"]["wall_s"]
    save()
    plot(data, OUT / f"starved_collapse{tag}.png")
    print(json.dumps(data["summary"], indent=1))


def plot(data: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for c in data["cases"]:
        lab = f"({c['M']:.3g}, {c['L']:g})"
        ax[0].semilogx(c["Hc_ff"], c["fit"]["delta"], "o")
        ax[0].annotate(lab, (c["Hc_ff"], c["fit"]["delta"]), fontsize=7)
        ax[1].semilogx(c["M"], c["fit"]["delta"], "o")
        ax[1].annotate(lab, (c["M"], c["fit"]["delta"]), fontsize=7)
    ax[0].set_xlabel("flooded Hc (Venner, h R/a^2)")
    ax[1].set_xlabel("M")
    for x in ax:
        x.set_ylabel("least-squares delta of (6.1)")
        x.grid(True, which="both", alpha=0.3)
    fig.suptitle(f"Starved circular contacts, {POINTS}^2: does the flooded inlet collapse delta?")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    main()
