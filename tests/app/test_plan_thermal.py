"""The traction stage of ``ehl run`` chooses its thermal model from the slips it sweeps, not
from the planner's decision at the operating slip, says which and why, and reports the
friction at the scene's own slip with its error.

The issue: the 6205 bearing runs in pure rolling, the planner switched the thermal model off
(no slip, no heat) and the traction curve then swept to 100 % slip isothermally (f 0.057 with
a 0 K rise)."""

from pathlib import Path

import pytest

from ehl_multigrid.app.plan import make_plan
from ehl_multigrid.app.stages import RunContext
from ehl_multigrid.model.scene import Scene, load_scene

pytest.importorskip("thermal.stage")

from thermal.options import ThermalOptions  # noqa: E402
from thermal.stage import finer, traction_stage  # noqa: E402
from thermal.traction import solve_traction  # noqa: E402


def run_stage(scene, tmp_path: Path, fidelity: str = "fast"):
    plan = make_plan(scene, fidelity=fidelity)
    ctx = RunContext(scene, plan, tmp_path, plots=False, progress=False)  # no film stage: Hertz + fit
    return plan, traction_stage(ctx)


def test_the_plans_thermal_decision_says_it_holds_at_the_operating_slip():
    dec = make_plan(load_scene("bearing_6205_inner_race"), fidelity="fast").get("thermal")
    assert not dec.include
    assert "operating" in dec.reason and "traction curve" in dec.reason


def test_pure_rolling_6205_traction_stage_uses_the_thermal_model_for_its_high_slips(tmp_path):
    sc = load_scene("bearing_6205_inner_race")
    assert sc.slip == 0.0
    plan, out = run_stage(sc, tmp_path)
    s = out.summary
    assert s["thermal"] is True and out.result.scalars["thermal"]
    model = s["thermal_model"]
    # decided at the largest slip (swept and operating), by the thermal model's own heating there
    assert model["slip"] == max(s["slip"]) == 1.0
    assert model["max_temperature_rise"] > 10.0 and model["relative_change"] > plan.tolerance
    assert s["max_temperature_rise"][-1] == pytest.approx(model["max_temperature_rise"], rel=1e-9)
    assert s["friction_coefficient"][-1] == pytest.approx(model["friction_coefficient_thermal"], rel=1e-9)
    assert s["friction_coefficient"][-1] < 0.9 * model["friction_coefficient_isothermal"]
    # the report says which model and why, and the stage notes the difference from the plan's decision
    assert "thermal model because" in out.text and "K" in out.text
    assert any("traction curve" in n and "thermal" in n for n in out.notes) and not plan.notes


def test_traction_stage_reports_the_friction_at_the_operating_slip_with_an_error_that_covers_it(tmp_path):
    sc = load_scene("appendix_c_line_42400N").with_operating(slip=0.3)
    _, out = run_stage(sc, tmp_path)
    s = out.summary
    op = s["operating_point"]
    assert s["operating_slip"] == sc.slip != 0.0
    assert out.result.scalars["friction_coefficient_at_operating_slip"] == s["friction_coefficient_at_operating_slip"]
    assert 0.0 < op["friction_coefficient_error"] < 0.1 * abs(op["friction_coefficient"])
    assert f"At the operating slip {sc.slip:g}" in out.text
    # the error estimate covers the difference from a solve twice as fine again
    opts = ThermalOptions.for_fidelity(sc, "fast", thermal=s["thermal"])
    ref = solve_traction(sc, sc.slip, options=finer(finer(opts)))
    assert abs(op["friction_coefficient"] - ref.coefficient) <= op["friction_coefficient_error"]


def test_a_scene_that_sets_the_thermal_switch_keeps_it(tmp_path):
    raw = load_scene("bearing_6205_inner_race").to_dict()
    raw.setdefault("solver", {})["thermal"] = {"thermal": False}
    from ehl_multigrid.model.scene import Scene

    _, out = run_stage(Scene.from_dict(raw), tmp_path)
    assert out.summary["thermal"] is False and "[solver.thermal]" in out.summary["thermal_model"]["reason"]


def without_ranges(scene: Scene) -> Scene:
    d = scene.to_dict()
    d.pop("ranges", None)
    return Scene.from_dict(d)


@pytest.mark.parametrize(("slip", "end"), [(0.0, 1.0), (0.3, 1.0), (-0.5, -1.0), (2.0, 2.0), (-1.5, -1.5)])
def test_the_default_traction_sweep_reaches_the_operating_slip(slip, end):
    from thermal.traction import default_slips

    s = default_slips(without_ranges(load_scene("appendix_c_line_4240N").with_operating(slip=slip)))
    assert s[0] == 0.0 and s[-1] == pytest.approx(end) and len(s) == 21
    assert min(s) <= slip <= max(s)


def test_a_sliding_scene_beyond_the_default_sweep_decides_its_model_at_its_own_slip(tmp_path):
    # a ball on a flat at rest (HFRR, SRV) slides purely: S = 2; the sweep used to stop at 1,
    # and the operating friction took the model and its error from there
    sc = without_ranges(load_scene("appendix_c_line_4240N").with_operating(slip=2.0))
    _, out = run_stage(sc, tmp_path)
    s = out.summary
    assert max(s["slip"]) == pytest.approx(2.0) and s["thermal_model"]["slip"] == pytest.approx(2.0)
    assert s["operating_slip"] == pytest.approx(2.0)


def test_a_slip_range_short_of_the_operating_slip_still_decides_the_model_there(tmp_path):
    d = load_scene("appendix_c_line_4240N").with_operating(slip=0.8).to_dict()
    d["ranges"] = {"slip": [0.0, 0.1, 0.2]}
    sc = Scene.from_dict(d)
    _, out = run_stage(sc, tmp_path)
    s = out.summary
    assert max(s["slip"]) == pytest.approx(0.2)
    assert s["thermal_model"]["slip"] == pytest.approx(0.8)


def test_a_point_contact_with_a_large_thermal_film_reduction_is_solved_coupled_in_the_main_job():
    from ehl_multigrid.app.plan import TEHL_POINT_FRACTION
    from ehl_multigrid.app.stages import TEHL_STAGED

    fast = make_plan(load_scene("default").with_operating(us=24.0)).get("tehl")
    assert fast.include and fast.setting == TEHL_STAGED and TEHL_POINT_FRACTION * fast.estimate > fast.threshold
    # the built-in default scene: Gupta's reduction above the tolerance, a third of it below:
    # advised only
    slow = make_plan(load_scene("default")).get("tehl")
    assert slow.include and slow.setting != TEHL_STAGED and "advised" in slow.setting
    assert TEHL_POINT_FRACTION * slow.estimate <= slow.threshold
