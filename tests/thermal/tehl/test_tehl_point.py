"""Thermal EHL point contact (appendix D ball on flat, T9, at 5 N so that 65 points resolve it):
isothermal limit, slip-sign symmetry, energy balance, errors."""

from __future__ import annotations

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import load_scene
from thermal.tehl import TEHLOptions
from thermal.tehl.point import solve_tehl_point


@pytest.fixture(scope="module")
def scene():
    return load_scene("appendix_d_point").with_operating(load=5.0)


@pytest.fixture(scope="module")
def pair(scene):
    return (solve_tehl_point(scene, 0.5, points=65, nz=10), solve_tehl_point(scene, -0.5, points=65, nz=10))


@pytest.mark.solver
def test_isothermal_newtonian_limit_equals_the_core_point_solver(scene):
    r = solve_tehl_point(scene, 0.0, TEHLOptions(points=65, nz=10, thermal=False, shear_thinning=False))
    assert np.all(r.a == 1.0) and np.all(r.c == 1.0)
    assert r.Hc == pytest.approx(r.Hc_isothermal, rel=1e-4)
    assert r.Hm == pytest.approx(r.Hm_isothermal, rel=1e-4)


@pytest.mark.solver
@pytest.mark.xdist_group("tehl_point_5n")
def test_point_slip_sign_mirrors_the_solution(pair):
    pos, neg = pair
    assert neg.Hc == pytest.approx(pos.Hc, rel=1e-6)
    assert neg.friction == pytest.approx(-pos.friction, rel=1e-6)
    np.testing.assert_allclose(neg.T_surface1, pos.T_surface2, atol=1e-5)
    assert neg.heat_partition[0] == pytest.approx(pos.heat_partition[1], rel=1e-6)


@pytest.mark.solver
@pytest.mark.xdist_group("tehl_point_5n")
def test_point_energy_balance_and_heating(pair):
    pos, _ = pair
    assert pos.heat_balance_error < 0.01
    assert pos.T_max > pos.scene.T_oil + 5.0
    assert pos.friction > 0 and pos.report.converged
    assert pos.T_mid.shape == pos.P.shape


def test_point_solver_refuses_a_line_contact():
    with pytest.raises(InputError, match="line contact"):
        solve_tehl_point(load_scene("appendix_c_line_4240N"), 0.5)


@pytest.mark.solver
@pytest.mark.xdist_group("tehl_point_5n")
def test_rows_started_from_the_previous_outer_iteration_give_the_same_solution(scene, pair):
    # pair[0] starts every row's thermal march from its previous outer iteration (the default)
    cold = solve_tehl_point(scene, 0.5, TEHLOptions(points=65, nz=10, warm_thermal=False))
    warm = pair[0]
    assert warm.options.warm_thermal and len(warm.outer) == len(cold.outer)
    for key in ("Hc", "Hm", "friction", "T_max"):
        assert getattr(warm, key) == pytest.approx(getattr(cold, key), rel=1e-6), key
    np.testing.assert_allclose(warm.T_mid, cold.T_mid, atol=1e-3)


def test_a_thermal_march_started_from_its_own_solution_settles_in_one_sweep():
    from thermal.line import Surroundings, solve_thermal_line
    from thermal.tehl import solve_tehl_line

    sc = load_scene("appendix_c_line_4240N")
    r = solve_tehl_line(sc, 0.5, points=129, nz=10)  # an EHL inlet: reverse flow, lagged sweeps
    env = Surroundings(sc.lubricant, sc.body1, sc.body2, r.u1, r.u2, sc.T_oil, sc.T_surface1, sc.T_surface2)
    prof, opts = r.thermal.profile, r.options.thermal_options()
    cold = solve_thermal_line(prof, env, opts, kernel_length=sc.length)
    again = solve_thermal_line(prof, env, opts, kernel_length=sc.length, start=cold)
    assert cold.report.iterations >= 2 and again.report.iterations == 1 and again.report.converged
    np.testing.assert_allclose(again.T, cold.T, rtol=0, atol=1e-3)
    assert again.force_per_length == pytest.approx(cold.force_per_length, rel=1e-5)
    with pytest.raises(InputError, match="129 stations x 10 intervals"):
        solve_thermal_line(prof, env, opts.with_changes(nz=5), kernel_length=sc.length, start=cold)


