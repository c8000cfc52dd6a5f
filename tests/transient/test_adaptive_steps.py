"""Adaptive time steps of the transient line contact (``time_tol``): BDF2's local film error,
estimated by Milne's device against the quadratic extrapolation of the three levels before a
step, sizes the steps inside each output interval; a step over the tolerance is solved again
smaller. Checked: steps grow on a smooth run, the accepted local errors stay at the tolerance,
and (slow) the film error against a run at a 32 times smaller fixed step falls with it."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.transient import Bump, solve_transient_line
from ehl_multigrid.transient.stepping import MIN_STEP_FRACTION

pytestmark = pytest.mark.solver

PB = dataclasses.replace(LineProblem.from_moes(20, 10), xmin=-4.5, xmax=1.5)
DENT = Bump(-0.1, 0.5, -1.2)  # 1.2 times the central film deep, passing at 1.5 u_m


def _run(feature, steps, time_tol, dt=0.04, **kw):
    return solve_transient_line(PB, feature, points=65, dt=dt, steps=steps, slide_roll=1.0,
                                cavitation="mass-conserving", time_tol=time_tol,
                                snapshot_every=100000, **kw)


def test_a_smooth_run_grows_its_steps_to_the_output_step():
    res = _run(None, 10, 1e-3)
    # the first interval starts at dt/16 and doubles; from the third on, one step per interval
    sub = np.asarray(res.series["substeps"][1:])
    assert sub[0] <= 5 and np.all(sub[2:] == 1.0)
    assert np.nanmax(res.series["time_error"]) <= 1e-3


def test_the_accepted_local_errors_stay_at_the_tolerance_with_rejected_steps():
    # eight output steps: 21 rejected steps, 11-20 inner steps each and the largest local
    # error 9.94e-4, that of fifteen (48 rejected, at twice the cost)
    res = _run(DENT, 8, 1e-3)
    s = res.summary()
    assert s["rejected_steps"] > 0 and s["time_error_max"] <= 1e-3 * (1 + 1e-9)
    assert np.all(np.asarray(res.series["substeps"][2:]) > 1)  # the dent needs smaller steps
    assert 0.5 / MIN_STEP_FRACTION > np.max(res.series["substeps"])


def test_a_time_tolerance_outside_its_range_is_refused():
    with pytest.raises(InputError, match="time_tol"):
        _run(None, 1, 0.5)


@pytest.mark.slow
def test_the_film_error_falls_with_the_time_tolerance():
    ref = _run(DENT, 30 * 32, None, dt=0.04 / 32, tol=1e-9, tol_load=1e-10)
    Hm_ref = ref.Hm[::32]
    err = {}
    for tt in (1e-2, 1e-3):
        res = _run(DENT, 30, tt, tol=1e-9, tol_load=1e-10)
        err[tt] = np.max(np.abs(res.Hm - Hm_ref)) / np.mean(Hm_ref)
    # measured 1.6 % and 0.53 % (reference at dt/64); global error a few times the local one
    assert err[1e-3] < 0.5 * err[1e-2]
    assert err[1e-3] < 10 * 1e-3
    # the stated time error (a second run at an eighth of the tolerance) covers the true one,
    # relative to the smooth film (measured true / stated 0.66 and 0.77 for Hm)
    from ehl_multigrid.transient import adaptive_time_error
    from ehl_multigrid.transient.accuracy import tighter_run_options
    from ehl_multigrid.transient.solve import solve_transient_line

    kw = dict(points=65, slide_roll=1.0, cavitation="mass-conserving", snapshot_every=100000, tol=1e-9,
              tol_load=1e-10)
    for tt in (1e-2, 1e-3):
        run = solve_transient_line(PB, DENT, dt=0.04, steps=30, time_tol=tt, **kw)
        est = adaptive_time_error(run, solve_transient_line(PB, DENT, **kw, **tighter_run_options(run, tt)))
        true = np.max(np.abs(run.Hm - Hm_ref)) / run.steady_film("Hm")
        assert true <= est["Hm"]


def test_a_point_contact_takes_adaptive_steps_within_the_tolerance():
    from ehl_multigrid.point.problem import problem_from_moes
    from ehl_multigrid.transient import Dent2D, solve_transient_point

    # four output steps on 33^2 points: 5 rejected steps, 8-16 inner steps per output step and
    # the largest local error 9.5e-4 (65^2: 8 rejected, 10-16 inner steps, 9.8e-4, at 1.7x the
    # cost)
    res = solve_transient_point(problem_from_moes(20, 10), Dent2D(-0.5, 0.6, x0=-1.4), points=33,
                                steps=4, dt=0.045, slide_roll=1.0, cavitation="mass-conserving",
                                time_tol=1e-3, snapshot_every=100000)
    s = res.summary()
    assert s["complete"] and s["rejected_steps"] > 0
    assert s["time_error_max"] <= 1e-3 * (1 + 1e-9)
    assert np.all(np.asarray(res.series["substeps"][2:]) > 1)


def test_the_time_error_of_adaptive_steps_comes_from_a_run_at_an_eighth_of_the_tolerance():
    from ehl_multigrid.transient import adaptive_time_error
    from ehl_multigrid.transient.accuracy import ADAPTIVE_FACTOR, TIGHTER_TOL, tighter_run_options
    from ehl_multigrid.transient.solve import solve_transient_line

    kw = dict(points=65, slide_roll=1.0, cavitation="mass-conserving", snapshot_every=100000)
    run = solve_transient_line(PB, DENT, dt=0.04, steps=6, time_tol=1e-2, **kw)
    # the second run (the front door's time_error): the same contact, feature and grid at half
    # the output step over the same time and an eighth of the tolerance (the run
    # _run(DENT, 12, 1e-2 * TIGHTER_TOL, dt=0.02))
    second = tighter_run_options(run, 1e-2)
    assert second == dict(dt=0.02, steps=12, t_end=None, time_tol=1e-2 * TIGHTER_TOL)
    tight = solve_transient_line(PB, DENT, **kw, **second)
    est = adaptive_time_error(run, tight)
    # ... with smaller inner steps
    assert np.sum(tight.series["substeps"][1:]) > np.sum(run.series["substeps"][1:])
    for k in ("Hc", "Hm"):
        diff = np.max(np.abs(getattr(run, k) - getattr(tight, k)[::2])) / run.steady_film(k)
        assert diff > 0.0 and est[k] == pytest.approx(ADAPTIVE_FACTOR * diff, rel=1e-12)
    # a second run at the same output step (here the run itself) is refused
    with pytest.raises(ValueError, match="half the output step"):
        adaptive_time_error(run, run)


def test_the_front_door_states_the_time_part_of_an_adaptive_run():
    import ehl_multigrid as ehl
    from ehl_multigrid import Scene, load_scene

    d = load_scene("page63_line_2000N").to_dict()
    d["feature"] = {"kind": "dent", "amplitude": 2e-8, "width": 5e-5, "x0": -1.5e-4}
    sol = ehl.solve(Scene.from_dict(d), physics="transient", accuracy=None,
                    options={"points": 129, "steps": 4, "time_tol": 1e-2, "time_error": True})
    t = sol.error.parts["time"]
    assert sol.success and np.isfinite(t.Hc) and np.isfinite(t.Hm) and t.Hm > 0.0
    assert any("eighth" in n and "time tolerance" in n for n in sol.error.notes)
