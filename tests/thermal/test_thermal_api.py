"""Public interface: film_friction contract, error paths, Result storage, CLI (thesis ch. 3)."""

import dataclasses
import inspect
import json
import math

import numpy as np
import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.model.convergence import ConvergenceReport
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.results import Result
from ehl_multigrid.model.scene import Scene
from thermal import (
    FilmFriction,
    ThermalOptions,
    film_friction,
    solve_traction,
    traction_curve,
    traction_result,
)


def test_film_friction_contract_signature_and_fields():
    sig = inspect.signature(film_friction)
    kw = [p for p in sig.parameters.values() if p.kind is inspect.Parameter.KEYWORD_ONLY]
    assert [p.name for p in kw] == ["load", "h", "us", "slip", "thermal", "pressure"]
    assert sig.parameters["thermal"].default is True and sig.parameters["pressure"].default == "hertz"
    assert [f.name for f in dataclasses.fields(FilmFriction)] == [
        "force", "coefficient", "mean_shear_stress", "area", "max_temperature_rise",
        "mean_temperature_rise", "converged", "report",
    ]


@pytest.mark.parametrize("name", ["line_lo", "point"])
def test_film_friction_returns_consistent_numbers(name, request):
    sc = request.getfixturevalue(name)
    load = 0.6 * sc.load
    h = 0.5 * sc.central_film_fit()[1]
    ff = film_friction(sc, load=load, h=h, us=5.0, slip=0.3, slices=4)
    assert isinstance(ff.report, ConvergenceReport) and ff.converged
    assert ff.force > 0
    assert ff.coefficient == pytest.approx(ff.force / load)
    assert ff.mean_shear_stress == pytest.approx(ff.force / ff.area)

    assert ff.area == pytest.approx(sc.hertz_at(load).area)  # at the given load
    assert ff.max_temperature_rise > ff.mean_temperature_rise > 0
    iso = film_friction(sc, load=load, h=h, us=5.0, slip=0.3, thermal=False, slices=4)
    assert iso.max_temperature_rise == 0.0 and iso.mean_temperature_rise == 0.0
    assert iso.force > ff.force
    neg = film_friction(sc, load=load, h=h, us=5.0, slip=-0.3, slices=4)
    assert neg.force == pytest.approx(-ff.force, rel=1e-9)


def test_film_friction_thesis_pressure_applies_to_point_slices(point):
    h = point.central_film_fit()[1]
    a = film_friction(point, load=point.load, h=h, us=8.0, slip=0.2, slices=4)
    b = film_friction(point, load=point.load, h=h, us=8.0, slip=0.2, slices=4, pressure="thesis")
    assert b.force > a.force
    with pytest.raises(InputError, match="pressure"):
        film_friction(point, load=point.load, h=h, us=8.0, slip=0.2, pressure="ehl")


# -- error paths ------------------------------------------------------------------------------
def test_zero_or_negative_film_is_rejected(line_lo):
    for h in (0.0, -1e-8, math.nan):
        with pytest.raises(InputError, match="film thickness h"):
            film_friction(line_lo, load=4240.0, h=h, us=8.0, slip=0.1)
    x = np.linspace(-3e-4, 2e-4, 50)
    with pytest.raises(InputError, match="film thickness h"):
        solve_traction(line_lo, 0.1, input="ehl", ehl=(x, np.zeros(50), np.zeros(50)))


def test_temperatures_outside_the_model_are_rejected(line_lo):
    with pytest.raises(InputError, match="T_oil"):
        solve_traction(line_lo, 0.1, T_oil=-300.0)
    with pytest.raises(InputError, match="T_surface2"):
        film_friction(line_lo, load=4240.0, h=2e-7, us=8.0, slip=0.1, T_surface2=-80.0)
    d = line_lo.to_dict()
    d["operating"]["T_surface1"] = -273.0
    with pytest.raises(InputError, match="T_surface1"):
        Scene.from_dict(d)


def test_unknown_oil_is_rejected(line_lo):
    known = r"'SAE-999'.*\['HVI-160', 'T9', 'T9-point'\]"  # the name given and the presets known
    with pytest.raises(InputError, match=known):
        solve_traction(line_lo, 0.1, lubricant="SAE-999")
    d = line_lo.to_dict()
    d["lubricant"] = {"preset": "SAE-999"}
    with pytest.raises(InputError, match=r"lubricant\.preset = " + known):
        Scene.from_dict(d)


def test_bad_operating_values_and_options_are_rejected(line_lo):
    with pytest.raises(InputError, match="slip"):
        solve_traction(line_lo, 2.5)
    with pytest.raises(InputError, match="load"):
        film_friction(line_lo, load=-1.0, h=2e-7, us=8.0, slip=0.1)
    with pytest.raises(InputError, match="us"):
        film_friction(line_lo, load=100.0, h=2e-7, us=0.0, slip=0.1)
    with pytest.raises(InputError, match="unknown key"):
        solve_traction(line_lo, 0.1, nxx=3)
    with pytest.raises(InputError, match="nz"):
        ThermalOptions(nz=2)
    with pytest.raises(InputError, match="surface_kernel"):
        ThermalOptions(surface_kernel="magic")
    with pytest.raises(InputError, match="ehl"):
        solve_traction(line_lo, 0.1, input="ehl")