@pytest.mark.solver
@pytest.mark.xdist_group("tehl_point_5n")
def test_a_solve_started_from_the_coarser_grids_factors_reaches_the_same_fixed_point(scene, pair,
                                                                                   tehl_ball_5n_129):
    coarse = pair[0]  # 65 points, nz = 10, S = 0.5
    cold = tehl_ball_5n_129  # 129 points, nz = 10, S = 0.5, from the isothermal start
    nested = solve_tehl_point(scene, 0.5, TEHLOptions(points=129, nz=10), coarse=coarse)
    assert any("factors" in a and "65 points" in a for a in nested.report.extra["actions"])
    assert len(nested.outer) < len(cold.outer)
    # the same fixed point within the outer tolerances (tol_H = 1e-4, tol_T = 0.01 K)
    for key in ("Hc", "Hm", "friction"):
        assert getattr(nested, key) == pytest.approx(getattr(cold, key), rel=2e-4), key
    assert nested.T_max == pytest.approx(cold.T_max, abs=0.05)


def test_a_coarse_start_of_the_wrong_grid_is_refused(scene):
    from types import SimpleNamespace

    with pytest.raises(InputError, match="coarse has 100 points along X.*needs 65"):
        solve_tehl_point(scene, 0.5, TEHLOptions(points=129, nz=10), coarse=SimpleNamespace(X=np.zeros(100)))


@pytest.mark.solver
@pytest.mark.xdist_group("tehl_point_5n")
def test_a_point_result_carries_the_dimensional_film_the_main_job_computes_on(pair):
    from ehl_multigrid.model.solved_film import SolvedFilm
    from thermal.tehl.results import tehl_point_result

    pos, _ = pair
    pb = pos.problem
    film = SolvedFilm.from_result(tehl_point_result(pos))
    assert film.contact == "point" and film.thermal
    assert film.hc == pytest.approx(pos.Hc * pb.film_scale, rel=1e-12)
    # the full domain, mirrored from the half one; the centre node holds the central film
    assert film.y[0] == pytest.approx(-film.y[-1]) and film.h.shape == (film.x.size, film.y.size)
    i, j = int(np.argmin(np.abs(film.x))), int(np.argmin(np.abs(film.y)))
    assert film.h[i, j] == pytest.approx(pos.H[0, i] * pb.a**2 / pb.Rx, rel=1e-12)
    assert film.h[i, j] == pytest.approx(film.hc, rel=1e-9)
    assert film.p.max() == pytest.approx(pos.P.max() * pb.pmax, rel=1e-12)


@pytest.mark.solver
def test_a_runaway_stress_slope_keeps_the_solves_poiseuille_flux():
    # a 6205 inner race at 18000 rpm and 60 N radial (thermal loading 1.3): on 129 points the
    # centre row's outlet spike drove h dp/dx into NaN temperatures; the line contact's remedy
    from importlib import resources

    import tomllib

    from ehl_multigrid.model.scene import Scene

    raw = tomllib.loads(resources.files("ehl_multigrid.scenes").joinpath("bearing_6205_inner_race.toml").read_text())
    raw["element"].update(shaft_speed="18000 rpm", radial_load="60 N")
    r = solve_tehl_point(Scene.from_dict(raw), 0.0, TEHLOptions(points=129, nz=10))
    assert r.report.converged and np.all(np.isfinite(r.T_mid))
    assert any("Poiseuille flux" in a for a in r.report.extra["actions"])
    # heat in the inlet at this speed: a fifth off the isothermal film (Gupta's factor 0.75)
    assert 0.7 < r.Hc / r.Hc_isothermal < 0.9


