"""The ehl command line: JSON output of the core subcommands and error exits."""

import json

import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.model.fits import moes_line_central, nijenbanning_central
from ehl_multigrid.model.scene import load_scene


def run_json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_show_json_gives_the_required_keys_for_a_point_contact(capsys):
    out = run_json(capsys, ["show", "appendix_d_point", "--json"])
    sc = load_scene("appendix_d_point")
    for key in ("pmax", "M", "L", "Hc_fit", "hc_fit", "a"):
        assert key in out
    assert out["pmax"] == pytest.approx(sc.hertz.pmax)
    assert out["hc_fit"] == pytest.approx(out["Hc_fit"] * sc.film_scale())
    assert out["Hc_fit"] == pytest.approx(nijenbanning_central(out["M"], out["L"]))


def test_show_json_gives_half_width_for_a_line_contact(capsys):
    out = run_json(capsys, ["show", "page63_line_500N", "--json"])
    assert out["b"] == pytest.approx(load_scene("page63_line_500N").hertz.b)
    assert out["Hc_fit"] == pytest.approx(moes_line_central(out["M"], out["L"]))


def test_fits_json(capsys):
    out = run_json(capsys, ["fits", "--contact", "line", "--M", "20", "--L", "10", "--json"])
    assert out["Hc"] == pytest.approx(moes_line_central(20, 10))
    out = run_json(capsys, ["fits", "--contact", "point", "--M", "20", "--L", "10", "--ellipticity", "0.25", "--gamma1", "2", "--json"])
    assert out["Hc"] == pytest.approx(nijenbanning_central(20, 10, 0.25, 2.0))


def test_fits_bad_input_exits_with_input_error(capsys):
    assert main(["fits", "--contact", "line", "--M", "-3", "--L", "10", "--json"]) == 2
    assert "M =" in capsys.readouterr().err


@pytest.mark.parametrize("name", ["default", "page63_line_500N", "bearing_6205_inner_race"])
def test_show_prints_a_scene_file_that_loads_as_the_same_scene(capsys, tmp_path, name):
    """``ehl show NAME > my.toml`` is how a user starts a scene of their own: the derived
    quantities must not break the TOML."""
    assert main(["show", name]) == 0
    path = tmp_path / "mine.toml"
    path.write_text(capsys.readouterr().out)
    assert load_scene(str(path)).to_dict() == load_scene(name).to_dict()


def test_show_unknown_scene_exits_2(capsys):
    assert main(["show", "nope"]) == 2
    assert "built-in scenes" in capsys.readouterr().err


def test_scenes_lists_the_builtins(capsys):
    out = run_json(capsys, ["scenes", "--json"])
    assert {"default", "appendix_d_point"} <= {r["name"] for r in out["scenes"]}
