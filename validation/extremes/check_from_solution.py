"""Reference check of one point result whose deep reference solves do not converge from the FMG
(the (20, 25, theta 10) extremes case: its 4097-point grid on a box twice as wide diverges from
the Hertzian start, converges from a converged neighbour, ``RETRY_FROM_NEIGHBOUR``).

The case is solved at the accuracy target as the map solves it; the same discrete problem (the
result's box and cells) is then solved deep (tolerances 1e-7 / 1e-6, as reference_check.py) on
``n/2``, ``n`` and ``2n - 1`` points, each started on its finest grid from the result's solution.
Richardson over the three films gives the grid limit on that box; the result is *wrong* when its
distance to the limit exceeds its stated grid plus algebraic error by more than the reference's
uncertainty (the box part is common to both and is not tested here). When the finest deep solve
fails, the two coarser ones give a weaker first-order bound (``judge``: status ``"pair bound"``).

    python validation/extremes/check_from_solution.py --case point:20:25:10 --accuracy 0.02 \\
        --max-points 4097

With ``--finer-film-stop`` the deep references are replaced by the map's own check (one grid
finer, stopped on the films at a quarter of the target), started from the result
(:func:`finer_check`), for results whose map check diverged from the FMG start.

Writes ``build/validation/extremes/check_from_solution_<M>_<L>_<theta>_<accuracy>[_finer].json`` after every solve.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from dataclasses import replace
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from accuracy_map import OUT  # noqa: E402
from reference_check import judge_against_limit, reference_films  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", required=True, help="point:M:L:THETA")
    ap.add_argument("--accuracy", type=float, default=0.02)
    ap.add_argument("--max-points", type=int, default=4097)
    ap.add_argument("--viscosity", default="roelands")
    ap.add_argument("--density", default="dowson-higginson")
    ap.add_argument("--finer-film-stop", action="store_true",
                    help="instead of the deep references: the map's one-grid-finer check (2n - 1 points, "
                         "the film stop of a quarter of the target), started from the result")
    ap.add_argument("--judge-only", action="store_true",
                    help="recompute the verdict of the existing output from its recorded solves")
    a = ap.parse_args()
    contact, M, L, theta = a.case.split(":")
    if contact != "point":
        raise SystemExit("--case: point contacts only (point:M:L:THETA)")
    M, L, theta = float(M), float(L), float(theta)

    from ehl_multigrid.point.solve import solve_fas, solve_point

    model = {"viscosity": a.viscosity, "density": a.density}
    tag = "" if a.viscosity == "roelands" and a.density == "dowson-higginson" else f"_{a.viscosity}_{a.density}"
    mode = "_finer" if a.finer_film_stop else ""
    path = OUT / f"check_from_solution_{M:g}_{L:g}_{theta:g}_{a.accuracy:g}{tag}{mode}.json"
    out: dict = {"case": {"contact": "point", "M": M, "L": L, "theta": theta, **model}, "accuracy": a.accuracy}

    def save() -> None:
        tmp = path.with_suffix(".tmp")
        tmp.write_text(json.dumps(out, indent=1))
        tmp.replace(path)

    if a.judge_only:
        out = json.loads(path.read_text())
        judge(out)
        save()
        print(json.dumps({k: out.get(k) for k in ("status", "wrong", "confirmed", "Hc", "Hm")}), flush=True)
        return

    t = time.perf_counter()
    res = solve_point(M, L, theta=theta, accuracy=a.accuracy, max_points=a.max_points,
                      raise_on_failure=False, threads=1, **model)
    b = res.error.budget if res.error is not None else None
    out["result"] = {"status": res.status_name, "message": res.message, "points": int(res.X.shape[0]),
                     "Hc": float(res.scalars["Hc"]), "Hm": float(res.scalars["Hm"]),
                     "Hc_error": res.scalars.get("Hc_error"), "Hm_error": res.scalars.get("Hm_error"),
                     "error_budget": b, "actions": list(res.actions),
                     "y_ratio": res.extra["y_ratio"], "domain": list(res.extra["domain"]),
                     "wall_total_s": time.perf_counter() - t}
    save()
    print(json.dumps(out["result"], default=str), flush=True)
    if not res.success:
        return
    n = res.X.shape[0]
    guess = (res.X, res.Y, res.P, float(res.H0))
    if a.finer_film_stop:
        finer_check(out, res, guess, a.accuracy, save)
        return
    solves = []
    for m in ((n - 1) // 2 + 1, n, 2 * (n - 1) + 1):
        t = time.perf_counter()
        opts = same_problem(res, m, tol=1e-7, tol_load=1e-6, film_tol=None, max_cycles=100)
        s = solve_fas(res.problem, opts, guess=guess)
        ref = reference_films(s)
        row = {"points": m, "status": s.status_name, "message": s.message, "cycles": s.cycles,
               "wall_s": time.perf_counter() - t}
        if ref is not None:
            films, unc = ref
            row.update(films, band=unc, status="converged" if s.success else "settled")
        solves.append(row)
        out["solves"] = solves
        save()
        print(json.dumps(row), flush=True)
        del s
    judge(out)
    save()
    print(json.dumps({k: out.get(k) for k in ("status", "wrong", "Hc", "Hm")}), flush=True)


def same_problem(res, points: int, **kw):
    """The options of ``res`` on ``points`` points with its box and cells (the same discrete
    problem on another grid), never raising on failure; ``kw`` overrides the rest."""
    xmin, xmax, ymax = res.extra["domain"]
    return replace(res.options, points=points, xmin=xmin, xmax=xmax, ymax=ymax,
                   y_ratio=res.extra["y_ratio"], raise_on_failure=False, **kw)


def finer_check(out: dict, res, guess: tuple, accuracy: float, save) -> None:
    """The map's check (``accuracy_map.check_case``: one grid finer on the result's box and
    cells, stopped on the films at a quarter of the target) for a result whose check diverges
    from the FMG start: the finer solve starts on its finest grid from the result instead.
    Such a solve has no coarser levels, so no grid estimate of its own: the difference is
    judged against the result's grid plus algebraic parts plus the check's algebraic part only,
    stricter than the map's rule (which adds the check's grid part too)."""
    from ehl_multigrid.multigrid.accuracy import film_tol
    from ehl_multigrid.point.solve import solve_fas

    t = time.perf_counter()
    opts = same_problem(res, 2 * (res.X.shape[0] - 1) + 1, film_tol=None)
    opts = replace(opts, film_tol=film_tol(opts, accuracy / 4))  # the package's film-stop rule
    s = solve_fas(res.problem, opts, guess=guess)
    row = {"points": opts.points, "status": s.status_name, "message": s.message, "cycles": s.cycles,
           "film_tol": opts.film_tol, "wall_s": time.perf_counter() - t}
    if s.success:
        row.update(Hc=float(s.scalars["Hc"]), Hm=float(s.scalars["Hm"]))
        alg = (s.error.budget or {}).get("algebraic") if s.error is not None else None
        row["algebraic"] = alg
    out["check"] = row
    r = out["result"]
    if s.success:
        b = r["error_budget"]
        out["check_difference"], out["allowed"] = {}, {}
        for film in ("Hc", "Hm"):
            d = abs(r[film] / row[film] - 1.0)
            allowed = b["grid"][film] + b["algebraic"][film] + ((alg or {}).get(film) or 0.0)
            out["check_difference"][film], out["allowed"][film] = d, allowed
        out["wrong"] = any(out["check_difference"][f] > out["allowed"][f] for f in ("Hc", "Hm"))
    save()
    print(json.dumps({k: out.get(k) for k in ("check", "check_difference", "allowed", "wrong")},
                     default=str), flush=True)


def judge(out: dict) -> None:
    """The verdict from the result and its deep solves (``out['solves']``, coarsest first).

    Three converged films: Richardson limit, as reference_check.py. When only the two coarser
    (``n/2`` and ``n``) converged, a weaker bound (status ``"pair bound"``): the result's distance
    to the deep ``n`` film (its true iteration error) plus the first-order bound of the ``n``
    grid's own error, ``|f_n - f_n/2|`` (an error that at least halves per grid), plus the deep
    solves' bands. That bound is an upper bound of the true error: within the stated grid plus
    algebraic error it confirms the statement (``confirmed``); above it, it neither confirms nor
    refutes it (``confirmed`` False, never counted as wrong)."""
    solves, r = out["solves"], out["result"]
    b = r["error_budget"]
    ok = [s["status"] in ("converged", "settled") for s in solves]
    if all(ok):
        judge_against_limit(out, r, solves)
        return
    if ok[:2] == [True, True]:
        out["status"], out["confirmed"] = "pair bound", True
        half, full = solves[0], solves[1]
        for film in ("Hc", "Hm"):
            iteration = abs(r[film] / full[film] - 1.0)
            grid = abs(full[film] / half[film] - 1.0)
            band = sum(s.get("band", {}).get(film, 0.0) for s in (half, full))
            bound = iteration + grid + band
            stated = b["grid"][film] + b["algebraic"][film]
            out[film] = {"true_iteration": iteration, "grid_first_order": grid, "band": band,
                         "bound": bound, "stated": stated, "ratio": bound / stated if stated > 0 else math.inf}
            if bound > stated:
                out["confirmed"] = False
        return
    out["status"] = "reference failed"


if __name__ == "__main__":
    main()
