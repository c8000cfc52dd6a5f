"""Starved point contact: moderate starvation of the high-M, low-L chapter-6 contact converges
with the supply conserved, the second coarse-grid rule takes over where the first stops, a
failed solve says so, and ``ehl solve`` routes a point scene with a finite oil layer to the
starved solver (keys, error estimate, planner)."""

from __future__ import annotations

import json
import math

import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.model.scene import Scene, load_scene
from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.starved.point import solve_starved_point

#: first-order flooded central film of (M, L) = (179, 4.17) at 257^2 (the supply unit below)
HC_FF_179 = 0.0609
#: the same for (20, 10) at 257^2
HC_FF_20 = 0.439


@pytest.mark.solver
def test_moderate_starvation_of_the_chapter6_contact_converges_and_conserves_mass():
    # Hoil = 0.8 Hc_ff at 129^2 stopped at max_cycles before the held-point projection
    s = solve_starved_point(problem_from_moes(179.0, 4.17), 0.8 * HC_FF_179, points=129, half=True,
                            raise_on_failure=False)
    assert s.status_name == "converged"
    assert s.extra["mass_balance_error"] < 1e-6
    assert s.scalars["Hc_venner"] < 0.8 * HC_FF_179  # side flow: the centre carries less than the supply


@pytest.mark.slow
@pytest.mark.parametrize("ratio", [1.0, 0.6, 0.1])
def test_chapter6_contact_row_converges_at_257(ratio):
    s = solve_starved_point(problem_from_moes(179.0, 4.17), ratio * HC_FF_179, points=257, half=True,
                            raise_on_failure=False)
    assert s.status_name == "converged"
    assert s.extra["mass_balance_error"] < (2e-6 if ratio >= 1.0 else 1e-6)


@pytest.mark.solver
def test_the_second_coarse_grid_rule_finishes_what_the_first_cannot():
    # (20, 10) at 129^2, Hoil = 0.25 Hc_ff: the default rule stops at a residual of 2.3e-8
    s = solve_starved_point(problem_from_moes(20.0, 10.0), 0.25 * HC_FF_20, points=129, half=True,
                            raise_on_failure=False)
    assert s.status_name == "converged"
    assert any("theta frozen" in a and ": converged" in a for a in s.actions)
    assert s.extra["mass_balance_error"] < 1e-6


@pytest.mark.solver
def test_a_failed_starved_solve_is_reported_as_not_converged():
    s = solve_starved_point(problem_from_moes(179.0, 4.17), 0.8 * HC_FF_179, points=129, half=True,
                            raise_on_failure=False, max_cycles=2)
    assert not s.success and s.status_name != "converged"
    assert "not converged" in s.message


def _starved_point_scene(tmp_path, hoil="20 nm", load_factor=1.0):
    d = load_scene("chapter6_starved_0.5GPa").to_dict()
    d["supply"] = {"hoil": hoil}
    d["operating"]["load"] *= load_factor
    path = tmp_path / "starved_ball.toml"
    path.write_text(Scene.from_dict(d).to_toml())
    return path


@pytest.mark.solver
def test_solve_uses_the_starved_point_solver_for_a_finite_oil_layer(tmp_path, capsys):
    # an eighth of the load (pmax 0.25 GPa, M = 22): 65^2 converges (0.5 GPa, M = 179, needs 129^2)
    scene = _starved_point_scene(tmp_path, load_factor=0.125)
    rc = main(["solve", str(scene), "--points", "65", "--accuracy", "none", "--no-plots", "--json",
               "--out", str(tmp_path / "o")])
    out = json.loads(capsys.readouterr().out)
    assert rc == 0 and out["converged"] and out["solver"] == "starved-fas"
    for key in ("Hc", "Hm", "Hc_flooded", "meniscus_x", "mass_balance_error"):
        assert key in out
    assert out["Hc"] < out["Hc_flooded"] and -1.3 < out["meniscus_x"] < -1.0
    assert out["mass_balance_error"] < 1e-6
    assert "first order" in out["note"]
    assert (tmp_path / "o" / "chapter6_starved_0.5GPa.h5").exists()
    # a failed solve is written and says so (exit 3)
    rc = main(["solve", str(scene), "--points", "65", "--max-cycles", "2", "--accuracy", "none",
               "--no-plots", "--json", "--out", str(tmp_path / "o2")])
    out = json.loads(capsys.readouterr().out)
    assert rc == 3 and out["converged"] is False and out["status"] != "converged"


@pytest.mark.solver
def test_the_starved_point_estimate_judges_the_accuracy(tmp_path):
    from ehl_multigrid.starved import solve_starved_point_scene

    # an eighth of the load (pmax 0.25 GPa, M = 22): 257^2 with its estimate from 129^2 and
    # 65^2 (two grids give no bound); the 20 nm layer is half the flooded film there
    scene = load_scene(_starved_point_scene(tmp_path, load_factor=0.125))
    sol = solve_starved_point_scene(scene, points=257, accuracy=0.5, raise_on_failure=False)
    assert sol.status_name == "converged" and sol.scalars["Hc_ratio"] < 0.8
    budget = sol.error.budget
    assert 0.0 < budget["grid"]["Hc"] < 0.5 and budget["domain"]["Hc"] == 0.0
    assert budget["algebraic"]["Hc"] >= sol.scalars["mass_balance_error"]
    # two grids alone (129^2 from 65^2): no bound, so no accuracy can be confirmed
    strict = solve_starved_point_scene(scene, points=129, accuracy=0.5, raise_on_failure=False,
                                       flooded=False)
    assert strict.status_name == "inaccurate" and not strict.scalars["converged"]
    assert math.isinf(strict.error.budget["grid"]["Hc"])


def test_the_plan_names_the_starved_point_solver(tmp_path):
    from ehl_multigrid.app.plan import make_plan

    dec = make_plan(load_scene(_starved_point_scene(tmp_path))).get("starvation")
    assert dec.include and "Elrod-Adams solver (starved point)" in dec.setting


def test_a_refinement_step_estimates_the_grid_error_from_the_previous_inaccurate_solve():
    """The coarse solve of a refinement step is the previous one, whose own verdict was
    'inaccurate' (its estimate missed the target): its iteration converged, so it still gives
    the grid part (it gave NaN, and ``ehl run`` reported 'errors nan' at 513^2)."""
    from ehl_multigrid.starved.point import starved_point_error

    pb = problem_from_moes(20.0, 10.0)
    coarser, coarse, fine = (solve_starved_point(pb, 0.4 * HC_FF_20, points=n, half=True, raise_on_failure=False)
                             for n in (33, 65, 129))
    assert coarser.status_name == coarse.status_name == fine.status_name == "converged"
    coarse.set_status(6, "short of its target")  # what attach_estimate makes of it
    assert coarse.status_name == "inaccurate"
    est = starved_point_error(fine, coarse, coarser)
    assert 0.0 < est.budget["grid"]["Hc"] < 1.0 and est.Hc < 1.0 and est.Hm < 1.0
