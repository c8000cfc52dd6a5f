"""Line-contact multigrid solver: balance, cavitation, limits, regression, errors."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from ehl_multigrid.line import LineProblem, solve_line, solve_line_problem
from ehl_multigrid.model.errors import ConvergenceError, InputError
from ehl_multigrid.model.results import Result

REF = json.loads(Path(__file__).with_name("reference.json").read_text())


@pytest.fixture(scope="module")
def sol_20_10():
    return solve_line(20.0, 10.0, points=1025)


def test_load_balance_holds_at_convergence(sol_20_10):
    # force balance: integral of P dX = pi/2 (Venner's load equation)
    s = sol_20_10
    h = s.X[1] - s.X[0]
    assert s.converged
    assert h * np.sum(s.P) == pytest.approx(math.pi / 2, rel=1e-6)
    assert abs(s.load_error) < 1e-6


def test_no_negative_pressure_and_cavitated_outlet(sol_20_10):
    s = sol_20_10
    assert np.all(s.P >= 0.0)
    assert np.all(s.P[s.X > 1.2] == 0.0)  # cavitation zone downstream of the contact
    assert s.P[0] == 0.0 and s.P[-1] == 0.0


def test_report_carries_histories(sol_20_10):
    rep = sol_20_10.report
    assert rep.converged and rep.residual_history[-1] < rep.tolerances["residual"]
    assert rep.extra["level_residuals"].shape[0] == len(rep.extra["cycle_residual"])
    assert rep.extra["fmg_points"][-1] == 1025
    assert rep.work_units > 0 and rep.wall_s > 0


def test_regression_against_stored_fine_grid_hc(sol_20_10):
    case = REF["cases"]["M20_L10"]
    grids = case["grids"]
    ref = grids[str(case["reference_points"])]["Hc"]
    # tolerance: 1.5 x the 1025-to-finest difference measured when reference.json was made
    tol = 1.5 * abs(grids["1025"]["Hc"] - ref)
    assert abs(sol_20_10.Hc - ref) <= tol
    # the stored coarse value itself is reproduced (same code, same grid)
    assert sol_20_10.Hc == pytest.approx(grids["1025"]["Hc"], rel=1e-4)


def test_moving_the_inlet_changes_hc_less_than_the_discretisation_error(sol_20_10):
    # the default inlet (default_xmin) is far enough upstream when moving it
    # further changes Hc by less than the discretisation error. Same mesh size h: the domain
    # is doubled upstream with twice the intervals.
    case = REF["cases"]["M20_L10"]
    grids = case["grids"]
    disc = abs(grids["1025"]["Hc"] - grids[str(case["reference_points"])]["Hc"])
    pb = sol_20_10.problem
    longer = solve_line(20.0, 10.0, points=2049, xmin=pb.xmin - (pb.xmax - pb.xmin))
    assert longer.converged
    assert longer.X[1] - longer.X[0] == pytest.approx(sol_20_10.X[1] - sol_20_10.X[0])
    assert abs(longer.Hc - sol_20_10.Hc) < disc


@pytest.mark.solver
def test_rigid_isoviscous_limit_is_martins_2_45_over_M():
    # L = 0, no deformation: Hc M = 2.45 exactly (Martin, Reynolds exit condition)
    s = solve_line(10.0, 0.0, points=1025, elastic=False, xmin=-6.0, xmax=1.0, fmg_start_points=257,
                   estimate=False)
    assert s.converged
    assert s.Hc * 10.0 == pytest.approx(2.45, rel=0.01)
    assert s.Hm * 10.0 == pytest.approx(2.45, rel=0.02)


def test_result_follows_the_naming_contract(sol_20_10, tmp_path):
    res = sol_20_10.to_result()
    assert res.kind == "ehl_line"
    for name in ("Hc", "Hm", "Hc_venner", "Hm_venner", "hc", "hm", "p_spike", "load_error",
                 "levels", "points", "cycles", "wall_s", "converged"):
        assert name in res.scalars
    back = Result.load(res.save(tmp_path / "r.h5"))
    assert np.array_equal(back["P"], sol_20_10.P)
    assert back.scalars["Hc"] == pytest.approx(sol_20_10.Hc)
    assert "residual" in back.history


def test_scene_mode_gives_films_in_metres():
    from ehl_multigrid.model.scene import load_scene

    sc = load_scene("page63_line_2000N")
    s = solve_line(scene=sc, points=1025)
    res = s.to_result(sc)
    assert s.hc == pytest.approx(s.Hc * sc.film_scale(), rel=1e-9)
    assert res["h"][np.argmin(np.abs(s.X))] == pytest.approx(s.hc, rel=0.05)
    assert res["x"][-1] == pytest.approx(1.5 * sc.hertz.b)


@pytest.mark.parametrize("kw, field", [
    (dict(M=-1.0, L=10.0), "M"), (dict(M=20.0, L=-2.0), "L"), (dict(M=1e6, L=10.0), "M"),
    (dict(M=20.0, L=10.0, points=1000), "points"), (dict(M=20.0, L=10.0, points=257, levels=9), "levels"),
    (dict(M=20.0, L=10.0, cycle="X"), "cycle"), (dict(M=20.0, L=10.0, deformation="magic"), "deformation"),
])
def test_bad_input_names_the_field(kw, field):
    with pytest.raises(InputError, match=field):
        solve_line(**kw)


def test_robustness_steps_fire_on_the_rigid_isoviscous_contact_and_it_still_converges():
    # rigid surfaces on the default box: the coarse Newton and the cycles struggle (measured:
    # 10 rejected cycles, a V-cycle stall, then dense Newton finishes; 170 WU)
    sol = solve_line(10.0, 0.0, points=513, elastic=False, raise_on_failure=False, estimate=False)
    acts = sol.actions
    assert any("rejected" in a and "omega = 0.25" in a for a in acts)  # halved under-relaxation
    assert any("stalled" in a and "V -> W" in a for a in acts)
    assert any("dense Newton" in a for a in acts)
    assert sol.success and sol.status_name == "converged"
    assert sol.residual_history[-1] < 1e-5 and abs(sol.load_error) < 1e-6


@pytest.mark.solver
def test_a_dense_newton_finish_counts_as_converged_under_the_film_stopping_rule():
    # the film jumps from the stalled cycles to the discrete solution; that jump is no
    # iteration error, so the film-change rule must not turn the finish into "stalled", and
    # the estimate's algebraic part is the load error alone. (Was (M, L) = (100, 0) at 513
    # points, whose cycles no longer stall since the Gauss-Seidel-next-to-cavitation rule and
    # the stall step that leaves the film-less coarse grids out (validation/line_fine); the
    # rigid isoviscous contact still stalls and is finished by dense Newton.)
    sol = solve_line(10.0, 0.0, points=513, elastic=False, raise_on_failure=False, film_tol=5e-4)
    assert any("dense Newton" in a for a in sol.actions)
    assert sol.status_name == "converged", sol.message
    alg = sol.error.budget["algebraic"]
    assert alg["Hc"] == pytest.approx(0.5 * abs(sol.load_error_history[-1]))


def test_stall_without_a_last_resort_raises_with_a_hint_when_asked_to():
    pb = LineProblem.from_moes(100.0, 10.0)
    # max_cycles 0: FMG only; tol 1e-14 cannot be met, so the solve fails and says what to try
    with pytest.raises(ConvergenceError) as exc:
        solve_line_problem(pb, points=257, cycles=1, max_cycles=0, tol=1e-14, tol_load=1e-14,
                           raise_on_failure=True)
    assert exc.value.hint and exc.value.hint in str(exc.value)


def test_unconverged_result_says_so_by_default():
    sol = solve_line(100.0, 10.0, points=257, cycles=1, max_cycles=0, tol=1e-14)
    assert sol.converged is False and sol.scalars["converged"] is False
    assert sol.to_result().scalars["converged"] is False


def test_the_line_stall_steps_keep_the_h_scaled_switch_on_the_finest_grid_then_widen_it():
    from ehl_multigrid.line.solver import line_solver
    from ehl_multigrid.multigrid.options import LineOptions

    solver = line_solver(LineProblem.from_moes(100.0, 10.0), LineOptions(points=1025))
    s, hz = solver.settings, solver.hierarchy
    s.switch_h = 0.5
    assert "finest grid only" in hz.raise_switch(s) and hz.classic_coarse_switch
    assert "switch raised" in hz.raise_switch(s) and s.switch_h == 1.0
    assert hz.raise_switch(s) == ""
