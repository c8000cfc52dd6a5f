"""Produce tests/surface/regression_surface.json (run: python tests/surface/make_regression_surface.py).

Statistics of two fixed-seed synthetic maps (512 x 512) analysed with the default chain
(plane removal, no filter). Re-run only when a deliberate change alters the numbers.
"""

from __future__ import annotations

import json
from pathlib import Path

from mixed.surface import analyse_surface, gaussian_random_surface, planted_asperities

KEYS = ("Ra", "Rq", "n", "beta", "sigma_s", "dd", "psi", "n_summits")
CASES = [
    ("gaussian", {"n": 512, "dx": 0.25e-6, "Rq": 30e-9, "corr_length": 1e-6, "seed": 2024}),
    ("planted", {"n": 512, "dx": 0.5e-6, "density": 1e10, "radius": 30e-6, "height_mean": 0.06e-6,
                 "height_std": 0.012e-6, "seed": 2024}),
]


def main() -> None:
    out = []
    for kind, p in CASES:
        if kind == "gaussian":
            hm = gaussian_random_surface(p["n"], p["dx"], p["Rq"], corr_length=p["corr_length"], seed=p["seed"])
        else:
            hm, _ = planted_asperities(p["n"], p["dx"], p["density"], p["radius"], p["height_mean"],
                                       p["height_std"], seed=p["seed"])
        st = analyse_surface(hm).stats
        out.append({"kind": kind, "params": p, "stats": {k: getattr(st, k) for k in KEYS}})
    path = Path(__file__).with_name("regression_surface.json")
    path.write_text(json.dumps({"produced_by": "tests/surface/make_regression_surface.py", "cases": out}, indent=1))
    print(path)


if __name__ == "__main__":
    main()
