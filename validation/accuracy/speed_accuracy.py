"""Time against requested accuracy: ``solve_line(M, L, accuracy=a)`` and
``solve_point(M, L, accuracy=a)`` at (M, L) = (20, 10), (100, 10), (1000, 10) for
a = 5 %, 1 %, 0.5 %, 0.1 %, 0.05 %. Per run: wall and CPU time, the achieved estimate, the
true error against the references of references.py, the grids and boxes the refinement used
(``sol.extra['refinements']``) and the status.

Each run is a fresh (spawned) child process -- a forked child of a process that has run the
point solver's OpenMP kernels is killed by the OpenMP runtime -- that first loads the compiled
kernels with a small solve, then runs the timed solve; it is stopped when the timed solve has
used more than LIMIT_CPU_S seconds of CPU time (CPU rather than wall time, so the limit does
not depend on what else the shared machine runs). A stopped run, and every tighter accuracy
of the same contact and (M, L), is recorded as skipped with the reason.

    python validation/accuracy/speed_accuracy.py [--contact line] [--limit-cpu 600]
    # writes build/validation/accuracy/speed_accuracy.json|png
"""

from __future__ import annotations

import math
import multiprocessing as mp
import os
import time
from typing import Any

from common import OUT, code_version, load_avg, nan, read_json, write_json
from references import reference
from tqdm import tqdm

ACCURACIES = (0.05, 0.01, 0.005, 0.001, 0.0005)
POINTS_ML = ((20.0, 10.0), (100.0, 10.0), (1000.0, 10.0))
LIMIT_CPU_S = 120.0
LIMIT_WALL_S = 600.0
PATH = OUT / "speed_accuracy.json"


def _cpu_of(pid: int) -> float:
    """User + system CPU seconds of a process (all its threads), from /proc."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return math.nan


def _child(contact: str, M: float, L: float, accuracy: float, q: Any) -> None:
    from ehl_multigrid.line import solve_line
    from ehl_multigrid.point import solve_point

    warm_up(contact)
    q.put({"started_cpu": _cpu_of(os.getpid())})
    t0, c0 = time.perf_counter(), time.process_time()
    try:
        if contact == "line":
            sol = solve_line(M, L, accuracy=accuracy, raise_on_failure=False)
        else:
            sol = solve_point(M, L, accuracy=accuracy)
        e = sol.error
        out = {"Hc_venner": sol.scalars["Hc_venner"], "Hm_venner": sol.scalars["Hm_venner"],
               "Hc_error": nan(sol.scalars.get("Hc_error")), "Hm_error": nan(sol.scalars.get("Hm_error")),
               "status": sol.status_name, "success": bool(sol.success), "message": sol.message,
               "refinements": sol.extra.get("refinements"), "budget": e.budget if e is not None else None,
               "points": int(sol.X.shape[0]), "half": bool(getattr(sol, "half", False))}
    except Exception as exc:  # noqa: BLE001 -- recorded
        out = {"status": "error", "success": False, "message": f"{type(exc).__name__}: {exc}"}
    out.update(wall_s=time.perf_counter() - t0, cpu_s=time.process_time() - c0)
    q.put(out)


def run_limited(contact: str, M: float, L: float, accuracy: float) -> dict[str, Any]:
    ctx = mp.get_context("spawn")
    q = ctx.Queue()
    p = ctx.Process(target=_child, args=(contact, M, L, accuracy, q))
    load0, t0 = load_avg(), time.perf_counter()
    p.start()
    reason = ""
    out: dict[str, Any] | None = None
    cpu0 = math.inf  # CPU used by the start and warm-up, known once the child reports it
    while True:
        try:
            msg = q.get(timeout=1.0)
            if "started_cpu" in msg:
                cpu0, t0 = msg["started_cpu"], time.perf_counter()
                continue
            out = msg
            break
        except Exception:  # noqa: BLE001 -- queue.Empty: still running
            pass
        cpu = _cpu_of(p.pid) - cpu0
        wall = time.perf_counter() - t0
        if cpu > LIMIT_CPU_S or wall > LIMIT_WALL_S:
            reason = (f"stopped after {cpu:.0f} s CPU / {wall:.0f} s wall "
                      f"(limit {LIMIT_CPU_S:g} s CPU, {LIMIT_WALL_S:g} s wall)")
            p.kill()
            break
        if not p.is_alive() and q.empty():
            reason = f"the solve process died (exit code {p.exitcode})"
            break
    p.join()
    if out is None:
        out = {"status": "skipped", "success": False, "message": reason,
               "wall_s": time.perf_counter() - t0, "cpu_s": math.nan}
    out.update(load_before=load0, load_after=load_avg())
    return out


def warm_up(contact: str) -> None:
    """Load (or compile) the contact's numba kernels with a small solve, outside the timing."""
    from ehl_multigrid.line import solve_line
    from ehl_multigrid.point import solve_point

    if contact == "line":
        solve_line(20, 10, points=257)
    else:
        solve_point(20, 10, points=129, half=True)


