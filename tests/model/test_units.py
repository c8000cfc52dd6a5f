"""Scene values with units (pint): conversion to SI / degC / degrees and wrong-dimension errors."""

import math

import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.units import convert_table, to_canonical


@pytest.mark.parametrize(
    ("text", "kind", "expected"),
    [
        ("7.94 mm", "length", 7.94e-3),
        ("1.5 GPa", "pressure", 1.5e9),
        ("68 cSt", "kinematic_viscosity", 68e-6),  # 1 cSt = 1 mm^2/s
        ("68 mm^2/s", "kinematic_viscosity", 68e-6),
        ("70 degC", "temperature", 70.0),
        ("343.15 K", "temperature", 70.0),
        ("158 degF", "temperature", 70.0),  # (158 - 32)/1.8
        ("1500 rpm", "angular_speed", 1500 * 2 * math.pi / 60),
        ("2 m/s", "speed", 2.0),
        ("20 deg", "angle", 20.0),
        ("0.5 rad", "angle", math.degrees(0.5)),
        ("15 1/GPa", "inverse_pressure", 15e-9),
        ("250 N*m", "torque", 250.0),
        ("2 kW", "power", 2000.0),
        ("5 %", "dimensionless", 0.05),
    ],
)
def test_strings_with_units_convert_to_the_canonical_unit(text, kind, expected):
    assert to_canonical("f", text, kind) == pytest.approx(expected, rel=1e-12)


def test_plain_numbers_pass_through_unchanged_without_pint():
    assert to_canonical("f", 7, "length") == 7.0
    assert to_canonical("f", 2.5e9, "pressure") == 2.5e9
    assert to_canonical("f", "7.5", "length") == 7.5  # a quoted plain number is a plain number
    assert to_canonical("f", math.inf, "length") == math.inf


def test_wrong_dimension_names_field_value_and_expected_dimension():
    with pytest.raises(InputError) as e:
        to_canonical("element.ball_diameter", "7 GPa", "length")
    msg = str(e.value)
    assert "element.ball_diameter" in msg and "'7 GPa'" in msg and "length" in msg and "[length]" in msg


@pytest.mark.parametrize("bad", ["abc def", "7 furlongz", True, [1.0], None])
def test_unreadable_values_are_rejected_with_the_field_name(bad):
    with pytest.raises(InputError, match="operating.us"):
        to_canonical("operating.us", bad, "speed")


def test_convert_table_converts_listed_keys_and_keeps_the_rest():
    out = convert_table("s", {"Rx": "10 mm", "name": "x", "n": 3, "lst": [1, 2]}, {"Rx": "length", "n": "length"})
    assert out == {"Rx": pytest.approx(0.01), "name": "x", "n": 3.0, "lst": [1, 2]}
