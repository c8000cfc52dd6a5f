"""`ehl stribeck`: JSON keys, HDF5 result, starved cases, plots, thermal run, error exits."""

import json

import numpy as np
import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.model.results import Result
from ehl_multigrid.model.scene import load_scene
from mixed.sharing import load_sharing


def thermal_available():
    try:
        import thermal

        return callable(getattr(thermal, "film_friction", None))
    except ImportError:
        return False


def run_json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_json_has_the_required_lists_and_matches_the_library(capsys, tmp_path):
    out = run_json(capsys, ["stribeck", "page63_line_2000N", "--json", "--n", "8", "--us-min", "0.01",
                            "--us-max", "1", "--out", str(tmp_path), "--no-plots"])
    for key in ("us", "friction_coefficient", "Pa", "Ph", "gamma1", "hfr", "hss", "regime"):
        assert isinstance(out[key], list) and len(out[key]) == 8, key
    assert out["converged"] is True
    us = np.geomspace(0.01, 1, 8)
    assert np.allclose(out["us"], us)
    ls = load_sharing(load_scene("page63_line_2000N"), us)
    assert np.allclose(out["gamma1"], ls.gamma1, rtol=1e-9)
    res = Result.load(tmp_path / "stribeck_page63_line_2000N.h5")
    assert res.kind == "stribeck"
    assert np.allclose(res["friction_coefficient"][0], out["friction_coefficient"])
    assert res.scalars["converged"] is True


def test_one_speed_is_a_curve_of_one_point_equal_to_that_point_of_a_longer_curve(capsys, tmp_path):
    one = run_json(capsys, ["stribeck", "page63_line_2000N", "--json", "--n", "1", "--us-min", "0.1",
                            "--us-max", "0.1", "--out", str(tmp_path), "--no-plots"])
    three = run_json(capsys, ["stribeck", "page63_line_2000N", "--json", "--n", "3", "--us-min", "0.01",
                              "--us-max", "1", "--out", str(tmp_path / "b"), "--no-plots"])
    assert one["us"] == [0.1] and one["gamma1"][0] == pytest.approx(three["gamma1"][1], rel=1e-12)
    assert one["friction_coefficient"][0] == pytest.approx(three["friction_coefficient"][1], rel=1e-9)


@pytest.mark.solver
def test_hoil_list_adds_starved_cases_and_plots_are_written(capsys, tmp_path):
    out = run_json(capsys, ["stribeck", "chapter6_starved_0.5GPa", "--json", "--n", "6", "--hoil", "0.5,3",
                            "--out", str(tmp_path)])
    assert [c["hoil_over_sigma"] for c in out["cases"]] == pytest.approx([0.5, 3.0])
    assert out["hoil"] is None  # flooded first case: inf -> null in JSON
    pngs = sorted(p.name for p in tmp_path.glob("*.png"))
    assert len(pngs) == 6 and all(p.startswith("stribeck_chapter6_starved_0.5GPa") for p in pngs)
    res = Result.load(tmp_path / "stribeck_chapter6_starved_0.5GPa.h5")
    assert res["friction_coefficient"].shape == (3, 6)


def test_human_output_shows_a_table(capsys, tmp_path):
    assert main(["stribeck", "series_A_disc1_1GPa", "--n", "5", "--out", str(tmp_path), "--no-plots"]) == 0
    text = capsys.readouterr().out
    assert "regime" in text and "gamma1" in text


@pytest.mark.skipif(not thermal_available(), reason="thermal.film_friction not available")
def test_thermal_curve_runs_end_to_end_from_the_cli(capsys, tmp_path):
    out = run_json(capsys, ["stribeck", "series_C_disc3_1.93GPa", "--thermal", "--json", "--n", "3",
                            "--out", str(tmp_path), "--no-plots"])
    assert out["thermal"] is True and out["converged"] is True
    assert len(out["mean_temperature_rise"]) == 3 and out["mean_temperature_rise"][-1] > 0


def test_errors_exit_with_code_2(capsys, tmp_path):
    assert main(["stribeck", "appendix_c_line_4240N", "--json", "--out", str(tmp_path)]) == 2
    assert "roughness" in capsys.readouterr().err
    assert main(["stribeck", "page63_line_500N", "--json", "--us-min", "1", "--us-max", "0.1", "--out", str(tmp_path)]) == 2
    assert main(["stribeck", "page63_line_500N", "--json", "--ehl-fraction", "0.99", "--out", str(tmp_path)]) == 2
    assert main(["stribeck", "no_such_scene", "--json", "--out", str(tmp_path)]) == 2


def test_human_output_names_each_starved_curve_by_its_supply(capsys, tmp_path):
    assert main(["stribeck", "series_A_disc1_1GPa", "--n", "5", "--hoil", "0.5,2", "--out", str(tmp_path),
                 "--no-plots"]) == 0
    text = capsys.readouterr().out
    lines = [ln for ln in text.splitlines() if ln.strip().startswith("starved hoil/Rq")]
    assert [ln.split()[3] for ln in lines] == ["0.5", "2"] and all("minimum" in ln for ln in lines)
    assert "hoil 21 nm" in lines[0]  # 0.5 Rq of the scene's Rq = 42 nm


def test_the_curve_says_its_films_are_the_fits_with_the_fits_bias_here(capsys, tmp_path):
    # series B disc 1 at 1 GPa: the fit lay 17-38 % above solved films over 0.37-12 m/s
    assert main(["stribeck", "series_B_disc1_1GPa", "--json", "--n", "4", "--out", str(tmp_path), "--no-plots"]) == 0
    shown = capsys.readouterr()
    out = json.loads(shown.out)
    note = load_scene("series_B_disc1_1GPa").summary()["hc_fit_note"]
    assert "fitted film" in out["film_source"] and "not a solved film" in out["film_source"]
    assert note in out["film_source"] and note in shown.err
