"""Produce reference.json: high-resolution FAS solves of the circular contact at
(M, L) = (20, 10), Roelands + Dowson-Higginson, default domain, W cycles, FFT deformation,
default tolerances (scaled residual 1e-4, load 1e-5), at 257^2, 513^2 and 1025^2, with the Richardson
extrapolation of Hc (observed order from the three grids). Run:
``python tests/point/make_reference.py`` (about a minute on 2 cores)."""

import json
import math
import platform
from pathlib import Path

from ehl_multigrid.point import problem_from_moes, solve_fas
from ehl_multigrid.point.postprocess import film_metrics, full_fields

pb = problem_from_moes(20.0, 10.0)
rows = []
for n in (257, 513, 1025):
    out = solve_fas(pb, points=n)
    Y, P, H = full_fields(out.X, out.Y, out.P, out.H, out.half)
    m = film_metrics(out.X, Y, P, H)
    rows.append({"points": n, "converged": out.report.converged, "Hc": m["Hc_center"] * pb.moes_factor,
                 "Hm": m["Hm"] * pb.moes_factor, "Hc_venner": m["Hc_center"], "Hm_venner": m["Hm"],
                 "p_spike": m["p_spike"], "wall_s": out.report.wall_s})
    print(rows[-1], flush=True)
h1, h2, h3 = (r["Hc"] for r in rows)
p = math.log2(abs(h2 - h1) / abs(h3 - h2))
ext = h3 + (h3 - h2) / (2**p - 1)
ref = {
    "produced_by": "tests/point/make_reference.py (FAS/FMG, W cycles, FFT deformation)",
    "python": platform.python_version(),
    "case": {"M": 20.0, "L": 10.0, "theta": 1.0, "viscosity": "roelands", "density": "dowson-higginson",
             "domain": [-4.5, 1.5, -3.0, 3.0]},
    "grids": rows,
    "observed_order_Hc": p,
    "Hc_extrapolated": ext,
    "Hm_finest": rows[-1]["Hm"],
}
Path(__file__).with_name("reference.json").write_text(json.dumps(ref, indent=1))
print(ref)