def test_scene_solver_table_sets_options(point):
    opt = ThermalOptions.from_scene(point)
    assert (opt.nx, opt.nz, opt.slices, opt.tol_T) == (80, 20, 10, 1e-5)
    assert ThermalOptions.from_scene(point, nx=40).nx == 40


# -- storage and CLI --------------------------------------------------------------------------
def test_traction_result_round_trips_through_hdf5(tmp_path, point):
    pts = traction_curve(point, [-0.2, 0.0, 0.3], slices=3, nx=40)
    res = traction_result(point, pts)
    path = res.save(tmp_path / "t.h5")
    back = Result.load(path)
    assert back.kind == "traction"
    assert back["friction_force"] == pytest.approx([p.force for p in pts])
    assert back["T"].shape == (3, 3, 40, 21)
    assert back.fields["T"].dims == ("slip", "Y", "X", "Z")
    assert back.scalars["converged"] is True
    assert back.scene.name == point.name


def test_cli_traction_json(tmp_path, capsys):
    code = main(["traction", "appendix_c_line_4240N", "--slip=-0.2,0,0.2,0.6", "--nx", "40", "--json",
                 "--out", str(tmp_path), "--no-plots"])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("slip", "friction_coefficient", "friction_force", "max_temperature_rise", "converged"):
        assert key in out
    assert out["slip"] == [-0.2, 0.0, 0.2, 0.6]
    f = out["friction_force"]
    assert f[0] == pytest.approx(-f[2]) and f[3] > f[2] > 0
    assert out["friction_coefficient"][3] == pytest.approx(f[3] / 4240.0)
    assert out["converged"] is True
    assert Result.load(out["hdf5"]).kind == "traction"
    # the operating slip's friction with its error, as the main job states it; the film is the
    # fit's, and its own error is said not to be counted
    assert out["film_source"].startswith("Hertz pressure and the fitted film") and " nm" in out["film_source"]
    op = out["operating_point"]
    assert op["slip"] == 0.0  # the scene's (pure rolling: the friction there is round-off)
    assert op["friction_coefficient_error"] == pytest.approx(sum(op["error_parts"].values()))
    assert out["friction_coefficient_at_operating_slip_error"] == op["friction_coefficient_error"]
    assert out["friction_error"].startswith("at the operating slip") and "not counted: the film" in out["friction_error"]
    # at a sliding operating slip the grid part is measured on the grid twice as fine
    assert main(["traction", "default", "--slip=0.05", "--nx", "40", "--json", "--out", str(tmp_path / "d"),
                 "--no-plots"]) == 0
    op = json.loads(capsys.readouterr().out)["operating_point"]
    assert op["slip"] == 0.05 and op["error_parts"]["grid"] > 0.0 and op["grid"].startswith("nx 80,")


@pytest.mark.solver
def test_cli_traction_isothermal_plots_and_default_slips(tmp_path, capsys):
    code = main(["traction", "appendix_c_line_4240N", "--isothermal", "--nx", "30", "--nz", "8",
                 "--json", "--out", str(tmp_path)])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert len(out["slip"]) == 21 and out["max_temperature_rise"] == [0.0] * 21
    assert all(p.endswith(".png") for p in out["plots"].values())


def test_cli_traction_bad_input_exits_2(tmp_path, capsys):
    assert main(["traction", "appendix_c_line_4240N", "--slip", "0.1,abc", "--out", str(tmp_path)]) == 2
    assert main(["traction", "no_such_scene", "--out", str(tmp_path)]) == 2
    assert main(["traction", "appendix_c_line_4240N", "--input", "ehl", "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "--slip" in err and "ehl-file" in err


def test_cli_traction_reads_ehl_result_file(tmp_path, capsys, line_lo):
    # an ehl_line result (naming contract) holding Hertz pressure and a uniform film: the EHL
    # path must then give the Hertz-input friction up to the pressure-gradient term of (3.4),
    # which the EHL input keeps and which moves the force by well under 0.2 % here
    from thermal.traction import ehl_result_from

    hz = line_lo.hertz
    x = np.linspace(-2.5 * hz.b, 1.0 * hz.b, 71)
    p = hz.pmax * np.sqrt(np.clip(1 - (x / hz.b) ** 2, 0, None))
    h = np.full_like(x, line_lo.central_film_fit()[1])
    path = ehl_result_from((x, p, h), line_lo).save(tmp_path / "ehl.h5")
    code = main(["traction", "appendix_c_line_4240N", "--input", "ehl", "--ehl-file", str(path), "--slip", "0.3",
                 "--nx", "71", "--json", "--out", str(tmp_path), "--no-plots"])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    ref = solve_traction(line_lo, 0.3, nx=71)
    assert out["input"] == "ehl" and out["h_uniform"] is None
    assert out["friction_force"][0] == pytest.approx(ref.force, rel=2e-3)


def test_the_thermal_line_solver_has_only_its_current_names():
    """The first version was never released: its names (``solve_line``, ``LineSolution``, which
    clashed with the EHL line solver's) are gone, not deprecated."""
    import thermal
    import thermal.line

    assert thermal.solve_thermal_line is thermal.line.solve_thermal_line
    for mod in (thermal, thermal.line):
        for old in ("solve_line", "LineSolution"):
            with pytest.raises(AttributeError):
                getattr(mod, old)
    with pytest.raises(AttributeError):
        thermal.line.no_such_name  # noqa: B018
