"""The EHL extremes matrix at an accuracy target: does every corner either meet the target or
fail with a clear reason, and is no "converged" answer wrong?

Each line and point case (M 1-5000, L 0-25, theta 0.1-10) is solved with ``accuracy=A``; a
case that says converged is checked against an independent solve one grid finer (its error
estimated and judged at ``A/4``): it is *wrong* when the two differ by more than the sum of
their estimated errors. Each case runs in its own process with a time limit;
results are written per case (resumable, keyed by the case and the target).

With ``--map fits`` the cases are the fit-check map instead: point contacts theta 0.25, 1, 4
x M 5-1000 x L 0-20 with Barus + incompressible (the assumptions of the Nijenbanning fit,
(2.23)-(2.29)) and Roelands + Dowson-Higginson at theta = 1, and line contacts with both
models against the Moes fit (2.17)-(2.22); each record also holds the fit's value, so the
fit deviation is read off a solve whose own error is known. Point checks are skipped (recorded
as such) where the check grid would exceed ``--check-max`` points.

Usage: python validation/extremes/accuracy_map.py [--map extremes|fits] [--accuracy 0.02]
       [--timeout 600] [--quick]
Writes build/validation/extremes/accuracy_map_<A>.json (fits: fit_map_<A>.json).
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("extremes")


def cases(quick: bool) -> list[dict]:
    out = []
    Ms = [1.0, 20.0, 1000.0, 5000.0] if not quick else [1.0, 5000.0]
    Ls = [0.0, 10.0, 25.0] if not quick else [0.0, 25.0]
    for contact, thetas in (("line", [1.0]), ("point", [0.1, 1.0, 10.0] if not quick else [1.0])):
        for M in Ms:
            for L in Ls:
                for th in thetas:
                    out.append({"contact": contact, "M": M, "L": L, "theta": th})
    return out


def fit_cases(quick: bool) -> list[dict]:
    out = []
    Ms = [5.0, 20.0, 100.0, 500.0, 1000.0] if not quick else [20.0, 500.0]
    Ls = [0.0, 5.0, 10.0, 20.0] if not quick else [0.0, 10.0]
    models = [("barus", "incompressible"), ("roelands", "dowson-higginson")]
    for v, d in models:
        for M in Ms:
            for L in Ls:
                out.append({"contact": "line", "M": M, "L": L, "theta": 1.0, "viscosity": v, "density": d})
    for th in ([1.0, 0.25, 4.0] if not quick else [1.0]):
        for v, d in models if th == 1.0 else models[:1]:
            for M in Ms:
                if M > 500.0 and th != 1.0:
                    continue  # elliptic contacts at M = 1000 need > 2049 points: out of budget
                for L in Ls:
                    out.append({"contact": "point", "M": M, "L": L, "theta": th, "viscosity": v, "density": d})
    # point contacts first, then lines by rising M (the slowest last): an interrupted run still
    # holds the most cases
    return sorted(out, key=lambda c: (c["contact"] == "line", c["M"] if c["contact"] == "line" else 0.0))


def fit_value(case: dict) -> float:
    from ehl_multigrid.model.fits import moes_line_central, nijenbanning_central

    if case["contact"] == "line":
        return float(moes_line_central(case["M"], case["L"]))
    return float(nijenbanning_central(case["M"], case["L"], case["theta"]))


def box_of(case: dict, box: float) -> dict:
    """Domain keywords of a box ``box`` times the solver's default (what an accuracy-driven
    solve reports as its refinement's ``box``)."""
    if box == 1.0:
        return {}
    model = {k: case[k] for k in ("viscosity", "density") if k in case}
    if case["contact"] == "line":
        from ehl_multigrid.line.problem import LineProblem

        pb = LineProblem.from_moes(case["M"], case["L"], **model)
        return {"xmin": pb.xmax - box * (pb.xmax - pb.xmin)}
    from ehl_multigrid.point.problem import default_domain, problem_from_moes

    pb = problem_from_moes(case["M"], case["L"], case["theta"], model.get("viscosity", "roelands"),
                           model.get("density", "dowson-higginson"), None, None, None)
    return dict(zip(("xmin", "xmax", "ymax"), (box * v for v in default_domain(pb)), strict=True))


