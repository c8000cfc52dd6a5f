"""Starved, mass-conserving (Elrod-Adams) line contact: flooded limit, mass balance, the
starved limit rho_c Hc = rho_0 Hoil, monotone film, the coupled inlet relaxation, bad input."""

import math
import re

import numpy as np
import pytest

from ehl_multigrid.line import LineProblem, solve_line
from ehl_multigrid.model.errors import ConvergenceError, InputError
from ehl_multigrid.starved import check_hoil, check_profile, hoil_venner, solve_starved_line
from ehl_multigrid.starved.line import solve_starved_problem, starved_options

PB = LineProblem.from_moes(20.0, 10.0)


@pytest.fixture(scope="module")
def half_starved():
    # Hoil about half the flooded flux (Venner units): meniscus near X = -1.1
    return solve_starved_line(PB, 0.05, points=513)


@pytest.mark.solver
def test_thick_supply_reproduces_the_flooded_core_solution_within_its_error():
    core = solve_line(20.0, 10.0, points=513)
    thick = solve_starved_line(PB, 10.0, points=513)
    assert thick.success and thick.scalars["inlet_flooded"]
    assert abs(thick.Hc / core.Hc - 1.0) <= core.Hc_error
    assert abs(thick.Hm / core.Hm - 1.0) <= core.Hm_error
    # the Elrod-Adams outlet against the Reynolds outlet on the same grid: in a steady line
    # contact the rupture conserves mass either way, so the films change by round-off only
    assert abs(thick.scalars["outlet_change_Hc"]) < 1e-5
    assert abs(thick.scalars["outlet_change_Hm"]) < 1e-4


def test_thick_supply_reproduces_the_flooded_core_solution_with_logarithmic_faces_too():
    # the Elrod-Adams kernels take the core's face coefficient (face = "auto": logarithmic here)
    core = solve_line(20.0, 10.0, points=513, estimate=False, face="auto")
    thick = solve_starved_line(PB, 10.0, points=513, face="auto", estimate=False)
    arith = solve_line(20.0, 10.0, points=513, estimate=False)
    assert core.extra["face"] == "logarithmic" and thick.success
    assert abs(arith.Hm / core.Hm - 1.0) > 1e-3  # the faces differ by far more than below
    assert abs(thick.Hc / core.Hc - 1.0) < 1e-5 and abs(thick.Hm / core.Hm - 1.0) < 1e-4
    assert thick.scalars["mass_balance_error"] < 1e-6
    # its error estimate is validated with the arithmetic faces only
    with pytest.raises(InputError, match="face"):
        solve_starved_line(PB, 10.0, points=513, face="auto")


@pytest.mark.solver
@pytest.mark.xdist_group("starved_line_half_starved")
def test_mass_is_conserved_to_1e6_relative(half_starved):
    s = half_starved.scalars
    assert half_starved.success
    assert s["mass_balance_error"] < 1e-6
    # what leaves on the track behind the contact is what the supply brought
    assert s["outlet_layer_venner"] == pytest.approx(0.05, rel=1e-6)
    # behind the rupture the film content carries that layer
    theta = half_starved.extra["theta"]
    assert np.all((theta > 0.0) & (theta <= 1.0))
    assert theta[-1] < 1.0


@pytest.mark.solver
@pytest.mark.xdist_group("starved_line_half_starved")
def test_starved_central_film_carries_the_supply_in_pure_rolling(half_starved):
    # rho_c Hc = rho_0 Hoil when the pressure flow at the centre vanishes
    assert half_starved.scalars["rho_c_Hc_over_hoil"] == pytest.approx(1.0, abs=1e-3)
    deep = solve_starved_line(PB, 0.01, points=257, estimate=False)
    assert deep.scalars["Hc_ratio"] < 0.15
    assert deep.scalars["rho_c_Hc_over_hoil"] == pytest.approx(1.0, abs=1e-3)
    assert deep.scalars["meniscus_x"] > half_starved.scalars["meniscus_x"]


