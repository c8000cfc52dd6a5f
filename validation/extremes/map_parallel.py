"""Run a map of accuracy_map.py with several case processes at once (resumable).

    python validation/extremes/map_parallel.py --map extremes --contact point --accuracy 0.02 \
        --max-points 2049 --check-max 2049 --tag point2049 --workers 2

Each case runs in its own process with one numba thread (as accuracy_map.py's serial loop);
records are written as they finish, keyed like accuracy_map.py's, so either script resumes
the other's file; a record is reused only when it was computed for the same accuracy, budgets
and (committed) code, so a resumed map never mixes inputs.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import threading
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from accuracy_map import (  # noqa: E402
    OUT,
    case_in_process,
    cases,
    count_classes,
    fit_cases,
    reusable,
    run_inputs,
    save_records,
)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--map", choices=("extremes", "fits"), default="extremes")
    ap.add_argument("--contact", choices=("line", "point"))
    ap.add_argument("--accuracy", type=float, default=0.02)
    ap.add_argument("--max-points", type=int, default=None, help="grid budget (default: the solver's own, 2049 point / 32769 line)")
    ap.add_argument("--check-max", type=int, default=2049)
    ap.add_argument("--guess-check-max", type=int, default=0,
                    help="check grids above --check-max up to this many points are solved from the "
                         "converged result (accuracy_map.from_converged) instead of skipped")
    ap.add_argument("--skipped-in", metavar="FILE",
                    help="only the cases whose check FILE (a map of the same kind) skipped")
    ap.add_argument("--timeout", type=float, default=900.0)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--tag", required=True)
    ap.add_argument("--m-min", type=float, default=None, help="only the cases with M >= this")
    ap.add_argument("--theta", type=float, default=None, help="only the cases of this ellipticity")
    a = ap.parse_args()
    stem = "accuracy_map" if a.map == "extremes" else "fit_map"
    path = OUT / f"{stem}_{a.accuracy:g}_{a.tag}.json"
    todo = cases(False) if a.map == "extremes" else fit_cases(False)
    if a.contact:
        todo = [c for c in todo if c["contact"] == a.contact]
    if a.m_min is not None:
        todo = [c for c in todo if c["M"] >= a.m_min]
    if a.theta is not None:
        todo = [c for c in todo if c["theta"] == a.theta]
    if a.skipped_in:
        old = json.loads(Path(a.skipped_in).read_text())
        skipped = {k for k, rec in old.items() if rec.get("check", {}).get("status") == "skipped"}
        todo = [c for c in todo if json.dumps(c, sort_keys=True) in skipped]
    done = json.loads(path.read_text()) if path.is_file() else {}
    inputs = run_inputs(a.accuracy, a.check_max, a.max_points, a.guess_check_max)
    lock = threading.Lock()
    env = dict(os.environ, NUMBA_NUM_THREADS="1")

    def run(case: dict) -> None:
        rec = {**case_in_process(case, a.accuracy, a.check_max, a.max_points, a.timeout, env,
                                 a.guess_check_max),
               "inputs": inputs}
        with lock:
            done[json.dumps(case, sort_keys=True)] = rec
            save_records(path, done)
            finished = sum(reusable(done, json.dumps(c, sort_keys=True), inputs) for c in todo)
            print(f"{finished}/{len(todo)} {case} {rec['result'].get('status')} -> {rec['class']}", flush=True)

    rest = [c for c in todo if not reusable(done, json.dumps(c, sort_keys=True), inputs)]
    with ThreadPoolExecutor(a.workers) as ex:
        list(ex.map(run, rest))
    print(json.dumps(count_classes(done)))


if __name__ == "__main__":
    main()
