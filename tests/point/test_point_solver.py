"""FAS/FMG point-contact solver: load balance, cavitation, symmetry, the rigid
limit against an independent direct solve, the Newton/pyamg path, regression and errors."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.model.scene import load_scene
from ehl_multigrid.point import build_result, problem_from_moes, solve_fas
from ehl_multigrid.point.fas import load_integral
from ehl_multigrid.point.problem import problem_from_scene
from ehl_multigrid.point.rigid import solve_rigid_direct

REF = json.loads(Path(__file__).with_name("reference.json").read_text())


@pytest.fixture(scope="module")
def sol65():
    return solve_fas(problem_from_moes(20.0, 10.0), points=65, far_field=False)  # P = 0 as the Newton path below


def test_small_solve_converges_with_load_balance(sol65):
    """∫∫ P dX dY = 2 pi/3 (circular load balance) to the stated load tolerance."""
    assert sol65.report.converged
    load = load_integral(sol65.P, sol65.X[1] - sol65.X[0], sol65.Y[1] - sol65.Y[0], False)
    assert abs(load - 2 * math.pi / 3) / (2 * math.pi / 3) < sol65.options.tol_load
    assert sol65.report.residual_history[-1] < sol65.options.tol


def test_pressure_is_non_negative_and_zero_on_boundary(sol65):
    P = sol65.P
    assert P.min() >= 0.0
    assert np.all(P[0] == 0) and np.all(P[-1] == 0) and np.all(P[:, 0] == 0) and np.all(P[:, -1] == 0)
    # a cavitated outlet exists (P = 0 inside the domain downstream of the contact)
    jc = (P.shape[0] - 1) // 2
    assert np.any(P[jc, 1:-1] == 0.0)


def test_half_domain_gives_the_full_domain_answer():
    """Both solved to a tight algebraic tolerance: the symmetric half domain reproduces the
    full-domain field (the discrete problems are identical; only round-off and the number
    of cycles differ)."""
    pb = problem_from_moes(20.0, 10.0)
    full = solve_fas(pb, points=65, tol=1e-8, tol_load=1e-9, max_cycles=60)
    half = solve_fas(pb, points=65, half=True, tol=1e-8, tol_load=1e-9, max_cycles=60)
    assert full.report.converged and half.report.converged
    r_full = build_result(full)
    r_half = build_result(half)
    assert r_half.scalars["Hc_venner"] == pytest.approx(r_full.scalars["Hc_venner"], rel=1e-8)
    assert r_half.scalars["Hm_venner"] == pytest.approx(r_full.scalars["Hm_venner"], rel=1e-8)
    assert np.abs(r_half["P"] - r_full["P"]).max() < 1e-7


def test_regression_129_against_stored_high_resolution_value():
    """129^2 Hc within 1.5 % of the stored Richardson value from 257/513/1025 (tests/point/
    reference.json, made by make_reference.py); its grid error at 129^2 is about 0.75 %."""
    out = solve_fas(problem_from_moes(20.0, 10.0), points=129)
    res = build_result(out)
    assert out.report.converged
    assert abs(res.scalars["Hc"] / REF["Hc_extrapolated"] - 1) < 0.015
    assert abs(res.scalars["Hm"] / REF["Hm_finest"] - 1) < 0.05


def test_rigid_isoviscous_limit_matches_independent_direct_solve():
    """Deformation off, L = 0, incompressible: the problem is linear in P for fixed H00; a
    sparse-direct active-set solve with Brent on H00 (rigid.py) is the reference."""
    pb = problem_from_moes(3.0, 0.0, 1.0, "barus", "incompressible")
    ref = solve_rigid_direct(pb, 33)
    out = solve_fas(pb, points=33, n_coarse=8, elastic=False, far_field=False, tol=1e-8,
                    tol_load=1e-10, xmin=-4.5, xmax=1.5, ymax=3.0)
    assert out.report.converged
    assert out.H00 == pytest.approx(ref["H00"], rel=1e-6)
    assert np.abs(out.P - ref["P"]).max() < 1e-5


@pytest.mark.solver
def test_newton_pyamg_path_reaches_the_fas_answer():
    from ehl_multigrid.point.newton import solve_newton_amg

    # (10, 5): 4 Newton steps, where the (20, 10) of the other tests here takes 11 (0.6 against 2.2 s)
    pb = problem_from_moes(10.0, 5.0)
    nw = solve_newton_amg(pb, points=65, max_iter=60)
    assert nw.report.converged, nw.report.message
    a, b = build_result(nw), build_result(solve_fas(pb, points=65, far_field=False))  # P = 0 as Newton
    # both stop at relative residual 1e-4; Hc and Hm agree to that algebraic level
    assert a.scalars["Hc_venner"] == pytest.approx(b.scalars["Hc_venner"], rel=3e-4)
    assert a.scalars["Hm_venner"] == pytest.approx(b.scalars["Hm_venner"], rel=3e-3)


@pytest.mark.solver
def test_thick_film_wide_box_converges_to_the_newton_answer():
    """At M = 1 the pressure spreads over the inlet length s = 8 a: on a box four times the
    default the coarse mesh follows s, so the FAS cycles converge (a coarse mesh tied to a left
    one level and stopped unconverged) and agree with the other solver path."""
    from ehl_multigrid.point.newton import solve_newton_amg
    from ehl_multigrid.point.problem import default_domain

    pb = problem_from_moes(1.0, 0.0)
    box = {k: 4.0 * v for k, v in zip(("xmin", "xmax", "ymax"), default_domain(pb), strict=True)}
    fas = solve_fas(pb, points=65, far_field=False, **box)  # the Newton path has P = 0 there
    assert fas.success and fas.levels >= 2 and fas.cycles <= 25, fas.message
    nw = solve_newton_amg(pb, points=65, max_iter=60, **box)
    assert nw.report.converged, nw.report.message
    assert build_result(nw).scalars["Hc_venner"] == pytest.approx(fas.scalars["Hc_venner"], rel=3e-4)


def test_elliptic_problem_load_and_scaling():
    pb = problem_from_moes(20.0, 10.0, 0.25)
    assert pb.b_over_a == pytest.approx(2.5007, rel=1e-3)
    assert pb.load == pytest.approx(2 * math.pi / 3 * pb.b_over_a)
    c = problem_from_moes(20.0, 10.0, 1.0)
    assert c.cd == pytest.approx(2 / math.pi**2, rel=1e-10)
    assert c.lam == pytest.approx((128 * math.pi**3 / (3 * 20.0**4)) ** (1 / 3), rel=1e-10)
    assert c.moes_factor == pytest.approx(30.0 ** (2 / 3), rel=1e-10)
    out = solve_fas(pb, points=65, far_field=False)  # all the load inside the box
    assert out.report.converged
    load = load_integral(out.P, out.X[1] - out.X[0], out.Y[1] - out.Y[0], False)
    assert abs(load / pb.load - 1) < 1e-4


def test_scene_problem_uses_hertz_of_the_scene():
    sc = load_scene("appendix_d_point")
    pb = problem_from_scene(sc)
    assert pb.pmax == pytest.approx(sc.hertz.pmax)
    assert pb.physical and pb.a == pytest.approx(sc.hertz.a)


@pytest.mark.parametrize("kw", [{"points": 100}, {"deformation": "spline"}, {"cycle": "X"},
                                {"xmin": 0.0}, {"tol": -1.0}, {"points": 65, "levels": 9}])
def test_bad_options_raise_input_error(kw):
    with pytest.raises(InputError):
        solve_fas(problem_from_moes(20.0, 10.0), **kw)


@pytest.mark.parametrize("M,L,theta", [(-1.0, 10.0, 1.0), (20.0, -2.0, 1.0), (20.0, 10.0, 0.0)])
def test_bad_problem_raises_input_error(M, L, theta):
    with pytest.raises(InputError):
        problem_from_moes(M, L, theta)