@pytest.mark.solver
def test_central_film_decreases_monotonically_with_the_supply():
    # 129 points (flooded Hc 0.068: the supplies are below it; 257 points: 4 times the cost)
    films, menisci = [], []
    for hoil in (0.06, 0.03, 0.015):
        r = solve_starved_line(PB, hoil, points=129, estimate=False)
        films.append(r.scalars["Hc_venner"])
        menisci.append(r.scalars["meniscus_x"])
    assert np.all(np.diff(films) < 0)
    assert np.all(np.diff(menisci) > 0)  # the meniscus nears the contact
    assert films[0] < solve_starved_line(PB, 10.0, points=129, estimate=False).scalars["Hc_venner"]


@pytest.mark.solver
def test_coupled_inlet_relaxation_agrees_with_the_meniscus_search():
    # the same Elrod-Adams problem with the meniscus found inside the multilevel iteration
    coupled = solve_starved_problem(PB, 0.05, starved_options(points=257, raise_on_failure=False))
    outer = solve_starved_line(PB, 0.05, points=257, estimate=False)
    assert coupled.success
    assert coupled.scalars["Hc_venner"] == pytest.approx(outer.scalars["Hc_venner"], rel=2e-3)
    assert coupled.scalars["mass_balance_error"] < 1e-5


@pytest.mark.solver
def test_supply_below_the_reachable_flux_is_a_failed_result_naming_it():
    r = solve_starved_line(PB, 0.0002, points=257, estimate=False)
    assert not r.success and r.status_name == "start_failed"
    assert re.search(r"Hoil = 0\.0002\b.*0\.000\d+ at X_m = -1\.00", r.message), r.message


@pytest.mark.solver
def test_a_meniscus_next_to_the_hertzian_edge_carries_the_supply():
    # half a percent of the flooded flux: the meniscus lies 0.0023 a from the Hertzian edge, the
    # film is nearly parallel and carries the supply, rho_c Hc = Hoil (a box this short
    # diverged in its first cycle before its start grid was relaxed: docs/starvation.md)
    r = solve_starved_line(PB, 0.001, points=257, estimate=False)
    assert r.success and -1.01 < r.scalars["meniscus_x"] < -1.0
    assert r.scalars["rho_c_Hc_over_hoil"] == pytest.approx(1.0, abs=1e-6)
    assert r.scalars["Hm_venner"] == pytest.approx(r.scalars["Hc_venner"], rel=0.02)


@pytest.mark.parametrize("bad", [-0.01, 0.0, math.nan, "thick"])
def test_bad_supply_is_rejected_naming_field_value_and_range(bad):
    shown = repr(bad) if isinstance(bad, str) else f"{bad:g}"
    with pytest.raises(InputError, match=rf"hoil = {re.escape(shown)} .*\(0, inf\]"):
        solve_starved_line(PB, bad, points=257)


def test_bad_supply_in_metres_names_the_scene_field():
    with pytest.raises(InputError, match=r"supply\.hoil = -1e-06 m .*\(0, inf\] m"):
        hoil_venner(-1e-6, 1e-4, 0.01)
    assert hoil_venner(1e-7, 1e-4, 0.01) == pytest.approx(0.1)
    assert math.isinf(hoil_venner(math.inf, 1e-4, 0.01))
    assert check_hoil(math.inf) == math.inf


def test_supply_profile_longer_than_the_grid_is_rejected():
    with pytest.raises(InputError, match=r"hoil_profile\b.*\b66\b.*\b65\b"):
        check_profile(np.full(66, 0.05), 65)
    with pytest.raises(InputError, match=r"hoil_profile\[3\] = nan"):
        check_profile([0.05, 0.05, 0.05, math.nan], 4)
    assert check_profile([0.05, math.inf], 2).shape == (2,)


@pytest.mark.solver
def test_scene_supply_in_metres_gives_the_film_that_carries_it():
    from ehl_multigrid.model.scene import load_scene
    from ehl_multigrid.starved import solve_starved_scene

    scene = load_scene("ehl_multigrid/scenes/page63_line_500N.toml")  # flooded hc about 25 nm
    r = solve_starved_scene(scene, hoil=1.5e-8, points=257, estimate=False)
    assert r.success and not r.scalars["inlet_flooded"]
    assert r.scalars["hc"] * r.scalars["rho_c"] == pytest.approx(1.5e-8, rel=1e-4)
    assert r.scalars["outlet_layer_m"] == pytest.approx(1.5e-8, rel=1e-6)


