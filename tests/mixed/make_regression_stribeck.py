"""Produce regression_stribeck.json: pinned isothermal Stribeck numbers of this code.

Run from the repository root: ``python tests/mixed/make_regression_stribeck.py``. Settings:
12 log-spaced sum velocities 1e-3..10 m/s, xtol = 1e-13 on ln(gamma1 - 1), flooded and one
starved case (hoil = 1 Rq) for the chapter-6 scene. Regenerate only when the model changes on
purpose, and say why in the commit.
"""

import json
from pathlib import Path

import numpy as np

from ehl_multigrid.model.scene import load_scene
from mixed.stribeck import stribeck_curve, stribeck_options

CASES = [("page63_line_2000N", None), ("series_C_disc3_1.93GPa", None), ("chapter6_starved_1.93GPa", 1.0)]


def compute():
    us = np.geomspace(1e-3, 10.0, 12)
    out = {"us": us.tolist(), "xtol": 1e-13, "cases": []}
    for name, hos in CASES:
        sc = load_scene(name)
        hoil = None if hos is None else hos * sc.roughness.Rq
        c = stribeck_curve(sc, us, hoil=hoil, options=stribeck_options(sc, xtol=1e-13), transitions=False)
        out["cases"].append({
            "scene": name, "hoil_over_sigma": hos,
            "friction_coefficient": c.friction.coefficient.tolist(),
            "gamma1": c.sharing.gamma1.tolist(),
            "hfr": c.sharing.hfr.tolist(),
            "hss": c.sharing.hss.tolist(),
        })
    return out


if __name__ == "__main__":
    path = Path(__file__).with_name("regression_stribeck.json")
    path.write_text(json.dumps(compute(), indent=1))
    print(f"wrote {path}")
