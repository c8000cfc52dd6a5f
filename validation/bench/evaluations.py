"""CPU time of one point-contact deformation evaluation (``make_deformation("fft", ...)``), one
thread, full and half domain, 17^2 .. 2049^2, and the minor page faults per evaluation (large
temporaries mapped and unmapped on every call show up there). Run it with a source tree on
PYTHONPATH to measure that tree::

    PYTHONPATH=/tmp/old python validation/bench/evaluations.py old
    python validation/bench/evaluations.py new

writes ``build/validation/bench/evaluations_<label>.json``. ``hierarchy N`` instead builds the circular (20, 10)
grid hierarchy on N^2 points and times two film updates (deformation, film, fluid properties)
of the finest grid with a random pressure, with the peak memory (a solve's storage without
solving)::

    python validation/bench/evaluations.py hierarchy 4097
"""

from __future__ import annotations

import json
import resource
import sys
import time
from pathlib import Path

import numba
import numpy as np

from ehl_multigrid.point.deformation import make_deformation

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("bench")


def main(label: str, max_n: int = 2049) -> None:
    numba.set_num_threads(1)
    rows = []
    for half in (False, True):
        for n in (17, 33, 65, 129, 257, 513, 1025, 2049):
            if n > max_n:
                continue
            ny = (n - 1) // 2 + 1 if half else n
            h = 6.0 / (n - 1)
            op = make_deformation("fft", n, ny, h, h, half, 1)
            P = np.random.default_rng(0).random((ny, n))
            out = np.empty_like(P)

            try:
                op(P, out=out)
                call = lambda op=op, P=P, out=out: op(P, out=out)  # noqa: E731
            except TypeError:  # operators without out=
                call = lambda op=op, P=P: op(P)  # noqa: E731
            call()
            reps = max(3, int(2e7 // (n * n)))
            r0 = resource.getrusage(resource.RUSAGE_SELF)
            c0 = time.process_time()
            for _ in range(reps):
                call()
            cpu = (time.process_time() - c0) / reps
            r1 = resource.getrusage(resource.RUSAGE_SELF)
            rows.append({"n": n, "half": half, "operator": type(op).__name__,
                         "cpu_ms": cpu * 1e3, "ns_per_point": cpu / (n * ny) * 1e9,
                         "minor_faults": (r1.ru_minflt - r0.ru_minflt) / reps})
            print(f"{label} n={n} half={half} {type(op).__name__}: {cpu * 1e3:.3f} ms, "
                  f"{rows[-1]['minor_faults']:.0f} minor faults per evaluation", flush=True)
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / f"evaluations_{label}.json").write_text(json.dumps(rows, indent=1))


def hierarchy(n: int, half: bool = False) -> dict:
    from ehl_multigrid.multigrid.options import PointOptions
    from ehl_multigrid.point.fas import PointHierarchy
    from ehl_multigrid.point.problem import problem_from_moes

    def rss() -> float:
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0

    base = rss()
    hz = PointHierarchy(problem_from_moes(20, 10), PointOptions(points=n, half=half, threads=1))
    built = rss()
    hz._initial_guess()
    fine = hz.levels[-1]
    fine.P = np.random.default_rng(0).random(fine.P.shape)
    cpu = []
    for _ in range(2):
        c0 = time.process_time()
        hz.update_film(fine)
        cpu.append(time.process_time() - c0)
    row = {"n": n, "half": half, "base_mb": base, "after_build_mb": built, "peak_mb": rss(),
           "eight_fields_all_levels_mb": sum(lv.P.nbytes for lv in hz.levels) * 8 / 2**20,
           "update_film_cpu_s": cpu}
    print(json.dumps(row))
    return row


if __name__ == "__main__":
    if sys.argv[1] == "hierarchy":
        hierarchy(int(sys.argv[2]))
    else:
        main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 2049)