def test_an_unconverged_solve_is_a_failed_result_with_the_reason_and_raises_when_asked_to():
    cycles = r"\b0 extra cycles\b.*residual \d\S* \(tol 1e-07\)"
    with pytest.raises(ConvergenceError, match=cycles):
        solve_starved_line(PB, 0.05, points=257, max_cycles=0, raise_on_failure=True)
    r = solve_starved_line(PB, 0.05, points=257, max_cycles=0)
    assert not r.success and r.status_name == "start_failed"  # the flooded start did not converge
    assert re.search(cycles, r.message), r.message


@pytest.mark.solver
@pytest.mark.xdist_group("starved_line_half_starved")
def test_the_outer_iteration_is_recorded(half_starved):
    hist = half_starved.extra["meniscus_history"]
    assert len(hist) == half_starved.extra["meniscus_solves"] - 1  # plus the flooded-inlet solve
    assert {h["points"] for h in hist} == {257, 513}
    last = [h for h in hist if h["points"] == 513 and h["meniscus_x"] == half_starved.scalars["meniscus_x"]]
    assert last and last[0]["flux"] == pytest.approx(0.05, rel=1e-8)
    assert half_starved.residual_history.size >= 1 and half_starved.load_error_history.size >= 1


@pytest.mark.solver
@pytest.mark.xdist_group("starved_line_half_starved")
def test_an_accuracy_the_estimate_does_not_meet_is_reported(half_starved):
    # 513 points: estimated Hm error about 4e-4 (the fixed-supply Richardson estimate)
    assert 1e-4 < half_starved.Hm_error < 2e-3
    r = solve_starved_line(PB, 0.05, accuracy=1e-4, points=513)
    assert not r.success and r.status_name == "inaccurate"
    assert re.search(r"Hm 0\.000\d+\b.*accuracy 0\.0001\b", r.message), r.message


def _edge_box(points: int = 513):
    """The flooded-inlet box of (100, 10) with its inlet 0.004 a ahead of the Hertzian edge."""
    import dataclasses

    pb = dataclasses.replace(LineProblem.from_moes(100.0, 10.0), xmin=-1.004)
    return solve_starved_problem(pb, math.inf, starved_options(points=points, raise_on_failure=False))


@pytest.fixture(scope="module")
def edge_box():
    """The edge box with its start grid not relaxed before the cycles (``SETTLE_SWEEPS = 0``):
    its first cycle is rejected and the dense Newton last resort finishes it."""
    from ehl_multigrid.starved import line as starved_line

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(starved_line, "SETTLE_SWEEPS", 0)
        return _edge_box()


@pytest.mark.solver
def test_box_solve_next_to_the_hertzian_edge_converges_by_its_cycles():
    """The start relaxed until the film content behind the rupture settles (1-6 sweeps): the
    box 0.004 a ahead of the edge converges by multigrid cycles alone, with the film and flux
    the dense Newton gives (the test below)."""
    r = _edge_box()
    assert r.success and not any("dense Newton" in a for a in r.actions)
    assert r.scalars["mass_balance_error"] < 1e-6
    assert r.residual_history[-1] < 1e-7


@pytest.mark.solver
@pytest.mark.xdist_group("starved_line_edge_box")
def test_box_solve_next_to_the_hertzian_edge_is_finished_by_dense_newton(edge_box):
    """A flooded-inlet box with its inlet 0.004 a ahead of the Hertzian edge, its start not
    relaxed: the coarse grids cannot carry the short inlet and the first finest-grid cycle is
    rejected; the dense Newton last resort finishes a failed first cycle of a solve started on
    the finest grid (before it: ``diverged``). It agrees with the cycles' solution."""
    r = edge_box
    assert r.success
    assert any("dense Newton" in a for a in r.actions)
    assert r.scalars["mass_balance_error"] < 1e-6
    cycles = _edge_box()
    assert r.scalars["flux_in"] == pytest.approx(cycles.scalars["flux_in"], rel=1e-6)
    assert r.scalars["Hc_venner"] == pytest.approx(cycles.scalars["Hc_venner"], rel=1e-6)