def solve(case: dict, accuracy: float, points: int | None = None, max_points: int | None = None,
          box: float = 1.0, keep: list | None = None) -> dict:
    """The record of one accuracy-driven solve; ``keep`` (a list) receives the result object."""
    from ehl_multigrid.line import solve_line
    from ehl_multigrid.point import solve_point

    t0 = time.perf_counter()
    try:
        grid = {} if points is None else {"points": points}
        if max_points is not None:
            grid["max_points"] = max_points
        grid.update(box_of(case, box))
        model = {k: case[k] for k in ("viscosity", "density") if k in case}
        if case["contact"] == "line":
            s = solve_line(case["M"], case["L"], accuracy=accuracy, raise_on_failure=False, **model, **grid)
        else:
            s = solve_point(case["M"], case["L"], theta=case["theta"], accuracy=accuracy, **model, **grid)
    except Exception as exc:  # a clear error is an outcome; its type and text are recorded
        return {"status": "error", "message": f"{type(exc).__name__}: {exc}".splitlines()[0],
                "wall_s": time.perf_counter() - t0}
    if keep is not None:
        keep.append(s)
    return {"status": s.status_name, "message": s.message, "Hc": s.scalars.get("Hc"),
            "Hm": s.scalars.get("Hm"), "Hc_error": s.scalars.get("Hc_error"),
            "Hm_error": s.scalars.get("Hm_error"), "points": int(s.X.shape[0]),
            "error_budget": s.extra.get("error_budget"),
            "refinements": s.extra.get("refinements"), "actions": [str(a) for a in s.actions][-10:],
            "wall_s": time.perf_counter() - t0}


def domain_decided(r: dict, accuracy: float) -> bool:
    """Whether a stored result missed ``accuracy`` only by its fixed domain factor: the
    accuracy loop's test for measuring the decay of the box change (decay_could_meet)."""
    from ehl_multigrid.multigrid.accuracy import ErrorEstimate, decay_could_meet

    b = r.get("error_budget")
    if r.get("status") != "inaccurate" or not b:
        return False
    est = ErrorEstimate(r["Hc_error"], r["Hm_error"], b)
    return decay_could_meet(est, accuracy)


def grid_and_iteration(r: dict, film: str) -> float:
    """The grid plus algebraic part of a solve's estimate (what a check on the same box tests)."""
    b = r.get("error_budget") or {}
    if not b:
        return math.nan
    return b["grid"][film] + b["algebraic"][film]


def run_case(case: dict, accuracy: float, check_max: int = 1 << 30, max_points: int | None = None,
             guess_check_max: int = 0) -> dict:
    """Solve one case and check it. A point contact whose check grid lies above ``check_max``
    is checked on that grid from its converged result (no FMG: :func:`from_converged`) when the
    grid is at most ``guess_check_max`` points, else not at all."""
    kept: list = []
    r = solve(case, accuracy, max_points=max_points, keep=kept)
    out = {"case": case, "accuracy": accuracy, "result": r}
    if "viscosity" in case:
        out["Hc_fit"] = fit_value(case)
    finer = 2 * (r.get("points", 0) - 1) + 1
    if r["status"] == "converged" and case["contact"] == "point" and finer > check_max:
        if finer <= guess_check_max and kept:
            chk = from_converged(kept[0], finer)
            out["check"] = {**chk, "box": result_box(r)}
            out.update(judged_from_converged(r, chk, kept[0]))
        else:
            out["check"] = {"status": "skipped", "message": f"check grid above {check_max} points"}
    elif r["status"] == "converged":
        out.update(check_case(case, accuracy, r, kept[0] if kept else None))
    return out


