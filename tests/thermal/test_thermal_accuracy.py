"""Accuracy: refining the grid, the error falls at the expected rate, and the default resolution
(appendix C: nx = 80, nz = 20) is within 1 % of the converged friction."""

import json
import math
from pathlib import Path

import pytest

from ehl_multigrid.model.scene import load_scene
from thermal import solve_traction

DATA = json.loads((Path(__file__).parent / "regression_thermal.json").read_text())


def observed_order(f1, f2, f3, ratio=2.0):
    return math.log(abs(f1 - f2) / abs(f2 - f3)) / math.log(ratio)


def test_film_direction_converges_at_second_order(line_hi):
    f = [solve_traction(line_hi, 0.4, nz=nz).force for nz in (10, 20, 40)]
    assert 1.7 < observed_order(*f) < 2.3


def test_default_resolution_within_one_percent_of_fine_grid():
    for case in DATA["cases"]:
        sc = load_scene(case["scene"])
        tp = solve_traction(sc, case["slip"])
        assert tp.force == pytest.approx(case["force"], rel=0.01), case["scene"]
        assert tp.max_temperature_rise == pytest.approx(case["max_temperature_rise"], rel=0.02)


def test_point_slices_converge_and_default_ten_slices_are_within_half_a_percent(point):
    fine = solve_traction(point, 0.5, slices=64, nx=40).force
    cos = [solve_traction(point, 0.5, slices=n, slice_rule="cosine", nx=40).force for n in (8, 16, 32)]
    assert 1.6 < observed_order(*cos) < 2.4
    default = solve_traction(point, 0.5, nx=40)  # thesis: 10 slices, midpoint rule
    assert default.force == pytest.approx(fine, rel=0.005)
