"""The operating friction's error counts the grid of the film it is computed on
(thermal/film_error.py): a fuel-pump roller (line, M 62, L 4.5) at the planner's 2 % whose
stated error without that part missed the friction on finer films by four times."""

from __future__ import annotations

import math

import pytest

from ehl_multigrid import solve
from ehl_multigrid.app.plan import make_plan
from ehl_multigrid.model.scene import load_scene
from ehl_multigrid.model.solved_film import SolvedFilm
from thermal.film_error import film_friction_part
from thermal.options import ThermalOptions
from thermal.stage import choose_model, finer, operating_friction, with_film_part
from thermal.traction import default_slips, solve_traction

FUEL_PUMP = """
name = "fuel_pump_roller"
description = "diesel-lubricated roller on a cam track: r 4 mm, 8 mm long, 1.2 kN, 4 m/s"
[contact]
kind = "line"
length = 0.008
[geometry]
R1x = 0.004
R2x = inf
[solids]
body1 = "steel"
body2 = "steel"
[lubricant]
preset = "T9"
eta0 = 0.0016
T0 = 60.0
alpha = 1.2e-8
rho0 = 820.0
name = "diesel fuel"
[operating]
load = 1200.0
us = 4.0
slip = 0.05
T_oil = 60.0
"""


@pytest.fixture(scope="module")
def operating(tmp_path_factory):
    path = tmp_path_factory.mktemp("scene") / "fuel_pump_roller.toml"
    path.write_text(FUEL_PUMP)
    scene = load_scene(path)
    plan = make_plan(scene)
    sol = solve(scene, accuracy=plan.tolerance)
    film = SolvedFilm.from_result(sol.to_result(), sol.grid)
    base = ThermalOptions.for_fidelity(scene, plan.fidelity)
    choice = choose_model(scene, [*map(float, default_slips(scene)), scene.slip], base, plan.tolerance,
                          input="ehl", ehl=film)
    options = base.with_changes(thermal=choice.thermal)
    op = operating_friction(scene, options, choice, input="ehl", ehl=film)
    part = film_friction_part(scene, film, finer(options), op.coefficient, input="ehl", ehl=film)
    # the friction on a film eight times finer, the same box: the film's grid error gone
    fine = solve(scene, accuracy=None, options={"points": 8 * (sol.grid.points - 1) + 1,
                                                "xmin": sol.grid.box[0], "xmax": sol.grid.box[1]})
    f_fine = solve_traction(scene, scene.slip, options=finer(options), input="ehl",
                            ehl=SolvedFilm.from_result(fine.to_result(), fine.grid)).coefficient
    return op, part, f_fine


def test_the_friction_on_a_finer_film_lies_within_the_error_with_the_film_part(operating):
    op, part, f_fine = operating
    total = with_film_part(op, part)
    assert total.converged and math.isfinite(part.error) and part.error > 0.0
    assert abs(total.coefficient - f_fine) <= total.error
    # without the film's part the stated error did not cover it: the part is what holds
    assert abs(op.coefficient - f_fine) > op.error


def test_the_film_part_is_richardson_over_three_nested_films(operating):
    _, part, _ = operating
    assert len(part.frictions) == 3 and "coarser grids" in part.how
    f4, f2, f1 = part.frictions
    assert (f4 - f2) / (f2 - f1) == pytest.approx(4.0, rel=0.2)  # second order in the film's grid


def test_a_film_without_its_grid_has_an_unknown_film_part(operating):
    op, part, _ = operating
    assert math.isnan(film_friction_part(load_scene("default"), None, ThermalOptions(), 0.01).error)
    unknown = with_film_part(op, type(part)(math.nan, (), "not known"))
    assert not unknown.converged and math.isnan(unknown.error)


def test_a_point_film_part_is_first_order_from_the_grid_with_half_the_intervals():
    from ehl_multigrid.multigrid.accuracy import GRID_SAFETY

    scene = load_scene("default")
    sol = solve(scene, accuracy=None, options={"points": 129, "half": True})
    film = SolvedFilm.from_result(sol.to_result(), sol.grid)
    options = ThermalOptions(nx=40, nz=10, slices=5)
    f = solve_traction(scene, scene.slip, options=options, input="ehl", ehl=film).coefficient
    part = film_friction_part(scene, film, options, f, input="ehl", ehl=film)
    coarse, fine = part.frictions
    assert fine == f and part.error == pytest.approx(GRID_SAFETY * abs(fine - coarse), rel=1e-12)
