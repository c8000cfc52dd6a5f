"""The film stage hands the later stages its solved film as a typed
:class:`~ehl_multigrid.model.solved_film.SolvedFilm` (``RunContext.film()``) next to the Result
that goes to HDF5: the same central film, starvation ratio and dimensional arrays; no solved
film when the film is the fit."""

from __future__ import annotations

import numpy as np
import pytest

from ehl_multigrid.app.mainjob import film_stage
from ehl_multigrid.app.plan import make_plan
from ehl_multigrid.app.stages import RunContext
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.results import Result
from ehl_multigrid.model.scene import Scene, load_scene
from ehl_multigrid.model.solved_film import SolvedFilm


def _run_film_stage(scene, tmp_path, **plan_args) -> RunContext:
    ctx = RunContext(scene, make_plan(scene, **plan_args), tmp_path, plots=False, progress=False)
    ctx.outputs["film"] = film_stage(ctx)
    return ctx


def _same_arrays(film: SolvedFilm, res: Result, names: tuple[str, ...]) -> None:
    for name in names:
        a = getattr(film, name)
        np.testing.assert_array_equal(a, res[name])
        assert not a.flags.writeable


@pytest.mark.solver
def test_the_film_stage_hands_on_its_solved_film_as_its_result_holds_it(tmp_path):
    sc = load_scene("appendix_c_line_4240N")
    ctx = _run_film_stage(sc, tmp_path, fidelity="fast")
    out = ctx.outputs["film"]
    assert ctx.plan.get("film").setting == "multigrid solver" and out.result.kind == "ehl_line"
    film = ctx.film()
    assert film is out.film and film.contact == "line" and film.kind == "ehl_line"
    assert film.hc == out.result.scalars["hc"] == out.summary["hc"] > 0.0
    assert film.Hc_ratio is None and film.y is None
    assert film.status == out.summary["status"] and film.status in ("converged", "inaccurate")
    assert film.scene is out.result.scene
    _same_arrays(film, out.result, ("x", "p", "h"))


@pytest.mark.solver
def test_a_starved_solve_hands_on_its_ratio_to_the_flooded_film(tmp_path):
    d = load_scene("page63_line_500N").with_supply(hoil=1.5e-8).to_dict()
    d.setdefault("solver", {}).setdefault("ehl", {})["points"] = 257  # kept and judged: a cheap solve
    sc = Scene.from_dict(d)
    ctx = _run_film_stage(sc, tmp_path, fidelity="standard")  # at "fast" the fit would do
    assert ctx.plan.get("film").setting == "multigrid solver"
    out = ctx.outputs["film"]
    film = ctx.film()
    assert film is not None and out.summary["Hc_ratio"] is not None
    assert film.Hc_ratio == out.result.scalars["Hc_ratio"] == out.summary["Hc_ratio"]
    assert 0.0 < film.Hc_ratio < 1.0 and film.hc == out.result.scalars["hc"]


def test_a_fitted_film_is_no_solved_film(tmp_path):
    sc = load_scene("appendix_c_line_4240N")
    assert RunContext(sc, make_plan(sc), tmp_path).film() is None  # no film stage yet
    ctx = _run_film_stage(sc, tmp_path, tolerance=0.5)
    assert ctx.plan.get("film").setting == "fit" and ctx.outputs["film"].result.kind == "hertz_fit"
    assert ctx.film() is None


def test_a_point_film_carries_both_coordinates_and_its_fields_on_them():
    sc = load_scene("appendix_d_point")
    x, y = np.linspace(-2e-4, 1e-4, 7), np.linspace(0.0, 1e-4, 4)
    res = Result("ehl_point", scene=sc)
    res.add_coord("x", x, "m")
    res.add_coord("y", y, "m")
    res.add_field("p", np.ones((7, 4)), "Pa", ("x", "y"))
    res.add_field("h", np.full((7, 4), 1e-7), "m", ("x", "y"))
    res.set_scalar("hc", 1e-7, "m")
    res.set_scalar("status", "converged")
    film = SolvedFilm.from_result(res)
    assert film.contact == "point" and film.hc == 1e-7 and film.status == "converged"
    _same_arrays(film, res, ("x", "y", "p", "h"))


def test_a_result_that_is_no_solved_film_is_refused():
    sc = load_scene("appendix_c_line_4240N")
    with pytest.raises(InputError, match="hertz_fit"):
        SolvedFilm.from_result(Result("hertz_fit", scene=sc))
    bare = Result("ehl_line", scene=sc)
    bare.set_scalar("hc", 1e-7, "m")
    with pytest.raises(InputError, match="x"):
        SolvedFilm.from_result(bare)
