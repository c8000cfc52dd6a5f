"""Scenes: built-ins load and resolve, round-trip, and every bad value is named."""

import copy
import math

import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import Scene, builtin_scene_names, load_scene

BASE = {
    "name": "t",
    "contact": {"kind": "line", "length": 0.01},
    "geometry": {"Rx": 0.02},
    "solids": {"E_reduced": 231e9},
    "lubricant": {"preset": "T9"},
    "operating": {"load": 500.0, "us": 1.0, "slip": 0.1, "T_oil": 40.0},
}


def scene_with(path: str, value, base=BASE) -> dict:
    d = copy.deepcopy(base)
    *head, last = path.split(".")
    node = d
    for k in head:
        node = node.setdefault(k, {})
    if value is _DELETE:
        node.pop(last)
    else:
        node[last] = value
    return d


_DELETE = object()


def test_every_builtin_scene_loads_and_summarises():
    names = builtin_scene_names()
    assert "default" in names and "appendix_c_line_42400N" in names
    for name in names:
        s = load_scene(name).summary()
        assert s["pmax"] > 0 and s["M"] > 0 and s["Hc_fit"] > 0 and s["hc_fit"] > 0


def test_builtin_scene_pressures_match_the_thesis():
    assert load_scene("page63_line_500N").hertz.pmax == pytest.approx(0.3e9, rel=0.02)
    assert load_scene("page63_line_2000N").hertz.pmax == pytest.approx(0.6e9, rel=0.02)
    assert load_scene("page63_line_8000N").hertz.pmax == pytest.approx(1.2e9, rel=0.02)
    assert load_scene("page63_line_16000N").hertz.pmax == pytest.approx(1.7e9, rel=0.02)
    assert load_scene("appendix_c_line_42400N").hertz.pmax == pytest.approx(1.58e9, rel=0.01)
    assert load_scene("appendix_c_line_4240N").hertz.pmax == pytest.approx(0.5e9, rel=0.01)
    assert load_scene("appendix_d_point").hertz.pmax == pytest.approx(1.0e9, rel=0.02)
    # scenes given by pmax resolve the load exactly
    assert load_scene("series_D_disc3_1.93GPa").hertz.pmax == pytest.approx(1.93e9, rel=1e-9)


def test_scene_round_trips_through_toml(tmp_path):
    for name in ("default", "page63_line_2000N", "chapter6_starved_0.5GPa"):
        s = load_scene(name)
        f = tmp_path / f"{name}.toml"
        f.write_text(s.to_toml())
        s2 = load_scene(f)
        assert s2.summary() == s.summary()
        assert s2.lubricant == s.lubricant and s2.roughness == s.roughness and s2.supply == s.supply


def test_body_radii_give_reduced_radius():
    d = scene_with("geometry", {"R1x": 0.0381, "R2x": 0.0381})
    assert Scene.from_dict(d).Rx == pytest.approx(0.0381 / 2)
    d = copy.deepcopy(BASE)
    d["contact"] = {"kind": "elliptic"}
    d["geometry"] = {"R1x": 0.01, "R1y": 0.01, "R2x": math.inf, "R2y": -0.02}  # concave groove
    s = Scene.from_dict(d)
    assert s.Ry == pytest.approx(1 / (1 / 0.01 - 1 / 0.02))
    assert s.hertz.kind == "elliptic"


def test_alpha_in_scene_sets_the_pressure_viscosity_coefficient():
    s = load_scene("page63_line_2000N")
    assert s.alpha == pytest.approx(2e-8, rel=1e-12)
    assert s.eta0 == pytest.approx(20.2e-3, rel=1e-12)


def test_velocities_of_the_surfaces_follow_the_slip_definition():
    s = Scene.from_dict(scene_with("operating.slip", 2.0))
    assert (s.u1, s.u2) == pytest.approx((1.0, 0.0))  # 200 % slip: surface 2 at rest
    s = Scene.from_dict(scene_with("operating.slip", 0.1))
    assert 2 * (s.u1 - s.u2) / (s.u1 + s.u2) == pytest.approx(0.1)


