"""Shared helpers of the accuracy studies: one solve -> flat record (cached on disk, one JSON
file per solve named by all its inputs, so an interrupted study resumes), the case lists, and
Richardson extrapolation in the mesh size and in the box size."""

from __future__ import annotations

import json
import math
import os
import sys
import time
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1]))
sys.path.insert(0, str(HERE.parent))
# require: re-exported to the studies that read another study's output
from _paths import out_dir, require  # noqa: E402, F401

OUT = out_dir("accuracy")
SOLVES = out_dir("accuracy/solves")
REFS = out_dir("accuracy/references")

from ehl_multigrid.line.problem import default_xmin  # noqa: E402
from ehl_multigrid.point.problem import default_domain, problem_from_moes  # noqa: E402

#: line cases (M, L): tested grids. The grids follow M: a line grid coarser than these either
#: fails to start at that M or leaves a single FMG grid (no Richardson estimate).
LINE_CASES: dict[tuple[float, float], tuple[int, ...]] = {
    (5.0, 0.0): (513, 1025), (5.0, 10.0): (513, 1025),
    (20.0, 0.0): (513, 1025), (20.0, 10.0): (513, 1025), (20.0, 20.0): (513, 1025),
    (100.0, 0.0): (1025, 2049), (100.0, 10.0): (1025, 2049), (100.0, 20.0): (1025, 2049),
    (1000.0, 10.0): (2049, 4097), (1000.0, 20.0): (2049, 4097),
    (3000.0, 10.0): (4097,),
}
#: point cases (M, L, theta): tested grids (at least the solver's minimum grid)
POINT_CASES: dict[tuple[float, float, float], tuple[int, ...]] = {
    (5.0, 0.0, 1.0): (129, 257), (20.0, 0.0, 1.0): (129, 257), (20.0, 10.0, 1.0): (129, 257),
    (100.0, 10.0, 1.0): (129, 257), (100.0, 20.0, 1.0): (129, 257),
    (1000.0, 10.0, 1.0): (513,),
    (20.0, 10.0, 0.25): (129, 257), (20.0, 10.0, 4.0): (257, 513),
}
#: (20, 20, 1) is not in the point set: the point solver does not converge there at 257 or 513
#: points (load error 2e-3 after 30 cycles), so it has no estimate to judge.
#: Tight tolerances of the reference solves. The line multigrid reaches 1e-8 / 1e-9; the point
#: W cycles end in a limit cycle with a load error near 1e-5 whatever the tolerance (tighter
#: tolerances only make the robustness policy damp and wander), so the point reference solves
#: ask for ten times the default tolerances and count when the films moved by < 3e-5 over the
#: last finest-grid cycles; that spread (plus half the load error) is their algebraic uncertainty.
LINE_TIGHT = {"tol": 1e-8, "tol_load": 1e-9}
POINT_TIGHT = {"tol": 1e-5, "tol_load": 1e-6, "max_cycles": 30}
#: largest grid of the dense direct line solver used where the line multigrid stalls
DENSE_MAX = 8193


def load_avg() -> float:
    return os.getloadavg()[0]


def code_version() -> str:
    """Hash of the numerical code (multigrid core, line and point contacts): records of
    estimated errors are redone when it changes, since the estimator and its constants live
    there."""
    import hashlib

    root = HERE.parents[1] / "ehl_multigrid"
    h = hashlib.sha1()
    for sub in ("multigrid", "line", "point"):
        for f in sorted((root / sub).glob("*.py")):
            h.update(f.name.encode())
            h.update(f.read_bytes())
    return h.hexdigest()[:12]


def fmt(x: float) -> str:
    return f"{x:g}"


def solve_key(contact: str, M: float, L: float, theta: float, points: int, box: float,
              **opts: Any) -> str:
    tail = "_".join(f"{k}{fmt(v) if isinstance(v, float) else v}" for k, v in sorted(opts.items()))
    return f"{contact}_M{fmt(M)}_L{fmt(L)}_t{fmt(theta)}_n{points}_box{fmt(box)}" + (f"_{tail}" if tail else "")


