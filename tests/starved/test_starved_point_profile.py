"""Starved point contact with a supply profile across the track (one layer per grid row):
the uniform profile is the scalar supply, bad profiles are clear errors, and side ridges
outside the over-rolled track feed the contact far less than the same oil spread evenly.
(M, L) = (20, 10), half domain, 129 points along X."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import Scene, load_scene
from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.starved.point import StarvedPointHierarchy, solve_starved_point

KW = dict(points=129, half=True, raise_on_failure=False)
HC_FF = 0.4466  # first-order flooded central film at 129^2


@pytest.fixture(scope="module")
def problem():
    return problem_from_moes(20.0, 10.0)


@pytest.fixture(scope="module")
def rows(problem):
    return StarvedPointHierarchy(problem, PointOptions.build(None, wedge_order=1, **KW), 1.0).levels[-1].Y


@pytest.mark.solver
def test_a_uniform_profile_is_the_scalar_supply(problem, rows):
    a = solve_starved_point(problem, 0.4 * HC_FF, **KW)
    b = solve_starved_point(problem, np.full(rows.size, 0.4 * HC_FF), **KW)
    assert a.status_name == b.status_name == "converged"
    assert np.array_equal(a.P, b.P) and np.array_equal(a.extra["theta"], b.extra["theta"])
    assert b.extra["hoil"] == pytest.approx(0.4 * HC_FF, rel=1e-14)


@pytest.mark.parametrize("bad", ["short", "long", "nan", "negative", "2d"])
def test_bad_supply_profiles_are_clear_errors(problem, rows, bad):
    prof = np.full(rows.size, 0.1)
    if bad == "short":
        prof = prof[:-1]
    elif bad == "long":
        prof = np.append(prof, 0.1)
    elif bad == "nan":
        prof[3] = math.nan
    elif bad == "negative":
        prof[3] = -0.1
    else:
        prof = prof[None, :]
    with pytest.raises(InputError, match="hoil_profile"):
        solve_starved_point(problem, prof, **KW)


@pytest.mark.solver
def test_side_ridges_outside_the_track_barely_feed_the_contact(problem, rows):
    h_in = 0.25 * HC_FF
    prof = np.where(np.abs(rows) >= 1.0, 3.0 * h_in, h_in)
    track = solve_starved_point(problem, h_in, **KW)
    ridge = solve_starved_point(problem, prof, **KW)
    spread = solve_starved_point(problem, ridge.extra["hoil"], **KW)
    for s in (track, ridge, spread):
        assert s.status_name == "converged" and s.extra["mass_balance_error"] < 1e-6
    Hc = [s.scalars["Hc_venner"] for s in (track, ridge, spread)]
    assert Hc[1] == pytest.approx(Hc[0], rel=0.01)  # the track's own layer sets the central film
    assert Hc[2] > 1.5 * Hc[1]  # the same oil spread evenly over the box feeds it much more


# -- a scene's [supply] hoil_profile ---------------------------------------------------------
def _profile_scene(supply, load_factor=1.0):
    import copy

    d = copy.deepcopy(load_scene("chapter6_starved_0.5GPa").to_dict())
    s = {k: v for k, v in d["supply"].items() if k != "hoil"}
    s.update(supply)
    d["supply"] = s
    d["operating"]["load"] *= load_factor
    return Scene.from_dict(d)


def test_a_scene_profile_round_trips_and_gives_the_centre_layer_as_hoil():
    sc = _profile_scene({"hoil_profile": {"y": [0.0, 60e-6, 90e-6], "hoil": [20e-9, 20e-9, 60e-9]}})
    assert sc.supply.hoil == 20e-9
    assert list(sc.supply.layer_at(np.array([0.0, -75e-6, 1e-3]))) == pytest.approx([20e-9, 40e-9, 60e-9])
    assert Scene.from_dict(sc.to_dict()).supply == sc.supply


@pytest.mark.parametrize("supply, match", [
    ({"hoil": 20e-9, "hoil_profile": {"y": [0.0, 1e-4], "hoil": [2e-8, 2e-8]}}, "not both"),
    ({"hoil_profile": {"y": [0.0, 1e-4, 5e-5], "hoil": [2e-8, 2e-8, 2e-8]}}, "must increase"),
    ({"hoil_profile": {"y": [0.0, 1e-4], "hoil": [2e-8, -1e-9]}}, r"hoil_profile.hoil\[1\]"),
    ({"hoil_profile": {"y": [0.0], "hoil": [2e-8]}}, "length >= 2"),
    ({"hoil_profile": [1, 2]}, "must be a table"),
])
def test_bad_scene_profiles_are_named(supply, match):
    from ehl_multigrid.model.errors import InputError

    with pytest.raises(InputError, match=match):
        _profile_scene(supply)


def test_a_flat_scene_profile_gives_the_uniform_supply_and_ridges_lift_the_minimum_film():
    from ehl_multigrid.starved import solve_starved_point_scene

    # an eighth of the load (pmax 0.25 GPa, M = 22, the 20 nm layer half the flooded film): 65^2
    # converges (0.5 GPa, M = 179, needs 129^2); the flooded film is not compared here
    kw = dict(points=65, estimate=False, flooded=False)
    uniform = solve_starved_point_scene(_profile_scene({"hoil": 20e-9}, 0.125), **kw)
    flat = solve_starved_point_scene(
        _profile_scene({"hoil_profile": {"y": [0.0, 1e-3], "hoil": [20e-9, 20e-9]}}, 0.125), **kw)
    assert flat.scalars["hc"] == uniform.scalars["hc"] and flat.scalars["hm"] == uniform.scalars["hm"]
    a = _profile_scene({"hoil": 20e-9}, 0.125).hertz.a
    ridges = solve_starved_point_scene(_profile_scene(
        {"hoil_profile": {"y": [0.0, 0.9 * a, 1.1 * a], "hoil": [20e-9, 20e-9, 60e-9]}}, 0.125), **kw)
    assert ridges.success and ridges.extra["mass_balance_error"] < 1e-6
    assert ridges.scalars["hm"] > uniform.scalars["hm"]
    assert ridges.scalars["hc"] == pytest.approx(uniform.scalars["hc"], rel=0.01)


def test_a_line_scene_refuses_a_supply_profile():
    from ehl_multigrid.model.errors import InputError

    d = load_scene("page63_line_2000N").to_dict()
    d["supply"] = {"hoil_profile": {"y": [0.0, 1e-4], "hoil": [1e-8, 2e-8]}}
    with pytest.raises(InputError, match=r"supply\.hoil_profile\b.*\bline\b.*supply\.hoil\b"):
        Scene.from_dict(d)
