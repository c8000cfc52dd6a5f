"""Which retry ``solve_fas`` takes after a failed attempt, and with which coarse grid, decided
without solving: every attempt is a stand-in that ends with a given status. The real solves of
the same retries (the 6205 inner race from a halved coarse grid, (1000, 0, theta 0.1) from the
uncapped rule) are the `slow` studies of ``test_point_coarse_retry.py``."""

from types import SimpleNamespace

import numpy as np
import pytest

import ehl_multigrid.point.solve as ps
from ehl_multigrid.model.errors import ConvergenceError
from ehl_multigrid.point.problem import default_domain, problem_from_moes


class Retried(Exception):
    """Raised by the stand-in solver when an attempt with an explicit coarse grid is made."""


def stand_in(status: str, n_coarse: int, attempts: list, ymax: float = 3.0,
             residuals=(1e-5,), loads=(1e-3,), alternate: bool = False, made: list | None = None):
    """A ``point_solver`` whose attempts end with ``status`` on ``n_coarse`` coarse intervals
    (box X -4.5 .. 1.5, Y up to ``ymax``, square cells on the circle's box) after the given
    residual and load-error histories, its grids alternating X and Y lines by the fine-grid rule
    when ``alternate``; an attempt on other coarse intervals than the first one's raises
    :class:`Retried`."""

    def point_solver(problem, opt, guess=None):
        if attempts and opt.n_coarse not in (None, attempts[0].n_coarse):
            raise Retried(opt.n_coarse)
        attempts.append(opt)
        hz = SimpleNamespace(levels=[SimpleNamespace(nx=n_coarse + 1, alternate=alternate)], xmin=-4.5,
                             xmax=1.5, ymax=ymax, y_ratio=opt.y_ratio or 1.0, solver=None,
                             alternating=bool(opt.alternating))
        res = SimpleNamespace(status_name=status, success=False, message="stand-in",
                              work_units=1.0, wall_s=0.1, residual_history=np.array(residuals),
                              load_error_history=np.array(loads), actions=[], report=None)
        if made is not None:
            made.append(res)
        return SimpleNamespace(hierarchy=hz, solve=lambda callback=None: res, hint="")

    return point_solver


def wide_probe_options():
    # (1000, 0, theta 0.1), b/a 4.4, 1025 points on twice the default box: a box probe's wide solve
    pb = problem_from_moes(1000, 0, 0.1)
    x0, x1, y = default_domain(pb)
    return pb, dict(points=1025, half=True, xmin=2 * x0, xmax=2 * x1, ymax=2 * y)


@pytest.mark.parametrize("status", ps.UNCAPPED_RETRY_STATUSES)
def test_a_capped_wide_contact_that_stops_short_is_solved_again_from_the_uncapped_rule(monkeypatch, status):
    pb, box = wide_probe_options()
    uncapped = ps.uncapped_coarse(pb, box["xmax"] - box["xmin"], box["points"])
    assert uncapped == 128
    attempts: list = []
    monkeypatch.setattr(ps, "point_solver", stand_in(status, 64, attempts))
    with pytest.raises(Retried) as got:
        ps.solve_fas(pb, **box)
    assert got.value.args == (uncapped,)
    # out of cycles, the alternating-line retries come first; at a residual floor nothing does
    assert len(attempts) == (1 if status == "residual_floor" else 3)


def test_a_wide_contact_not_capped_or_converging_is_not_solved_again_uncapped(monkeypatch):
    pb, box = wide_probe_options()
    attempts: list = []
    # on the rule's own coarse grid there is nothing uncapped to go to
    monkeypatch.setattr(ps, "point_solver", stand_in("residual_floor", 128, attempts))
    with pytest.raises(ConvergenceError):
        ps.solve_fas(pb, **box, raise_on_failure=True)
    assert all(o.n_coarse is None for o in attempts)
    # the option switches the retry off
    attempts.clear()
    monkeypatch.setattr(ps, "point_solver", stand_in("residual_floor", 64, attempts))
    with pytest.raises(ConvergenceError):
        ps.solve_fas(pb, **box, raise_on_failure=True, retry_uncapped_start=False)


def test_a_diverged_start_is_solved_again_from_half_the_coarse_intervals_after_the_line_retries(monkeypatch):
    # a wide contact (b/a >= ALTERNATE_BELOW): alternating lines and the whole-refresh retry
    # come first, then the halved coarse grid (retry_coarser_start)
    pb = problem_from_moes(3000, 10, 0.1)
    attempts: list = []
    monkeypatch.setattr(ps, "point_solver", stand_in("diverged", 128, attempts))
    with pytest.raises(Retried) as got:
        ps.solve_fas(pb, points=513, half=True)
    assert got.value.args == (64,)
    assert [o.alternating for o in attempts[:2]] == [None, True]
    # an explicit coarse grid is the user's: not changed
    attempts.clear()
    monkeypatch.setattr(ps, "point_solver", stand_in("diverged", 128, attempts))
    with pytest.raises(ConvergenceError):
        ps.solve_fas(pb, points=513, half=True, n_coarse=128, raise_on_failure=True)
    assert len(attempts) > 1 and all(o.n_coarse == 128 for o in attempts)


