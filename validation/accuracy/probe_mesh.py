"""How the box change the domain probes measure depends on the probe mesh (docs/accuracy.md,
"Domain error"): can the probes of contacts whose probe mesh is held at the solver's minimum
grid (narrow and wide ellipses, high M) run on a coarser mesh?

For each case, the relative changes of Hc and Hm from the default box to twice it (``d2``) and
from twice to four times (``d4``), each pair on the same mesh, measured on meshes of 65 to 513
points per default box (film and load tolerance 1e-4, as the box-series probes:
``point.solve.SERIES_FILM_TOL``), with the status, work units and seconds of each probe. The
finest mesh is the reference for the others: a coarser mesh qualifies for the probes where its
changes stay within the fixed factor's margin of the finest one's.

    python validation/accuracy/probe_mesh.py [--quick]

writes ``build/validation/accuracy/probe_mesh.json``.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

from ehl_multigrid.multigrid.options import PointOptions  # noqa: E402
from ehl_multigrid.point.problem import default_domain, min_points, problem_from_moes  # noqa: E402
from ehl_multigrid.point.solve import SERIES_FILM_TOL, solve_fas  # noqa: E402

OUT = out_dir("accuracy")
#: (M, L, theta, meshes: points per default box)
CASES = ((50.0, 10.0, 3.0, (65, 129, 257, 513)), (20.0, 10.0, 4.0, (65, 129, 257, 513)),
         (50.0, 10.0, 0.3, (65, 129, 257)), (100.0, 10.0, 1.0, (65, 129, 257)),
         (20.0, 10.0, 1.0, (65, 129, 257)))


def films(pb, n: int, box: float) -> dict:
    x0, x1, y = default_domain(pb)
    t0 = time.perf_counter()
    r = solve_fas(pb, PointOptions(points=int(round((n - 1) * box)) + 1, half=True, xmin=box * x0,
                                   xmax=box * x1, ymax=box * y, film_tol=SERIES_FILM_TOL,
                                   tol_load=SERIES_FILM_TOL, raise_on_failure=False))
    return {"status": r.status_name, "Hc": float(r.scalars.get("Hc_venner", float("nan"))),
            "Hm": float(r.scalars.get("Hm_venner", float("nan"))), "work_units": float(r.work_units),
            "wall_s": time.perf_counter() - t0}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="the first case on its two coarsest meshes")
    a = ap.parse_args(argv)
    out = []
    for M, L, theta, meshes in CASES[:1] if a.quick else CASES:
        pb = problem_from_moes(M, L, theta)
        rows = []
        for n in meshes[:2] if a.quick else meshes:
            f = {b: films(pb, n, b) for b in (1.0, 2.0, 4.0)}
            row = {"mesh": n, "probes": {str(b): v for b, v in f.items()}}
            for k in ("Hc", "Hm"):
                row[f"d2_{k}"] = f[2.0][k] / f[1.0][k] - 1.0
                row[f"d4_{k}"] = f[4.0][k] / f[2.0][k] - 1.0
            rows.append(row)
            print(json.dumps({"M": M, "L": L, "theta": theta, "mesh": n,
                              **{k: row[k] for k in ("d2_Hc", "d2_Hm", "d4_Hc", "d4_Hm")},
                              "status": [v["status"] for v in f.values()],
                              "wall_s": [round(v["wall_s"], 2) for v in f.values()]}), flush=True)
        out.append({"M": M, "L": L, "theta": theta, "b_over_a": pb.b_over_a,
                    "min_points": min_points(pb.M, pb.b_over_a), "rows": rows})
        OUT.mkdir(parents=True, exist_ok=True)
        name = "probe_mesh" + ("_quick" if a.quick else "")
        (OUT / f"{name}.json").write_text(json.dumps(out, indent=1))
    print(f"wrote {OUT / name}.json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
