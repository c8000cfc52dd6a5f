
"""``ehl solve`` and ``ehl run`` on a line scene with a finite ``[supply] hoil``: the
mass-conserving starved solver, its keys, and the planner naming it."""

import json

import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.model.scene import Scene, load_scene


def _starved_scene_file(tmp_path, hoil="0.15 um", points=None):
    d = load_scene("roller_bearing_inner_race").to_dict()
    d["supply"] = {"hoil": hoil}
    if points is not None:  # the scene's grid: kept and judged, not refined
        d["solver"] = {"ehl": {"points": points}}
    path = tmp_path / "starved_roller.toml"
    path.write_text(Scene.from_dict(d).to_toml())
    return path


def test_solve_uses_the_starved_solver_when_the_scene_supplies_a_finite_oil_layer(tmp_path, capsys):
    scene = _starved_scene_file(tmp_path)
    # an explicit grid judged on its iteration alone (the estimate needs the refinement sequence)
    rc = main(["solve", str(scene), "--points", "129", "--accuracy", "none", "--no-plots", "--json",
               "--out", str(tmp_path / "o")])
    out = json.loads(capsys.readouterr().out)
    assert rc == 0 and out["converged"]
    for key in ("Hc", "Hm", "Hc_flooded", "meniscus_x", "mass_balance_error"):
        assert key in out
    assert out["Hc"] < out["Hc_flooded"] and out["meniscus_x"] > -4.0
    assert abs(out["mass_balance_error"]) < 1e-6
    # the film carries what the supply brings (severe-starvation limit of rolling)
    assert abs(out["rho_c_Hc_over_hoil"] - 1.0) < 1e-6
    assert (tmp_path / "o" / "roller_bearing_inner_race.h5").exists()


def test_the_plan_names_the_starved_solver_for_a_starved_line_scene(tmp_path):
    from ehl_multigrid.app.plan import make_plan

    dec = make_plan(load_scene(_starved_scene_file(tmp_path))).get("starvation")
    assert dec.include and "Elrod-Adams" in dec.setting
    flooded = make_plan(load_scene("roller_bearing_inner_race")).get("starvation")
    assert not flooded.include


@pytest.mark.solver
def test_a_time_budget_stops_the_refinement_of_a_starved_solve(tmp_path, capsys):
    # 1025 points (the starved line's start) estimate Hm at 0.13 %: 0.1 % needs the next grid,
    # predicted to take longer than what is left of 0.5 s
    d = load_scene("page63_line_500N").to_dict()
    d["supply"] = {"hoil": 1.5e-8}
    path = tmp_path / "starved_500N.toml"
    path.write_text(Scene.from_dict(d).to_toml())
    rc = main(["solve", str(path), "--accuracy", "0.001", "--time-budget", "0.5", "--no-plots", "--json",
               "--out", str(tmp_path / "o")])
    out = json.loads(capsys.readouterr().out)
    assert rc == 3 and out["status"] == "inaccurate" and out["points"] == 1025
    assert "budget" in out["message"] and "0.5 s" in out["message"]
