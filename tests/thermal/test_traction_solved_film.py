"""The traction functions take the main job's typed film
(:class:`~ehl_multigrid.model.solved_film.SolvedFilm`) as they take its Result: the same
friction to the last bit, and the same refusals of another contact's film and of a film whose
solve failed."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.results import Result
from ehl_multigrid.model.scene import load_scene
from ehl_multigrid.model.solved_film import SolvedFilm
from thermal.options import ThermalOptions
from thermal.stage import (
    ModelChoice,
    OperatingFriction,
    choose_model,
    operating_friction,
    with_coupled_friction,
)
from thermal.traction import ehl_result_from, solve_traction, traction_curve


def solved_hertz_film(scene, status: str = "converged") -> Result:
    """Hertz pressure with a film that narrows towards the outlet, as a solved EHL result of
    ``scene`` (a uniform film would not exercise the pressure-driven flux)."""
    hz = scene.hertz
    hc = scene.central_film_fit()[1]
    if scene.kind == "line":
        x = np.linspace(-2.5 * hz.b, 1.0 * hz.b, 61)
        p = hz.pmax * np.sqrt(np.clip(1 - (x / hz.b) ** 2, 0, None))
        res = ehl_result_from((x, p, hc * (1.2 - 0.2 * x / x[-1])), scene)
    else:
        x = np.linspace(-2.5 * hz.a, 1.0 * hz.a, 61)
        y = np.linspace(0.0, hz.b, 11)
        P = hz.pmax * np.sqrt(np.clip(1 - (x[:, None] / hz.a) ** 2 - (y[None, :] / hz.b) ** 2, 0, None))
        H = np.broadcast_to(hc * (1.2 - 0.2 * x[:, None] / x[-1]), P.shape).copy()
        res = ehl_result_from((x, y, P, H), scene)
    res.set_scalar("hc", hc, "m")
    res.set_scalar("status", status)
    return res


@pytest.mark.parametrize("name", ["appendix_c_line_4240N", "appendix_d_point"])
def test_friction_on_the_typed_film_is_friction_on_its_result(name):
    sc = load_scene(name)
    res = solved_hertz_film(sc)
    film = SolvedFilm.from_result(res)
    opts = ThermalOptions.for_fidelity(sc, "fast")
    a = traction_curve(sc, [0.1, 0.5], input="ehl", ehl=film, options=opts)
    b = traction_curve(sc, [0.1, 0.5], input="ehl", ehl=res, options=opts)
    for pa, pb in zip(a, b, strict=True):
        assert pa.coefficient == pb.coefficient and pa.max_temperature_rise == pb.max_temperature_rise
    # the traction stage's model choice and operating point, through the same keyword
    ca = choose_model(sc, [0.1, 0.5], opts, 0.1, input="ehl", ehl=film)
    cb = choose_model(sc, [0.1, 0.5], opts, 0.1, input="ehl", ehl=res)
    assert (ca.thermal, ca.f_thermal, ca.f_isothermal) == (cb.thermal, cb.f_thermal, cb.f_isothermal)
    choice = ModelChoice(True, 0.5, "test")
    oa = operating_friction(sc, opts, choice, input="ehl", ehl=film)
    ob = operating_friction(sc, opts, choice, input="ehl", ehl=res)
    assert (oa.coefficient, oa.error) == (ob.coefficient, ob.error)


def test_a_typed_film_of_another_contact_is_refused_naming_the_quantity():
    sc = load_scene("appendix_c_line_4240N")
    other = SolvedFilm.from_result(solved_hertz_film(sc.with_operating(load=2.0 * sc.load)))
    with pytest.raises(InputError, match="load"):
        solve_traction(sc, 0.1, input="ehl", ehl=other, nx=20, nz=5)


def test_a_typed_film_whose_solve_failed_is_refused():
    sc = load_scene("appendix_c_line_4240N")
    failed = SolvedFilm.from_result(solved_hertz_film(sc, status="diverged"))
    with pytest.raises(InputError, match="diverged"):
        solve_traction(sc, 0.1, input="ehl", ehl=failed, nx=20, nz=5)


def test_the_coupled_solves_friction_widens_the_operating_frictions_error_by_their_difference():
    op = OperatingFriction(0.6, 0.04443, 8.3e-5, {"grid": 8.0e-5, "iteration": 3e-7})
    assert with_coupled_friction(op, None) is op and with_coupled_friction(op, math.nan) is op
    both = with_coupled_friction(op, 0.04426)
    assert both.parts["coupled"] == pytest.approx(1.7e-4) and both.parts["grid"] == 8.0e-5
    assert both.error == pytest.approx(8.0e-5 + 3e-7 + 1.7e-4) and both.coefficient == op.coefficient
