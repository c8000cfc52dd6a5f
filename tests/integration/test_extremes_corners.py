"""A fast subset of the extremes matrix (validation/extremes/extremes.py): each
corner must end converged or failed-with-a-clear-message, never wrong (NaN, negative film,
P < 0, friction outside [0, fc], or unconverged returned as converged)."""

import importlib.util
import math
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "validation" / "extremes" / "extremes.py"


@pytest.fixture(scope="module")
def extremes():
    spec = importlib.util.spec_from_file_location("extremes_script", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


# one pinned outcome per corner (measured with the shared multilevel core): "converged", a
# returned failure whose message names the remedy, or ("no_solution") a returned failure
# without a film (its start failed: Hc is NaN, not a number that could be taken for a film)
EHL = [
    ({"model": "point_ehl", "M": 1.0, "L": 25.0, "theta": 1.0}, 65, "converged", ""),
    ({"model": "point_ehl", "M": 5000.0, "L": 0.0, "theta": 1.0}, 65, "failed", "use points >= 513"),
    ({"model": "point_ehl", "M": 20.0, "L": 10.0, "theta": 10.0}, 65, "failed", "use points >= 513"),
    ({"model": "line_ehl", "M": 1.0, "L": 0.0, "theta": 1.0}, 1025, "converged", ""),
    ({"model": "line_ehl", "M": 5000.0, "L": 25.0, "theta": 1.0}, 1025, "no_solution",
     "not positive on the 1025-point start grid"),
]


@pytest.mark.parametrize(("case", "points", "outcome", "says"), EHL, ids=lambda c: str(c))
def test_ehl_corner_has_its_measured_outcome(extremes, case, points, outcome, says):
    verdict, info = extremes.run_ehl(case, points=points)
    if outcome == "no_solution":
        assert info["converged"] is False and not math.isfinite(info["Hc"]), info
        assert says in info["message"]
        return
    assert verdict == outcome, info
    assert says in info["message"]
    if outcome == "converged":
        assert all(info["checks"].values()), info["checks"]


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