@pytest.mark.solver
def test_severe_starvation_at_three_percent_of_the_flooded_flux_carries_the_supply():
    """The meniscus 0.003-0.004 a ahead of the Hertzian edge (searched closer than the scan's
    first position, ``meniscus.EDGE_SCAN``): the central film carries the supply."""
    from ehl_multigrid.starved.line import flooded_flux_estimate

    hoil = 0.03 * flooded_flux_estimate(solve_line(20.0, 10.0))
    # 257 points: the grid of the root search, which the 513-point solve polishes (a third of its cost)
    r = solve_starved_line(PB, hoil, points=257, estimate=False)
    assert r.success
    assert -1.006 < r.scalars["meniscus_x"] < -1.0
    assert r.scalars["rho_c_Hc_over_hoil"] == pytest.approx(1.0, abs=1e-6)
    assert r.scalars["mass_balance_error"] < 1e-6


@pytest.mark.solver
def test_a_failed_box_solve_in_the_meniscus_search_is_a_result_unless_raising(monkeypatch):
    from ehl_multigrid.starved import meniscus

    real = meniscus._FluxMap.flux
    # the boxes strictly inside the bracket [-1.02, -1.01] of Hoil = 0.01 fail (NaN flux)
    monkeypatch.setattr(meniscus._FluxMap, "flux",
                        lambda fm, xm: math.nan if -1.02 < xm < -1.01 else real(fm, xm))
    r = solve_starved_line(PB, 0.01, points=257, estimate=False)
    assert not r.success and r.status_name == "diverged"
    assert re.search(r"meniscus search\b.*X_m = -1\.01", r.message), r.message
    with pytest.raises(ConvergenceError, match=r"X_m = -1\.01"):
        solve_starved_line(PB, 0.01, points=257, estimate=False, raise_on_failure=True)


@pytest.mark.solver
@pytest.mark.xdist_group("starved_line_edge_box")
def test_dense_newton_leaves_cavitated_points_at_exactly_zero_pressure(edge_box):
    """On 1025 points the Newton-finished box 0.004 a ahead of the edge kept round-off
    pressures (~1e-17) behind the rupture; with eps/h^2 ~ 1e7 there they left a relative
    residual of 1.6e-7, above the starved tolerance 1e-7, and the box counted as diverged.
    ``newton.exact_cavitation`` zeroes them and marches the film content: residual 6e-10.
    The same box on 513 points (the solve of the test above) shows it for a fifth of the cost:
    without ``exact_cavitation`` its round-off pressures (5e-17) stay and its residual is
    3.6e-8 (measured), with it 3.8e-10."""
    r = edge_box
    assert r.success
    assert any("dense Newton" in a for a in r.actions)
    assert r.residual_history[-1] < 1e-8
    theta = r.extra["theta"]
    assert np.all(r.P[1:-1][theta[1:-1] < 1.0] == 0.0)
    assert r.scalars["mass_balance_error"] < 1e-9


@pytest.mark.solver
def test_box_solve_whose_flooded_start_fails_is_continued_from_the_nearest_meniscus():
    """(50, 5) on 513 points: the flooded box solve with its inlet at X_m = -1.00483 diverges in
    its FMG from the Hertzian guess; started on the finest grid from the converged box at
    X_m = -1.006 it converges (continuation in the meniscus position)."""
    from ehl_multigrid.starved.meniscus import _FluxMap

    pb = LineProblem.from_moes(50.0, 5.0)
    alone = _FluxMap(pb, starved_options(), 513).solve(-1.00483)
    assert alone.status_name == "start_failed"
    fm = _FluxMap(pb, starved_options(), 513)
    assert fm.solve(-1.006).success
    r = fm.solve(-1.00483)
    assert r.success
    assert fm.flux(-1.00483) < fm.flux(-1.006)  # the meniscus nearer the edge carries less
