"""The unified point-contact API (solve_point), its domain and grid rules, and the CLI's
--solver / --rigid switches."""

import json
import math

import pytest

import ehl_multigrid.point.solve as point_solve
from ehl_multigrid.app.cli import main
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import load_scene
from ehl_multigrid.point import default_domain, problem_from_moes, solve_point
from ehl_multigrid.point.problem import coarse_intervals, domain_scale, hertz_shape, min_points


def test_solve_point_from_moes_returns_result_with_line_solver_shape():
    sol = solve_point(20, 10, points=65, estimate=False)  # the estimate's probes are not what is checked
    assert sol.converged
    res = sol.to_result()
    assert res.kind == "ehl_point"
    assert sol.Hc == pytest.approx(res.scalars["Hc"])
    assert set(("Hc", "Hm", "load_error", "converged", "solver")) <= set(sol.payload())


@pytest.mark.solver
def test_solve_point_newton_path_agrees_with_fas_on_the_same_grid():
    # no error estimate: its extra solves do not change the films compared. 33 points: the
    # Newton path's start grid only (its continuation from 33 to 65 points is
    # test_point_solver.py::test_newton_pyamg_path_reaches_the_fas_answer). The Newton path
    # holds P = 0 on the boundary: the FAS solve without its far field is the same problem
    a = solve_point(20, 10, points=33, estimate=False, far_field=False)
    b = solve_point(20, 10, points=33, solver="newton", estimate=False)
    assert b.converged, b.report.message
    assert b.Hc == pytest.approx(a.Hc, rel=3e-4)


def test_solve_point_from_scene_gives_physical_film():
    sol = solve_point(scene=load_scene("appendix_d_point"), points=257, estimate=False)
    assert sol.converged
    assert 1e-8 < sol.hc < 1e-6


def test_solve_point_rejects_bad_combinations():
    with pytest.raises(InputError, match="solver"):
        solve_point(20, 10, solver="sor")
    with pytest.raises(InputError, match=r"\bscene\b.*\bM\b.*\bL\b"):
        solve_point(20, 10, scene=load_scene("appendix_d_point"))
    with pytest.raises(InputError, match="rigid"):
        solve_point(20, 10, solver="newton", rigid=True)


def test_default_domain_is_model_domain_at_moderate_load_and_grows_at_low_M():
    assert default_domain(problem_from_moes(20, 10)) == pytest.approx((-4.5, 1.5, 3.0))
    assert domain_scale(problem_from_moes(10, 0)) == 1.0
    xmin, xmax, ymax = default_domain(problem_from_moes(1, 0))
    assert xmin < -20 and ymax > 15 and xmax > 5


def test_low_M_thick_film_converges_with_the_default_domain():
    """M = 2, L = 0: the pressure spreads over several a; the widened domain and the rigid
    H00 gain make the default solve converge (it failed with the fixed [-4.5, 1.5] box)."""
    sol = solve_point(2, 0, points=65, estimate=False)  # the iteration's verdict, not the estimate
    assert sol.converged, sol.report.message
    assert sol.Hc > 0


def test_elliptic_grid_stretches_cells_with_the_ellipse():
    # hy/hx follows b/a (within the power-of-2 rounding) on both sides of the circle (no error
    # estimate: its probes are not what is checked)
    for theta in (4.0, 0.25):
        sol = solve_point(20, 10, theta=theta, points=129, estimate=False)
        hx = sol.X[1] - sol.X[0]
        hy = sol.Y[1] - sol.Y[0]
        boa = hertz_shape(theta)[2]
        assert 0.7 < (hy / hx) / boa < 1.42
        assert sol.converged


def test_coarse_grid_and_minimum_grid_rules():
    assert coarse_intervals(20, 6.0, 129) == 16
    assert coarse_intervals(500, 6.0, 129) == 32
    assert coarse_intervals(2000, 6.0, 513) == 64
    assert coarse_intervals(20, 24.0, 513) == 64  # widened domain keeps the coarse mesh size
    assert min_points(100) == 129 and min_points(500) == 257 and min_points(5000) == 513


def test_wide_contacts_keep_at_most_64_coarse_intervals():
    # twice the default box at M >= 1000: 128 intervals by the mesh-size rule, 64 when b/a >= 4
    assert coarse_intervals(3000, 12.0, 1025) == 128
    assert coarse_intervals(3000, 12.0, 1025, b_over_a=2.0) == 128
    assert coarse_intervals(3000, 12.0, 1025, b_over_a=9.4) == 64
    assert coarse_intervals(3000, 6.0, 1025, b_over_a=9.4) == 64
    assert coarse_intervals(20, 6.0, 129, b_over_a=9.4) == 16


def test_unconverged_coarse_high_M_solve_names_the_grid_it_needs():
    sol = solve_point(5000, 10, points=65, max_cycles=3)
    assert not sol.converged
    assert "points >= 513" in sol.report.message