@pytest.mark.parametrize(
    "path, value, match",
    [
        ("operating.load", 0.0, r"operating.load = 0 N is outside the allowed range \(0, inf\)"),
        ("operating.load", -100.0, "operating.load = -100 N"),
        ("operating.us", 0.0, "operating.us = 0 m/s"),
        ("operating.us", -1.0, "operating.us = -1 m/s"),
        ("operating.slip", 2.5, r"operating.slip = 2.5 is outside the allowed range \[-2, 2\]"),
        ("operating.T_oil", -60.0, r"operating.T_oil = -60 degC is outside the allowed range \[-50, 400\]"),
        ("operating.T_surface1", 450.0, "operating.T_surface1 = 450 degC"),
        ("operating.load", "heavy", "operating.load = 'heavy' is not a number"),
        ("operating.speed", 1.0, r"unknown key\(s\) \['speed'\] in \[operating\]"),
        ("lubricant.preset", "SAE-30", "lubricant.preset = 'SAE-30' is not a known oil"),
        ("lubricant.viscosity", 0.1, r"unknown key\(s\) \['viscosity'\] in \[lubricant\]"),
        ("lubricant.tau0", -1.0, "tau0 = -1 Pa"),
        ("solids.body1", {"preset": "steel", "nu": 0.5}, r"nu = 0.5 is outside the allowed range \[0, 0.5\)"),
        ("solids.body1", {"preset": "steel", "nu": -0.1}, "nu = -0.1"),
        ("solids.body1", "unobtainium", "solid preset 'unobtainium' is not known"),
        ("contact.kind", "spherical", "contact.kind = 'spherical' is not one of"),
        ("contact.length", _DELETE, r"contact.length \(B, m\) is required"),
        ("contact.length", -0.01, "contact.length = -0.01 m"),
        ("geometry.Rx", 0.0, "geometry.Rx = 0 m"),
        ("geometry.Ry", 0.05, "geometry.Ry = 0.05 m must be inf for a line contact"),
        ("roughness", {"n": 1e11}, r"roughness.Rq \(m\) is required"),
        ("roughness", {"Rq": -1e-7}, "roughness.Rq = -1e-07 m"),
        ("roughness", {"Rq": 1e-7, "fc": 1.5}, "roughness.fc = 1.5"),
        ("ranges.us", {"min": 0.0, "max": 1.0, "n": 10, "log": True}, r"ranges.us.min = 0 m/s is outside"),
        ("ranges.us", {"min": 1e-3, "max": 1.0, "n": 0}, "ranges.us.n = 0"),
        ("supply.delta", 0.0, "supply.delta = 0"),
        ("colour", "red", r"unknown key\(s\) \['colour'\] in \[scene top level\]"),
    ],
)
def test_bad_scene_value_raises_error_naming_field_value_and_range(path, value, match):
    with pytest.raises(InputError, match=match):
        Scene.from_dict(scene_with(path, value))


def test_load_and_pmax_together_are_rejected():
    with pytest.raises(InputError, match=r"\bload\b.*\bpmax\b"):
        Scene.from_dict(scene_with("operating.pmax", 1e9))


def test_point_contact_with_unequal_radii_must_be_declared_elliptic():
    d = copy.deepcopy(BASE)
    d["contact"] = {"kind": "point"}
    d["geometry"] = {"Rx": 0.01, "Ry": 0.02}
    with pytest.raises(InputError, match="use 'elliptic'"):
        Scene.from_dict(d)


def test_unknown_scene_name_lists_builtins():
    with pytest.raises(InputError, match=r"'no_such_scene'.*'default'"):
        load_scene("no_such_scene")


def test_invalid_toml_file_is_reported(tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text("[contact\nkind = 'line'")
    with pytest.raises(InputError, match="not valid TOML"):
        load_scene(f)


def test_with_operating_revalidates():
    s = load_scene("page63_line_500N")
    assert s.with_operating(load=2000.0).hertz.pmax == pytest.approx(load_scene("page63_line_2000N").hertz.pmax)
    with pytest.raises(InputError, match="operating.us"):
        s.with_operating(us=-1.0)


def test_feature_table_converts_units_and_round_trips_through_toml(tmp_path):
    d = scene_with("feature", {"kind": "dent", "amplitude": "0.1 um", "width": "40 um", "x0": -3.0})
    s = Scene.from_dict(d)
    assert s.feature["amplitude"] == pytest.approx(1e-7) and s.feature["width"] == pytest.approx(4e-5)
    f = tmp_path / "dent.toml"
    f.write_text(s.to_toml())
    assert load_scene(f).feature == s.feature
    assert Scene.from_dict(BASE).feature == {} and "feature" not in Scene.from_dict(BASE).to_dict()
    with pytest.raises(InputError, match="feature.width"):
        Scene.from_dict(scene_with("feature", {"kind": "dent", "width": "40 parsecs-per-volt"}))


def test_a_slide_to_roll_ratio_on_the_sum_speed_is_read_as_half_the_slip(tmp_path):
    """``[operating] srr`` = (u1 - u2)/(u1 + u2), the convention of many papers, is the
    package's slip S = 2(u1 - u2)/(u1 + u2) halved; giving both is refused, as is an SRR
    outside [-1, 1] (one surface at rest at the ends)."""
    import tomli_w

    d = load_scene("default").to_dict()
    d["operating"].pop("slip")
    d["operating"]["srr"] = -0.25
    path = tmp_path / "srr.toml"
    path.write_text(tomli_w.dumps(d))
    assert load_scene(str(path)).slip == pytest.approx(-0.5)
    d["operating"]["slip"] = 0.1
    path.write_text(tomli_w.dumps(d))
    with pytest.raises(InputError) as both:
        load_scene(str(path))
    assert "operating.slip" in str(both.value) and "operating.srr" in str(both.value)
    d["operating"].pop("slip")
    d["operating"]["srr"] = 1.5
    path.write_text(tomli_w.dumps(d))
    with pytest.raises(InputError, match=r"operating\.srr = 1\.5 .*\[-1, 1\]"):
        load_scene(str(path))
