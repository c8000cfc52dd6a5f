"""The extremes matrix: every solver over the corners of its range.

Each case ends as exactly one of
  converged  - the solver says converged and the answer passes the sanity checks;
  failed     - the solver raised a clear error (InputError / ConvergenceError) or returned
               converged=False (it said so);
  wrong      - NaN, negative film, P < 0, friction outside its bounds, or a result marked
               converged that fails its own convergence criteria. Must be zero.

Usage: python validation/extremes/extremes.py [--quick] [--models line,point,thermal,mixed]
Writes build/validation/extremes/extremes[_quick].json (resumes: finished cases are kept).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
import traceback
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

from ehl_multigrid.model.errors import ConvergenceError, InputError
from ehl_multigrid.model.scene import load_scene

HERE = Path(__file__).resolve().parent

Case = dict[str, Any]


# -- EHL line and point ----------------------------------------------------------------------------
def ehl_cases(contact: str, quick: bool) -> Iterator[Case]:
    Ms = [1.0, 20.0, 1000.0, 5000.0] if not quick else [1.0, 5000.0]
    Ls = [0.0, 10.0, 25.0] if not quick else [0.0, 25.0]
    thetas = [1.0] if contact == "line" else ([0.1, 1.0, 10.0] if not quick else [1.0])
    for M in Ms:
        for L in Ls:
            for th in thetas:
                yield {"model": f"{contact}_ehl", "M": M, "L": L, "theta": th}


def ehl_points(contact: str, M: float, theta: float = 1.0) -> int:
    """Grid per case: the line solver's 1025 points (4097 from M = 2000) and the point
    solver's own minimum grid (129, 257 from M = 200, 513 from M = 1000; more when b < a)."""
    if contact == "line":
        return 1025 if M < 2000 else 4097
    from ehl_multigrid.point.problem import hertz_shape, min_points

    return max(129, min_points(M, hertz_shape(theta)[2]))


def run_ehl(case: Case, points: int | None = None) -> tuple[str, dict[str, Any]]:
    contact = "line" if case["model"] == "line_ehl" else "point"
    n = points or ehl_points(contact, case["M"], case.get("theta", 1.0))
    if contact == "line":
        from ehl_multigrid.line import solve_line

        sol = solve_line(case["M"], case["L"], points=n)
    else:
        from ehl_multigrid.point import solve_point

        sol = solve_point(case["M"], case["L"], theta=case["theta"], points=n)
    s = dict(sol.scalars)
    out = {k: s.get(k) for k in ("Hc", "Hm", "load_error", "residual", "converged", "points", "wall_s")}
    out["message"] = sol.report.message
    P = np.asarray(sol.P)
    checks = {
        "finite": bool(np.all(np.isfinite(P)) and np.all(np.isfinite(sol.H)) and math.isfinite(s["Hc"])),
        "P_nonnegative": bool(P.min() >= 0.0),
        "film_positive": bool(s["Hm"] > 0),
    }
    if sol.converged:  # a result marked converged must meet its own tolerances
        tol = sol.report.tolerances
        checks["load_error_within_tol"] = abs(s["load_error"]) <= tol.get("load", math.inf) * (1 + 1e-9)
        res_hist = sol.report.residual_history
        if len(res_hist) and "residual" in tol:
            checks["residual_within_tol"] = float(res_hist[-1]) <= tol["residual"] * (1 + 1e-9)
    return classify(sol.converged, checks), {**out, "checks": checks}


# -- thermal ---------------------------------------------------------------------------------------
def thermal_cases(quick: bool) -> Iterator[Case]:
    slips = [0.0, 0.05, 1.0, 2.0] if not quick else [0.05, 2.0]
    speeds = [0.01, 1.0, 50.0] if not quick else [0.01, 50.0]
    pmaxs = [0.3e9, 1.0e9, 3.0e9] if not quick else [0.3e9, 3.0e9]
    for scene in ("appendix_c_line_4240N", "appendix_d_point"):
        for s in slips:
            for u in speeds:
                for p in pmaxs:
                    yield {"model": "thermal", "scene": scene, "slip": s, "us": u, "pmax": p}


def run_thermal(case: Case) -> tuple[str, dict[str, Any]]:
    from thermal.traction import solve_traction

    sc = load_scene(case["scene"]).with_operating(pmax=case["pmax"], us=case["us"], slip=case["slip"])
    th = solve_traction(sc)
    iso = solve_traction(sc, thermal=False)
    f, fi = th.coefficient, iso.coefficient
    checks = {
        "finite": math.isfinite(f) and math.isfinite(th.max_temperature_rise),
        "sign_follows_slip": (f == 0.0) if case["slip"] == 0 else (np.sign(f) == np.sign(case["slip"])),
        # heating only lowers viscosity, so thermal friction cannot exceed the isothermal one
        "thermal_below_isothermal": abs(f) <= abs(fi) * (1 + 1e-3) + 1e-12,
        "no_cooling_below_inlet": th.max_temperature_rise >= -1e-6,
    }
    out = {"f": f, "f_isothermal": fi, "dT_max": th.max_temperature_rise, "converged": th.converged, "checks": checks}
    return classify(th.converged and iso.converged, checks), out


