"""Plausibility of scene inputs and derived results (issue 41): each value a unit mistake
typically produces warns naming the field, the value and the probable mistake; strict mode
refuses it; hard impossibilities stay errors; rotational frequencies convert with 2 pi; the
fitted film carries its validity and measured bias."""

import math
import sys
import warnings
from importlib import resources

import pytest

from ehl_multigrid.model import fits
from ehl_multigrid.model.errors import InputError, PlausibilityWarning, strict_plausibility
from ehl_multigrid.model.plausibility import PLAUSIBLE, implausibility, unit_hint
from ehl_multigrid.model.scene import Scene, builtin_scene_names, load_scene
from ehl_multigrid.model.units import to_canonical

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


@pytest.fixture(autouse=True)
def _not_strict(monkeypatch):
    monkeypatch.delenv("EHL_STRICT", raising=False)


def raw(name):
    """The built-in scene ``name`` as written (its [element] table kept)."""
    return tomllib.loads((resources.files("ehl_multigrid") / "scenes" / f"{name}.toml").read_text())


def changed(name, section, key, value):
    d = raw(name)
    d[section][key] = value
    if key == "R1x":  # a ball: both radii
        d[section]["R1y"] = value
    return d


def plausibility_warnings(data):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        Scene.from_dict(data)
    return [str(w.message) for w in caught if issubclass(w.category, PlausibilityWarning)]


# each example of the issue: (scene, section, key, value, words the warning must contain)
ISSUE_EXAMPLES = [
    ("default", "operating", "load", 1e12, ["operating.load = 1e+12 N", "Hertz pmax"]),
    ("default", "geometry", "R1x", 10.32, ["geometry.R1x = 10.32 m", "millimetres", "0.01032 m"]),
    ("appendix_c_line_4240N", "contact", "length", 10.0, ["contact.length = 10 m", "millimetres", "0.01 m"]),
    ("default", "lubricant", "eta0", 1e6, ["eta0", "1e+06 Pa s", "fitted central film"]),
    ("default", "operating", "T_oil", 343.0, ["operating.T_oil = 343 degC", "kelvin", "69.85 degC"]),
    ("bearing_6205_inner_race", "element", "shaft_speed", 3000, ["element.shaft_speed = 3000 rad/s",
                                                                 "28647.9 rpm", "revolutions per minute"]),
    ("spur_gear_pitch_point", "element", "z1", 5, ["element.z1 = 5", "teeth", "undercut"]),
]


@pytest.mark.parametrize("name, section, key, value, words", ISSUE_EXAMPLES,
                         ids=[f"{e[2]}={e[3]}" for e in ISSUE_EXAMPLES])
def test_each_issue_example_warns_naming_the_field_and_the_probable_mistake(name, section, key, value, words):
    found = " | ".join(plausibility_warnings(changed(name, section, key, value)))
    for word in words:
        assert word in found, f"{word!r} missing from: {found}"
    assert "plausible range" in found


def test_a_fast_spindle_given_in_rpm_is_not_told_it_gave_rpm():
    # 20000 rpm is above the range that catches rpm written as rad/s, and the user named the unit
    found = " | ".join(plausibility_warnings(changed("bearing_6205_inner_race", "element", "shaft_speed",
                                                     "20000 rpm")))
    assert "element.shaft_speed = 2094.4 rad/s (20000 rpm)" in found
    assert "did you give" not in found and "spindle" in found


@pytest.mark.parametrize("name", builtin_scene_names())
def test_no_builtin_scene_triggers_a_plausibility_warning(name):
    assert plausibility_warnings(raw(name)) == []


def test_strict_mode_refuses_an_implausible_value_as_an_input_error(monkeypatch):
    d = changed("default", "geometry", "R1x", 10.32)
    with strict_plausibility(), pytest.raises(InputError, match=r"geometry\.R1x = 10\.32 m.*millimetres"):
        Scene.from_dict(d)
    Scene.from_dict(changed("default", "operating", "load", 50.0))  # the filter is restored
    monkeypatch.setenv("EHL_STRICT", "1")
    with pytest.raises(InputError, match="strict"):
        Scene.from_dict(d)
    monkeypatch.setenv("EHL_STRICT", "0")
    with pytest.warns(PlausibilityWarning):
        Scene.from_dict(d)


