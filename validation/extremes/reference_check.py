"""A stronger check of the results of an accuracy map: the true error of each converged result
against a reference from converged solves two and four times finer (line contacts up to 65537
points, point contacts up to 2049 along X: results on at most 513 points; ``--coarse-refs``:
half as fine, the same and twice as fine for results whose 4n grid is above the limit).

The map's own check (accuracy_map.check_case: one grid finer, wrong when the two differ by more
than the sum of their estimates) misses an optimistic result next to a pessimistic check
(isoviscous (100, 0): a stated Hm error of 0.011 % with a true 0.16 %, check estimate 1.2 %).
Here the same discrete problem (the result's grid and box) is solved deep (tolerances 1e-8 /
1e-9 line; point 1e-7 / 1e-6: the point load error stalls near 5e-8 at 513 points, and it
moves the films by less than half of itself) on ``n``, ``2n - 1`` and ``4n - 3`` points;
Richardson over the three converged films gives the grid limit on that box, and the result's film (with its own iteration error) is compared
with it. A result is *wrong* when its distance to the limit exceeds its stated grid plus
algebraic error (the box part is common to both) by more than the reference's own uncertainty
(the finest reference's distance to the limit).

    python validation/extremes/reference_check.py [--contact line|point] [--max-points N] \
        build/validation/extremes/fit_map_0.01.json build/validation/extremes/accuracy_map_0.02.json

``--max-points`` raises the finest reference grid (default 65537 line, 2049 point; a line
result on 65537 points needs 262145: about 1.5 GB and a minute per deep solve).

Writes ``build/validation/extremes/<contact>_reference_check_<tag>.json`` (resumable: a record already there for the same
result is not solved again).
"""

from __future__ import annotations

import json
import math
import sys
import time
from pathlib import Path

from tqdm import tqdm

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import require  # noqa: E402
from accuracy_map import OUT, box_of  # noqa: E402

MAX_POINTS = {"line": 65537, "point": 2049}

#: a deep solve that ran out of cycles still serves as the reference when the films of its
#: last STALL_FILMS finest cycles lie within a band this narrow (relative): the mean, with the
#: band's half width as its uncertainty (point solves whose residual stalls near 1e-6-1e-5 while
#: the films settle: theta 10 isoviscous, Barus L = 20 at theta 0.25, L = 25 at theta 0.1)
STALL_BAND = 1e-3
STALL_FILMS = 10


def reference_films(deep) -> tuple[dict, dict] | None:
    """Films (Moes units) of the deep solve and their relative uncertainty, or None."""
    if deep.success:
        return {h: float(deep.scalars[h]) for h in ("Hc", "Hm")}, {"Hc": 0.0, "Hm": 0.0}
    if deep.status_name == "residual_floor":
        # stopped where the residual stops falling (tolerance below the relaxation's floor):
        # the last finest-grid film change is the reference's uncertainty
        from ehl_multigrid.multigrid.accuracy import last_film_change

        unc = last_film_change(deep.history)
        if unc is None or not max(unc.values()) <= STALL_BAND:
            return None
        return {h: float(deep.scalars[h]) for h in ("Hc", "Hm")}, unc
    if deep.status_name != "max_cycles":
        return None
    top = max(h.level for h in deep.history)
    fin = [h for h in deep.history if h.level == top][-STALL_FILMS:]
    films, unc = {}, {}
    for h in ("Hc", "Hm"):
        moes = float(deep.scalars[h]) / float(deep.scalars[h + "_venner"])
        vals = [getattr(f, h) * moes for f in fin]
        mean = sum(vals) / len(vals)
        films[h], unc[h] = mean, 0.5 * (max(vals) - min(vals)) / mean
    if len(fin) < STALL_FILMS or max(unc.values()) > STALL_BAND:
        return None
    return films, unc


def deep(case: dict, points: int, box: float) -> dict:
    from ehl_multigrid.line import solve_line
    from ehl_multigrid.point import solve_point

    model = {k: case[k] for k in ("viscosity", "density") if k in case}
    t = time.perf_counter()
    if case["contact"] == "line":
        s = solve_line(case["M"], case["L"], points=points, estimate=False, tol=1e-8, tol_load=1e-9,
                       max_cycles=200, raise_on_failure=False, **model, **box_of(case, box))
    else:
        s = solve_point(case["M"], case["L"], theta=case["theta"], points=points, estimate=False,
                        tol=1e-7, tol_load=1e-6, max_cycles=100, raise_on_failure=False, **model,
                        **box_of(case, box))
    ref = reference_films(s)
    if ref is None:
        return {"points": points, "status": s.status_name, "Hc": s.scalars.get("Hc"),
                "Hm": s.scalars.get("Hm"), "wall_s": time.perf_counter() - t}
    films, unc = ref
    return {"points": points, "status": "converged" if s.success else "settled", **films,
            "band": unc, "wall_s": time.perf_counter() - t}


def limit(films: list[float]) -> tuple[float, float]:
    """Richardson limit of three converged films (refinement 2) and its uncertainty (the
    finest film's distance to it; the first-order bound when the sequence is irregular).
    Written here rather than taken from ``multigrid.accuracy.richardson``: the reference must
    not share the order caps and safety factor of the estimator it checks."""
    a, b, c = films
    d1, d2 = b - a, c - b
    if d1 != 0.0 and d2 != 0.0 and (d1 > 0) == (d2 > 0) and abs(d2) < abs(d1):
        p = math.log2(d1 / d2)
        ext = c + d2 / (2.0**p - 1.0)
        return ext, abs(c - ext)
    return c, max(abs(d2), 0.5 * abs(d1))


