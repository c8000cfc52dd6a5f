"""How starved a line contact the solver reaches: supplies down to 2 % of the flooded flux.

For (M, L) = (20, 10), (100, 10), (50, 5) and supplies of 12, 8, 5, 3 and 2 % of the flooded
flux, ``solve_starved_line`` on its defaults (1025 points, nested root searches on 257, 513,
1025): status, message, meniscus, ``Hc/Hc_ff``, ``rho_c Hc/Hoil - 1`` (the severely starved
limit: 0 when the central film carries the supply), the error estimate, the mass balance and
the wall time.

    python validation/starved/study_edge.py [--label NAME]

Writes ``build/validation/starved/starved_edge_<label>.json`` (default label ``now``).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _paths import out_dir  # noqa: E402

OUT = out_dir("starved")
CASES = [(20.0, 10.0), (100.0, 10.0), (50.0, 5.0)]
FRACTIONS = [0.12, 0.08, 0.05, 0.03, 0.02]


def main() -> None:
    from ehl_multigrid.line import solve_line
    from ehl_multigrid.starved.line import flooded_flux_estimate
    from ehl_multigrid.starved.meniscus import solve_starved_line

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--label", default="now")
    a = ap.parse_args()
    OUT.mkdir(exist_ok=True)
    rows = []
    for M, L in CASES:
        ff = solve_line(M, L, raise_on_failure=False)
        F = flooded_flux_estimate(ff)
        for frac in FRACTIONS:
            t0 = time.perf_counter()
            row = {"M": M, "L": L, "supply_over_flooded_flux": frac}
            try:
                s = solve_starved_line(ff.problem, frac * F, raise_on_failure=False)
                sc = s.scalars
                row.update(status=s.status_name, message=s.message,
                           **{k: float(sc.get(k, math.nan)) for k in (
                               "Hc_ratio", "Hm_ratio", "meniscus_x", "rho_c_Hc_over_hoil", "Hc_error",
                               "Hm_error", "mass_balance_error")})
            except Exception as exc:  # a clear error is an outcome
                row.update(status="error", message=f"{type(exc).__name__}: {exc}".splitlines()[0])
            row["wall_s"] = time.perf_counter() - t0
            rows.append(row)
            print(json.dumps(row), flush=True)
            tmp = OUT / f"starved_edge_{a.label}.json.tmp"
            tmp.write_text(json.dumps({"rows": rows}, indent=1))
            tmp.replace(OUT / f"starved_edge_{a.label}.json")
    print(f"{sum(r['status'] == 'converged' for r in rows)} of {len(rows)} converged")


if __name__ == "__main__":
    main()