@pytest.mark.solver
def test_cli_solver_newton_and_rigid(tmp_path, capsys, monkeypatch):
    # the Newton path on the light (3, 0) contact of the rigid comparison below (fewer Newton steps)
    rc = main(["solve", "--M", "3", "--L", "0", "--contact", "point", "--points", "65", "--accuracy", "none",
               "--solver", "newton", "--json", "--no-plots", "--out", str(tmp_path)])
    assert rc == 0
    d = json.loads(capsys.readouterr().out)
    assert d["solver"] == "newton" and d["converged"]
    # the rigid box's domain probe (a wide rigid solve, nearly all of the command's time; under
    # --accuracy none it only adds to the reported estimate) is skipped: the films and the
    # iteration's verdict are the same (the rigid probes: test_point_rigid.py)
    monkeypatch.setattr(point_solve, "point_domain_change", lambda *a, **k: None)
    rc = main(["solve", "--M", "3", "--L", "0", "--contact", "point", "--points", "65", "--accuracy", "none", "--rigid",
               "--json", "--no-plots", "--out", str(tmp_path)])
    assert rc == 0
    rigid = json.loads(capsys.readouterr().out)
    # undeformed surfaces: the thinnest film is the central one
    assert rigid["converged"]
    assert math.isclose(rigid["Hc"], rigid["Hm"], rel_tol=1e-2)


def test_cli_line_refuses_newton_path(capsys, tmp_path):
    rc = main(["solve", "--M", "20", "--L", "10", "--contact", "line", "--solver", "newton", "--json",
               "--out", str(tmp_path)])
    assert rc == 2


@pytest.mark.solver
def test_highly_piezoviscous_case_converges_with_the_default_switch():
    """(M, L) = (100, 20), alpha_bar = 34 at 257^2: the default GS/JD switch (40) converges;
    the switch of moderate loads (1) does not within the same cycle budget."""
    sol = solve_point(100, 20, points=257, max_cycles=30, estimate=False)
    assert sol.converged, sol.report.message
    assert sol.report.extra["final_switch"] >= 40.0
    low = solve_point(100, 20, points=257, max_cycles=30, switch=1.0, adapt=False, estimate=False)
    assert not low.converged


def test_half_domain_equals_full_domain_for_an_elliptic_contact_with_square_cells():
    # y_ratio 2: twice the intervals along Y (the default stretches the cells with the ellipse);
    # the films compared are the solves' own (no error estimate)
    # solved to 1e-8 (the grid rule's stop leaves the two 3e-5 apart)
    kw = dict(points=65, y_ratio=2, estimate=False, tol=1e-8, tol_load=1e-9, max_cycles=60)
    full = solve_point(20, 10, theta=0.25, half=False, **kw)
    half = solve_point(20, 10, theta=0.25, half=True, **kw)
    assert full.P.shape == (129, 65) and half.P.shape == (65, 65)
    assert full.converged and half.converged
    assert half.Hc == pytest.approx(full.Hc, rel=1e-7)
    assert half.Hm == pytest.approx(full.Hm, rel=1e-7)


def test_a_finished_solve_frees_its_grids_without_the_cycle_collector(monkeypatch):
    # accuracy mode runs several solves and probes in a row: each one's grids must go when the
    # solve returns, not when Python's cycle collector happens to run
    import gc
    import weakref

    import ehl_multigrid.point.solve as ps

    made = []
    build = ps.point_solver

    def tracked(*a, **k):
        s = build(*a, **k)
        made.append(weakref.ref(s.hierarchy))
        return s

    monkeypatch.setattr(ps, "point_solver", tracked)
    gc.disable()
    try:
        ps.solve_point(20.0, 10.0, points=65, estimate=False)
        assert made and all(r() is None for r in made)
    finally:
        gc.enable()


def test_the_fas_solver_takes_the_symmetric_half_domain_unless_told_otherwise():
    half = solve_point(20, 10, points=65, estimate=False)
    full = solve_point(20, 10, points=65, estimate=False, half=False)
    assert half.half and half.P.shape == (33, 65)
    assert not full.half and full.P.shape == (65, 65)
    assert half.Hc == pytest.approx(full.Hc, rel=1e-5) and half.Hm == pytest.approx(full.Hm, rel=1e-5)
    # explicit options are taken as given (their default is the full domain)
    from ehl_multigrid.multigrid.options import PointOptions

    assert not solve_point(20, 10, options=PointOptions(points=65), estimate=False).half


def test_a_rigid_solve_on_a_coarse_mesh_that_cannot_hold_its_film_ends_as_a_named_failure():
    """Rigid surfaces (elastic = False) at (20, 0), theta 4, forced onto 16 coarse intervals
    (about 2 rigid inlet lengths each): the coarse film closes (no flow, no film response on
    the diagonal, where the residual scaling once divided by zero); the solve returns a failure
    that names the rigid surfaces' scale, not a finer grid."""
    res = solve_point(20, 0, theta=4.0, rigid=True, points=129, n_coarse=16, estimate=False)
    assert not res.success and res.status_name == "diverged"
    assert "rigid film's inlet length" in res.message and "too coarse" not in res.message