def test_a_warnings_error_filter_also_gives_an_input_error():
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        with pytest.raises(InputError, match="operating.T_oil"):
            Scene.from_dict(changed("default", "operating", "T_oil", 343.0))


def test_one_mistake_gives_one_warning_for_defaulted_fields():
    # the surface temperatures default to the oil's; sigma_s and dd to fractions of Rq
    d = raw("default")
    d["operating"].pop("T_surface1")
    d["operating"].pop("T_surface2")
    d["operating"]["T_oil"] = 343.0
    assert len(plausibility_warnings(d)) == 1
    d = raw("default")
    d["roughness"] = {"Rq": 5e-5, "n": 5.8e10, "beta": 6e-5}
    found = plausibility_warnings(d)
    assert len(found) == 1 and "roughness.Rq" in found[0]


def test_changed_operating_values_are_checked_but_the_scene_is_not_rechecked():
    sc = load_scene("default")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sc.with_operating(us=2.0)
        sc.with_operating(us=500.0)
    found = [str(w.message) for w in caught]
    assert len(found) == 1 and "operating.us = 500 m/s" in found[0] and "mm/s" in found[0]


@pytest.mark.parametrize("text, kind, expected", [
    ("10 Hz", "angular_speed", 2 * math.pi * 10),
    ("50 1/s", "angular_speed", 2 * math.pi * 50),
    ("3000 1/min", "angular_speed", 2 * math.pi * 50),
    ("3000 rpm", "angular_speed", 2 * math.pi * 50),
    ("5 turn/s", "angular_speed", 2 * math.pi * 5),
    ("10 rad/s", "angular_speed", 10.0),
    ("90 deg/s", "angular_speed", math.pi / 2),
    ("10 Hz", "frequency", 10.0),
    ("3000 rpm", "frequency", 50.0),
    ("10 rad/s", "frequency", 10 / (2 * math.pi)),
])
def test_speeds_of_rotation_convert_with_2_pi_per_revolution(text, kind, expected):
    assert to_canonical("element.shaft_speed", text, kind) == pytest.approx(expected, rel=1e-12)


def test_shaft_speed_of_10_hz_is_62_83_rad_s_in_a_bearing_scene():
    hz = Scene.from_dict(changed("bearing_6205_inner_race", "element", "shaft_speed", "10 Hz"))
    rad = Scene.from_dict(changed("bearing_6205_inner_race", "element", "shaft_speed", 2 * math.pi * 10))
    assert hz.us == pytest.approx(rad.us, rel=1e-12)
    assert hz.element.details["cage_speed"] == pytest.approx(0.5 * 62.83185 * (1 - hz.element.details["gamma"]))


@pytest.mark.parametrize("slip", [5.0, -2.5, math.nan])
def test_slip_outside_minus_2_2_is_refused_at_load_with_its_definition(slip):
    with pytest.raises(InputError) as e:
        Scene.from_dict(changed("default", "operating", "slip", slip))
    msg = str(e.value)
    assert "operating.slip" in msg and "[-2, 2]" in msg and "S = 2(u1-u2)/(u1+u2)" in msg


def test_slip_range_outside_minus_2_2_is_refused_with_its_definition():
    d = raw("default")
    d["ranges"] = {"slip": [0.0, 3.0]}
    with pytest.raises(InputError, match=r"ranges\.slip\[1\] = 3.*S = 2\(u1-u2\)"):
        Scene.from_dict(d)


@pytest.mark.parametrize("value", [math.nan, math.inf])
def test_a_non_finite_feature_position_is_refused_at_load(value):
    d = raw("appendix_c_line_4240N")
    d["feature"] = {"kind": "bump", "amplitude": 1e-7, "width": 5e-5, "x0": value}
    with pytest.raises(InputError, match="feature.x0"):
        Scene.from_dict(d)