def check_case(case: dict, accuracy: float, r: dict, sol: Any = None) -> dict:
    """Independent check of a converged result: one grid finer on the same box, judged at a
    quarter of the target. The box error is common to both, so their difference tests the
    grid and iteration parts: wrong when it exceeds the sum of those parts of the two
    estimates (or the totals differ by more than the two total estimates).

    Where the finer solve fails from its FMG start (Barus at alpha_bar 33-73 diverges there),
    the same finer grid is solved from the converged result ``sol`` instead, as the accuracy
    loop retries a failed refinement from its converged neighbour. That solve has no FMG films
    and so no estimate of its own: its grid error is taken as a third of its difference from
    the result's finest-grid film (second order), and the result's film is compared on the
    result's box (a box correction taken off)."""
    box = result_box(r)
    points = 2 * (r["points"] - 1) + 1
    chk = solve(case, accuracy / 4, points=points, box=box)
    if chk["status"] not in ("converged", "inaccurate") and sol is not None:
        chk = {**from_converged(sol, points), "fmg_check": {k: chk.get(k) for k in ("status", "message")}}
    out: dict = {"check": {**chk, "box": box}}
    if chk["status"] in ("converged", "inaccurate") and chk.get("Hc_error") is not None:
        d = {f: abs(r[f] / chk[f] - 1.0) for f in ("Hc", "Hm")}
        out["check_difference"] = d
        out["wrong"] = any(d[f] > grid_and_iteration(r, f) + grid_and_iteration(chk, f)
                           or d[f] > r[f + "_error"] + chk[f + "_error"] for f in ("Hc", "Hm"))
    else:
        out.update(judged_from_converged(r, chk, sol))
    return out


def judged_from_converged(r: dict, chk: dict, sol: Any) -> dict:
    """The verdict on result ``r`` (its object ``sol``) from ``chk``, the finer grid solved from
    it (:func:`from_converged`; nothing when that did not converge). Compared on the result's
    box (a box correction taken off); the finer grid's own error is taken as the second-order
    share of its difference from the result's finest raw film."""
    if chk.get("status") != "converged" or chk.get("start") != "converged result":
        return {}
    on_box, raw = films_on_box(r, sol)
    d, own = {}, {}
    for f in ("Hc", "Hm"):
        d[f] = abs(on_box[f] / chk[f] - 1.0)
        own[f] = abs(raw[f] / chk[f] - 1.0) / 3.0
    return {"check_difference": d, "check_own_error": own,
            "wrong": any(d[f] > grid_and_iteration(r, f) + own[f] for f in ("Hc", "Hm"))}


def films_on_box(r: dict, sol: Any) -> tuple[dict, dict]:
    """The films of record ``r`` (its object ``sol``) on the solve's own box (a box correction
    taken off), and its finest grid's raw films (the grid extrapolation taken off too)."""
    corr = getattr(sol.error, "correction", None) or {}
    on_box = {f: r[f] / (1.0 + corr.get("box", {}).get(f, 0.0)) for f in ("Hc", "Hm")}
    return on_box, {f: on_box[f] / (1.0 + corr.get("grid", {}).get(f, 0.0)) for f in ("Hc", "Hm")}


def result_box(r: dict) -> float:
    """The box (in units of the solver's default) of a record's last refinement."""
    return (r.get("refinements") or [{}])[-1].get("box", 1.0)


def from_converged(sol: Any, points: int, keep: list | None = None, options: Any = None) -> dict:
    """The record of ``sol``'s contact solved on ``points`` from ``sol`` itself (no FMG, a
    quarter of the tolerances of ``options``, default ``sol``'s, no error estimate); ``keep``
    (a list) receives the result object."""
    import dataclasses

    o = sol.options if options is None else options
    tight = dict(tol=o.tol / 4, tol_load=o.tol_load / 4, raise_on_failure=False)
    t0 = time.perf_counter()
    if sol.contact == "line":
        from ehl_multigrid.line.solver import solve_line_problem

        s = solve_line_problem(sol.problem, dataclasses.replace(o, points=points, levels=None, **tight),
                               guess=(sol.X, sol.P, sol.H0), from_guess=True)
    else:
        from ehl_multigrid.point.solve import solve_fas

        s = solve_fas(sol.problem, o, points=points, guess=(sol.X, sol.Y, sol.P, sol.H0), **tight)
    if keep is not None:
        keep.append(s)
    return {"status": s.status_name, "message": s.message, "Hc": s.scalars.get("Hc"),
            "Hm": s.scalars.get("Hm"), "Hc_error": None, "Hm_error": None, "points": points,
            "start": "converged result", "wall_s": time.perf_counter() - t0}


