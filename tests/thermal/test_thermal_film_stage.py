"""`ehl run`: where the plan includes thermal EHL for a line contact, the thermal layer's stage
solves the coupled thermal film at the operating point (thermal.film_stage) and the later
stages compute on it; a point contact's coupled solve runs where a third of that reduction
exceeds the tolerance, else it is advised; a failed coupled solve leaves the isothermal film to
the later stages and fails the run."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest

import ehl_multigrid.front as front
from ehl_multigrid.app.mainjob import MainJobOptions, run_main_job
from ehl_multigrid.app.plan import make_plan
from ehl_multigrid.app.stages import RunContext
from ehl_multigrid.model.errors import ConvergenceError
from ehl_multigrid.model.results import load_results
from ehl_multigrid.model.scene import load_scene
from thermal.film_stage import thermal_film_stage

# appendix C at 42400 N, 8 m/s: Gupta's reduction 0.03 at the operating point > 0.02
SCENE = "appendix_c_line_42400N"

pytestmark = [pytest.mark.solver, pytest.mark.xdist_group("thermal_film_stage")]


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out_dir = tmp_path_factory.mktemp("thermal_film")
    out = run_main_job(load_scene(SCENE), MainJobOptions(out_dir=out_dir, plots=False, quiet=True))
    return out, load_results(out["hdf5"])


def test_the_later_stages_compute_on_the_coupled_thermal_film(run):
    out, results = run
    assert out["plan"]["tehl"] == "coupled thermal EHL film (thermal film stage)"
    th, iso = out["thermal_film"], out["film"]
    assert th["converged"] is True and th["status"] == "converged"
    assert max(th["Hc_error"], th["Hm_error"]) <= 0.02
    assert results["thermal_film"].kind == "tehl_line"
    # the inlet heats the oil: a thinner film than the isothermal one of the same grid, and the
    # film stage's isothermal film agrees with that one within both stated errors
    assert th["Hc"] < th["Hc_isothermal"] and th["T_max"] > load_scene(SCENE).T_oil
    assert iso["Hc"] == pytest.approx(th["Hc_isothermal"], rel=iso["Hc_error"] + 0.02)
    # the traction stage's film is the thermal one (resampled onto its own grid)
    assert "coupled thermal EHL pressure and film" in out["traction"]["film_source"]
    assert f"hc = {th['hc'] * 1e9:.4g} nm" in out["traction"]["film_source"]
    np.testing.assert_allclose(results["traction"]["h"].min(), results["thermal_film"]["h"].min(), rtol=0.05)
    # the operating friction's error counts its distance from the coupled solve's own friction
    op = out["traction"]["operating_point"]
    assert op["error_parts"]["coupled"] == abs(op["friction_coefficient"] - th["friction_coefficient"])
    assert op["friction_coefficient_error"] >= op["error_parts"]["coupled"] + op["error_parts"]["grid"]


def test_the_stage_runs_only_where_the_plan_stages_thermal_ehl(tmp_path):
    point = load_scene("default")
    plan = make_plan(point, tolerance=0.02)
    assert plan.includes("tehl") and "--thermal" in plan.get("tehl").setting  # advised, not run
    assert thermal_film_stage(RunContext(point, plan, Path(tmp_path))) is None
    line = load_scene("appendix_c_line_4240N")  # reduction 0.019 at the operating point
    plan = make_plan(line, tolerance=0.02)
    assert not plan.includes("tehl")
    assert thermal_film_stage(RunContext(line, plan, Path(tmp_path))) is None


def test_a_failed_coupled_solve_leaves_the_isothermal_film_and_fails_the_stage(tmp_path, monkeypatch):
    real = front.solve

    def thermal_fails(problem, *, physics="steady", accuracy=0.005, **kw):
        if physics == "thermal":
            return front.failed_solution("thermal", "line", ConvergenceError("injected divergence"), accuracy,
                                         time.perf_counter(), problem)
        return real(problem, physics=physics, accuracy=accuracy, **kw)

    monkeypatch.setattr(front, "solve", thermal_fails)
    scene = load_scene(SCENE)
    out = run_main_job(scene, MainJobOptions(out_dir=tmp_path, fidelity="standard", plots=False, quiet=True))
    th = out["thermal_film"]
    assert th["converged"] is False and "injected divergence" in th["message"]
    assert "thermal_film" not in load_results(out["hdf5"])
    assert out["traction"]["film_source"].startswith("solved EHL pressure and film of the film stage")


def test_beyond_the_coupled_solvers_thermal_loading_the_stage_fails_at_once_without_solving(tmp_path, monkeypatch):
    # page 63 at 2000 N and 50 m/s: thermal loading 3.7, where the coupled line solve ends
    # erratically (a spindle bearing at 6.7 spent the whole 600 s budget)
    def no_solve(*a, **kw):
        raise AssertionError("the coupled solve was tried")

    monkeypatch.setattr(front, "solve", no_solve)
    scene = load_scene("page63_line_2000N")
    scene = scene.with_operating(us=50.0)
    assert scene.thermal_properties()["thermal_loading"] > 3.0
    plan = make_plan(scene, tolerance=0.02)
    out = thermal_film_stage(RunContext(scene, plan, Path(tmp_path)))
    assert out.summary["converged"] is False and out.summary["status"] == "not_tried"
    assert "thermal loading 3.7" in out.summary["message"] and "--thermal" in out.summary["message"]


@pytest.mark.slow
def test_a_fast_point_contact_runs_on_its_coupled_thermal_film(tmp_path):
    # the default ball on flat at 24 m/s: Gupta's reduction 0.09, a third of it above 0.02; the
    # coupled solve found 2.6 % (35 s whole run, 2-core machine)
    sc = load_scene("default").with_operating(us=24.0)
    out = run_main_job(sc, MainJobOptions(out_dir=tmp_path, plots=False, quiet=True))
    results = load_results(out["hdf5"])
    th, iso = out["thermal_film"], out["film"]
    assert out["plan"]["tehl"] == "coupled thermal EHL film (thermal film stage)"
    assert th["converged"] is True and results["thermal_film"].kind == "tehl_point"
    assert th["Hc"] < th["Hc_isothermal"]
    assert iso["Hc"] == pytest.approx(th["Hc_isothermal"], rel=iso["Hc_error"] + 0.02)
    assert f"hc = {th['hc'] * 1e9:.4g} nm" in out["traction"]["film_source"]