def _traction_drive():
    # a ball on a disc at 600 N (Hertz 2.5 GPa), 7.9 m/s, 5 % slip, traction fluid at 60 degC:
    # alpha_bar 67, flow factors of the Eyring film up to 1e24
    from ehl_multigrid.model.scene import Scene

    return Scene.from_dict({
        "name": "traction_drive", "element": {"kind": "ball_on_disc", "ball_radius": "10 mm",
                                              "track_radius": "40 mm", "disc_speed": "970 rpm",
                                              "ball_speed": 3.86, "load": "600 N"},
        "lubricant": {"oil": "traction-fluid"}, "operating": {"T_oil": "60 degC"}})


@pytest.mark.solver
def test_an_eyring_film_at_high_pressure_converges_to_the_fixed_point_of_its_factors():
    # the multilevel solves held a = eta_iso/eta_eff frozen while the pressure moved by
    # exp(alpha dp): at S = 0.2 on 129 points they stopped with jumping films at outer
    # iteration 5 (on 257 points at the scene's 5 %: diverged at iteration 8); with the
    # viscosity response they converge
    r = solve_tehl_point(_traction_drive(), 0.2, TEHLOptions(points=129, nz=10))
    assert r.report.converged
    assert r.a.max() > 1e20  # the Eyring regime the response is for
    assert abs(r.Hc / r.Hc_isothermal - 1.0) < 0.05


@pytest.mark.solver
def test_films_alternating_at_the_relaxation_floor_are_accepted_as_their_uncertainty():
    # an HFRR (3 mm ball on a flat at rest, S = 2, 50 Hz, 2 N): an inner solve stopped at its
    # residual floor below the tolerance with Hm jumping within 10 tol_H; it failed the solve
    from ehl_multigrid.model.scene import Scene

    sc = Scene.from_dict({
        "name": "hfrr", "element": {"kind": "ball_on_flat", "ball_radius": "3 mm", "stroke": "1 mm",
                                    "frequency": "50 Hz", "load": "2 N"},
        "lubricant": {"oil": "PAO-VG68"}, "operating": {"T_oil": "60 degC"}})
    r = solve_tehl_point(sc, None, TEHLOptions(points=129, nz=20))
    assert r.report.converged
    assert any("accepted as their uncertainty" in a for a in r.report.extra["actions"])


def test_the_flow_responds_to_the_viscosity_fully_when_newtonian_and_little_under_eyring_stress():
    from types import SimpleNamespace

    from ehl_multigrid.model.lubricant import lubricant_preset
    from thermal.tehl.coefficients import flow_response, viscosity_response

    lub = lubricant_preset("T9")
    nz = 11
    p = np.array([1e8, 1e9])
    T = np.full((2, nz), 60.0)
    env = SimpleNamespace(lubricant=lub)
    newtonian = SimpleNamespace(profile=SimpleNamespace(p=p), T=T, tau=np.full((2, nz), 1e-3 * lub.tau0))
    np.testing.assert_allclose(viscosity_response(newtonian, env), 0.0, atol=1e-6)
    t = 50.0  # |tau| = 50 tau0 across the film: d ln eta*/d ln eta = tanh(t)/t
    eyring = SimpleNamespace(profile=SimpleNamespace(p=p), T=T, tau=np.full((2, nz), t * lub.tau0))
    np.testing.assert_allclose(viscosity_response(eyring, env), 1.0 - np.tanh(t) / t, rtol=1e-12)
    assert viscosity_response(eyring, env, shear_thinning=False).tolist() == [0.0, 0.0]
    np.testing.assert_allclose(flow_response(np.array([0.5, 1.0, 10.0 ** 1.5, 1e12]), np.full(4, 0.9)), [0.0, 0.0, 0.45, 0.9])
