"""Regression: isothermal Stribeck numbers pinned from a stored run of this code
(regression_stribeck.json, produced by make_regression_stribeck.py). Accuracy is tested
elsewhere (Table 4.1, the equations at the solution, tolerance refinement); this only
guards against unintended changes."""

import json
from pathlib import Path

import numpy as np
import pytest

from ehl_multigrid.model.scene import load_scene
from mixed.stribeck import stribeck_curve, stribeck_options

STORED = json.loads(Path(__file__).with_name("regression_stribeck.json").read_text())


@pytest.mark.parametrize("case", STORED["cases"], ids=lambda c: f"{c['scene']}-{c['hoil_over_sigma']}")
def test_stribeck_curve_matches_the_stored_run(case):
    sc = load_scene(case["scene"])
    hos = case["hoil_over_sigma"]
    hoil = None if hos is None else hos * sc.roughness.Rq
    c = stribeck_curve(sc, np.array(STORED["us"]), hoil=hoil,
                       options=stribeck_options(sc, xtol=STORED["xtol"]), transitions=False)
    assert np.allclose(c.friction.coefficient, case["friction_coefficient"], rtol=1e-9, atol=0)
    assert np.allclose(c.sharing.gamma1, case["gamma1"], rtol=1e-9, atol=0)
    assert np.allclose(c.sharing.hfr, case["hfr"], rtol=1e-9, atol=0)
    assert np.allclose(c.sharing.hss, case["hss"], rtol=1e-9, atol=1e-20)
