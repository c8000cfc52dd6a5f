"""Machine elements against hand calculations written out here (Harris & Kotzalas curvatures,
Hamrock & Dowson entrainment speed, involute gear geometry), and bad input."""

import math

import pytest

from ehl_multigrid.model.elements import (
    ball_bearing,
    ball_on_disc,
    ball_on_flat,
    element_contact,
    roller_bearing,
    spur_gear,
)
from ehl_multigrid.model.errors import InputError

RPM = 2 * math.pi / 60
# 6205: 9 balls of 5/16 in = 7.938 mm on dm = (25 + 52)/2 = 38.5 mm
D, DM = 7.938e-3, 38.5e-3


def test_6205_inner_race_radii_from_the_four_curvatures():
    c = ball_bearing(D, DM, 9, 0.52, 0.525, 1500 * RPM, radial_load=350.0)
    gamma = D / DM
    # Harris & Kotzalas ch. 2: rho_I1 = rho_II1 = 2/D, rho_I2 = 2 gamma/(D (1 - gamma)), rho_II2 = -1/(f_i D)
    r_i1 = r_ii1 = 2 / D
    r_i2 = 2 / D * gamma / (1 - gamma)
    r_ii2 = -1 / (0.52 * D)
    assert 1 / c.Rx == pytest.approx(r_i1 + r_i2, rel=1e-12)
    assert 1 / c.Ry == pytest.approx(r_ii1 + r_ii2, rel=1e-12)
    f_rho = ((r_i1 - r_ii1) + (r_i2 - r_ii2)) / (r_i1 + r_ii1 + r_i2 + r_ii2)
    assert c.details["curvature_difference"] == pytest.approx(f_rho, rel=1e-12)
    # Numbers: Rx = 3.1507 mm, Ry = 103.19 mm, theta about 0.03 (a very elongated ellipse)
    assert c.Rx == pytest.approx(3.1507e-3, rel=1e-4)
    assert c.Ry == pytest.approx(103.19e-3, rel=1e-4)
    assert 0.02 < c.theta < 0.035
    assert c.kind == "elliptic"


def test_ball_bearing_entrainment_speed_is_hamrock_dowson():
    c = ball_bearing(D, DM, 9, 0.52, 0.525, 1500 * RPM, ball_load=100.0)
    # Hamrock & Dowson (1981): u = |w_o - w_i| (dm^2 - D^2)/(4 dm) for a zero contact angle
    u = 1500 * RPM * (DM**2 - D**2) / (4 * DM)
    assert c.u1 == pytest.approx(u, rel=1e-12) and c.u2 == pytest.approx(u, rel=1e-12)
    assert c.u1 == pytest.approx(1.4476, rel=1e-4)
    assert c.slip == 0.0
    # cage speed w_i (1 - gamma)/2: 0.397 of the shaft speed for this bearing
    assert c.details["cage_speed"] / (1500 * RPM) == pytest.approx(0.5 * (1 - D / DM), rel=1e-12)


def test_stribeck_load_and_outer_race_and_angular_contact():
    c = ball_bearing(D, DM, 9, 0.52, 0.525, 1500 * RPM, radial_load=350.0)
    assert c.load == pytest.approx(5 * 350.0 / 9, rel=1e-12)
    o = ball_bearing(D, DM, 9, 0.52, 0.525, 1500 * RPM, race="outer", ball_load=100.0)
    assert o.Rx == pytest.approx(D * (1 + D / DM) / 2, rel=1e-12)
    assert o.Ry == pytest.approx(0.525 * D / (2 * 0.525 - 1), rel=1e-12)
    a = ball_bearing(D, DM, 9, 0.52, 0.525, 1500 * RPM, contact_angle=40.0, axial_load=900.0)
    g = D * math.cos(math.radians(40)) / DM
    assert a.Rx == pytest.approx(D * (1 - g) / 2, rel=1e-12)
    assert a.load == pytest.approx(900.0 / (9 * math.sin(math.radians(40))), rel=1e-12)


def test_ball_bearing_bad_input_names_field_value_and_range():
    with pytest.raises(InputError, match=r"f_inner = 0.49.*\(0.5, 0.7\]"):
        ball_bearing(D, DM, 9, 0.49, 0.525, 100.0, ball_load=1.0)
    with pytest.raises(InputError, match=r"ball_load.*radial_load.*axial_load.*\['ball_load', 'radial_load'\]"):
        ball_bearing(D, DM, 9, 0.52, 0.525, 100.0, ball_load=1.0, radial_load=2.0)
    with pytest.raises(InputError, match="race = 'middle'"):
        ball_bearing(D, DM, 9, 0.52, 0.525, 100.0, race="middle", ball_load=1.0)
    with pytest.raises(InputError, match=r"axial_load.*angle.* 0 deg"):
        ball_bearing(D, DM, 9, 0.52, 0.525, 100.0, axial_load=1.0)


def test_spur_gear_pitch_point_radius_is_r_sin_alpha_and_pure_rolling():
    # m = 5 mm, 20/40 teeth, 20 deg: r1 = 50 mm, r2 = 100 mm
    g = spur_gear(5e-3, 20, 40, 0.02, 100.0, torque=200.0)
    s20 = math.sin(math.radians(20))
    rho1, rho2 = 0.05 * s20, 0.10 * s20
    assert g.details["rho1"] == pytest.approx(rho1, rel=1e-12)
    assert g.Rx == pytest.approx(rho1 * rho2 / (rho1 + rho2), rel=1e-12)
    assert g.Rx == pytest.approx(11.4007e-3, rel=1e-4)
    assert g.u1 == pytest.approx(g.u2, rel=1e-12) and g.slip == pytest.approx(0.0, abs=1e-12)
    # normal force T1/r_b1 in the single-pair zone, over the face width
    assert g.load == pytest.approx(200.0 / (0.05 * math.cos(math.radians(20))), rel=1e-12)
    assert g.length == 0.02


