"""(M, L) = (1000, 10) at 513 points, half domain, tol 1e-7: X lines alone against the default
(fine-grid alternation). Prints one line per solve (kept as build/validation/point_floor/m1000_tight.log)."""
from ehl_multigrid.point.solve import solve_point

for alt in (False, None):
    r = solve_point(1000.0, 10.0, points=513, half=True, alternating=alt, estimate=False, tol=1e-7,
                    tol_load=1e-7, max_cycles=20, raise_on_failure=False)
    print("alternating", alt, r.status_name, f"WU {r.work_units:.1f}",
          f"Hc {r.scalars['Hc']:.6f} Hm {r.scalars['Hm']:.6f}",
          "res", " ".join(f"{x:.1e}" for x in r.residual_history[-6:]))
