"""A point solve whose FMG start diverges on the automatic coarse grid is solved again from a
coarser one (``retry_coarser_start``): the 6205 inner-race contact (M 3620, b/a 9.4)
converges from 64 coarse intervals and diverges from 128, the count the coarse-grid rule gives
on a box twice as long (the domain probe's wide solve)."""

import re

import pytest

import ehl_multigrid.point.fas as fas
from ehl_multigrid.model.scene import load_scene
from ehl_multigrid.multigrid.options import PointOptions
from ehl_multigrid.point.problem import problem_from_scene
from ehl_multigrid.point.solve import solve_fas

pytestmark = pytest.mark.solver


@pytest.fixture(scope="module")
def bearing():
    return problem_from_scene(load_scene("bearing_6205_inner_race"), "roelands", "dowson-higginson")


@pytest.mark.slow  # the retry decision: test_point_retry_chain.py (no solves)
def test_diverged_fmg_start_is_solved_again_from_a_coarser_grid(bearing, monkeypatch):
    rule = fas.coarse_intervals
    # the rule as it falls on a box twice as long: twice the coarse intervals
    monkeypatch.setattr(fas, "coarse_intervals", lambda *a, **k: min(2 * rule(*a, **k), a[2] - 1))
    sol = solve_fas(bearing, points=513, half=True, tol_load=1e-4, raise_on_failure=False)
    assert sol.status_name == "converged"
    assert any(re.search(r"\b64 coarse intervals\b.*\b128\b.*retry_coarser_start", a) for a in sol.actions)
    assert sol.levels == 4
    # the same discrete problem as a solve started from 64 intervals directly
    ref = solve_fas(bearing, points=513, half=True, tol_load=1e-4, n_coarse=64)
    assert sol.scalars["Hc_venner"] == pytest.approx(ref.scalars["Hc_venner"], rel=2e-4)


@pytest.mark.slow  # the retry decision: test_point_retry_chain.py (no solves)
def test_explicit_coarse_grid_is_not_changed(bearing):
    # alternating on every grid from the start: one diverged attempt (115 WU) instead of three
    # (the alternating and whole-refresh retries, 379 WU); on the rule's 128 intervals the same
    # options are solved again from 64 (retry_coarser_start), which an explicit n_coarse forbids
    sol = solve_fas(bearing, points=513, half=True, tol_load=1e-4, n_coarse=128, alternating=True,
                    raise_on_failure=False)
    assert sol.status_name == "diverged"
    assert not any("retry_coarser_start" in a for a in sol.actions)


def test_wide_contact_on_twice_the_box_converges_without_a_coarser_retry():
    # (3000, 10, theta 0.05), b/a 6.7: with 128 coarse intervals the 513-point solve on twice
    # the default box ran out of cycles (934 WU, 26 s); the wide-contact cap gives 64
    from ehl_multigrid.point.problem import default_domain, problem_from_moes

    pb = problem_from_moes(3000, 10, 0.05)
    x0, x1, y = default_domain(pb)
    sol = solve_fas(pb, points=513, xmin=2 * x0, xmax=2 * x1, ymax=2 * y, half=True, film_tol=2.5e-4,
                    raise_on_failure=False, retry_coarser_start=False)
    assert sol.status_name == "converged"
    assert (513 - 1) // 2 ** (sol.levels - 1) == 64
    assert not any("coarse intervals instead" in a for a in sol.actions)


def test_wide_contact_runs_w_cycles_without_rejected_cycles():
    # (100, 10, theta 0.05), b/a 6.7, 513 points: F cycles rejected two cycles and took 126 WU
    # (3.7 s); W cycles converge with none in 41 WU
    from ehl_multigrid.point.fas import point_cycle
    from ehl_multigrid.point.problem import problem_from_moes

    sol = solve_fas(problem_from_moes(100, 10, 0.05), points=513, half=True, film_tol=2.5e-4,
                    raise_on_failure=False)
    assert sol.status_name == "converged"
    assert sol.settings.cycle == "W" and not sol.actions
    assert sol.work_units < 80
    # the options' own cycle, and X-line solves of other contacts, are left as they were
    assert point_cycle(PointOptions(points=513, cycle="F"), False, wide=True) == "F"
    assert point_cycle(PointOptions(points=513), False) == "F"


@pytest.mark.slow  # the retry decision: test_point_retry_chain.py (no solves)
def test_wide_contact_at_its_floor_from_the_capped_coarse_grid_is_solved_again_from_the_rule():
    # (1000, 0, theta 0.1), b/a 4.4, 1025 points on twice the default box (a box probe's wide
    # solve): from the capped 64 coarse intervals the films wander by 1.8 % at a residual floor
    # of 1e-5, Hc 2 % above the discrete solution; from the rule's 128 it converges
    from ehl_multigrid.point.problem import default_domain, problem_from_moes

    pb = problem_from_moes(1000, 0, 0.1)
    x0, x1, y = default_domain(pb)
    wide = dict(points=1025, half=True, xmin=2 * x0, xmax=2 * x1, ymax=2 * y, film_tol=2e-4, tol_load=2e-4)
    sol = solve_fas(pb, **wide, raise_on_failure=False)
    assert sol.status_name == "converged"
    assert any(a.startswith("ended residual_floor")
               and re.search(r"\b128 coarse intervals\b.*\b64\b.*retry_uncapped_start.*converged", a)
               for a in sol.actions)
    # the box changes the film by far less than the floor's error: the default box on the same mesh
    narrow = solve_fas(pb, points=513, half=True, film_tol=2e-4, tol_load=2e-4)
    assert sol.scalars["Hc"] == pytest.approx(narrow.scalars["Hc"], rel=1e-3)


def test_a_probe_out_of_cycles_from_the_uncapped_start_is_not_solved_again_from_the_capped_one(monkeypatch):
    # the wide contact's solve already tried the capped 64 intervals before the rule's 128
    # (retry_uncapped_start); halving 128 would repeat that attempt
    from types import SimpleNamespace

    import ehl_multigrid.point.solve as ps
    from ehl_multigrid.point.problem import default_domain, problem_from_moes

    pb = problem_from_moes(1000, 0, 0.1)
    x0, x1, y = default_domain(pb)
    opts = PointOptions(points=1025, xmin=2 * x0, xmax=2 * x1, ymax=2 * y, half=True)
    res = SimpleNamespace(success=False, status_name="max_cycles", levels=4, work_units=1.0, wall_s=1.0,
                          actions=["ended max_cycles (...); solved again with 128 coarse intervals instead "
                                   "of 64 (retry_uncapped_start): max_cycles"])

    def no_solve(*a, **k):
        raise AssertionError("solved again")

    monkeypatch.setattr(ps, "solve_fas", no_solve)
    assert ps.coarser_probe(pb, opts, res) is res
    # without that retry the halving is tried
    res.actions = []
    with pytest.raises(AssertionError, match="solved again"):
        ps.coarser_probe(pb, opts, res)