def test_spur_gear_contact_ratio_by_the_centre_distance_formula():
    g = spur_gear(5e-3, 20, 40, 0.02, 100.0, torque=200.0)
    c20 = math.cos(math.radians(20))
    ra1, ra2, rb1, rb2, a = 0.055, 0.105, 0.05 * c20, 0.10 * c20, 0.15
    eps = (math.sqrt(ra1**2 - rb1**2) + math.sqrt(ra2**2 - rb2**2) - a * math.sin(math.radians(20))) / (
        math.pi * 5e-3 * c20
    )
    assert g.details["contact_ratio"] == pytest.approx(eps, rel=1e-12)
    assert eps == pytest.approx(1.635, abs=1e-3)


def test_spur_gear_off_the_pitch_point_slides_and_shares_load_in_the_double_zone():
    w1 = 100.0
    end = spur_gear(5e-3, 20, 40, 0.02, w1, torque=200.0).details["path_end"]
    s = 0.9 * end  # near the pinion tip: two pairs in mesh
    g = spur_gear(5e-3, 20, 40, 0.02, w1, torque=200.0, position=s)
    assert g.details["sliding_speed"] == pytest.approx((w1 + w1 * 20 / 40) * s, rel=1e-12)
    assert g.details["load_share"] == 0.5
    assert g.slip > 0.0  # pinion flank faster near its tip
    with pytest.raises(InputError, match=r"spur_gear\)\.position = 0\.0126\d* m.*\[-0\.0126\d*, 0\.0114\d*\]"):
        spur_gear(5e-3, 20, 40, 0.02, w1, torque=200.0, position=1.1 * end)


def test_helical_gear_base_helix_angle_and_normal_radius():
    g = spur_gear(3e-3, 25, 50, 0.03, 100.0, pressure_angle=20.0, helix_angle=15.0, power=5e3)
    at = math.radians(g.details["transverse_pressure_angle"])
    bb = math.radians(g.details["base_helix_angle"])
    # ISO 21771: tan(beta_b) = tan(beta) cos(alpha_t), an independent form of sin(b_b) = sin(b) cos(a_n)
    assert math.tan(bb) == pytest.approx(math.tan(math.radians(15)) * math.cos(at), rel=1e-12)
    rho_t = g.details["rho1"] * g.details["rho2"] / (g.details["rho1"] + g.details["rho2"])
    assert g.Rx == pytest.approx(rho_t / math.cos(bb), rel=1e-12)
    assert g.details["pinion_torque"] == pytest.approx(5e3 / 100.0)


def test_roller_bearing_line_contact():
    r = roller_bearing(10e-3, 62.5e-3, 14, 10e-3, 1500 * RPM, radial_load=10e3)
    assert r.kind == "line" and math.isinf(r.Ry) and r.length == 10e-3
    assert r.Rx == pytest.approx(10e-3 * (1 - 0.16) / 2, rel=1e-12)
    assert r.load == pytest.approx(4.08 * 10e3 / 14, rel=1e-12)


def test_ball_on_disc_rolling_fixed_ball_and_driven_ball():
    c = ball_on_disc(9.525e-3, 0.04, 120 * RPM, 20.0)
    assert c.u2 == pytest.approx(120 * RPM * 0.04, rel=1e-12) and c.slip == 0.0
    fixed = ball_on_disc(9.525e-3, 0.04, 120 * RPM, 20.0, ball_speed=0.0)
    assert fixed.slip == pytest.approx(-2.0)  # pin-on-disc: pure sliding, ball at rest
    with pytest.raises(InputError, match=r"u1 \+ u2 = -0\.497\d* m/s.*> 0"):
        ball_on_disc(9.525e-3, 0.04, 120 * RPM, 20.0, ball_speed=-1.0)


def test_ball_on_flat_hfrr_speeds():
    # HFRR (ISO 12156-1): 1 mm stroke at 50 Hz: max speed pi f L = 0.157 m/s, mean 2 f L = 0.1 m/s
    c = ball_on_flat(3e-3, 1e-3, 50.0, 2.0)
    assert c.u1 == pytest.approx(0.15708, rel=1e-4) and c.u2 == 0.0 and c.slip == 2.0
    assert c.details["mean_speed"] == pytest.approx(0.1)


def test_element_table_with_units_matches_the_si_call():
    t = {"kind": "ball_bearing", "ball_diameter": "7.938 mm", "pitch_diameter": "38.5 mm",
         "n_balls": 9, "f_inner": 0.52, "f_outer": 0.525, "shaft_speed": "1500 rpm",
         "radial_load": "0.35 kN"}
    assert element_contact(t) == ball_bearing(D, DM, 9, 0.52, 0.525, 1500 * RPM, radial_load=350.0)


def test_element_table_errors_name_the_problem():
    with pytest.raises(InputError, match="element.kind = 'cam'"):
        element_contact({"kind": "cam"})
    with pytest.raises(InputError, match=r"\['radius'\].*\['ball_radius', 'frequency', 'load', 'stroke'\]"):
        element_contact({"kind": "ball_on_flat", "radius": 1.0})
    with pytest.raises(InputError, match="missing"):
        element_contact({"kind": "ball_on_flat", "ball_radius": "3 mm"})
    with pytest.raises(InputError, match=r"n_balls = 8\.5 .*whole"):
        element_contact({"kind": "ball_bearing", "n_balls": 8.5})
    with pytest.raises(InputError, match=r"element.ball_radius = '3 GPa'.*length"):
        element_contact({"kind": "ball_on_flat", "ball_radius": "3 GPa"})
