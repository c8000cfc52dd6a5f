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
@pytest.mark.xdist_group("tehl_point_pair")
def test_point_slip_sign_mirrors_the_solution(pair):
    pos, neg = pair
    assert neg.Hc == pytest.approx(pos.Hc, rel=1e-6)
    assert neg.friction == pytest.approx(-pos.friction, rel=1e-6)
    np.testing.assert_allclose(neg.T_surface1, pos.T_surface2, atol=1e-5)
    assert neg.heat_partition[0] == pytest.approx(pos.heat_partition[1], rel=1e-6)


@pytest.mark.solver
@pytest.mark.xdist_group("tehl_point_pair")
def test_point_energy_balance_and_heating(pair):
    pos, _ = pair
    assert pos.heat_balance_error < 0.01
    assert pos.T_max > pos.scene.T_oil + 5.0
    assert pos.friction > 0 and pos.report.converged
    assert pos.T_mid.shape == pos.P.shape


def test_point_solver_refuses_a_line_contact():
    with pytest.raises(InputError, match="line contact"):
        solve_tehl_point(load_scene("appendix_c_line_4240N"), 0.5)
