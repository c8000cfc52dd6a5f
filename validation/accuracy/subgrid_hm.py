"""The minimum film of point contacts taken between the nodes (docs/accuracy.md, "Extrapolated
films"): does the sub-grid minimum converge more regularly than the nodal one?

For each case, converged full-domain solves on the default box at successive grids (tolerance
1e-7, load 1e-8): Hm as the smallest nodal film, and as the package's sub-grid minimum
(``point.postprocess.subgrid_min_film``: the minimum of the quadratic fitted to the 3 x 3 nodes
around it, where it lies within one cell of the node).
Reported per definition: the films, the ratios of successive differences and whether the
package's second-order extrapolation test (``multigrid.accuracy.extrapolated``: the last two
ratios in [2^1.5, 2^2.5]) passes on the finest four grids.

    python validation/accuracy/subgrid_hm.py [--quick]

writes ``build/validation/accuracy/subgrid_hm.json``.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

from ehl_multigrid.multigrid.accuracy import extrapolated  # noqa: E402
from ehl_multigrid.point.postprocess import subgrid_min_film  # noqa: E402
from ehl_multigrid.point.problem import problem_from_moes  # noqa: E402
from ehl_multigrid.point.solve import solve_fas  # noqa: E402

OUT = out_dir("accuracy")
#: (M, L, theta, grids)
CASES = ((20.0, 10.0, 1.0, (129, 257, 513, 1025)), (100.0, 10.0, 1.0, (129, 257, 513, 1025)),
         (20.0, 0.0, 1.0, (129, 257, 513, 1025)), (100.0, 20.0, 1.0, (129, 257, 513, 1025)),
         (20.0, 10.0, 4.0, (257, 513, 1025, 2049)), (20.0, 10.0, 0.25, (129, 257, 513, 1025)))


def ratios(v: list[float]) -> list[float]:
    d = np.diff(v)
    return [float(a / b) if b != 0.0 else float("nan") for a, b in zip(d, d[1:], strict=False)]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="the first case only")
    a = ap.parse_args(argv)
    out = []
    for M, L, theta, grids in CASES[:1] if a.quick else CASES:
        pb = problem_from_moes(M, L, theta)
        nodal, sub, status = [], [], []
        t0 = time.perf_counter()
        for n in grids:
            r = solve_fas(pb, points=n, half=False, tol=1e-7, tol_load=1e-8, max_cycles=60,
                          raise_on_failure=False)
            status.append(r.status_name)
            h_node, h_sub = float(r.H.min()), subgrid_min_film(r.H, half=False)
            nodal.append(h_node)
            sub.append(h_sub)
        row = {"M": M, "L": L, "theta": theta, "grids": list(grids), "status": status,
               "Hm_nodal": nodal, "Hm_subgrid": sub, "ratios_nodal": ratios(nodal),
               "ratios_subgrid": ratios(sub), "extrapolates_nodal": extrapolated(nodal) is not None,
               "extrapolates_subgrid": extrapolated(sub) is not None, "wall_s": time.perf_counter() - t0}
        print(json.dumps({k: row[k] for k in ("M", "L", "theta", "status", "ratios_nodal", "ratios_subgrid",
                                              "extrapolates_nodal", "extrapolates_subgrid")}), flush=True)
        out.append(row)
    name = "subgrid_hm" + ("_quick" if a.quick else "")
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / f"{name}.json").write_text(json.dumps(out, indent=1))
    print(f"wrote {OUT / name}.json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
