"""``ehl transient`` refuses at input what it cannot solve, naming the field, the value and the
allowed range in the units the scene gave: a starving oil supply (the transient solvers model a
flooded inlet only), non-finite or out-of-range feature values, a dent deeper than the solver
takes; it warns when a height map is wider than the box. No test here solves."""

from __future__ import annotations

import argparse
import math
import re

import numpy as np
import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import Scene, load_scene
from ehl_multigrid.point.problem import problem_from_scene
from ehl_multigrid.transient import cli
from ehl_multigrid.transient.scene_feature import (
    feature_from_scene_table,
    point_feature_from_scene_table,
)
from ehl_multigrid.transient.supply import check_flooded_supply, flooded_ratio

DENT = {"kind": "dent", "amplitude": 20e-9, "width": 40e-6, "x0": -2.0}


def _scene(name, feature=DENT, **supply):
    d = load_scene(name).to_dict()
    d["feature"] = dict(feature)
    d.setdefault("supply", {}).update(supply)
    return Scene.from_dict(d)


def _run(monkeypatch, tmp_path, scene, *extra, points=129):
    p = argparse.ArgumentParser()
    cli.register(p.add_subparsers(dest="command"))
    monkeypatch.setattr(cli, "load_scene", lambda name: scene)
    args = p.parse_args(["transient", "x", "--accuracy", "none", "--out", str(tmp_path), "--points", str(points),
                         *extra])
    return args.func(args)


@pytest.mark.parametrize("name", ["ball_on_disc_tribometer", "page63_line_2000N"])
def test_a_starving_supply_is_refused_naming_hoil_and_the_flooded_inlet(monkeypatch, tmp_path, name):
    sc = _scene(name, hoil=20e-9)  # the flooded film is 23 nm (line) to 205 nm (ball)
    with pytest.raises(InputError) as err:
        _run(monkeypatch, tmp_path, sc)
    msg = str(err.value)
    assert "[supply] hoil = 2e-08 m" in msg and "flooded" in msg
    least = float(re.search(r"\[([0-9.e+-]+), inf\] m", msg).group(1))
    _, hc = sc.central_film_fit()
    assert least > 2.0 * hc  # "well above" the flooded film
    assert not list(tmp_path.glob("*.h5"))


def test_a_supply_well_above_the_flooded_film_is_solved_as_flooded_with_a_note():
    sc = _scene("ball_on_disc_tribometer", hoil=5e-6)
    note = check_flooded_supply(sc, 20e-9)
    assert "hoil = 5e-06 m" in note and "flooded" in note
    assert check_flooded_supply(_scene("ball_on_disc_tribometer")) is None  # hoil = inf
    # the threshold: Chevalier's film (thesis (6.1)) within 1 % of the flooded film
    r = flooded_ratio(3.5)
    assert r / (1.0 + r**3.5) ** (1.0 / 3.5) == pytest.approx(0.99)


@pytest.mark.solver
def test_a_layer_across_the_track_of_a_scene_feeds_a_mass_conserving_run(monkeypatch, tmp_path, capsys):
    # a starved centre track (50 nm, the flooded film is 205 nm) with more oil at its sides
    d = _scene("ball_on_disc_tribometer").to_dict()
    d["supply"] = {"hoil_profile": {"y": [0.0, 5e-5, 1e-4, 1e-3], "hoil": [5e-8, 5e-8, 3e-7, 3e-7]}}
    sc = Scene.from_dict(d)
    with pytest.raises(InputError, match="hoil_profile"):
        _run(monkeypatch, tmp_path, sc)  # the projection: flooded inlets only
    # 65 points (the layer and the mass balance are the same as on 129: hc 0.209 and 0.208 of
    # the flooded fit, mass error 3e-7 and 4e-10, at a quarter of the cost)
    out = _run(monkeypatch, tmp_path, sc, "--cavitation", "mass-conserving", "--steps", "1",
               "--no-plots", points=65)
    assert "[supply] hoil_profile:" in capsys.readouterr().err
    assert out["converged"] and out["mass_error_max"] <= 1e-6
    # the centre track's layer governs: far below the flooded film (measured 0.21 of it)
    assert out["hc_min"] < 0.3 * sc.central_film_fit()[1]


