"""A starved result that does not conserve mass is a failure (issue 41): the ball-on-flat
contact of the issue (M = 741, L = 6.34, a 20 nm layer) converges to a starved film instead
of stopping at the flooded one, and any result whose boundary flows do not balance, or whose
central film carries more oil than the supply, gets a failed status whose message says that
mass is not conserved and gives the numbers (``ehl solve``: exit code 3)."""

from __future__ import annotations

import json

import pytest

from ehl_multigrid.app.cli import main
from ehl_multigrid.line import LineProblem
from ehl_multigrid.model.scene import load_scene
from ehl_multigrid.multigrid.result import EHLResult
from ehl_multigrid.starved import line as starved_line
from ehl_multigrid.starved import point as starved_point
from ehl_multigrid.starved.gate import MASS_GATE, apply_mass_gate
from ehl_multigrid.starved.line import solve_starved_problem, starved_options
from ehl_multigrid.starved.point import solve_starved_point_scene

#: statuses a result that does not conserve mass must not have
NOT_FAILED = ("converged", "residual_floor", "inaccurate")


pytestmark = pytest.mark.solver


@pytest.fixture
def ball_on_flat(tmp_path, report_scene):
    """The issue's point contact with a 20 nm layer."""
    return report_scene("ball", tmp_path, "ball_on_flat_starved", 2e-8)


@pytest.fixture
def without_exact_zone_solve(monkeypatch):
    """The starved point solver without its exact zone solve and with no other coarse-grid rule
    for its re-solve (``exact_rules=()``, also under ``ehl solve``): on the issue's contact the
    cycles then stop at the flooded film. No continuation in the supply is tried after it (it
    fails there too and returns the same result)."""
    real, real_solve = starved_point._solve_once, starved_point.solve_starved_point
    monkeypatch.setattr(starved_point, "CONTINUATION_MAX_POINTS", 0)

    def no_exact(problem, hoil, opt, coarse_theta, exact=False, guess=None):
        return real(problem, hoil, opt, coarse_theta, False, guess)

    monkeypatch.setattr(starved_point, "_solve_once", no_exact)
    monkeypatch.setattr(starved_point, "solve_starved_point",
                        lambda problem, hoil, options=None, *a, **kw:
                        real_solve(problem, hoil, options, *a, **{"exact_rules": (), **kw}))


def test_the_ball_on_flat_of_issue_41_converges_to_a_starved_film_not_the_flooded_one(ball_on_flat):
    # 129^2 reproduced the issue: status residual_floor with Hc_ratio 0.995, rho_c Hc / Hoil 3.5
    # and a mass imbalance of 27 times the inflow
    s = solve_starved_point_scene(load_scene(ball_on_flat), points=129, estimate=False)
    assert s.status_name == "converged" and s.success
    # the supply (0.35 of the flooded film's flux) sets the film: rho_c Hc = Hoil
    assert 0.2 < s.scalars["Hc_ratio"] < 0.4
    assert abs(s.scalars["rho_c_Hc_over_hoil"] - 1.0) < 0.01
    assert s.scalars["mass_balance_error"] < 1e-6
    assert s.scalars["meniscus_x"] > -1.2  # near the Hertzian edge, not at the box inlet (-4.5)


def test_a_starved_point_result_that_creates_oil_fails_with_a_mass_message(ball_on_flat, without_exact_zone_solve):
    s = solve_starved_point_scene(load_scene(ball_on_flat), points=129, estimate=False, flooded=False)
    mb = s.scalars["mass_balance_error"]
    # the flooded film: far more oil leaves than the supply brings
    assert mb > 1.0 and s.scalars["rho_c_Hc_over_hoil"] > 3.0
    assert not s.success and s.status_name not in NOT_FAILED
    assert s.scalars["converged"] is False
    assert "mass is not conserved" in s.message
    assert f"{mb:.3g}" in s.message and f"{s.scalars['rho_c_Hc_over_hoil']:.3g}" in s.message


def test_ehl_solve_exits_3_on_a_starved_result_that_does_not_conserve_mass(ball_on_flat, without_exact_zone_solve,
                                                                          tmp_path, capsys):
    # on 65^2, at 0.4 of the cost: the solve stops near the flooded film there too (0.85 of
    # it) with a mass-balance error of 0.9 of the inflow (27 on 129^2, the test above)
    rc = main(["solve", str(ball_on_flat), "--points", "65", "--accuracy", "none", "--no-plots", "--json",
               "--out", str(tmp_path / "o")])
    out = json.loads(capsys.readouterr().out)
    assert rc == 3
    assert out["converged"] is False and out["status"] not in NOT_FAILED
    assert "mass is not conserved" in out["message"] and out["mass_balance_error"] > MASS_GATE


def test_the_gate_fails_a_result_with_a_mass_imbalance_and_names_the_numbers():
    r = EHLResult(status=8, message="the residual stopped falling at 1.82e-06")
    assert apply_mass_gate(r, 32.7, 3.52)
    assert not r.success and r.status_name not in NOT_FAILED and r.scalars["converged"] is False
    assert "mass is not conserved" in r.message
    assert "32.7" in r.message and "3.52" in r.message
    # the iteration's own verdict stays in the message
    assert "residual_floor" in r.message and "1.82e-06" in r.message


def test_the_gate_fails_a_central_film_that_carries_more_oil_than_the_supply():
    r = EHLResult(status=0, message="converged")
    assert apply_mass_gate(r, 1e-7, 1.5)
    assert not r.success and "rho_c Hc / Hoil = 1.5" in r.message


def test_the_gate_keeps_a_result_that_conserves_mass():
    r = EHLResult(status=0, message="converged")
    # the side flow of a point contact leaves the centre with less than the supply
    assert not apply_mass_gate(r, 1e-7, 0.996)
    assert r.success and r.status_name == "converged"


def test_a_starved_line_result_with_a_mass_imbalance_fails(monkeypatch):
    real = starved_line.starved_scalars

    def leaky(lv, hoil, flooded, pb):
        s = real(lv, hoil, flooded, pb)
        s["mass_balance_error"] = 0.2
        return s

    monkeypatch.setattr(starved_line, "starved_scalars", leaky)
    opts = starved_options(points=129, raise_on_failure=False)
    res = solve_starved_problem(LineProblem.from_moes(20, 10), 10.0, opts)  # flooded inlet, finite supply
    assert not res.success and res.status_name not in NOT_FAILED
    assert "mass is not conserved" in res.message and "0.2" in res.message