@pytest.mark.parametrize("section, key, value, words", [
    ("roughness", "Rq", 0.2, ["roughness.Rq = 0.2 m", "micrometres", "2e-07 m"]),
    ("operating", "T_oil", 500.0, ["operating.T_oil = 500", "kelvin", "226.9 degC"]),
    ("solids", "E_reduced", 230.0, ["solids.E_reduced = 230", "GPa"]),
])
def test_a_refused_value_also_names_the_probable_unit_mistake(section, key, value, words):
    d = raw("default")
    d[section][key] = value
    with pytest.raises(InputError) as e:
        Scene.from_dict(d)
    for word in words:
        assert word in str(e.value)


def test_every_plausible_range_is_ordered_and_its_mistakes_lead_back_into_it():
    for key, spec in PLAUSIBLE.items():
        assert spec.lo < spec.hi, key
        assert implausibility("f", 0.5 * (spec.lo + spec.hi), key) is None, key
        for mk in spec.mistakes:
            # a value the mistake explains: the plausible middle written in the wrong unit
            si = math.sqrt(spec.lo * spec.hi) if spec.lo > 0 else 0.5 * spec.hi
            given = (si - mk.offset) / mk.scale
            if implausibility("f", given, key) is not None:
                assert unit_hint(key, given).startswith("did you give"), (key, mk.name)


def test_derived_results_warn_beyond_10_gpa_and_a_millimetre_film():
    assert implausibility("Hertz pmax", 1.2e10, "hertz_pmax") is not None
    assert implausibility("Hertz pmax", 3e9, "hertz_pmax") is None
    assert implausibility("hc_fit", 2e-3, "film") is not None
    assert implausibility("hc_fit", 5e-11, "film") is not None
    assert implausibility("hc_fit", 2e-7, "film") is None


def test_fit_validity_inside_the_range_gives_the_measured_bias_from_the_table():
    tab = fits.deviation_table("point")
    i, j = tab["M"].index(200.0), tab["L"].index(10.0)
    v = fits.fit_validity("point", 200.0, 10.0)  # a table point: the measured value itself
    assert v["in_range"] and v["deviation"] == pytest.approx(tab["deviation"][i, j])
    assert v["deviation_min"] <= v["deviation"] <= v["deviation_max"]
    # the note states the measured bias and its sign against the solver
    assert f"{100 * v['deviation']:+.0f} %" in v["note"] and "above" in v["note"]
    sc = load_scene("default")
    M, L = sc.moes()
    v = fits.fit_validity("point", M, L)
    corners = tab["deviation"][i:i + 2, j - 1:j + 1]  # M in [200, 500], L in [5, 10]
    assert corners.min() == v["deviation_min"] and corners.max() == v["deviation_max"]
    assert corners.min() < v["deviation"] < corners.max()


def test_fit_validity_outside_the_range_says_extrapolated_and_gives_no_bias():
    v = fits.fit_validity("point", 3620.0, 13.1, 0.0305)
    assert not v["in_range"] and math.isnan(v["deviation"])
    assert "extrapolated" in v["note"] and "M = 3620" in v["note"] and "theta = 0.0305" in v["note"]
    v = fits.fit_validity("point", 20.0, 10.0, 4.0)  # theta > 1: the table (theta = 1) does not apply
    assert v["in_range"] and math.isnan(v["deviation"]) and "theta = 4 > 1" in v["note"]


def test_show_summary_of_the_6205_bearing_says_the_fit_is_outside_its_range():
    s = load_scene("bearing_6205_inner_race").summary()
    assert s["hc_fit_in_range"] is False and "extrapolated" in s["hc_fit_note"]
    assert "M in [5, 1000]" in s["hc_fit_range"] and math.isnan(s["hc_fit_deviation"])
    s = load_scene("roller_bearing_inner_race").summary()
    assert s["hc_fit_in_range"] is True and 0.1 < s["hc_fit_deviation"] < 0.4
