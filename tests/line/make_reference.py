"""Produce tests/line/reference.json: Hc, Hm of the line solver on fine grids.

Run ``python tests/line/make_reference.py`` (about a minute). The regression test compares a
coarse (1025-point) solve against the finest value stored here, with a tolerance of 1.5 times
the coarse-to-finest difference measured when the file was made.
"""

import json
import platform
import time
from pathlib import Path

from ehl_multigrid.line import solve_line
from ehl_multigrid.model.results import package_version

CASES = {"M20_L10": dict(M=20.0, L=10.0)}
GRIDS = [1025, 2049, 4097, 8193]


def main() -> None:
    out = {"produced_by": "tests/line/make_reference.py", "package_version": package_version(),
           "date": time.strftime("%Y-%m-%d"), "python": platform.python_version(),
           "options": "defaults of solve_line (Roelands + Dowson-Higginson, MOES_ONLY_DEFAULTS oil, "
                      "X in [-4.5, 1.5], MLMI, V cycles, tol 1e-5, tol_load 1e-6)", "cases": {}}
    for name, kw in CASES.items():
        rows = {}
        for n in GRIDS:
            s = solve_line(kw["M"], kw["L"], points=n)
            rows[str(n)] = {"Hc": s.Hc, "Hm": s.Hm, "p_spike": s.p_spike, "converged": s.converged}
            print(name, n, rows[str(n)])
        out["cases"][name] = {**kw, "grids": rows, "reference_points": GRIDS[-1]}
    Path(__file__).with_name("reference.json").write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
