"""A fast subset of the extremes matrix (validation/extremes/extremes.py, issue 8 item 5): each
corner must end converged or failed-with-a-clear-message, never wrong (NaN, negative film,
P < 0, friction outside [0, fc], or unconverged returned as converged)."""

import importlib.util
import math
from pathlib import Path

import pytest

from ehl_multigrid.model.errors import ConvergenceError

SCRIPT = Path(__file__).resolve().parents[2] / "validation" / "extremes" / "extremes.py"


@pytest.fixture(scope="module")
def extremes():
    spec = importlib.util.spec_from_file_location("extremes_script", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


EHL = [
    ({"model": "point_ehl", "M": 1.0, "L": 25.0, "theta": 1.0}, 65),
    ({"model": "point_ehl", "M": 5000.0, "L": 0.0, "theta": 1.0}, 65),
    ({"model": "point_ehl", "M": 20.0, "L": 10.0, "theta": 10.0}, 65),
    ({"model": "line_ehl", "M": 1.0, "L": 0.0, "theta": 1.0}, 1025),
    ({"model": "line_ehl", "M": 5000.0, "L": 25.0, "theta": 1.0}, 1025),
]


@pytest.mark.parametrize(("case", "points"), EHL, ids=lambda c: str(c))
def test_ehl_corner_is_converged_or_a_clear_failure(extremes, case, points):
    try:
        verdict, info = extremes.run_ehl(case, points=points)
    except ConvergenceError as exc:  # a clear error is an allowed outcome
        assert "points" in str(exc)
        return
    assert verdict in ("converged", "failed"), info
    if verdict == "failed":
        assert "not converged" in info["message"]


THERMAL = [
    {"model": "thermal", "scene": "appendix_c_line_4240N", "slip": 2.0, "us": 50.0, "pmax": 3.0e9},
    {"model": "thermal", "scene": "appendix_c_line_4240N", "slip": 0.0, "us": 0.01, "pmax": 0.3e9},
    {"model": "thermal", "scene": "appendix_d_point", "slip": 0.05, "us": 0.01, "pmax": 0.3e9},
]


@pytest.mark.parametrize("case", THERMAL, ids=lambda c: f"{c['scene']}-{c['slip']}-{c['us']}-{c['pmax']:.1e}")
def test_thermal_corner_is_never_wrong(extremes, case):
    verdict, info = extremes.run_thermal(case)
    assert verdict != "wrong", info


MIXED = [
    {"model": "mixed", "scene": "page63_line_2000N", "us": 1e-5, "hoil_over_sigma": 0.01, "sigma_s": 1e-9},
    {"model": "mixed", "scene": "page63_line_2000N", "us": 100.0, "hoil_over_sigma": math.inf, "sigma_s": 1e-6},
    {"model": "mixed", "scene": "series_D_disc3_1.93GPa", "us": 100.0, "hoil_over_sigma": 0.01, "sigma_s": 1e-9},
    {"model": "mixed", "scene": "series_D_disc3_1.93GPa", "us": 1e-5, "hoil_over_sigma": 1.0, "sigma_s": 1e-6},
]


@pytest.mark.parametrize("case", MIXED, ids=lambda c: f"{c['scene']}-{c['us']}-{c['hoil_over_sigma']}-{c['sigma_s']}")
def test_mixed_corner_friction_stays_within_bounds(extremes, case):
    verdict, info = extremes.run_mixed(case)
    assert verdict == "converged", info
    assert info["checks"]["friction_in_0_fc"]
