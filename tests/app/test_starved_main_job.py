"""``ehl run`` when the film solve fails (issue 41): the run exits 3, the film stage says it
failed (converged false, a status and a message) and reports an estimate labelled as such --
for a starved scene never the flooded fit -- and a starved line supply the solver cannot reach
is a clear failure like ``ehl solve``'s, not a TypeError."""

from __future__ import annotations

import json

import pytest

import ehl_multigrid.point as point_pkg
import ehl_multigrid.starved as starved_pkg
from ehl_multigrid.app.cli import main
from ehl_multigrid.model.results import load_results
from ehl_multigrid.multigrid.result import EHLResult
from ehl_multigrid.starved import point as starved_point


def _film_section(report: str) -> str:
    return report.split("## film", 1)[1].split("\n## ", 1)[0]


@pytest.mark.solver
def test_run_on_a_starved_scene_whose_film_solve_fails_exits_3_and_reports_no_fitted_film(
        tmp_path, capsys, monkeypatch, report_scene):
    # the starved point solver without its exact zone solve, on 65^2: it stops near the
    # flooded film (0.85 of it, carrying 2.5 times the supply; 0.99 on 129^2), which the mass
    # gate fails (mass-balance error 0.9 of the inflow, where 1e-3 is allowed); no continuation
    # in the supply is tried after it (it fails here too)
    real_once, real_scene = starved_point._solve_once, starved_pkg.solve_starved_point_scene
    monkeypatch.setattr(starved_point, "CONTINUATION_MAX_POINTS", 0)
    monkeypatch.setattr(starved_point, "_solve_once",
                        lambda pb, h, opt, rule, exact=False, guess=None: real_once(pb, h, opt, rule, False, guess))
    monkeypatch.setattr(starved_pkg, "solve_starved_point_scene",
                        lambda scene, **kw: real_scene(scene, **{**kw, "points": 65, "exact_rules": ()}))
    scene = str(report_scene("ball", tmp_path, "ball_starved", 2e-8))
    rc = main(["run", scene, "--no-plots", "--json", "--out", str(tmp_path / "o")])
    out = json.loads(capsys.readouterr().out)
    assert rc == 3
    film = out["film"]
    assert film["converged"] is False and film["status"] != "converged"
    assert "mass is not conserved" in film["message"]
    # the film is the starved estimate (Chevalier's reduction), well below the flooded fit
    assert film["hc_estimate"] < 0.5 * film["hc_fit"]
    assert out["plan"]["film"] == "starved estimate (solver fallback)"
    report = (tmp_path / "o" / "ball_starved_report.md").read_text()
    text = _film_section(report)
    assert "ESTIMATE" in text and "Film from the Nijenbanning fit" not in text
    assert f"{film['hc_estimate'] * 1e9:.4g} nm" in text
    res = load_results(out["hdf5"])["film"]
    assert res.kind == "hertz_fit" and res.scalars["hc_estimate"] == pytest.approx(film["hc_estimate"])


def test_run_on_a_flooded_scene_whose_film_solve_fails_exits_3(tmp_path, capsys, monkeypatch, report_scene):
    monkeypatch.setattr(point_pkg, "solve_point",
                        lambda **kw: EHLResult(status=2, message="stalled: the residual fell only from 1e-3 to 9e-4"))
    scene = str(report_scene("ball", tmp_path, "ball_flooded"))
    rc = main(["run", scene, "--no-plots", "--json", "--out", str(tmp_path / "o")])
    out = json.loads(capsys.readouterr().out)
    assert rc == 3
    assert out["film"]["converged"] is False and out["film"]["status"] == "stalled"
    assert "the residual fell only" in out["film"]["message"]
    assert out["plan"]["film"] == "fit (solver fallback)"
    text = _film_section((tmp_path / "o" / "ball_flooded_report.md").read_text())
    assert "ESTIMATE" in text and "stalled" in text


#: what the starved line solver returns for a supply below the flux it reaches (no fields)
UNREACHABLE = ("Hoil = 0.0004 is below the flux the solver reaches with the meniscus next to the "
               "Hertzian edge (0.0011 at X_m = -1.001, 0.014 of the flooded flux): severe starvation "
               "beyond this solver's range")


@pytest.mark.parametrize("command", ["run", "solve"])
def test_a_starved_line_supply_the_solver_cannot_reach_is_a_clear_failure(tmp_path, capsys, monkeypatch, command,
                                                                          report_scene):
    monkeypatch.setattr(starved_pkg, "solve_starved_scene", lambda scene, **kw: EHLResult(status=5, message=UNREACHABLE))
    scene = str(report_scene("roller", tmp_path, "roller_1nm", 1e-9))
    rc = main([command, scene, "--no-plots", "--json", "--out", str(tmp_path / "o")])
    cap = capsys.readouterr()
    assert rc == 3  # not 1 (the TypeError "this result has no field builder")
    assert "Hoil = 0.0004" in cap.err and "0.0011 at X_m = -1.001" in cap.err  # the supply, the reachable flux
    if command == "run":
        film = json.loads(cap.out)["film"]
        assert film["converged"] is False and film["status"] == "start_failed"
        assert film["hc_estimate"] < 0.05 * film["hc_fit"]


@pytest.mark.slow
def test_run_on_the_line_scene_of_issue_41_at_1_nm_is_a_clear_failure(tmp_path, capsys, report_scene):
    scene = str(report_scene("roller", tmp_path, "roller_1nm", 1e-9))
    rc = main(["run", scene, "--no-plots", "--json", "--out", str(tmp_path / "o")])
    cap = capsys.readouterr()
    # measured: the meniscus search fails next to the Hertzian edge (exit 3); a solver that
    # reaches the supply would give the starved film (exit 0); never the internal error (1)
    assert rc in (0, 3)
    film = json.loads(cap.out)["film"]
    if rc == 3:
        assert film["converged"] is False and film["hc_estimate"] < 0.05 * film["hc_fit"]
        assert "ESTIMATE" in _film_section((tmp_path / "o" / "roller_1nm_report.md").read_text())
    else:
        assert "meniscus_x" in film


def test_a_solved_starved_film_is_set_beside_the_fit_for_its_supply(tmp_path, capsys, report_scene):
    # the flooded fit alone (169 nm beside a 41 nm starved film) read as the film the oil gives
    scene = str(report_scene("roller", tmp_path, "roller_starved", 2e-8))
    main(["run", scene, "--no-plots", "--json", "--out", str(tmp_path / "o"), "--tolerance", "0.05"])
    film = json.loads(capsys.readouterr().out)["film"]
    assert "meniscus_x" in film  # solved starved, not the fallback estimate
    assert film["hc_fit_supplied"] < 0.5 * film["hc_fit"]
    text = _film_section((tmp_path / "o" / "roller_starved_report.md").read_text())
    assert f"{film['hc_fit_supplied'] * 1e9:.4g} nm for the supply" in text
