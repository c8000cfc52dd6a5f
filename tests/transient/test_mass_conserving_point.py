"""Mass-conserving (Elrod-Adams) cavitation in the transient point contact
(``solve_transient_point(..., cavitation="mass-conserving")``): its steady limit is the starved
point solver's flooded-inlet solution, it conserves oil over a dent passage to its mass
tolerance, the two cavitation models agree while no film ruptures inside the contact, and a
starved inlet needs the mass-conserving model."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.starved.point import solve_starved_point
from ehl_multigrid.transient import Dent2D, solve_transient_point

pytestmark = pytest.mark.solver

PB = problem_from_moes(20, 10)  # Hc = 0.418 (Venner units h Rx/a^2) on 65^2 points


def _run(cavitation, feature, steps, points=65, **kw):
    return solve_transient_point(PB, feature, points=points, steps=steps, cavitation=cavitation,
                                 snapshot_every=1, **kw)


def test_steady_limit_is_the_starved_solvers_flooded_inlet_solution():
    res = _run("mass-conserving", None, 6, dt=0.05)
    # the same discretisation (second-order flux-form wedge) solved as one steady problem
    ref = solve_starved_point(PB, math.inf, points=65, half=False, wedge_order=2)
    assert ref.success
    Hc_ref, Hm_ref = float(ref.scalars["Hc_venner"]), float(ref.scalars["Hm_venner"])
    # every step's residual is below the step tolerance 1e-5 (a relative pressure change),
    # which moves the films by ~1e-6 (measured: 1.3e-6 in Hm, 1e-7 in Hc)
    assert np.max(np.abs(res.Hc / Hc_ref - 1.0)) < 1e-5
    assert np.max(np.abs(res.Hm / Hm_ref - 1.0)) < 1e-5
    # the film content behind the outlet rupture carries the flux the contact lets through
    theta = res.snapshots[res.steps]["theta"]
    assert theta.min() < 0.9 and np.all(theta >= 0.0) and np.all(theta <= 1.0)
    err = np.asarray(res.series["mass_error"][1:])
    assert np.all(np.isfinite(err)) and np.max(np.abs(err)) < 1e-6  # measured 7e-8


def test_a_deep_dent_under_sliding_conserves_oil_to_the_mass_tolerance():
    # a dent 2.4 x the central film deep moving at 1.5 u_m (slip S = 1, SRR = 0.5) from the
    # inlet through the contact and its outlet rupture (the cycles stall once as it enters,
    # and the X/Y alternating relaxation that this turns on carries the rest)
    dent = Dent2D(-1.0, 1.0, x0=-1.8)
    res = _run("mass-conserving", dent, 36, slide_roll=1.0)
    assert res.complete and not np.any(res.stalled)
    assert np.max(res.Hc) > 2.0 * res.Hc_steady  # the dent passed the centre (measured 3.1)
    err = np.asarray(res.series["mass_error"][1:])
    # oil gained per step over the inflow within the default mass_tol = 1e-6 (measured: mean
    # 6e-8, largest 9.8e-7)
    assert abs(np.mean(err)) < 2e-7 and np.max(np.abs(err)) <= 1e-6


def test_a_dent_four_film_units_deep_enters_the_contact_conserving_oil():
    # 9.6 Hc deep (a micrometre dent on a film of a tenth of a micrometre), at S = 1 from
    # X = -2 until its centre is at X = -0.5, inside the Hertzian circle
    res = _run("mass-conserving", Dent2D(-4.0, 1.0, x0=-2.0), 16, slide_roll=1.0)
    assert res.complete and not np.any(res.stalled)
    assert 0.0 < np.min(res.Hm) < 0.5 * res.Hm_steady  # measured 0.097 against 0.26
    assert np.max(np.abs(res.series["mass_error"][1:])) <= 1e-6


def test_the_step_tolerances_alone_leave_the_oil_balance_to_the_load_tolerance():
    # the same dent without the mass criterion, up to its entry into the Hertzian circle: a
    # film-constant offset within the load tolerance gains oil over the whole contact through
    # the squeeze term (measured 5.6e-6 over these 12 steps, 1.3e-5 over the whole passage)
    dent = Dent2D(-1.0, 1.0, x0=-1.8)
    res = _run("mass-conserving", dent, 12, slide_roll=1.0, mass_tol=None)
    assert res.complete
    assert np.max(np.abs(res.series["mass_error"][1:])) > 3e-6


def test_without_a_rupture_in_the_contact_both_models_give_the_same_film():
    # a shallow dent (a quarter of the film) under pure rolling, from the inlet to the centre:
    # the film ruptures only at the outlet, where the two models treat the free boundary
    # differently; inside the Hertzian circle both are the same second-order scheme (on any
    # grid: 33^2 at half the cost of 65^2, where the films differed by 3.1e-7)
    dent = Dent2D(-0.1, 1.0, x0=-1.8)
    mc, pr = (_run(c, dent, 18, points=33, dt=0.1, tol=1e-7) for c in ("mass-conserving", "projection"))
    assert np.ptp(mc.Hc) > 0.01  # the dent changes the film there (measured 0.066)
    inside = (mc.X[None, :] ** 2 + mc.Y[:, None] ** 2) <= 1.0
    for n in sorted(mc.snapshots):
        assert np.all(mc.snapshots[n]["theta"][inside] == 1.0)
        # measured 4.7e-7 (films ~0.3-0.5): the outlet's two discretisations and tol 1e-7
        assert np.max(np.abs(mc.snapshots[n]["H"] - pr.snapshots[n]["H"])[inside]) < 2e-6
    assert np.all(np.isnan(pr.series["mass_error"]))  # not measured for the projection


def test_a_starved_inlet_holds_the_starved_steady_film_and_conserves_its_supply():
    # Hoil = 0.1: a fifth of the flooded film, the meniscus inside the box; 33^2 points (65^2:
    # Hc within 3.1e-6, Hm within 1.5e-6, oil balance 3.6e-7, at twice the cost)
    res = _run("mass-conserving", None, 8, points=33, dt=0.05, hoil=0.1, tol=1e-7)
    ref = solve_starved_point(PB, 0.1, points=33, half=False, wedge_order=2)
    assert ref.success
    Hc_ref, Hm_ref = float(ref.scalars["Hc_venner"]), float(ref.scalars["Hm_venner"])
    assert np.all(res.snapshots[res.steps]["theta"][1:-1, 0] < 0.1)  # the gap is unfilled at the inlet
    # the start is that steady solution, re-solved to the step tolerance; the steps hold it
    # (measured: Hc within 4.2e-7, Hm within 3.5e-7)
    assert np.max(np.abs(res.Hc / Hc_ref - 1.0)) < 1e-5
    assert np.max(np.abs(res.Hm / Hm_ref - 1.0)) < 1e-5
    assert np.max(np.abs(res.series["mass_error"][1:])) < 1e-5  # measured 1.1e-9


def _centre_track(Y):
    return 0.1 if abs(Y) < 0.6 else 0.4  # a starved centre track, more oil at its sides


def test_a_layer_across_the_track_is_fed_row_by_row_and_holds_its_starved_film():
    res = _run("mass-conserving", None, 6, dt=0.05, hoil_y=_centre_track)
    ref = solve_starved_point(PB, _centre_track, points=65, half=False, wedge_order=2)
    assert ref.success
    assert abs(res.Hc[-1] / res.Hc[0] - 1.0) < 1e-5  # a steady start stays steady
    assert abs(res.Hc[-1] / float(ref.scalars["Hc_venner"]) - 1.0) < 1e-4  # measured 2.4e-5
    assert np.max(np.abs(res.series["mass_error"][1:])) <= 1e-6
    # the centre track's layer sets the central film; the side oil adds a little
    uniform = _run("mass-conserving", None, 1, dt=0.05, hoil=0.1).Hc[-1]
    assert uniform < res.Hc[-1] < 1.05 * uniform  # measured +0.7 %


def test_a_layer_across_the_track_needs_the_mass_conserving_model_and_no_uniform_layer():
    with pytest.raises(InputError, match="hoil_y.*mass-conserving"):
        _run("projection", None, 1, hoil_y=_centre_track)
    with pytest.raises(InputError, match="hoil and hoil_y"):
        _run("mass-conserving", None, 1, hoil=0.1, hoil_y=_centre_track)


@pytest.mark.parametrize("bad", [0.0, 2.0, math.nan])
def test_a_mass_tolerance_outside_its_range_is_refused_naming_it(bad):
    with pytest.raises(InputError, match="mass_tol"):
        _run("mass-conserving", None, 1, mass_tol=bad)


def test_a_starved_inlet_needs_the_mass_conserving_model():
    with pytest.raises(InputError, match=r"hoil = 0\.1 .*needs cavitation = 'mass-conserving'.*'projection'"):
        _run("projection", None, 1, hoil=0.1)
    with pytest.raises(InputError, match="cavitation.*projection.*mass-conserving"):
        _run("reynolds", None, 1)
