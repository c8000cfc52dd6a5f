"""Regression: pinned numbers of stored high-resolution runs of this code
(regression_thermal.json, written by validation/thermal/make_regression_data.py)."""

import json
from pathlib import Path

import pytest

from ehl_multigrid.model.scene import load_scene
from thermal import solve_traction

DATA = json.loads((Path(__file__).parent / "regression_thermal.json").read_text())


@pytest.mark.parametrize("case", DATA["cases"], ids=lambda c: f"{c['scene']}-S{c['slip']}")
def test_high_resolution_results_are_unchanged(case):
    kw = {k: case[k] for k in ("nx", "nz", "slices") if k in case}
    tp = solve_traction(load_scene(case["scene"]), case["slip"], **kw)
    assert tp.converged == case["converged"]
    assert tp.force == pytest.approx(case["force"], rel=1e-5)
    assert tp.max_temperature_rise == pytest.approx(case["max_temperature_rise"], rel=1e-4)
    assert tp.mean_temperature_rise == pytest.approx(case["mean_temperature_rise"], rel=1e-4)
