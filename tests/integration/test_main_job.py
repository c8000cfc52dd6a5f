"""`ehl run`: the planned chain end to end, one HDF5 with every stage, and a report."""

import json

import numpy as np
import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.model.results import load_results
from ehl_multigrid.model.scene import load_scene


@pytest.mark.solver
def test_main_job_on_a_rough_line_contact_runs_film_traction_and_stribeck(capsys, tmp_path):
    # no figures: the stages' plots are tests/app/test_plots_backend.py's
    assert main(["run", "page63_line_2000N", "--fidelity", "fast", "--out", str(tmp_path), "--json", "--no-plots"]) == 0
    out = json.loads(capsys.readouterr().out)
    results = load_results(out["hdf5"])
    assert set(results) == {"film", "traction", "stribeck"}
    film = results["film"]
    assert film.kind == "ehl_line" and film.scalars["converged"] is True
    # the stored plan says why the solver was used
    assert film.meta["plan"]["decisions"][0]["model"] == "film"
    # the solver's central film is below the Moes fit (Roelands + Dowson-Higginson against Barus-type fits)
    assert film.scalars["hc"] < load_scene("page63_line_2000N").central_film_fit()[1]
    assert results["stribeck"].scene.name == "page63_line_2000N"
    report = (tmp_path / "page63_line_2000N_report.md").read_text()
    assert "What was modelled and why" in report and "## stribeck" in report
    # a line contact's grid has points along X only
    assert f"on {film.scalars['points']} points along X" in report
    assert out["stribeck"]["converged"] is True and out["traction"]["converged"] is True
    # the mixed friction at the scene's own speed, computed there, lies on the curve (log-us
    # interpolation between the grid's neighbours), and the smooth-film traction says it is one
    scene = load_scene("page63_line_2000N")
    op = out["stribeck"]["operating_point"]
    us, f = np.asarray(out["stribeck"]["us"]), np.asarray(out["stribeck"]["friction_coefficient"])
    assert op["us"] == pytest.approx(scene.us)
    assert op["friction_coefficient"] == pytest.approx(np.interp(np.log(scene.us), np.log(us), f), rel=0.02)
    assert 0.0 <= op["asperity_fraction"] <= 1.0 and op["regime"] in ("BL", "ML", "EHL")
    assert "carry" in report and "of the load" in report
    assert out["traction"]["full_film_only"] is True


def test_main_job_skips_the_stribeck_stage_for_smooth_surfaces(capsys, tmp_path):
    assert main(["run", "appendix_c_line_4240N", "--tolerance", "0.5", "--out", str(tmp_path), "--json", "--no-plots"]) == 0
    out = json.loads(capsys.readouterr().out)
    results = load_results(out["hdf5"])
    assert set(results) == {"film", "traction"}
    assert out["plan"]["film"] == "fit" and results["film"].kind == "hertz_fit"
    assert "full_film_only" not in out["traction"]


@pytest.mark.slow
def test_main_job_on_the_default_scene(capsys, tmp_path):
    assert main(["run", "--out", str(tmp_path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert set(load_results(out["hdf5"])) == {"film", "traction", "stribeck"}


@pytest.mark.solver
def test_unconverged_solver_film_falls_back_to_the_fit_fails_the_run_and_says_so(capsys, tmp_path, monkeypatch):
    # M = 1595 at 1.93 GPa: forced onto a 129^2 grid (the accuracy target would take 513 or
    # more) the point solver does not converge, which must not reach the later stages (slip
    # 0.05: at fast fidelity the plan stages no coupled thermal film)
    import ehl_multigrid.point as point

    real = point.solve_point
    monkeypatch.setattr(point, "solve_point", lambda **kw: real(**kw, points=129))
    # an estimate in place of the failed solve is not a success: exit 3, every stage on it says so
    assert main(["run", "series_D_disc3_1.93GPa", "--fidelity", "fast", "--out", str(tmp_path), "--json", "--no-plots"]) == 3
    out = json.loads(capsys.readouterr().out)
    assert out["plan"]["film"] == "fit (solver fallback)"
    assert out["film"]["solver_fallback"] is True
    assert out["film"]["converged"] is False
    for stage in ("traction", "stribeck"):
        assert out[stage]["converged"] is False and "estimate" in out[stage]["message"]
    results = load_results(out["hdf5"])
    assert results["film"].kind == "hertz_fit"
    assert any("129 points" in n and "positive film" in n for n in results["film"].meta["notes"])
    assert results["film"].meta["setting"] == "fit (solver fallback)"
    assert results["film"].meta["plan"]["decisions"][0]["setting"] == "multigrid solver"  # the plan as made
    report = (tmp_path / "series_D_disc3_1.93GPa_report.md").read_text()
    assert "Note: multigrid solve" in report  # the film stage's note, in its own section