def test_a_diverged_narrow_start_is_solved_again_from_four_times_the_coarse_intervals(monkeypatch):
    # theta 10 (b/a 0.22), square cells asked for: retry_finer_start, 64 -> 256 intervals
    pb = problem_from_moes(1000.0, 0.0, 10.0)
    attempts: list = []
    monkeypatch.setattr(ps, "point_solver", stand_in("diverged", 64, attempts))
    with pytest.raises(Retried) as got:
        ps.solve_fas(pb, points=1025, half=True, y_ratio=0.25, retry_coarser_start=False)
    assert got.value.args == (256,)
    # not where four times the intervals leave fewer than four points per coarse interval
    attempts.clear()
    with pytest.raises(ConvergenceError):
        ps.solve_fas(pb, points=513, half=True, y_ratio=0.25, retry_coarser_start=False,
                     raise_on_failure=True)
    assert all(o.n_coarse is None for o in attempts)


def test_a_diverged_solve_on_stretched_cells_is_solved_again_on_square_ones_and_charged_for_both(monkeypatch):
    # (20, 20, theta 4): b/a 0.40, stretched cells y_ratio 1, square cells 0.5
    pb = problem_from_moes(20.0, 20.0, 4.0)
    attempts: list = []
    monkeypatch.setattr(ps, "point_solver", stand_in("diverged", 64, attempts, default_domain(pb)[2]))
    with pytest.raises(ConvergenceError):
        ps.solve_fas(pb, points=257, retry_finer_start=False, retry_coarser_start=False,
                     raise_on_failure=True)
    ratios = [o.y_ratio for o in attempts]
    assert ratios[0] is None and ratios[1] == 0.5
    # every attempt is the answer's cost, and its actions say what was tried
    solver = ps.point_solver(pb, attempts[0])
    first = solver.solve()
    _, kept = ps._again(pb, attempts[0], solver, first, None, "a test retry")
    assert kept.work_units == 2.0 and kept.wall_s == pytest.approx(0.2)
    last = kept.actions[-1]  # the first attempt's status and message, the retry named
    assert last.startswith("ended diverged") and "(stand-in)" in last and "a test retry" in last


SLOW = dict(residuals=1e-6 * 0.9 ** np.arange(12), loads=-1e-3 * 0.9 ** np.arange(12))


def test_a_solve_out_of_cycles_but_contracting_steadily_is_not_retried_with_other_relaxations(monkeypatch):
    # circular (5, 0) on eight times the box: every grid alternates by the fine-grid rule and the
    # residual falls by 0.91 a cycle; the alternating and whole-refresh retries (17 s each) were as slow
    pb, box = problem_from_moes(5.0, 0.0, 1.0), dict(points=1025, half=True, raise_on_failure=True)
    attempts: list = []
    made: list = []
    monkeypatch.setattr(ps, "point_solver", stand_in("max_cycles", 128, attempts, alternate=True,
                                                     made=made, **SLOW))
    with pytest.raises(ConvergenceError):
        ps.solve_fas(pb, **box)
    assert len(attempts) == 1
    # one action names both retries left out and the contraction that decided it
    assert len(made[0].actions) == 1
    note = made[0].actions[0]
    assert "x0.90 a cycle" in note and "slow, not unstable" in note
    assert "alternating on every grid" in note and "retry_full_refresh" in note
    # grids that did not alternate yet: the alternating retry runs, the whole refresh does not
    attempts.clear()
    monkeypatch.setattr(ps, "point_solver", stand_in("max_cycles", 128, attempts, alternate=False, **SLOW))
    with pytest.raises(ConvergenceError):
        ps.solve_fas(pb, **box)
    assert [o.alternating for o in attempts] == [None, True]
    assert all(o.local_film_update for o in attempts)


@pytest.mark.parametrize("history", [
    dict(residuals=SLOW["residuals"] * np.r_[np.ones(11), 1.2], loads=SLOW["loads"]),  # a residual rise
    dict(residuals=SLOW["residuals"], loads=-1e-3 * 0.99 ** np.arange(12)),  # a load error near a stall
])
def test_a_solve_out_of_cycles_that_is_not_steadily_contracting_gets_every_relaxation_retry(monkeypatch, history):
    pb = problem_from_moes(5.0, 0.0, 1.0)
    attempts: list = []
    monkeypatch.setattr(ps, "point_solver", stand_in("max_cycles", 128, attempts, alternate=True, **history))
    with pytest.raises(ConvergenceError):
        ps.solve_fas(pb, points=1025, half=True, raise_on_failure=True)
    assert [o.alternating for o in attempts] == [None, True, None]
    assert attempts[2].local_film_update is False


def test_steady_contraction_is_judged_on_max_cycles_only():
    res = SimpleNamespace(status_name="diverged", actions=[], **{
        "residual_history": SLOW["residuals"], "load_error_history": SLOW["loads"]})
    assert not ps.steadily_contracting(res)
    res.status_name = "max_cycles"
    assert ps.steadily_contracting(res)
    res.actions = ["cycle 3 on grid 2 rejected (residual 1e-3)"]
    assert not ps.steadily_contracting(res)
