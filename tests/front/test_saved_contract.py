"""A saved solution keeps its outcome and error estimate, the same way for every physics:
``Result.load`` of ``Solution.to_result().save(path)`` gives the status, message, success,
``Hc_error``, ``Hm_error`` and the error budget under the part names of
``Solution.error.parts``; an older file's ``algebraic`` part is read as ``iteration``."""

from __future__ import annotations

import math

import numpy as np
import pytest

import ehl_multigrid as ehl
from ehl_multigrid import Result, load_scene

from .test_front_contract import bump_line_scene, same, starved_line_scene

#: one cheap solve per physics; ``estimated``: its error estimate is finite (checked, so that the
#: round trip compares numbers, not NaN with NaN)
SOLVES = {
    "steady_line": (lambda: ehl.solve(ehl.MoesProblem("line", 20, 10), accuracy=0.01,
                                      options={"points": 257}), True),
    "starved_line": (lambda: ehl.solve(starved_line_scene(), accuracy=0.05), True),
    "thermal_line": (lambda: ehl.solve("appendix_c_line_4240N", physics="thermal", accuracy=0.05,
                                       options={"points": 129, "nz": 8, "slip": 0.5}), True),
    # at 0.03 the films are anchored on the core's isothermal films: the part "isothermal"
    "thermal_point": (lambda: ehl.solve(load_scene("appendix_d_point").with_operating(load=5.0),
                                        physics="thermal", accuracy=0.03,
                                        options={"points": 129, "nz": 8, "slip": 0.5}), True),
    # time part measured (a run at twice the step), grid part not (no target): NaN, saved as NaN
    "transient_line": (lambda: ehl.solve(bump_line_scene(), physics="transient", accuracy=None,
                                         options={"points": 129, "steps": 4, "dt": 0.001,
                                                  "time_error": True}), False),
}


@pytest.mark.parametrize("case", list(SOLVES))
def test_saved_result_keeps_status_errors_and_part_names(case, tmp_path):
    make, estimated = SOLVES[case]
    sol = make()
    assert sol.fields, sol.message
    if estimated:
        assert math.isfinite(sol.error.Hc) and math.isfinite(sol.error.Hm), sol.error
    back = Result.load(sol.to_result().save(tmp_path / f"{case}.h5"))
    s = back.scalars
    assert s["status"] == sol.status.label and s["success"] is sol.success and s["message"] == sol.message
    assert same(s["Hc_error"], sol.error.Hc) and same(s["Hm_error"], sol.error.Hm)
    budget = back.meta["error_budget"]
    assert set(budget) == set(sol.error.parts) and set(budget) >= {"grid"}
    for name, part in sol.error.parts.items():
        assert same(budget[name]["Hc"], part.Hc) and same(budget[name]["Hm"], part.Hm), name
    assert back.meta["accuracy"] == sol.error.target and back.meta["physics"] == sol.physics
    assert back.meta["error_notes"] == list(sol.error.notes)
    if sol.physics == "thermal":
        assert math.isfinite(sol.details.friction_coefficient_error)
        assert same(s["friction_coefficient_error"], sol.details.friction_coefficient_error)
        assert same(s["T_max_error_K"], sol.details.T_max_error_K) and back.scalar_units["T_max_error_K"] == "K"
    if case == "thermal_point":
        assert "isothermal" in budget
    if case == "transient_line":
        assert math.isfinite(budget["time"]["Hc"]) and back.scalars["steps"] == sol.details.steps
        np.testing.assert_array_equal(back["Hc_series"], sol.details.Hc_series)
        np.testing.assert_array_equal(back["H"], sol.fields["H"])


def test_an_older_file_with_an_algebraic_part_loads_it_as_iteration(tmp_path):
    old = Result("ehl_line")
    old.add_coord("X", np.linspace(-4.0, 1.5, 5))
    old.set_scalar("status", "converged")
    old.meta["error_budget"] = {"grid": {"Hc": 1e-3, "Hm": 2e-3}, "domain": {"Hc": 0.0, "Hm": 1e-4},
                                "algebraic": {"Hc": 3e-5, "Hm": 4e-5}}
    back = Result.load(old.save(tmp_path / "old.h5"))
    assert back.meta["error_budget"] == {"grid": {"Hc": 1e-3, "Hm": 2e-3}, "domain": {"Hc": 0.0, "Hm": 1e-4},
                                         "iteration": {"Hc": 3e-5, "Hm": 4e-5}}


def test_a_thermal_result_saved_at_another_slip_than_its_scenes_records_that_slip(tmp_path):
    # solved at options["slip"] 0.5, the file's scene said the scene's slip 0: solved again from
    # it, the answer differed
    sol = ehl.solve("appendix_c_line_4240N", physics="thermal", accuracy=0.05, options={"slip": 0.5})
    path = tmp_path / "th.h5"
    sol.to_result().save(path)
    loaded = Result.load(path)
    assert sol.scene.slip == 0.5 and loaded.scene.slip == 0.5 and loaded.scalars["slip"] == 0.5