def recheck(path: Path, timeout: float, check_max: int) -> None:
    """Re-run the converged records of ``path`` (written before the checks used the result's
    own box and recorded the error budgets): solve and check again, one process each."""
    from tqdm import tqdm

    done = json.loads(path.read_text())
    for rec in tqdm(list(done.values()), desc="recheck"):
        chk = rec.get("check", {})
        if rec["result"].get("status") != "converged" or "box" in chk or chk.get("status") == "skipped":
            continue
        try:
            p = subprocess.run([sys.executable, __file__, "--accuracy", str(rec["accuracy"]),
                                "--check-max", str(check_max), "--case", json.dumps(rec["case"], sort_keys=True)],
                               capture_output=True, text=True, timeout=timeout)
            new = json.loads(p.stdout.strip().splitlines()[-1]) if p.returncode == 0 else None
        except subprocess.TimeoutExpired:
            new = None
        if new is None:
            rec["check"] = {"status": "recheck failed", "box": math.nan}
        else:
            rec.clear()
            rec.update(new)
        rec["class"] = classify(rec)
        tmp = path.with_suffix(".tmp")
        tmp.write_text(json.dumps(done, indent=1))
        tmp.replace(path)


def classify(rec: dict) -> str:
    st = rec["result"]["status"]
    if st == "converged":
        if rec.get("wrong"):
            return "wrong"
        if "check_difference" not in rec:
            return "converged to target, check " + rec.get("check", {}).get("status", "missing")
        return "converged to target"
    return "honest failure"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--accuracy", type=float, default=0.02)
    ap.add_argument("--timeout", type=float, default=600.0)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--map", choices=("extremes", "fits"), default="extremes")
    ap.add_argument("--check-max", type=int, default=1 << 30,
                    help="skip a point contact's check solve where its grid would exceed this many points")
    ap.add_argument("--max-points", type=int, default=None,
                    help="largest grid the accuracy target may refine to (default: the solver's)")
    ap.add_argument("--guess-check-max", type=int, default=0,
                    help="a point check grid above --check-max but not above this is solved from the "
                         "converged result (no FMG) instead of skipped")
    ap.add_argument("--retry-grid-budget", metavar="FILE",
                    help="re-run only the cases of FILE (a map of this script) that stopped at the grid "
                         "budget, with --max-points; writes <FILE stem>_max<N>.json")
    ap.add_argument("--domain-decided", metavar="FILE",
                    help="re-run only the cases of FILE that ended inaccurate where the fixed domain "
                         "factor alone decided the miss (the accuracy loop now measures the box "
                         "change's decay there); writes <FILE stem>_decay.json")
    ap.add_argument("--theta-min", type=float, default=None,
                    help="only the point cases with theta >= this (written to <map>_theta<T>.json)")
    ap.add_argument("--recheck", metavar="FILE",
                    help="re-run every converged case of FILE whose check predates the same-box "
                         "check (rewrites FILE)")
    ap.add_argument("--tag", default="",
                    help="suffix of the output file (a run on other code or budgets beside the old one)")
    ap.add_argument("--contact", choices=("line", "point"), default=None, help="only this contact's cases")
    ap.add_argument("--select", action="append", metavar="CONTACT:M:L:THETA",
                    help="only these cases (repeatable; e.g. point:5000:0:1), written to "
                         "<map>_<tag or 'select'>.json")
    ap.add_argument("--case", help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.recheck:
        recheck(Path(a.recheck), a.timeout, a.check_max)
        return
    if a.case:  # child process: one case
        print(json.dumps(run_case(json.loads(a.case), a.accuracy, a.check_max, a.max_points,
                                  a.guess_check_max)))
        return
    from tqdm import tqdm

    OUT.mkdir(parents=True, exist_ok=True)
    stem = "accuracy_map" if a.map == "extremes" else "fit_map"
    path = OUT / f"{stem}_{a.accuracy:g}{'_quick' if a.quick else ''}.json"
    if a.tag:
        path = path.with_name(f"{path.stem}_{a.tag}.json")
    todo = cases(a.quick) if a.map == "extremes" else fit_cases(a.quick)
    if a.contact:
        todo = [c for c in todo if c["contact"] == a.contact]
    if a.select:
        want = set()
        for text in a.select:
            try:
                contact, M, L, theta = text.split(":")
                want.add((contact, float(M), float(L), float(theta)))
            except ValueError:
                ap.error(f"--select {text!r}: expected CONTACT:M:L:THETA, e.g. point:5000:0:1")
        todo = [c for c in todo if (c["contact"], c["M"], c["L"], c.get("theta", 1.0)) in want]
        missing = want - {(c["contact"], c["M"], c["L"], c.get("theta", 1.0)) for c in todo}
        if missing:
            ap.error(f"--select: {sorted(missing)} not in the {a.map} map")
        if not a.tag:
            path = path.with_name(f"{path.stem}_select.json")
    if a.retry_grid_budget:
        if a.max_points is None:
            ap.error("--retry-grid-budget needs --max-points (the larger grid budget)")
        src = Path(a.retry_grid_budget)
        old = json.loads(src.read_text())
        todo = [rec["case"] for rec in old.values()
                if "grid error dominates" in str(rec["result"].get("message", ""))]
        path = src.with_name(f"{src.stem}_max{a.max_points}.json")
    if a.domain_decided:
        src = Path(a.domain_decided)
        old = json.loads(src.read_text())
        todo = [rec["case"] for rec in old.values() if domain_decided(rec["result"], a.accuracy)]
        path = src.with_name(f"{src.stem}_decay.json")
    if a.theta_min is not None:
        todo = [c for c in todo if c["contact"] == "point" and c["theta"] >= a.theta_min]
        path = path.with_name(f"{path.stem}_theta{a.theta_min:g}.json")
    done = json.loads(path.read_text()) if path.is_file() else {}
    inputs = run_inputs(a.accuracy, a.check_max, a.max_points, a.guess_check_max)
    for case in tqdm(todo):
        key = json.dumps(case, sort_keys=True)
        if reusable(done, key, inputs):
            continue
        done[key] = {**case_in_process(case, a.accuracy, a.check_max, a.max_points, a.timeout,
                                       guess_check_max=a.guess_check_max),
                     "inputs": inputs}
        save_records(path, done)
    print(json.dumps(count_classes(done)))


def case_in_process(case: dict, accuracy: float, check_max: int, max_points: int | None, timeout: float,
                    env: dict | None = None, guess_check_max: int = 0) -> dict:
    """One case solved and checked in its own process (``--case``), classified; a crash or a
    timeout is a record too."""
    key = json.dumps(case, sort_keys=True)
    extra = [] if max_points is None else ["--max-points", str(max_points)]
    if guess_check_max:
        extra += ["--guess-check-max", str(guess_check_max)]
    try:
        p = subprocess.run([sys.executable, __file__, "--accuracy", str(accuracy),
                            "--check-max", str(check_max), *extra, "--case", key],
                           capture_output=True, text=True, timeout=timeout, env=env)
        rec = json.loads(p.stdout.strip().splitlines()[-1]) if p.returncode == 0 else {
            "case": case, "accuracy": accuracy,
            "result": {"status": "crash", "message": p.stderr.strip().splitlines()[-1:]}}
    except subprocess.TimeoutExpired:
        rec = {"case": case, "accuracy": accuracy,
               "result": {"status": "timeout", "message": f"over {timeout:g} s"}}
    rec["class"] = classify(rec)
    return rec


def code_version() -> str:
    """The commit of the checkout this script runs from (``+dirty`` with uncommitted changes to
    the package): a record computed by other code is not reused."""
    root = Path(__file__).resolve().parents[2]
    try:
        head = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True,
                              text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--",
                                "ehl_multigrid", "thermal", "mixed"],
                               capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return head + ("+dirty" if dirty else "")


def run_inputs(accuracy: float, check_max: int, max_points: int | None, guess_check_max: int = 0) -> dict:
    """What a map record depends on besides its case: a resumed map reuses only the records
    computed for the same inputs (and recomputes the rest)."""
    out = {"accuracy": accuracy, "check_max": check_max, "max_points": max_points,
           "code": code_version()}
    if guess_check_max:
        out["guess_check_max"] = guess_check_max
    return out


def reusable(done: dict, key: str, inputs: dict) -> bool:
    """True when ``done`` holds the case ``key`` computed for ``inputs`` (not for other inputs,
    and not by another or an uncommitted version of the code)."""
    rec = done.get(key)
    return (rec is not None and rec.get("inputs") == inputs
            and not str(inputs["code"]).endswith(("+dirty", "unknown")))


def save_records(path: Path, done: dict) -> None:
    """Write the map's records whole (temporary file, then rename)."""
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(done, indent=1))
    tmp.replace(path)


def count_classes(done: dict) -> dict[str, int]:
    counts: dict[str, int] = {}
    for rec in done.values():
        counts[rec["class"]] = counts.get(rec["class"], 0) + 1
    return counts

if __name__ == "__main__":
    main()