def plot(rows: list[dict[str, Any]], path) -> None:
    from matplotlib.figure import Figure

    marker = {"converged": "o", "inaccurate": "s"}
    fig = Figure(figsize=(11, 4.6))
    axes = fig.subplots(1, 2)
    for ax, contact in zip(axes, ("line", "point"), strict=True):
        for (M, L), col in zip(POINTS_ML, ("C0", "C1", "C2"), strict=True):
            rr = [r for r in rows if r["contact"] == contact and r["M"] == M and r["L"] == L
                  and math.isfinite(nan(r.get("wall_s"))) and r.get("status") != "skipped"]
            ax.plot([r["accuracy"] for r in rr], [r["wall_s"] for r in rr], "-", color=col, lw=1,
                    label=f"(M, L) = ({M:g}, {L:g})")
            for r in rr:
                # met beyond doubt: the true error plus the reference's own uncertainty
                met = r.get("true_max") is not None and r["true_max"] + nan(r.get("ref_unc")) <= r["accuracy"]
                ax.plot(r["accuracy"], r["wall_s"], marker.get(r["status"], "v"), color=col, ms=7,
                        mfc=col if met else "none")
            sk = [r["accuracy"] for r in rows if r["contact"] == contact and r["M"] == M
                  and r["L"] == L and r.get("status") == "skipped"]
            if sk:
                ax.plot(sk, [LIMIT_CPU_S] * len(sk), "x", color=col, ms=8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.invert_xaxis()
        ax.set_xlabel("requested accuracy (relative error of Hc and Hm)")
        ax.set_ylabel("wall time [s] (shared 2-core machine, 1 thread)")
        ax.set_title(f"{contact} contact", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("o converged, square: inaccurate (estimate above the request), v: failed, x: over the "
                 "time limit; filled: the true error meets the request beyond the reference's uncertainty",
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=130)


def main() -> None:
    global LIMIT_CPU_S, LIMIT_WALL_S
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--contact", choices=("line", "point", "all"), default="all",
                    help="re-run the records of this contact only (the others are kept as stored)")
    ap.add_argument("--limit-cpu", type=float, default=LIMIT_CPU_S,
                    help=f"CPU seconds a timed solve may use (default {LIMIT_CPU_S:g}; the point "
                         f"solver's 4097-point budget needs about 600)")
    ap.add_argument("--limit-wall", type=float, default=LIMIT_WALL_S,
                    help=f"wall seconds a timed solve may use (default {LIMIT_WALL_S:g})")
    args = ap.parse_args()
    LIMIT_CPU_S, LIMIT_WALL_S = args.limit_cpu, args.limit_wall
    contacts = ("line", "point") if args.contact == "all" else (args.contact,)
    data = read_json(PATH) or {}
    todo = [(c, M, L, a) for c in contacts for M, L in POINTS_ML for a in ACCURACIES]
    bar = tqdm(todo, desc="speed-accuracy")
    for contact, M, L, a in bar:
        key = f"{contact}_M{M:g}_L{L:g}_a{a:g}"
        bar.set_postfix_str(key)
        if key in data and data[key].get("code") == code_version() and not (
                data[key].get("status") == "skipped" and data[key].get("limit_cpu_s", 120.0) < LIMIT_CPU_S):
            continue
        looser = [data.get(f"{contact}_M{M:g}_L{L:g}_a{b:g}") for b in ACCURACIES if b > a]
        if any(r and r.get("status") == "skipped" and r.get("code") == code_version()
               and r.get("limit_cpu_s", 120.0) >= LIMIT_CPU_S for r in looser):
            row = {"status": "skipped", "success": False, "wall_s": math.nan,
                   "message": "a looser accuracy of this case already exceeded the time limit"}
        else:
            row = run_limited(contact, M, L, a)
        row.update(contact=contact, M=M, L=L, accuracy=a, code=code_version(), limit_cpu_s=LIMIT_CPU_S)
        ref = reference(contact, M, L, 1.0)
        if ref.get("ok") and row.get("Hc_venner") is not None:
            row["Hc_ref"], row["Hm_ref"] = ref["Hc_ref"], ref["Hm_ref"]
            row["ref_unc"] = max(ref["Hc_unc"], ref["Hm_unc"])
            row["Hc_true"] = row["Hc_venner"] / ref["Hc_ref"] - 1.0
            row["Hm_true"] = row["Hm_venner"] / ref["Hm_ref"] - 1.0
            row["true_max"] = max(abs(row["Hc_true"]), abs(row["Hm_true"]))
        data[key] = row
        write_json(PATH, data)
    rows = list(data.values())
    plot(rows, OUT / "speed_accuracy.png")
    print("| contact | (M, L) | requested | status | wall s | CPU s | est Hc, Hm | true Hc, Hm | solves (points, box, tol) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        steps = ", ".join(f"({s['points']}, {s['box']:g}, {s['tol']:g})" for s in (r.get("refinements") or []))
        est = (f"{100 * r['Hc_error']:.3g} %, {100 * r['Hm_error']:.3g} %"
               if r.get("Hc_error") is not None else "-")
        tru = (f"{100 * r['Hc_true']:+.3g} %, {100 * r['Hm_true']:+.3g} %"
               if r.get("Hc_true") is not None else "-")
        print(f"| {r['contact']} | ({r['M']:g}, {r['L']:g}) | {100 * r['accuracy']:g} % | {r['status']} | "
              f"{nan(r.get('wall_s')):.3g} | {nan(r.get('cpu_s')):.3g} | {est} | {tru} | {steps or r.get('message', '')[:80]} |")


if __name__ == "__main__":
    main()
