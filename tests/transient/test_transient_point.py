"""Time-dependent point contact: steady limit, time-step order, mass conservation, feature
paths (dent, waviness at an angle, height map), named errors.

Venner's transient point-contact Reynolds equation (Venner & Lubrecht 2000, ch. 13) with the
squeeze term d(rho H)/dT, T = t u_m/a; BDF2 steps on the shared multilevel driver.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from ehl_multigrid.model.errors import InputError
from ehl_multigrid.point.problem import problem_from_moes
from ehl_multigrid.transient import (
    Dent2D,
    HeightMap,
    Waviness2D,
    load_series,
    solve_transient_point,
    time_error,
)
from ehl_multigrid.transient.accuracy import TIME_SAFETY


@pytest.fixture(scope="module")
def problem():
    return problem_from_moes(20, 10)


def test_zero_amplitude_point_feature_reproduces_the_steady_solution(problem):
    res = solve_transient_point(problem, Dent2D(0.0, 0.5, x0=-2.5), dt=0.05, steps=12, points=65,
                                snapshot_every=12)
    assert res.steady.success
    # the steady solution is converged to a relative residual of 1e-5 (the step tolerance):
    # the films of every step agree with it to that order
    assert np.max(np.abs(res.Hc / res.Hc_steady - 1.0)) < 1e-5
    assert np.max(np.abs(res.Hm / res.Hm_steady - 1.0)) < 1e-5
    assert np.max(np.abs(res.snapshots[12]["P"] - res.steady.P)) < 1e-3
    assert res.summary()["cycles_max"] <= 2


@pytest.mark.solver
def test_bdf2_time_step_order_is_two_on_a_coarse_grid(problem):
    # a Gaussian bump (0.24 Hc high) entering the contact, T in [0, 1.2], 33^2 points (the
    # order and the estimate's ratio as on 65^2: 1.92 and 1.26 against 1.88 and 1.23, at 0.4 of the cost)
    bump = Dent2D(0.1, 0.8, x0=-2.4, shape="gaussian")
    runs = [solve_transient_point(problem, bump, dt=dt, steps=round(1.2 / dt), points=33, tol=1e-7,
                                  tol_load=1e-9, snapshot_every=1000) for dt in (0.1, 0.05, 0.025)]
    d1 = np.max(np.abs(runs[0].Hc - runs[1].Hc[::2]))
    d2 = np.max(np.abs(runs[1].Hc - runs[2].Hc[::2]))
    assert d1 > 1e-4  # the bump changes the film: the differences are time errors, not noise
    assert 1.6 < math.log2(d1 / d2) < 2.4  # measured 1.92
    # Richardson estimate of the time error of the dT = 0.05 run against the dT = 0.025 run
    est = time_error(runs[1], runs[0])["Hc"] * runs[1].Hc_steady
    assert 0.8 < est / TIME_SAFETY / d2 < 2.0  # the Richardson term, without the safety factor
    assert est >= d2


@pytest.mark.solver
def test_squeeze_formulation_conserves_mass_in_the_pressurised_zone(problem):
    # a dent (0.5 Hc deep) crossing the centre: storage d(rho H)/dT is a real part of the balance
    dent = Dent2D(-0.2, 0.6, x0=-1.5)
    res = solve_transient_point(problem, dent, dt=0.06, steps=20, points=65, tol=1e-6, tol_load=1e-8)
    bal, storage = np.abs(res.mass_balance[1:]), np.abs(np.asarray(res.series["storage"][1:]))
    ok = np.isfinite(bal)
    assert ok.sum() > 15
    assert storage[ok].max() > 1e-2  # squeeze flow reaches > 1 % of the through-flow (measured 4 %)
    assert bal[ok].max() < 1e-4  # measured 3e-6 at a residual of 1e-6


@pytest.mark.solver
def test_longitudinal_waviness_is_steady_and_transverse_waviness_is_reduced(problem):
    lon = solve_transient_point(problem, Waviness2D(0.04, 1.0, angle=90.0), dt=0.1, steps=10, points=65)
    assert np.ptp(lon.Hc) < 1e-5 * lon.Hc_steady  # ridges along the rolling direction do not move
    assert abs(lon.Hc[0] - lon.Hc_steady) > 1e-3  # ... but they do change the film
    tr = solve_transient_point(problem, Waviness2D(0.02, 1.5), t_end=3.0, points=65)
    s = tr.summary()
    assert 0.05 < s["Ad_over_Ai"] < 0.9
    ang = solve_transient_point(problem, Waviness2D(0.02, 1.5, angle=45.0), steps=8, points=65)
    assert ang.summary()["stalled_steps"] == 0


@pytest.mark.solver
def test_height_map_of_a_dent_moves_like_the_dent(problem):
    dent = Dent2D(-0.1, 0.8, x0=-2.0, shape="gaussian")
    h = 0.1  # about the 65^2 grid's spacing (0.094); a step may move 0.25 of 4 h
    xs, ys = np.arange(-2.0, 2.0 + h / 2, h) - 2.0, np.arange(-2.0, 2.0 + h / 2, h)
    hm = HeightMap(dent.height(xs[None, :], ys[:, None]), h, h, float(xs[0]), float(ys[0]))
    a = solve_transient_point(problem, dent, dt=0.1, steps=20, points=65)
    b = solve_transient_point(problem, hm, dt=0.1, steps=20, points=65)
    assert np.max(a.Hc) > a.Hc_steady + 0.02  # the dent (0.1 deep) reaches the centre
    assert np.max(np.abs(a.Hc - b.Hc)) < 2e-3 * a.Hc_steady
    assert b.yf == a.yf == 0.0  # the film change followed on the map's centre row, not its edge


def test_point_features_too_large_or_bad_steps_are_named(problem):
    with pytest.raises(InputError, match="feature.width"):
        solve_transient_point(problem, Dent2D(-0.1, 4.0, x0=-1.0), points=65, steps=2)
    with pytest.raises(InputError, match="feature.x0"):
        solve_transient_point(problem, Dent2D(-0.1, 0.5, x0=-4.3), points=65, steps=2)
    with pytest.raises(InputError, match="feature.y0"):
        solve_transient_point(problem, Dent2D(-0.1, 0.5, x0=-2.0, y0=2.8), points=65, steps=2)
    with pytest.raises(InputError, match="feature.wavelength"):
        solve_transient_point(problem, Waviness2D(0.01, 8.0), points=65, steps=2)
    with pytest.raises(InputError, match=r"dt = 0\.5 .*\(0, 0\.0625\]"):
        solve_transient_point(problem, Dent2D(-0.1, 0.5, x0=-2.0), dt=0.5, points=65, steps=2)
    for steps in (0, 2.5):
        with pytest.raises(InputError, match="steps"):
            solve_transient_point(problem, None, dt=0.1, steps=steps, points=65)
    with pytest.raises(InputError, match="half"):
        solve_transient_point(problem, None, dt=0.1, steps=2, points=65, half=True)
    with pytest.raises(InputError, match="feature.x_end"):
        solve_transient_point(problem, HeightMap(np.zeros((8, 8)), 0.1, 0.1, -9.0, 0.0), points=65, steps=2)
    with pytest.raises(InputError, match="feature.angle"):
        Waviness2D(0.01, 1.0, angle=120.0)


@pytest.mark.solver
def test_point_series_round_trip_through_hdf5(problem, tmp_path):
    res = solve_transient_point(problem, Dent2D(-0.1, 0.5, x0=-2.0), dt=0.05, steps=6, points=65,
                                snapshot_every=3)
    back = load_series(res.to_hdf5(tmp_path / "p.h5"))
    assert back["kind"] == "ehl_transient_point"
    assert back["snapshots"]["H"].shape == (3, res.Y.size, res.X.size)
    assert np.allclose(back["series"]["Hc"], res.Hc)
    assert back["summary"]["contact"] == "point"


@pytest.mark.solver
def test_a_run_leaves_the_steady_reference_unchanged(problem):
    # the pressure fluctuation is measured against the steady solution: the time loop must work
    # on a copy (an alias overwrote it, so dP(0) read 0 with the dent already in the contact)
    from ehl_multigrid.point import solve_point

    dent = Dent2D(-0.2, 0.6, x0=-0.5)
    res = solve_transient_point(problem, dent, dt=0.05, steps=2, points=65, snapshot_every=2)
    steady = solve_point(20, 10, points=65, estimate=False, half=False, far_field=False,
                         tol=res.steady.tolerances["residual"])
    assert np.array_equal(res.steady.P, steady.P)
    assert res.dP[0] > 0.01
