"""Mass-conserving (Elrod-Adams) cavitation in the transient line contact
(``solve_transient_line(..., cavitation="mass-conserving")``): its steady limit is the
starved solver's flooded-inlet solution, it conserves oil over a dent passage to its mass
tolerance, its film differs from the projection ``P >= 0`` behind a deep dent, and the two
models agree while no film ruptures inside the contact."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from ehl_multigrid.line.problem import LineProblem
from ehl_multigrid.model.errors import InputError
from ehl_multigrid.starved import solve_starved_line
from ehl_multigrid.transient import Bump, solve_transient_line

pytestmark = pytest.mark.solver

PB = dataclasses.replace(LineProblem.from_moes(20, 10), xmin=-4.5, xmax=1.5)


def _run(cavitation, feature, steps, points=129, **kw):
    return solve_transient_line(PB, feature, points=points, steps=steps, cavitation=cavitation,
                                snapshot_every=1, **kw)


def test_steady_limit_is_the_starved_solvers_flooded_inlet_solution():
    res = _run("mass-conserving", None, 6, points=257, dt=0.05)
    ref = solve_starved_line(PB, math.inf, points=257, estimate=False)
    assert ref.success
    Hc_ref, Hm_ref = float(np.interp(0.0, ref.X, ref.H)), float(ref.scalars["Hm_venner"])
    assert abs(res.Hc[-1] / Hc_ref - 1.0) < 1e-5
    assert abs(res.Hm[-1] / Hm_ref - 1.0) < 1e-5
    # the film content behind the outlet rupture carries the flux the contact lets through
    theta = res.snapshots[res.steps]["theta"]
    assert theta.min() < 0.9 and np.all(theta > 0.0) and np.all(theta <= 1.0)


def test_a_deep_dent_under_sliding_conserves_oil_to_the_mass_tolerance():
    # a dent 3.5x the central film deep, moving at 1.5 u_m (SRR +0.5), through the contact
    dent = Bump(-0.3, 0.5, -1.6)
    mc = _run("mass-conserving", dent, slide_roll=1.0, steps=55)
    pr = _run("projection", dent, slide_roll=1.0, steps=55)
    assert mc.complete and pr.complete and not np.any(mc.stalled)
    assert sum(mc.series["substeps"][1:]) == 55  # no step halved
    err = np.asarray(mc.series["mass_error"][1:])
    # oil gained per step over the inflow within the default mass_tol = 1e-6 (measured:
    # largest 9.9e-7, mean -2.4e-7; without the criterion 2.6e-5)
    assert abs(np.mean(err)) < 5e-7 and np.max(np.abs(err)) <= 1e-6
    assert np.all(np.isnan(pr.series["mass_error"]))  # not measured for the projection
    # the models' films agree while the film ruptures only at the outlet (the dent in the
    # contact, to step 47: measured 6e-8) and part when the dent reaches the outlet rupture
    # (steps 53-55: 7.8e-4 to 2.1e-3)
    assert np.max(np.abs(mc.Hm[:48] - pr.Hm[:48])) < 1e-6
    assert np.max(np.abs(mc.Hm[53:] - pr.Hm[53:])) > 1e-4


def test_without_a_rupture_in_the_contact_both_models_give_the_same_film():
    # a shallow dent under pure rolling: the film only ruptures at the outlet; the same scheme
    # inside the contact on any grid (65 points: 4.9e-8 apart; 129: 3.1e-8 at twice the cost)
    dent = Bump(-0.02, 0.5, -2.5)
    mc, pr = (_run(c, dent, 40, points=65, dt=0.05) for c in ("mass-conserving", "projection"))
    inside = np.abs(mc.X) <= 1.0
    for n in sorted(mc.snapshots):
        assert np.max(np.abs(mc.snapshots[n]["H"] - pr.snapshots[n]["H"])[inside]) < 1e-6


def test_an_unknown_cavitation_model_is_refused_naming_the_choices():
    with pytest.raises(InputError, match="cavitation.*projection.*mass-conserving"):
        _run("reynolds", None, 1)


def test_a_starved_inlet_holds_the_starved_steady_film_and_its_supply():
    # Hoil = 0.05: about half the flooded flux, the meniscus near X = -1.1
    res = _run("mass-conserving", None, 8, points=257, dt=0.05, hoil=0.05)
    ref = solve_starved_line(PB, 0.05, points=257, estimate=False)  # the meniscus search
    assert ref.success
    Hc_ref = float(np.interp(0.0, ref.X, ref.H))
    assert abs(res.Hc[-1] / res.Hc[0] - 1.0) < 1e-6  # a steady start stays steady
    assert abs(res.Hc[-1] / Hc_ref - 1.0) < 1e-3  # two discretisations of the meniscus
    assert np.max(np.abs(res.series["mass_error"][1:])) < 1e-8


def test_a_starved_inlet_needs_the_mass_conserving_model():
    with pytest.raises(InputError, match="hoil.*mass-conserving"):
        _run("projection", None, 1, hoil=0.05)


def test_a_thinner_supply_reaches_the_contact_at_the_mean_speed_and_thins_the_film():
    # the layer drops from 0.05 to 0.035 at T = 0 at the inlet X = -4.5; carried at the mean
    # speed it reaches the meniscus (X ~ -1.1) near T = 3.4, then the film thins towards the
    # new steady film (later steps stall with the meniscus at the Hertzian edge: docs)
    res = _run("mass-conserving", None, 50, dt=0.1, hoil=lambda T: 0.05 if T < 0.05 else 0.035)
    new = _run("mass-conserving", None, 1, dt=0.1, hoil=0.035).Hc[0]
    assert abs(res.Hc[30] / res.Hc[0] - 1.0) < 1e-3  # T = 3: not arrived yet
    assert (res.Hc[0] - res.Hc[-1]) > 0.5 * (res.Hc[0] - new)  # T = 5: most of the way
    assert np.max(np.abs(res.series["mass_error"][1:])) < 1e-5


def test_a_dent_that_nearly_cuts_through_the_film_fails_naming_the_time_and_the_place():
    from ehl_multigrid.model.errors import ConvergenceError

    # 0.3 deep (3.5 Hc) under pure rolling on 65 points: the film over the dent's edge thins to
    # 0.0014 (a fortieth of the smooth Hm) and the step stalls at T = 0.7
    with pytest.raises(ConvergenceError) as err:
        _run("mass-conserving", Bump(-0.3, 0.5, x0=-1.8), 100, points=65, dt=0.02, slide_roll=0.0)
    msg = str(err.value)
    assert "T = 0.7" in msg and "at X = -0.84" in msg and "cuts through the film" in msg
    assert err.value.partial.steps == 34
