"""Mass conservation of the starved point solver at mild starvation of a thick-film contact:
the exact solve of the Poiseuille-dominated zone (ehl_multigrid/starved/point_mass.py) in the
mass re-solve. (M, L) = (20, 10), half domain, 129 points along X (65 for the zone solve)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.point.solve import solve_fas
from ehl_multigrid.starved.point import (
    MASS_TOL,
    STARVED_TOL,
    _solve_once,
    face_fluxes,
    imbalance_of,
    solve_starved_point,
)
from ehl_multigrid.starved.point_mass import inlet_solve

KW = dict(points=129, half=True, raise_on_failure=False)


@pytest.fixture(scope="module")
def problem():
    return problem_from_moes(20.0, 10.0)


@pytest.fixture(scope="module")
def flooded(problem):
    return solve_fas(problem, wedge_order=1, tol=STARVED_TOL, max_cycles=40, far_field=False, **KW)


@pytest.mark.solver
@pytest.mark.xdist_group("starved_point_mass_flooded")
def test_mild_starvation_of_a_thick_film_conserves_mass_to_1e_6(problem, flooded):
    # Hoil = 2 Hc_ff: the meniscus far upstream; the cycles alone stop at an imbalance of 3.6e-5
    s = solve_starved_point(problem, 2.0 * flooded.scalars["Hc_venner"], **KW)
    assert s.status_name == "converged"
    assert s.extra["mass_balance_error"] <= MASS_TOL
    fl = s.extra["fluxes"]
    assert fl["out"] + fl["side"] == pytest.approx(fl["in"], rel=MASS_TOL)
    # the kept solve is the one with the exact zone solve
    assert any("exact solve" in a and "kept the second" in a for a in s.actions)


@pytest.mark.solver
@pytest.mark.xdist_group("starved_point_mass_flooded")
def test_exact_zone_solve_zeroes_the_residual_of_its_zone(problem, flooded):
    opt = PointOptions.build(None, points=65, half=True, raise_on_failure=False, tol=1e-6, wedge_order=1)
    sol, hz = _solve_once(problem, 2.0 * flooded.scalars["Hc_venner"], opt, None)
    lev = hz.levels[-1]
    zone = hz.exact_zone_mask(lev)
    inner = np.zeros(zone.shape, dtype=bool)
    inner[:-1, 1:-1] = True
    before = hz._raw_residual(lev, lev.P, lev.theta)
    ok, iterations, note = inlet_solve(lev.P, lev.H, lev.rho, lev.eps, lev.theta, lev.f, lev.hx, lev.hy,
                                       True, 1, zone, lambda P, t: hz._raw_residual(lev, P, t))
    assert ok, note
    after = hz._raw_residual(lev, lev.P, lev.theta)
    scale = np.abs(before[zone & inner]).max()
    assert scale > 0.0
    assert np.abs(after[zone & inner]).max() < 1e-9 * scale
    # complementarity: pressurised points are full, P >= 0, 0 <= theta <= 1
    assert np.all(lev.P >= 0.0)
    assert np.all((lev.theta >= 0.0) & (lev.theta <= 1.0))
    assert np.all(lev.theta[lev.P > 0.0] == 1.0)
    # the flux form: the sum of the residuals is the imbalance of the boundary flows
    hz.update_film(lev)
    hz._march(lev)
    r = hz._raw_residual(lev, lev.P, lev.theta)
    w = np.ones(lev.ny)
    w[0] = 0.5
    fl = face_fluxes(lev.P, lev.H, lev.rho, lev.eps, lev.theta, lev.hx, lev.hy, True, 1)
    total = float((w[:, None] * r).sum()) * lev.hx * lev.hy
    assert total == pytest.approx(-(fl["in"] - fl["out"] - fl["side"]), abs=1e-12 * fl["in"])
    assert imbalance_of(hz) == pytest.approx(abs(total) / fl["in"], rel=1e-6, abs=1e-14)


@pytest.mark.solver
@pytest.mark.xdist_group("starved_point_mass_flooded")
def test_flooded_limit_is_unchanged(problem, flooded):
    s = solve_starved_point(problem, math.inf, **KW)
    assert s.status_name == "converged"
    assert not any("exact solve" in a for a in s.actions)
    assert s.scalars["Hc_venner"] == pytest.approx(flooded.scalars["Hc_venner"], rel=1e-6)
    assert s.scalars["Hm_venner"] == pytest.approx(flooded.scalars["Hm_venner"], rel=1e-6)
    assert s.extra["mass_balance_error"] < 1e-8