def clean(o: Any) -> Any:
    if isinstance(o, dict):
        return {str(k): clean(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [clean(v) for v in o]
    if isinstance(o, float) and not math.isfinite(o):
        return None
    if hasattr(o, "item"):
        return clean(o.item())
    return o


def write_json(path: Path, data: Any) -> None:
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(clean(data), indent=1))
    os.replace(tmp, path)


def read_json(path: Path) -> Any:
    return json.loads(path.read_text()) if path.exists() else None


def nan(x: Any) -> float:
    return math.nan if x is None else float(x)


def line_xmin(M: float, L: float, box: float, xmax: float = 1.5) -> float:
    """Inlet of a line box ``box`` times the default length; nodes stay aligned with the
    default box's (the extra length is a whole number of default lengths)."""
    return xmax - box * (xmax - default_xmin(M, L))


def point_box(M: float, L: float, theta: float, box: float) -> tuple[float, float, float]:
    x0, x1, y = default_domain(problem_from_moes(M, L, theta))
    return box * x0, box * x1, box * y


def finest_spread(sol: Any) -> float:
    """Relative spread of Hc and Hm over the last three finest-grid cycles (algebraic noise)."""
    top = sol.levels - 1
    fin = [h for h in sol.history if h.level == top][-3:]
    if len(fin) < 2:
        return math.nan
    hc = [h.Hc for h in fin]
    hm = [h.Hm for h in fin]
    le = abs(float(sol.load_error_history[-1])) if sol.load_error_history.size else 0.0
    return max((max(hc) - min(hc)) / abs(hc[-1]), (max(hm) - min(hm)) / abs(hm[-1])) + 0.5 * le


def record(sol: Any, wall: float, cpu: float, load0: float) -> dict[str, Any]:
    s = sol.scalars
    return {"Hc_venner": s.get("Hc_venner"), "Hm_venner": s.get("Hm_venner"), "Hc": s.get("Hc"),
            "Hm": s.get("Hm"), "status": sol.status_name, "success": bool(sol.success),
            "message": sol.message, "cycles": int(sol.cycles), "levels": int(sol.levels),
            "load_error": float(sol.load_error_history[-1]) if sol.load_error_history.size else None,
            "spread": finest_spread(sol), "solver_wall_s": float(sol.wall_s), "wall_s": wall,
            "cpu_s": cpu, "load_before": load0, "load_after": load_avg(),
            "fmg": [{k: d.get(k) for k in ("level", "points", "Hc", "Hm")} for d in sol.fmg]}


def cached_solve(contact: str, M: float, L: float, theta: float, points: int, box: float = 1.0,
                 **opts: Any) -> dict[str, Any]:
    """A reference solve (no error estimate) at ``points`` on a box ``box`` times the default
    at equal mesh size, cached in build/validation/accuracy/solves."""
    path = SOLVES / f"{solve_key(contact, M, L, theta, points, box, **opts)}.json"
    rec = read_json(path)
    # far-field solves are redone when the numerical code changed (their boundary is part of
    # it); the P = 0 references are kept (hours of solves, their model unchanged)
    if rec is not None and (opts.get("far_field") is not True or rec.get("code") == code_version()):
        return rec
    from ehl_multigrid.line import solve_line
    from ehl_multigrid.point import solve_point

    load0, t0, c0 = load_avg(), time.perf_counter(), time.process_time()
    try:
        if contact == "line":
            sol = solve_line(M, L, points=points, xmin=line_xmin(M, L, box), estimate=False,
                             raise_on_failure=False, **opts)
            extra = {"xmin": sol.problem.xmin, "xmax": sol.problem.xmax}
        else:
            x0, x1, y = point_box(M, L, theta, box)
            dom = {} if box == 1.0 else {"xmin": x0, "xmax": x1, "ymax": y}
            if "y_ratio" not in opts and box != 1.0:
                base = cached_solve(contact, M, L, theta, (points - 1) // int(box) + 1, 1.0, **opts)
                dom["y_ratio"] = base["y_ratio"]
            # P = 0 on the boundary unless the options ask for the far field (then in the key):
            # the references of references.py are independent of it
            sol = solve_point(M, L, theta=theta, points=points, estimate=False, **dom,
                              **{"far_field": False, **opts})
            extra = {"domain": list(sol.extra["domain"]), "y_ratio": sol.extra["y_ratio"],
                     "shape": list(sol.P.shape)}
        rec = record(sol, time.perf_counter() - t0, time.process_time() - c0, load0)
        rec.update(extra)
    except Exception as exc:  # noqa: BLE001 -- a failed reference solve is recorded, not fatal
        rec = {"status": "error", "success": False, "message": f"{type(exc).__name__}: {exc}",
               "wall_s": time.perf_counter() - t0, "load_before": load0}
    rec.update(contact=contact, M=M, L=L, theta=theta, points=points, box=box, options=opts,
               code=code_version())
    write_json(path, rec)
    return rec


def usable(rec: dict[str, Any] | None, max_spread: float = 3e-5) -> bool:
    """A reference solve that converged, or stopped at max_cycles with its films settled."""
    if not rec or rec.get("Hc_venner") is None:
        return False
    if rec.get("success"):
        return True
    return rec.get("status") == "max_cycles" and nan(rec.get("spread")) <= max_spread


# -- extrapolation ----------------------------------------------------------------------------
def richardson_reference(values: list[float], noise: float = 0.0,
                         two_grid_regular: bool = False) -> dict[str, Any]:
    """Limit of films on grids refined by 2 each time (coarse to fine), from the last three.

    Regular (monotone, contracting) sequences: observed order ``p`` (clipped to [1, 3]),
    extrapolation from the two finest values; uncertainty = change of the extrapolation when
    ``p`` moves by +-0.5, plus twice the algebraic noise. Irregular sequences: the finest
    value, uncertainty = the last change.
    """
    v = [float(x) for x in values]
    f3 = v[-1]
    out: dict[str, Any] = {"values": v}
    if len(v) < 3:
        d2 = v[-1] - v[-2]
        # formal order 2; the extrapolation's change for p +- 0.5 when the caller knows the
        # order is regular (the central film: 1.98-2.05 in every three-grid case), else the
        # whole last change
        u = abs(d2) * (1.0 / (2.0**1.5 - 1.0) - 1.0 / 3.0) if two_grid_regular else abs(d2)
        out.update(value=f3 + d2 / 3.0, order=math.nan, order_used=2.0, regular=False,
                   uncertainty=u + 2 * noise * abs(f3), note="two grids: formal order 2")
        return out
    d1, d2 = v[-2] - v[-3], v[-1] - v[-2]
    regular = d1 != 0 and d2 != 0 and (d1 > 0) == (d2 > 0) and abs(d2) < abs(d1)
    if not regular:
        out.update(value=f3, order=math.nan, order_used=math.nan, regular=False,
                   uncertainty=abs(d2) + 2 * noise * abs(f3),
                   note="irregular: finest value, uncertainty = last change")
        return out
    p = math.log2(d1 / d2)
    pu = min(max(p, 1.0), 3.0)

    def ext(q: float) -> float:
        return f3 + d2 / (2.0**q - 1.0)

    val = ext(pu)
    u = max(abs(ext(max(pu - 0.5, 0.7)) - val), abs(ext(pu + 0.5) - val))
    out.update(value=val, order=p, order_used=pu, regular=True, value_p2=ext(2.0),
               uncertainty=u + 2 * noise * abs(f3), note="")
    return out


def box_extrapolation(g1: float, g2: float, g4: float | None, g8: float | None = None) -> dict[str, Any]:
    """Relative change of a film from the default box to an unbounded one, from boxes 1, 2, 4
    (and 8) times the default at equal mesh: ``d_k = g_k/g1 - 1``; the decay ``r`` of the
    change per doubling from the last two doublings; the remainder beyond the largest box
    ``(last change)/(r - 1)`` (geometric), with that remainder itself as uncertainty.
    Without g4: ``d2 (1 + 1/3)`` (decay 4 assumed), uncertainty d2."""
    d2 = g2 / g1 - 1.0
    if g4 is None:
        return {"d2": d2, "d4": math.nan, "d8": math.nan, "decay": math.nan, "beyond": math.nan,
                "total": d2 * 4.0 / 3.0, "uncertainty": abs(d2), "note": "no 4x box: decay 4 assumed"}
    d4 = g4 / g1 - 1.0
    d8 = math.nan if g8 is None else g8 / g1 - 1.0
    ds = [0.0, d2, d4] + ([d8] if g8 is not None else [])
    prev, step = ds[-2] - ds[-3], ds[-1] - ds[-2]
    if prev != 0 and step != 0 and (prev > 0) == (step > 0) and abs(step) < abs(prev):
        r = prev / step
        beyond = step / (r - 1.0)
        note, unc = "", abs(beyond)
    else:
        r, beyond = math.nan, 0.0
        note, unc = "box sequence not contracting: no extrapolation beyond the largest box", abs(step)
    return {"d2": d2, "d4": d4, "d8": d8, "decay": r, "beyond": beyond, "total": ds[-1] + beyond,
            "uncertainty": unc, "note": note}


def dense_line_solve(M: float, L: float, points: int, box: float = 1.0) -> dict[str, Any]:
    """Reference line solve by the dense direct solver (dense_line.py) where the multigrid
    stalls: the tight multigrid solve on the next coarser grid of the same box that converges,
    then dense Newton on each finer grid up to ``points``, each started from the previous
    grid's solution. Cached like :func:`cached_solve`."""
    import numpy as np
    from dense_line import DenseFailure, DenseLine

    from ehl_multigrid.line import solve_line
    from ehl_multigrid.line.problem import LineProblem

    path = SOLVES / f"{solve_key('line', M, L, 1.0, points, box, solver='dense')}.json"
    rec = read_json(path)
    if rec is not None:
        return rec
    load0, t0, c0 = load_avg(), time.perf_counter(), time.process_time()
    xmin = line_xmin(M, L, box)
    chain, m, sol = [points], points, None
    while m > 65:
        m = (m - 1) // 2 + 1
        sol = solve_line(M, L, points=m, xmin=xmin, estimate=False, raise_on_failure=False, **LINE_TIGHT)
        if sol.success:
            break
        chain.append(m)
    rec = {"solver": "dense", "start_grid": m}
    if sol is None or not sol.success:
        rec.update(status="error", success=False, message="no converged multigrid start grid")
    else:
        pb = LineProblem.from_moes(M, L, xmin=xmin)
        X, P, H0 = sol.X, sol.P, sol.H0
        try:
            its = []
            for n in reversed(chain):
                dl = DenseLine(pb, n)
                d = dl.solve(np.interp(dl.X, X, P), H0)
                X, P, H0 = dl.X, d["P"], d["H0"]
                its.append(d["iterations"])
            rec.update(Hc_venner=d["Hc_venner"], Hm_venner=d["Hm_venner"], status="converged",
                       success=True, message=f"dense Newton on {list(reversed(chain))} from the "
                       f"multigrid solution on {m} points", iterations=its, spread=0.0,
                       max_phi=d["max_phi"], load_error=d["load_error"], xmin=xmin)
        except DenseFailure as exc:
            rec.update(status="error", success=False, message=f"dense Newton failed: {exc}")
    rec.update(contact="line", M=M, L=L, theta=1.0, points=points, box=box, wall_s=time.perf_counter() - t0,
               cpu_s=time.process_time() - c0, load_before=load0, load_after=load_avg())
    write_json(path, rec)
    return rec


def line_reference_solve(M: float, L: float, points: int, box: float = 1.0,
                         dense: bool = True) -> dict[str, Any]:
    """Tight multigrid solve; where it stalls (isoviscous and long-inlet cases on fine grids),
    the dense direct solver up to :data:`DENSE_MAX` points (when ``dense``)."""
    rec = cached_solve("line", M, L, 1.0, points, box, **LINE_TIGHT)
    if usable(rec) or points > DENSE_MAX or not dense:
        return rec
    dense = dense_line_solve(M, L, points, box)
    dense["multigrid"] = {k: rec.get(k) for k in ("status", "message", "Hc_venner", "Hm_venner")}
    return dense


def consecutive_chain(recs: dict[int, dict[str, Any]], max_spread: float = 3e-5) -> list[int]:
    """The longest run of usable grids, each twice as fine as the previous, ending at the
    finest usable grid (coarse to fine)."""
    ns = sorted(n for n, r in recs.items() if usable(r, max_spread))
    if not ns:
        return []
    chain = [ns[-1]]
    while (chain[0] - 1) // 2 + 1 in ns:
        chain.insert(0, (chain[0] - 1) // 2 + 1)
    return chain