def judge_against_limit(entry: dict, r: dict, solves: list[dict]) -> None:
    """Status ``"checked"``, per film the Richardson limit of the three converged reference
    films, its uncertainty and the result's true error against its stated grid plus algebraic
    error, and ``wrong`` when the true error exceeds that statement by more than the
    reference's uncertainty; written into ``entry``."""
    entry["status"] = "checked"
    entry["wrong"] = False
    b = r["error_budget"]
    for film in ("Hc", "Hm"):
        ext, unc = limit([s[film] for s in solves])
        # a settled (stalled) reference film's band enters the limit amplified by at most 3
        # (Richardson at order >= 1)
        unc += 3.0 * abs(ext) * max(s.get("band", {}).get(film, 0.0) for s in solves)
        true = abs(r[film] / ext - 1.0)
        stated = b["grid"][film] + b["algebraic"][film]
        entry[film] = {"limit": ext, "uncertainty": unc / abs(ext), "true": true,
                       "stated": stated, "ratio": true / stated if stated > 0 else math.inf}
        if true > stated + unc / abs(ext):
            entry["wrong"] = True


def main() -> None:
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--contact", choices=("line", "point"), default="line")
    ap.add_argument("--max-points", type=int, default=None, help="finest reference grid")
    ap.add_argument("--coarse-refs", action="store_true",
                    help="a result whose 4n grid exceeds --max-points is checked on n/2, n and 2n "
                         "(a weaker reference: its uncertainty is that of the 2n film)")
    ap.add_argument("files", nargs="+")
    a = ap.parse_args()
    contact = a.contact
    max_points = a.max_points or MAX_POINTS[contact]
    files = [Path(f) for f in a.files]
    tag = "_".join(f.stem for f in files)
    path = OUT / f"{contact}_reference_check_{tag}.json"
    todo = []
    for f in files:
        for key, rec in json.loads(require(f, "python validation/extremes/accuracy_map.py").read_text()).items():
            r = rec["result"]
            if rec["case"]["contact"] == contact and r.get("status") == "converged" and r.get("error_budget"):
                todo.append((f"{f.stem}|{key}", rec))
    # resume: keep only the records of results still in the inputs (no stale entry)
    before = json.loads(path.read_text()) if path.is_file() else {}
    # (a record skipped for its grid is tried again: the grid limit may have been raised; so is
    # a failed reference that ran out of cycles, its films may have settled, or diverged: before
    # POINT_POLICY.quiet_below a deep point solve at its residual floor could end "diverged")
    out = {k: before[k] for k, rec in todo if k in before and before[k]["result"] == rec["result"]
           and before[k]["status"] != "skipped"
           and not (before[k]["status"] == "reference failed"
                    and any(s["status"] in ("max_cycles", "diverged") for s in before[k]["solves"]))}

    def save() -> None:
        tmp = path.with_suffix(".tmp")
        tmp.write_text(json.dumps(out, indent=1))
        tmp.replace(path)

    save()
    # cheapest first (grid, then load): an interrupted run has checked as many as it could
    todo.sort(key=lambda kr: (kr[1]["result"]["points"], kr[1]["case"]["M"], kr[1]["case"]["L"]))
    for key, rec in tqdm(todo):
        r = rec["result"]
        if key in out:
            continue
        n = r["points"]
        box = (r.get("refinements") or [{}])[-1].get("box", 1.0)
        grids = (n, 2 * (n - 1) + 1, 4 * (n - 1) + 1)
        if grids[-1] > max_points and a.coarse_refs and n >= 513:
            grids = ((n - 1) // 2 + 1, n, 2 * (n - 1) + 1)
        if grids[-1] > max_points:
            out[key] = {"case": rec["case"], "result": r, "status": "skipped",
                        "message": f"reference grid above {max_points} points"}
            save()
            continue
        solves = [deep(rec["case"], m, box) for m in grids]
        entry = {"case": rec["case"], "result": r, "box": box, "grids": list(grids), "solves": solves}
        if all(s["status"] in ("converged", "settled") for s in solves):
            judge_against_limit(entry, r, solves)
        else:
            entry["status"] = "reference failed"
        out[key] = entry
        save()
    checked = [v for v in out.values() if v["status"] == "checked"]
    ratios = {f: sorted(v[f]["ratio"] for v in checked) for f in ("Hc", "Hm")}
    summary = {"results": len(out), "checked": len(checked),
               "of them on n/2, n, 2n (--coarse-refs)": sum(v.get("grids", [0, 0])[1] == v["result"]["points"]
                                                            for v in checked),
               "wrong": sum(v["wrong"] for v in checked),
               "skipped": sum(v["status"] == "skipped" for v in out.values()),
               "reference failed": sum(v["status"] == "reference failed" for v in out.values()),
               "median true/stated": {f: ratios[f][len(ratios[f]) // 2] if ratios[f] else None for f in ratios},
               "max true/stated": {f: ratios[f][-1] if ratios[f] else None for f in ratios}}
    print(json.dumps(summary, indent=1))
    for k, v in out.items():
        if v.get("wrong"):
            print("WRONG", k, {f: v[f] for f in ("Hc", "Hm")})


if __name__ == "__main__":
    main()
