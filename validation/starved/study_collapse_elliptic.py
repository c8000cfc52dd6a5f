"""Does the flooded inlet length collapse the starved film reduction of elliptic contacts?

The circular rule (docs/fits.md, "Starved films") takes Chevalier's exponent from the flooded
central film, ``delta = 2.37 - 0.95 log10(Hc_ff)`` (Venner units), because in a circular contact
the dry Hertzian gap upstream of the edge grows as ``(X - 1)^(3/2)``: the inlet length over which
it closes to the film is a function of ``Hc_ff`` alone (Damiens et al. 2004). In an elliptic
contact the gap along the centre line grows at a rate that depends on the ellipticity, and the
oil also leaves sideways. This study measures the exponent of elliptic contacts with the
mass-conserving starved point solver (the 11-supply maps of ``study_point.run_case``, half
domain, 129^2, as the circular fit) and sets it against

* the circular rule applied to ``Hc_ff`` as it is;
* the circular rule applied to the film of the circular contact with the same inlet length:
  ``Hc_eq = G_1(-1 - Lambda)``, where ``G_theta(X)`` is the dry Hertzian gap on the centre line
  (film equation of ``ehl_multigrid.point.problem`` with the Hertz pressure; zero in the
  contact) and ``Lambda`` the distance upstream of the edge where ``G_theta`` reaches ``Hc_ff``;
* the circular rule with a shift in ``log10(theta)``, fitted here.

    python validation/starved/study_collapse_elliptic.py [--quick] [--workers N]

Writes ``build/validation/starved/starved_collapse_elliptic.json`` (``_quick``); resumes from
the JSON of an interrupted run with the same plan.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

import numpy as np
import scipy.optimize

sys.path.insert(0, str(Path(__file__).resolve().parent))
from study_point import RATIOS, fit_delta, resumable, run_case  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

from ehl_multigrid.model.starvation import INLET_DELTA_FIT, INLET_HC_RANGE  # noqa: E402
from ehl_multigrid.point.problem import hertz_shape  # noqa: E402

OUT = out_dir("starved")
POINTS = 129
THETAS = (0.25, 0.5, 1.0, 2.0, 4.0)
LOADS = ((50.0, 10.0), (100.0, 10.0), (100.0, 5.0), (300.0, 5.0))


def dry_gap(theta: float, X: np.ndarray, n: int = 400) -> np.ndarray:
    """Dry Hertzian gap ``X^2/2 + cd D(X) - cd D(0)`` on the centre line ``Y = 0`` (Venner units,
    zero inside the contact), ``D`` the integral of the Hertz pressure over ``r`` by Gauss-Legendre
    quadrature in elliptic polar coordinates (``X' = rho cos phi``, ``Y' = (b/a) rho sin phi``)."""
    f, g, ba = hertz_shape(theta)
    cd = 2.0 * g / (math.pi * f)
    t, wt = np.polynomial.legendre.leggauss(n)
    s = 0.5 * (t + 1.0) * (math.pi / 2)  # rho = sin(s): P = cos(s), drho = cos(s) ds
    ws = 0.5 * wt * (math.pi / 2)
    phi = (t + 1.0) * math.pi
    wphi = wt * math.pi
    rho = np.sin(s)[:, None]
    P = np.cos(s)[:, None]
    jac = (ba * rho * np.cos(s)[:, None]) * ws[:, None] * wphi[None, :]
    xs = rho * np.cos(phi)[None, :]
    ys = ba * rho * np.sin(phi)[None, :]

    def D(x: float) -> float:
        r = np.hypot(x - xs, ys)
        return float(np.sum(P * jac / r))

    d0 = D(0.0)
    return np.array([0.5 * x * x + cd * (D(float(x)) - d0) for x in np.atleast_1d(X)])


def inlet_length(theta: float, hc: float) -> float:
    """Distance upstream of the contact edge where the dry gap reaches ``hc``."""
    return float(scipy.optimize.brentq(lambda lam: dry_gap(theta, np.array([-1.0 - lam]))[0] - hc,
                                       1e-6, 50.0, xtol=1e-9))


def circular_rule(hc: float) -> float:
    a, b = INLET_DELTA_FIT
    return a + b * math.log10(min(max(hc, INLET_HC_RANGE[0]), INLET_HC_RANGE[1]))


def one_case(M: float, L: float, theta: float) -> dict:
    c = run_case(M, L, POINTS, RATIOS, theta=theta)
    c["fit"] = fit_delta(c["runs"])
    c["all_converged"] = all(r["status"] == "converged" for r in c["runs"])
    return c


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="theta 0.5 and 2 at one load")
    ap.add_argument("--workers", type=int, default=2)
    a = ap.parse_args()
    tag = "_quick" if a.quick else ""
    path = OUT / f"starved_collapse_elliptic{tag}.json"
    thetas = (0.5, 2.0) if a.quick else THETAS
    loads = LOADS[1:2] if a.quick else LOADS
    plan = {"thetas": list(thetas), "loads": [list(x) for x in loads], "points": POINTS, "ratios": RATIOS}
    data, save = resumable(path, plan)
    done = {(c["M"], c["L"], c["theta"]) for c in data["cases"]}
    t0 = time.perf_counter()

    todo = [(M, L, th) for th in thetas for M, L in loads if (M, L, th) not in done]
    with ProcessPoolExecutor(max_workers=a.workers) as pool:
        futures = {pool.submit(one_case, *job): job for job in todo}
        for i, fut in enumerate(as_completed(futures), 1):
            c = fut.result()
            data["cases"].append(c)
            save()
            print(f"{i}/{len(todo)} (M, L, theta) = {futures[fut]}: delta {c['fit']['delta']:.3f}, "
                  f"Hc_ff {c['Hc_ff']:.4g}, all converged {c['all_converged']}", file=sys.stderr, flush=True)
    # the inlet-length mapping and the theta shift
    rows = []
    for c in sorted(data["cases"], key=lambda c: (c["theta"], c["M"], c["L"])):
        lam = inlet_length(c["theta"], c["Hc_ff"])
        hc_eq = float(dry_gap(1.0, np.array([-1.0 - lam]))[0])
        rows.append({"M": c["M"], "L": c["L"], "theta": c["theta"], "Hc_ff": c["Hc_ff"], "inlet_length": lam,
                     "Hc_eq": hc_eq, "delta": c["fit"]["delta"], "rms_log_misfit": c["fit"]["rms_log_misfit"],
                     "delta_circular_rule": circular_rule(c["Hc_ff"]),
                     "delta_equal_inlet": circular_rule(hc_eq), "all_converged": c["all_converged"]})
    d = np.array([r["delta"] for r in rows])
    lt = np.log10([r["theta"] for r in rows])
    base = np.array([r["delta_circular_rule"] for r in rows])
    # delta = circular rule + s log10(theta) + q log10(theta)^2: least squares
    A = np.column_stack([lt, lt ** 2])
    coef, *_ = np.linalg.lstsq(A, d - base, rcond=None)
    shifted = base + A @ coef
    s1, *_ = np.linalg.lstsq(lt[:, None], d - base, rcond=None)

    def stats(pred: np.ndarray) -> dict:
        e = d - pred
        return {"rms": float(np.sqrt(np.mean(e ** 2))), "max_abs": float(np.max(np.abs(e)))}

    data["rows"] = rows
    data["summary"] = {
        "circular_rule": stats(base),
        "equal_inlet_length": stats(np.array([r["delta_equal_inlet"] for r in rows])),
        "shift_linear_in_log10_theta": {"s": float(s1[0]), **stats(base + lt * s1[0])},
        "shift_quadratic_in_log10_theta": {"s": float(coef[0]), "q": float(coef[1]), **stats(shifted)},
        "edge_gap_check": {str(th): float(dry_gap(th, np.array([-1.0]))[0]) for th in thetas},
        "wall_s": data.get("wall_s", 0.0) + time.perf_counter() - t0,
    }
    data["wall_s"] = data["summary"]["wall_s"]
    save()
    for r in rows:
        print(f"theta {r['theta']:5.2f} (M, L) ({r['M']:g}, {r['L']:g}): Hc_ff {r['Hc_ff']:.4f}, inlet "
              f"{r['inlet_length']:.3f}, Hc_eq {r['Hc_eq']:.4f}; delta {r['delta']:.3f} against circular rule "
              f"{r['delta_circular_rule']:.3f}, equal inlet {r['delta_equal_inlet']:.3f}")
    print(json.dumps(data["summary"], indent=1))


if __name__ == "__main__":
    main()