def test_a_starving_scene_exits_2_before_any_solve(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text(_scene("ball_on_disc_tribometer", hoil=20e-9).to_toml())
    assert main(["transient", str(path), "--points", "65", "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "[supply] hoil" in err and "2e-08" in err and len(err.strip().splitlines()) == 1


def test_x0_nan_in_a_scene_file_is_refused_at_input(tmp_path, capsys):
    path = tmp_path / "s.toml"
    text = _scene("page63_line_2000N").to_toml()
    path.write_text(re.sub(r"x0 = .*", "x0 = nan", text))
    assert main(["transient", str(path), "--points", "129", "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "feature.x0" in err and "nan" in err


@pytest.mark.parametrize("key, value", [
    ("x0", math.nan), ("x0", math.inf), ("x0", "abc"), ("x0", -4.4), ("amplitude", math.nan),
    ("amplitude", -1e-8), ("width", math.nan), ("width", 1e-2), ("body", 1.5), ("body", 3),
    ("shape", "square"),
])
def test_bad_line_feature_values_are_refused_naming_field_value_and_range(key, value):
    pb = LineProblem.from_scene(load_scene("page63_line_2000N"))
    with pytest.raises(InputError) as err:
        feature_from_scene_table({**DENT, key: value}, pb)
    msg = str(err.value)
    assert f"feature.{key} = " in msg and (str(value) in msg or f"{value:g}" in msg)
    assert re.search(r"\[[^\]]+, [^\]]+\]", msg)  # the allowed range or values


@pytest.mark.parametrize("feature, key", [
    ({**DENT, "y0": math.nan}, "y0"), ({**DENT, "y0": 3.0}, "y0"), ({**DENT, "x0": math.nan}, "x0"),
    ({"kind": "waviness", "amplitude": 1e-8, "wavelength": 1e-4, "angle": math.nan}, "angle"),
    ({"kind": "waviness", "amplitude": 1e-8, "wavelength": 1e-4, "phase": math.inf}, "phase"),
    ({"kind": "waviness", "amplitude": 1e-8, "wavelength": 1.0}, "wavelength"),
])
def test_bad_point_feature_values_are_refused_naming_field_value_and_range(feature, key):
    pb = problem_from_scene(load_scene("ball_on_disc_tribometer"))
    with pytest.raises(InputError, match=rf"feature\.{key} = .*range"):
        point_feature_from_scene_table(feature, pb)


def test_a_micrometre_dent_on_a_nanometre_film_is_taken():
    # 7 um deep on the tribometer ball, about 70 times its film: 3.8 film units a^2/Rx
    pb = problem_from_scene(load_scene("ball_on_disc_tribometer"))
    dent, _ = point_feature_from_scene_table({**DENT, "amplitude": 7e-6}, pb)
    assert dent.amplitude == pytest.approx(-7e-6 * pb.Rx / pb.a**2)
    assert dent.amplitude < -3.0


def test_a_dent_too_deep_is_refused_in_metres_with_its_sign():
    sc = load_scene("ball_on_disc_tribometer")
    pb = problem_from_scene(sc)
    with pytest.raises(InputError) as err:
        point_feature_from_scene_table({**DENT, "amplitude": 25e-6}, pb)
    msg = str(err.value)
    most = 10.0 * pb.a**2 / pb.Rx
    # the depth as the scene gave it (positive, metres) and the range in metres
    assert "feature.amplitude = 2.5e-05 m" in msg and "depth" in msg
    assert re.search(rf"\[0, {most:.6g}\] m", msg)
    assert "-13" not in msg and "a Rx/a^2" not in msg  # no film units, no flipped sign


def test_a_bump_higher_than_one_film_unit_is_refused():
    pb = problem_from_scene(load_scene("ball_on_disc_tribometer"))
    with pytest.raises(InputError, match=r"feature\.amplitude = 3e-06 m .*range"):
        point_feature_from_scene_table({**DENT, "kind": "bump", "amplitude": 3e-6}, pb)


def test_slip_outside_its_range_is_refused_naming_the_scene_field(monkeypatch, tmp_path):
    d = _scene("page63_line_2000N").to_dict()
    sc = Scene.from_dict(d)
    object.__setattr__(sc, "slip", 5.0)  # a scene built elsewhere: checked again here
    with pytest.raises(InputError, match=r"operating\.slip = 5 .*\[-2, 2\]"):
        _run(monkeypatch, tmp_path, sc)


def test_a_height_map_wider_than_the_box_in_y_warns_in_metres(tmp_path):
    sc = load_scene("ball_on_disc_tribometer")
    pb = problem_from_scene(sc)
    f = tmp_path / "map.npy"
    np.save(f, np.zeros((40, 30)))
    table = {"kind": "map", "file": str(f), "dx": 2e-6, "dy": 20e-6, "level": "none"}
    warnings: list[str] = []
    point_feature_from_scene_table(table, pb, (-4.5, 1.5, 2.0), warnings)
    assert len(warnings) == 1
    half = 0.5 * 39 * 20e-6
    assert f"y = {-half:.4g} .. {half:.4g} m" in warnings[0]
    assert f"|y| <= {2.0 * pb.a:.4g} m" in warnings[0] and "clipped" in warnings[0]
    narrow: list[str] = []
    point_feature_from_scene_table({**table, "dy": 2e-6}, pb, (-4.5, 1.5, 2.0), narrow)
    assert narrow == []