# -- mixed -----------------------------------------------------------------------------------------
def mixed_cases(quick: bool) -> Iterator[Case]:
    speeds = [1e-5, 1e-2, 1.0, 100.0] if not quick else [1e-5, 100.0]
    hoils = [0.01, 1.0, math.inf] if not quick else [0.01, math.inf]
    sigmas = [1e-9, 1e-7, 1e-6] if not quick else [1e-9, 1e-6]
    for scene in ("page63_line_2000N", "series_D_disc3_1.93GPa"):
        for u in speeds:
            for h in hoils:
                for s in sigmas:
                    yield {"model": "mixed", "scene": scene, "us": u, "hoil_over_sigma": h, "sigma_s": s}


def run_mixed(case: Case) -> tuple[str, dict[str, Any]]:
    from ehl_multigrid.model.scene import Scene
    from mixed.tasks import stribeck_point_task

    d = load_scene(case["scene"]).to_dict()
    s = case["sigma_s"]
    d["roughness"].update({"sigma_s": s, "Rq": s / 0.7, "dd": 0.82 * s / 0.7})
    d["operating"]["us"] = case["us"]
    sc = Scene.from_dict(d)
    hoil = case["hoil_over_sigma"] * sc.roughness.Rq
    r = stribeck_point_task(sc, hoil=None if math.isinf(hoil) else hoil)
    fc = sc.roughness.fc
    checks = {
        "finite": all(math.isfinite(r[k]) for k in ("friction_coefficient", "Pa", "hfr")),
        "friction_in_0_fc": -1e-12 <= r["friction_coefficient"] <= fc + 1e-12,
        "loads_add_up": abs(r["Pa"] + (r["Ph"] if math.isfinite(r["Ph"]) else 0.0) - sc.load) <= 1e-6 * sc.load,
        "gamma1_at_least_1": r["gamma1"] >= 1.0 - 1e-12,
    }
    return classify(r["converged"], checks), {**r, "checks": checks}


# -- driver ------------------------------------------------------------------------------------------
def classify(converged: bool, checks: dict[str, bool]) -> str:
    """wrong if any sanity check (finite values included) fails on a result that claims
    convergence; a result that does not claim it is failed, whatever its values (a returned
    failure carries NaN films)."""
    if converged:
        return "converged" if all(checks.values()) else "wrong"
    return "failed"


MODELS: dict[str, tuple[Callable[[bool], Iterator[Case]], Callable[[Case], tuple[str, dict]]]] = {
    "line": (lambda q: ehl_cases("line", q), run_ehl),
    "point": (lambda q: ehl_cases("point", q), run_ehl),
    "thermal": (thermal_cases, run_thermal),
    "mixed": (mixed_cases, run_mixed),
}


def case_key(case: Case) -> str:
    return json.dumps(case, sort_keys=True, default=str)


def run(models: list[str], quick: bool, progress: bool = True) -> dict[str, Any]:
    # the folder is made here, not at import: tests import this module for its runners
    sys.path.insert(0, str(HERE.parent))
    from _paths import out_dir

    path = out_dir("extremes") / f"extremes{'_quick' if quick else ''}.json"
    done: dict[str, Any] = json.loads(path.read_text())["cases"] if path.exists() else {}
    cases = [c for m in models for c in MODELS[m][0](quick)]
    it = cases
    if progress:
        from tqdm import tqdm

        it = tqdm(cases, desc="extremes", unit="case")
    for case in it:
        key = case_key(case)
        if key in done:
            continue
        runner = MODELS[case["model"].replace("_ehl", "")][1]
        t0 = time.perf_counter()
        try:
            verdict, info = runner(case)
        except (InputError, ConvergenceError) as exc:
            verdict, info = "failed", {"error": f"{type(exc).__name__}: {str(exc).splitlines()[0]}"}
        except Exception as exc:  # an unexpected exception is a bug: count it as wrong
            verdict, info = "wrong", {"error": f"{type(exc).__name__}: {exc}", "traceback": traceback.format_exc()}
        done[key] = {"case": case, "verdict": verdict, "wall_s": time.perf_counter() - t0, **info}
        _save(path, done)
    return _save(path, done)


def _save(path: Path, done: dict[str, Any]) -> dict[str, Any]:
    counts: dict[str, dict[str, int]] = {}
    for rec in done.values():
        m = rec["case"]["model"]
        counts.setdefault(m, {"converged": 0, "failed": 0, "wrong": 0})[rec["verdict"]] += 1
    payload = {"counts": counts, "cases": done}
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(payload, indent=1, default=lambda o: o.item() if hasattr(o, "item") else str(o)))
    tmp.replace(path)
    return payload


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--models", default="line,point,thermal,mixed")
    args = ap.parse_args()
    payload = run(args.models.split(","), args.quick)
    print(json.dumps(payload["counts"], indent=1))
    for rec in payload["cases"].values():
        if rec["verdict"] != "converged":
            print(rec["verdict"], rec["case"], rec.get("error", rec.get("checks")))


if __name__ == "__main__":
    main()
