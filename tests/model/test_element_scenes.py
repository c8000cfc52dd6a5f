"""The four machine-element scenes load, and `ehl show --json` prints their radii, speeds and load."""

import json
import math

import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.model.elements import ball_bearing
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import Scene, load_scene

ELEMENT_SCENES = {
    "bearing_6205_inner_race": "ball_bearing",
    "spur_gear_pitch_point": "spur_gear",
    "roller_bearing_inner_race": "roller_bearing",
    "ball_on_disc_tribometer": "ball_on_disc",
}


@pytest.mark.parametrize("name", sorted(ELEMENT_SCENES))
def test_show_json_prints_radii_speeds_and_load(capsys, name):
    assert main(["show", name, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    sc = load_scene(name)
    assert out["element"] == ELEMENT_SCENES[name]
    for key in ("Rx", "Ry", "u1", "u2", "us", "entrainment_speed", "slip", "load", "pmax", "hc_fit"):
        assert key in out, key
    assert out["Rx"] == pytest.approx(sc.element.Rx) and out["load"] == pytest.approx(sc.element.load)
    assert out["us"] == pytest.approx(sc.element.u1 + sc.element.u2)
    # the resolved scene round-trips without the element table
    assert Scene.from_dict(sc.to_dict()).hertz.pmax == pytest.approx(sc.hertz.pmax, rel=1e-12)


def test_6205_scene_is_the_hand_calculated_contact_at_about_1_5_gpa():
    sc = load_scene("bearing_6205_inner_race")
    c = ball_bearing(7.938e-3, 38.5e-3, 9, 0.52, 0.525, 1500 * 2 * math.pi / 60, radial_load=350.0)
    assert (sc.Rx, sc.Ry, sc.load, sc.us) == pytest.approx((c.Rx, c.Ry, c.load, c.us), rel=1e-12)
    assert sc.kind == "elliptic" and sc.hertz.pmax == pytest.approx(1.5e9, rel=0.02)
    # the oil is exact at the inlet temperature: eta0 = nu(70 degC) rho(70 degC)
    assert sc.eta0 == pytest.approx(sc.oil.dynamic_viscosity(70.0), rel=1e-12)
    assert sc.oil.viscosity_index == pytest.approx(100.0, abs=1e-6)


def _bod(**changes):
    d = {
        "element": {"kind": "ball_on_disc", "ball_radius": "9.525 mm", "track_radius": "40 mm",
                    "disc_speed": "120 rpm", "load": "20 N"},
        "lubricant": {"oil": "PAO-VG68"},
        "operating": {"T_oil": "40 degC"},
    }
    for k, v in changes.items():
        d[k] = v
    return Scene.from_dict(d)


def test_operating_values_override_the_element_and_entrainment_speed_doubles_to_us():
    sc = _bod(operating={"T_oil": 40.0, "pmax": "1 GPa", "entrainment_speed": "0.5 m/s", "slip": 0.1})
    assert sc.hertz.pmax == pytest.approx(1e9, rel=1e-9)
    assert sc.us == pytest.approx(1.0) and sc.slip == 0.1
    with pytest.raises(InputError, match=r"\bus\b.*entrainment_speed"):
        _bod(operating={"us": 1.0, "entrainment_speed": 0.5})


def test_element_scene_errors():
    with pytest.raises(InputError, match=r"\[geometry\].*\[element\]"):
        _bod(geometry={"Rx": 0.01})
    with pytest.raises(InputError, match=r"contact\.kind = 'line'.*'ball_on_disc'.*'point'"):
        _bod(contact={"kind": "line", "length": 0.01})


def test_units_in_an_ordinary_scene_and_scene_materials():
    d = load_scene("default").to_dict()
    d["geometry"] = {"Rx": "10.32 mm", "Ry": "10.32 mm"}
    d["operating"].update(load="42.8 N", us="8 m/s", T_oil="60 degC")
    d["solids"] = {"body1": "mySi3N4", "body2": {"preset": "steel", "E": "200 GPa"}}
    d["materials"] = {"mySi3N4": {"preset": "Si3N4", "E": "300 GPa"}}
    sc = Scene.from_dict(d)
    assert sc.Rx == pytest.approx(0.01032) and sc.body1.E == 300e9 and sc.body2.E == 200e9
    d["operating"]["load"] = "42.8 m"
    with pytest.raises(InputError, match=r"operating.load = '42.8 m'.*force"):
        Scene.from_dict(d)
