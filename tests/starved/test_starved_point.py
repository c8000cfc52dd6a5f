"""Starved, mass-conserving point contact (Elrod-Adams film content, meniscus inside the
multilevel iteration): flooded limit, mass balance, the starved limit, monotone film
reduction and bad supply input. (M, L) = (20, 10), half domain, 129 points along X."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.point.solve import solve_fas
from ehl_multigrid.starved.point import STARVED_TOL, solve_starved_point

KW = dict(points=129, half=True, raise_on_failure=False, max_cycles=40)


@pytest.fixture(scope="module")
def problem():
    return problem_from_moes(20.0, 10.0)


@pytest.fixture(scope="module")
def flooded(problem):
    return solve_fas(problem, wedge_order=1, tol=STARVED_TOL, far_field=False, **KW)  # P = 0 as starved


@pytest.fixture(scope="module")
def starved(problem, flooded):
    Hff = flooded.scalars["Hc_venner"]
    return {ratio: solve_starved_point(problem, ratio * Hff, **KW) for ratio in (0.03, 0.4, 1.0)}


@pytest.mark.solver
@pytest.mark.xdist_group("starved_point_row")
def test_flooded_inlet_reproduces_the_core_flooded_solution(problem, flooded):
    for hoil in (math.inf, 50.0):  # 50: thicker than the gap at the inlet boundary
        s = solve_starved_point(problem, hoil, **KW)
        assert s.status_name == "converged"
        assert s.scalars["Hc_venner"] == pytest.approx(flooded.scalars["Hc_venner"], rel=1e-6)
        assert s.scalars["Hm_venner"] == pytest.approx(flooded.scalars["Hm_venner"], rel=1e-6)
        assert s.extra["mass_balance_error"] < 1e-8
        assert np.all(s.extra["theta"][s.P > 0.0] == 1.0)


@pytest.mark.solver
@pytest.mark.xdist_group("starved_point_row")
def test_starved_solutions_conserve_mass(starved):
    for s in starved.values():
        assert s.status_name == "converged"
        assert s.extra["mass_balance_error"] < 2e-6
        fl = s.extra["fluxes"]
        # the supply enters the inlet face and leaves through the outlet face (no side flow
        # out of the box at these supplies)
        assert fl["out"] == pytest.approx(fl["in"], rel=2e-6)
        assert fl["in"] == pytest.approx(s.extra["hoil"] * (s.Y[-1] - 0.5 * (s.Y[1] - s.Y[0])), rel=1e-3)


@pytest.mark.solver
@pytest.mark.xdist_group("starved_point_row")
def test_severe_starvation_carries_the_supply_through_the_centre(starved):
    s = starved[0.03]
    ratio = s.extra["rho_c"] * s.scalars["Hc_venner"] / s.extra["hoil"]
    assert ratio == pytest.approx(1.0, abs=2e-4)
    # at mild starvation the pressure pushes oil around the contact: less through the centre
    m = starved[1.0]
    assert m.extra["rho_c"] * m.scalars["Hc_venner"] / m.extra["hoil"] < 0.9


@pytest.mark.solver
@pytest.mark.xdist_group("starved_point_row")
def test_film_and_meniscus_fall_with_the_supply(starved, flooded):
    ratios = sorted(starved)
    Hc = [starved[r].scalars["Hc_venner"] for r in ratios]
    xm = [starved[r].extra["meniscus_x"] for r in ratios]
    assert np.all(np.diff(Hc) > 0.0)
    assert Hc[-1] < flooded.scalars["Hc_venner"]
    assert np.all(np.diff(xm) < 0.0)  # meniscus moves upstream with more oil
    assert -1.1 < xm[0] < -1.0  # severe starvation: meniscus at the Hertzian edge
    # the film fills the gap from the meniscus to the outlet rupture on the centre line
    th = starved[0.4].extra["theta"][0]
    X = starved[0.4].X
    assert np.all(th[(X > xm[1] + 0.05) & (X < 0.8)] == 1.0)
    assert np.all(th[X < xm[1] - 0.05] < 1.0)


@pytest.mark.parametrize("hoil", [-0.1, 0.0, float("nan")])
def test_bad_supply_is_a_clear_error(problem, hoil):
    with pytest.raises(InputError, match="hoil"):
        solve_starved_point(problem, hoil, **KW)


def test_point_scene_supply_in_metres_gives_films_in_metres():
    from ehl_multigrid.model.scene import load_scene
    from ehl_multigrid.point.problem import problem_from_scene
    from ehl_multigrid.starved import solve_starved_point_scene

    scene = load_scene("ehl_multigrid/scenes/chapter6_starved_0.5GPa.toml")
    # an eighth of the load (pmax 0.25 GPa, M = 22; flooded hc ~ 34 nm): 65^2 converges (at
    # 0.5 GPa, flooded hc ~ 30 nm, M = 179 needs 129^2)
    scene = scene.with_operating(pmax=2.5e8)
    pb = problem_from_scene(scene)
    sol = solve_starved_point_scene(scene, hoil=5e-9, points=65, raise_on_failure=False)
    sc = sol.scalars
    assert sc["hoil_venner"] == pytest.approx(5e-9 * pb.Rx / pb.a**2, rel=1e-12)
    assert sc["hc"] == pytest.approx(sc["Hc_venner"] * pb.a**2 / pb.Rx, rel=1e-12)
    assert sc["flooded_status"] == "converged"
    assert 0.1 < sc["Hc_ratio"] < 0.2  # a 5 nm layer against a flooded film of about 34 nm
    assert sc["mass_balance_error"] < 1e-5
    with pytest.raises(InputError, match="supply.hoil"):
        solve_starved_point_scene(scene, hoil=-1e-9, points=129)


def test_an_options_objects_tolerance_is_kept_and_keywords_default_to_the_starved_one(problem):
    from ehl_multigrid.multigrid.options import PointOptions

    given = solve_starved_point(problem, 1.0, PointOptions(points=33, half=True, tol=1e-10, max_cycles=2,
                                                         raise_on_failure=False))
    default = solve_starved_point(problem, 1.0, points=33, half=True, max_cycles=2, raise_on_failure=False)
    assert given.options.tol == 1e-10
    assert default.options.tol == STARVED_TOL


def test_a_flooded_point_scene_has_no_supply_ratio_as_the_line():
    from ehl_multigrid.model.scene import load_scene
    from ehl_multigrid.starved import solve_starved_point_scene

    sol = solve_starved_point_scene(load_scene("default"), hoil=math.inf, points=33, flooded=False, accuracy=None)
    assert math.isnan(sol.scalars["rho_c_Hc_over_hoil"])  # rho_c Hc / inf is not a starvation measure
